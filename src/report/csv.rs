//! `history.csv`: one row per recorded time.

use std::path::Path;

use super::table::{Column, Table};
use crate::error::Result;
use crate::run::RunOutput;

/// The history as a table: `t, x_m, beam_w, mass_q, gap, force,
/// in_contact, force_filtered` (the last only when the history holds every
/// step: the filtered force, `[analysis] band`), then one column per probe, then `dropper_<name>_force` per
/// dropper (N, tension positive). With several carriers the
/// per-carrier columns are suffixed `_0`, `_1`, … (carrier by carrier).
pub fn history_table(out: &RunOutput) -> Table {
    history_rows(out, 0..out.history.t.len())
}

/// Rows `rows` of [`history_table`].
fn history_rows(out: &RunOutput, rows: std::ops::Range<usize>) -> Table {
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
    t.push("t", Column::Real(h.t[rows.clone()].to_vec()));
    for (c, tr) in h.carriers.iter().enumerate() {
        for (n, v) in [
            ("x_m", &tr.x),
            ("beam_w", &tr.w),
            ("mass_q", &tr.q),
            ("gap", &tr.gap),
            ("force", &tr.force),
        ] {
            t.push(name(n, c), Column::Real(v[rows.clone()].to_vec()));
        }
        t.push(
            name("in_contact", c),
            Column::Bit(tr.in_contact[rows.clone()].to_vec()),
        );
        if !tr.force_filtered.is_empty() {
            t.push(
                name("force_filtered", c),
                Column::Real(tr.force_filtered[rows.clone()].to_vec()),
            );
        }
    }
    for (n, col) in &h.probes {
        t.push(n.clone(), Column::Real(col[rows.clone()].to_vec()));
    }
    for (n, col) in &h.droppers {
        t.push(
            format!("dropper_{n}_force"),
            Column::Real(col[rows.clone()].to_vec()),
        );
    }
    t
}

pub use crate::resolve::memory::HISTORY_ROWS_AT_A_TIME;

/// Write the history ([`history_table`]) to `path`, a block of rows at a
/// time: the same bytes as the whole table's CSV.
pub(crate) fn write_history(path: &Path, out: &RunOutput) -> Result<()> {
    use std::io::Write;
    let io = |e| crate::error::Error::io(path, e);
    let file = std::fs::File::create(path).map_err(io)?;
    let mut w = std::io::BufWriter::new(file);
    let n = out.history.t.len();
    let mut start = 0;
    loop {
        let end = (start + HISTORY_ROWS_AT_A_TIME).min(n);
        history_rows(out, start..end)
            .lines_into(start == 0, &mut |line| w.write_all(line.as_bytes()))
            .map_err(io)?;
        if end >= n {
            break;
        }
        start = end;
    }
    w.flush().map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_in_blocks_the_history_is_the_whole_tables_bytes() {
        // more rows than one block, and not a multiple of it
        let sc = crate::resolve_scene(
            include_str!("../../scenes/t2_stationary_mass.toml"),
            &[
                "mesh.elements=4".to_string(),
                format!("time.end={}", (HISTORY_ROWS_AT_A_TIME + 1234) as f64 * 1e-6),
                "time.step=1e-6".to_string(),
            ],
        )
        .unwrap();
        let out = crate::run(&sc, &mut |_, _| {}).unwrap();
        assert!(out.history.t.len() > HISTORY_ROWS_AT_A_TIME + 1000);
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("history.csv");
        write_history(&path, &out).unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            history_table(&out).to_csv()
        );
    }
}
