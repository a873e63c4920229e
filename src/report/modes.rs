//! `modes.csv` and `mode_shapes.csv` of `taut modes` (docs/output.md).

use std::path::Path;

use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::modes::Modes;

/// `modes.csv`: `index` (1, 2, …), `frequency_hz`, `source` (`fe_eigen` or
/// `exact`), `string_hz` (the taut string's j c / (2L); empty where it does
/// not apply).
pub fn modes_table(m: &Modes) -> Table {
    let n = m.frequencies_hz.len();
    let mut t = Table::new();
    t.push("index", Column::Count((1..=n as u64).collect()));
    t.push("frequency_hz", Column::Real(m.frequencies_hz.clone()));
    t.push(
        "source",
        Column::Label(vec![m.source.name().to_string(); n]),
    );
    t.push(
        "string_hz",
        Column::RealOrNone(m.string_hz.clone().unwrap_or_else(|| vec![f64::NAN; n])),
    );
    t
}

/// `mode_shapes.csv`: `x` (m) and one column `mode_1`, `mode_2`, … per mode
/// (kg^−1/2, mass-normalized; [`crate::study::modes`]).
pub fn mode_shapes_table(m: &Modes) -> Table {
    let mut t = Table::new();
    t.push("x", Column::Real(m.x.clone()));
    for (j, s) in m.shapes.iter().enumerate() {
        t.push(format!("mode_{}", j + 1), Column::Real(s.clone()));
    }
    t
}

/// Write `modes.csv` and `mode_shapes.csv` into `dir`.
pub(crate) fn write_modes(dir: &Path, m: &Modes) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    modes_table(m).write_csv(&dir.join("modes.csv"))?;
    mode_shapes_table(m).write_csv(&dir.join("mode_shapes.csv"))
}
