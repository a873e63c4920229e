//! The bundled multi-span line (`scenes/line_10_spans.toml` and its linear
//! twin): each study runs on it end to end from the CLI, cut down
//! to a few spans and a fraction of a second so the default suite stays
//! fast (the full runs and their convergence in N and Δt are in
//! docs/lines.md "The bundled line").

use crate::common;

use std::path::Path;

use serde_json::Value;

const LINE: &str = "scenes/line_10_spans.toml";
const TWIN: &str = "scenes/line_10_spans_linear.toml";

/// Two spans and the first 0.4 s (the pantograph, at 69.4 m/s, crosses the
/// first support at 0.79 s; by 0.4 s it has passed five droppers).
const CUT: [&str; 4] = ["--set", "line.spans=2", "--set", "time.end=0.4"];

fn ok(args: &[&str]) {
    let o = common::taut_bin(args);
    assert!(
        o.status.success(),
        "taut {args:?} failed:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("file written")).expect("JSON")
}

fn with_cut<'a>(head: &[&'a str], out: &'a str) -> Vec<&'a str> {
    let mut v = head.to_vec();
    v.extend_from_slice(&["--out", out, "--quiet"]);
    v.extend_from_slice(&CUT);
    v
}

/// Both bundled scenes run; the messenger's supports are the line's
/// supports (spans.csv, supports.csv), and the tension-only line's droppers
/// slacken where the twin's never do. (That a static start stays still is
/// `messenger::a_static_start_stays_still`.)
#[test]
fn the_line_and_its_twin_run_with_spans_and_supports() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (common::out_dir(&tmp, "line"), common::out_dir(&tmp, "twin"));
    let (a_s, b_s) = (a.to_str().unwrap(), b.to_str().unwrap());
    ok(&with_cut(&["run", LINE], a_s));
    ok(&with_cut(&["run", TWIN], b_s));
    let (sa, sb) = (json(&a.join("summary.json")), json(&b.join("summary.json")));
    // two spans of 55 m: supports at 0, 55, 110 m from the messenger
    let supports: Vec<f64> = sa["supports"]
        .as_array()
        .expect("supports in the summary")
        .iter()
        .map(|s| s["x"].as_f64().unwrap())
        .collect();
    assert_eq!(supports, [0.0, 55.0, 110.0]);
    assert_eq!(sa["spans"].as_array().unwrap().len(), 2);
    assert!(a.join("spans.csv").exists() && a.join("supports.csv").exists());
    // 9 droppers a span, tension-only in the line, linear in the twin
    assert_eq!(sa["droppers"].as_array().unwrap().len(), 18);
    let slack = |s: &Value| -> f64 {
        s["droppers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d["slack_fraction"].as_f64().unwrap_or(0.0))
            .sum()
    };
    assert!(
        slack(&sa) > 0.0,
        "the pantograph (120 N static, 5 cm uplift) slackens droppers near it"
    );
    assert_eq!(slack(&sb), 0.0, "linear droppers never slack");
    let mean = |s: &Value| s["carriers"][0]["force"]["mean"].as_f64().unwrap();
    assert!(
        mean(&sa) != mean(&sb),
        "slack droppers change the contact force"
    );
}

/// The bundled line scenes run without warnings: their 50 kN/m contact
/// is declared the physical contact stiffness (`contact.penalty.physical`),
/// whose penetration is the model, not a soft penalty to warn of; both set
/// `[analysis]`.
#[test]
fn the_bundled_line_scenes_run_without_warnings() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, scene) in [("line", LINE), ("twin", TWIN)] {
        let text = std::fs::read_to_string(common::crate_root().join(scene)).unwrap();
        assert!(text.contains("\n[analysis]\n"), "{scene} sets [analysis]");
        let dir = common::out_dir(&tmp, name);
        ok(&with_cut(&["run", scene], dir.to_str().unwrap()));
        let s = json(&dir.join("summary.json"));
        let warnings = s["warnings"].as_array().expect("warnings in the summary");
        assert!(warnings.is_empty(), "{scene}: {warnings:?}");
    }
}

