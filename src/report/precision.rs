//! `precision.csv` and `precision.svg` of `taut precision`.

use std::path::Path;

use plotters::prelude::*;

use super::PALETTE;
use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::precision::{Precision, PrecisionRow};

/// Column order of `precision.csv`.
pub(crate) const PRECISION_COLUMNS: [&str; 16] = [
    "method",
    "discretization",
    "formulation",
    "mesh_level",
    "step_level",
    "elements",
    "modes",
    "dt",
    "dofs",
    "steps",
    "dof_steps",
    "wall_seconds",
    "force_error",
    "displacement_error",
    "loss_fraction_error",
    "pareto",
];

/// `precision.csv` as a table (`PRECISION_COLUMNS`): one row per run.
pub fn precision_rows(p: &Precision) -> Table {
    let rows = &p.rows;
    let label = |f: fn(&PrecisionRow) -> &str| {
        Column::Label(rows.iter().map(|r| f(r).to_string()).collect())
    };
    let count =
        |f: fn(&PrecisionRow) -> usize| Column::Count(rows.iter().map(|r| f(r) as u64).collect());
    let real = |f: fn(&PrecisionRow) -> f64| Column::Real(rows.iter().map(f).collect());
    let columns = [
        label(|r| &r.method),
        label(|r| &r.discretization),
        label(|r| &r.formulation),
        count(|r| r.mesh_level),
        count(|r| r.step_level),
        count(|r| r.elements),
        Column::CountOrNone(rows.iter().map(|r| r.modes.map(|j| j as u64)).collect()),
        real(|r| r.dt),
        count(|r| r.dofs),
        count(|r| r.steps),
        real(|r| r.dof_steps),
        real(|r| r.wall_seconds),
        real(|r| r.force_error),
        real(|r| r.displacement_error),
        real(|r| r.loss_fraction_error),
        Column::Bool(rows.iter().map(|r| r.pareto).collect()),
    ];
    let mut t = Table::new();
    for (name, column) in PRECISION_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t.push_quantities(rows.iter().map(|r| &r.quantities));
    t
}

/// Write `precision.csv` and `precision.svg` into `dir`.
pub(crate) fn write_precision(dir: &Path, p: &Precision) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    precision_rows(p).write_csv(&dir.join("precision.csv"))?;
    let svg = dir.join("precision.svg");
    draw(&svg, p).map_err(|e| Error::Output {
        path: svg.clone(),
        reason: e.to_string(),
    })
}

/// The terminal table: every row, Pareto points starred.
pub fn precision_table(p: &Precision) -> String {
    let space = p
        .rows
        .iter()
        .any(|r| r.discretization != p.rows[0].discretization);
    let who = |r: &PrecisionRow| {
        if space {
            format!("{}/{}", r.method, r.discretization)
        } else {
            r.method.clone()
        }
    };
    let w = if space { 28 } else { 19 };
    let mut s = format!(
        "{:<w$} {:<16} {:>6} {:>10} {:>12} {:>9} {:>11} {:>11} {:>9}\n",
        "method", "formulation", "N", "dt s", "dof-steps", "wall s", "force err", "w err", "ΔP_l"
    );
    for r in &p.rows {
        s.push_str(&format!(
            "{:<w$} {:<16} {:>6} {:>10.3e} {:>12.3e} {:>9.4} {:>11.3e} {:>11.3e} {:>9.5}{}\n",
            who(r),
            r.formulation,
            r.modes
                .map_or_else(|| r.elements.to_string(), |j| format!("J={j}")),
            r.dt,
            r.dof_steps,
            r.wall_seconds,
            r.force_error,
            r.displacement_error,
            r.loss_fraction_error,
            if r.pareto { " *" } else { "" }
        ));
    }
    s.push_str(&format!(
        "(* Pareto front per method, discretization and formulation; N is J for a modal basis; reference: {}/lagrange, {} elements, dt = {:e} s, {:.2} s wall)\n",
        p.reference_method, p.reference.0, p.reference.1, p.reference_wall
    ));
    for n in &p.skipped {
        s.push_str(&format!(
            "  skipped  {}/{}: {}\n",
            n.method, n.formulation, n.reason
        ));
    }
    s
}

