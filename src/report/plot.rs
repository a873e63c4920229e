//! SVG line plots: `force.svg` of a run and `compare.svg` of a comparison.
//! Both are contact forces along x_m/L (or t for stationary carriers) with
//! contact loss shaded; one helper draws them.

use std::path::Path;

use plotters::prelude::*;

use super::PALETTE;
use super::style;
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::RunOutput;

/// One line of a plot, with the x-intervals to shade in its colour.
pub(crate) struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Intervals [x0, x1] to shade (contact lost).
    pub shaded: Vec<[f64; 2]>,
    /// The same quantity filtered (the filtered contact force), drawn bold
    /// over `points`, which are then drawn light; empty: none.
    pub filtered: Vec<(f64, f64)>,
}

/// One panel of a plot of small multiples: its title and its lines.
pub(crate) struct Panel {
    /// Title above the panel (empty for a single panel: the plot's
    /// caption says it all).
    pub title: String,
    /// Lines.
    pub series: Vec<Series>,
    /// x of vertical ticks along the bottom (a line's supports); empty:
    /// none.
    pub marks: Vec<f64>,
}

/// The label of a run's x axis: x_m/L, x_m in metres on a line (whose
/// supports are marked), or t when every carrier is stationary
/// ([`force_series`] reads the values from the history as it decimates; a
/// copy of a column here was 8 bytes a row beyond the memory estimate).
pub(crate) fn abscissa_label(sc: &Resolved) -> &'static str {
    if sc.carriers.iter().all(|c| c.motion.is_stationary()) {
        "time t (s)"
    } else if in_metres(sc) {
        "carrier position x_m (m); supports ticked"
    } else {
        "carrier position x_m / L (–)"
    }
}

/// A line (a scene with supports) is drawn against x in metres, the
/// supports marked: a span of 50 m reads off the axis, a share of L not.
fn in_metres(sc: &Resolved) -> bool {
    !sc.wire.supports.is_empty()
}

/// The support ticks of a run's force plot: a moving carrier's line's
/// supports, m; else none.
pub(crate) fn support_marks(sc: &Resolved) -> Vec<f64> {
    if in_metres(sc) && !sc.carriers.iter().all(|c| c.motion.is_stationary()) {
        sc.wire.supports.clone()
    } else {
        Vec::new()
    }
}

/// The force series of every carrier of a run, labelled `prefix` + carrier,
/// each with its filtered force when the history holds it.
pub(crate) fn force_series(sc: &Resolved, out: &RunOutput, prefix: &str) -> Vec<Series> {
    let in_time = sc.carriers.iter().all(|c| c.motion.is_stationary());
    let metres = !in_time && in_metres(sc);
    let nc = out.history.carriers.len();
    (0..nc)
        .map(|c| {
            // rows 1 … n, reduced as they are read (no copy of the history)
            let h = &out.history;
            let tr = &h.carriers[c];
            let l = sc.beam.length;
            let x = |i: usize| {
                if in_time {
                    h.t[i + 1]
                } else if metres {
                    tr.x[i + 1]
                } else {
                    tr.x[i + 1] / l
                }
            };
            let points = decimate_with(tr.force.len().saturating_sub(1), |i| {
                (x(i), tr.force[i + 1])
            });
            let filtered = if c < crate::resolve::memory::MAX_FILTERED_LINES {
                decimate_with(tr.force_filtered.len().saturating_sub(1), |i| {
                    (x(i), tr.force_filtered[i + 1])
                })
            } else {
                Vec::new()
            };
            let stats = &out.stats[c];
            let label = match (prefix.is_empty(), nc) {
                (true, 1) => "λ".to_string(),
                (true, _) => format!("carrier {c}"),
                (false, 1) => prefix.to_string(),
                (false, _) => format!("{prefix} {c}"),
            };
            Series {
                label,
                points,
                shaded: if in_time {
                    stats.loss_intervals_time.clone()
                } else if metres {
                    let scale = |iv: &[f64; 2]| [iv[0] * l, iv[1] * l];
                    stats.loss_intervals.iter().map(scale).collect()
                } else {
                    stats.loss_intervals.clone()
                },
                filtered,
            }
        })
        .collect()
}

