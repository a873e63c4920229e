//! What every plot of taut shares so that it reads as a journal figure:
//! a colour-blind-safe palette with a marker per series (colour is never
//! the only cue), tick values from a nice-number rule (decades on log
//! axes, an offset where the range is tiny against the values), a robust
//! y range (outliers marked at the edge, not setting the scale) and a
//! legend beside the data, never over it.

use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};

/// Series colours: Okabe–Ito's eight (Okabe & Ito 2008, "Color Universal
/// Design"), then Paul Tol's "muted" nine without its pale grey (Tol 2021,
/// "Colour schemes"): seventeen colours told apart under the common colour
/// vision deficiencies, Okabe–Ito first because they differ most.
pub(crate) const PALETTE: [RGBColor; 16] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(230, 159, 0),   // orange
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(51, 34, 136),   // Tol indigo
    RGBColor(17, 119, 51),   // Tol green
    RGBColor(136, 34, 85),   // Tol wine
    RGBColor(68, 170, 153),  // Tol teal
    RGBColor(153, 153, 51),  // Tol olive
    RGBColor(204, 102, 119), // Tol rose
    RGBColor(170, 68, 153),  // Tol purple
    RGBColor(136, 204, 238), // Tol cyan
    RGBColor(221, 204, 119), // Tol sand
];

/// Marker shapes, cycled with the colours; six shapes against sixteen
/// colours repeat a (colour, marker) pair only after 48 series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Marker {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Cross,
}

/// The marker cycle (see [`Marker`]).
pub(crate) const MARKERS: [Marker; 6] = [
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Cross,
];

/// Colour and marker of series `i`.
pub(crate) fn series_style(i: usize) -> (RGBColor, Marker) {
    (PALETTE[i % PALETTE.len()], MARKERS[i % MARKERS.len()])
}

/// Dash patterns (dash, gap in px) of reference lines (slope guides), one
/// per line so that they differ without colour.
pub(crate) const DASHES: [(u32, u32); 4] = [(2, 3), (8, 4), (14, 4), (4, 8)];

/// A marker of `shape` at `at` (data coordinates), `r` px in radius: an
/// element of its own (plotters' composed elements cannot be returned by
/// shape without boxing, and boxing them ties them to the backend's
/// lifetime).
pub(crate) struct MarkerElement<C> {
    at: C,
    shape: Marker,
    r: i32,
    colour: RGBColor,
}

/// [`MarkerElement`] of `shape` at `at`.
pub(crate) fn marker<C>(shape: Marker, at: C, r: i32, colour: RGBColor) -> MarkerElement<C> {
    MarkerElement {
        at,
        shape,
        r,
        colour,
    }
}

impl<'a, C> PointCollection<'a, C> for &'a MarkerElement<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for MarkerElement<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut pos: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = pos.next() else {
            return Ok(());
        };
        let r = self.r;
        let fill = self.colour.filled();
        let poly = |pts: &[(i32, i32)]| {
            pts.iter()
                .map(|&(dx, dy)| (x + dx, y + dy))
                .collect::<Vec<_>>()
        };
        match self.shape {
            Marker::Circle => backend.draw_circle((x, y), r as u32, &fill, true),
            Marker::Square => {
                backend.fill_polygon(poly(&[(-r, -r), (r, -r), (r, r), (-r, r)]), &fill)
            }
            Marker::TriangleUp => {
                backend.fill_polygon(poly(&[(0, -r - 1), (r + 1, r), (-r - 1, r)]), &fill)
            }
            Marker::TriangleDown => {
                backend.fill_polygon(poly(&[(0, r + 1), (r + 1, -r), (-r - 1, -r)]), &fill)
            }
            Marker::Diamond => backend.fill_polygon(
                poly(&[(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)]),
                &fill,
            ),
            Marker::Cross => {
                let pen = self.colour.stroke_width(2);
                backend.draw_line((x - r, y - r), (x + r, y + r), &pen)?;
                backend.draw_line((x - r, y + r), (x + r, y - r), &pen)
            }
        }
    }
}

