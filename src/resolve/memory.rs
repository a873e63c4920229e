//! The memory a run will need, estimated from the validated scene before
//! anything is allocated, and the budget it must fit.
//!
//! Every input within its documented range is accepted by the range checks,
//! but some combinations (10⁹ steps recorded row by row, 10⁵ probes, 10⁴
//! carriers on a fine mesh) would exhaust the machine's memory and abort the
//! process. Such a run is refused at validation with the estimate, the
//! budget and a way out (`output.record_every`, fewer probes, elements or
//! carriers) — never started.

use crate::error::{Error, Result};
use crate::model::banded::rhs_columns;

/// Bytes of one stored contact event of a carrier: its loss interval in
/// x/L and in t (two `[f64; 2]`, 32), the interval's class (1) and a
/// re-contact (80: seven f64 or usize, an `Option<f64>` and a flag, padded
/// to 8) of the record layer's statistics (`record::stats`); a run reserves
/// room for [`event_capacity`] of them per carrier before its first step.
/// `record/stats.rs` asserts at compile time that its types take exactly
/// this, so the plan cannot drift from them.
pub const EVENT_BYTES: u64 = 113;

/// Most loss intervals and re-contacts a run stores one by one (they are
/// all counted): a contact that chatters every step over 10⁹ steps would
/// otherwise hold gigabytes of intervals.
pub const MAX_STORED_EVENTS: usize = 10_000;

/// The most loss intervals (and re-contacts) a run of `steps` steps can
/// store per carrier: an interval needs a lost step, and two intervals a
/// closed step between them, so at most ⌈steps/2⌉; and at most
/// [`MAX_STORED_EVENTS`] are stored.
pub fn event_capacity(steps: usize) -> usize {
    steps.div_ceil(2).min(MAX_STORED_EVENTS)
}

/// Largest memory one run may plan to use, bytes (2 GiB). A fixed number,
/// not the machine's free memory, so that a scene is accepted or refused the
/// same way on every machine (and in CI); 2 GiB fits a laptop running a
/// sweep on a few cores, and is 100× the reference case at its finest
/// converge level. The largest mesh (10⁶ elements, ≈ 0.5 GiB by the estimate
/// below) fits it with room for its history.
pub const MEMORY_BUDGET_BYTES: u64 = 2 << 30;

/// Largest `history.csv` a run may plan to write, bytes (4 GiB), by the
/// estimate [`CSV_BYTES_PER_VALUE`] × values per row × rows: like the memory
/// budget a fixed number, so a scene is accepted the same way everywhere.
/// A 4.35·10⁷-row run wrote a 4.15 GB file before it (issue 25).
pub const OUTPUT_BUDGET_BYTES: u64 = 4 << 30;

/// Bytes of one value of `history.csv`, counted generously: a value is at
/// most 24 characters in shortest round-trip form and a comma; measured
/// 95 bytes a row for 7 values (13.6 a value) on a 4.35·10⁷-row
/// `t2_stationary_mass` run, so 16 is an upper estimate for typical rows.
pub const CSV_BYTES_PER_VALUE: u64 = 16;

/// Bytes of one history row for the time column (`t`, f64).
pub const ROW_TIME_BYTES: u64 = 8;

/// Bytes of one history row per carrier: x_m, w, q, g and λ as f64, and the
/// contact flag as a bool (`record::CarrierTrace`).
pub const ROW_CARRIER_BYTES: u64 = 5 * 8 + 1;

/// Bytes of one history row per probe (v as f64).
pub const ROW_PROBE_BYTES: u64 = 8;

/// Banded n×n matrices a run keeps at once, counted generously: mass,
/// stiffness, damping, the effective matrix and its factor, the mass
/// factor of the initial state, and two spare for a method's second stage
/// (Bathe) or the spectrum estimate (central difference).
pub const BANDED_MATRICES: u64 = 8;

