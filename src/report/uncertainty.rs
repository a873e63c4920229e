//! `uncertainty.csv`, `uncertainty.json` and `uncertainty.svg` of `taut
//! uncertainty` (docs/output.md#taut-uncertainty).

use std::path::Path;

use plotters::prelude::*;
use serde::Serialize;

use super::PALETTE;
use super::style;
use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::uncertainty::{QuantityUncertainty, RATIO, Role, Uncertainty};

/// Column order of `uncertainty.csv`.
pub(crate) const UNCERTAINTY_COLUMNS: [&str; 23] = [
    "quantity",
    "unit",
    "smooth",
    "value",
    "u_num",
    "u_relative",
    "error",
    "extrapolated",
    "safety_factor",
    "estimator",
    "fit",
    "behaviour",
    "observed_order",
    "formal_order",
    "order_space",
    "order_time",
    "space_share",
    "asymptotic",
    "sigma",
    "data_range",
    "value_scene",
    "u_scene",
    "note",
];

/// `uncertainty.csv` as a table (`UNCERTAINTY_COLUMNS`): one row a
/// quantity.
pub fn uncertainty_table(u: &Uncertainty) -> Table {
    let q = &u.quantities;
    let label = |f: fn(&QuantityUncertainty) -> String| Column::Label(q.iter().map(f).collect());
    let opt = |f: fn(&QuantityUncertainty) -> Option<f64>| {
        Column::RealOrNone(q.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect())
    };
    let columns = [
        label(|r| r.quantity.to_string()),
        label(|r| r.unit.to_string()),
        Column::Bool(q.iter().map(|r| r.smooth).collect()),
        opt(|r| r.assessment.value),
        opt(|r| r.assessment.u_num),
        opt(|r| match (r.assessment.u_num, r.assessment.value) {
            (Some(u), Some(v)) if v != 0.0 => Some(u / v.abs()),
            _ => None,
        }),
        opt(|r| r.assessment.error),
        opt(|r| r.assessment.extrapolated),
        opt(|r| r.assessment.safety_factor),
        label(|r| r.assessment.estimator.name().to_string()),
        Column::Text(
            q.iter()
                .map(|r| Some(r.assessment.fit.clone()).filter(|f| !f.is_empty()))
                .collect(),
        ),
        label(|r| r.assessment.behaviour.name().to_string()),
        opt(|r| r.assessment.observed_order),
        opt(|r| Some(r.assessment.formal_order)),
        opt(|r| r.assessment.order_space),
        opt(|r| r.assessment.order_time),
        opt(|r| r.assessment.space_share),
        Column::Bool(q.iter().map(|r| r.assessment.asymptotic).collect()),
        opt(|r| r.assessment.sigma),
        opt(|r| r.assessment.data_range),
        opt(|r| r.value_scene),
        opt(|r| r.u_scene),
        Column::Text(q.iter().map(|r| Some(r.assessment.note.clone())).collect()),
    ];
    let mut t = Table::new();
    for (name, column) in UNCERTAINTY_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t
}

/// The family's runs as a table: role, level, N, J, h, Δt, steps, unknowns.
pub fn family_table(u: &Uncertainty) -> Table {
    let f = &u.family;
    let mut t = Table::new();
    t.push(
        "role",
        Column::Label(
            f.iter()
                .map(|m| match m.role {
                    Role::Diagonal => "diagonal".to_string(),
                    Role::Space => "space".to_string(),
                })
                .collect(),
        ),
    );
    t.push(
        "level",
        Column::Count(f.iter().map(|m| m.level as u64).collect()),
    );
    t.push(
        "elements",
        Column::Count(f.iter().map(|m| m.elements as u64).collect()),
    );
    t.push(
        "modes",
        Column::CountOrNone(f.iter().map(|m| m.modes.map(|j| j as u64)).collect()),
    );
    t.push("h", Column::Real(f.iter().map(|m| m.h).collect()));
    t.push("dt", Column::Real(f.iter().map(|m| m.dt).collect()));
    t.push(
        "steps",
        Column::Count(f.iter().map(|m| m.steps as u64).collect()),
    );
    t.push(
        "dofs",
        Column::Count(f.iter().map(|m| m.dofs as u64).collect()),
    );
    t
}

#[derive(Serialize)]
struct UncertaintyJson<'a> {
    taut_version: &'static str,
    scene: &'a crate::scene::Scene,
    ratio: usize,
    #[serde(flatten)]
    study: &'a Uncertainty,
}