/// Plot the contact force of every carrier, its filtered force over it,
/// loss shaded and marked (`force.svg`).
pub(crate) fn write_force_plot(path: &Path, sc: &Resolved, out: &RunOutput) -> Result<()> {
    let title = format!(
        "contact force: {} elements, dt = {} s, P_l = {:.4} ({:.4} in span)",
        sc.elements, sc.dt, out.stats[0].loss_fraction, out.stats[0].loss_fraction_span
    );
    let x_desc = abscissa_label(sc);
    panels_plot(
        path,
        &title,
        (x_desc, "contact force λ (N)"),
        &[Panel {
            title: String::new(),
            series: force_series(sc, out, ""),
            marks: support_marks(sc),
        }],
        LOSS_SHADING,
        &filtered_label(out.history.band_hz()),
    )
}

/// The legend of a filtered force line.
pub(crate) fn filtered_label(band_hz: f64) -> String {
    format!("0–{band_hz} Hz filtered")
}

/// What the shaded intervals of a force plot mean.
pub(crate) const LOSS_SHADING: &str = "contact lost (shaded, marked below)";

/// Draw series as lines with shaded intervals (meaning `shading`, in the
/// legend); clip the y axis above spikes.
pub(crate) fn line_plot(
    path: &Path,
    title: &str,
    descs: (&str, &str),
    series: &[Series],
    shading: &str,
) -> Result<()> {
    let panel = Panel {
        title: String::new(),
        series: series
            .iter()
            .map(|s| Series {
                label: s.label.clone(),
                points: s.points.clone(),
                shaded: s.shaded.clone(),
                filtered: s.filtered.clone(),
            })
            .collect(),
        marks: Vec::new(),
    };
    panels_plot(path, title, descs, &[panel], shading, "filtered")
}

/// Draw `panels` as small multiples on common axes (one column up to three
/// panels, two above), each with its lines, their filtered lines (legend
/// `filtered`) and shaded intervals (legend `shading`); clip the y axis
/// above spikes.
pub(crate) fn panels_plot(
    path: &Path,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    panels: &[Panel],
    shading: &str,
    filtered: &str,
) -> Result<()> {
    draw(path, title, (x_desc, y_desc), panels, (shading, filtered)).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

/// Pixel size of a line plot.
const SIZE: (u32, u32) = (960, 480);

pub(crate) use crate::resolve::memory::PLOT_BUCKETS;

/// `points` reduced to at most 4 × [`PLOT_BUCKETS`], in order: per bucket
/// of consecutive points, the first, the lowest, the highest and the last
/// (each once). Points with a non-finite coordinate are dropped (nothing to
/// draw).
pub(crate) fn decimate(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    decimate_with(points.len(), |i| points[i])
}

/// [`decimate`] of the `n` points `at(0) … at(n − 1)`, read once each in
/// order and never gathered (a run's history is not copied to be drawn).
pub(crate) fn decimate_with(n: usize, at: impl Fn(usize) -> (f64, f64)) -> Vec<(f64, f64)> {
    let finite = |p: (f64, f64)| p.0.is_finite() && p.1.is_finite();
    if n <= 4 * PLOT_BUCKETS {
        // room for every point at once (no doubling: the memory estimate
        // counts 4 × PLOT_BUCKETS points)
        let mut out = Vec::with_capacity(n);
        out.extend((0..n).map(&at).filter(|&p| finite(p)));
        return out;
    }
    let per = n.div_ceil(PLOT_BUCKETS);
    let mut out = Vec::with_capacity(4 * PLOT_BUCKETS);
    let mut start = 0;
    while start < n {
        let end = (start + per).min(n);
        // (index, point) of the first, lowest, highest and last finite points
        let mut picks: [Option<(usize, (f64, f64))>; 4] = [None; 4];
        for i in start..end {
            let p = at(i);
            if !finite(p) {
                continue;
            }
            if picks[0].is_none() {
                picks[0] = Some((i, p));
            }
            if picks[1].is_none_or(|(_, q)| p.1 < q.1) {
                picks[1] = Some((i, p));
            }
            if picks[2].is_none_or(|(_, q)| p.1 > q.1) {
                picks[2] = Some((i, p));
            }
            picks[3] = Some((i, p));
        }
        let mut kept: Vec<(usize, (f64, f64))> = picks.into_iter().flatten().collect();
        kept.sort_by_key(|k| k.0);
        kept.dedup_by_key(|k| k.0);
        out.extend(kept.into_iter().map(|k| k.1));
        start = end;
    }
    out
}

/// Loss intervals narrower than this share of the x range are widened to
/// it when drawn, so that a single lost step shows (the numbers are in the
/// tables; the picture only has to show where).
const MIN_MARK_WIDTH: f64 = 0.003;

/// Opacity of the loss shading and of a raw line under its filtered one.
const SHADE_OPACITY: f64 = 0.22;
const RAW_OPACITY: f64 = 0.45;

/// The colour of the loss marks under the plot area (Okabe–Ito's
/// vermillion).
const LOSS_MARK: RGBColor = RGBColor(213, 94, 0);

/// Markers drawn along each line (its colour is not the only cue).
const MARKS_PER_LINE: usize = 8;

/// The data of a panel as drawn: decimated, non-finite intervals dropped.
fn decimated(p: &Panel) -> Panel {
    Panel {
        title: p.title.clone(),
        series: p
            .series
            .iter()
            .map(|s| Series {
                label: s.label.clone(),
                points: decimate(&s.points),
                filtered: decimate(&s.filtered),
                shaded: {
                    let mut v = Vec::with_capacity(s.shaded.len());
                    v.extend(
                        s.shaded
                            .iter()
                            .copied()
                            .filter(|iv| iv[0].is_finite() && iv[1].is_finite()),
                    );
                    v
                },
            })
            .collect(),
        marks: p.marks.clone(),
    }
}

/// The y range of a panel: the robust range of its raw lines
/// ([`style::robust_range`]) widened to hold its filtered lines whole, and
/// the true extremes (for the caption of what was clipped).
fn panel_range(p: &Panel) -> Option<((f64, f64), (f64, f64))> {
    let mut ys: Vec<f64> = Vec::with_capacity(p.series.iter().map(|s| s.points.len()).sum());
    let (mut f0, mut f1) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut t0, mut t1) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in &p.series {
        ys.extend(s.points.iter().map(|q| q.1));
        for &(_, y) in &s.filtered {
            f0 = f0.min(y);
            f1 = f1.max(y);
        }
        for &(_, y) in s.points.iter().chain(&s.filtered) {
            t0 = t0.min(y);
            t1 = t1.max(y);
        }
    }
    let r =
        style::robust_range(&mut ys, (f0, f1)).or_else(|| f0.is_finite().then_some((f0, f1)))?;
    // nothing left out: the full range, margin included
    let r = if t0 >= r.0 && t1 <= r.1 {
        let pad = style::ROBUST_MARGIN * (t1 - t0).max(1e-9 * t1.abs().max(1.0));
        (t0 - pad, t1 + pad)
    } else {
        r
    };
    Some((r, (t0, t1)))
}

