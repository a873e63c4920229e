//! What a line engineer reads of a run with supports (`[output] supports`,
//! or a `[messenger]`'s) or `[output] envelope` (docs/output.md#spans):
//! `spans.csv` (contact force statistics per carrier and span),
//! `supports.csv` (the wire's uplift at each support) and `envelope.csv`
//! (v's range over time at every node), with `line.svg` (`line_svg.rs`).
//! Each file is written only when the scene has what it needs; a scene with
//! neither supports nor the envelope writes none of them.

use std::path::Path;

use super::table::{Column, Table};
use crate::error::Result;
use crate::record::{Envelope, SpanStats, SupportUplift};
use crate::resolve::Resolved;
use crate::run::RunOutput;

/// A column of optional reals: `None` an empty cell (NaN in Python).
fn optional(rows: &[SpanStats], f: impl Fn(&SpanStats) -> Option<f64>) -> Column {
    Column::RealOrNone(rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect())
}

/// `spans.csv`: a row per carrier and span (carrier by carrier): `carrier`,
/// `span`, `x_start`, `x_end` (m), `samples` (steps), `force_mean`,
/// `force_std`, `force_max`, `force_min`, `filtered_mean`, `filtered_std`
/// (N), `loss_fraction`; an empty cell where a span has no step (or the
/// filtered force is not available).
pub fn spans_table(rows: &[SpanStats]) -> Table {
    let mut t = Table::new();
    let count =
        |f: fn(&SpanStats) -> usize| Column::Count(rows.iter().map(|r| f(r) as u64).collect());
    let real = |f: fn(&SpanStats) -> f64| Column::Real(rows.iter().map(f).collect());
    t.push("carrier", count(|r| r.carrier));
    t.push("span", count(|r| r.span));
    t.push("x_start", real(|r| r.x_start));
    t.push("x_end", real(|r| r.x_end));
    t.push("samples", count(|r| r.samples));
    t.push("force_mean", optional(rows, |r| r.force_mean));
    t.push("force_std", optional(rows, |r| r.force_std));
    t.push("force_max", optional(rows, |r| r.force_max));
    t.push("force_min", optional(rows, |r| r.force_min));
    t.push("filtered_mean", optional(rows, |r| r.filtered_mean));
    t.push("filtered_std", optional(rows, |r| r.filtered_std));
    t.push("loss_fraction", optional(rows, |r| r.loss_fraction));
    t
}

/// `supports.csv`: a row per support: `x` (m), `v_max`, `v_min` (m,
/// positive up), `t_max` (s, the first time of `v_max`), `v_static` (m,
/// the static position with no carrier) and `uplift` (m, v_max − v_static).
pub fn supports_table(rows: &[SupportUplift]) -> Table {
    let mut t = Table::new();
    let real = |f: fn(&SupportUplift) -> f64| Column::Real(rows.iter().map(f).collect());
    t.push("x", real(|r| r.x));
    t.push("v_max", real(|r| r.v_max));
    t.push("v_min", real(|r| r.v_min));
    t.push("t_max", real(|r| r.t_max));
    let opt = |f: fn(&SupportUplift) -> Option<f64>| {
        Column::RealOrNone(rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect())
    };
    t.push("v_static", opt(|r| r.v_static));
    t.push("uplift", opt(|r| r.uplift));
    t
}

/// `envelope.csv`: a row per mesh node: `x` (m), `v_min`, `v_max` (m,
/// positive up).
pub fn envelope_table(e: &Envelope) -> Table {
    let mut t = Table::new();
    t.push("x", Column::Real(e.x.clone()));
    t.push("v_min", Column::Real(e.v_min.clone()));
    t.push("v_max", Column::Real(e.v_max.clone()));
    t
}

/// Write `spans.csv` and `supports.csv` (with `[output] supports`; `spans`
/// are the summary's, filtered force included) and `envelope.csv` with
/// `line.svg` (with `[output] envelope`) into `dir`.
pub(crate) fn write_line(
    dir: &Path,
    sc: &Resolved,
    out: &RunOutput,
    spans: &[SpanStats],
) -> Result<()> {
    let h = &out.history;
    if !h.supports.is_empty() {
        if !spans.is_empty() {
            spans_table(spans).write_csv(&dir.join("spans.csv"))?;
        }
        supports_table(&h.supports).write_csv(&dir.join("supports.csv"))?;
    }
    if !h.envelope.is_empty() {
        envelope_table(&h.envelope).write_csv(&dir.join("envelope.csv"))?;
        super::line_svg::write_line_plot(&dir.join("line.svg"), sc, out)?;
    }
    Ok(())
}
