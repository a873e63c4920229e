//! A check, read from a plot's SVG alone, that its legend is clear of the
//! data: every plotting area is found from its axis lines (plotters draws
//! the left and bottom axes of a chart as two black lines meeting at its
//! lower-left corner), every legend entry from its label, and the entry's
//! text box must lie outside every plotting area; each series' key (the
//! line and marker drawn left of its label) is non-empty and differs from
//! every other series' in colour or marker. The tests draw every kind of
//! plot taut writes from small data and run the check on it.

/// An axis-aligned box, px: x0, y0, x1, y1.
type Bbox = [f64; 4];

/// A drawn element other than text: its box, its colour, what it is.
#[derive(Debug, Clone)]
struct Shape {
    bbox: Bbox,
    colour: String,
    /// "line" (a horizontal or vertical stroke) or a marker's kind
    /// ("circle", "polygon3", "polygon4", "diagonal").
    kind: String,
    /// A black stroke of two points (a candidate axis line).
    axis: Option<[(f64, f64); 2]>,
}

/// A text element: its box (estimated from its font size) and content.
#[derive(Debug, Clone)]
struct TextBox {
    bbox: Bbox,
    content: String,
}

fn attr(attrs: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let at = format!(" {attrs}").find(&key)?;
    let rest = &format!(" {attrs}")[at + key.len()..];
    Some(rest[..rest.find('"')?].to_string())
}

fn num(attrs: &str, name: &str) -> f64 {
    attr(attrs, name)
        .and_then(|v| v.parse().ok())
        .unwrap_or(f64::NAN)
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// The elements of `svg` (plotters' SVG: one element a line or two).
fn parse(svg: &str) -> (Vec<Shape>, Vec<TextBox>) {
    let mut shapes = Vec::new();
    let mut texts = Vec::new();
    let mut rest = svg;
    while let Some(open) = rest.find('<') {
        rest = &rest[open + 1..];
        let name_end = rest
            .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
            .unwrap_or(rest.len());
        let name = &rest[..name_end];
        let Some(close) = rest.find('>') else { break };
        let attrs = &rest[name_end..close];
        let colour = |a: &str| {
            attr(a, "stroke")
                .filter(|s| s != "none")
                .or_else(|| attr(a, "fill"))
                .unwrap_or_default()
        };
        match name {
            "text" => {
                let end = rest.find("</text>").unwrap_or(rest.len());
                let content = unescape(rest[close + 1..end].trim());
                rest = &rest[end..];
                if attrs.contains("rotate(") || content.is_empty() {
                    continue;
                }
                let (x, y) = (num(attrs, "x"), num(attrs, "y"));
                let fs = num(attrs, "font-size");
                let w = 0.6 * fs * content.chars().count() as f64;
                let x0 = match attr(attrs, "text-anchor").as_deref() {
                    Some("middle") => x - 0.5 * w,
                    Some("end") => x - w,
                    _ => x,
                };
                let y0 = match attr(attrs, "dy").as_deref() {
                    Some("0.76em") => y,
                    Some("0.5ex") => y - 0.5 * fs,
                    Some("-0.5ex") => y - fs,
                    _ => y - 0.8 * fs,
                };
                texts.push(TextBox {
                    bbox: [x0, y0, x0 + w, y0 + fs],
                    content,
                });
            }
            "polyline" | "polygon" => {
                let pts: Vec<(f64, f64)> = attr(attrs, "points")
                    .unwrap_or_default()
                    .split_whitespace()
                    .filter_map(|p| {
                        let (a, b) = p.split_once(',')?;
                        Some((a.parse().ok()?, b.parse().ok()?))
                    })
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                let bbox = pts.iter().fold(
                    [
                        f64::INFINITY,
                        f64::INFINITY,
                        f64::NEG_INFINITY,
                        f64::NEG_INFINITY,
                    ],
                    |b, &(x, y)| [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)],
                );
                let straight = bbox[2] - bbox[0] < 1.0 || bbox[3] - bbox[1] < 1.0;
                let kind = if name == "polygon" {
                    format!("polygon{}", pts.len())
                } else if straight {
                    "line".into()
                } else {
                    "diagonal".into()
                };
                let axis = (name == "polyline"
                    && pts.len() == 2
                    && attr(attrs, "stroke").as_deref() == Some("#000000"))
                .then_some([pts[0], pts[1]]);
                shapes.push(Shape {
                    bbox,
                    colour: colour(attrs),
                    kind,
                    axis,
                });
            }
            "line" => {
                let (x1, y1) = (num(attrs, "x1"), num(attrs, "y1"));
                let (x2, y2) = (num(attrs, "x2"), num(attrs, "y2"));
                let straight = (x1 - x2).abs() < 1.0 || (y1 - y2).abs() < 1.0;
                shapes.push(Shape {
                    bbox: [x1.min(x2), y1.min(y2), x1.max(x2), y1.max(y2)],
                    colour: colour(attrs),
                    kind: if straight { "line" } else { "diagonal" }.into(),
                    axis: None,
                });
            }
            "circle" => {
                let (x, y, r) = (num(attrs, "cx"), num(attrs, "cy"), num(attrs, "r"));
                shapes.push(Shape {
                    bbox: [x - r, y - r, x + r, y + r],
                    colour: colour(attrs),
                    kind: "circle".into(),
                    axis: None,
                });
            }
            "rect" => {
                let (x, y) = (num(attrs, "x"), num(attrs, "y"));
                let (w, h) = (num(attrs, "width"), num(attrs, "height"));
                shapes.push(Shape {
                    bbox: [x, y, x + w, y + h],
                    colour: colour(attrs),
                    kind: "rect".into(),
                    axis: None,
                });
            }
            _ => {}
        }
    }
    (shapes, texts)
}

