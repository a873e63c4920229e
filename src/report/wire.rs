//! `snapshots.csv` and `field.csv`: the wire's displacement along the span
//! (docs/output.md#snapshots), long form, one row per (time, point).

use std::path::Path;

use super::table::{Column, Table};
use crate::error::Result;
use crate::record::{History, WireSeries};

/// Columns `t` (the step's time, s), `x` (m) and `v` (m, positive up), a
/// row per (time, point) in time order then x order; with `requested`,
/// `t_requested` (the time asked for, s) first.
fn long_table(s: &WireSeries, requested: bool) -> Table {
    let np = s.x.len();
    let rows = s.rows() * np;
    let per_row = |col: &[f64]| -> Vec<f64> {
        col.iter()
            .flat_map(|&v| std::iter::repeat_n(v, np))
            .collect()
    };
    let mut t = Table::new();
    if requested {
        t.push("t_requested", Column::Real(per_row(&s.requested)));
    }
    t.push("t", Column::Real(per_row(&s.t)));
    t.push(
        "x",
        Column::Real(s.x.iter().copied().cycle().take(rows).collect()),
    );
    t.push("v", Column::Real(s.v.clone()));
    t
}

/// `snapshots.csv`: `t_requested`, `t`, `x`, `v`.
pub fn snapshots_table(s: &WireSeries) -> Table {
    long_table(s, true)
}

/// `field.csv`: `t`, `x`, `v`.
pub fn field_table(s: &WireSeries) -> Table {
    long_table(s, false)
}

/// Write `snapshots.csv` and `field.csv` into `dir`, each only when the
/// scene asked for it.
pub fn write_wire(dir: &Path, h: &History) -> Result<()> {
    if !h.snapshots.is_empty() {
        snapshots_table(&h.snapshots).write_csv(&dir.join("snapshots.csv"))?;
    }
    if !h.field.is_empty() {
        field_table(&h.field).write_csv(&dir.join("field.csv"))?;
    }
    Ok(())
}
