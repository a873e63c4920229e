//! SVG maps of a sweep (`taut sweep` / `taut merge`; the study's Figs 8–12).
//!
//! * 1-D sweep: `force_map.svg`, the mean contact force over
//!   (x_m/L, parameter) as a heat map with a colour bar (the upper panels of
//!   the study's Figs 8–11), and `loss_map.svg`, contact loss in black and
//!   white over the same axes (black where some step in the x_m/L bin had
//!   the contact open; the lower panels).
//! * 2-D sweep: `loss_fraction_map.svg`, P_l over the grid as a heat map
//!   (white where P_l = 0) with iso-lines of V0/c drawn by marching squares
//!   from each run's `speed_ratio` (the study's Fig. 12 and its band borders
//!   at V0/c ≈ 0.64 and 0.96, TARGETS T7).
//!
//! Each cell is drawn over its own extent: bin edges in x_m/L, midpoints
//! between grid values (geometric ones on a `--log` axis) in a parameter.
//! A cell with no value (a run that stopped with an error, a bin no step fell
//! in) is light grey. A shard holds only part of the grid, so it draws no
//! maps; `taut merge` draws them for the whole.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::{Error, Result};
use crate::study::sweep::{Axis, PROFILE_BINS, SweepRecord, SweepSpec};

/// The V0/c iso-lines of a 2-D map: the band borders of TARGETS T7 (0.64,
/// 0.96, drawn bold) and a few others for orientation.
pub const SPEED_RATIO_LEVELS: [f64; 7] = [0.4, 0.5, 0.64, 0.8, 0.96, 1.1, 1.3];

/// Levels drawn bold (the study's band borders).
const BOLD_LEVELS: [f64; 2] = [0.64, 0.96];

/// The force colour scale ends at this quantile of the cell values, so the
/// re-contact spikes near the supports (no impact law: TARGETS; bin means
/// of 10⁴ N and more where the level is 50 N) do not wash out the map; larger
/// cells take the top colour and the bar says so.
const FORCE_CLIP_QUANTILE: f64 = 0.98;

/// A P_l map's colour scale is logarithmic when its largest positive value
/// is more than this multiple of its smallest.
const LOG_SPAN: f64 = 100.0;

/// Number of distinct colours of a colour scale (and steps of its bar).
const COLOUR_STEPS: usize = 64;

/// Pixel size of every map.
const SIZE: (u32, u32) = (960, 620);
/// Width of the colour-bar panel, px.
const BAR_PANEL: u32 = 170;

const NO_DATA: RGBColor = RGBColor(205, 205, 205);

type DynResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The label of a swept key: the key, its symbol and unit.
pub fn axis_label(key: &str) -> String {
    let last = key.rsplit('.').next().unwrap_or(key);
    let sym = match (key, last) {
        ("speed_ratio", _) => "V0/c",
        ("tension_ratio", _) => "T/EA",
        ("mass_ratio", _) => "m/M, M = ρAL",
        ("stiffness_ratio", _) => "k/(T/L)",
        (_, "tension") => "T (N)",
        (_, "cruise") | (_, "value") => "V0 (m/s)",
        (_, "mass") => "m (kg)",
        (_, "stiffness") => "k (N/m)",
        (_, "preload") => "δ0 (m)",
        (_, "damping") => "c_s (N·s/m)",
        (_, "start") => "x0 (m)",
        (_, "force") => "F (N)",
        (_, "length") => "L (m)",
        (_, "density") => "ρ (kg/m³)",
        (_, "area") => "A (m²)",
        (_, "youngs_modulus") => "E (Pa)",
        (_, "second_moment") => "I (m⁴)",
        (_, "mass_per_length") => "ρA (kg/m)",
        (_, "bending_stiffness") => "EI (N·m²)",
        (_, "elements") => "N (elements)",
        (_, "step") => "Δt (s)",
        (_, "rho_inf") => "ρ∞",
        (_, "g") => "g (m/s²)",
        _ => "",
    };
    if sym.is_empty() {
        key.to_string()
    } else {
        format!("{sym}   [{key}]")
    }
}