/// Shortest axis line, px: tick marks and the marks of a legend are
/// shorter.
const MIN_AXIS: f64 = 40.0;

/// The plotting areas of a plot: a vertical axis line and a horizontal
/// one from its lower end (within 2 px) span each.
fn plot_areas(shapes: &[Shape]) -> Vec<Bbox> {
    let lines: Vec<[(f64, f64); 2]> = shapes.iter().filter_map(|s| s.axis).collect();
    let vertical = lines
        .iter()
        .filter(|l| (l[0].0 - l[1].0).abs() < 0.5 && (l[0].1 - l[1].1).abs() >= MIN_AXIS);
    let mut areas = Vec::new();
    for v in vertical {
        let (x, top, bottom) = (v[0].0, v[0].1.min(v[1].1), v[0].1.max(v[1].1));
        let h = lines.iter().find(|h| {
            (h[0].1 - h[1].1).abs() < 0.5
                && (h[0].1 - bottom).abs() <= 2.0
                && (h[0].0.min(h[1].0) - x).abs() <= 2.0
                && (h[0].0 - h[1].0).abs() >= MIN_AXIS
        });
        if let Some(h) = h {
            areas.push([x, top, h[0].0.max(h[1].0), bottom]);
        }
    }
    areas
}

fn overlap(a: &Bbox, b: &Bbox) -> bool {
    // 1 px of slack: boxes that touch do not overlap
    a[0] < b[2] - 1.0 && b[0] < a[2] - 1.0 && a[1] < b[3] - 1.0 && b[1] < a[3] - 1.0
}

/// The text of a legend entry labelled `label` (its first line when
/// wrapped).
fn entry<'a>(texts: &'a [TextBox], label: &str) -> Option<&'a TextBox> {
    texts.iter().find(|t| t.content == label).or_else(|| {
        texts.iter().find(|t| {
            label.starts_with(&t.content) && t.content.chars().count() >= label.len().min(8)
        })
    })
}

/// The key drawn left of a legend text (within 44 px, on its line).
fn key_of<'a>(shapes: &'a [Shape], t: &TextBox) -> Vec<&'a Shape> {
    let mid = 0.5 * (t.bbox[1] + t.bbox[3]);
    shapes
        .iter()
        .filter(|s| {
            s.bbox[0] >= t.bbox[0] - 44.0
                && s.bbox[2] <= t.bbox[0]
                && s.bbox[1] >= mid - 10.0
                && s.bbox[3] <= mid + 10.0
        })
        .collect()
}