fn draw(
    path: &Path,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    panels: &[Panel],
    (shading, filtered_legend): (&str, &str),
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let panels: Vec<Panel> = panels.iter().map(decimated).collect();
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in panels.iter().flat_map(|p| &p.series) {
        for &(x, _) in s.points.iter().chain(&s.filtered) {
            x0 = x0.min(x);
            x1 = x1.max(x);
        }
    }
    for p in &panels {
        for &m in &p.marks {
            x0 = x0.min(m);
            x1 = x1.max(m);
        }
    }
    if !x0.is_finite() {
        (x0, x1) = (0.0, 1.0);
    }
    // one y scale per panel, from its robust range
    let mut y_ranges = Vec::with_capacity(panels.len());
    let mut clipped_any = false;
    let mut failed = super::axis_range::drawable("horizontal", x0, x1, false).err();
    for p in &panels {
        let ((lo, hi), (t0, t1)) = panel_range(p).unwrap_or(((0.0, 1.0), (0.0, 1.0)));
        clipped_any |= t0 < lo || t1 > hi;
        match super::axis_range::drawable("vertical", lo, hi, false) {
            Ok(r) => y_ranges.push(r),
            Err(reason) => {
                failed.get_or_insert(reason);
                y_ranges.push((0.0, 1.0));
            }
        }
    }
    let mut caption = title.to_string();
    if clipped_any {
        caption.push_str(" (y: 1st–99th percentile; ▲▼ beyond)");
    }
    let single = panels.len() <= 1;
    let cols = if panels.len() <= 3 { 1 } else { 2 };
    let rows = panels.len().max(1).div_ceil(cols);
    let size = if single {
        (SIZE.0 + style::LEGEND_WIDTH, SIZE.1)
    } else {
        (
            SIZE.0 + style::LEGEND_WIDTH,
            40 + rows as u32 * PANEL_HEIGHT,
        )
    };
    if let Some(reason) = failed {
        let table = if path.file_name().is_some_and(|n| n == "force.svg") {
            "history.csv and summary.json"
        } else {
            "the CSV and JSON tables beside it"
        };
        super::axis_range::write_note(path, size, &caption, &reason, table)?;
        return Ok(());
    }
    let (x0, x1) = super::axis_range::drawable("horizontal", x0, x1, false)?;

    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    // a long title in a smaller font rather than cut at the edges
    let title_px = if caption.chars().count() > LONG_TITLE {
        14
    } else {
        18
    };
    let root = root.titled(&caption, ("sans-serif", title_px))?;
    let (plot_area, legend_area) = root.split_horizontally(style::legend_layout(size).0[2]);
    let areas = plot_area.split_evenly((rows, cols));
    let min_width = MIN_MARK_WIDTH * (x1 - x0);
    // the legend once, from the panel with the most lines
    let mut key: Vec<(String, style::Key)> = Vec::new();
    if let Some(p) = panels.iter().max_by_key(|p| p.series.len()) {
        for (i, s) in p.series.iter().enumerate() {
            let (col, m) = style::series_style(i);
            let label = if s.filtered.is_empty() {
                s.label.clone()
            } else {
                format!("{} (raw)", s.label)
            };
            key.push((label, style::Key::Line(light(col), 1, None)));
            if !s.filtered.is_empty() {
                let label = if p.series.len() == 1 {
                    filtered_legend.to_string()
                } else {
                    format!("{} ({filtered_legend})", s.label)
                };
                key.push((label, style::Key::Line(dark(col), 2, Some(m))));
            } else {
                key.last_mut().expect("pushed").1 = style::Key::Line(col, 1, Some(m));
            }
        }
    }
    if panels
        .iter()
        .flat_map(|p| &p.series)
        .any(|s| !s.shaded.is_empty())
    {
        key.push((
            shading.to_string(),
            style::Key::Shade(PALETTE[0].mix(SHADE_OPACITY)),
        ));
    }
    if clipped_any {
        key.push((
            "beyond the axis (clipped)".into(),
            style::Key::Mark(BLACK, style::Marker::TriangleUp),
        ));
    }
    if panels.iter().any(|p| !p.marks.is_empty()) {
        key.push(("supports".into(), style::Key::Line(SUPPORT_MARK, 2, None)));
    }
    for ((panel, area), &(y0, y1)) in panels.iter().zip(areas).zip(&y_ranges) {
        let mut builder = ChartBuilder::on(&area);
        builder
            .margin(10)
            .x_label_area_size(if single { 44 } else { 36 })
            .y_label_area_size(if single { 72 } else { 64 });
        if !panel.title.is_empty() {
            builder.caption(&panel.title, ("sans-serif", 13));
        }
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1)?;
        style_axes(&mut chart, x_desc, y_desc)?;
        let mark = 0.035 * (y1 - y0);
        let clamp = |y: f64| y.clamp(y0, y1);
        let widened = |iv: &[f64; 2]| {
            let c = 0.5 * (iv[0] + iv[1]);
            let w = (iv[1] - iv[0]).max(min_width);
            (c - 0.5 * w, c + 0.5 * w)
        };
        for (i, s) in panel.series.iter().enumerate() {
            let shade = style::series_style(i).0.mix(SHADE_OPACITY);
            chart.draw_series(s.shaded.iter().map(|iv| {
                let (a, b) = widened(iv);
                Rectangle::new([(a, y0), (b, y1)], shade.filled())
            }))?;
            // a mark per loss under the lines, visible however short
            chart.draw_series(s.shaded.iter().map(|iv| {
                let (a, b) = widened(iv);
                Rectangle::new([(a, y0), (b, y0 + mark)], LOSS_MARK.filled())
            }))?;
        }
        // the supports: ticks up from the bottom edge
        chart.draw_series(panel.marks.iter().map(|&x| {
            PathElement::new(
                vec![(x, y0), (x, y0 + 2.0 * mark)],
                SUPPORT_MARK.stroke_width(2),
            )
        }))?;
        for (i, s) in panel.series.iter().enumerate() {
            let (col, m) = style::series_style(i);
            let pts: Vec<(f64, f64)> = s.points.iter().map(|&(x, y)| (x, clamp(y))).collect();
            let raw = if s.filtered.is_empty() {
                col.stroke_width(1)
            } else {
                col.mix(RAW_OPACITY).stroke_width(1)
            };
            chart.draw_series(LineSeries::new(pts, raw))?;
            // what lies beyond the axis: a triangle at the edge it crosses
            chart.draw_series(s.points.iter().filter(|p| p.1 > y1 || p.1 < y0).map(
                |&(x, y)| {
                    let shape = if y > y1 {
                        style::Marker::TriangleUp
                    } else {
                        style::Marker::TriangleDown
                    };
                    style::marker(shape, (x, clamp(y)), 3, BLACK)
                },
            ))?;
            let line = if s.filtered.is_empty() {
                &s.points
            } else {
                &s.filtered
            };
            let col = if s.filtered.is_empty() {
                col
            } else {
                dark(col)
            };
            if !s.filtered.is_empty() {
                let pts: Vec<(f64, f64)> = s.filtered.iter().map(|&(x, y)| (x, clamp(y))).collect();
                chart.draw_series(LineSeries::new(pts, col.stroke_width(2)))?;
            }
            chart.draw_series(
                spaced(line, i).map(|(x, y)| style::marker(m, (x, clamp(y)), 3, col)),
            )?;
        }
    }
    style::draw_legend(&legend_area, &key, 60)?;
    root.present()?;
    Ok(())
}

