//! `force.svg`: contact force along the span (or in time for stationary
//! carriers), contact loss shaded.

use std::path::Path;

use plotters::prelude::*;

use crate::error::{Error, Result};
use crate::run::RunOutput;
use crate::scene::Resolved;

/// Line colours for carriers 0, 1, 2, … (cycled).
const PALETTE: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];

/// The force axis is clipped at this multiple of the 99.5th percentile.
const CLIP_FACTOR: f64 = 2.0;

/// Plot the contact force of every carrier against x_m/L, or against t when
/// every carrier is stationary; shade each carrier's loss intervals.
pub fn write_force_plot(path: &Path, sc: &Resolved, out: &RunOutput) -> Result<()> {
    draw(path, sc, out).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

fn draw(
    path: &Path,
    sc: &Resolved,
    out: &RunOutput,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let h = &out.history;
    let l = sc.beam.length;
    let in_time = sc.carriers.iter().all(|c| c.motion.is_stationary());
    let xs = |c: usize| -> Vec<f64> {
        if in_time {
            h.t.clone()
        } else {
            h.carriers[c].x.iter().map(|x| x / l).collect()
        }
    };
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for c in 0..h.carriers.len() {
        for (&x, &f) in xs(c).iter().zip(&h.carriers[c].force).skip(1) {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(f);
            y1 = y1.max(f);
        }
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    // Re-contact spikes (no impact law, TARGETS "What the study does not
    // settle") can be ten times the force level and flatten the curve: clip
    // the axis at CLIP_FACTOR × the 99.5th percentile and say so.
    let mut all: Vec<f64> = h
        .carriers
        .iter()
        .flat_map(|c| c.force[1..].iter().copied())
        .collect();
    all.sort_by(f64::total_cmp);
    let p995 = all
        .get((0.995 * (all.len() as f64 - 1.0)) as usize)
        .copied()
        .unwrap_or(y1);
    let clipped = p995 > 0.0 && y1 > CLIP_FACTOR * p995;
    let true_max = y1;
    if clipped {
        y1 = CLIP_FACTOR * p995;
    }
    let pad = 0.05 * (y1 - y0).max(1e-9 * y1.abs().max(1.0));
    let (y0, y1) = (y0 - pad, y1 + pad);

    let root = SVGBackend::new(path, (960, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut title = format!(
        "contact force: {} elements, dt = {} s, P_l = {:.4}",
        sc.elements, sc.dt, out.stats[0].loss_fraction
    );
    if clipped {
        title.push_str(&format!(" (axis clipped; peak {true_max:.0} N)"));
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(if in_time { "t (s)" } else { "x_m / L" })
        .y_desc("contact force λ (N)")
        .draw()?;

    for (c, stats) in out.stats.iter().enumerate() {
        let col = PALETTE[c % PALETTE.len()];
        let shade = col.mix(0.15);
        let ivs = if in_time {
            &stats.loss_intervals_time
        } else {
            &stats.loss_intervals
        };
        chart.draw_series(
            ivs.iter()
                .map(|iv| Rectangle::new([(iv[0], y0), (iv[1], y1)], shade.filled())),
        )?;
    }
    for c in 0..h.carriers.len() {
        let col = PALETTE[c % PALETTE.len()];
        let pts: Vec<(f64, f64)> = xs(c)
            .into_iter()
            .zip(h.carriers[c].force.iter().map(|&f| f.min(y1)))
            .skip(1)
            .collect();
        let label = if h.carriers.len() == 1 {
            "λ".to_string()
        } else {
            format!("carrier {c}")
        };
        chart
            .draw_series(LineSeries::new(pts, col.stroke_width(1)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], col));
    }
    if out.stats.iter().any(|s| !s.loss_intervals.is_empty()) {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x0, y0), (x0, y0)],
                PALETTE[0].mix(0.15).filled(),
            )))?
            .label("contact lost (shaded)")
            .legend(|(x, y)| {
                Rectangle::new([(x, y - 5), (x + 18, y + 5)], PALETTE[0].mix(0.15).filled())
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