/// A tick label: the value rounded to 9 significant digits, shortest form
/// (so 0.30000000000000004 reads 0.3).
pub fn tick(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let r: f64 = format!("{v:.8e}").parse().unwrap_or(v);
    let a = r.abs();
    if r == 0.0 {
        "0".into()
    } else if (1e-4..1e6).contains(&a) {
        format!("{r}")
    } else {
        let s = format!("{r:e}");
        s.replace("e-", "e−")
    }
}

/// Cell edges around grid values `v` (midpoints; geometric when `log`).
fn edges(v: &[f64], log: bool) -> Vec<f64> {
    let t = |x: f64| if log { x.ln() } else { x };
    let u = |x: f64| if log { x.exp() } else { x };
    let n = v.len();
    if n == 1 {
        return if log {
            vec![v[0] / 1.1, v[0] * 1.1]
        } else {
            let h = if v[0] == 0.0 { 0.5 } else { 0.05 * v[0].abs() };
            vec![v[0] - h, v[0] + h]
        };
    }
    let mut e = Vec::with_capacity(n + 1);
    e.push(u(t(v[0]) - 0.5 * (t(v[1]) - t(v[0]))));
    for i in 0..n - 1 {
        e.push(u(0.5 * (t(v[i]) + t(v[i + 1]))));
    }
    e.push(u(t(v[n - 1]) + 0.5 * (t(v[n - 1]) - t(v[n - 2]))));
    e
}

fn axis_values(a: &Axis) -> Vec<f64> {
    (0..a.count).map(|i| a.value(i)).collect()
}

/// Colour maps: piecewise-linear through control points.
#[derive(Clone, Copy)]
enum Ramp {
    /// matplotlib's viridis (perceptually uniform).
    Viridis,
    /// White at zero, then light yellow → orange → red → dark red.
    Heat,
}

impl Ramp {
    fn stops(self) -> &'static [(u8, u8, u8)] {
        match self {
            Ramp::Viridis => &[
                (68, 1, 84),
                (72, 40, 120),
                (62, 74, 137),
                (49, 104, 142),
                (38, 130, 142),
                (31, 158, 137),
                (53, 183, 121),
                (109, 205, 89),
                (180, 222, 44),
                (253, 231, 37),
            ],
            Ramp::Heat => &[
                (255, 237, 160),
                (254, 217, 118),
                (254, 178, 76),
                (253, 141, 60),
                (240, 59, 32),
                (189, 0, 38),
                (110, 0, 30),
            ],
        }
    }

    /// Colour of `f` in [0, 1], in one of COLOUR_STEPS steps (equal
    /// neighbours merge into one rectangle: files a third the size).
    fn at(self, f: f64) -> RGBColor {
        let s = self.stops();
        let n = COLOUR_STEPS as f64;
        let f = (((f.clamp(0.0, 1.0) * n).floor()).min(n - 1.0) + 0.5) / n;
        let x = f * (s.len() - 1) as f64;
        let i = (x.floor() as usize).min(s.len() - 2);
        let w = x - i as f64;
        let mix = |a: u8, b: u8| (a as f64 + w * (b as f64 - a as f64)).round() as u8;
        RGBColor(
            mix(s[i].0, s[i + 1].0),
            mix(s[i].1, s[i + 1].1),
            mix(s[i].2, s[i + 1].2),
        )
    }
}

/// How cell values become colours.
#[derive(Clone)]
enum Paint {
    /// A colour ramp over [lo, hi] with a colour bar; `zero_white` paints
    /// exact zeros white (and shows a white swatch on the bar).
    Scale {
        ramp: Ramp,
        lo: f64,
        hi: f64,
        zero_white: bool,
        /// Logarithmic scale (lo > 0; positive values below lo take the
        /// bottom colour).
        log: bool,
        bar_label: String,
        /// The largest value when it is above `hi` (the bar says so).
        clipped_max: Option<f64>,
    },
    /// Black where the value is > 0, white where it is 0.
    BlackWhite,
}

impl Paint {
    fn colour(&self, v: Option<f64>) -> RGBColor {
        let Some(v) = v.filter(|v| v.is_finite()) else {
            return NO_DATA;
        };
        match self {
            Paint::BlackWhite => {
                if v > 0.0 {
                    BLACK
                } else {
                    WHITE
                }
            }
            Paint::Scale {
                ramp,
                lo,
                hi,
                zero_white,
                log,
                ..
            } => {
                if *zero_white && v == 0.0 {
                    WHITE
                } else if *log {
                    let f = (v.max(*lo).ln() - lo.ln()) / (hi.ln() - lo.ln()).max(1e-300);
                    ramp.at(f)
                } else {
                    ramp.at((v - lo) / (hi - lo).max(1e-300))
                }
            }
        }
    }
}

