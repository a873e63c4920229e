//! `precision.csv` and `precision.svg` of `taut precision`.

use std::path::Path;

use plotters::prelude::*;

use super::style;
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

/// A labelled refinement path of one formulation, its line width and
/// dashes (none: solid).
type RefinementPath<'a> = (&'a str, Vec<(f64, f64)>, u32, Option<(u32, u32)>);

/// Pixel size of `precision.svg` (the legend column included).
const SIZE: (u32, u32) = (900 + style::LEGEND_WIDTH, 600);

/// Work–precision on log–log axes (decade ticks): a colour and a marker a
/// (method, formulation), its three refinement paths solid (both refined)
/// and dashed (mesh alone, step alone), Pareto points larger; the legend
/// beside the plot.
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
            super::axis_range::write_note(path, SIZE, title, &reason, "precision.csv")?;
            return Ok(());
        }
    };
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 18))?;
    let (plot_area, legend_area) = root.split_horizontally(style::legend_layout(SIZE).0[2]);
    let mut chart = style::log_log_chart(
        &plot_area,
        (x0, x1),
        (y0, y1),
        ("wall time per run (s)", "relative RMS force error"),
    )?;
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
    let mut legend: Vec<(String, style::Key)> = Vec::new();
    for (fi, key) in keys.iter().enumerate() {
        let (col, m) = style::series_style(fi);
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
            ("both", of(&|r| r.mesh_level == r.step_level), 2, None),
            (
                "mesh",
                of(&|r| r.step_level == levels),
                1,
                Some(style::DASHES[1]),
            ),
            (
                "step",
                of(&|r| r.mesh_level == levels),
                1,
                Some(style::DASHES[0]),
            ),
        ];
        for (label, v, width, dash) in paths {
            let label = format!("{name}, refine {label}");
            match dash {
                None => {
                    chart.draw_series(LineSeries::new(v, col.stroke_width(width)))?;
                    legend.push((label, style::Key::Line(col, width, Some(m))));
                }
                Some((on, off)) => {
                    chart.draw_series(DashedLineSeries::new(
                        v,
                        on,
                        off,
                        col.stroke_width(width),
                    ))?;
                    legend.push((label, style::Key::Dashed(col, (on, off))));
                }
            }
        }
        chart.draw_series(p.rows.iter().filter(|r| of_key(r)).filter(ok).map(|r| {
            style::marker(
                m,
                (r.wall_seconds, r.force_error),
                if r.pareto { 5 } else { 3 },
                col,
            )
        }))?;
    }
    legend.push((
        "larger marker: on the Pareto front".into(),
        style::Key::Mark(BLACK, style::Marker::Circle),
    ));
    style::draw_legend(&legend_area, &legend, 50)?;
    root.present()?;
    Ok(())
}
