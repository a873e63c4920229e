//! The memory a run will need, estimated from the validated scene before
//! anything is allocated, and the budget it must fit.
//!
//! Every input within its documented range is accepted by the range checks,
//! but some combinations (10⁹ steps recorded row by row, 10⁵ probes, 10⁴
//! carriers on a fine mesh) would exhaust the machine's memory and abort the
//! process. Such a run is refused at validation with the estimate, the
//! budget and a way out, naming the key that drives the part that does not
//! fit (`super::budget_check`) — never started.
//!
//! Every allocation that grows with the scene is counted, from the sizes
//! the scene's keys give ([`RunSizes`]): the history (carriers, probes,
//! droppers: a column each), the model (mesh, both lines, the masses), the
//! contact problem's dense matrices (carriers and tension-only droppers),
//! the droppers' dense responses, a clarabel solver per problem size, the
//! wire's snapshots, field and envelope, the statistics' events, and the
//! working memory of every output. The files a run writes are estimated
//! too (`history.csv`, `snapshots.csv`, `field.csv`, `summary.json`).
//! `tests/memory_budget.rs` runs scenes across these keys and checks that
//! what a run allocates stays within the estimate.

use crate::model::banded::rhs_columns;

/// Bytes of one stored contact event of a carrier: its loss interval in
/// x/L and in t (two `[f64; 2]`, 32), the interval's class (1) and a
/// re-contact (80: seven f64 or usize, an `Option<f64>` and a flag, padded
/// to 8) of the record layer's statistics (`record::stats`); a run reserves
/// room for [`event_capacity`] of them per carrier before its first step.
/// `record/stats.rs` asserts at compile time that its types take exactly
/// this, so the plan cannot drift from them.
pub(crate) const EVENT_BYTES: u64 = 113;

/// Most loss intervals and re-contacts a run stores one by one (they are
/// all counted): a contact that chatters every step over 10⁹ steps would
/// otherwise hold gigabytes of intervals.
pub(crate) const MAX_STORED_EVENTS: usize = 10_000;