/// Dense n × `rhs_columns(nc)` blocks a run keeps at once: the step's
/// right-hand sides and the constraint columns A⁻¹r of every carrier, plus
/// the initial state's, counted generously.
pub const RHS_BLOCKS: u64 = 4;

/// Dense nc × nc matrices of the contact solve (W, its reduced and modified
/// copies, the active block), counted generously.
pub const DENSE_CONTACT_MATRICES: u64 = 6;

/// The extra memory of a `modal` basis of J modes over n_fe FE unknowns:
/// the dense eigenproblem at its peak ([`crate::model::eigen::eigen_bytes`]:
/// C, the eigenvectors and faer's workspace, from faer's own requirement,
/// ≈ 5 n² · 8 bytes; counted as 4 n² · 8 before, which a run at n = 1999
/// exceeded by 32 MiB) and the n_fe × J mode shapes kept for the run.
pub fn modal_bytes(n_fe: usize, modes: usize) -> u64 {
    let n = n_fe as u64;
    let eigen = if n_fe <= crate::model::eigen::MAX_MODAL_DOFS {
        crate::model::eigen::eigen_bytes(n_fe)
    } else {
        // refused by validation; an over-estimate that cannot overflow
        n.saturating_mul(n).saturating_mul(8 * 6)
    };
    eigen.saturating_add(n.saturating_mul(modes as u64).saturating_mul(8))
}

/// Index buckets a series is reduced to before drawing (`report::plot`):
/// each keeps its first, lowest, highest and last point, so the drawn
/// envelope is the data's at any length (a 4·10⁷-step run drew a 347 MB
/// `force.svg`; now at most 4 × 2000 points a series, about two buckets a
/// pixel column). Defined here, with the memory plan that counts it.
pub const PLOT_BUCKETS: usize = 2000;

/// A force plot draws the filtered force of at most this many carriers
/// (the first; one line a colour of the palette): beyond, the raw lines
/// alone, so that a scene of thousands of carriers does not double its
/// plot's memory.
pub const MAX_FILTERED_LINES: usize = 10;

/// Rows of the history formatted at a time by `report::write_history`: a
/// few MB of columns, however long the history (building the whole table
/// copied the history once more: 1 GB more at 2·10⁷ rows, issue 25).
/// Defined here, with the memory plan that counts it ([`csv_block_rows`]).
pub const HISTORY_ROWS_AT_A_TIME: usize = 1 << 16;

/// Characters of one `history.csv` cell at most: a value in shortest
/// round-trip form (`-1.2345678901234567e-308`, 24) and its comma.
pub const CSV_CELL_CHARS: u64 = 25;

/// `force.svg` text per point of a force line: `x,y ` in pixels of a
/// 960 × 480 plot, at most 3 + 1 + 3 + 1.
pub const SVG_POINT_BYTES: u64 = 8;

/// `force.svg` text per shaded loss interval: a `<rect …/>` line, measured
/// 88–90 bytes (reference scene, `contact.placement=alpha`), rounded up.
pub const SVG_RECT_BYTES: u64 = 96;

/// `force.svg` text that does not grow with the data (axes, ticks, labels,
/// legend): measured ≈ 22 KB, counted as 64 KiB.
pub const SVG_FIXED_BYTES: u64 = 64 << 10;

/// A text grown by doubling holds at most 3× its length at once (the old
/// buffer and the new one, twice the old, while it is copied).
pub const GROWN_TEXT_FACTOR: u64 = 3;

