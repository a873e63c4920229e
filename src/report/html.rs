//! `report.html` (`taut report DIR…`): one self-contained page from the
//! outputs taut wrote into one or more folders: each run's scene, summary,
//! the standards' statistics and warnings, every SVG plot, and the tables
//! of the studies (compare, converge, precision, sweep, verify, gate) with
//! their verdicts. Inline CSS and `data:` images only: no script, no link,
//! no font or image to fetch, so the file opens the same offline, attached
//! to a review or kept as a CI artefact (docs/output.md#report).
//!
//! Safe to open whatever the folders hold: a folder may have been edited
//! or made by someone else, so nothing read from it is pasted into the page
//! as markup. Text and numbers are escaped; a plot is embedded as an
//! `<img>` of a base64 `data:` URL (an SVG shown as an image runs no script
//! and fetches nothing, whatever it holds), and a file named `.svg` that is
//! no SVG is left out. The page's Content-Security-Policy ([`CSP`]) forbids
//! script and every fetch besides. Files are read only when regular, never
//! through a symbolic link and at most [`MAX_FILE_BYTES`] each
//! ([`crate::input::read_regular_text`]); a file left out is named in the
//! page with the reason, not fatal, and so is a file that does not parse.
//! A folder still marked [`INCOMPLETE_FILE`] is shown as partial, under a
//! banner, its values not presented as results.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::report::INCOMPLETE_FILE;

/// The page's Content-Security-Policy: nothing is fetched (`default-src
/// 'none'`), no script runs (no `script-src`), images only from `data:`
/// URLs (the plots, embedded), style only inline (the page's one `<style>`
/// element). A page edited after it was written still cannot fetch or run
/// anything.
pub(crate) const CSP: &str = "default-src 'none'; img-src data:; style-src 'unsafe-inline'";

/// Most bytes of one file a report reads (16 MiB, as
/// [`crate::input::MAX_INPUT_BYTES`]); a larger one is named as left out
/// and not read. taut's own outputs are far below it: a plot is drawn from
/// at most 4 × [`crate::resolve::memory::PLOT_BUCKETS`] points per series (under
/// 1 MiB), a summary a few KiB, a study's table a row per run or point; the
/// page shows at most [`MAX_ROWS`] rows of a table anyway. It bounds the
/// memory a report takes per file (a 2 GB table was read whole) and the
/// page's size (an SVG grows by a third as base64).
pub(crate) const MAX_FILE_BYTES: u64 = 16 << 20;

/// Most bytes of the [`INCOMPLETE_FILE`] marker shown in the page (taut
/// writes a few lines: the command and why it stopped).
const MAX_MARKER_BYTES: u64 = 64 << 10;

