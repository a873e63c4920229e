//! `report.html` (`taut report DIR…`): one self-contained page from the
//! outputs taut wrote into one or more folders, of any command: first the
//! verdicts of every folder, then each folder's runs (scene, summary,
//! statistics, warnings), plots and study tables with their verdicts;
//! every file a command writes is shown or named with the reason it is
//! not (`super::page::FILES`). Inline CSS and `data:` images only: no script, no link,
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

use super::outputs::Outputs;
use super::outputs::Show;
use super::page::{self, Grid, Tally, grid_html};
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
    /// Each file left out of the page because it could not be shown, with
    /// the reason (a symbolic link, not a regular file, too large, not
    /// UTF-8, not an SVG, a JSON that does not parse, a name that is not
    /// UTF-8).
    pub left_out: Vec<String>,
    /// Each file in the folders the page does not show by design, with the
    /// reason (a time series drawn in a plot, a table's JSON twin, a file
    /// taut does not write): `path: reason`.
    pub not_shown: Vec<String>,
    /// The folders shown as incomplete (marked by an `INCOMPLETE` file).
    pub incomplete: Vec<PathBuf>,
}

/// Make `report.html` at `out` from the folders `dirs`. A folder without
/// any output taut writes is an error naming it.
pub(crate) fn write_report(
    dirs: &[PathBuf],
    out: &Path,
    declared: &[Outputs],
) -> Result<ReportSummary> {
    let files = page::files(declared);
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
    let mut not_shown = Vec::new();
    let mut incomplete = Vec::new();
    let mut overview = String::from(
        "<section id=\"verdicts\"><h2>Verdicts</h2>\n<table class=\"overview\"><thead><tr><th>folder</th><th>command</th><th>verdicts</th><th>warnings</th><th>state</th><th>plots, tables</th><th>not shown</th></tr></thead><tbody>\n",
    );
    let mut all = Tally::default();
    for (k, dir) in dirs.iter().enumerate() {
        let section = folder_section(dir, k, &files)?;
        plots += section.plots;
        tables += section.tables;
        let name = esc(&dir.display().to_string());
        let mark = if section.incomplete {
            incomplete.push(dir.clone());
            " <span class=\"fail\">INCOMPLETE</span>"
        } else {
            ""
        };
        let _ = writeln!(toc, "<li><a href=\"#f{k}\">{name}</a>{mark}</li>");
        let _ = writeln!(
            overview,
            "<tr><td class=\"text\"><a href=\"#f{k}\">{name}</a></td><td class=\"text\">{}</td><td class=\"text\">{}</td><td class=\"{}\">{}</td><td class=\"text {}\">{}</td><td>{}, {}</td><td class=\"{}\">{}</td></tr>",
            esc(&section.commands.join(", ")),
            section.verdicts.html(),
            if section.warnings > 0 { "warn" } else { "good" },
            section.warnings,
            if section.incomplete { "bad" } else { "good" },
            if section.incomplete {
                "INCOMPLETE"
            } else {
                "complete"
            },
            section.plots,
            section.tables,
            if section.left_out.is_empty() {
                ""
            } else {
                "bad"
            },
            section.left_out.len() + section.not_shown.len(),
        );
        all.extend(&section.verdicts);
        body.push_str(&section.html);
        let full = |v: &[(String, String)]| {
            v.iter()
                .map(|(file, why)| format!("{}: {why}", dir.join(file).display()))
                .collect::<Vec<_>>()
        };
        left_out.extend(full(&section.left_out));
        not_shown.extend(full(&section.not_shown));
    }
    let _ = writeln!(
        overview,
        "</tbody></table>\n<p>All verdicts: {}</p>\n</section>",
        all.html()
    );
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
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta http-equiv=\"Content-Security-Policy\" content=\"{CSP}\">\n<meta name=\"viewport\" content=\"width=device-width\">\n<title>taut report</title>\n<style>{CSS}</style>\n</head>\n<body>\n<header><h1>taut report</h1><p>taut {} · {} folder{} · {plots} plot{} · {tables} table{}{notes}</p><ol>{toc}</ol></header>\n{overview}\n{body}</body>\n</html>\n",
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
        not_shown,
        incomplete,
    })
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The inline style: readable in print and on screen, figures scaled to
/// the page, tables that wrap within it (never a horizontal scroll: a wide
/// table is split or transposed, `page::MAX_COLUMNS`), every verdict
/// coloured (`good`, `warn`, `bad`).
const CSS: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1300px;margin:2em auto;padding:0 1em;color:#222;line-height:1.4}\
h1{margin-bottom:0.2em}h2{border-bottom:2px solid #1f77b4;padding-bottom:0.2em;margin-top:2em;overflow-wrap:anywhere}h3{margin-top:1.5em;overflow-wrap:anywhere}\
figure{margin:1em 0;border:1px solid #ddd;padding:0.5em;background:#fff;break-inside:avoid}figure img{display:block;max-width:100%;height:auto;margin:0 auto}\
figcaption{font-size:0.9em;color:#555;margin-top:0.3em}\
table{border-collapse:collapse;font-size:0.78em;margin:0.5em 0;max-width:100%;table-layout:auto}\
th,td{border:1px solid #ccc;padding:2px 5px;text-align:right;white-space:normal;overflow-wrap:anywhere;vertical-align:top}th{background:#f0f4f8}\
td.text{text-align:left}.pass,.good{background:#e3f4e3}.fail,.bad{background:#fbe3e3}.warn{background:#fff6dc}\
tr.row-note td{text-align:left;background:#fff3cd;font-size:0.95em}\
table.transposed th,table.overview th{text-align:left}table.overview th,table.overview td:nth-child(n+4){white-space:nowrap}\
.warning{background:#fff3cd;border-left:4px solid #e0a800;padding:0.4em 0.8em;margin:0.3em 0;overflow-wrap:anywhere}\
.note{color:#555;font-size:0.9em}pre{background:#f7f7f7;padding:0.6em;white-space:pre-wrap;overflow-wrap:anywhere;font-size:0.85em}\
li{overflow-wrap:anywhere}\
.incomplete{background:#fbe3e3;border:2px solid #c62828;padding:0.5em 0.8em;margin:0.5em 0;font-weight:bold}\
.partial{border-left:6px solid #c62828;padding-left:0.8em;opacity:0.75}.partial td,.partial span{background:none}\
.partial h3::after{content:' (partial: not a result)';color:#c62828;font-weight:normal;font-size:0.8em}\
@media print{body{max-width:none;margin:0;padding:0}table{font-size:7pt}h2,h3{break-after:avoid}tr{break-inside:avoid}}";

struct Section {
    html: String,
    plots: usize,
    tables: usize,
    /// Files left out of the page because they could not be shown: (file
    /// name, reason).
    left_out: Vec<(String, String)>,
    /// Files not shown by design: (file name, reason).
    not_shown: Vec<(String, String)>,
    /// Whether the folder is marked [`INCOMPLETE_FILE`].
    incomplete: bool,
    /// The commands whose outputs the folder holds.
    commands: Vec<String>,
    /// The verdicts of its tables, counted.
    verdicts: Tally,
    /// Warnings shown (a run's, a compared run's, a sweep point's).
    warnings: usize,
}

/// One folder's part of the page: a part per command whose outputs it
/// holds ([`page::FILES`]), every file shown or named with the reason it
/// is not.
fn folder_section(
    dir: &Path,
    k: usize,
    files: &[(&'static str, Outputs, Show)],
) -> Result<Section> {
    if !dir.is_dir() {
        return Err(Error::invalid(
            format!("OUT_DIR {}", dir.display()),
            "not a folder",
            "give folders taut wrote outputs into (taut run --out DIR, …)",
        ));
    }
    let mut left_out = Vec::new();
    let mut not_shown = Vec::new();
    // the folder's entries by name (a name that is not UTF-8 is named as
    // left out: taut writes none)
    let mut names: Vec<String> = Vec::new();
    let mut dirs_in: Vec<String> = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))? {
        let entry = entry.map_err(|e| Error::io(dir, e))?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else {
            left_out.push((
                name.to_string_lossy().into_owned(),
                "its name is not UTF-8: taut writes no such file, so not read".into(),
            ));
            continue;
        };
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            dirs_in.push(name.to_string());
        } else {
            names.push(name.to_string());
        }
    }
    names.sort();
    dirs_in.sort();
    let present = |f: &str| names.iter().any(|n| n == f);
    // the marker's presence is what counts (a link or an unreadable
    // marker still marks the folder); its text, when readable, says why
    let marker = dir.join(INCOMPLETE_FILE);
    let incomplete = std::fs::symlink_metadata(&marker).is_ok();
    let kinds: Vec<Outputs> = {
        let mut v: Vec<Outputs> = Vec::new();
        for (f, kind, _) in files {
            if present(f) && !v.contains(kind) {
                v.push(*kind);
            }
        }
        v
    };
    if kinds.is_empty() && !incomplete {
        return Err(Error::invalid(
            format!("OUT_DIR {}", dir.display()),
            "no taut outputs",
            "a folder a taut command wrote: run, compare, converge, precision, uncertainty, modes, verify, gate, sweep or merge (summary.json, compare.csv, … uncertainty.csv, modes.csv)",
        ));
    }
    let commands: Vec<String> = kinds
        .iter()
        .map(|&kind| page::command(kind, &present))
        .collect();
    let mut html = format!(
        "<section id=\"f{k}\"><h2>{}{}</h2>\n<p class=\"note\">written by {}</p>\n",
        esc(&dir.display().to_string()),
        if incomplete { " — INCOMPLETE" } else { "" },
        esc(&if commands.is_empty() {
            "a command that did not finish".to_string()
        } else {
            commands.join(", ")
        })
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
    let read =
        |file: &str, left_out: &mut Vec<(String, String)>| match crate::input::read_regular_text(
            &dir.join(file),
            WHAT,
            MAX_FILE_BYTES,
        ) {
            Ok(text) => text,
            Err(e) => {
                left_out.push((file.to_string(), reason(&e)));
                None
            }
        };
    let (mut plots, mut tables, mut warnings) = (0, 0, 0);
    let mut verdicts = Tally::default();
    for (&kind, command) in kinds.iter().zip(&commands) {
        let _ = writeln!(html, "<h3>{}</h3>", esc(command));
        // the JSON a table needs beside it (compare's warnings, …)
        let mut extra: Option<serde_json::Value> = None;
        for &(file, _, show) in files.iter().filter(|(f, k, _)| *k == kind && present(f)) {
            match show {
                Show::Summary => {
                    if let Some(s) = read(file, &mut left_out)
                        .and_then(|t| parse_json(file, &t, &mut html, &mut left_out))
                    {
                        warnings += s["warnings"].as_array().map_or(0, Vec::len);
                        html.push_str(&summary_html(&s, &mut verdicts));
                    }
                }
                Show::Json => {
                    let Some(v) = read(file, &mut left_out)
                        .and_then(|t| parse_json(file, &t, &mut html, &mut left_out))
                    else {
                        continue;
                    };
                    match file {
                        "gate.json" => {
                            tables += 1;
                            html.push_str(&gate_html(&v, &mut verdicts));
                        }
                        "uncertainty.json" => {
                            html.push_str(&uncertainty_html(&v, &mut verdicts));
                            tables += 1;
                        }
                        _ => {}
                    }
                    extra = Some(v);
                }
                Show::Table(title, verdict) => {
                    let Some(text) = read(file, &mut left_out) else {
                        continue;
                    };
                    tables += 1;
                    let _ = writeln!(
                        html,
                        "<h4>{} <span class=\"note\">({file})</span></h4>",
                        esc(title)
                    );
                    let mut grid = Grid::from_csv(&text);
                    if file == "compare.csv" {
                        warnings += with_run_verdicts(&mut grid, extra.as_ref());
                    }
                    if let Some(w) = grid.col("warnings") {
                        warnings += grid
                            .rows
                            .iter()
                            .filter_map(|r| r.get(w)?.parse::<usize>().ok())
                            .sum::<usize>();
                    }
                    html.push_str(&grid_html(&grid, verdict, MAX_ROWS, &mut verdicts));
                    if let Some(v) = extra.as_ref() {
                        html.push_str(&not_run_html(v, &mut verdicts));
                    }
                }
                Show::Plot(caption) => {
                    let Some(svg) = read(file, &mut left_out) else {
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
                Show::Named(why) => not_shown.push((file.to_string(), why.to_string())),
            }
        }
    }
    // what else the folder holds: named, not read
    for n in &names {
        if files.iter().any(|(f, _, _)| f == n) || page::QUIET.contains(&n.as_str()) {
            continue;
        }
        let why = if n.starts_with(super::outputs::FAILED_CONTACT_PREFIX) && n.ends_with(".json") {
            "a failed contact solve's problem: `taut replay` solves it again"
        } else if n == "sweep.json" {
            "the sweep's definition and progress, read to resume or merge it"
        } else if n.starts_with("report.html.tmp-") || n.starts_with('.') {
            continue;
        } else if [".svg", ".csv", ".json"].iter().any(|e| n.ends_with(e)) {
            "not a file taut writes: not read"
        } else {
            continue;
        };
        not_shown.push((n.clone(), why.into()));
    }
    for d in &dirs_in {
        if d == "runs" {
            not_shown.push((
                format!("{d}/"),
                "the sweep's record of each point: its tables and maps above are drawn from them"
                    .into(),
            ));
        }
    }
    if !left_out.is_empty() {
        html.push_str(
            "<div class=\"warning\"><p>Left out of this page (could not be shown):</p><ul>\n",
        );
        for (file, why) in &left_out {
            let _ = writeln!(html, "<li>{}: {}</li>", esc(file), esc(why));
        }
        html.push_str("</ul></div>\n");
    }
    if !not_shown.is_empty() {
        html.push_str("<div class=\"note\"><p>In the folder, not shown here:</p><ul>\n");
        for (file, why) in &not_shown {
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
        not_shown,
        incomplete,
        commands,
        verdicts,
        warnings,
    })
}

/// compare.csv's rows joined with compare.json's (by method,
/// discretization and formulation): a `verdict` column beside the run's
/// name (`page::run_verdict`) and each warning in a row under it. Returns
/// the warnings shown.
fn with_run_verdicts(grid: &mut Grid, json: Option<&serde_json::Value>) -> usize {
    let Some(rows) = json.and_then(|j| j["rows"].as_array()) else {
        return 0;
    };
    let key = |m: &str, d: &str, f: &str| format!("{m}\u{1}{d}\u{1}{f}");
    let col = |g: &Grid, n: &str| g.col(n);
    let (Some(m), Some(d), Some(f)) = (
        col(grid, "method"),
        col(grid, "discretization"),
        col(grid, "formulation"),
    ) else {
        return 0;
    };
    let mut count = 0;
    let mut verdict = Vec::with_capacity(grid.rows.len());
    for (r, notes) in grid.rows.iter().zip(grid.notes.iter_mut()) {
        let cell = |i: usize| r.get(i).map_or("", String::as_str);
        let k = key(cell(m), cell(d), cell(f));
        let found = rows.iter().find(|j| {
            key(
                j["method"].as_str().unwrap_or_default(),
                j["discretization"].as_str().unwrap_or_default(),
                j["formulation"].as_str().unwrap_or_default(),
            ) == k
        });
        let ws: Vec<String> = found
            .and_then(|j| j["warnings"].as_array())
            .into_iter()
            .flatten()
            .filter_map(|w| w.as_str().map(str::to_string))
            .collect();
        verdict.push(match found {
            Some(_) => page::run_verdict(&ws).to_string(),
            None => "not in compare.json".to_string(),
        });
        count += ws.len();
        *notes = ws;
    }
    grid.insert(f + 1, "verdict", verdict);
    count
}

/// A study's combinations that gave no row (`skipped`, `failed` of
/// compare.json or converge.json), each with its reason.
fn not_run_html(v: &serde_json::Value, tally: &mut Tally) -> String {
    let mut h = String::new();
    for (key, what) in [("skipped", "skipped"), ("failed", "failed")] {
        let list = v[key].as_array().cloned().unwrap_or_default();
        if list.is_empty() {
            continue;
        }
        let _ = writeln!(
            h,
            "<div class=\"warning\"><p>{} combination{} {what}:</p><ul>",
            list.len(),
            plural(list.len())
        );
        for n in &list {
            tally.add(what, page::verdict_class("", what));
            let who: Vec<&str> = ["method", "discretization", "formulation"]
                .iter()
                .filter_map(|k| n[*k].as_str().filter(|s| !s.is_empty()))
                .collect();
            let reason = match &n["reason"] {
                serde_json::Value::String(s) => s.clone(),
                other => other.to_string(),
            };
            let _ = writeln!(
                h,
                "<li><span class=\"bad\">{what}</span> {}: {}</li>",
                esc(&who.join("/")),
                esc(&reason)
            );
        }
        h.push_str("</ul></div>\n");
    }
    h
}

/// uncertainty.json's notes and the family of runs it made.
fn uncertainty_html(v: &serde_json::Value, tally: &mut Tally) -> String {
    let mut h = String::new();
    for n in v["notes"].as_array().into_iter().flatten() {
        let _ = writeln!(
            h,
            "<p class=\"warning\">NOTE {}</p>",
            esc(n.as_str().unwrap_or_default())
        );
    }
    let family = v["family"].as_array().cloned().unwrap_or_default();
    if !family.is_empty() {
        let _ = writeln!(
            h,
            "<h4>the family of runs <span class=\"note\">(uncertainty.json)</span></h4>"
        );
        let g = page::json_grid(
            &family,
            &[
                "role",
                "level",
                "elements",
                "modes",
                "h",
                "dt",
                "steps",
                "dofs",
                "wall_seconds",
            ],
        );
        h.push_str(&grid_html(&g, &[], MAX_ROWS, tally));
    }
    h
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
fn parse_json(
    file: &str,
    text: &str,
    html: &mut String,
    left_out: &mut Vec<(String, String)>,
) -> Option<serde_json::Value> {
    match serde_json::from_str(text) {
        Ok(v) => Some(v),
        Err(e) => {
            let _ = writeln!(
                html,
                "<p class=\"warning\">{} could not be read: {}</p>",
                esc(file),
                esc(&e.to_string())
            );
            left_out.push((file.to_string(), format!("not JSON taut wrote: {e}")));
            None
        }
    }
}

/// A run's summary: the scene, the derived figures, each carrier's
/// statistics (raw and filtered) and the warnings.
fn summary_html(s: &serde_json::Value, tally: &mut Tally) -> String {
    let mut h = String::from("<h4>the run <span class=\"note\">(summary.json)</span></h4>\n");
    h.push_str(&accuracy_html(&s["accuracy"], tally));
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

/// `gate.json`: each check and its verdict, and the cases that could not
/// run.
fn gate_html(g: &serde_json::Value, tally: &mut Tally) -> String {
    let mut h =
        String::from("<h4>the gate's checks <span class=\"note\">(gate.json)</span></h4>\n");
    let checks = g["checks"].as_array().cloned().unwrap_or_default();
    let mut grid = page::json_grid(
        &checks,
        &[
            "case",
            "quantity",
            "value",
            "reference",
            "difference",
            "tolerance",
            "reason",
        ],
    );
    let verdict = checks
        .iter()
        .map(|c| if c["pass"] == true { "pass" } else { "fail" }.to_string())
        .collect();
    grid.insert(2, "verdict", verdict);
    h.push_str(&grid_html(&grid, &["verdict"], MAX_ROWS, tally));
    for e in g["errors"].as_array().into_iter().flatten() {
        tally.add("error", "bad");
        let text = match e {
            serde_json::Value::String(s) => s.clone(),
            other => other.to_string(),
        };
        let _ = writeln!(
            h,
            "<p class=\"warning\"><span class=\"bad\">error</span> {}</p>",
            esc(&text)
        );
    }
    h
}

/// A `--tolerance` run's outcome: its tolerance, the reported run's u_num
/// and resolution, and whether it met the tolerance.
fn accuracy_html(a: &serde_json::Value, tally: &mut Tally) -> String {
    let (Some(tol), Some(u)) = (a["tolerance"].as_f64(), a["u_num"].as_f64()) else {
        return String::new();
    };
    let met = if u <= tol { "met" } else { "not met" };
    let class = page::verdict_class("tolerance_met", met);
    tally.add(met, class);
    let level = match a["modes"].as_u64() {
        Some(j) => format!("J = {j}"),
        None => format!("N = {}", num(&a["elements"])),
    };
    format!(
        "<p>accuracy target on {}: tolerance {}, value {} ± {} (u_num, {}) at {level}, Δt = {} s: <span class=\"{class}\">{met}</span></p>\n",
        esc(a["quantity"].as_str().unwrap_or_default()),
        short(tol),
        num(&a["value"]),
        short(u),
        num(&a["estimator"]),
        num(&a["dt"]),
    )
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
pub(crate) fn short(x: f64) -> String {
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
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let e = write_report(&[d.path().to_path_buf()], &d.path().join("r.html"), &[])
            .unwrap_err()
            .to_string();
        assert!(e.contains("no taut outputs"), "{e}");
    }
}