/// The working memory of writing a run's outputs, bytes, beyond the
/// history, the statistics and the block of `history.csv` formatted at a
/// time ([`csv_block_rows`]): a line of `history.csv`'s text, `summary.json`'s copy of every carrier's
/// `events` (carrier 0 twice: `contact` and `carriers[0]`; the JSON text
/// itself is streamed to the file), and per carrier of `force.svg`: the
/// decimated points of the force and of the filtered force (at most
/// 4 × [`PLOT_BUCKETS`] each; four copies of 16 bytes and two of 8 on
/// their way to the drawing), the shaded intervals (two copies; each
/// drawn twice, as a shade and as a mark on the axis) and the SVG text, which the plotting
/// library holds whole until it writes the file.
pub fn output_bytes(csv_values: u64, carriers: usize, events: usize) -> u64 {
    let (nc, ev) = (carriers as u64, events as u64);
    let line = csv_values
        .saturating_mul(CSV_CELL_CHARS)
        .saturating_mul(2)
        .saturating_add(8 << 10); // the line's String and the file's buffer
    let summary = nc
        .saturating_add(1)
        .saturating_mul(ev)
        .saturating_mul(EVENT_BYTES);
    let points = 4 * PLOT_BUCKETS as u64;
    let svg_text = (points * SVG_POINT_BYTES)
        .saturating_add(ev.saturating_mul(2 * SVG_RECT_BYTES))
        .saturating_mul(GROWN_TEXT_FACTOR);
    let per_carrier = (points * (4 * 16 + 2 * 8))
        .saturating_add(ev.saturating_mul(2 * 16))
        .saturating_add(svg_text);
    // the filtered lines: as many again for the first MAX_FILTERED_LINES
    let per_filtered =
        (points * (4 * 16 + 2 * 8)).saturating_add(points * SVG_POINT_BYTES * GROWN_TEXT_FACTOR);
    let filtered = nc.min(MAX_FILTERED_LINES as u64);
    line.saturating_add(summary)
        .saturating_add(nc.saturating_mul(per_carrier))
        .saturating_add(filtered.saturating_mul(per_filtered))
        .saturating_add(SVG_FIXED_BYTES * GROWN_TEXT_FACTOR)
}

/// Rows of the block of `history.csv` formatted at a time (its columns
/// copied from the history: a second copy of that many rows).
pub fn csv_block_rows(rows: u64) -> u64 {
    rows.min(HISTORY_ROWS_AT_A_TIME as u64)
}

/// The memory a run is estimated to need, bytes: an upper bound of what it
/// holds at its peak, writing its outputs included (checked against the
/// binary's peak resident size by `tests/memory_peak.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// The recorded history: rows × (t + carriers + probes).
    pub history: u64,
    /// Bytes of one history row.
    pub row: u64,
    /// Rows the history will hold.
    pub rows: u64,
    /// The model and the integrator's work arrays.
    pub model: u64,
    /// The statistics' stored events (loss intervals and re-contacts,
    /// [`event_capacity`] per carrier, reserved before the first step).
    pub events: u64,
    /// The block of `history.csv` formatted at a time: [`csv_block_rows`]
    /// rows × [`Self::row`].
    pub csv_block: u64,
    /// The rest of the working memory of writing the outputs
    /// ([`output_bytes`]).
    pub outputs: u64,
    /// The filtered force the history keeps beside the force: one copy of
    /// every carrier's force history ([`FILTER_BYTES_PER_ROW`] a row and
    /// carrier), when the history holds every step (else there is no
    /// filtered force and this is 0). It shrinks with the rows, like the
    /// history.
    pub filter: u64,
    /// The estimated size of `history.csv`, bytes (on disk, not in memory).
    pub csv: u64,
    /// Values in one row of `history.csv`.
    pub csv_values: u64,
}

impl MemoryEstimate {
    /// Everything, bytes.
    pub fn total(&self) -> u64 {
        self.history
            .saturating_add(self.csv_block)
            .saturating_add(self.model)
            .saturating_add(self.other())
            .saturating_add(self.filter)
    }

    /// The statistics' events and the output buffers but the history's
    /// block: what does not grow with the rows.
    pub fn other(&self) -> u64 {
        self.events.saturating_add(self.outputs)
    }
}

/// Bytes a history row adds per carrier for its filtered force
/// (`CarrierTrace::force_filtered`: the forward pass's output, one f64 a
/// row, filtered back in place).
pub const FILTER_BYTES_PER_ROW: u64 = 8;