/// A line over the map (an iso-line segment), in data coordinates.
struct Overlay {
    points: Vec<(f64, f64)>,
    bold: bool,
}

/// A text label over the map, in data coordinates.
struct Label {
    at: (f64, f64),
    text: String,
    anchor: Pos,
}

/// Everything one map needs.
struct Map {
    title: String,
    x_desc: String,
    y_desc: String,
    x_edges: Vec<f64>,
    y_edges: Vec<f64>,
    x_log: bool,
    y_log: bool,
    /// `cells[j][i]`: row j (y), column i (x).
    cells: Vec<Vec<Option<f64>>>,
    paint: Paint,
    overlays: Vec<Overlay>,
    labels: Vec<Label>,
    /// A line under the plot (legend, notes).
    footer: String,
}

fn span(e: &[f64]) -> (f64, f64) {
    let lo = e.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

fn draw_map(path: &Path, map: &Map) -> Result<()> {
    // every axis drawable first (axis_range), else a note in the map's place
    let (x0, x1) = span(&map.x_edges);
    let (y0, y1) = span(&map.y_edges);
    let mut checked = super::axis_range::drawable(&map.x_desc, x0, x1, map.x_log)
        .and_then(|_| super::axis_range::drawable(&map.y_desc, y0, y1, map.y_log))
        .map(|_| ());
    if let (
        Ok(()),
        Paint::Scale {
            lo,
            hi,
            log,
            bar_label,
            ..
        },
    ) = (&checked, &map.paint)
    {
        let hi = if hi > lo { *hi } else { lo + 1.0 };
        checked = super::axis_range::drawable(bar_label, *lo, hi, *log).map(|_| ());
    }
    if let Err(reason) = checked {
        return super::axis_range::write_note(
            path,
            SIZE,
            &map.title,
            &reason,
            "sweep.csv, sweep_force.csv and sweep_loss.csv",
        );
    }
    render(path, map).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })
}

fn render(path: &Path, map: &Map) -> DynResult<()> {
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let (top, foot) = root.split_vertically(SIZE.1 - 34);
    foot.draw(&Text::new(
        map.footer.clone(),
        (14, 8),
        ("sans-serif", 15).into_font().color(&BLACK.mix(0.85)),
    ))?;
    let titled = top.titled(&map.title, ("sans-serif", 19))?;
    let has_bar = matches!(map.paint, Paint::Scale { .. });
    let (plot_area, bar_area) = if has_bar {
        let (a, b) = titled.split_horizontally(SIZE.0 - BAR_PANEL);
        (a, Some(b))
    } else {
        (titled, None)
    };
    let (x0, x1) = span(&map.x_edges);
    let (y0, y1) = span(&map.y_edges);
    match (map.x_log, map.y_log) {
        (false, false) => plot(&plot_area, x0..x1, y0..y1, map)?,
        (false, true) => plot(&plot_area, x0..x1, (y0..y1).log_scale(), map)?,
        (true, false) => plot(&plot_area, (x0..x1).log_scale(), y0..y1, map)?,
        (true, true) => plot(&plot_area, (x0..x1).log_scale(), (y0..y1).log_scale(), map)?,
    }
    if let (Some(area), Paint::Scale { .. }) = (bar_area, &map.paint) {
        colour_bar(&area, &map.paint)?;
    }
    root.present()?;
    Ok(())
}