/// What a report's inputs are called in the reasons a file is left out.
const WHAT: &str = "a report's input";

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
    /// Plots embedded (as images).
    pub plots: usize,
    /// Tables shown.
    pub tables: usize,
    /// Folders read.
    pub folders: usize,
    /// Each file left out of the page, with the reason (a symbolic link,
    /// not a regular file, too large, not UTF-8, not an SVG).
    pub left_out: Vec<String>,
    /// The folders shown as incomplete (marked by an `INCOMPLETE` file).
    pub incomplete: Vec<PathBuf>,
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
    let mut left_out = Vec::new();
    let mut incomplete = Vec::new();
    for (k, dir) in dirs.iter().enumerate() {
        let section = folder_section(dir, k)?;
        plots += section.plots;
        tables += section.tables;
        let mark = if section.incomplete {
            incomplete.push(dir.clone());
            " <span class=\"fail\">INCOMPLETE</span>"
        } else {
            ""
        };
        let _ = writeln!(
            toc,
            "<li><a href=\"#f{k}\">{}</a>{mark}</li>",
            esc(&dir.display().to_string())
        );
        body.push_str(&section.html);
        left_out.extend(
            section
                .left_out
                .iter()
                .map(|(file, why)| format!("{}: {why}", dir.join(file).display())),
        );
    }
    let mut notes = String::new();
    if !incomplete.is_empty() {
        let _ = write!(
            notes,
            " · <span class=\"fail\">{} folder{} INCOMPLETE</span>",
            incomplete.len(),
            plural(incomplete.len())
        );
    }
    if !left_out.is_empty() {
        let _ = write!(
            notes,
            " · <span class=\"fail\">{} file{} left out</span>",
            left_out.len(),
            plural(left_out.len())
        );
    }
    let page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta http-equiv=\"Content-Security-Policy\" content=\"{CSP}\">\n<title>taut report</title>\n<style>{CSS}</style>\n</head>\n<body>\n<header><h1>taut report</h1><p>taut {} · {} folder{} · {plots} plot{} · {tables} table{}{notes}</p><ol>{toc}</ol></header>\n{body}</body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        dirs.len(),
        plural(dirs.len()),
        plural(plots),
        plural(tables),
    );
    // the folder the page goes into is claimed as every writer of a folder
    // claims it (created if need be): a report never writes beside a
    // command writing there, and no command starts there while it does
    let folder = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let _claim = crate::study::lock::claim_folder(folder, "taut report")?;
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
        left_out,
        incomplete,
    })
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The inline style: readable in print and on screen, figures scaled to
/// the page.
const CSS: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.4}\
h1{margin-bottom:0.2em}h2{border-bottom:2px solid #1f77b4;padding-bottom:0.2em;margin-top:2em}h3{margin-top:1.5em}\
figure{margin:1em 0;border:1px solid #ddd;padding:0.5em;background:#fff}figure img{display:block;width:100%;height:auto}\
figcaption{font-size:0.9em;color:#555;margin-top:0.3em}\
table{border-collapse:collapse;font-size:0.82em;margin:0.5em 0;display:block;overflow-x:auto}\
th,td{border:1px solid #ccc;padding:2px 6px;text-align:right;white-space:nowrap}th{background:#f0f4f8}\
td.text{text-align:left}.pass,.asymptotic,.yes,.true{background:#e3f4e3}.fail,.no,.diverged{background:#fbe3e3}\
.known,.pre-asymptotic,.reported,.cannot{background:#fff6dc}.warning{background:#fff3cd;border-left:4px solid #e0a800;padding:0.4em 0.8em;margin:0.3em 0}\
.note{color:#555;font-size:0.9em}pre{background:#f7f7f7;padding:0.6em;overflow-x:auto;font-size:0.85em}\
.incomplete{background:#fbe3e3;border:2px solid #c62828;padding:0.5em 0.8em;margin:0.5em 0;font-weight:bold}\
.partial{border-left:6px solid #c62828;padding-left:0.8em;opacity:0.75}.partial td,.partial span{background:none}\
.partial h3::after{content:' (partial: not a result)';color:#c62828;font-weight:normal;font-size:0.8em}";

struct Section {
    html: String,
    plots: usize,
    tables: usize,
    /// Files left out of the page: (file name, reason).
    left_out: Vec<(String, String)>,
    /// Whether the folder is marked [`INCOMPLETE_FILE`].
    incomplete: bool,
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
    let mut left_out = Vec::new();
    // the marker's presence is what counts (a link or an unreadable
    // marker still marks the folder); its text, when readable, says why
    let marker = dir.join(INCOMPLETE_FILE);
    let incomplete = std::fs::symlink_metadata(&marker).is_ok();
    let mut html = format!(
        "<section id=\"f{k}\"><h2>{}{}</h2>\n",
        esc(&dir.display().to_string()),
        if incomplete { " — INCOMPLETE" } else { "" }
    );
    if incomplete {
        let why = crate::input::read_regular_text(&marker, WHAT, MAX_MARKER_BYTES)
            .ok()
            .flatten()
            .map(|t| format!("<pre>{}</pre>", esc(t.trim_end())))
            .unwrap_or_default();
        let _ = writeln!(
            html,
            "<div class=\"incomplete\"><p>INCOMPLETE: this folder holds the marker {INCOMPLETE_FILE}: the command writing it did not finish. \
             Its files are partial: what is shown below is not a result, and a verdict in it is not one.</p>{why}</div>\n<div class=\"partial\">"
        );
    }
    let mut found = incomplete;
    let read = |file: &str, found: &mut bool, left_out: &mut Vec<(String, String)>| {
        match crate::input::read_regular_text(&dir.join(file), WHAT, MAX_FILE_BYTES) {
            Ok(text) => {
                *found |= text.is_some();
                text
            }
            Err(e) => {
                *found = true;
                left_out.push((file.to_string(), reason(&e)));
                None
            }
        }
    };
    if let Some(s) = read("summary.json", &mut found, &mut left_out)
        .and_then(|t| parse_json("summary.json", &t, &mut html))
    {
        html.push_str(&summary_html(&s));
    }
    let (mut plots, mut tables) = (0, 0);
    for (file, title, verdict) in TABLES {
        if let Some(text) = read(file, &mut found, &mut left_out) {
            tables += 1;
            let _ = writeln!(
                html,
                "<h3>{} <span class=\"note\">({file})</span></h3>",
                esc(title)
            );
            html.push_str(&csv_html(&text, verdict));
        }
    }
    if let Some(g) = read("gate.json", &mut found, &mut left_out)
        .and_then(|t| parse_json("gate.json", &t, &mut html))
    {
        tables += 1;
        html.push_str(&gate_html(&g));
    }
    for (file, caption) in PLOTS {
        let Some(svg) = read(file, &mut found, &mut left_out) else {
            continue;
        };
        if !is_svg(&svg) {
            left_out.push((
                file.to_string(),
                "not an SVG image (its text does not begin with an <svg> element), so not shown"
                    .into(),
            ));
            continue;
        }
        plots += 1;
        let alt = format!("{file}: {caption}");
        let _ = writeln!(
            html,
            "<figure>{}<figcaption>{file}: {}</figcaption></figure>",
            svg_img(&svg, &alt),
            esc(caption)
        );
    }
    if !found {
        return Err(Error::invalid(
            format!("OUT_DIR {}", dir.display()),
            "no taut outputs",
            "a folder with summary.json, compare.csv, converge.csv, precision.csv, sweep.csv, verify.csv, gate.json or their plots",
        ));
    }
    if !left_out.is_empty() {
        html.push_str("<div class=\"warning\"><p>Left out of this page:</p><ul>\n");
        for (file, why) in &left_out {
            let _ = writeln!(html, "<li>{}: {}</li>", esc(file), esc(why));
        }
        html.push_str("</ul></div>\n");
    }
    if incomplete {
        html.push_str("</div>\n");
    }
    html.push_str("</section>\n");
    Ok(Section {
        html,
        plots,
        tables,
        left_out,
        incomplete,
    })
}

/// Why a file was not read, without its path (the page names it).
fn reason(e: &Error) -> String {
    match e {
        Error::Io { source, .. } => source.to_string(),
        e => e.to_string(),
    }
}

/// A JSON file's text parsed (`file` names it); one that does not parse
/// is named in the page.
fn parse_json(file: &str, text: &str, html: &mut String) -> Option<serde_json::Value> {
    match serde_json::from_str(text) {
        Ok(v) => Some(v),
        Err(e) => {
            let _ = writeln!(
                html,
                "<p class=\"warning\">{} could not be read: {}</p>",
                esc(file),
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

/// Whether `text` is an SVG document: after an optional byte order mark,
/// white space, XML declaration or processing instructions, comments and
/// document type declaration, its first element is `<svg`. Anything else
/// (HTML, a CSV, a script renamed `.svg`) is not embedded.
fn is_svg(text: &str) -> bool {
    let mut t = text.trim_start_matches('\u{feff}');
    loop {
        t = t.trim_start();
        let skip = if t.starts_with("<?") {
            t.find("?>").map(|e| e + 2)
        } else if t.starts_with("<!--") {
            t.find("-->").map(|e| e + 3)
        } else if t.starts_with("<!DOCTYPE") {
            t.find('>').map(|e| e + 1)
        } else {
            break;
        };
        match skip {
            Some(n) => t = &t[n..],
            None => return false,
        }
    }
    t.strip_prefix("<svg")
        .and_then(|r| r.chars().next())
        .is_some_and(|c| c.is_ascii_whitespace() || c == '>' || c == '/')
}

/// An SVG as an `<img>` of a base64 `data:` URL with the text `alt`: shown
/// as an image, the SVG runs no script and fetches nothing, and none of its
/// text reaches the page's markup (base64 has no `<`, `"` or `&`).
fn svg_img(svg: &str, alt: &str) -> String {
    format!(
        "<img src=\"data:image/svg+xml;base64,{}\" alt=\"{}\">",
        base64(svg.as_bytes()),
        esc(alt)
    )
}

/// Standard base64 (RFC 4648 §4, with `=` padding). Written here: no crate
/// in the dependency tree provides it, and these few lines are the whole
/// encoder.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
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
    fn base64_matches_the_rfc_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded, "{plain}");
        }
        assert_eq!(base64(&[0xff, 0xfe, 0x00]), "//4A");
    }

    #[test]
    fn only_svg_documents_are_svgs() {
        assert!(is_svg("<svg width=\"1\"></svg>"));
        assert!(is_svg(
            "\u{feff}<?xml version=\"1.0\"?>\n<!-- drawn -->\n<!DOCTYPE svg>\n <svg>"
        ));
        assert!(!is_svg("<html><svg></svg></html>"));
        assert!(!is_svg("x,y\n1,2\n<svg>"));
        assert!(!is_svg("<svgx>"));
        assert!(!is_svg("<!-- never closed <svg>"));
        assert!(!is_svg(""));
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
