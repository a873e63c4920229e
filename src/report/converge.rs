//! `converge.csv`, `converge.json` and `converge.svg` of `taut converge`.

use std::path::Path;

use plotters::prelude::*;
use serde::Serialize;

use super::style;
use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::compare::NotRun;
use crate::study::converge::{
    ConvergeRow, Convergence, Diverged, MethodStudy, Refine, quantity_names,
};
use crate::study::uncertainty::{FS_ASYMPTOTIC, FS_CAUTIOUS};

/// Column order of `converge.csv`.
pub const CONVERGE_COLUMNS: [&str; 19] = [
    "method",
    "discretization",
    "level",
    "h",
    "modes",
    "dt",
    "quantity",
    "value",
    "error",
    "observed_order",
    "gci",
    "u_num",
    "mesh_share",
    "reference",
    "error_order",
    "ratio_change",
    "formal_order",
    "regime",
    "omega_max_dt",
];

#[derive(Serialize)]
struct ConvergeJson<'a> {
    taut_version: &'static str,
    refine: Refine,
    ratio: f64,
    /// Roache's F_s: near the formal order, and otherwise.
    gci_safety_factors: [f64; 2],
    scene: &'a crate::scene::Scene,
    /// One entry per method: its levels.
    methods: Vec<MethodLevels<'a>>,
    rows: Vec<&'a ConvergeRow>,
    skipped: &'a [NotRun],
}

#[derive(Serialize)]
struct MethodLevels<'a> {
    method: &'a str,
    levels: Vec<Level>,
    /// `--refine both`: level ℓ's mesh at level ℓ − 1's Δt.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    split: Vec<Level>,
    /// The level whose run blew up, if one did.
    #[serde(skip_serializing_if = "Option::is_none")]
    diverged: Option<&'a Diverged>,
}

#[derive(Serialize)]
struct Level {
    level: usize,
    elements: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    modes: Option<usize>,
    h: f64,
    dt: f64,
    dofs: usize,
    steps: usize,
    wall_seconds: f64,
}

/// `converge.csv` as a table (`CONVERGE_COLUMNS`): one row per level and
/// quantity, study after study.
pub fn converge_rows(rows: &[&ConvergeRow]) -> Table {
    let label = |f: fn(&ConvergeRow) -> &str| {
        Column::Label(rows.iter().map(|r| f(r).to_string()).collect())
    };
    // h and Δt are always known; the measured columns may not be (NaN)
    let real = |f: fn(&ConvergeRow) -> f64| Column::Real(rows.iter().map(|r| f(r)).collect());
    let measured =
        |f: fn(&ConvergeRow) -> f64| Column::RealOrNone(rows.iter().map(|r| f(r)).collect());
    let columns = [
        label(|r| &r.method),
        label(|r| &r.discretization),
        Column::Count(rows.iter().map(|r| r.level as u64).collect()),
        real(|r| r.h),
        Column::CountOrNone(rows.iter().map(|r| r.modes.map(|j| j as u64)).collect()),
        real(|r| r.dt),
        label(|r| &r.quantity),
        measured(|r| r.value),
        measured(|r| r.error),
        measured(|r| r.observed_order),
        measured(|r| r.gci),
        measured(|r| r.u_num),
        measured(|r| r.mesh_share),
        Column::Label(rows.iter().map(|r| r.reference.replace(',', ";")).collect()),
        measured(|r| r.error_order),
        measured(|r| r.ratio_change),
        measured(|r| r.formal_order),
        Column::Text(
            rows.iter()
                .map(|r| Some(r.regime.clone()).filter(|x| !x.is_empty()))
                .collect(),
        ),
        measured(|r| r.omega_max_dt),
    ];
    let mut t = Table::new();
    for (name, column) in CONVERGE_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t
}

/// Write the three files of one study into `dir`.
pub(crate) fn write_converge(dir: &Path, c: &Convergence) -> Result<()> {
    let name = c.rows.first().map_or("", |r| r.method.as_str());
    write_studies(dir, &[(name, c)], &[])
}