fn plot<X, Y>(area: &DrawingArea<SVGBackend<'_>, Shift>, xs: X, ys: Y, map: &Map) -> DynResult<()>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(area)
        .margin_top(8)
        .margin_left(10)
        .margin_right(28)
        .x_label_area_size(52)
        .y_label_area_size(86)
        .build_cartesian_2d(xs, ys)?;
    let fmt = |v: &f64| tick(*v);
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(map.x_desc.as_str())
        .y_desc(map.y_desc.as_str())
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&fmt)
        .y_label_formatter(&fmt)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 16))
        .draw()?;

    // Cells, merged along x where neighbours share a colour (smaller files).
    let mut rects = Vec::new();
    for (j, row) in map.cells.iter().enumerate() {
        let (ya, yb) = (map.y_edges[j], map.y_edges[j + 1]);
        let mut i = 0;
        while i < row.len() {
            let col = map.paint.colour(row[i]);
            let mut k = i + 1;
            while k < row.len() && map.paint.colour(row[k]) == col {
                k += 1;
            }
            rects.push(Rectangle::new(
                [(map.x_edges[i], ya), (map.x_edges[k], yb)],
                col.filled(),
            ));
            i = k;
        }
    }
    chart.draw_series(rects)?;

    // lines with a light halo, so they read on dark and light cells alike
    for o in &map.overlays {
        // even widths on whole-pixel centres stay crisp (no half-covered pixels)
        let w = if o.bold { 4 } else { 2 };
        chart.draw_series(std::iter::once(PathElement::new(
            o.points.clone(),
            WHITE.mix(0.7).stroke_width(w + 2),
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(
            o.points.clone(),
            BLACK.stroke_width(w),
        )))?;
    }
    // labels on a light box (text width estimated at 0.55 em per character)
    let plain = chart.plotting_area().strip_coord_spec();
    let base = chart.plotting_area().get_base_pixel();
    for l in &map.labels {
        let (ax, ay) = chart.backend_coord(&l.at);
        let (x, y) = (ax - base.0, ay - base.1);
        let (w, h) = ((l.text.chars().count() as f64 * 0.55 * 15.0) as i32, 15);
        let x0 = match l.anchor.h_pos {
            HPos::Left => x,
            HPos::Center => x - w / 2,
            HPos::Right => x - w,
        };
        let y0 = match l.anchor.v_pos {
            VPos::Top => y,
            VPos::Center => y - h / 2,
            VPos::Bottom => y - h,
        };
        plain.draw(&Rectangle::new(
            [(x0 - 3, y0 - 2), (x0 + w + 3, y0 + h + 2)],
            WHITE.mix(0.8).filled(),
        ))?;
        plain.draw(&Text::new(
            l.text.clone(),
            (x, y),
            ("sans-serif", 15).into_font().color(&BLACK).pos(l.anchor),
        ))?;
    }
    // frame over the cells
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

fn colour_bar(area: &DrawingArea<SVGBackend<'_>, Shift>, paint: &Paint) -> DynResult<()> {
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
        b.margin_top(8)
            .margin_bottom(52 + 4)
            .margin_right(4)
            .y_label_area_size(96);
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

fn bar_body<Y>(
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

fn round_sig(v: f64, digits: i32) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let p = 10f64.powi(digits - 1 - v.abs().log10().floor() as i32);
    (v * p).round() / p
}

fn failed_note(records: &[SweepRecord]) -> String {
    let failed = records.iter().filter(|r| r.error.is_some()).count();
    if failed == 0 {
        String::new()
    } else {
        format!("; {failed} run(s) stopped with an error (grey)")
    }
}

/// Rows of a 1-D sweep's profiles, one per record in axis order.
fn profile_rows(
    records: &[SweepRecord],
    pick: fn(&SweepRecord) -> &Vec<Option<f64>>,
) -> Vec<Vec<Option<f64>>> {
    records
        .iter()
        .map(|r| {
            let p = pick(r);
            (0..PROFILE_BINS)
                .map(|b| p.get(b).copied().flatten().filter(|v| v.is_finite()))
                .collect()
        })
        .collect()
}

fn one_d_axes(spec: &SweepSpec, records: &[SweepRecord]) -> Result<(Vec<f64>, Vec<f64>)> {
    if spec.axes.len() != 1 || records.len() != spec.len() {
        return Err(Error::invalid(
            "sweep maps",
            format!("{} axes, {} records", spec.axes.len(), records.len()),
            "a 1-D map needs a one-axis sweep with every point present",
        ));
    }
    let x: Vec<f64> = (0..=PROFILE_BINS)
        .map(|b| b as f64 / PROFILE_BINS as f64)
        .collect();
    let a = &spec.axes[0];
    Ok((x, edges(&axis_values(a), a.log)))
}

fn sorted_by_index(records: &[SweepRecord]) -> Vec<SweepRecord> {
    let mut r = records.to_vec();
    r.sort_by_key(|r| r.index);
    r
}

/// The mean contact force over (x_m/L, parameter) of a 1-D sweep, with a
/// colour bar (the study's Figs 8–11, upper panels). `title` replaces the
/// default title when given.
pub fn write_force_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
) -> Result<()> {
    let (x_edges, y_edges) = one_d_axes(spec, records)?;
    let records = sorted_by_index(records);
    let cells = profile_rows(&records, |r| &r.force_profile);
    let mut all: Vec<f64> = cells.iter().flatten().flatten().copied().collect();
    all.sort_by(f64::total_cmp);
    let (lo, max) = (
        all.first().copied().unwrap_or(0.0),
        all.last().copied().unwrap_or(1.0),
    );
    let q = all
        .get(((all.len().max(1) - 1) as f64 * FORCE_CLIP_QUANTILE).round() as usize)
        .copied()
        .unwrap_or(max);
    // clip only when the tail is a few spikes, not the bulk
    let hi = if max > 1.05 * q && q > lo { q } else { max };
    let key = &spec.axes[0].key;
    let map = Map {
        title: title.map_or_else(
            || format!("mean contact force over (x_m/L, {key})"),
            str::to_string,
        ),
        x_desc: "carrier position x_m / L".into(),
        y_desc: axis_label(key),
        x_edges,
        y_edges,
        x_log: false,
        y_log: spec.axes[0].log,
        cells,
        paint: Paint::Scale {
            ramp: Ramp::Viridis,
            lo,
            hi,
            zero_white: false,
            log: false,
            bar_label: "mean contact force λ in the bin (N)".into(),
            clipped_max: (hi < max).then_some(max),
        },
        overlays: vec![],
        labels: vec![],
        footer: format!(
            "{PROFILE_BINS} bins in x_m/L × {} values of {key}; each cell: mean λ over the steps with x_m in the bin{}",
            spec.axes[0].count,
            failed_note(&records)
        ),
    };
    draw_map(path, &map)
}

/// Contact loss over (x_m/L, parameter) of a 1-D sweep in black and white:
/// black where some step in the bin had the contact open (the study's
/// Figs 8–11, lower panels).
pub fn write_loss_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
) -> Result<()> {
    let (x_edges, y_edges) = one_d_axes(spec, records)?;
    let records = sorted_by_index(records);
    let cells = profile_rows(&records, |r| &r.loss_profile);
    let key = &spec.axes[0].key;
    let lost_runs = records.iter().filter(|r| r.loss_fraction > 0.0).count();
    let map = Map {
        title: title.map_or_else(
            || format!("contact loss over (x_m/L, {key})"),
            str::to_string,
        ),
        x_desc: "carrier position x_m / L".into(),
        y_desc: axis_label(key),
        x_edges,
        y_edges,
        x_log: false,
        y_log: spec.axes[0].log,
        cells,
        paint: Paint::BlackWhite,
        overlays: vec![],
        labels: vec![],
        footer: format!(
            "black: contact lost in the bin (some step with λ = 0, gap open); white: kept; {lost_runs} of {} runs lose contact{}",
            records.len(),
            failed_note(&records)
        ),
    };
    draw_map(path, &map)
}

