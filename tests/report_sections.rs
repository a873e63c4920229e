//! `taut report` over a folder of each kind a command writes, made by the
//! real binary at small settings: each has its section, every table and
//! plot of it is on the page or named with the reason it is not, verdicts
//! are coloured, a compared run's warnings sit under its row, wide tables
//! are split instead of scrolled, and the page opens on a summary of every
//! folder's verdicts (docs/output.md, "report.html").

use std::path::{Path, PathBuf};

use taut::app::{ReportRequest, report};
use taut::report::ReportSummary;

use super::common::{scene_path, taut_ok};

/// `taut ARGS… --out DIR` (DIR in `tmp`), asserting success; returns DIR.
fn made(tmp: &tempfile::TempDir, name: &str, args: &[&str]) -> PathBuf {
    let dir = tmp.path().join(name);
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["--out", dir.to_str().unwrap()]);
    taut_ok(&all);
    dir
}

/// The page of `dirs` and what the report says of it.
fn page(tmp: &tempfile::TempDir, dirs: &[&Path]) -> (String, ReportSummary) {
    let out = tmp.path().join("report.html");
    let r = report(&ReportRequest {
        dirs: dirs.iter().map(|d| d.to_path_buf()).collect(),
        out: Some(out.clone()),
    })
    .unwrap();
    (std::fs::read_to_string(out).unwrap(), r)
}

/// The reference scene, short: the carrier crosses a tenth of the span.
const SHORT: [&str; 2] = ["--set", "time.end=0.04"];

#[test]
fn uncertainty_and_modes_folders_have_their_sections() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = scene_path("reference.toml");
    let u = made(
        &tmp,
        "unc",
        &[
            "uncertainty",
            &reference,
            "--levels",
            "3",
            SHORT[0],
            SHORT[1],
            "--set",
            "mesh.elements=50",
            "--quiet",
        ],
    );
    let m = made(&tmp, "modes", &["modes", &reference, "--count", "4"]);
    let (p, r) = page(&tmp, &[&u, &m]);
    for s in [
        "taut uncertainty",
        "(uncertainty.csv)",
        "uncertainty.svg: ",
        "the family of runs",
        "taut modes",
        "(modes.csv)",
    ] {
        assert!(p.contains(s), "{s} missing from the page");
    }
    assert!(
        r.not_shown.iter().any(|n| n.contains("mode_shapes.csv: ")),
        "{:?}",
        r.not_shown
    );
    assert!(
        p.contains("mode_shapes.csv: the mode shapes"),
        "the page names it"
    );
}

#[test]
fn a_form_finding_run_and_a_line_show_every_table() {
    let tmp = tempfile::tempdir().unwrap();
    let f = made(
        &tmp,
        "form",
        &[
            "run",
            &scene_path("catenary_designed.toml"),
            "--set",
            "time.end=0.02",
            "--quiet",
        ],
    );
    let (p, r) = page(&tmp, &[&f]);
    for s in [
        "(static_heights.csv)",
        "(droppers_static.csv)",
        "(spans.csv)",
        "(supports.csv)",
        "force.svg: ",
        "(line, form-finding)",
    ] {
        assert!(p.contains(s), "{s} missing from the page");
    }
    // the time series is named, not shown, with its reason
    assert!(
        r.not_shown
            .iter()
            .any(|n| n.contains("history.csv: ") && n.contains("force.svg")),
        "{:?}",
        r.not_shown
    );
}

#[test]
fn a_tolerance_sweep_shows_its_plot_and_coloured_verdicts() {
    let tmp = tempfile::tempdir().unwrap();
    let s = made(
        &tmp,
        "tol",
        &[
            "sweep",
            &scene_path("reference.toml"),
            "--vary",
            "speed_ratio=0.6:0.8:2",
            SHORT[0],
            SHORT[1],
            "--set",
            "mesh.elements=48",
            "--tolerance",
            "0.05",
            "--quiet",
        ],
    );
    let (p, r) = page(&tmp, &[&s]);
    assert!(
        p.contains("tolerance.svg: "),
        "tolerance.svg is on the page"
    );
    assert!(p.contains("taut sweep --tolerance"), "the command is named");
    // tolerance_met's cells carry a verdict class, counted above the table
    assert!(
        p.contains("<td class=\"text good\">yes</td>")
            || p.contains("<td class=\"text bad\">no</td>"),
        "tolerance_met is not coloured"
    );
    assert!(p.contains("tolerance_met"), "its column");
    for n in ["sweep_force.csv: ", "sweep_loss.csv: ", "runs/: "] {
        assert!(
            r.not_shown.iter().any(|x| x.contains(n)),
            "{n} not named: {:?}",
            r.not_shown
        );
    }
}

