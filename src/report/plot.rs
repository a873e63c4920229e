//! SVG line plots: `force.svg` of a run and `compare.svg` of a comparison.
//! Both are contact forces along x_m/L (or t for stationary carriers) with
//! contact loss shaded; one helper draws them.

use std::path::Path;

use plotters::prelude::*;

use super::PALETTE;
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::RunOutput;

/// The force axis is clipped at this multiple of the 99.5th percentile:
/// re-contact spikes (no impact law, TARGETS "What the study does not
/// settle") can be ten times the force level and would flatten the curve.
const CLIP_FACTOR: f64 = 2.0;

/// One line of a plot, with the x-intervals to shade in its colour.
pub(crate) struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Intervals [x0, x1] to shade (contact lost).
    pub shaded: Vec<[f64; 2]>,
}

/// The label of a run's x axis: x_m/L, or t when every carrier is
/// stationary ([`force_series`] reads the values from the history as it
/// decimates; a copy of a column here was 8 bytes a row beyond the memory
/// estimate, issue 25).
pub(crate) fn abscissa_label(sc: &Resolved) -> &'static str {
    if sc.carriers.iter().all(|c| c.motion.is_stationary()) {
        "t (s)"
    } else {
        "x_m / L"
    }
}

/// The force series of every carrier of a run, labelled `prefix` + carrier.
pub(crate) fn force_series(sc: &Resolved, out: &RunOutput, prefix: &str) -> Vec<Series> {
    let in_time = sc.carriers.iter().all(|c| c.motion.is_stationary());
    let nc = out.history.carriers.len();
    (0..nc)
        .map(|c| {
            // rows 1 … n, reduced as they are read (no copy of the history)
            let h = &out.history;
            let force = &h.carriers[c].force;
            let l = sc.beam.length;
            let at = |i: usize| {
                let x = if in_time {
                    h.t[i + 1]
                } else {
                    h.carriers[c].x[i + 1] / l
                };
                (x, force[i + 1])
            };
            let points = decimate_with(force.len().saturating_sub(1), at);
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
                } else {
                    stats.loss_intervals.clone()
                },
            }
        })
        .collect()
}

/// Plot the contact force of every carrier, loss shaded (`force.svg`).
pub fn write_force_plot(path: &Path, sc: &Resolved, out: &RunOutput) -> Result<()> {
    let title = format!(
        "contact force: {} elements, dt = {} s, P_l = {:.4} ({:.4} in span)",
        sc.elements, sc.dt, out.stats[0].loss_fraction, out.stats[0].loss_fraction_span
    );
    let x_desc = abscissa_label(sc);
    line_plot(
        path,
        &title,
        (x_desc, "contact force λ (N)"),
        &force_series(sc, out, ""),
        LOSS_SHADING,
    )
}

/// What the shaded intervals of a force plot mean.
pub(crate) const LOSS_SHADING: &str = "contact lost (shaded)";

/// Draw series as lines with shaded intervals (meaning `shading`, in the
/// legend); clip the y axis above spikes.
pub(crate) fn line_plot(
    path: &Path,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    series: &[Series],
    shading: &str,
) -> Result<()> {
    draw(path, title, x_desc, y_desc, series, shading).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

/// Pixel size of a line plot.
const SIZE: (u32, u32) = (960, 480);

pub use crate::resolve::memory::PLOT_BUCKETS;

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

fn draw(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    shading: &str,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let series: Vec<Series> = series
        .iter()
        .map(|s| Series {
            label: s.label.clone(),
            points: decimate(&s.points),
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
        .collect();
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut ys: Vec<f64> = Vec::with_capacity(series.iter().map(|s| s.points.len()).sum());
    for s in &series {
        for &(x, y) in &s.points {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
            ys.push(y);
        }
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    ys.sort_by(f64::total_cmp);
    let p995 = ys
        .get((0.995 * (ys.len().max(1) - 1) as f64) as usize)
        .copied()
        .unwrap_or(y1);
    let true_max = y1;
    let clipped = p995 > 0.0 && y1 > CLIP_FACTOR * p995;
    if clipped {
        y1 = CLIP_FACTOR * p995;
    }
    let pad = 0.05 * (y1 - y0).max(1e-9 * y1.abs().max(1.0));
    let (y0, y1) = (y0 - pad, y1 + pad);
    let mut caption = title.to_string();
    if clipped {
        caption.push_str(&format!(
            " (axis clipped; peak {})",
            crate::error::compact_number(true_max.round())
        ));
    }
    let ranges = super::axis_range::drawable("horizontal", x0, x1, false)
        .and_then(|x| super::axis_range::drawable("vertical", y0, y1, false).map(|y| (x, y)));
    let ((x0, x1), (y0, y1)) = match ranges {
        Ok(r) => r,
        Err(reason) => {
            let table = if path.file_name().is_some_and(|n| n == "force.svg") {
                "history.csv and summary.json"
            } else {
                "the CSV and JSON tables beside it"
            };
            super::axis_range::write_note(path, SIZE, &caption, &reason, table)?;
            return Ok(());
        }
    };

    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;

    for (i, s) in series.iter().enumerate() {
        let shade = PALETTE[i % PALETTE.len()].mix(0.15);
        chart.draw_series(
            s.shaded
                .iter()
                .map(|iv| Rectangle::new([(iv[0], y0), (iv[1], y1)], shade.filled())),
        )?;
    }
    for (i, s) in series.iter().enumerate() {
        let col = PALETTE[i % PALETTE.len()];
        let pts: Vec<(f64, f64)> = s.points.iter().map(|&(x, y)| (x, y.min(y1))).collect();
        chart
            .draw_series(LineSeries::new(pts, col.stroke_width(1)))?
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], col));
    }
    if series.iter().any(|s| !s.shaded.is_empty()) {
        let shade = PALETTE[0].mix(0.15);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x0, y0), (x0, y0)],
                shade.filled(),
            )))?
            .label(shading)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 18, y + 5)], shade.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
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
        let n = 1_000_003;
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