/// Bytes of one point vector r_b(x) of the recorder on a mesh: four
/// indices and four weights (a modal basis adds J dense weights).
const POINT_VECTOR_BYTES: u64 = 64;

/// Memory of the wire's snapshots and field (`[output] snapshots`,
/// `field`): `values` f64 and `points` point vectors of a basis of
/// `modes` dense weights each (0 on a mesh).
pub fn wire_bytes(values: u64, points: u64, modes: u64) -> u64 {
    let per_point = POINT_VECTOR_BYTES.saturating_add(modes.saturating_mul(8));
    values
        .saturating_mul(8)
        .saturating_add(points.saturating_mul(per_point))
}

/// Rows of a history that records row 0 (t = 0), every `every`-th step and
/// always the last step.
pub fn history_rows(steps: usize, every: usize) -> usize {
    1 + steps.div_ceil(every.max(1))
}

/// The sizes of a run that its memory estimate reads ([`estimate`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunSize {
    /// Steps of the run.
    pub steps: usize,
    /// The history records every `every`-th step (`output.record_every`).
    pub every: usize,
    /// Elements of the mesh.
    pub elements: usize,
    /// Dofs per node (2 for Hermite beam elements, 1 for a string).
    pub per_node: usize,
    /// Half-bandwidth of the banded matrices.
    pub half_band: usize,
    /// Carriers.
    pub carriers: usize,
    /// Carriers with a mass dof.
    pub masses: usize,
    /// Probes.
    pub probes: usize,
}

/// Estimate the memory of a run of `size.steps` steps on `size.elements`
/// elements (`per_node` dofs per node, half-bandwidth `half_band`) with
/// `carriers` carriers (`masses` of them with a mass dof) and `probes`
/// probes, recording every `every`-th step. Saturating arithmetic: an
/// absurd input gives `u64::MAX`, never an overflow.
pub fn estimate(size: &RunSize) -> MemoryEstimate {
    let RunSize {
        steps,
        every,
        elements,
        per_node,
        half_band,
        carriers,
        masses,
        probes,
    } = *size;
    let u = |x: usize| x as u64;
    let rows = u(history_rows(steps, every));
    let row = ROW_TIME_BYTES
        .saturating_add(ROW_CARRIER_BYTES.saturating_mul(u(carriers)))
        .saturating_add(ROW_PROBE_BYTES.saturating_mul(u(probes)));
    let dofs = u(elements)
        .saturating_add(1)
        .saturating_mul(u(per_node))
        .saturating_add(u(masses));
    let per_dof = BANDED_MATRICES
        .saturating_mul(2 * u(half_band) + 1)
        .saturating_add(RHS_BLOCKS.saturating_mul(u(rhs_columns(carriers))));
    let model = dofs
        .saturating_mul(per_dof)
        .saturating_mul(8)
        .saturating_add(
            u(carriers)
                .saturating_mul(u(carriers))
                .saturating_mul(8 * DENSE_CONTACT_MATRICES),
        );
    // t, then x, w, q, gap, λ, the contact flag and (with every step kept)
    // the filtered λ per carrier, then probes
    let per_carrier = if every <= 1 { 7 } else { 6 };
    let csv_values = 1 + per_carrier * u(carriers) + u(probes);
    let events = event_capacity(steps);
    MemoryEstimate {
        history: rows.saturating_mul(row),
        row,
        rows,
        model,
        events: u(carriers)
            .saturating_mul(u(events))
            .saturating_mul(EVENT_BYTES),
        csv_block: csv_block_rows(rows).saturating_mul(row),
        outputs: output_bytes(csv_values, carriers, events),
        filter: if every <= 1 {
            rows.saturating_mul(FILTER_BYTES_PER_ROW)
                .saturating_mul(u(carriers).max(1))
        } else {
            0
        },
        csv: rows
            .saturating_mul(csv_values)
            .saturating_mul(CSV_BYTES_PER_VALUE),
        csv_values,
    }
}