/// One iso-line level by marching squares over node values `s[i][j]` at
/// plotted coordinates (`px[i]`, `py[j]`): segments in plotted coordinates.
fn marching_squares(px: &[f64], py: &[f64], s: &[Vec<f64>], level: f64) -> Vec<[(f64, f64); 2]> {
    let mut segs = Vec::new();
    if px.len() < 2 || py.len() < 2 {
        return segs;
    }
    let cross = |a: (f64, f64, f64), b: (f64, f64, f64)| {
        let t = (level - a.2) / (b.2 - a.2);
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    };
    for i in 0..px.len() - 1 {
        for j in 0..py.len() - 1 {
            // corners counter-clockwise: (i,j) (i+1,j) (i+1,j+1) (i,j+1)
            let c = [
                (px[i], py[j], s[i][j]),
                (px[i + 1], py[j], s[i + 1][j]),
                (px[i + 1], py[j + 1], s[i + 1][j + 1]),
                (px[i], py[j + 1], s[i][j + 1]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let above: Vec<bool> = c.iter().map(|p| p.2 >= level).collect();
            // crossings on the edges k: corner k → corner k+1
            let mut pts: Vec<(usize, (f64, f64))> = Vec::new();
            for k in 0..4 {
                let (a, b) = (c[k], c[(k + 1) % 4]);
                if above[k] != above[(k + 1) % 4] {
                    pts.push((k, cross(a, b)));
                }
            }
            match pts.len() {
                2 => segs.push([pts[0].1, pts[1].1]),
                4 => {
                    // saddle: decide by the centre value
                    let centre = c.iter().map(|p| p.2).sum::<f64>() / 4.0;
                    let centre_above = centre >= level;
                    if centre_above == above[0] {
                        // corners 0 and 2 join through the centre: cut off
                        // corner 1 (edges 0, 1) and corner 3 (edges 2, 3)
                        segs.push([pts[0].1, pts[1].1]);
                        segs.push([pts[2].1, pts[3].1]);
                    } else {
                        // corners 1 and 3 join: cut off corners 0 and 2
                        segs.push([pts[3].1, pts[0].1]);
                        segs.push([pts[1].1, pts[2].1]);
                    }
                }
                _ => {}
            }
        }
    }
    segs
}

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
            cells[j][i] = Some(r.loss_fraction).filter(|v| v.is_finite());
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
    let with_loss = records.iter().filter(|r| r.loss_fraction > 0.0).count();
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
            bar_label: "P_l = time with contact lost / run time".into(),
            clipped_max: None,
        },
        overlays,
        labels,
        footer: format!(
            "{nx} × {ny} runs, {with_loss} with loss; lines: V0/c of each run (marching squares), bold at 0.64 and 0.96 (the study's band borders){}",
            failed_note(records)
        ),
    };
    draw_map(path, &map)
}

