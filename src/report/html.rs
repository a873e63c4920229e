//! `report.html` (`taut report DIR…`): one self-contained page from the
//! outputs taut wrote into one or more folders: each run's scene, summary,
//! the standards' statistics and warnings, every SVG plot inline, and the
//! tables of the studies (compare, converge, precision, sweep, verify,
//! gate) with their verdicts. Inline CSS and inline SVG only: no script,
//! no link, no font or image to fetch, so the file opens the same offline,
//! attached to a review or kept as a CI artefact (docs/output.md#report).
//!
//! The page reads the files back as they are on disk, so it shows what a
//! reader of the folder would find; a file it cannot parse is named in the
//! page, not fatal.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// The plots a report draws, in this order, with their captions.
pub(crate) const PLOTS: [(&str, &str); 14] = [
    (
        "force.svg",
        "contact force (light), filtered force (bold), contact loss",
    ),
    (
        "line.svg",
        "the line: both wires, droppers and the uplift envelope",
    ),
    ("compare.svg", "contact force of each compared run"),
    ("converge.svg", "errors against refinement"),
    ("precision.svg", "error against cost"),
    ("sweep.svg", "the sweep's results against its axis"),
    ("force_map.svg", "mean contact force over the sweep"),
    ("loss_map.svg", "where contact is lost over the sweep"),
    ("refinement.svg", "the in-span P_l under refinement"),
    ("loss_fraction_map.svg", "P_l over the sweep's grid"),
    (
        "loss_fraction_span_map.svg",
        "in-span P_l over the sweep's grid",
    ),
    ("refinement_map.svg", "where the loss map is converged"),
    ("reference_force.svg", "contact force"),
    ("timing.svg", "timing"),
];

/// The tables a report shows, in this order: (file, title, the column
/// that holds a verdict, if any).
pub(crate) const TABLES: [(&str, &str, Option<&str>); 9] = [
    (
        "standard.csv",
        "the standards' statistics over the analysis section",
        None,
    ),
    ("spans.csv", "contact force per span", None),
    ("supports.csv", "uplift at the supports", None),
    (
        "compare.csv",
        "formulations, methods and discretizations compared",
        None,
    ),
    (
        "converge.csv",
        "convergence: errors, orders and regimes",
        Some("regime"),
    ),
    ("precision.csv", "work–precision", Some("pareto")),
    (
        "verify.csv",
        "verification: observed against expected orders",
        Some("status"),
    ),
    (
        "sweep.csv",
        "the sweep's points",
        Some("loss_fraction_span_converged"),
    ),
    (
        "accuracy.csv",
        "accuracy-targeted run: pilots and the chosen run",
        None,
    ),
];

/// At most this many rows of a table are shown (the rest are counted, and
/// are in the CSV beside the report).
pub(crate) const MAX_ROWS: usize = 200;

/// What a report was made from.
#[derive(Debug, Clone)]
pub struct ReportSummary {
    /// The page, written to this file.
    pub path: PathBuf,
    /// Plots inlined.
    pub plots: usize,
    /// Tables shown.
    pub tables: usize,
    /// Folders read.
    pub folders: usize,
}

