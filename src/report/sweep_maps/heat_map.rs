//! A heat map of cells with iso-lines and labels over it, drawn to SVG with
//! a colour bar beside it (or a note in its place when an axis cannot be
//! drawn).

use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::{span, tick};
use super::colour::Paint;
use super::colour_bar::{DynResult, colour_bar};
use crate::error::{Error, Result};
/// Pixel size of every map.
pub(super) const SIZE: (u32, u32) = (960, 620);
/// Width of the colour-bar panel, px.
pub(super) const BAR_PANEL: u32 = 130;

/// A line over the map (an iso-line segment), in data coordinates.
pub(super) struct Overlay {
    pub(super) points: Vec<(f64, f64)>,
    pub(super) bold: bool,
}

/// A text label over the map, in data coordinates.
pub(super) struct Label {
    pub(super) at: (f64, f64),
    pub(super) text: String,
    pub(super) anchor: Pos,
}

/// Everything one map needs.
pub(super) struct Map {
    pub(super) title: String,
    pub(super) x_desc: String,
    pub(super) y_desc: String,
    pub(super) x_edges: Vec<f64>,
    pub(super) y_edges: Vec<f64>,
    pub(super) x_log: bool,
    pub(super) y_log: bool,
    /// `cells[j][i]`: row j (y), column i (x).
    pub(super) cells: Vec<Vec<Option<f64>>>,
    pub(super) paint: Paint,
    pub(super) overlays: Vec<Overlay>,
    pub(super) labels: Vec<Label>,
    /// A line under the plot (legend, notes).
    pub(super) footer: String,
}

pub(super) fn draw_map(path: &Path, map: &Map) -> Result<()> {
    // every axis drawable first (axis_range), else a note in the map's place
    let (x0, x1) = span(&map.x_edges);
    let (y0, y1) = span(&map.y_edges);
    let mut checked = crate::report::axis_range::drawable(&map.x_desc, x0, x1, map.x_log)
        .and_then(|_| crate::report::axis_range::drawable(&map.y_desc, y0, y1, map.y_log))
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
        checked = crate::report::axis_range::drawable(bar_label, *lo, hi, *log).map(|_| ());
    }
    if let Err(reason) = checked {
        return crate::report::axis_range::write_note(
            path,
            SIZE,
            &map.title,
            &reason,
            "sweep.csv, sweep_force.csv and sweep_loss.csv",
        );
    }
    render(path, map)
        .and_then(|()| crisp_cells(path))
        .map_err(|e| Error::Output {
            path: path.into(),
            reason: e.to_string(),
        })
}

/// Draw the map's rectangles with crisp edges: adjacent cells anti-aliased
/// each on its own leave a hairline of the background between them in a
/// browser (a seam at every cell border); lines and text keep their
/// smoothing.
fn crisp_cells(path: &Path) -> DynResult<()> {
    let svg = std::fs::read_to_string(path)?;
    if let Some(open) = svg.find("<svg")
        && let Some(end) = svg[open..].find('>')
    {
        let at = open + end + 1;
        let styled = format!(
            "{}\n<style>rect{{shape-rendering:crispEdges}}</style>{}",
            &svg[..at],
            &svg[at..]
        );
        std::fs::write(path, styled)?;
    }
    Ok(())
}

pub(super) fn render(path: &Path, map: &Map) -> DynResult<()> {
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

pub(super) fn plot<X, Y>(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    xs: X,
    ys: Y,
    map: &Map,
) -> DynResult<()>
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