/// The nice step (1, 2 or 5 × 10^k) nearest above `range / target`
/// (Heckbert, "Nice numbers for graph labels", Graphics Gems 1990).
pub(crate) fn nice_step(range: f64, target: usize) -> f64 {
    let raw = (range / target.max(1) as f64).abs();
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let e = raw.log10().floor() as i32;
    let f = raw / exact(1, e);
    // a small tolerance: 1e-4 / 1e-5 may come out as 9.999…
    match f {
        f if f <= 1.0 + 1e-9 => exact(1, e),
        f if f <= 2.0 + 1e-9 => exact(2, e),
        f if f <= 5.0 + 1e-9 => exact(5, e),
        _ => exact(1, e + 1),
    }
}

/// k × 10^e as the nearest double (as the literal `{k}e{e}` reads), not
/// the product of two rounded numbers (0.1 × 3 is not 0.3).
pub(crate) fn exact(k: i64, e: i32) -> f64 {
    format!("{k}e{e}").parse().unwrap_or(f64::NAN)
}

/// Tick values of a linear axis over `[lo, hi]`: multiples of a nice step,
/// about `target` of them, and the step.
pub(crate) fn nice_ticks(lo: f64, hi: f64, target: usize) -> (Vec<f64>, f64) {
    let step = nice_step(hi - lo, target);
    // a tick on an end survives the end's round-off (1.0000000000000009e-6)
    const SLACK: f64 = 1e-9;
    let first = (lo / step - SLACK).ceil() as i64;
    let last = (hi / step + SLACK).floor() as i64;
    let ticks = (first..=last.max(first - 1))
        .take(64)
        .map(|k| {
            let v = k as f64 * step;
            // 0.30000000000000004 → 0.3: round to the step's decimals
            round_to(v, decimals(step))
        })
        .collect();
    (ticks, step)
}

/// Digits after the point that a tick step needs (0 for steps ≥ 1).
pub(crate) fn decimals(step: f64) -> usize {
    if !(step.is_finite() && step > 0.0) {
        return 0;
    }
    (-step.log10().floor()).max(0.0) as usize
}

fn round_to(v: f64, d: usize) -> f64 {
    let s = 10f64.powi(d.min(300) as i32);
    (v * s).round() / s
}

/// A tick label at the precision of `step`: fixed point for values within
/// 1e-3 … 1e5, else a mantissa with as many digits as the step needs.
pub(crate) fn tick_label(v: f64, step: f64) -> String {
    if v == 0.0 || v.abs() < 1e-9 * step.abs() {
        return "0".into();
    }
    let a = v.abs().max(step.abs());
    if (1e-3..1e5).contains(&a) {
        format!("{v:.*}", decimals(step))
    } else {
        let digits = ((v.abs().log10().floor() - step.log10().floor()).max(0.0)) as usize;
        format!("{v:.*e}", digits.min(12))
    }
}

/// Relative width of a range below which its tick labels would repeat the
/// leading digits (2.9312e-2, 2.9311e-2): such an axis is drawn as an
/// offset plus small labels.
pub(crate) const OFFSET_BELOW: f64 = 1e-3;

/// The offset of an axis over `[lo, hi]`: None when the range is wide
/// against its values (labels as they are); else a round value near the
/// middle, to be subtracted from the data and named in the axis label.
pub(crate) fn axis_offset(lo: f64, hi: f64) -> Option<f64> {
    let mag = lo.abs().max(hi.abs());
    let width = hi - lo;
    if !(mag > 0.0 && width.is_finite()) || width >= OFFSET_BELOW * mag {
        return None;
    }
    // the middle rounded to the range's leading digit
    let e = width.max(mag * 1e-15).log10().ceil() as i32;
    let mid = 0.5 * (lo + hi);
    Some(exact((mid / exact(1, e)).round() as i64, e))
}

/// The offset as an axis label shows it: "+2.931e-2", "−4.2e3".
pub(crate) fn offset_label(offset: f64) -> String {
    let s = format!("{offset:e}");
    if offset < 0.0 {
        format!("−{}", &s[1..])
    } else {
        format!("+{s}")
    }
}