/// Make `report.html` at `out` from the folders `dirs`. A folder without
/// any output taut writes is an error naming it.
pub(crate) fn write_report(dirs: &[PathBuf], out: &Path) -> Result<ReportSummary> {
    if dirs.is_empty() {
        return Err(Error::invalid(
            "OUT_DIR",
            "none",
            "give one or more folders taut wrote outputs into",
        ));
    }
    let mut body = String::new();
    let mut toc = String::new();
    let (mut plots, mut tables) = (0, 0);
    for (k, dir) in dirs.iter().enumerate() {
        let section = folder_section(dir, k)?;
        plots += section.plots;
        tables += section.tables;
        let _ = writeln!(
            toc,
            "<li><a href=\"#f{k}\">{}</a></li>",
            esc(&dir.display().to_string())
        );
        body.push_str(&section.html);
    }
    let page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>taut report</title>\n<style>{CSS}</style>\n</head>\n<body>\n<header><h1>taut report</h1><p>taut {} · {} folder{} · {plots} plot{} · {tables} table{}</p><ol>{toc}</ol></header>\n{body}</body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        dirs.len(),
        plural(dirs.len()),
        plural(plots),
        plural(tables),
    );
    if let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
    }
    // written beside and renamed over: a report that fails while writing
    // (a full disk) leaves an earlier page whole
    let mut tmp = out.as_os_str().to_owned();
    tmp.push(format!(".tmp-{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, page)
        .and_then(|()| std::fs::rename(&tmp, out))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            Error::io(out, e)
        })?;
    Ok(ReportSummary {
        path: out.to_path_buf(),
        plots,
        tables,
        folders: dirs.len(),
    })
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The inline style: readable in print and on screen, figures scaled to
/// the page.
const CSS: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.4}\
h1{margin-bottom:0.2em}h2{border-bottom:2px solid #1f77b4;padding-bottom:0.2em;margin-top:2em}h3{margin-top:1.5em}\
figure{margin:1em 0;border:1px solid #ddd;padding:0.5em;background:#fff}figure svg{display:block;width:100%;height:auto}\
figcaption{font-size:0.9em;color:#555;margin-top:0.3em}\
table{border-collapse:collapse;font-size:0.82em;margin:0.5em 0;display:block;overflow-x:auto}\
th,td{border:1px solid #ccc;padding:2px 6px;text-align:right;white-space:nowrap}th{background:#f0f4f8}\
td.text{text-align:left}.pass,.asymptotic,.yes,.true{background:#e3f4e3}.fail,.no,.diverged{background:#fbe3e3}\
.known,.pre-asymptotic,.reported,.cannot{background:#fff6dc}.warning{background:#fff3cd;border-left:4px solid #e0a800;padding:0.4em 0.8em;margin:0.3em 0}\
.note{color:#555;font-size:0.9em}pre{background:#f7f7f7;padding:0.6em;overflow-x:auto;font-size:0.85em}";

struct Section {
    html: String,
    plots: usize,
    tables: usize,
}

/// One folder's part of the page.
fn folder_section(dir: &Path, k: usize) -> Result<Section> {
    if !dir.is_dir() {
        return Err(Error::invalid(
            format!("OUT_DIR {}", dir.display()),
            "not a folder",
            "give folders taut wrote outputs into (taut run --out DIR, …)",
        ));
    }
    let mut html = format!(
        "<section id=\"f{k}\"><h2>{}</h2>\n",
        esc(&dir.display().to_string())
    );
    let mut found = false;
    if let Some(s) = read_json(&dir.join("summary.json"), &mut html) {
        found = true;
        html.push_str(&summary_html(&s));
    }
    let (mut plots, mut tables) = (0, 0);
    for (file, title, verdict) in TABLES {
        let p = dir.join(file);
        if let Ok(text) = std::fs::read_to_string(&p) {
            found = true;
            tables += 1;
            let _ = writeln!(
                html,
                "<h3>{} <span class=\"note\">({file})</span></h3>",
                esc(title)
            );
            html.push_str(&csv_html(&text, verdict));
        }
    }
    if let Some(g) = read_json(&dir.join("gate.json"), &mut html) {
        found = true;
        tables += 1;
        html.push_str(&gate_html(&g));
    }
    for (file, caption) in PLOTS {
        let p = dir.join(file);
        if let Ok(svg) = std::fs::read_to_string(&p) {
            found = true;
            plots += 1;
            let _ = writeln!(
                html,
                "<figure>{}<figcaption>{file}: {}</figcaption></figure>",
                inline_svg(&svg),
                esc(caption)
            );
        }
    }
    if !found {
        return Err(Error::invalid(
            format!("OUT_DIR {}", dir.display()),
            "no taut outputs",
            "a folder with summary.json, compare.csv, converge.csv, precision.csv, sweep.csv, verify.csv, gate.json or their plots",
        ));
    }
    html.push_str("</section>\n");
    Ok(Section {
        html,
        plots,
        tables,
    })
}

/// A JSON file, or None when absent; a file that does not parse is named
/// in the page.
fn read_json(path: &Path, html: &mut String) -> Option<serde_json::Value> {
    let text = std::fs::read_to_string(path).ok()?;
    match serde_json::from_str(&text) {
        Ok(v) => Some(v),
        Err(e) => {
            let _ = writeln!(
                html,
                "<p class=\"warning\">{} could not be read: {}</p>",
                esc(&path.display().to_string()),
                esc(&e.to_string())
            );
            None
        }
    }
}

/// A run's summary: the scene, the derived figures, each carrier's
/// statistics (raw and filtered) and the warnings.
fn summary_html(s: &serde_json::Value) -> String {
    let mut h = String::from("<h3>run</h3>\n");
    for w in s["warnings"].as_array().into_iter().flatten() {
        let _ = writeln!(
            h,
            "<p class=\"warning\">WARNING {}</p>",
            esc(w.as_str().unwrap_or_default())
        );
    }
    let _ = writeln!(h, "<table><tbody>");
    let carriers = s["carriers"].as_array().cloned().unwrap_or_default();
    let row = |h: &mut String, name: &str, unit: &str, vals: Vec<String>| {
        let _ = write!(
            h,
            "<tr><th>{}</th><td class=\"text\">{unit}</td>",
            esc(name)
        );
        for v in vals {
            let _ = write!(h, "<td>{v}</td>");
        }
        h.push_str("</tr>\n");
    };
    let per = |f: &dyn Fn(&serde_json::Value) -> &serde_json::Value| {
        carriers.iter().map(|c| num(f(c))).collect::<Vec<_>>()
    };
    row(
        &mut h,
        "carrier",
        "",
        (0..carriers.len()).map(|i| i.to_string()).collect(),
    );
    row(&mut h, "P_l", "–", per(&|c| &c["loss_fraction"]));
    row(
        &mut h,
        "P_l in span",
        "–",
        per(&|c| &c["loss_fraction_span"]),
    );
    row(
        &mut h,
        "first loss x/L",
        "–",
        per(&|c| &c["first_loss_position"]),
    );
    for (k, name) in [
        ("mean", "force mean"),
        ("std", "force σ"),
        ("max", "force max"),
        ("min", "force min"),
    ] {
        row(&mut h, name, "N", per(&|c| &c["force"][k]));
    }
    for (k, name) in [
        ("mean", "filtered force mean"),
        ("std", "filtered force σ"),
        ("max", "filtered force max"),
        ("min", "filtered force min"),
        ("statistical_max", "filtered mean + 3σ"),
        ("statistical_min", "filtered mean − 3σ"),
    ] {
        row(&mut h, name, "N", per(&|c| &c["force_filtered"][k]));
    }
    h.push_str("</tbody></table>\n");
    let d = &s["derived"];
    let _ = writeln!(
        h,
        "<p class=\"note\">{} elements ({}), {} unknowns, Δt = {} s, {} steps to t = {} s; c = {} m/s, V0/c = {}; wall {} s</p>",
        num(&s["scene"]["mesh"]["elements"]),
        esc(d["elements"].as_str().unwrap_or_default()),
        num(&d["dofs"]),
        num(&d["dt"]),
        num(&d["steps"]),
        num(&d["end_time"]),
        num(&d["wave_speed"]),
        num(&d["speed_ratio"]),
        num(&s["wall_seconds"])
    );
    let scene = serde_json::to_string_pretty(&s["scene"]).unwrap_or_default();
    let _ = writeln!(
        h,
        "<details><summary>the scene as run</summary><pre>{}</pre></details>",
        esc(&scene)
    );
    h
}

/// `gate.json`: each check and its verdict.
fn gate_html(g: &serde_json::Value) -> String {
    let mut h = String::from("<h3>gate <span class=\"note\">(gate.json)</span></h3>\n");
    let checks = g["checks"].as_array().cloned().unwrap_or_default();
    let failed = checks.iter().filter(|c| c["pass"] == false).count();
    let _ = writeln!(
        h,
        "<p class=\"{}\">{} checks, {failed} failed</p>",
        if failed == 0 { "pass" } else { "fail" },
        checks.len()
    );
    h.push_str("<table><thead><tr><th>case</th><th>quantity</th><th>value</th><th>reference</th><th>verdict</th></tr></thead><tbody>\n");
    for c in checks.iter().take(MAX_ROWS) {
        let pass = c["pass"] == true;
        let _ = writeln!(
            h,
            "<tr><td class=\"text\">{}</td><td class=\"text\">{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
            esc(c["case"].as_str().unwrap_or_default()),
            esc(c["quantity"].as_str().unwrap_or_default()),
            num(&c["value"]),
            num(&c["reference"]),
            if pass { "pass" } else { "fail" },
            if pass { "pass" } else { "fail" }
        );
    }
    h.push_str("</tbody></table>\n");
    h
}

/// A JSON number (or count, text, null) as a person reads it.
fn num(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::Number(n) => match n.as_f64() {
            Some(x) if n.is_f64() => short(x),
            _ => n.to_string(),
        },
        serde_json::Value::String(s) => esc(s),
        serde_json::Value::Bool(b) => b.to_string(),
        _ => "—".to_string(),
    }
}

/// A real to 6 significant digits.
fn short(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-3..1e6).contains(&x.abs()) {
        let digits = (5 - x.abs().log10().floor() as i32).clamp(0, 9) as usize;
        let s = format!("{x:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        // the mantissa without trailing zeros: 1e-4, 2.5e-12
        let t = format!("{x:.5e}");
        match t.split_once('e') {
            Some((m, e)) if m.contains('.') => {
                format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => t,
        }
    }
}

/// A CSV file as an HTML table (at most [`MAX_ROWS`] rows), numbers to 6
/// significant digits, the verdict column's cells classed by their value.
fn csv_html(text: &str, verdict: Option<&str>) -> String {
    let mut lines = text.lines();
    let Some(header) = lines.next() else {
        return "<p class=\"note\">empty</p>\n".into();
    };
    let names = split_csv(header);
    let v = verdict.and_then(|v| names.iter().position(|n| n == v));
    let rows: Vec<Vec<String>> = lines.map(split_csv).collect();
    let mut h = String::new();
    if let Some(vi) = v {
        // the verdicts, counted
        let mut counts: Vec<(String, usize)> = Vec::new();
        for r in &rows {
            let key = r.get(vi).cloned().unwrap_or_default();
            let key = if key.is_empty() { "—".into() } else { key };
            match counts.iter_mut().find(|(k, _)| *k == key) {
                Some((_, n)) => *n += 1,
                None => counts.push((key, 1)),
            }
        }
        let list: Vec<String> = counts
            .iter()
            .map(|(k, n)| format!("<span class=\"{}\">{} {n}</span>", class(k), esc(k)))
            .collect();
        let _ = writeln!(h, "<p>{}: {}</p>", esc(&names[vi]), list.join(" · "));
    }
    h.push_str("<table><thead><tr>");
    for n in &names {
        let _ = write!(h, "<th>{}</th>", esc(n));
    }
    h.push_str("</tr></thead><tbody>\n");
    for r in rows.iter().take(MAX_ROWS) {
        h.push_str("<tr>");
        for (i, c) in r.iter().enumerate() {
            let (text, numeric) = match c.parse::<f64>() {
                Ok(x) if !c.is_empty() => (short(x), true),
                _ => (esc(c), false),
            };
            let mut classes = Vec::new();
            if !numeric {
                classes.push("text".to_string());
            }
            if Some(i) == v && !c.is_empty() {
                classes.push(class(c));
            }
            if classes.is_empty() {
                let _ = write!(h, "<td>{text}</td>");
            } else {
                let _ = write!(h, "<td class=\"{}\">{text}</td>", classes.join(" "));
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody></table>\n");
    if rows.len() > MAX_ROWS {
        let _ = writeln!(
            h,
            "<p class=\"note\">{} of {} rows shown; the CSV beside the report has them all.</p>",
            MAX_ROWS,
            rows.len()
        );
    }
    h
}

/// A verdict as a CSS class name (letters, digits and '-').
fn class(v: &str) -> String {
    v.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect::<String>()
        .to_ascii_lowercase()
}

/// One CSV line's cells: commas separate, a quoted cell may hold commas
/// (taut writes no quote inside a quoted cell).
fn split_csv(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cell = String::new();
    let mut quoted = false;
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cell)),
            c => cell.push(c),
        }
    }
    out.push(cell);
    out
}

/// An SVG file as inline markup: without its XML declaration, with a
/// viewBox from its width and height so that it scales with the page.
fn inline_svg(svg: &str) -> String {
    let start = svg.find("<svg").unwrap_or(0);
    let svg = &svg[start..];
    let attr = |name: &str| -> Option<&str> {
        let tag_end = svg.find('>')?;
        let tag = &svg[..tag_end];
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        let len = tag[at..].find('"')?;
        Some(&tag[at..at + len])
    };
    match (attr("width"), attr("height"), attr("viewBox")) {
        (Some(w), Some(h), None) => {
            svg.replacen("<svg", &format!("<svg viewBox=\"0 0 {w} {h}\""), 1)
        }
        _ => svg.to_string(),
    }
}

/// Text escaped for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_cells_keep_quoted_commas() {
        assert_eq!(split_csv("a,\"b, c\",,1"), ["a", "b, c", "", "1"]);
    }

    #[test]
    fn svgs_get_a_view_box_and_lose_their_declaration() {
        let s = inline_svg(
            "<?xml version=\"1.0\"?>\n<svg width=\"960\" height=\"480\" xmlns=\"x\"></svg>",
        );
        assert!(
            s.starts_with("<svg viewBox=\"0 0 960 480\" width=\"960\""),
            "{s}"
        );
    }

    #[test]
    fn numbers_read_to_six_digits() {
        assert_eq!(short(45.90072271366183), "45.9007");
        assert_eq!(short(0.006), "0.006");
        assert_eq!(short(1e-12), "1e-12");
        assert_eq!(short(2.5e-7), "2.5e-7");
    }

    #[test]
    fn a_folder_without_outputs_is_named() {
        let d = tempfile::tempdir().unwrap();
        let e = write_report(&[d.path().to_path_buf()], &d.path().join("r.html"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no taut outputs"), "{e}");
    }
}