/// A labelled refinement path of one formulation and its line style.
type RefinementPath<'a> = (&'a str, Vec<(f64, f64)>, ShapeStyle);

fn draw(path: &Path, p: &Precision) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let ok = |r: &&PrecisionRow| r.force_error > 0.0 && r.wall_seconds > 0.0;
    let pts: Vec<&PrecisionRow> = p.rows.iter().filter(ok).collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for r in &pts {
        x0 = x0.min(r.wall_seconds);
        x1 = x1.max(r.wall_seconds);
        y0 = y0.min(r.force_error);
        y1 = y1.max(r.force_error);
    }
    if pts.is_empty() {
        (x0, x1, y0, y1) = (1e-3, 1.0, 1e-6, 1.0);
    }
    let title = "work–precision: contact force error against wall time";
    let ranges = super::axis_range::drawable("wall time", x0 / 1.5, x1 * 1.5, true).and_then(|x| {
        super::axis_range::drawable("force error", y0 / 2.0, y1 * 2.0, true).map(|y| (x, y))
    });
    let ((x0, x1), (y0, y1)) = match ranges {
        Ok(r) => r,
        Err(reason) => {
            super::axis_range::write_note(path, (900, 600), title, &reason, "precision.csv")?;
            return Ok(());
        }
    };
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("wall time per run (s)")
        .x_labels(6)
        .y_desc("relative RMS force error")
        .x_label_formatter(&|x| format!("{x:.1e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    let levels = p.rows.iter().map(|r| r.mesh_level).max().unwrap_or(0);
    // one family of lines per (method, formulation), in row order
    let key_of = |r: &PrecisionRow| {
        (
            r.method.clone(),
            r.discretization.clone(),
            r.formulation.clone(),
        )
    };
    let mut keys: Vec<(String, String, String)> = p.rows.iter().map(key_of).collect();
    keys.dedup();
    let several_methods = keys.iter().any(|k| k.0 != keys[0].0);
    let several_spaces = keys.iter().any(|k| k.1 != keys[0].1);
    for (fi, key) in keys.iter().enumerate() {
        let col = PALETTE[fi % PALETTE.len()];
        let name = match (several_methods, several_spaces) {
            (true, true) => format!("{}/{}/{}", key.0, key.1, key.2),
            (true, false) => format!("{}/{}", key.0, key.2),
            (false, true) => format!("{}/{}", key.1, key.2),
            (false, false) => key.2.clone(),
        };
        let of_key = |r: &PrecisionRow| key_of(r) == *key;
        let of = |pred: &dyn Fn(&PrecisionRow) -> bool| -> Vec<(f64, f64)> {
            p.rows
                .iter()
                .filter(|r| of_key(r) && pred(r))
                .filter(ok)
                .map(|r| (r.wall_seconds, r.force_error))
                .collect()
        };
        let paths: [RefinementPath; 3] = [
            (
                "both",
                of(&|r| r.mesh_level == r.step_level),
                col.stroke_width(2),
            ),
            (
                "mesh",
                of(&|r| r.step_level == levels),
                col.mix(0.6).stroke_width(1),
            ),
            (
                "step",
                of(&|r| r.mesh_level == levels),
                col.mix(0.35).stroke_width(1),
            ),
        ];
        for (label, v, style) in paths {
            chart
                .draw_series(LineSeries::new(v, style))?
                .label(format!("{name}, refine {label}"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
        }
        chart.draw_series(p.rows.iter().filter(|r| of_key(r)).filter(ok).map(|r| {
            Circle::new(
                (r.wall_seconds, r.force_error),
                if r.pareto { 5 } else { 2 },
                col.filled(),
            )
        }))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