/// Decade ticks of a log axis over `[lo, hi]` (lo > 0): the powers of ten
/// inside (labelled) and 2 … 9 × each decade (minor, unlabelled). A range
/// within one decade gets its ends' nice values as labelled ticks too, so
/// an axis never carries a single label.
pub(crate) fn decade_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return (Vec::new(), Vec::new());
    }
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut major = Vec::new();
    let mut minor = Vec::new();
    for e in a..=b {
        let d = exact(1, e);
        if d >= lo * (1.0 - 1e-12) && d <= hi * (1.0 + 1e-12) {
            major.push(d);
        }
        for m in 2..=9i64 {
            let v = exact(m, e);
            if v >= lo && v <= hi {
                minor.push(v);
            }
        }
    }
    if major.len() < 3 {
        // fewer than three decades inside: label the 2 and 5 multiples too,
        // and if still fewer than three, every multiple
        major.extend(minor.iter().copied().filter(|&v| {
            let m = v / 10f64.powf(v.log10().floor());
            (m - 2.0).abs() < 1e-9 || (m - 5.0).abs() < 1e-9
        }));
        if major.len() < 3 {
            major.extend(minor.iter().copied());
        }
        major.sort_by(f64::total_cmp);
        major.dedup();
        minor.retain(|v| !major.contains(v));
    } else if major.len() > MAX_DECADE_LABELS {
        // many decades: every k-th labelled, the others minor
        let k = major.len().div_ceil(MAX_DECADE_LABELS);
        let (keep, drop): (Vec<_>, Vec<_>) =
            major.iter().enumerate().partition(|(i, _)| i % k == 0);
        minor.extend(drop.into_iter().map(|(_, &v)| v));
        major = keep.into_iter().map(|(_, &v)| v).collect();
    }
    (major, minor)
}

/// Most labelled decades on a log axis (more crowd 600 px).
const MAX_DECADE_LABELS: usize = 9;

/// A log tick label: 1e-5, 2e-5.
pub(crate) fn log_label(v: f64) -> String {
    format!("{v:.0e}")
}

/// Both axes of a log–log plot: decades labelled, the 2–9 between them as
/// light grid lines ([`decade_ticks`]).
pub(crate) type LogLog = plotters::coord::cartesian::Cartesian2d<
    plotters::coord::combinators::WithKeyPoints<plotters::coord::combinators::LogCoord<f64>>,
    plotters::coord::combinators::WithKeyPoints<plotters::coord::combinators::LogCoord<f64>>,
>;

/// A log–log chart on `area` over `x` and `y` with decade ticks, its grid
/// and axes drawn and described by `x_desc`, `y_desc`: the one builder the
/// work–precision and convergence plots share.
pub(crate) fn log_log_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (x_desc, y_desc): (&str, &str),
) -> std::result::Result<ChartContext<'a, DB, LogLog>, DrawingAreaErrorKind<DB::ErrorType>> {
    let (xm, xn) = decade_ticks(x0, x1);
    let (ym, yn) = decade_ticks(y0, y1);
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (x0..x1)
                .log_scale()
                .with_key_points(xm)
                .with_light_points(xn),
            (y0..y1)
                .log_scale()
                .with_key_points(ym)
                .with_light_points(yn),
        )?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(("sans-serif", 14))
        .label_style(("sans-serif", 12))
        .bold_line_style(BLACK.mix(0.18))
        .light_line_style(BLACK.mix(0.06))
        .x_label_formatter(&|x| log_label(*x))
        .y_label_formatter(&|y| log_label(*y))
        .draw()?;
    Ok(chart)
}

/// Share of the data left out at each end when a robust range is chosen.
pub(crate) const ROBUST_TAIL: f64 = 0.01;

/// Margin added on each side of a robust range, as a share of its width.
pub(crate) const ROBUST_MARGIN: f64 = 0.08;

/// The robust range of `values` (finite ones): the [`ROBUST_TAIL`] and
/// 1 − [`ROBUST_TAIL`] quantiles widened to hold `keep` (values that must
/// show whole, e.g. a filtered line), plus [`ROBUST_MARGIN`] each side.
/// None for no finite value.
pub(crate) fn robust_range(values: &mut [f64], keep: (f64, f64)) -> Option<(f64, f64)> {
    let mut n = 0;
    for i in 0..values.len() {
        if values[i].is_finite() {
            values.swap(n, i);
            n += 1;
        }
    }
    let v = &mut values[..n];
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((q * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)];
    let (mut lo, mut hi) = (at(ROBUST_TAIL), at(1.0 - ROBUST_TAIL));
    if keep.0.is_finite() {
        lo = lo.min(keep.0);
    }
    if keep.1.is_finite() {
        hi = hi.max(keep.1);
    }
    let pad = ROBUST_MARGIN * (hi - lo).max(1e-9 * lo.abs().max(hi.abs()).max(1.0));
    Some((lo - pad, hi + pad))
}