/// Write the three files into `dir`.
pub(crate) fn write_uncertainty(dir: &Path, u: &Uncertainty) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    uncertainty_table(u).write_csv(&dir.join("uncertainty.csv"))?;
    let doc = UncertaintyJson {
        taut_version: env!("CARGO_PKG_VERSION"),
        scene: &u.scene,
        ratio: RATIO,
        study: u,
    };
    // serde_json writes NaN as null
    super::write_json(&dir.join("uncertainty.json"), &doc)?;
    let svg = dir.join("uncertainty.svg");
    draw(&svg, u).map_err(|e| Error::Output {
        path: svg.clone(),
        reason: e.to_string(),
    })
}

/// The terminal table: value ± u_num of each quantity, its estimator and
/// what it says.
pub fn uncertainty_lines(u: &Uncertainty) -> String {
    let mut s = format!(
        "  {:<22} {:>13} {:>10} {:>6} {:>5} {:>6} {:>6} {:>6}  {}\n",
        "quantity",
        "value",
        "± u_num",
        "F_s",
        "p",
        "p_h",
        "p_Δt",
        "space",
        "estimator: what the data say"
    );
    let num = |v: Option<f64>, w: usize, prec: usize| match v {
        Some(x) if x.is_finite() => format!("{x:>w$.prec$e}"),
        _ => format!("{:>w$}", "—"),
    };
    let fixed = |v: Option<f64>, w: usize| match v {
        Some(x) if x.is_finite() => format!("{x:>w$.2}"),
        _ => format!("{:>w$}", "—"),
    };
    for r in &u.quantities {
        let a = &r.assessment;
        s.push_str(&format!(
            "  {:<22} {} {} {} {} {} {} {}  {}: {}\n",
            format!("{} ({})", r.quantity, r.unit),
            num(a.value, 13, 5),
            num(a.u_num, 10, 2),
            fixed(a.safety_factor, 6),
            fixed(a.observed_order, 5),
            fixed(a.order_space, 6),
            fixed(a.order_time, 6),
            match a.space_share {
                Some(x) => format!("{:>5.0}%", 100.0 * x),
                None => format!("{:>6}", "—"),
            },
            a.estimator.name(),
            a.note
        ));
    }
    for n in &u.notes {
        s.push_str(&format!("  note     {n}\n"));
    }
    s
}

/// The abscissa of the panels, naming the levels' N (or J) and Δt:
/// "level ℓ (N = 100…800, Δt = 1e-4…1.25e-5 s)".
fn abscissa(u: &Uncertainty) -> String {
    let diag: Vec<_> = u
        .family
        .iter()
        .filter(|m| m.role == Role::Diagonal)
        .collect();
    let (Some(a), Some(b)) = (diag.first(), diag.last()) else {
        return "level ℓ".into();
    };
    let range = |x: String, y: String| if x == y { x } else { format!("{x}…{y}") };
    let count = match (a.modes, b.modes) {
        (Some(ja), Some(jb)) => format!("J = {}", range(ja.to_string(), jb.to_string())),
        _ => format!(
            "N = {}",
            range(a.elements.to_string(), b.elements.to_string())
        ),
    };
    format!(
        "level ℓ ({count}, Δt = {} s)",
        range(super::fmt_f64(a.dt), super::fmt_f64(b.dt))
    )
}

