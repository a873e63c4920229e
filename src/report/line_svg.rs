//! `line.svg`: the picture of the line (`[output] envelope = true`;
//! docs/output.md#line-svg). Two panels over x (m):
//!
//! - the line where the run started: the contact wire (at rest v = 0, or
//!   its static sag with `[time] initial = "static"`), the supports, each
//!   dropper as a vertical segment from the wire up to its anchor (a fixed
//!   height, or the messenger where it hangs), a messenger wire when the
//!   scene has one ([`messenger_line`]: its rest line h_m, or h_m + v_m(x, 0)
//!   after a static start), and each carrier's travel (the x_m it covered)
//!   as a bar below the wire;
//! - the uplift envelope: the largest and smallest v(x, t) over the run at
//!   every node (`envelope.csv`), in mm, with the supports and their largest
//!   uplift (`supports.csv`) marked.
//!
//! Each panel's legend is a column beside it ([`style::draw_legend`]).

use std::path::Path;

use plotters::prelude::*;

use super::PALETTE;
use super::axis_range::{drawable, write_note};
use super::style::{self, Key};
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::RunOutput;
use crate::scene::Anchor;

/// Pixel size of `line.svg`.
const SIZE: (u32, u32) = (1200, 720);

/// Metres to the envelope panel's millimetres.
const MM: f64 = 1e3;

/// The height of a dropper's upper end above the wire at rest, m: a fixed
/// anchor's own height, or a messenger dropper's messenger rest line h_m.
fn anchor_height(a: &Anchor) -> f64 {
    match *a {
        Anchor::Fixed { height } | Anchor::Messenger { height } => height,
    }
}

/// The messenger wire as (x, height) points, m, when the resolved scene
/// has one, between its outermost supports: its rest line at h_m, or
/// h_m + v_m(x, 0) at the envelope's nodes when the run started displaced
/// (`sag`: the envelope's `messenger_start`).
fn messenger_line(sc: &Resolved, x: &[f64], sag: &[f64]) -> Option<Vec<(f64, f64)>> {
    let m = sc.beam.messenger.as_ref()?;
    let (a, b) = (m.supports[0], m.supports[m.supports.len() - 1]);
    if sag.iter().all(|v| *v == 0.0) {
        return Some(m.supports.iter().map(|&x| (x, m.height)).collect());
    }
    Some(
        x.iter()
            .zip(sag)
            .filter(|(x, _)| (a..=b).contains(*x))
            .map(|(&x, &v)| (x, m.height + v))
            .collect(),
    )
}

/// Linear interpolation of `v` on the increasing points `x` at `at` (0
/// without points): a picture's reading of a recorded shape between nodes.
fn interpolate(x: &[f64], v: &[f64], at: f64) -> f64 {
    match x.len() {
        0 => 0.0,
        _ if v.len() != x.len() => 0.0,
        1 => v[0],
        n => {
            let i = x.partition_point(|&p| p <= at).clamp(1, n - 1);
            let (x0, x1) = (x[i - 1], x[i]);
            let s = ((at - x0) / (x1 - x0)).clamp(0.0, 1.0);
            v[i - 1] + s * (v[i] - v[i - 1])
        }
    }
}

/// Each carrier's travel: the smallest and largest x_m in its history, m
/// (`None` for a carrier with no finite position).
fn travel(out: &RunOutput) -> Vec<Option<(f64, f64)>> {
    out.history
        .carriers
        .iter()
        .map(|tr| {
            let xs = tr.x.iter().copied().filter(|x| x.is_finite());
            let lo = xs.clone().fold(f64::INFINITY, f64::min);
            let hi = xs.fold(f64::NEG_INFINITY, f64::max);
            lo.is_finite().then_some((lo, hi))
        })
        .collect()
}