/// `--check-refinement` on a 1-D sweep: the in-span P_l at the sweep's
/// resolution and refined (N × 2, Δt / 2) along the axis, the axis shaded
/// where the two differ by more than the convergence criterion.
pub fn write_refinement_plot(path: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    use super::plot::{Series, line_plot};
    use crate::study::sweep::{REFINEMENT_ABS, REFINEMENT_REL, refinement_converged};
    let records = sorted_by_index(records);
    let x: Vec<f64> = records.iter().map(|r| r.values[0]).collect();
    // each point owns the axis up to halfway to its neighbours
    let half = |i: usize| -> [f64; 2] {
        let lo = if i > 0 { 0.5 * (x[i - 1] + x[i]) } else { x[i] };
        let hi = if i + 1 < x.len() {
            0.5 * (x[i] + x[i + 1])
        } else {
            x[i]
        };
        [lo, hi]
    };
    let unconverged: Vec<[f64; 2]> = records
        .iter()
        .enumerate()
        .filter(|(_, r)| {
            r.refined.as_ref().is_none_or(|f| {
                refinement_converged(r.loss_fraction_span, f.loss_fraction_span) != Some(true)
            })
        })
        .map(|(i, _)| half(i))
        .collect();
    let base: Vec<(f64, f64)> = records
        .iter()
        .map(|r| (r.values[0], r.loss_fraction_span))
        .filter(|p| p.1.is_finite())
        .collect();
    let refined: Vec<(f64, f64)> = records
        .iter()
        .filter_map(|r| Some((r.values[0], r.refined.as_ref()?.loss_fraction_span)))
        .filter(|p| p.1.is_finite())
        .collect();
    let title = format!(
        "P_l in span under refinement (N×2, Δt/2): {} of {} points converged (≤ {:.0} % or {REFINEMENT_ABS:e})",
        records.len() - unconverged.len(),
        records.len(),
        100.0 * REFINEMENT_REL
    );
    let series = [
        Series {
            label: "at the sweep's N, Δt".into(),
            points: base,
            shaded: unconverged,
        },
        Series {
            label: "refined: 2N, Δt/2".into(),
            points: refined,
            shaded: vec![],
        },
    ];
    line_plot(
        path,
        &title,
        (&axis_label(&spec.axes[0].key), "P_l in span"),
        &series,
        "not converged (shaded)",
    )
}