/// Write the three files of a `--methods` study into `dir`.
pub fn write_converge_methods(
    dir: &Path,
    studies: &[MethodStudy],
    skipped: &[NotRun],
) -> Result<()> {
    let list: Vec<(&str, &Convergence)> = studies
        .iter()
        .map(|m| (m.method.as_str(), &m.study))
        .collect();
    write_studies(dir, &list, skipped)
}

fn write_studies(dir: &Path, studies: &[(&str, &Convergence)], skipped: &[NotRun]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let Some(&(_, first)) = studies.first() else {
        return Ok(());
    };
    let rows: Vec<&ConvergeRow> = studies.iter().flat_map(|(_, c)| &c.rows).collect();
    converge_rows(&rows).write_csv(&dir.join("converge.csv"))?;

    let json = dir.join("converge.json");
    let levels = |c: &Convergence| -> Vec<Level> {
        c.scenes
            .iter()
            .zip(&c.runs)
            .enumerate()
            .map(|(l, (s, o))| Level {
                level: l,
                elements: s.elements,
                modes: s.discretization.modes(),
                h: s.resolution(),
                dt: s.dt,
                dofs: o.dofs,
                steps: o.steps,
                wall_seconds: o.wall_seconds,
            })
            .collect()
    };
    // level ℓ's mesh (scene ℓ) at level ℓ − 1's Δt (the run's own)
    let split_levels = |c: &Convergence| -> Vec<Level> {
        c.split
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let s = &c.scenes[i + 1];
                Level {
                    level: i + 1,
                    elements: s.elements,
                    modes: s.discretization.modes(),
                    h: s.resolution(),
                    dt: o.dt,
                    dofs: o.dofs,
                    steps: o.steps,
                    wall_seconds: o.wall_seconds,
                }
            })
            .collect()
    };
    let doc = ConvergeJson {
        taut_version: env!("CARGO_PKG_VERSION"),
        refine: first.refine,
        ratio: first.ratio,
        gci_safety_factors: [FS_ASYMPTOTIC, FS_CAUTIOUS],
        scene: &first.scenes[0].scene,
        methods: studies
            .iter()
            .map(|(m, c)| MethodLevels {
                method: m,
                levels: levels(c),
                split: split_levels(c),
                diverged: c.diverged.as_ref(),
            })
            .collect(),
        rows: studies.iter().flat_map(|(_, c)| &c.rows).collect(),
        skipped,
    };
    // serde_json writes NaN as null
    super::write_json(&json, &doc)?;
    let svg = dir.join("converge.svg");
    let drawn = if studies.len() == 1 {
        draw(&svg, first)
    } else {
        draw_methods(&svg, studies)
    };
    drawn.map_err(|e| Error::Output {
        path: svg.clone(),
        reason: e.to_string(),
    })
}

/// The terminal table of a `--methods` study: each method's table, then
/// the methods that did not run.
pub fn converge_methods_table(studies: &[MethodStudy], skipped: &[NotRun]) -> String {
    let mut s = String::new();
    for m in studies {
        s.push_str(&format!("method {}\n", m.method));
        s.push_str(&converge_table(&m.study));
    }
    for n in skipped {
        s.push_str(&format!("  skipped  {}: {}\n", n.method, n.reason));
    }
    s
}