/// One panel a quantity: the diagonal's values with their ±U bars against
/// the level, the split runs between levels, the extrapolated value
/// dashed, each panel on its own value axis ([`value_range`]); the legend
/// once, beside the panels.
fn draw(path: &Path, u: &Uncertainty) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let shown: Vec<&QuantityUncertainty> = u
        .quantities
        .iter()
        .filter(|q| q.diagonal.iter().any(|v| v.is_some()))
        .collect();
    let cols = 3usize;
    let rows = shown.len().div_ceil(cols).max(1);
    let (w, h) = (1200u32 + style::LEGEND_WIDTH, 300 * rows as u32 + 40);
    let root = SVGBackend::new(path, (w, h)).into_drawing_area();
    root.fill(&WHITE)?;
    let (title, body) = root.split_vertically(40);
    title.draw(&Text::new(
        format!(
            "value ± u_num against the level ({} and Δt refined ×{RATIO} a level)",
            u.level_symbol
        ),
        (10, 12),
        ("sans-serif", 17).into_font(),
    ))?;
    let (body, legend) = body.split_horizontally(style::legend_layout((w, h)).0[2]);
    let x_desc = abscissa(u);
    let panels = body.split_evenly((rows, cols));
    let mut clipped = false;
    for (q, area) in shown.iter().zip(panels.iter()) {
        clipped |= panel(area, q, u.levels, &x_desc)?;
    }
    let mut key = vec![
        (
            format!("value ± u_num ({} and Δt refined)", u.level_symbol),
            style::Key::Line(PALETTE[0], 2, Some(style::Marker::Circle)),
        ),
        (
            format!("{} refined alone (Δt of the level before)", u.level_symbol),
            style::Key::Mark(PALETTE[1], style::Marker::Cross),
        ),
        (
            "extrapolated value (Richardson, dashed)".to_string(),
            style::Key::Dashed(RGBColor(110, 110, 110), (6, 4)),
        ),
    ];
    if clipped {
        key.push((
            "bar beyond the axis (an outlier, clipped)".into(),
            style::Key::Mark(BLACK, style::Marker::TriangleUp),
        ));
    }
    style::draw_legend(&legend, &key, 30)?;
    root.present()?;
    Ok(())
}

/// Tick labels on a panel's value axis.
const Y_TICKS: usize = 5;

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    q: &QuantityUncertainty,
    levels: usize,
    x_desc: &str,
) -> std::result::Result<bool, Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let a = &q.assessment;
    let bars: Vec<(f64, f64, f64)> = q
        .diagonal
        .iter()
        .enumerate()
        .filter_map(|(l, v)| {
            let v = (*v)?;
            let e = a.u_levels.get(l).copied().flatten().unwrap_or(0.0);
            Some((l as f64, v, e))
        })
        .collect();
    let split: Vec<(f64, f64)> = q
        .space
        .iter()
        .enumerate()
        .filter_map(|(i, v)| Some((i as f64 + 0.5, (*v)?)))
        .collect();
    let caption = format!("{} ({}): {}", q.quantity, q.unit, a.estimator.name());
    let range = value_range(&bars, &split, a.extrapolated)
        .ok_or_else(|| "no value is a finite number".to_string())
        .and_then(|(lo, hi)| super::axis_range::drawable("value", lo, hi, false));
    let y = match range {
        Ok(y) => y,
        Err(reason) => {
            area.draw(&Text::new(
                format!("{caption}: not drawn, {reason}"),
                (10, 20),
                ("sans-serif", 12).into_font(),
            ))?;
            return Ok(false);
        }
    };
    // a range tiny against its values is drawn as an offset and small labels
    let off = style::axis_offset(y.0, y.1).unwrap_or(0.0);
    let y_desc = if off == 0.0 {
        format!("value ({})", q.unit)
    } else {
        format!(
            "value {} ({})",
            style::offset_label(-off)
                .replacen('+', "+ ", 1)
                .replacen('−', "− ", 1),
            q.unit
        )
    };
    // plotters picks 1-2-5 ticks near this count; the labels get the
    // digits of such a step
    let (ticks, step) = style::nice_ticks(y.0 - off, y.1 - off, Y_TICKS);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 14))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(64)
        .build_cartesian_2d(-0.3..(levels as f64 - 0.7), (y.0 - off)..(y.1 - off))?;
    chart
        .configure_mesh()
        .x_labels(levels)
        .y_labels(ticks.len().max(2))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|v| style::tick_label(*v, step))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(("sans-serif", 12))
        .label_style(("sans-serif", 11))
        .draw()?;
    let col = PALETTE[0];
    if let Some(x) = a.extrapolated.filter(|x| x.is_finite()) {
        chart.draw_series(DashedLineSeries::new(
            vec![(-0.3, x - off), (levels as f64 - 0.7, x - off)],
            6,
            4,
            RGBColor(110, 110, 110).stroke_width(1),
        ))?;
    }
    // a bar or value beyond the axis ends at the edge, a triangle there
    let clamp = |v: f64| v.clamp(y.0, y.1) - off;
    let mut clipped = false;
    let mut beyond = |v: f64, x: f64| -> Option<style::MarkerElement<(f64, f64)>> {
        let shape = if v > y.1 {
            style::Marker::TriangleUp
        } else if v < y.0 {
            style::Marker::TriangleDown
        } else {
            return None;
        };
        clipped = true;
        Some(style::marker(shape, (x, clamp(v)), 4, BLACK))
    };
    let mut edges = Vec::new();
    for &(l, v, e) in &bars {
        if e > 0.0 {
            chart.draw_series(LineSeries::new(
                vec![(l, clamp(v - e)), (l, clamp(v + e))],
                col.stroke_width(2),
            ))?;
        }
        edges.extend(beyond(v + e, l));
        edges.extend(beyond(v - e, l));
        if (y.0..=y.1).contains(&v) {
            chart.draw_series(std::iter::once(Circle::new((l, v - off), 4, col.filled())))?;
        }
    }
    let sq = PALETTE[1];
    for &(x, v) in &split {
        match beyond(v, x) {
            Some(m) => edges.push(m),
            None => {
                chart.draw_series(std::iter::once(Cross::new(
                    (x, v - off),
                    4,
                    sq.stroke_width(2),
                )))?;
            }
        }
    }
    chart.draw_series(edges)?;
    Ok(clipped)
}

