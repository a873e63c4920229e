//! `history.csv`: one row per recorded time.

use std::path::Path;

use super::table::{Column, Table};
use crate::error::Result;
use crate::run::RunOutput;

/// The history as a table: `t, x_m, beam_w, mass_q, gap, force,
/// in_contact`, then one column per probe. With several carriers the
/// per-carrier columns are suffixed `_0`, `_1`, … (carrier by carrier).
pub fn history_table(out: &RunOutput) -> Table {
    let h = &out.history;
    let nc = h.carriers.len();
    let name = |n: &str, c: usize| {
        if nc == 1 {
            n.to_string()
        } else {
            format!("{n}_{c}")
        }
    };
    let mut t = Table::new();
    t.push("t", Column::Real(h.t.clone()));
    for (c, tr) in h.carriers.iter().enumerate() {
        for (n, v) in [
            ("x_m", &tr.x),
            ("beam_w", &tr.w),
            ("mass_q", &tr.q),
            ("gap", &tr.gap),
            ("force", &tr.force),
        ] {
            t.push(name(n, c), Column::Real(v.clone()));
        }
        t.push(name("in_contact", c), Column::Bit(tr.in_contact.clone()));
    }
    for (n, col) in &h.probes {
        t.push(n.clone(), Column::Real(col.clone()));
    }
    t
}

/// Write the history ([`history_table`]) to `path`.
pub fn write_history(path: &Path, out: &RunOutput) -> Result<()> {
    history_table(out).write_csv(path)
}
