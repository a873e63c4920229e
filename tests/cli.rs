//! End-to-end through the `taut` binary: outputs on disk, `--set`, and how a
//! bad scene is reported.

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{crate_root, out_dir, run_fails, taut_bin};

use serde_json::Value;

const HISTORY_HEADER: &str = "t,x_m,beam_w,mass_q,gap,force,in_contact,force_filtered";

/// Steps of the reference run: the carrier leaves after 1.2 L / V0 = 0.6 s at Δt = 1e-4 s.
const REFERENCE_STEPS: u64 = 6000;

/// Steps of T1: 7.62 m at 50.8 m/s is 0.15 s at Δt = 1e-4 s.
const T1_STEPS: u64 = 1500;

/// Reference ρA = 8900 · 1.5e-4 kg/m, so c = sqrt(T/ρA) ≈ 149.9 m/s at T = 3e4 N.
const REFERENCE_RHO_A: f64 = 8900.0 * 1.5e-4;

/// summary.json is written with shortest round-trip floats and c is the same
/// closed form, so only a few ulps of round-off may separate them.
const FORMULA_REL_TOL: f64 = 1e-12;

/// The brief's "c ≈ 149.9 m/s" is quoted to 0.1 m/s.
const QUOTED_WAVE_SPEED_TOL: f64 = 0.05;

/// `taut run SCENE --out DIR --quiet [--set …]…`, asserting success.
fn run_ok(scene: &str, out: &Path, sets: &[&str]) -> Output {
    let mut args = vec!["run", scene, "--out", out.to_str().unwrap(), "--quiet"];
    for s in sets {
        args.push("--set");
        args.push(s);
    }
    let o = taut_bin(&args);
    assert!(
        o.status.success(),
        "taut {args:?} failed ({}):\n{}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn summary(dir: &Path) -> Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("summary.json exists");
    serde_json::from_str(&text).expect("summary.json is valid JSON")
}

fn num(v: &Value, pointer: &str) -> f64 {
    v.pointer(pointer)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("summary.json has no number at {pointer}"))
}

fn uint(v: &Value, pointer: &str) -> u64 {
    v.pointer(pointer)
        .and_then(Value::as_u64)
        .unwrap_or_else(|| panic!("summary.json has no integer at {pointer}"))
}

/// The header line and the data rows of history.csv.
fn history(dir: &Path) -> (String, Vec<String>) {
    let text = std::fs::read_to_string(dir.join("history.csv")).expect("history.csv exists");
    let mut lines = text.lines().map(str::to_string);
    let header = lines.next().expect("history.csv has a header");
    (header, lines.collect())
}