/// Check the legend of the plot `svg`: the entries `series` (each a line
/// or marker set of its own) and `others` (shading, guides, notes) are
/// there, outside every plotting area; each series' key is non-empty and
/// carries a marker when `markers`; no two series' keys are alike (the
/// same colours and marker kinds). Err says what failed.
pub(crate) fn check_legend(
    svg: &str,
    series: &[&str],
    others: &[&str],
    markers: bool,
) -> Result<(), String> {
    let (shapes, texts) = parse(svg);
    let areas = plot_areas(&shapes);
    if areas.is_empty() {
        return Err("no plotting area found (no pair of axis lines)".into());
    }
    for (i, a) in areas.iter().enumerate() {
        if let Some(b) = areas[..i].iter().find(|b| overlap(a, b)) {
            return Err(format!("the plotting areas {a:?} and {b:?} overlap"));
        }
    }
    let mut keys: Vec<(&str, Vec<String>)> = Vec::new();
    for (k, label) in series.iter().chain(others).enumerate() {
        let t = entry(&texts, label).ok_or_else(|| format!("no legend entry {label:?}"))?;
        if let Some(a) = areas.iter().find(|a| overlap(a, &t.bbox)) {
            return Err(format!(
                "the legend entry {label:?} (box {:?}) lies in the plotting area {a:?}",
                t.bbox.map(f64::round)
            ));
        }
        if k < series.len() {
            let key = key_of(&shapes, t);
            if key.is_empty() {
                return Err(format!("the legend entry {label:?} has no key"));
            }
            if markers && key.iter().all(|s| s.kind == "line") {
                return Err(format!("the legend entry {label:?} has no marker"));
            }
            let mut sig: Vec<String> = key
                .iter()
                .map(|s| format!("{} {}", s.kind, s.colour))
                .collect();
            sig.sort();
            sig.dedup();
            if let Some((other, _)) = keys.iter().find(|(_, s)| *s == sig) {
                return Err(format!(
                    "the series {label:?} and {other:?} are drawn alike ({sig:?})"
                ));
            }
            keys.push((label, sig));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::plot::{Panel, Series, panels_plot};
    use std::path::Path;

    fn read(p: &Path) -> String {
        std::fs::read_to_string(p).unwrap()
    }

    /// A copy of each plot for a person to look at, when
    /// `TAUT_PLOT_CHECK_DIR` names a folder.
    fn keep(p: &Path) {
        if let Some(d) = std::env::var_os("TAUT_PLOT_CHECK_DIR") {
            std::fs::create_dir_all(&d).unwrap();
            std::fs::copy(p, Path::new(&d).join(p.file_name().unwrap())).unwrap();
        }
    }

    fn check(p: &Path, series: &[&str], others: &[&str], markers: bool) {
        keep(p);
        if let Err(e) = check_legend(&read(p), series, others, markers) {
            panic!("{}: {e}", p.display());
        }
    }

    /// A wavy series `k` over 0 … 1 that fills its panel's upper left
    /// (where a legend inside the plot would sit).
    fn wave(k: usize) -> Vec<(f64, f64)> {
        (0..200)
            .map(|i| {
                let x = i as f64 / 199.0;
                (x, 50.0 + 10.0 * (1.0 - x) * (k as f64 + (20.0 * x).sin()))
            })
            .collect()
    }

    /// A scene of the study at a small size (debug builds run it in well
    /// under a second).
    const SMALL: [&str; 2] = ["mesh.elements=40", "time.step=4e-4"];

    fn small(extra: &[&str]) -> Vec<String> {
        SMALL.iter().chain(extra).map(|s| s.to_string()).collect()
    }

    #[test]
    fn the_check_finds_a_legend_inside_the_plot() {
        // plotters' own legend, drawn over the data: the check fails
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("inside.svg");
        {
            use plotters::prelude::*;
            let root = SVGBackend::new(&p, (600, 400)).into_drawing_area();
            root.fill(&WHITE).unwrap();
            let mut chart = ChartBuilder::on(&root)
                .margin(10)
                .x_label_area_size(30)
                .y_label_area_size(40)
                .build_cartesian_2d(0.0..1.0, 0.0..100.0)
                .unwrap();
            chart.configure_mesh().draw().unwrap();
            chart
                .draw_series(LineSeries::new(wave(0), BLUE))
                .unwrap()
                .label("first series")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLUE));
            chart.configure_series_labels().draw().unwrap();
        }
        let e = check_legend(&read(&p), &["first series"], &[], false).unwrap_err();
        assert!(e.contains("lies in the plotting area"), "{e}");
        assert!(check_legend(&read(&p), &["absent"], &[], false).is_err());
    }

    #[test]
    fn force_and_compare_plots_keep_their_legend_beside_the_data() {
        let dir = tempfile::tempdir().unwrap();
        // force.svg of a run
        let sc = crate::resolve_scene(
            include_str!("../../scenes/reference.toml"),
            &small(&["time.end=0.2"]),
        )
        .unwrap();
        let out = crate::run(&sc, &mut |_, _| {}).unwrap();
        let p = dir.path().join("force.svg");
        crate::report::write_force_plot(&p, &sc, &out).unwrap();
        let band = crate::report::plot::filtered_label(out.history.band_hz());
        check(&p, &["λ (raw)", &band], &[], false);
        // compare.svg: panels of three series each, the legend once
        let panels: Vec<Panel> = (0..4)
            .map(|j| Panel {
                title: format!("method {j}"),
                series: (0..3)
                    .map(|k| Series {
                        label: format!("formulation {k}"),
                        points: wave(k + j),
                        shaded: vec![[0.2, 0.25]],
                        filtered: vec![],
                    })
                    .collect(),
                marks: vec![],
            })
            .collect();
        let p = dir.path().join("compare.svg");
        panels_plot(&p, "compare", ("x", "λ (N)"), &panels, "lost", "filtered").unwrap();
        check(
            &p,
            &["formulation 0", "formulation 1", "formulation 2"],
            &["lost"],
            true,
        );
    }

    #[test]
    fn converge_and_precision_plots_keep_their_legend_beside_the_data() {
        let dir = tempfile::tempdir().unwrap();
        // converge.svg: twelve series and three slope guides
        let names: Vec<String> = (0..12).map(|k| format!("quantity {k}")).collect();
        let series: Vec<(String, Vec<(f64, f64)>)> = names
            .iter()
            .enumerate()
            .map(|(k, n)| {
                let pts = (0..4)
                    .map(|l| {
                        let h = 0.1 / 2f64.powi(l);
                        (h, (1.0 + k as f64) * 1e-3 * h * 10.0)
                    })
                    .collect();
                (n.clone(), pts)
            })
            .collect();
        let p = dir.path().join("converge.svg");
        crate::report::converge::log_log(&p, "converge", "h (m)", &series, &[1.0, 2.0, 4.0])
            .unwrap();
        let labels: Vec<&str> = names.iter().map(String::as_str).collect();
        check(&p, &labels, &["slope guide, order 1"], true);
        // precision.svg: two formulations, a 2 × 2 grid each
        let row = |f: &str, i: usize, j: usize| crate::study::precision::PrecisionRow {
            method: "generalized_alpha".into(),
            discretization: "hermite".into(),
            formulation: f.into(),
            mesh_level: i,
            step_level: j,
            elements: 100 << i,
            modes: None,
            dt: 1e-4 / f64::from(1 << j),
            dofs: 200 << i,
            steps: 1000 << j,
            dof_steps: 1e5 * f64::from(1 << (i + j)),
            wall_seconds: 0.01 * f64::from(1 << (i + j)),
            force_error: 0.1 / f64::from(1 << (i + j)) * if f == "penalty" { 1.5 } else { 1.0 },
            displacement_error: 0.01,
            loss_fraction_error: 0.0,
            quantities: Default::default(),
            pareto: i == j,
        };
        let rows = ["lagrange", "penalty"]
            .iter()
            .flat_map(|f| (0..2).flat_map(move |i| (0..2).map(move |j| row(f, i, j))))
            .collect();
        let pr = crate::study::precision::Precision {
            reference: (800, 1e-5),
            reference_wall: 1.0,
            reference_method: "generalized_alpha".into(),
            rows,
            skipped: vec![],
        };
        crate::report::write_precision(dir.path(), &pr).unwrap();
        check(
            &dir.path().join("precision.svg"),
            &["lagrange, refine both", "penalty, refine both"],
            &["lagrange, refine mesh", "penalty, refine step"],
            true,
        );
    }

    #[test]
    fn the_uncertainty_plot_keeps_its_legend_beside_the_panels() {
        let dir = tempfile::tempdir().unwrap();
        let set = small(&["time.end=0.15"]);
        let u = crate::study::uncertainty::uncertainty(
            include_str!("../../scenes/reference.toml"),
            &set,
            3,
            &mut |_, _| {},
        )
        .unwrap();
        crate::report::uncertainty::write_uncertainty(dir.path(), &u).unwrap();
        let first = format!("value ± u_num ({} and Δt refined)", u.level_symbol);
        let second = format!("{} refined alone (Δt of the level before)", u.level_symbol);
        check(
            &dir.path().join("uncertainty.svg"),
            &[&first, &second],
            &["extrapolated value (Richardson, dashed)"],
            true,
        );
    }

    fn spec(json: &str) -> crate::study::sweep::SweepSpec {
        let mut v: serde_json::Value = serde_json::from_str(json).unwrap();
        v["scene_text"] = include_str!("../../scenes/reference.toml").into();
        v["set"] = small(&["time.end=0.15"]).into();
        serde_json::from_value(v).unwrap()
    }

    #[test]
    fn sweep_tolerance_and_refinement_plots_keep_their_legend_beside_the_data() {
        let dir = tempfile::tempdir().unwrap();
        let axis = r#"{"key": "speed_ratio", "start": 0.6, "stop": 1.2, "count": 3, "log": false}"#;
        let tol = r#"{"quantity": "loss_fraction_span", "tolerance": 0.05, "budget": 64.0}"#;
        // a 1-D sweep to a tolerance: sweep.svg and tolerance.svg
        let s = spec(&format!(r#"{{"axes": [{axis}], "tolerance": {tol}}}"#));
        let records =
            crate::study::sweep::sweep(&s, &dir.path().join("t"), None, &|_, _| {}).unwrap();
        crate::report::write_sweep_maps(dir.path(), &s, &records).unwrap();
        // two panels, a legend each
        let p = dir.path().join("sweep.svg");
        check(
            &p,
            &["P_l (whole run)", "P_l in span (the number to quote)"],
            &[],
            true,
        );
        check(&p, &["mean F_m", "F_m + 3σ", "F_m − 3σ", "max"], &[], true);
        check(
            &dir.path().join("tolerance.svg"),
            &["loss_fraction_span", "+ u_num", "− u_num"],
            &[],
            true,
        );
        // a 1-D sweep checked under refinement: refinement.svg
        let s = spec(&format!(
            r#"{{"axes": [{axis}], "check_refinement": true}}"#
        ));
        let records =
            crate::study::sweep::sweep(&s, &dir.path().join("r"), None, &|_, _| {}).unwrap();
        crate::report::write_sweep_maps(dir.path(), &s, &records).unwrap();
        check(
            &dir.path().join("refinement.svg"),
            &["at the sweep's N, Δt", "refined: 2N, Δt/2"],
            &[],
            true,
        );
        // a 2-D sweep to a tolerance: u_num_map.svg, its colour bar beside
        let axis2 = r#"{"key": "beam.tension", "start": 15000.0, "stop": 25000.0, "count": 2, "log": false}"#;
        let s = spec(&format!(
            r#"{{"axes": [{axis}, {axis2}], "tolerance": {tol}}}"#
        ));
        let records =
            crate::study::sweep::sweep(&s, &dir.path().join("m"), None, &|_, _| {}).unwrap();
        crate::report::write_sweep_maps(dir.path(), &s, &records).unwrap();
        let p = dir.path().join("u_num_map.svg");
        check(&p, &[], &[], false);
        // the colour bar (its axis: a long vertical line) right of the map
        let shapes = parse(&read(&p)).0;
        let map = plot_areas(&shapes);
        assert_eq!(map.len(), 1, "{map:?}");
        let bar = shapes.iter().filter_map(|s| s.axis).find(|l| {
            (l[0].0 - l[1].0).abs() < 0.5
                && (l[0].1 - l[1].1).abs() >= MIN_AXIS
                && l[0].0 > map[0][2]
        });
        assert!(bar.is_some(), "no colour bar right of the map {map:?}");
    }

    #[test]
    fn the_line_plot_keeps_its_legends_beside_the_line_and_the_envelope() {
        let dir = tempfile::tempdir().unwrap();
        let sc = crate::resolve_scene(
            include_str!("../../scenes/line_10_spans.toml"),
            &[
                "time.end=0.3".to_string(),
                "output.envelope=true".to_string(),
            ],
        )
        .unwrap();
        let out = crate::run(&sc, &mut |_, _| {}).unwrap();
        let p = dir.path().join("line.svg");
        crate::report::line_svg::write_line_plot(&p, &sc, &out).unwrap();
        check(
            &p,
            &["max v(x, t) over t", "min v(x, t) over t"],
            &[
                "supports",
                "droppers (to their anchors)",
                "carrier 0 travel",
            ],
            false,
        );
    }
}