#[test]
fn compare_warnings_sit_under_the_row_they_qualify() {
    let tmp = tempfile::tempdir().unwrap();
    // newmark without damping chatters on the reference case
    // (docs/methods.md); generalized_alpha does not
    let c = made(
        &tmp,
        "cmp",
        &[
            "compare",
            &scene_path("reference.toml"),
            "--methods",
            "newmark,generalized_alpha",
            "--formulations",
            "lagrange",
            "--set",
            "time.end=0.2",
            "--quiet",
        ],
    );
    let (p, _) = page(&tmp, &[&c]);
    // two runs of many columns: transposed, a column per run, the verdict
    // beside the runs' names
    let verdict = p.find("<tr><th>verdict</th>").expect("a verdict row");
    let row = &p[verdict..verdict + p[verdict..].find("</tr>").unwrap()];
    assert_eq!(
        row,
        "<tr><th>verdict</th><td class=\"text bad\">chatter</td><td class=\"text good\">clean</td>",
        "newmark chatters, generalized_alpha is clean"
    );
    // newmark's warnings named by its run, none for generalized_alpha
    assert!(
        p.contains(
            "<p class=\"warning\">WARNING newmark/hermite/lagrange: carrier 0: contact switched"
        ),
        "newmark's chatter warning"
    );
    assert!(
        !p.contains("WARNING generalized_alpha/"),
        "no warning of generalized_alpha"
    );
}

#[test]
fn the_page_opens_on_every_folders_verdicts_and_tables_never_scroll() {
    let tmp = tempfile::tempdir().unwrap();
    let v = made(
        &tmp,
        "verify",
        &[
            "verify",
            "--quick",
            "--methods",
            "generalized_alpha",
            "--discretizations",
            "hermite",
            "--formulations",
            "lagrange",
            "--quiet",
        ],
    );
    let run = made(
        &tmp,
        "run",
        &[
            "run",
            &scene_path("reference.toml"),
            SHORT[0],
            SHORT[1],
            "--quiet",
        ],
    );
    // a file taut does not write, and a name that is not UTF-8
    std::fs::write(run.join("extra.csv"), "a,b\n1,2\n").unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let name = std::ffi::OsStr::from_bytes(b"bad\xff.csv");
        std::fs::write(run.join(name), "x\n").unwrap();
    }
    let (p, r) = page(&tmp, &[&run, &v]);
    let first = p.find("<section").unwrap();
    assert!(
        p[first..].starts_with("<section id=\"verdicts\"><h2>Verdicts</h2>"),
        "the first section is the verdicts'"
    );
    let summary = &p[first..p[first + 1..].find("<section").unwrap() + first];
    assert!(summary.contains("taut verify"), "{summary}");
    assert!(summary.contains("<span class=\"good\">pass "), "{summary}");
    assert!(summary.contains("complete"), "{summary}");
    // verify.csv (29 columns) is split into parts that repeat its keys
    assert!(p.contains("part 1 of "), "verify.csv split");
    assert!(!p.contains("overflow-x:auto"), "no table scrolls");
    assert!(p.contains("overflow-wrap:anywhere"), "cells wrap");
    assert!(
        r.not_shown
            .iter()
            .any(|n| n.contains("extra.csv: not a file taut writes")),
        "{:?}",
        r.not_shown
    );
    #[cfg(unix)]
    assert!(
        r.left_out.iter().any(|n| n.contains("not UTF-8")),
        "{:?}",
        r.left_out
    );
    for n in ["verify.json: ", "verify.md: "] {
        assert!(r.not_shown.iter().any(|x| x.contains(n)), "{n}");
    }
}