fn rel_err(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn reference_run_writes_history_summary_and_plot() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "reference");
    run_ok("scenes/reference.toml", &out, &[]);

    // summary.json
    let s = summary(&out);
    let steps = uint(&s, "/derived/steps");
    assert_eq!(steps, REFERENCE_STEPS);
    let c = num(&s, "/derived/wave_speed");
    assert!(
        rel_err(c, (3.0e4 / REFERENCE_RHO_A).sqrt()) < FORMULA_REL_TOL,
        "c = {c}"
    );
    assert!((c - 149.9).abs() < QUOTED_WAVE_SPEED_TOL, "c = {c}");
    let ratio = num(&s, "/derived/speed_ratio");
    assert!(
        rel_err(ratio, 100.0 / c) < FORMULA_REL_TOL,
        "V0/c = {ratio}"
    );
    assert_eq!(
        s.pointer("/scene/time/end"),
        Some(&Value::from("carrier_leaves"))
    );

    let loss = num(&s, "/contact/loss_fraction");
    assert!((0.0..=1.0).contains(&loss), "P_l = {loss}");
    let (mean, std, min, max) = (
        num(&s, "/contact/force/mean"),
        num(&s, "/contact/force/std"),
        num(&s, "/contact/force/min"),
        num(&s, "/contact/force/max"),
    );
    assert!(
        min <= mean && mean <= max,
        "min {min} ≤ mean {mean} ≤ max {max}"
    );
    assert!(std >= 0.0 && std.is_finite(), "std = {std}");
    // unilateral contact can only push: λ ≥ 0, and the preloaded mass presses on average
    assert!(min >= 0.0, "unilateral λ went negative: min = {min}");
    assert!(mean > 0.0, "mean contact force = {mean}");
    assert_eq!(
        s.pointer("/contact"),
        s.pointer("/carriers/0"),
        "contact is carrier 0's stats"
    );
    let wall = num(&s, "/wall_seconds");
    assert!(wall > 0.0 && wall.is_finite(), "wall_seconds = {wall}");

    // history.csv
    let (header, rows) = history(&out);
    assert_eq!(header, HISTORY_HEADER);
    assert_eq!(rows.len() as u64, steps + 1, "one row per step plus t = 0");
    assert!(
        rows[0].starts_with("0,0,"),
        "first row is t = 0 at x = 0: {}",
        rows[0]
    );
    for row in [&rows[0], &rows[rows.len() / 2], rows.last().unwrap()] {
        assert_eq!(row.split(',').count(), 8, "row {row:?}");
    }
    let t_last: f64 = rows
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        rel_err(t_last, num(&s, "/derived/end_time")) < FORMULA_REL_TOL,
        "last row t = {t_last}"
    );

    // force.svg
    let svg = std::fs::read_to_string(out.join("force.svg")).expect("force.svg exists");
    assert!(
        svg.starts_with("<svg") || svg.starts_with("<?xml"),
        "force.svg starts with {:?}",
        &svg[..40.min(svg.len())]
    );
    assert!(svg.trim_end().ends_with("</svg>"), "force.svg is complete");
}

#[test]
fn set_on_the_command_line_reaches_the_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "set");
    run_ok(
        "scenes/reference.toml",
        &out,
        &["beam.tension=2e4", "mesh.elements=100", "time.end=0.05"],
    );
    let s = summary(&out);
    assert_eq!(num(&s, "/scene/beam/tension"), 2.0e4);
    assert_eq!(uint(&s, "/scene/mesh/elements"), 100);
    assert_eq!(num(&s, "/scene/time/end"), 0.05);
    assert_eq!(num(&s, "/derived/element_length"), 0.5);
    let steps = uint(&s, "/derived/steps");
    assert_eq!(steps, 500);
    let c = num(&s, "/derived/wave_speed");
    assert!(
        rel_err(c, (2.0e4 / REFERENCE_RHO_A).sqrt()) < FORMULA_REL_TOL,
        "c = {c}"
    );
    let (_, rows) = history(&out);
    assert_eq!(rows.len() as u64, steps + 1);
}

#[test]
fn out_of_range_value_is_reported_on_stderr() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "never");
    let err = run_fails("scenes/reference.toml", &out, &["--set", "beam.length=-1"]);
    assert!(
        err.contains("`beam.length` = -1: must be > 0 (m)"),
        "stderr:\n{err}"
    );
}

#[test]
fn unknown_key_is_reported_on_stderr() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "never");
    let err = run_fails(
        "scenes/reference.toml",
        &out,
        &["--set", "carrier.colour=red"],
    );
    assert!(
        err.contains("scenes/reference.toml"),
        "names the file:\n{err}"
    );
    assert!(err.contains("carrier.0.colour"), "names the key:\n{err}");
}

#[test]
fn bad_override_is_reported_on_stderr() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "never");
    let err = run_fails("scenes/reference.toml", &out, &["--set", "beam.length"]);
    assert!(
        err.contains("invalid override `beam.length`"),
        "stderr:\n{err}"
    );
}

#[test]
fn missing_scene_file_is_reported_on_stderr() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "never");
    let err = run_fails("scenes/no_such_scene.toml", &out, &[]);
    assert!(err.contains("no_such_scene.toml"), "stderr:\n{err}");
}