/// The terminal table: per level the error against the reference and its
/// order (`err p`), the order from successive differences (`diff p`, never
/// from the reference), the GCI, ω_max·Δt and the regime.
pub fn converge_table(c: &Convergence) -> String {
    let mut s = format!(
        "{:<20} {:>5} {:>10} {:>10} {:>13} {:>11} {:>6} {:>6} {:>10} {:>10} {:>6} {:>8}  {:<22} {}\n",
        "quantity",
        "level",
        "h m",
        "dt s",
        "value",
        "error",
        "err p",
        "diff p",
        "GCI",
        "u_num",
        "mesh",
        "ωmax·Δt",
        "regime",
        "reference"
    );
    let order = |p: f64| {
        if p.is_finite() {
            format!("{p:>6.2}")
        } else {
            format!("{:>6}", "—")
        }
    };
    for q in quantity_names() {
        for r in c.rows.iter().filter(|r| r.quantity == q) {
            let f = |v: f64, w: usize| {
                if v.is_finite() {
                    format!("{v:>w$.4e}")
                } else {
                    format!("{:>w$}", "—")
                }
            };
            s.push_str(&format!(
                "{:<20} {:>5} {:>10.4e} {:>10.3e} {} {} {} {} {} {} {} {}  {:<22} {}\n",
                r.quantity,
                r.level,
                r.h,
                r.dt,
                f(r.value, 13),
                f(r.error, 11),
                order(r.error_order),
                order(r.observed_order),
                f(r.gci, 10),
                f(r.u_num, 10),
                if r.mesh_share.is_finite() {
                    format!("{:>5.0}%", 100.0 * r.mesh_share)
                } else {
                    format!("{:>6}", "—")
                },
                if r.omega_max_dt.is_finite() {
                    format!("{:>8.3}", r.omega_max_dt)
                } else {
                    format!("{:>8}", "—")
                },
                r.regime,
                r.reference
            ));
        }
    }
    s
}

/// What a study refines, in words for a plot's title.
fn refine_words(r: Refine) -> &'static str {
    match r {
        Refine::Mesh => "refine: mesh h (Δt fixed)",
        Refine::Step => "refine: time step Δt (mesh fixed)",
        Refine::Both => "refine: both h and Δt",
    }
}

/// The abscissa of a study, naming the levels' N and Δt: "h (m); levels
/// N = 100…800, Δt = 1e-4…1.25e-5 s".
fn abscissa(c: &Convergence) -> String {
    let axis = match c.refine {
        Refine::Mesh => "h (m)",
        Refine::Step => "Δt (s)",
        Refine::Both => "h (m), Δt ∝ h",
    };
    let (Some(a), Some(b)) = (c.scenes.first(), c.scenes.last()) else {
        return axis.to_string();
    };
    let n = if a.elements == b.elements {
        format!("N = {}", a.elements)
    } else {
        format!("N = {}…{}", a.elements, b.elements)
    };
    let dt = if a.dt == b.dt {
        format!("Δt = {} s", super::fmt_f64(a.dt))
    } else {
        format!("Δt = {}…{} s", super::fmt_f64(a.dt), super::fmt_f64(b.dt))
    };
    format!("{axis}; levels {n}, {dt}")
}

/// One study: each quantity's relative error against h (or Δt), with
/// reference slopes 1, 2 and 4.
fn draw(path: &Path, c: &Convergence) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let series: Vec<(String, Vec<(f64, f64)>)> = quantity_names()
        .into_iter()
        .map(|q| (q.to_string(), relative_errors(c, q)))
        .collect();
    let caption = format!(
        "relative error against the reference; {}, ratio r = {}",
        refine_words(c.refine),
        c.ratio
    );
    log_log(path, &caption, &abscissa(c), &series, &[1.0, 2.0, 4.0])
}

/// Several methods: the relative error of the displacement under the
/// carrier (L2 over the history), one line per method, with slopes 1 and 2.
fn draw_methods(
    path: &Path,
    studies: &[(&str, &Convergence)],
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    const QUANTITY: &str = "displacement_history_l2";
    let first = studies[0].1;
    let series: Vec<(String, Vec<(f64, f64)>)> = studies
        .iter()
        .map(|(m, c)| (m.to_string(), relative_errors(c, QUANTITY)))
        .collect();
    let caption = format!(
        "{QUANTITY}: relative error by method; {}, ratio r = {}",
        refine_words(first.refine),
        first.ratio
    );
    log_log(path, &caption, &abscissa(first), &series, &[1.0, 2.0])
}

/// (h or Δt, relative error) of a quantity's rows with a known error.
fn relative_errors(c: &Convergence, quantity: &str) -> Vec<(f64, f64)> {
    let by_dt = c.refine == Refine::Step;
    c.rows
        .iter()
        .filter(|r| r.quantity == quantity && r.error.is_finite() && r.error > 0.0)
        .map(|r| {
            let x = if by_dt { r.dt } else { r.h };
            (x, r.error / r.value.abs().max(f64::MIN_POSITIVE))
        })
        .collect()
}

