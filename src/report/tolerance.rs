//! Outputs of an accuracy-targeted run (`taut run --tolerance`): the usual
//! files of the reported run, `summary.json` with an `accuracy` object,
//! `accuracy.csv` (every run the one-point sweep made), and the terminal
//! lines that put a u_num next to every result (formats in
//! `docs/output.md`).

use std::path::Path;

use serde::Serialize;

use super::table::{Column, Table};
use super::{Summary, write_force_plot, write_history};
use crate::error::{Error, Result};
use crate::study::tolerance::{Accuracy, ResultEstimate, TolerantRun};

/// Column order of `accuracy.csv`.
pub const ACCURACY_COLUMNS: [&str; 9] = [
    "role",
    "mesh_exponent",
    "step_exponent",
    "elements",
    "modes",
    "dt",
    "value",
    "dof_steps",
    "u_num",
];

/// `summary.json` of an accuracy-targeted run: the ordinary summary with
/// `accuracy` added at the top level.
#[derive(Serialize)]
pub struct WithAccuracy<'a> {
    /// The run's summary.
    #[serde(flatten)]
    pub summary: &'a Summary,
    /// How the resolution was chosen and the estimated errors.
    pub accuracy: &'a Accuracy,
}

/// Write `history.csv`, `summary.json` (with `accuracy`), `force.svg` and
/// `accuracy.csv` into `dir` (created if missing).
pub(crate) fn write_tolerant_run(dir: &Path, r: &TolerantRun) -> Result<Summary> {
    super::write_whole(dir, "taut run --tolerance", || {
        write_history(&dir.join("history.csv"), &r.output)?;
        let summary = Summary::new(&r.scene, &r.output);
        write_force_plot(&dir.join("force.svg"), &r.scene, &r.output)?;
        super::write_standard(dir, &r.scene, &summary.standard, &summary.supports)?;
        super::write_wire(dir, &r.output.history)?;
        super::write_line(dir, &r.scene, &r.output, &summary.spans)?;
        let csv = dir.join("accuracy.csv");
        std::fs::write(&csv, accuracy_csv(&r.accuracy)).map_err(|e| Error::io(&csv, e))?;
        // last: a folder with a summary and no marker is a finished run's
        super::write_json(
            &dir.join("summary.json"),
            &WithAccuracy {
                summary: &summary,
                accuracy: &r.accuracy,
            },
        )?;
        Ok(summary)
    })
}

/// `accuracy.csv` as a table ([`ACCURACY_COLUMNS`]): one row per run
/// made, coarsest first; a run's (a, b) are the exponents of N₀·2^a (J₀ on
/// a modal basis) and Δt₀/2^b; `u_num` is given on the run that ends a
/// candidate's family. Unknown values are empty cells.
pub fn accuracy_table(a: &Accuracy) -> Table {
    let rows = &a.point.runs_made;
    let columns = [
        Column::Label(rows.iter().map(|r| r.role.name().to_string()).collect()),
        Column::Label(rows.iter().map(|r| r.mesh_exponent.to_string()).collect()),
        Column::Label(rows.iter().map(|r| r.step_exponent.to_string()).collect()),
        Column::Count(rows.iter().map(|r| r.elements as u64).collect()),
        Column::CountOrNone(rows.iter().map(|r| r.modes.map(|j| j as u64)).collect()),
        Column::Real(rows.iter().map(|r| r.dt).collect()),
        Column::RealOrNone(rows.iter().map(|r| r.value.unwrap_or(f64::NAN)).collect()),
        Column::Real(rows.iter().map(|r| r.dof_steps).collect()),
        Column::RealOrNone(rows.iter().map(|r| r.u_num.unwrap_or(f64::NAN)).collect()),
    ];
    let mut t = Table::new();
    for (name, column) in ACCURACY_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t
}

/// `accuracy.csv`'s text ([`accuracy_table`]).
pub(crate) fn accuracy_csv(a: &Accuracy) -> String {
    accuracy_table(a).to_csv()
}

/// The terminal lines before the usual summary: what was asked, the runs
/// made and the resolution reported.
pub fn accuracy_header(a: &Accuracy) -> String {
    let p = &a.point;
    let mut s = format!(
        "  accuracy {} ≤ {:e}{} requested (u_num, as a one-point `taut sweep --tolerance`): {}\n",
        a.quantity,
        a.tolerance,
        unit(a.unit),
        a.definition
    );
    let own = a
        .point
        .runs_made
        .iter()
        .find(|r| (r.mesh_exponent, r.step_exponent) == (0, 0))
        .map_or(f64::NAN, |r| r.dof_steps);
    s.push_str(&format!(
        "  runs     {} runs (the pilots and {} check(s)): {:.3e} DOF-steps, {:.1}× the scene's own run (--max-cost {})\n",
        p.runs,
        p.checks,
        p.dof_steps,
        p.dof_steps / own,
        a.max_cost
    ));
    let (sym, key, level) = match p.modes {
        Some(j) => ("J", "mesh.modes", j),
        None => ("N", "mesh.elements", p.elements),
    };
    let fe = match p.modes {
        // a modal basis's FE mesh grows with J
        Some(_) if a.point.runs_made.iter().any(|r| r.elements != p.elements) => {
            format!(" --set mesh.elements={}", p.elements)
        }
        _ => String::new(),
    };
    s.push_str(&format!(
        "  chosen   {sym} = {level}, Δt = {:.5e} s: {} = {:.6e} ± {:.3e} (u_num, {}); the same run: --set {key}={level}{fe} --set time.step={:e}\n",
        p.dt, a.quantity, p.value, p.u_num, p.estimator, p.dt
    ));
    s
}

/// Labels of the results in the terminal ([`crate::quantity::Quantity::label`]).
fn label(name: &str) -> &'static str {
    crate::quantity::by_name(name).map_or("result", |q| q.label)
}

/// A unit after a number: none for a dimensionless quantity (`-`).
fn unit(u: &str) -> String {
    if u == "-" {
        String::new()
    } else {
        format!(" {u}")
    }
}

fn estimate_text(r: &ResultEstimate) -> String {
    match r.u_num {
        Some(0.0) => format!("± 0 (u_num, {})", r.estimator),
        Some(u) => format!("± {u:.2e} (u_num, {})", r.estimator),
        None if r.value.is_none() => "no u_num (undefined)".to_string(),
        None => format!("no u_num (values {})", r.behaviour),
    }
}

/// One line per result of carrier 0 (the carrier a sweep's quantities
/// are of): value, unit, u_num.
pub fn result_lines(a: &Accuracy) -> String {
    let mut s = String::new();
    for r in &a.results {
        let value = match r.value {
            Some(v) if r.unit == "N" => format!("{v:.4} N"),
            Some(v) => format!("{v:.4}"),
            None => "none".to_string(),
        };
        s.push_str(&format!(
            "    {:<20} {:>14}  {}\n",
            label(r.name),
            value,
            estimate_text(r)
        ));
    }
    s
}