/// Characters of a title above which it is set smaller (about what 18 px
/// fits across 1210 px).
const LONG_TITLE: usize = 110;

/// The colour of the support ticks.
const SUPPORT_MARK: RGBColor = RGBColor(90, 90, 90);

/// [`MARKS_PER_LINE`] points of `line`, evenly spaced, shifted by the
/// series `i` so that markers of lines that agree do not hide each other.
fn spaced(line: &[(f64, f64)], i: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
    let n = line.len();
    let every = (n / MARKS_PER_LINE).max(1);
    let shift = (i * every / 3) % every;
    line.iter().skip(shift).step_by(every).copied()
}

/// Tick labels a side of a line plot, at most.
const AXIS_LABELS: usize = 10;

/// A chart of two real axes on an SVG (every line plot of taut's).
pub(crate) type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// The axes of a line plot: labelled (with their units) in 14 px, ticks in
/// 12 px, the major grid only.
pub(crate) fn style_axes(
    chart: &mut Chart<'_, '_>,
    x_desc: &str,
    y_desc: &str,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    // labels at the precision of plotters' 1-2-5 steps (about ten a side)
    let step = |r: std::ops::Range<f64>| style::nice_step(r.end - r.start, AXIS_LABELS);
    let (sx, sy) = (step(chart.x_range()), step(chart.y_range()));
    chart
        .configure_mesh()
        .x_labels(AXIS_LABELS)
        .y_labels(AXIS_LABELS)
        .x_label_formatter(&|v| style::tick_label(*v, sx))
        .y_label_formatter(&|v| style::tick_label(*v, sy))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(("sans-serif", 14))
        .label_style(("sans-serif", 12))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    Ok(())
}