/// Width in px of the legend column beside a plot.
pub(crate) const LEGEND_WIDTH: u32 = 250;

/// The plot and legend rectangles (x0, y0, x1, y1 in px) of a figure of
/// `size`: the legend is a column at the right, outside the plot.
pub(crate) fn legend_layout(size: (u32, u32)) -> ([u32; 4], [u32; 4]) {
    let split = size.0.saturating_sub(LEGEND_WIDTH);
    ([0, 0, split, size.1], [split, 0, size.0, size.1])
}

/// How a legend entry is drawn.
#[derive(Clone, Copy)]
pub(crate) enum Key {
    /// A line with a marker on it.
    Line(RGBColor, u32, Option<Marker>),
    /// A dashed line (dash, gap px).
    Dashed(RGBColor, (u32, u32)),
    /// A filled box (shading).
    Shade(RGBAColor),
    /// A marker alone.
    Mark(RGBColor, Marker),
    /// A short vertical bar of this width (supports, droppers).
    Bar(RGBColor, u32),
}

/// Draw a legend of `entries` in `area` (beside the plot), top down.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(String, Key)],
    top: i32,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let font = ("sans-serif", 12).into_font();
    let (w, _) = area.dim_in_pixel();
    let max_chars = ((w as i32 - 40) / 6).max(8) as usize;
    let mut y = top;
    for (label, key) in entries {
        match *key {
            Key::Line(c, width, m) => {
                area.draw(&PathElement::new(
                    vec![(8, y), (32, y)],
                    c.stroke_width(width),
                ))?;
                if let Some(m) = m {
                    area.draw(&marker(m, (20, y), 4, c))?;
                }
            }
            Key::Dashed(c, (dash, gap)) => {
                let mut x = 8;
                while x < 32 {
                    let e = (x + dash as i32).min(32);
                    area.draw(&PathElement::new(vec![(x, y), (e, y)], c.stroke_width(1)))?;
                    x = e + gap as i32;
                }
            }
            Key::Shade(c) => {
                area.draw(&Rectangle::new([(8, y - 5), (32, y + 5)], c.filled()))?;
            }
            Key::Mark(c, m) => area.draw(&marker(m, (20, y), 4, c))?,
            Key::Bar(c, width) => area.draw(&PathElement::new(
                vec![(20, y - 7), (20, y + 7)],
                c.stroke_width(width),
            ))?,
        }
        // long labels wrap onto a second line rather than run off the page
        let (first, rest) = split_label(label, max_chars);
        area.draw(&Text::new(first, (40, y - 6), font.clone()))?;
        y += 18;
        if let Some(rest) = rest {
            area.draw(&Text::new(rest, (48, y - 6), font.clone()))?;
            y += 18;
        }
    }
    Ok(())
}