/// `compare`, `converge` and `sweep` run on the line (cut down).
#[test]
fn compare_converge_and_sweep_run_on_the_line() {
    let tmp = tempfile::tempdir().unwrap();
    let c = common::out_dir(&tmp, "compare");
    let mut args = with_cut(&["compare", LINE], c.to_str().unwrap());
    args.extend_from_slice(&["--formulations", "penalty,lagrange", "--yes"]);
    ok(&args);
    let rows = std::fs::read_to_string(c.join("compare.csv")).unwrap();
    assert_eq!(rows.lines().count(), 3, "a header and two formulations");

    let v = common::out_dir(&tmp, "converge");
    let mut args = vec![
        "converge",
        LINE,
        "--out",
        v.to_str().unwrap(),
        "--quiet",
        "--yes",
        "--levels",
        "2",
    ];
    args.extend_from_slice(&["--set", "line.spans=1", "--set", "time.end=0.1"]);
    ok(&args);
    assert!(v.join("converge.csv").exists());

    let s = common::out_dir(&tmp, "sweep");
    let mut args = with_cut(&["sweep", LINE], s.to_str().unwrap());
    args.extend_from_slice(&["--vary", "carrier.0.speed.value=60,80", "--yes"]);
    ok(&args);
    let sweep = std::fs::read_to_string(s.join("sweep.csv")).unwrap();
    assert_eq!(sweep.lines().count(), 3, "a header and two speeds");
}

/// `gate` on a suite holding a line case: it passes on references it just
/// recorded (`--update`) and fails once the line's dropper stiffness moves.
#[test]
fn gate_checks_a_line_case_and_catches_a_change() {
    let tmp = tempfile::tempdir().unwrap();
    let suite = tmp.path().join("suite");
    std::fs::create_dir(&suite).unwrap();
    let scene = common::crate_root().join(LINE);
    let case = |stiffness: &str| {
        serde_json::json!({
            "description": "line_10_spans cut to 2 spans and 0.3 s",
            "scene": scene.to_str().unwrap(),
            "set": ["line.spans=2", "time.end=0.3", format!("line.dropper_stiffness={stiffness}")],
            "quantities": {
                "force_mean": { "value": 0.0, "abs": 0.0, "rel": 1e-9, "reason": "round-off: the same scene and binary" },
                "steps": { "value": 0.0, "abs": 0.0, "rel": 0.0, "reason": "integer" }
            }
        })
        .to_string()
    };
    std::fs::write(suite.join("line.json"), case("1.0e5")).unwrap();
    let out = tmp.path().join("gate");
    let (suite_s, out_s) = (suite.to_str().unwrap(), out.to_str().unwrap());
    ok(&["gate", suite_s, "--out", out_s, "--quiet", "--update"]);
    ok(&["gate", suite_s, "--out", out_s, "--quiet"]);
    // the recorded references, then a stiffer dropper against them
    let recorded: Value = json(&suite.join("line.json"));
    let mut changed = recorded.clone();
    changed["set"][2] = Value::from("line.dropper_stiffness=2.0e5");
    std::fs::write(suite.join("line.json"), changed.to_string()).unwrap();
    let o = common::taut_bin(&["gate", suite_s, "--out", out_s, "--quiet"]);
    assert!(
        !o.status.success(),
        "a stiffer dropper must fail the line's force_mean check"
    );
}

/// Pantograph static force, N: uplift − g Σm = 490 − 9.81 · 37.7 (the
/// roof spring is 0, so the chain's static stiffness S is 0 and the force
/// does not depend on the wire's height, docs/lines.md W7).
const PANTOGRAPH_STATIC: f64 = 490.0 - 9.81 * 37.7;

/// Round-off of the static solve and of 500 steps of a system at rest
/// (relative; measured below 1e-12).
const AT_REST: f64 = 1e-9;

/// A static start puts the three-mass pantograph anywhere on the line: at
/// rest in span 2 (x = 57.5 m, between droppers) it presses with its static
/// force from t = 0 (its lower masses at their equilibrium against the held
/// head, the penalty contact at its static penetration) and nothing moves.
#[test]
fn a_static_start_holds_a_chain_anywhere_on_the_line() {
    let sc = common::scene(
        "line_10_spans.toml",
        &[
            "line.spans=2",
            "carrier.0.start=57.5",
            "carrier.0.speed.value=0.0",
            "time.end=0.1",
        ],
    );
    let out = common::run(&sc);
    let force = &out.history.carriers[0].force;
    let worst = force
        .iter()
        .map(|f| (f - PANTOGRAPH_STATIC).abs() / PANTOGRAPH_STATIC)
        .fold(0.0, f64::max);
    println!(
        "static pantograph at x = 57.5 m: force {:.9} N (static {PANTOGRAPH_STATIC:.9} N), worst relative deviation over {} samples {worst:.1e}",
        force[0],
        force.len()
    );
    assert!(worst < AT_REST, "{worst}");
}