/// Pixel height of one panel of small multiples.
const PANEL_HEIGHT: u32 = 260;

/// `c` at [`RAW_OPACITY`] over white (a raw line in the legend).
fn light(c: RGBColor) -> RGBColor {
    let l = |v: u8| (RAW_OPACITY * f64::from(v) + (1.0 - RAW_OPACITY) * 255.0) as u8;
    RGBColor(l(c.0), l(c.1), l(c.2))
}

/// A darker shade of `c` (the filtered line over its raw line).
fn dark(c: RGBColor) -> RGBColor {
    let d = |v: u8| (f64::from(v) * 0.55) as u8;
    RGBColor(d(c.0), d(c.1), d(c.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_the_envelope_and_drops_non_finite_points() {
        // short series: as they are, less the non-finite points
        let short = vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0)];
        assert_eq!(decimate(&short), vec![(0.0, 1.0), (2.0, 3.0)]);
        // a long series: bounded, in order, with its extremes and ends
        let n: usize = 1_000_003;
        let pts: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                (
                    i as f64,
                    ((i * 7919) % 1013) as f64 - if i == 500_000 { 1e6 } else { 0.0 },
                )
            })
            .collect();
        let d = decimate(&pts);
        assert!(d.len() <= 4 * PLOT_BUCKETS, "{}", d.len());
        assert!(d.windows(2).all(|w| w[0].0 < w[1].0));
        assert_eq!(d.first(), pts.first());
        assert_eq!(d.last(), pts.last());
        let lowest = d.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let highest = d.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let extreme = |f: fn(f64, f64) -> f64, from: f64| pts.iter().map(|p| p.1).fold(from, f);
        assert_eq!(lowest, extreme(f64::min, f64::INFINITY));
        assert!(lowest < -9e5);
        assert_eq!(highest, extreme(f64::max, f64::NEG_INFINITY));
    }
}
