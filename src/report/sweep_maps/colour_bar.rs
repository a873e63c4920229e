//! The colour bar beside a heat map: the ramp's steps over the value scale,
//! with notes on white zeros, a log scale and a clipped top.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::axes::{round_sig, tick};
use super::colour::{COLOUR_STEPS, Paint, Ramp};

/// The result of a plotters drawing (its errors boxed).
pub(super) type DynResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;
pub(super) fn colour_bar(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    paint: &Paint,
) -> DynResult<()> {
    let Paint::Scale {
        ramp,
        lo,
        hi,
        zero_white,
        log,
        bar_label,
        clipped_max,
    } = paint
    else {
        return Ok(());
    };
    let (lo, hi) = (*lo, *hi);
    let hi = if hi > lo { hi } else { lo + 1.0 };
    let builder = |area| {
        let mut b = ChartBuilder::on(area);
        // a narrow bar, its ticks and label right beside it
        b.margin_top(8)
            .margin_bottom(52 + 4)
            .margin_right(22)
            .y_label_area_size(60);
        b
    };
    if *log {
        let mut chart = builder(area).build_cartesian_2d(0.0..1.0, (lo..hi).log_scale())?;
        bar_body(&mut chart, *ramp, lo, hi, true, bar_label)?;
    } else {
        let mut chart = builder(area).build_cartesian_2d(0.0..1.0, lo..hi)?;
        bar_body(&mut chart, *ramp, lo, hi, false, bar_label)?;
    }
    let mut notes = Vec::new();
    if *zero_white {
        notes.push("white: exactly 0".to_string());
    }
    if *log {
        notes.push("(log scale)".to_string());
    }
    if let Some(m) = clipped_max {
        notes.push(format!("top colour: ≥ {}", tick(round_sig(hi, 3))));
        notes.push(format!("(max {})", tick(round_sig(*m, 3))));
    }
    let below = area.strip_coord_spec();
    let (_, h) = below.dim_in_pixel();
    for (k, t) in notes.iter().enumerate() {
        below.draw(&Text::new(
            t.clone(),
            (8, h as i32 - 52 + 4 + 16 * k as i32),
            ("sans-serif", 13).into_font(),
        ))?;
    }
    Ok(())
}

pub(super) fn bar_body<Y>(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, Y>>,
    ramp: Ramp,
    lo: f64,
    hi: f64,
    log: bool,
    bar_label: &str,
) -> DynResult<()>
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let fmt = |v: &f64| tick(*v);
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(8)
        .y_label_formatter(&fmt)
        .y_desc(bar_label)
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 15))
        .draw()?;
    let n = COLOUR_STEPS;
    let at = |f: f64| {
        if log {
            (lo.ln() + f * (hi.ln() - lo.ln())).exp()
        } else {
            lo + f * (hi - lo)
        }
    };
    chart.draw_series((0..n).map(|k| {
        let (a, b) = (at(k as f64 / n as f64), at((k + 1) as f64 / n as f64));
        let f = (k as f64 + 0.5) / n as f64;
        Rectangle::new([(0.0, a), (1.0, b)], ramp.at(f).filled())
    }))?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    chart
        .plotting_area()
        .strip_coord_spec()
        .draw(&Rectangle::new(
            [(0, 0), (px.end - px.start - 1, py.end - py.start - 1)],
            BLACK.stroke_width(1),
        ))?;
    Ok(())
}