fn split_label(s: &str, max: usize) -> (String, Option<String>) {
    if s.chars().count() <= max {
        return (s.to_string(), None);
    }
    let cut: usize = s
        .char_indices()
        .take_while(|&(i, _)| s[..i].chars().count() <= max)
        .filter(|&(_, c)| c == ' ')
        .map(|(i, _)| i)
        .last()
        .unwrap_or_else(|| s.char_indices().nth(max).map_or(s.len(), |(i, _)| i));
    (
        s[..cut].to_string(),
        Some(s[cut..].trim_start().to_string()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_sixteen_series_differ_in_colour_and_every_48_in_colour_and_marker() {
        for i in 0..16 {
            for j in 0..i {
                assert_ne!(series_style(i).0, series_style(j).0, "{i} {j}");
            }
        }
        for i in 0..48 {
            for j in 0..i {
                assert_ne!(series_style(i), series_style(j), "{i} {j}");
            }
        }
        // the 12 series of a converge plot: distinct in colour and in marker pairs
        assert!(PALETTE.iter().all(|c| (c.0, c.1, c.2) != (255, 255, 255)));
    }

    #[test]
    fn nice_numbers_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(nice_step(10.0, 5), 2.0);
        assert_eq!(nice_step(1.0, 4), 0.5);
        assert_eq!(nice_step(0.0003, 3), 1e-4);
        assert_eq!(nice_step(700.0, 5), 200.0);
        let (t, s) = nice_ticks(0.1, 1.05, 5);
        assert_eq!(s, 0.2);
        assert_eq!(t, vec![0.2, 0.4, 0.6, 0.8, 1.0]);
        let (t, s) = nice_ticks(-3.0, 997.0, 5);
        assert_eq!(s, 200.0);
        assert_eq!(t, vec![0.0, 200.0, 400.0, 600.0, 800.0]);
        assert_eq!(tick_label(0.4, 0.2), "0.4");
        assert_eq!(tick_label(400.0, 200.0), "400");
        assert_eq!(tick_label(3e-5, 1e-5), "3e-5");
        assert_eq!(tick_label(2.5e-5, 5e-6), "2.5e-5");
    }

    #[test]
    fn a_tiny_range_is_shown_as_an_offset_and_small_labels() {
        // 2.9311e-2 … 2.9312e-2: the leading digits go into the offset
        let (lo, hi) = (2.93110e-2, 2.93122e-2);
        let off = axis_offset(lo, hi).expect("an offset");
        assert_eq!(off, 2.931e-2);
        assert!(lo - off > 0.0 && hi - off < 1e-5);
        let (ticks, step) = nice_ticks(lo - off, hi - off, 4);
        assert!(ticks.len() >= 3, "{ticks:?}");
        let labels: Vec<String> = ticks.iter().map(|&t| tick_label(t, step)).collect();
        assert!(labels.iter().all(|l| l.len() <= 7), "{labels:?}");
        let mut sorted = labels.clone();
        sorted.dedup();
        assert_eq!(sorted, labels);
        assert!(offset_label(off).starts_with('+'), "{}", offset_label(off));
        // a wide range needs none
        assert_eq!(axis_offset(0.0, 350.0), None);
        assert_eq!(axis_offset(40.0, 60.0), None);
    }

    #[test]
    fn log_axes_carry_decades_with_minor_ticks_never_a_single_label() {
        let (major, minor) = decade_ticks(3e-7, 2e-3);
        assert_eq!(major, vec![1e-6, 1e-5, 1e-4, 1e-3]);
        // two decades: the 2 and 5 multiples labelled too
        let (major, _) = decade_ticks(0.15, 8.0);
        assert_eq!(major, vec![0.2, 0.5, 1.0, 2.0, 5.0]);
        assert!(minor.contains(&2e-5) && minor.contains(&9e-4));
        assert_eq!(offset_label(2.931e-2), "+2.931e-2");
        assert_eq!(offset_label(-4.2e3), "−4.2e3");
        assert_eq!(log_label(1e-5), "1e-5");
        // within one decade: more than one label
        let (major, _) = decade_ticks(1.5e-3, 8e-3);
        assert!(major.len() >= 2, "{major:?}");
        let (major, _) = decade_ticks(0.7e-3, 3e-3);
        assert!(major.len() >= 2, "{major:?}");
    }

    #[test]
    fn the_robust_range_leaves_outliers_out_and_keeps_what_must_show() {
        let mut v: Vec<f64> = (0..1000).map(|i| 50.0 + (i % 10) as f64).collect();
        v[3] = 1000.0;
        v[7] = f64::NAN;
        let (lo, hi) = robust_range(&mut v, (f64::NAN, f64::NAN)).unwrap();
        assert!(
            lo < 50.0 && lo > 45.0 && hi > 59.0 && hi < 65.0,
            "{lo} {hi}"
        );
        let (lo, _) = robust_range(&mut v, (0.0, 0.0)).unwrap();
        assert!(lo < 0.0);
    }

    #[test]
    fn the_legend_lies_outside_the_plot_rectangle() {
        for size in [(960, 480), (1200, 900), (900, 600)] {
            let (plot, legend) = legend_layout(size);
            assert!(plot[2] <= legend[0], "{plot:?} {legend:?}");
            assert_eq!(legend[2], size.0);
            assert!(plot[2] - plot[0] >= size.0 / 2);
        }
    }
}
