//! `loss_fraction_map.svg`: P_l over a 2-D sweep's grid with iso-lines of
//! V0/c (the study's Fig. 12).

use std::path::Path;

use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::{axis_label, axis_values, edges, span, tick};
use super::colour::{Paint, Ramp};
use super::contour::marching_squares;
use super::heat_map::{Label, Map, Overlay, draw_map};
use super::records::failed_note;
use crate::error::{Error, Result};
use crate::study::sweep::{SweepRecord, SweepSpec};
/// The V0/c iso-lines of a 2-D map: the band borders of TARGETS T7 (0.64,
/// 0.96, drawn bold) and a few others for orientation.
pub const SPEED_RATIO_LEVELS: [f64; 7] = [0.4, 0.5, 0.64, 0.8, 0.96, 1.1, 1.3];

/// Levels drawn bold (the study's band borders).
pub(super) const BOLD_LEVELS: [f64; 2] = [0.64, 0.96];

/// A P_l map's colour scale is logarithmic when its largest positive value
/// is more than this multiple of its smallest.
pub(super) const LOG_SPAN: f64 = 100.0;

/// P_l over a 2-D sweep's grid as a heat map, with iso-lines of V0/c at
/// `levels` (each run's `speed_ratio`; 0.64 and 0.96 bold): the study's
/// Fig. 12.
pub fn write_loss_fraction_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
    levels: &[f64],
) -> Result<()> {
    write_map_hatched(path, spec, records, title, levels, false, None)
}