#[test]
fn t1_history_has_a_tip_column() {
    let tmp = tempfile::tempdir().unwrap();
    let out = out_dir(&tmp, "t1");
    run_ok("scenes/t1_cantilever_riding_mass.toml", &out, &[]);
    let s = summary(&out);
    let steps = uint(&s, "/derived/steps");
    assert_eq!(steps, T1_STEPS);
    let (header, rows) = history(&out);
    assert_eq!(header, format!("{HISTORY_HEADER},tip"));
    assert_eq!(rows.len() as u64, steps + 1);
    let tip = |row: &str| -> f64 { row.split(',').nth(8).unwrap().parse().unwrap() };
    assert_eq!(tip(&rows[0]), 0.0, "the cantilever starts at rest");
    // the 2629 kg mass has reached the tip: the cantilever is bent down
    let last = tip(rows.last().unwrap());
    assert!(last < 0.0, "tip deflection at the end = {last}");
}

#[test]
fn compare_writes_the_table_and_three_files() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "cmp");
    let scene = crate_root().join("scenes/reference.toml");
    let out = taut_bin(&[
        "compare",
        scene.to_str().unwrap(),
        "--formulations",
        "lagrange,penalty,complementarity,impact",
        "--set",
        "time.end=0.3",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    for f in [
        "lagrange",
        "penalty",
        "complementarity",
        "impact",
        "differences against generalized_alpha/lagrange",
    ] {
        assert!(stdout.contains(f), "{stdout}");
    }
    let csv = std::fs::read_to_string(dir.join("compare.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        // the comparison's own columns, every quantity the tables with one
        // row per run offer (the registry's), then the wall time
        taut::report::COMPARE_COLUMNS
            .into_iter()
            .chain(
                taut::quantity::offered(taut::quantity::Offer::RUN_TABLES)
                    .iter()
                    .map(|q| q.name)
            )
            .chain(["wall_seconds"])
            .collect::<Vec<_>>()
            .join(",")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 4);
    // the reference row differs from itself by exactly nothing
    let lagrange: Vec<&str> = rows[0].split(',').collect();
    assert_eq!(
        (
            lagrange[0],
            lagrange[1],
            lagrange[2],
            lagrange[3],
            lagrange[4]
        ),
        ("generalized_alpha", "hermite", "lagrange", "0", "0")
    );
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("compare.json")).unwrap()).unwrap();
    assert_eq!(json["reference"], "lagrange");
    assert_eq!(json["reference_method"], "generalized_alpha");
    assert_eq!(json["rows"].as_array().unwrap().len(), 4);
    let svg = std::fs::read_to_string(dir.join("compare.svg")).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
}

#[test]
fn a_failed_qp_is_saved_and_replays() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "qp");
    let scene = crate_root().join("scenes/reference.toml");
    let out = taut_bin(&[
        "run",
        scene.to_str().unwrap(),
        "--set",
        "contact.formulation=complementarity",
        "--set",
        "contact.complementarity.solver=clarabel",
        "--set",
        "contact.complementarity.max_iter=1",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("MaxIterations") && stderr.contains("saved the failing contact problem"),
        "{stderr}"
    );
    let saved = dir.join("failed_contact_step_0.json");
    assert!(saved.is_file());
    // the replay reproduces the failure, and solves with a sane limit
    let again = taut_bin(&["replay", saved.to_str().unwrap()]);
    assert!(!again.status.success());
    let fixed = taut_bin(&["replay", saved.to_str().unwrap(), "--max-iter", "50"]);
    assert!(
        fixed.status.success(),
        "{}",
        String::from_utf8_lossy(&fixed.stderr)
    );
    assert!(String::from_utf8_lossy(&fixed.stdout).contains("λ"));
    // the direct solver answers the same file
    let direct = taut_bin(&["replay", saved.to_str().unwrap(), "--solver", "direct"]);
    assert!(
        direct.status.success(),
        "{}",
        String::from_utf8_lossy(&direct.stderr)
    );
}