/// Bytes as GiB (MiB below 1 GiB), for messages.
fn gib(b: u64) -> String {
    if b >= 1 << 30 {
        format!("{:.3} GiB", b as f64 / (1u64 << 30) as f64)
    } else {
        format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64)
    }
}

/// Refuse a run whose estimate is above [`MEMORY_BUDGET_BYTES`], naming the
/// estimate, the budget and what to change: `output.record_every` when the
/// history is what does not fit, else the mesh, carriers or probes.
pub fn check_budget(
    e: &MemoryEstimate,
    steps: usize,
    every: usize,
    elements: usize,
    carriers: usize,
    probes: usize,
) -> Result<()> {
    let budget = MEMORY_BUDGET_BYTES;
    let memory_over = e.total() > budget;
    if !memory_over && e.csv <= OUTPUT_BUDGET_BYTES {
        return Ok(());
    }
    let filter = if e.filter > 0 {
        format!(" + {} of the filtered force", gib(e.filter))
    } else {
        String::new()
    };
    let need = format!(
        "the run needs an estimated {} ({} rows × {} bytes of history, {} of them again while history.csv is written, + {} of model + {} of contact events and output buffers{filter}), above the memory budget of {}",
        gib(e.total()),
        e.rows,
        e.row,
        csv_block_rows(e.rows),
        gib(e.model),
        gib(e.other()),
        gib(budget)
    );
    // what does not shrink with fewer rows (the filter does: it is gone
    // at record_every ≥ 2, which every hint below asks for)
    let fixed = e.model.saturating_add(e.other());
    if memory_over && fixed.saturating_add(4 * e.row) > budget {
        // even a two-row history does not fit: the model, the carriers'
        // events or a row is too big
        return Err(if fixed > budget / 2 {
            Error::invalid(
                "mesh.elements",
                elements,
                format!("with {carriers} carrier(s): {need}: use fewer elements or carriers"),
            )
        } else {
            Error::invalid(
                "probe",
                format!("{probes} probes"),
                format!("{need}: use fewer probes or carriers"),
            )
        });
    }
    // the fewest rows that fit both budgets, and the record_every that gives
    // them (at record_every ≥ 2 the filtered force's column is gone too)
    let thinned_values = if every <= 1 {
        e.csv_values.saturating_sub(carriers as u64)
    } else {
        e.csv_values
    };
    let row_csv = thinned_values.saturating_mul(CSV_BYTES_PER_VALUE).max(1);
    let rows_fit_csv = (OUTPUT_BUDGET_BYTES / row_csv).max(2);
    let rows_fit_memory = if memory_over {
        // rows r that fit: fixed + r·row + min(r, block)·row ≤ budget
        let (avail, row) = (budget - fixed, e.row.max(1));
        let block = HISTORY_ROWS_AT_A_TIME as u64;
        if avail >= 2 * block * row {
            (avail - block * row) / row
        } else {
            avail / (2 * row) // ≥ 2 here
        }
    } else {
        u64::MAX
    };
    let rows_fit = rows_fit_csv.min(rows_fit_memory).max(2);
    let min_every = (steps as u64).div_ceil(rows_fit - 1).max(every as u64 + 1);
    let csv = format!(
        "history.csv would hold an estimated {} ({} rows × {} values × {CSV_BYTES_PER_VALUE} bytes), above the output budget of {}",
        gib(e.csv),
        e.rows,
        e.csv_values,
        gib(OUTPUT_BUDGET_BYTES)
    );
    let why = match (memory_over, e.csv > OUTPUT_BUDGET_BYTES) {
        (true, true) => format!("{need}; {csv}"),
        (true, false) => need,
        _ => csv,
    };
    Err(Error::invalid(
        "output.record_every",
        every,
        format!(
            "{why}: record fewer rows with [output] record_every ≥ {min_every} (statistics still use every step), or give fewer steps or probes"
        ),
    ))
}
