//! What a catenary engineer checks of a form-found line at rest
//! (`docs/lines.md` eq. F1–F5, docs/output.md#form-finding):
//! `static_heights.csv` (the contact wire's static height at each design
//! dropper against its design) and `droppers_static.csv` (every dropper's
//! length, force and wire height at rest). Written only when a dropper has
//! a `design_height`.

use std::path::Path;

use super::table::{Column, Table};
use crate::error::Result;
use crate::integrate::FormFound;
use crate::resolve::Resolved;

/// `static_heights.csv`: a row per dropper with a design height: `name`,
/// `x` (m), `design` (V_d, m), `static` (v_c(x_d) at rest, m, v up) and
/// `difference` (static − design, m).
pub fn static_heights_table(sc: &Resolved, form: &FormFound) -> Table {
    let rows: Vec<(usize, f64, f64)> = form
        .droppers
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.design.map(|v| (i, v, d.height)))
        .collect();
    let mut t = Table::new();
    t.push(
        "name",
        Column::Label(rows.iter().map(|r| sc.droppers[r.0].name.clone()).collect()),
    );
    t.push(
        "x",
        Column::Real(rows.iter().map(|r| sc.droppers[r.0].x).collect()),
    );
    t.push("design", Column::Real(rows.iter().map(|r| r.1).collect()));
    t.push("static", Column::Real(rows.iter().map(|r| r.2).collect()));
    t.push(
        "difference",
        Column::Real(rows.iter().map(|r| r.2 - r.1).collect()),
    );
    t
}

/// `droppers_static.csv`: a row per dropper, in scene order: `name`, `x`
/// (m), `length` (ℓ_0 the run uses, m), `force` (N_d at rest, N, tension
/// positive), `height` (v_c(x_d) at rest, m, v up).
pub fn droppers_static_table(sc: &Resolved, form: &FormFound) -> Table {
    let d = &form.droppers;
    let mut t = Table::new();
    t.push(
        "name",
        Column::Label(sc.droppers.iter().map(|d| d.name.clone()).collect()),
    );
    t.push("x", Column::Real(sc.droppers.iter().map(|d| d.x).collect()));
    t.push("length", Column::Real(d.iter().map(|d| d.length).collect()));
    t.push("force", Column::Real(d.iter().map(|d| d.force).collect()));
    t.push("height", Column::Real(d.iter().map(|d| d.height).collect()));
    t
}

/// Write both tables into `dir` when the run form-found its line.
pub(crate) fn write_form(dir: &Path, sc: &Resolved, form: Option<&FormFound>) -> Result<()> {
    if let Some(form) = form {
        static_heights_table(sc, form).write_csv(&dir.join("static_heights.csv"))?;
        droppers_static_table(sc, form).write_csv(&dir.join("droppers_static.csv"))?;
    }
    Ok(())
}