#[test]
fn compare_methods_tabulates_every_combination_and_skips_what_means_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "methods");
    let scene = crate_root().join("scenes/reference.toml");
    let out = taut_bin(&[
        "compare",
        scene.to_str().unwrap(),
        "--methods",
        "generalized_alpha,bathe,moreau_jean",
        "--formulations",
        "lagrange,penalty",
        "--set",
        "time.end=0.2",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // moreau_jean with penalty means nothing: skipped, naming both keys
    assert!(
        stdout.contains("skipped  moreau_jean/penalty") && stdout.contains("contact.formulation"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(dir.join("compare.csv")).unwrap();
    let methods: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(
        methods,
        [
            "generalized_alpha",
            "generalized_alpha",
            "bathe",
            "bathe",
            "moreau_jean"
        ]
    );
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("compare.json")).unwrap()).unwrap();
    assert_eq!(json["skipped"].as_array().unwrap().len(), 1);
    assert_eq!(json["failed"].as_array().unwrap().len(), 0);
}

#[test]
fn converge_and_precision_take_methods() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = crate_root().join("scenes/moving_force_beam.toml");
    let dir = out_dir(&tmp, "cv");
    let out = taut_bin(&[
        "converge",
        scene.to_str().unwrap(),
        "--refine",
        "step",
        "--levels",
        "3",
        "--methods",
        "bathe,central_difference",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("converge.csv")).unwrap();
    for m in ["bathe", "central_difference"] {
        assert!(
            csv.lines().any(|l| l.starts_with(&format!("{m},"))),
            "{csv}"
        );
    }
    let dir = out_dir(&tmp, "pr");
    let out = taut_bin(&[
        "precision",
        crate_root().join("scenes/reference.toml").to_str().unwrap(),
        "--methods",
        "generalized_alpha,moreau_jean",
        "--formulations",
        "lagrange",
        "--levels",
        "1",
        "--set",
        "time.end=0.1",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("precision.csv")).unwrap();
    assert!(
        csv.starts_with("method,discretization,formulation"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 3, "{csv}");
}

/// `--discretizations` in compare, converge and precision (MODEL §9.2):
/// one row (or ladder) per discretization, J as the modal kinds' level
/// parameter, and a bad list named.
#[test]
fn studies_take_discretizations() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = crate_root().join("scenes/moving_force_beam.toml");
    let ok = |args: &[&str]| {
        let out = taut_bin(args);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let dir = out_dir(&tmp, "cmp");
    ok(&[
        "compare",
        scene.to_str().unwrap(),
        "--formulations",
        "lagrange",
        "--discretizations",
        "hermite,galerkin:20,modal:20",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let csv = std::fs::read_to_string(dir.join("compare.csv")).unwrap();
    let kinds: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(kinds, ["hermite", "galerkin J=20", "modal J=20"], "{csv}");
    let dir = out_dir(&tmp, "cv");
    ok(&[
        "converge",
        scene.to_str().unwrap(),
        "--refine",
        "mesh",
        "--levels",
        "3",
        "--discretizations",
        "galerkin:5,modal:5",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let csv = std::fs::read_to_string(dir.join("converge.csv")).unwrap();
    // J doubles level by level: the modes column of the modal ladders
    for (kind, j) in [("galerkin", "5"), ("galerkin", "10"), ("modal", "20")] {
        assert!(
            csv.lines()
                .any(|l| l.contains(&format!("{kind},")) && l.split(',').nth(4) == Some(j)),
            "{kind} J={j}: {csv}"
        );
    }
    let dir = out_dir(&tmp, "pr");
    ok(&[
        "precision",
        scene.to_str().unwrap(),
        "--formulations",
        "lagrange",
        "--discretizations",
        "hermite,modal:10",
        "--levels",
        "1",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let csv = std::fs::read_to_string(dir.join("precision.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(
        csv.lines()
            .any(|l| l.contains(",modal,") && l.contains(",10,")),
        "{csv}"
    );
    let out = taut_bin(&[
        "compare",
        scene.to_str().unwrap(),
        "--discretizations",
        "hermite,fourier",
        "--out",
        out_dir(&tmp, "bad").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--discretizations") && err.contains("fourier"),
        "{err}"
    );
}

/// A thread count the machine cannot use is refused before any run, naming
/// `--threads`, the value and the range; it used to spawn threads for
/// minutes and then panic (`GlobalPoolAlreadyInitialized`) under a memory
/// limit.
#[test]
fn sweep_threads_are_bounded_and_never_panic() {
    let tmp = tempfile::tempdir().unwrap();
    let max = taut::study::threads::max_threads();
    let too_many = (max + 1).to_string();
    for bad in ["0", too_many.as_str(), "100000"] {
        let dir = out_dir(&tmp, "threads");
        let start = std::time::Instant::now();
        let out = taut_bin(&[
            "sweep",
            "scenes/reference.toml",
            "--vary",
            "carrier.speed.cruise=50:60:2",
            "--set",
            "time.end=0.01",
            "--threads",
            bad,
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "--threads {bad}: {stderr}");
        assert!(
            stderr.starts_with("error: ")
                && stderr.contains(&format!("`--threads` = {bad}:"))
                && stderr.contains(&format!("1 ..= {max}"))
                && !stderr.contains("panicked"),
            "{stderr}"
        );
        assert!(!dir.exists(), "no output for a refused sweep");
        // refused up front: no thread was started (generous for a busy CI)
        assert!(start.elapsed().as_secs() < 30, "{:?}", start.elapsed());
    }
}

/// A file that is not a scene is named and refused, its content never
/// reproduced: toml's own message quotes the offending line.
#[test]
fn a_file_that_is_not_a_scene_is_refused_without_its_content() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        ("passwd", "root:x:0:0:SECRET_A:/root:/bin/bash\n"),
        (
            "env.toml",
            "SECRET_B = \"hunter2\"\n[package]\nname = \"x\"\n",
        ),
    ];
    for (name, content) in cases {
        let file = tmp.path().join(name);
        std::fs::write(&file, content).unwrap();
        let err = run_fails(file.to_str().unwrap(), &out_dir(&tmp, "o"), &[]);
        assert!(err.contains(file.to_str().unwrap()), "{err}");
        for secret in ["SECRET", "hunter2", "root", "package"] {
            assert!(!err.contains(secret), "{name}: content reproduced: {err}");
        }
    }
}

/// Sweep files read back are checked: a tampered spec (no axes) and a record
/// in the wrong file are errors naming what is wrong, not a silent merge.
#[test]
fn merge_checks_the_files_it_reads_back() {
    let tmp = tempfile::tempdir().unwrap();
    let shard = out_dir(&tmp, "shard");
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "carrier.speed.cruise=50:60:2",
        "--set",
        "time.end=0.01",
        "--out",
        shard.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let merge = |name: &str| {
        let o = taut_bin(&[
            "merge",
            shard.to_str().unwrap(),
            "--out",
            out_dir(&tmp, name).to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    // a record moved into another point's file
    let runs = shard.join("runs");
    let first = std::fs::read_to_string(runs.join("000000.json")).unwrap();
    let second = std::fs::read_to_string(runs.join("000001.json")).unwrap();
    std::fs::write(runs.join("000001.json"), &first).unwrap();
    let e = merge("m1");
    assert!(
        e.contains("000001.json") && e.contains("holds point 0"),
        "{e}"
    );
    std::fs::write(runs.join("000001.json"), second).unwrap();
    // a spec whose axes were removed
    let spec_path = shard.join("sweep.json");
    let mut spec: Value =
        serde_json::from_str(&std::fs::read_to_string(&spec_path).unwrap()).unwrap();
    spec["axes"] = serde_json::json!([]);
    std::fs::write(&spec_path, spec.to_string()).unwrap();
    let e = merge("m2");
    assert!(e.contains("`--vary` = 0: give one or two axes"), "{e}");
}
