//! Outputs of an accuracy-targeted run (`taut run --tolerance`): the usual
//! three files, `summary.json` with an `accuracy` object, `accuracy.csv`
//! (the pilots and the chosen run), and the terminal lines that put an
//! estimated error next to every result (formats in `docs/output.md`).

use std::path::Path;

use serde::Serialize;

use super::table::{Column, Table};
use super::{Summary, write_force_plot, write_history};
use crate::error::{Error, Result};
use crate::study::tolerance::{Accuracy, Estimate, LadderFit, ResultEstimate, TolerantRun};

/// Column order of `accuracy.csv`.
pub const ACCURACY_COLUMNS: [&str; 12] = [
    "role",
    "elements",
    "modes",
    "dt",
    "steps",
    "dofs",
    "dof_steps",
    "wall_seconds",
    "ladder_difference",
    "estimated_error",
    "estimated_mesh_error",
    "estimated_step_error",
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

/// `accuracy.csv` as a table ([`ACCURACY_COLUMNS`]): one row per pilot,
/// then the chosen run (`chosen`). Unknown values (a pilot's ladder
/// difference before it has a finer neighbour, an estimate that cannot be
/// made) are empty cells.
pub fn accuracy_table(a: &Accuracy) -> Table {
    struct Row<'a> {
        role: &'a str,
        elements: usize,
        modes: Option<usize>,
        dt: f64,
        steps: usize,
        dof_steps: f64,
        wall: f64,
        diff: f64,
        estimate: &'a Estimate,
    }
    let mut rows: Vec<Row> = a
        .pilots
        .iter()
        .map(|p| Row {
            role: p.role,
            elements: p.elements,
            modes: p.modes,
            dt: p.dt,
            steps: p.steps,
            dof_steps: p.dof_steps,
            wall: p.wall_seconds,
            diff: p.ladder_difference,
            estimate: &p.estimate,
        })
        .collect();
    let wall = match a.met_by_pilot {
        Some(role) => a
            .pilots
            .iter()
            .find(|p| p.role == role)
            .map_or(f64::NAN, |p| p.wall_seconds),
        None => a.run_wall_seconds,
    };
    rows.push(Row {
        role: "chosen",
        elements: a.elements,
        modes: a.modes,
        dt: a.dt,
        steps: a.steps,
        dof_steps: a.dof_steps,
        wall,
        diff: f64::NAN,
        estimate: &a.estimated_error,
    });
    let count = |f: fn(&Row) -> u64| Column::Count(rows.iter().map(f).collect());
    let measured = |f: fn(&Row) -> f64| Column::RealOrNone(rows.iter().map(f).collect());
    let columns = [
        Column::Label(rows.iter().map(|r| r.role.to_string()).collect()),
        count(|r| r.elements as u64),
        Column::CountOrNone(rows.iter().map(|r| r.modes.map(|j| j as u64)).collect()),
        Column::Real(rows.iter().map(|r| r.dt).collect()),
        count(|r| r.steps as u64),
        count(|r| (r.dof_steps / r.steps.max(1) as f64).round() as u64),
        Column::Real(rows.iter().map(|r| r.dof_steps).collect()),
        measured(|r| r.wall),
        measured(|r| r.diff),
        measured(|r| r.estimate.total),
        measured(|r| r.estimate.mesh),
        measured(|r| r.estimate.step),
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

fn order_text(f: &LadderFit) -> String {
    if f.status == crate::study::tolerance::LadderStatus::Exact {
        "none (no change over the pilots)".to_string()
    } else if f.order == f.observed_order {
        format!("{:.2}", f.order)
    } else if f.observed_order.is_finite() {
        format!(
            "{:.2} (observed {:.3}, capped at the method's)",
            f.order, f.observed_order
        )
    } else {
        format!("{:.2}", f.order)
    }
}

/// The terminal lines before the usual summary: what was asked, the pilots,
/// the model and the choice.
pub fn accuracy_header(a: &Accuracy) -> String {
    let mut s = format!(
        "  accuracy {} ≤ {:e} requested: {}\n",
        a.quantity.name(),
        a.tolerance,
        a.description
    );
    // the mesh ladder's level: N, or J on a modal basis
    let (sym, key) = match a.modes {
        Some(_) => ("J", "mesh.modes"),
        None => ("N", "mesh.elements"),
    };
    let pilots: Vec<String> = a
        .pilots
        .iter()
        .map(|p| {
            let n = p.modes.unwrap_or(p.elements);
            format!("{n} × {:e} s ({:.2} s)", p.dt, p.wall_seconds)
        })
        .collect();
    s.push_str(&format!(
        "  pilots   {sym} × Δt: {}; {:.2} s wall\n",
        pilots.join(", "),
        a.pilot_wall_seconds
    ));
    s.push_str(&format!(
        "  model    e ≈ {}·(C_h h^p + C_t Δt^q): p = {}, C_h = {:.3e}; q = {}, C_t = {:.3e}\n",
        a.model.safety_factor,
        order_text(&a.model.mesh),
        a.c_h,
        order_text(&a.model.step),
        a.c_t
    ));
    let how = match a.met_by_pilot {
        Some(role) => format!("the pilot `{role}` already meets it"),
        None => "the cheapest resolution the model allows".to_string(),
    };
    let level = a.modes.unwrap_or(a.elements);
    let fe = match a.modes {
        // a modal basis's FE mesh grows with J
        Some(_) if a.pilots.first().is_some_and(|p| p.elements != a.elements) => {
            format!(" --set mesh.elements={}", a.elements)
        }
        _ => String::new(),
    };
    s.push_str(&format!(
        "  chosen   {sym} = {level}, Δt = {:.5e} s ({how}): estimated error {:.3e} (mesh {:.3e}, step {:.3e}); the same run: --set {key}={level}{fe} --set time.step={:e}\n",
        a.dt,
        a.estimated_error.total,
        a.estimated_error.mesh,
        a.estimated_error.step,
        a.dt
    ));
    for n in &a.notes {
        s.push_str(&format!("  note     {n}\n"));
    }
    s
}

/// Labels of the results in the terminal ([`crate::quantity::Quantity::label`]).
fn label(name: &str) -> &'static str {
    crate::quantity::by_name(name).map_or("result", |q| q.label)
}

fn estimate_text(r: &ResultEstimate) -> String {
    match (r.estimated_error, r.status.as_str()) {
        (Some(e), "exact") => format!("± {e:.2e} (exact over the pilots)"),
        (Some(e), _) => format!("± {e:.2e} (est.)"),
        (None, status) => {
            let diffs = |f: &Option<LadderFit>| {
                f.as_ref().map_or(String::new(), |f| {
                    format!("{:.3e}, {:.3e}", f.differences[0], f.differences[1])
                })
            };
            match status {
                "not converging in h" => {
                    format!("{status} (mesh differences {})", diffs(&r.mesh))
                }
                "not converging in Δt" => {
                    format!("{status} (step differences {})", diffs(&r.step))
                }
                "not converging in h and Δt" => format!(
                    "{status} (mesh differences {}; step differences {})",
                    diffs(&r.mesh),
                    diffs(&r.step)
                ),
                other => other.to_string(),
            }
        }
    }
}

/// One line per result of carrier `carrier`: value, unit, estimated error.
pub fn result_lines(a: &Accuracy, carrier: usize) -> String {
    let mut s = String::new();
    for r in a.results.iter().filter(|r| r.carrier == carrier) {
        let value = match r.value {
            Some(v) if r.unit == "N" => format!("{v:.4} N"),
            Some(v) if matches!(r.name, "loss_interval_count" | "contact_switches") => {
                format!("{v:.0}")
            }
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