/// A labelled error series: (label, (h or Δt, relative error) points).
type ErrorSeries = (String, Vec<(f64, f64)>);

/// Pixel size of a convergence plot (the legend column included).
const SIZE: (u32, u32) = (900 + style::LEGEND_WIDTH, 600);

/// Labelled error series on log–log axes (decade ticks, a colour and a
/// marker per series, the legend beside the plot), with reference slopes
/// through the middle of the data, each dashed its own way and labelled
/// "order p" at its right end.
pub(super) fn log_log(
    path: &Path,
    caption: &str,
    x_desc: &str,
    series: &[(String, Vec<(f64, f64)>)],
    slopes: &[f64],
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    // (index in the palette, (label, points)) of the series with points
    let series: Vec<(usize, &ErrorSeries)> = series
        .iter()
        .enumerate()
        .filter(|(_, (_, v))| !v.is_empty())
        .collect();
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|(_, (_, v))| v.iter().copied())
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in &all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if all.is_empty() {
        (x0, x1, y0, y1) = (1e-3, 1.0, 1e-6, 1.0);
    }
    let (x0, x1) = (x0 / 1.5, x1 * 1.5);
    let (y0, y1) = (y0 / 3.0, y1 * 3.0);
    let ranges = super::axis_range::drawable("horizontal", x0, x1, true)
        .and_then(|x| super::axis_range::drawable("vertical", y0, y1, true).map(|y| (x, y)));
    let ((x0, x1), (y0, y1)) = match ranges {
        Ok(r) => r,
        Err(reason) => {
            super::axis_range::write_note(
                path,
                SIZE,
                caption,
                &reason,
                "converge.csv and converge.json",
            )?;
            return Ok(());
        }
    };
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(caption, ("sans-serif", 17))?;
    let (plot_area, legend_area) = root.split_horizontally(style::legend_layout(SIZE).0[2]);
    let mut chart = style::log_log_chart(
        &plot_area,
        (x0, x1),
        (y0, y1),
        (x_desc, "relative error |q − q_ref| / |q|"),
    )?;
    let mut key: Vec<(String, style::Key)> = Vec::new();
    for &(i, (label, v)) in &series {
        let (col, m) = style::series_style(i);
        chart.draw_series(LineSeries::new(v.clone(), col.stroke_width(2)))?;
        chart.draw_series(v.iter().map(|&p| style::marker(m, p, 4, col)))?;
        key.push((label.clone(), style::Key::Line(col, 2, Some(m))));
    }
    if let Some(&(xm, ym)) = all.get(all.len() / 2) {
        let grey = RGBColor(70, 70, 70);
        for (k, &p) in slopes.iter().enumerate() {
            let dash = style::DASHES[k % style::DASHES.len()];
            let at = |x: f64| ym * (x / xm).powf(p);
            let line = vec![(x0, at(x0)), (x1, at(x1))];
            chart.draw_series(DashedLineSeries::new(
                line,
                dash.0,
                dash.1,
                grey.stroke_width(1),
            ))?;
            // the label on the line where it is inside the plot, leaving
            // room for the text at the right, each guide further left (the
            // guides meet at the middle point: apart, their labels are too)
            let start = 0.12 + 0.1 * k as f64;
            let inside = (0..=40)
                .map(|j| x1 * (x0 / x1).powf(start + (1.0 - start) * f64::from(j) / 40.0))
                .find(|&x| (y0..y1).contains(&at(x)) && at(x) < y1 / 2.0 && at(x) > y0 * 2.0);
            if let Some(x) = inside {
                chart.draw_series(std::iter::once(Text::new(
                    format!("order {p}"),
                    (x / 1.02, at(x)),
                    ("sans-serif", 12).into_font().color(&grey),
                )))?;
            }
            key.push((
                format!("slope guide, order {p}"),
                style::Key::Dashed(grey, dash),
            ));
        }
    }
    style::draw_legend(&legend_area, &key, 50)?;
    root.present()?;
    Ok(())
}