/// [`write_loss_fraction_map`], with the cells of the points whose
/// `--tolerance` was not met crossed out when `hatch`, and the colour
/// bar's label `bar` for a map of another quantity than P_l (put in the
/// records' `loss_fraction`).
pub(super) fn write_map_hatched(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
    levels: &[f64],
    hatch: bool,
    bar: Option<&str>,
) -> Result<()> {
    if spec.axes.len() != 2 || records.len() != spec.len() {
        return Err(Error::invalid(
            "sweep maps",
            format!("{} axes, {} records", spec.axes.len(), records.len()),
            "a 2-D map needs a two-axis sweep with every point present",
        ));
    }
    let (ax, ay) = (&spec.axes[0], &spec.axes[1]);
    let (xv, yv) = (axis_values(ax), axis_values(ay));
    let (nx, ny) = (ax.count, ay.count);
    let mut cells = vec![vec![None; nx]; ny];
    let mut ratio = vec![vec![f64::NAN; ny]; nx];
    for r in records {
        let (i, j) = (r.index / ny, r.index % ny);
        if i < nx {
            cells[j][i] = Some(r.loss_fraction()).filter(|v| v.is_finite());
            ratio[i][j] = r.speed_ratio.unwrap_or(f64::NAN);
        }
    }
    let positive: Vec<f64> = cells
        .iter()
        .flatten()
        .flatten()
        .copied()
        .filter(|v| *v > 0.0)
        .collect();
    let hi = positive.iter().copied().fold(0.0_f64, f64::max);
    let lo_pos = positive.iter().copied().fold(f64::INFINITY, f64::min);
    // a logarithmic colour scale when the positive P_l span more than
    // LOG_SPAN (a 1e-3 loss at the support and a 0.5 loss past V0/c = 1 in
    // one map); its bottom is a power of ten
    let log_scale = hi > 0.0 && hi / lo_pos > LOG_SPAN;
    let lo = if log_scale {
        10f64.powf(lo_pos.max(hi * 1e-6).log10().floor())
    } else {
        0.0
    };
    // plotted coordinates: ln on a log axis (interpolation happens there)
    let tx = |v: f64| if ax.log { v.ln() } else { v };
    let ty = |v: f64| if ay.log { v.ln() } else { v };
    let ux = |v: f64| if ax.log { v.exp() } else { v };
    let uy = |v: f64| if ay.log { v.exp() } else { v };
    let px: Vec<f64> = xv.iter().map(|&v| tx(v)).collect();
    let py: Vec<f64> = yv.iter().map(|&v| ty(v)).collect();
    let (x_edges, y_edges) = (edges(&xv, ax.log), edges(&yv, ay.log));
    let (xe0, xe1) = span(&x_edges);
    let (ye0, ye1) = span(&y_edges);
    let (pxa, pxb) = (tx(xe0), tx(xe1));
    let (pya, pyb) = (ty(ye0), ty(ye1));
    let mut overlays = Vec::new();
    let mut labels = Vec::new();
    for &level in levels {
        let segs = marching_squares(&px, &py, &ratio, level);
        if segs.is_empty() {
            continue;
        }
        let bold = BOLD_LEVELS.iter().any(|b| (b - level).abs() < 1e-9);
        // label at the segment end nearest the upper-right corner that
        // leaves room above it; right-aligned and above the line, which
        // rises to the right there (lines of V0/c over (T, V0) do)
        let mut best = (f64::NEG_INFINITY, (0.0, 0.0));
        let mut fallback = best;
        for s in &segs {
            for &(x, y) in s {
                let (fx, fy) = ((x - pxa) / (pxb - pxa), (y - pya) / (pyb - pya));
                let score = fx + fy;
                if score > fallback.0 {
                    fallback = (score, (x, y));
                }
                if fy <= 0.9 && fx >= 0.12 && score > best.0 {
                    best = (score, (x, y));
                }
            }
            overlays.push(Overlay {
                points: s.iter().map(|&(x, y)| (ux(x), uy(y))).collect(),
                bold,
            });
        }
        let ((bx, by), room) = if best.0.is_finite() {
            (best.1, true)
        } else {
            (fallback.1, false)
        };
        let (anchor, at) = if room {
            (
                Pos::new(HPos::Right, VPos::Bottom),
                (ux(bx - 0.01 * (pxb - pxa)), uy(by + 0.015 * (pyb - pya))),
            )
        } else {
            (
                Pos::new(HPos::Right, VPos::Top),
                (ux(bx - 0.01 * (pxb - pxa)), uy(by - 0.015 * (pyb - pya))),
            )
        };
        labels.push(Label {
            at,
            text: format!("V0/c = {}", tick(level)),
            anchor,
        });
    }
    if hatch {
        // an X over each cell whose point did not reach its tolerance
        for r in records {
            let (i, j) = (r.index / ny, r.index % ny);
            if i >= nx || r.accuracy.as_ref().is_none_or(|a| a.met) {
                continue;
            }
            let (x0, x1) = (x_edges[i], x_edges[i + 1]);
            let (y0, y1) = (y_edges[j], y_edges[j + 1]);
            overlays.push(Overlay {
                points: vec![(x0, y0), (x1, y1)],
                bold: false,
            });
            overlays.push(Overlay {
                points: vec![(x0, y1), (x1, y0)],
                bold: false,
            });
        }
    }
    let with_loss = records.iter().filter(|r| r.loss_fraction() > 0.0).count();
    let map = Map {
        title: title.map_or_else(
            || {
                format!(
                    "possibility of contact loss P_l over ({}, {})",
                    ax.key, ay.key
                )
            },
            str::to_string,
        ),
        x_desc: axis_label(&ax.key),
        y_desc: axis_label(&ay.key),
        x_edges,
        y_edges,
        x_log: ax.log,
        y_log: ay.log,
        cells,
        paint: Paint::Scale {
            ramp: Ramp::Heat,
            lo,
            hi: if hi > 0.0 { hi } else { 1.0 },
            zero_white: true,
            log: log_scale,
            bar_label: bar
                .unwrap_or("P_l = time with contact lost / run time")
                .into(),
            clipped_max: None,
        },
        overlays,
        labels,
        footer: format!(
            "{nx} × {ny} runs, {with_loss} {}; lines: V0/c of each run (marching squares), bold at 0.64 and 0.96 (the study's band borders){}",
            if bar.is_some() {
                "above 0"
            } else {
                "with loss"
            },
            failed_note(records)
        ),
    };
    draw_map(path, &map)
}