/// Draw `line.svg` for a run that recorded the envelope.
pub fn write_line_plot(path: &Path, sc: &Resolved, out: &RunOutput) -> Result<()> {
    let fail = |e: Box<dyn std::error::Error>| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    };
    let l = sc.beam.length;
    let env = &out.history.envelope;
    let (mut v0, mut v1) = (0.0f64, 0.0f64);
    for (&lo, &hi) in env.v_min.iter().zip(&env.v_max) {
        v0 = v0.min(lo * MM);
        v1 = v1.max(hi * MM);
    }
    // where the run started: both wires' shapes at t = 0 (zero at rest)
    let start = &env.start;
    let displaced = start.iter().any(|v| *v != 0.0);
    let wire_at = |x: f64| interpolate(&env.x, start, x);
    let messenger_at = |x: f64| interpolate(&env.x, &env.messenger_start, x);
    // each dropper from the wire to its anchor (a messenger's at its start)
    let ends: Vec<(f64, f64)> = sc
        .droppers
        .iter()
        .map(|d| {
            let top = anchor_height(&d.anchor)
                + if d.on_messenger() {
                    messenger_at(d.x)
                } else {
                    0.0
                };
            (wire_at(d.x), top)
        })
        .collect();
    let heights: Vec<f64> = ends.iter().map(|e| e.1).collect();
    let messenger = messenger_line(sc, &env.x, &env.messenger_start);
    let top = heights
        .iter()
        .copied()
        .chain(messenger.iter().flatten().map(|p| p.1))
        .fold(0.0f64, f64::max);
    let bottom = heights
        .iter()
        .copied()
        .chain(start.iter().copied())
        .fold(0.0f64, f64::min);
    // the carriers' bars sit below the wire, a twentieth of the height apart
    let step = 0.05 * (top - bottom).max(1.0);
    let nc = out.history.carriers.len();
    let line_lo = bottom - step * (nc as f64 + 1.0);
    let line_hi = top + step;
    let title = format!(
        "the line: {} supports, {} droppers; uplift envelope (max {:.2} mm, min {:.2} mm)",
        out.history.supports.len(),
        sc.droppers.len(),
        v1,
        v0
    );
    let ranges = drawable("x", 0.0, l, false).and_then(|x| {
        drawable("height", line_lo, line_hi, false)
            .and_then(|h| drawable("v", v0, v1, false).map(|v| (x, h, v)))
    });
    let (xr, hr, vr) = match ranges {
        Ok(r) => r,
        Err(reason) => {
            return write_note(path, SIZE, &title, &reason, "envelope.csv and supports.csv");
        }
    };
    let pad = |(lo, hi): (f64, f64)| {
        let p = 0.05 * (hi - lo);
        (lo - p, hi + p)
    };
    let vr = pad(vr);
    let draw = || -> std::result::Result<(), Box<dyn std::error::Error>> {
        let root = SVGBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(&title, ("sans-serif", 18))?;
        let (upper, lower) = root.split_vertically(SIZE.1 / 2 - 20);
        // each half's legend in a column of its own on the right, off the wires
        let split = style::legend_layout(SIZE).0[2];
        let (upper, upper_key) = upper.split_horizontally(split);
        let (lower, lower_key) = lower.split_horizontally(split);
        let mut key: Vec<(String, Key)> = Vec::new();

        // the line
        let mut chart = ChartBuilder::on(&upper)
            .margin(12)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(xr.0..xr.1, hr.0..hr.1)?;
        chart
            .configure_mesh()
            .x_desc("x (m)")
            .y_desc("height (m)")
            .draw()?;
        let (wire, wire_label): (Vec<(f64, f64)>, _) = if displaced {
            (
                env.x.iter().copied().zip(start.iter().copied()).collect(),
                "contact wire at t = 0 (static start)",
            )
        } else {
            (vec![(0.0, 0.0), (l, 0.0)], "contact wire at rest")
        };
        chart.draw_series(LineSeries::new(wire, BLACK.stroke_width(2)))?;
        key.push((wire_label.into(), Key::Line(BLACK, 2, None)));
        let support = RGBColor(90, 90, 90);
        let masts = out
            .history
            .supports
            .iter()
            .map(|s| PathElement::new(vec![(s.x, hr.0), (s.x, hr.1)], support.stroke_width(2)));
        if !out.history.supports.is_empty() {
            chart.draw_series(masts)?;
            key.push(("supports".into(), Key::Bar(support, 2)));
        }
        let dropper = PALETTE[2];
        if !sc.droppers.is_empty() {
            chart.draw_series(sc.droppers.iter().zip(&ends).map(|(d, &(z0, z1))| {
                PathElement::new(vec![(d.x, z0), (d.x, z1)], dropper.stroke_width(1))
            }))?;
            key.push(("droppers (to their anchors)".into(), Key::Bar(dropper, 1)));
        }
        if let Some(m) = messenger {
            let col = PALETTE[4];
            chart.draw_series(LineSeries::new(m, col.stroke_width(2)))?;
            key.push(("messenger wire".into(), Key::Line(col, 2, None)));
        }
        for (c, span) in travel(out).into_iter().enumerate() {
            let Some((a, b)) = span else { continue };
            let y = bottom - step * (c as f64 + 1.0);
            let col = PALETTE[c % PALETTE.len()];
            chart.draw_series(LineSeries::new([(a, y), (b, y)], col.stroke_width(4)))?;
            key.push((format!("carrier {c} travel"), Key::Line(col, 4, None)));
        }
        style::draw_legend(&upper_key, &std::mem::take(&mut key), 24)?;

        // the uplift envelope
        let mut chart = ChartBuilder::on(&lower)
            .margin(12)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(xr.0..xr.1, vr.0..vr.1)?;
        chart
            .configure_mesh()
            .x_desc("x (m)")
            .y_desc("v (mm, up)")
            .draw()?;
        chart.draw_series(
            out.history
                .supports
                .iter()
                .map(|s| PathElement::new(vec![(s.x, vr.0), (s.x, vr.1)], support.mix(0.5))),
        )?;
        for (k, (name, col)) in [
            ("max v(x, t) over t", PALETTE[0]),
            ("min v(x, t) over t", PALETTE[1]),
        ]
        .into_iter()
        .enumerate()
        {
            let v = if k == 0 { &env.v_max } else { &env.v_min };
            let pts: Vec<(f64, f64)> = env.x.iter().zip(v).map(|(&x, &v)| (x, v * MM)).collect();
            chart.draw_series(LineSeries::new(pts, col.stroke_width(2)))?;
            key.push((name.into(), Key::Line(col, 2, None)));
        }
        if !out.history.supports.is_empty() {
            chart.draw_series(out.history.supports.iter().map(|s| {
                style::marker(style::Marker::TriangleUp, (s.x, s.v_max * MM), 5, BLACK)
            }))?;
            key.push((
                "uplift at the supports".into(),
                Key::Mark(BLACK, style::Marker::TriangleUp),
            ));
        }
        style::draw_legend(&lower_key, &key, 24)?;
        root.present()?;
        Ok(())
    };
    draw().map_err(fail)
}