/// `--check-refinement` on a 2-D sweep: the change of the in-span P_l under
/// one refinement (N × 2, Δt / 2) as a heat map, so a reader sees where the
/// loss map is converged (title: the criterion) and where it is not.
pub fn write_refinement_map(path: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    use crate::study::sweep::{REFINEMENT_ABS, REFINEMENT_REL, refinement_converged};
    let changes: Vec<SweepRecord> = records
        .iter()
        .map(|r| {
            let d = r.refined.as_ref().map_or(f64::NAN, |f| {
                (f.loss_fraction_span - r.loss_fraction_span).abs()
            });
            SweepRecord {
                loss_fraction: d,
                ..r.clone()
            }
        })
        .collect();
    let converged = records
        .iter()
        .filter(|r| {
            r.refined.as_ref().is_some_and(|f| {
                refinement_converged(r.loss_fraction_span, f.loss_fraction_span) == Some(true)
            })
        })
        .count();
    let title = format!(
        "|ΔP_l in span| under refinement (N×2, Δt/2): {converged} of {} points converged (≤ {:.0} % or {REFINEMENT_ABS:e})",
        records.len(),
        100.0 * REFINEMENT_REL
    );
    write_loss_fraction_map(path, spec, &changes, Some(&title), &SPEED_RATIO_LEVELS)
}
/// Draw the maps of a finished sweep into `dir` (none for a shard, which
/// holds only part of the grid). Returns the files written.
pub fn write_sweep_maps(
    dir: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<Vec<PathBuf>> {
    if records.len() != spec.len() {
        return Ok(vec![]);
    }
    match spec.axes.len() {
        1 => {
            let (f, l) = (dir.join("force_map.svg"), dir.join("loss_map.svg"));
            write_force_map(&f, spec, records, None)?;
            write_loss_map(&l, spec, records, None)?;
            let mut maps = vec![f, l];
            if spec.check_refinement {
                let r = dir.join("refinement.svg");
                write_refinement_plot(&r, spec, records)?;
                maps.push(r);
            }
            Ok(maps)
        }
        2 => {
            let p = dir.join("loss_fraction_map.svg");
            write_loss_fraction_map(&p, spec, records, None, &SPEED_RATIO_LEVELS)?;
            // the in-span part, the one to quote (docs/contact_loss.md)
            let s = dir.join("loss_fraction_span_map.svg");
            let span: Vec<SweepRecord> = records
                .iter()
                .map(|r| SweepRecord {
                    loss_fraction: r.loss_fraction_span,
                    ..r.clone()
                })
                .collect();
            write_loss_fraction_map(
                &s,
                spec,
                &span,
                Some("P_l in span (outside the support zones)"),
                &SPEED_RATIO_LEVELS,
            )?;
            let mut maps = vec![p, s];
            if spec.check_refinement {
                let r = dir.join("refinement_map.svg");
                write_refinement_map(&r, spec, records)?;
                maps.push(r);
            }
            Ok(maps)
        }
        _ => Ok(vec![]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(0.1 + 0.2), "0.3");
        assert_eq!(tick(0.0012000000000000001), "0.0012");
        assert_eq!(tick(20100.000000000004), "20100");
        assert_eq!(tick(0.0), "0");
        assert_eq!(tick(2.5e-5), "2.5e−5");
    }

    #[test]
    fn edges_bracket_values() {
        let e = edges(&[1.0, 2.0, 3.0], false);
        assert_eq!(e, vec![0.5, 1.5, 2.5, 3.5]);
        let l = edges(&[1.0, 100.0], true);
        assert!((l[1] - 10.0).abs() < 1e-9);
    }

    #[test]
    fn marching_squares_finds_a_straight_iso_line() {
        // s = x: the level 0.5 is the vertical line x = 0.5
        let px = [0.0, 1.0];
        let py = [0.0, 1.0, 2.0];
        let s = vec![vec![0.0, 0.0, 0.0], vec![1.0, 1.0, 1.0]];
        let segs = marching_squares(&px, &py, &s, 0.5);
        assert_eq!(segs.len(), 2);
        for sg in segs {
            for p in sg {
                assert!((p.0 - 0.5).abs() < 1e-12);
            }
        }
    }
}