/// The most loss intervals (and re-contacts) a run of `steps` steps can
/// store per carrier: an interval needs a lost step, and two intervals a
/// closed step between them, so at most ⌈steps/2⌉; and at most
/// [`MAX_STORED_EVENTS`] are stored.
pub(crate) fn event_capacity(steps: usize) -> usize {
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
/// A 4.35·10⁷-row run wrote a 4.15 GB file before this bound.
pub(crate) const OUTPUT_BUDGET_BYTES: u64 = 4 << 30;

/// Bytes of one value of `history.csv`, counted generously: a value is at
/// most 24 characters in shortest round-trip form and a comma; measured
/// 95 bytes a row for 7 values (13.6 a value) on a 4.35·10⁷-row
/// `t2_stationary_mass` run, so 16 is an upper estimate for typical rows.
pub(crate) const CSV_BYTES_PER_VALUE: u64 = 16;

/// Bytes of one history row for the time column (`t`, f64).
pub(crate) const ROW_TIME_BYTES: u64 = 8;

/// Bytes of one history row per carrier: x_m, w, q, g and λ as f64, and the
/// contact flag as a bool (`record::CarrierTrace`).
pub(crate) const ROW_CARRIER_BYTES: u64 = 5 * 8 + 1;

/// Bytes of one history row per probe (v as f64).
pub(crate) const ROW_PROBE_BYTES: u64 = 8;

/// Banded n×n matrices a run keeps at once, counted generously: mass,
/// stiffness, damping, the effective matrix and its factor, the mass
/// factor of the initial state, and two spare for a method's second stage
/// (Bathe) or the spectrum estimate (central difference).
pub(crate) const BANDED_MATRICES: u64 = 8;

/// Dense n × `rhs_columns(nc)` blocks a run keeps at once: the step's
/// right-hand sides and the constraint columns A⁻¹r of every carrier, plus
/// the initial state's, counted generously.
pub(crate) const RHS_BLOCKS: u64 = 4;

/// Dense nc × nc matrices of the contact solve (W, its reduced and modified
/// copies, the active block), counted generously.
pub(crate) const DENSE_CONTACT_MATRICES: u64 = 6;

/// The extra memory of a `modal` basis of J modes over n_fe FE unknowns:
/// the dense eigenproblem at its peak ([`crate::model::eigen::eigen_bytes`]:
/// C, the eigenvectors and faer's workspace, from faer's own requirement,
/// ≈ 5 n² · 8 bytes; counted as 4 n² · 8 before, which a run at n = 1999
/// exceeded by 32 MiB) and the n_fe × J mode shapes kept for the run.
pub(crate) fn modal_bytes(n_fe: usize, modes: usize) -> u64 {
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
pub(crate) const PLOT_BUCKETS: usize = 2000;

/// A force plot draws the filtered force of at most this many carriers
/// (the first; one line a colour of the palette): beyond, the raw lines
/// alone, so that a scene of thousands of carriers does not double its
/// plot's memory.
pub(crate) const MAX_FILTERED_LINES: usize = 10;

/// Rows of the history formatted at a time by `report::write_history`: a
/// few MB of columns, however long the history (building the whole table
/// copied the history once more: 1 GB more at 2·10⁷ rows).
/// Defined here, with the memory plan that counts it (`csv_block_rows`).
pub const HISTORY_ROWS_AT_A_TIME: usize = 1 << 16;

/// Characters of one `history.csv` cell at most: a value in shortest
/// round-trip form (`-1.2345678901234567e-308`, 24) and its comma.
pub(crate) const CSV_CELL_CHARS: u64 = 25;

/// `force.svg` text per point of a force line: `x,y ` in pixels of a
/// 960 × 480 plot, at most 3 + 1 + 3 + 1.
pub(crate) const SVG_POINT_BYTES: u64 = 8;

/// `force.svg` text per shaded loss interval: a `<rect …/>` line, measured
/// 88–90 bytes (reference scene, `contact.placement=alpha`), rounded up.
pub(crate) const SVG_RECT_BYTES: u64 = 96;

/// `force.svg` text that does not grow with the data (axes, ticks, labels,
/// legend): measured ≈ 22 KB, counted as 64 KiB.
pub(crate) const SVG_FIXED_BYTES: u64 = 64 << 10;

/// A text grown by doubling holds at most 3× its length at once (the old
/// buffer and the new one, twice the old, while it is copied).
pub(crate) const GROWN_TEXT_FACTOR: u64 = 3;

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
pub(crate) fn output_bytes(csv_values: u64, carriers: usize, events: usize) -> u64 {
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
pub(crate) fn csv_block_rows(rows: u64) -> u64 {
    rows.min(HISTORY_ROWS_AT_A_TIME as u64)
}

/// The sizes a run's memory grows with, read off a validated scene
/// (`crate::Resolved::run_sizes`): every count, from every key, that an
/// allocation of the run, its records or its outputs is proportional to.
/// [`estimate`] turns them into bytes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RunSizes {
    /// Steps of the run.
    pub steps: usize,
    /// Elements of the mesh (`mesh.elements`).
    pub elements: usize,
    /// The history keeps every this-many steps (`output.record_every`).
    pub every: usize,
    /// FE unknowns of the wire model, both lines (`mesh.elements`,
    /// `[messenger]`), before a modal truncation.
    pub fe_unknowns: usize,
    /// Half-bandwidth of the banded matrices (3 for Hermite elements, 1
    /// for string ones; 7 and 3 with a messenger, its unknowns
    /// interleaved with the contact wire's).
    pub half_band: usize,
    /// Mass unknowns of the carriers: one per mass–spring, one per mass
    /// of a multi-mass pantograph.
    pub masses: usize,
    /// Carriers (`[[carrier]]`).
    pub carriers: usize,
    /// Probes (`[[probe]]`).
    pub probes: usize,
    /// Droppers, linear and tension-only (`[[dropper]]`, or generated by
    /// `[line]`): a `history.csv` column and statistics each.
    pub droppers: usize,
    /// Tension-only droppers: a row of the step's contact problem each,
    /// with a dense response over the unknowns.
    pub tension_droppers: usize,
    /// Point attachments (`[[attachment]]`, steady arms of `[line]`).
    pub attachments: usize,
    /// The contact law is complementarity solved by clarabel, which keeps
    /// one QP solver per problem size it meets.
    pub clarabel: bool,
    /// Modes of a `modal` basis: its dense eigenproblem (`None` otherwise).
    pub modal_modes: Option<usize>,
    /// Dense weights of a point vector (the modes J of a `modal` or
    /// `galerkin` basis; 0 on a mesh).
    pub dense_weights: usize,
    /// Snapshot times (`output.snapshots`) and points each.
    pub snapshots: usize,
    /// Points of each snapshot.
    pub snapshot_points: usize,
    /// Rows of the field (`output.field`: steps 0, K, 2K, …; 0 without).
    pub field_rows: usize,
    /// Points of each field row.
    pub field_points: usize,
    /// Nodes of the envelope (`output.envelope`; 0 without).
    pub envelope_points: usize,
    /// The line's supports (`output.supports` or the messenger's).
    pub supports: usize,
    /// Load vectors over the unknowns of a manufactured source (two or
    /// three a term, on each line).
    pub source_vectors: usize,
    /// Values of the scene's tabulated series (speed tables, external
    /// forces), held in the scene, its copy in the run and the motion.
    pub table_values: usize,
}

impl RunSizes {
    /// Unknowns of the time stepping: the wire model's and the masses'.
    pub fn unknowns(&self) -> u64 {
        (self.fe_unknowns as u64).saturating_add(self.masses as u64)
    }

    /// Rows of the step's contact problem at most: the contacts and the
    /// tension-only droppers.
    pub fn problem_rows(&self) -> u64 {
        (self.carriers as u64).saturating_add(self.tension_droppers as u64)
    }
}

/// Bytes of one point vector (`model::beam::PointVector`: four indices,
/// four weights and the handle of a modal basis's dense weights), beside
/// its dense weights on the heap.
pub(crate) const POINT_VECTOR_BYTES: u64 =
    std::mem::size_of::<crate::model::beam::PointVector>() as u64;

/// Bytes of one dropper beside its dense blocks and its records, counted
/// generously: its spec in the scene and in the run's copy of it (name,
/// position, stiffness, anchor, length: ≈ 150 bytes each), its resolved
/// props, its link in the run (two point vectors, k, c, e₀), its
/// statistics' accumulator and its history column's header and name, and,
/// for a linear dropper, the attachment its spring becomes. Measured
/// ≈ 1.1 KB a dropper on a 1980-dropper line (`tests/memory_budget.rs`).
pub(crate) const DROPPER_BYTES: u64 = 2048;

/// Bytes of one point attachment beside the model's matrices: its spec
/// twice (scene, run), its props and its point vector, counted generously.
pub(crate) const ATTACHMENT_BYTES: u64 = 1024;

/// Bytes of one carrier beside its history and events: its spec twice,
/// its props and motion, its point vectors and work arrays (a few KB;
/// counted generously).
pub(crate) const CARRIER_BYTES: u64 = 8192;

/// Bytes of one stored slack interval of a dropper (`[t_start, t_end]`).
pub(crate) const SLACK_INTERVAL_BYTES: u64 = 16;

/// Copies of a dropper's slack intervals held at once: the list grows by
/// doubling (up to twice its length in capacity) and `summary.json`'s
/// statistics copy it once.
pub(crate) const SLACK_INTERVAL_COPIES: u64 = 3;

/// Dense (n × tension-only droppers) blocks of the droppers' step: the
/// responses z'_d = A'⁻¹ r_d, one column of n a dropper
/// (`integrate::dropper`).
pub(crate) const DROPPER_RESPONSE_BLOCKS: u64 = 1;

/// Dense (droppers × droppers) matrices of the droppers' step: Q, H's
/// Cholesky factor and G = H⁻¹ (`integrate::dropper`).
pub(crate) const DROPPER_SQUARE_MATRICES: u64 = 3;

/// Dense (contacts × droppers) blocks of the droppers' step: P, Ê and ÊG.
pub(crate) const DROPPER_COUPLING_BLOCKS: u64 = 3;

/// Bytes clarabel's solver for a dense QP of size s holds, per entry of
/// s²: P's upper triangle (values and row indices), the KKT matrix and
/// its LDLᵀ factor (dense for a dense P) and their maps, counted
/// generously; measured ≈ 70 s² bytes at s = 60 (`tests/memory_budget.rs`).
pub(crate) const CLARABEL_BYTES_PER_ENTRY: u64 = 128;

/// `envelope.csv`, `line.svg` and the envelope's record per node: x,
/// v_min, v_max and both wires' start shapes (5 f64), two point vectors
/// (the contact wire's and the messenger's) and the picture's points and
/// text (three lines of (x, v) pairs held twice, and the SVG text grown by
/// doubling), counted generously.
pub(crate) const ENVELOPE_BYTES_PER_NODE: u64 = 5 * 8 + 3 * 2 * 16 + 3 * 8 * GROWN_TEXT_FACTOR;

/// `line.svg` text per dropper (its line and label), counted generously.
pub(crate) const LINE_SVG_BYTES_PER_DROPPER: u64 = 256 * GROWN_TEXT_FACTOR;

/// Copies a tabulated value of the scene is held in during a run: the
/// scene and the run's copy of it, the resolved motion or force series,
/// and a spare.
pub(crate) const TABLE_VALUE_COPIES: u64 = 4;

/// Characters of one value of `summary.json` as serde_json's pretty
/// printer writes it inside the nested lists of events: its indentation
/// (up to 14 spaces at the depth of a dropper's slack interval), up to 24
/// characters and a comma and line break.
pub(crate) const JSON_BYTES_PER_VALUE: u64 = 48;

/// `summary.json` values per stored contact event of a carrier: its loss
/// interval in x/L and t (4), its class (1) and a re-contact's seven
/// fields with their names (counted as 3 values each).
pub(crate) const JSON_VALUES_PER_EVENT: u64 = 4 + 1 + 7 * 3;

/// `summary.json` text that does not grow with the events (the scene
/// echoed, the derived figures, the statistics), counted generously.
pub(crate) const SUMMARY_FIXED_BYTES: u64 = 1 << 20;

/// The memory a run is estimated to need, bytes: an upper bound of what it
/// holds at its peak, writing its outputs included (checked against the
/// allocations of runs across the size-driving keys by
/// `tests/memory_budget.rs` and against the binary's peak resident size by
/// `tests/memory_peak.rs`), and the sizes of the files it writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// The recorded history: rows × (t + carriers + probes + droppers).
    pub history: u64,
    /// Bytes of one history row.
    pub row: u64,
    /// Rows the history will hold.
    pub rows: u64,
    /// The model and the integrator's work arrays: banded matrices, the
    /// carriers' columns, the contact problem's dense matrices, a modal
    /// basis's eigenproblem, a manufactured source's load vectors.
    pub model: u64,
    /// The droppers: their dense responses and matrices (tension-only)
    /// and each dropper's own data; the attachments'; the carriers'.
    pub droppers: u64,
    /// A complementarity law's clarabel solvers, one per problem size.
    pub solvers: u64,
    /// The statistics' stored events: the carriers' loss intervals and
    /// re-contacts (`event_capacity` per carrier, reserved before the
    /// first step) and the droppers' slack intervals.
    pub events: u64,
    /// The wire's records: snapshots, the field, the envelope and the
    /// supports, with their point vectors.
    pub wire: u64,
    /// The block of `history.csv` formatted at a time: `csv_block_rows`
    /// rows × [`Self::row`].
    pub csv_block: u64,
    /// The rest of the working memory of writing the outputs
    /// (`output_bytes`, `line.svg`, `summary.json`'s copies).
    pub outputs: u64,
    /// The filtered force the history keeps beside the force: one copy of
    /// every carrier's force history (`FILTER_BYTES_PER_ROW` a row and
    /// carrier), when the history holds every step (else there is no
    /// filtered force and this is 0). It shrinks with the rows, like the
    /// history.
    pub filter: u64,
    /// The estimated size of `history.csv`, bytes (on disk, not in memory).
    pub csv: u64,
    /// Values in one row of `history.csv`.
    pub csv_values: u64,
    /// The estimated size of `snapshots.csv`, `field.csv`,
    /// `envelope.csv` and `line.svg`, bytes.
    pub wire_csv: u64,
    /// The estimated size of `summary.json`, bytes.
    pub summary_json: u64,
}

impl MemoryEstimate {
    /// Everything, bytes.
    pub fn total(&self) -> u64 {
        self.history
            .saturating_add(self.csv_block)
            .saturating_add(self.filter)
            .saturating_add(self.fixed())
    }

    /// What does not grow with the history's rows.
    pub fn fixed(&self) -> u64 {
        self.model
            .saturating_add(self.droppers)
            .saturating_add(self.solvers)
            .saturating_add(self.wire)
            .saturating_add(self.other())
    }

    /// The statistics' events and the output buffers.
    pub fn other(&self) -> u64 {
        self.events.saturating_add(self.outputs)
    }

    /// Every file the run writes, bytes (`history.csv`, `snapshots.csv`,
    /// `field.csv`, `summary.json`; the plots are bounded by
    /// `output_bytes`'s terms and small).
    pub fn files(&self) -> u64 {
        self.csv
            .saturating_add(self.wire_csv)
            .saturating_add(self.summary_json)
    }
}

/// Bytes a history row adds per carrier for its filtered force
/// (`CarrierTrace::force_filtered`: the forward pass's output, one f64 a
/// row, filtered back in place).
pub(crate) const FILTER_BYTES_PER_ROW: u64 = 8;

/// Rows of a history that records row 0 (t = 0), every `every`-th step and
/// always the last step.
pub(crate) fn history_rows(steps: usize, every: usize) -> usize {
    1 + steps.div_ceil(every.max(1))
}

/// Values of `snapshots.csv` (`t_requested`, `t`, `x`, `v`) and
/// `field.csv` (`t`, `x`, `v`) a row.
const SNAPSHOT_CSV_VALUES: u64 = 4;
const FIELD_CSV_VALUES: u64 = 3;

/// Σ_{s=1}^{n} s², saturating: the entries of one dense QP of every size
/// up to n.
fn squares_up_to(n: u64) -> u64 {
    // n(n+1)(2n+1)/6, each factor first divided where it can be
    let (a, b, c) = (
        n,
        n.saturating_add(1),
        n.saturating_mul(2).saturating_add(1),
    );
    let (mut f, mut g, mut h) = (a, b, c);
    for d in [2u64, 3] {
        if f % d == 0 {
            f /= d;
        } else if g % d == 0 {
            g /= d;
        } else {
            h /= d;
        }
    }
    f.saturating_mul(g).saturating_mul(h)
}

/// Estimate the memory of a run of the given sizes and the files it
/// writes. Saturating arithmetic: an absurd input gives `u64::MAX`, never
/// an overflow.
pub fn estimate(s: &RunSizes) -> MemoryEstimate {
    let u = |x: usize| x as u64;
    let rows = u(history_rows(s.steps, s.every));
    let row = ROW_TIME_BYTES
        .saturating_add(ROW_CARRIER_BYTES.saturating_mul(u(s.carriers)))
        .saturating_add(ROW_PROBE_BYTES.saturating_mul(u(s.probes)))
        .saturating_add(ROW_PROBE_BYTES.saturating_mul(u(s.droppers)));
    let n = s.unknowns();
    let nt = s.problem_rows();
    let per_dof = BANDED_MATRICES
        .saturating_mul(2 * u(s.half_band) + 1)
        .saturating_add(RHS_BLOCKS.saturating_mul(u(rhs_columns(s.carriers))))
        .saturating_add(u(s.source_vectors));
    let (m, nc) = (u(s.tension_droppers), u(s.carriers));
    // the contact problem's dense matrices: the contacts' block in the
    // model, the rest of nt × nt the droppers'
    let dense = |rows: u64| {
        rows.saturating_mul(rows)
            .saturating_mul(8 * DENSE_CONTACT_MATRICES)
    };
    let mut model = n
        .saturating_mul(per_dof)
        .saturating_mul(8)
        .saturating_add(dense(nc));
    if let Some(modes) = s.modal_modes {
        model = model.saturating_add(modal_bytes(s.fe_unknowns, modes));
    }
    let droppers = dense(nt)
        .saturating_sub(dense(nc))
        .saturating_add(
            n.saturating_mul(m)
                .saturating_mul(8 * DROPPER_RESPONSE_BLOCKS),
        )
        .saturating_add(
            m.saturating_mul(m)
                .saturating_mul(8 * DROPPER_SQUARE_MATRICES),
        )
        .saturating_add(
            nc.saturating_mul(m)
                .saturating_mul(8 * DROPPER_COUPLING_BLOCKS),
        )
        .saturating_add(u(s.droppers).saturating_mul(DROPPER_BYTES))
        .saturating_add(u(s.attachments).saturating_mul(ATTACHMENT_BYTES))
        .saturating_add(nc.saturating_mul(CARRIER_BYTES))
        .saturating_add(
            u(s.table_values)
                .saturating_mul(8)
                .saturating_mul(TABLE_VALUE_COPIES),
        );
    let solvers = if s.clarabel {
        squares_up_to(nt).saturating_mul(CLARABEL_BYTES_PER_ENTRY)
    } else {
        0
    };
    // t, then x, w, q, gap, λ, the contact flag and (with every step kept)
    // the filtered λ per carrier, then probes, then droppers
    let per_carrier = if s.every <= 1 { 7 } else { 6 };
    let csv_values = 1 + per_carrier * nc + u(s.probes) + u(s.droppers);
    let events = event_capacity(s.steps);
    let ev = u(events);
    let slack = u(s.droppers)
        .saturating_mul(ev)
        .saturating_mul(SLACK_INTERVAL_BYTES);
    let wire_values = u(s.snapshots)
        .saturating_mul(u(s.snapshot_points))
        .saturating_add(u(s.field_rows).saturating_mul(u(s.field_points)));
    let wire_points = u(s.snapshot_points)
        .saturating_add(u(s.field_points))
        .saturating_add(u(s.supports));
    let point = POINT_VECTOR_BYTES.saturating_add(u(s.dense_weights).saturating_mul(8));
    // each value once; each point's x in the plan and in the record, and
    // its point vector; the envelope's nodes
    let wire = wire_values
        .saturating_mul(8)
        .saturating_add(wire_points.saturating_mul(point.saturating_add(16)))
        .saturating_add(u(s.supports).saturating_mul(64))
        .saturating_add(
            u(s.envelope_points).saturating_mul(ENVELOPE_BYTES_PER_NODE.saturating_add(2 * point)),
        );
    let summary_json = nc
        .saturating_add(1)
        .saturating_mul(ev)
        .saturating_mul(JSON_VALUES_PER_EVENT)
        .saturating_add(u(s.droppers).saturating_mul(ev).saturating_mul(2))
        .saturating_mul(JSON_BYTES_PER_VALUE)
        .saturating_add(SUMMARY_FIXED_BYTES);
    // snapshots.csv, field.csv, and envelope.csv (x, v_min, v_max) with
    // line.svg's text (three lines of points, ≤ 16 characters a point)
    let wire_csv = u(s.envelope_points)
        .saturating_mul(3 * CSV_BYTES_PER_VALUE + 3 * 16)
        .saturating_add(
            u(s.snapshots)
                .saturating_mul(u(s.snapshot_points))
                .saturating_mul(SNAPSHOT_CSV_VALUES)
                .saturating_add(
                    u(s.field_rows)
                        .saturating_mul(u(s.field_points))
                        .saturating_mul(FIELD_CSV_VALUES),
                )
                .saturating_mul(CSV_BYTES_PER_VALUE),
        );
    MemoryEstimate {
        history: rows.saturating_mul(row),
        row,
        rows,
        model,
        droppers,
        solvers,
        events: nc
            .saturating_mul(ev)
            .saturating_mul(EVENT_BYTES)
            .saturating_add(slack.saturating_mul(SLACK_INTERVAL_COPIES)),
        wire,
        csv_block: csv_block_rows(rows).saturating_mul(row),
        outputs: output_bytes(csv_values, s.carriers, events)
            .saturating_add(u(s.droppers).saturating_mul(LINE_SVG_BYTES_PER_DROPPER)),
        filter: if s.every <= 1 {
            rows.saturating_mul(FILTER_BYTES_PER_ROW)
                .saturating_mul(nc.max(1))
        } else {
            0
        },
        csv: rows
            .saturating_mul(csv_values)
            .saturating_mul(CSV_BYTES_PER_VALUE),
        csv_values,
        wire_csv,
        summary_json,
    }
}

/// Bytes as GiB (MiB below 1 GiB), for messages.
pub(crate) fn gib(b: u64) -> String {
    if b >= 1 << 30 {
        format!("{:.3} GiB", b as f64 / (1u64 << 30) as f64)
    } else {
        format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squares_up_to_is_the_sum_of_squares() {
        for n in 0..200u64 {
            assert_eq!(squares_up_to(n), (1..=n).map(|s| s * s).sum::<u64>(), "{n}");
        }
        assert_eq!(squares_up_to(u64::MAX), u64::MAX);
    }
}