/// A bar whose half-width is more than this many times the median bar's
/// is an outlier: the axis does not stretch to hold it (its end is marked
/// ▲▼ at the edge). A pre-asymptotic first level's bar is typically 10–100×
/// the finer levels' (docs/verification.md); bars within a factor of a few
/// of one another are all drawn whole, since reading them is the plot's
/// purpose.
const BAR_OUTLIER: f64 = 4.0;

/// The value axis of a panel: the robust range ([`style::robust_range`])
/// of the values drawn (the diagonal's, the split runs', the extrapolated
/// one kept whole) and of the ends of every bar that is not an outlier
/// ([`BAR_OUTLIER`]): a first level's bar ten times the others' no longer
/// squashes the levels that converge, while the ordinary bars show whole.
/// Where every value is the same the bars set it (with
/// [`style::ROBUST_MARGIN`]); None without a finite value.
fn value_range(
    bars: &[(f64, f64, f64)],
    split: &[(f64, f64)],
    extrapolated: Option<f64>,
) -> Option<(f64, f64)> {
    let x = extrapolated.filter(|x| x.is_finite());
    let mut values: Vec<f64> = bars
        .iter()
        .map(|b| b.1)
        .chain(split.iter().map(|s| s.1))
        .chain(x)
        .filter(|v| v.is_finite())
        .collect();
    let (v0, v1) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    if !v0.is_finite() {
        return None;
    }
    let mut widths: Vec<f64> = bars
        .iter()
        .map(|b| b.2.abs())
        .filter(|e| e.is_finite() && *e > 0.0)
        .collect();
    if v1 > v0 {
        widths.sort_by(f64::total_cmp);
        if let Some(&median) = widths.get(widths.len() / 2) {
            for &(_, v, e) in bars {
                if v.is_finite() && e.is_finite() && e > 0.0 && e <= BAR_OUTLIER * median {
                    values.push(v - e);
                    values.push(v + e);
                }
            }
        }
        let keep = x.unwrap_or(f64::NAN);
        return style::robust_range(&mut values, (keep, keep));
    }
    // one value: the bars around it (or the axis code's own widening)
    let e = widths.iter().copied().fold(0.0, f64::max);
    let pad = style::ROBUST_MARGIN * 2.0 * e;
    Some((v0 - e - pad, v0 + e + pad))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panel_is_scaled_by_its_values_not_by_a_wide_bar() {
        // level 0's bar is 100 times the others': the axis holds the values
        // (and the extrapolated one), not the bar
        let bars = [(0.0, 57.0, 50.0), (1.0, 57.2, 0.5), (2.0, 57.1, 0.2)];
        let split = [(0.5, 57.3), (1.5, 57.15)];
        let (lo, hi) = value_range(&bars, &split, Some(56.9)).unwrap();
        // the ordinary bars show whole (57.2 ± 0.5 reaches 56.7 and 57.7)
        assert!(lo < 56.7 && lo > 56.5, "{lo}");
        assert!(hi > 57.7 && hi < 57.9, "{hi}");
        // one value throughout: the bars set the axis
        let flat = [(0.0, 2.0, 0.1), (1.0, 2.0, 0.05)];
        let (lo, hi) = value_range(&flat, &[], None).unwrap();
        assert!(lo < 1.9 && hi > 2.1 && hi - lo < 0.3, "{lo} {hi}");
        // nothing finite: no axis
        assert_eq!(value_range(&[(0.0, f64::NAN, 1.0)], &[], None), None);
    }
}
