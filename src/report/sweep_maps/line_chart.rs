//! `sweep.svg`: a 1-D sweep's results as line charts against its axis (the
//! figure a paper shows: P_l against speed; the filtered contact force's
//! mean, its statistical max and min F_m ± 3σ and its actual max), read
//! from `sweep.csv`'s own table, with error bars where the table has an
//! uncertainty column for a quantity (`<column>_u_num`, or
//! `<column>_uncertainty`: ± that value). Each panel's legend is beside
//! it, a colour and a marker a line ([`style`]).

use std::path::Path;

use plotters::prelude::*;

use super::axes::axis_label;
use crate::error::{Error, Result};
use crate::report::plot::style_axes;
use crate::report::style;
use crate::report::table::{Column, Table};

/// The columns of each panel: (y axis label, [(column, legend)]).
type PanelSpec<'a> = (&'a str, &'a [(&'a str, &'a str)]);

/// The panels of `sweep.svg`.
const PANELS: [PanelSpec<'static>; 2] = [
    (
        "contact loss P_l (–)",
        &[
            ("loss_fraction", "P_l (whole run)"),
            ("loss_fraction_span", "P_l in span (the number to quote)"),
        ],
    ),
    (
        "filtered contact force (N)",
        &[
            ("filtered_force_mean", "mean F_m"),
            ("statistical_max", "F_m + 3σ"),
            ("statistical_min", "F_m − 3σ"),
            ("filtered_force_max", "max"),
        ],
    ),
];

/// A line of a panel: its legend, its values and their ± errors, if any.
type Line<'a> = (&'a str, Vec<f64>, Option<Vec<f64>>);

/// Pixel size of `sweep.svg` (the legend column included).
const SIZE: (u32, u32) = (960 + style::LEGEND_WIDTH, 720);

/// The values of column `name` of `t` as reals (NaN for an empty cell);
/// the statistical max and min are made from the mean and σ columns.
fn column(t: &Table, name: &str) -> Option<Vec<f64>> {
    let sigma = |sign: f64| {
        let m = column(t, "filtered_force_mean")?;
        let s = column(t, "filtered_force_std")?;
        Some(m.iter().zip(&s).map(|(m, s)| m + sign * 3.0 * s).collect())
    };
    match name {
        "statistical_max" => return sigma(1.0),
        "statistical_min" => return sigma(-1.0),
        _ => {}
    }
    match t.get(name)? {
        Column::Real(v) | Column::RealOrNone(v) => Some(v.clone()),
        Column::Count(v) => Some(v.iter().map(|&c| c as f64).collect()),
        _ => None,
    }
}

/// The ± error of column `name`, when the table has one.
fn error_bars(t: &Table, name: &str) -> Option<Vec<f64>> {
    column(t, &format!("{name}_u_num")).or_else(|| column(t, &format!("{name}_uncertainty")))
}

/// Draw `sweep.svg` from a 1-D sweep's table `t` over its axis `key`.
pub fn write_sweep_chart(path: &Path, key: &str, t: &Table) -> Result<()> {
    draw(path, key, t).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

fn draw(path: &Path, key: &str, t: &Table) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let Some(x) = column(t, key) else {
        return Ok(());
    };
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!("sweep over {}: {} points", axis_label(key), x.len()),
        ("sans-serif", 18),
    )?;
    let finite = |v: &f64| v.is_finite();
    let (x0, x1) = x
        .iter()
        .copied()
        .filter(finite)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !x0.is_finite() {
        return Ok(());
    }
    let xpad = 0.02 * (x1 - x0).max(1e-12 * x1.abs().max(1.0));
    for ((y_desc, lines), row) in PANELS.iter().zip(root.split_evenly((2, 1))) {
        let (w, h) = row.dim_in_pixel();
        let (area, legend_area) = row.split_horizontally(style::legend_layout((w, h)).0[2]);
        let mut entries: Vec<(String, style::Key)> = Vec::new();
        let data: Vec<Line<'_>> = lines
            .iter()
            .filter_map(|(name, legend)| Some((*legend, column(t, name)?, error_bars(t, name))))
            .collect();
        let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
        for (_, y, e) in &data {
            for (i, v) in y.iter().enumerate() {
                let u = e.as_ref().map_or(0.0, |e| e[i].abs()).max(0.0);
                if v.is_finite() {
                    y0 = y0.min(v - if u.is_finite() { u } else { 0.0 });
                    y1 = y1.max(v + if u.is_finite() { u } else { 0.0 });
                }
            }
        }
        if !y0.is_finite() {
            (y0, y1) = (0.0, 1.0);
        }
        let span = (y1 - y0).max(1e-9 * y1.abs().max(1.0));
        let (y0, y1) = (y0 - 0.05 * span, y1 + 0.05 * span);
        let mut chart = ChartBuilder::on(&area)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(72)
            .build_cartesian_2d((x0 - xpad)..(x1 + xpad), y0..y1)?;
        style_axes(&mut chart, &axis_label(key), y_desc)?;
        for (i, (legend, y, e)) in data.iter().enumerate() {
            let (col, m) = style::series_style(i);
            let pts: Vec<(f64, f64)> = x
                .iter()
                .zip(y)
                .map(|(&a, &b)| (a, b))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            chart.draw_series(LineSeries::new(pts.clone(), col.stroke_width(2)))?;
            // larger markers first: a later line on an earlier one leaves it showing
            let r = (5 - i as i32).max(3);
            chart.draw_series(pts.iter().map(|&p| style::marker(m, p, r, col)))?;
            entries.push((legend.to_string(), style::Key::Line(col, 2, Some(m))));
            if let Some(e) = e {
                // ± u: a vertical bar with caps 1 % of the axis wide
                let cap = 0.01 * (x1 - x0);
                let bars = x.iter().zip(y).zip(e).filter_map(|((&a, &b), &u)| {
                    (a.is_finite() && b.is_finite() && u.is_finite()).then_some((a, b, u.abs()))
                });
                for (a, b, u) in bars {
                    for seg in [
                        vec![(a, b - u), (a, b + u)],
                        vec![(a - cap, b - u), (a + cap, b - u)],
                        vec![(a - cap, b + u), (a + cap, b + u)],
                    ] {
                        chart.draw_series(std::iter::once(PathElement::new(
                            seg,
                            col.stroke_width(1),
                        )))?;
                    }
                }
            }
        }
        style::draw_legend(&legend_area, &entries, 24)?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_bars_come_from_an_uncertainty_column() {
        let mut t = Table::new();
        t.push("v", Column::Real(vec![1.0, 2.0]));
        t.push("loss_fraction", Column::RealOrNone(vec![0.1, f64::NAN]));
        assert_eq!(error_bars(&t, "loss_fraction"), None);
        t.push("loss_fraction_u_num", Column::RealOrNone(vec![0.01, 0.02]));
        assert_eq!(error_bars(&t, "loss_fraction"), Some(vec![0.01, 0.02]));
        t.push("filtered_force_mean", Column::RealOrNone(vec![40.0, 50.0]));
        t.push("filtered_force_std", Column::RealOrNone(vec![1.0, 2.0]));
        assert_eq!(column(&t, "statistical_max"), Some(vec![43.0, 56.0]));
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("sweep.svg");
        write_sweep_chart(&p, "v", &t).unwrap();
        let svg = std::fs::read_to_string(&p).unwrap();
        assert!(
            svg.contains("P_l (whole run)"),
            "the legend names the columns"
        );
        assert!(
            !svg.contains("P_l in span"),
            "a column the table lacks is not drawn"
        );
    }
}
