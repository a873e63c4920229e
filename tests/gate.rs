//! `taut gate` on the project's own golden suite (`golden/*.json`), and on a
//! tampered copy: a regression must turn the gate red (exit code 1, a JUnit
//! failure) and `--update` must accept the new values. Each golden case's
//! rounded values and integer statistics are also pinned as insta snapshots
//! in `golden/` (never raw float bits).

use std::path::{Path, PathBuf};
use std::process::Command;

use taut::study::gate::{gate, quantity, read_case, run_case};

const BIN: &str = env!("CARGO_BIN_EXE_taut");

fn golden() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("golden")
}

#[test]
fn the_golden_suite_passes() {
    let r = gate(&golden(), false, &mut |_, _, _| {}).unwrap();
    for c in r.checks.iter().filter(|c| !c.pass) {
        eprintln!("{c:?}");
    }
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(r.passed());
    assert!(
        r.checks.len() >= 20,
        "the suite gates a meaningful number of quantities"
    );
}

/// A copy of one case in a temporary suite, with the scene path made absolute.
fn tampered_suite(tmp: &Path, factor: f64) -> PathBuf {
    let src = golden().join("reference.json");
    let mut case: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(src).unwrap()).unwrap();
    let scene = golden().join(case["scene"].as_str().unwrap());
    case["scene"] = serde_json::Value::String(scene.to_string_lossy().into_owned());
    let v = case["quantities"]["force_mean"]["value"].as_f64().unwrap();
    case["quantities"]["force_mean"]["value"] = serde_json::json!(v * factor);
    let suite = tmp.join("suite");
    std::fs::create_dir_all(&suite).unwrap();
    std::fs::write(
        suite.join("reference.json"),
        serde_json::to_string_pretty(&case).unwrap(),
    )
    .unwrap();
    suite
}

#[test]
fn a_regression_turns_the_gate_red_and_update_accepts_it() {
    let tmp = tempfile::tempdir().unwrap();
    // 1 % off the reference mean force: far outside its 1e-6 tolerance
    let suite = tampered_suite(tmp.path(), 1.01);
    let out = tmp.path().join("out");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "gate",
            suite.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        args.extend_from_slice(extra);
        Command::new(BIN).args(&args).output().unwrap()
    };
    let red = run(&[]);
    assert_eq!(
        red.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&red.stdout)
    );
    let table = String::from_utf8_lossy(&red.stdout);
    assert!(
        table.contains("force_mean") && table.contains("FAIL"),
        "{table}"
    );
    let junit = std::fs::read_to_string(out.join("junit.xml")).unwrap();
    assert!(
        junit.contains("<testsuites") && junit.contains("<failure message="),
        "{junit}"
    );
    assert!(junit.contains("failures=\"1\""));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("gate.json")).unwrap()).unwrap();
    assert_eq!(json["passed"], false);

    let upd = run(&["--update"]);
    assert!(upd.status.success());
    assert!(String::from_utf8_lossy(&upd.stdout).contains("UPDATED"));
    let green = run(&[]);
    assert!(
        green.status.success(),
        "{}",
        String::from_utf8_lossy(&green.stdout)
    );
}

#[test]
fn a_case_with_an_unknown_quantity_or_no_reason_is_rejected() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.json");
    std::fs::write(
        &bad,
        r#"{"description": "x", "scene": "s.toml", "quantities": {"force_avg": {"value": 1, "abs": 0, "rel": 0, "reason": "r"}}}"#,
    )
    .unwrap();
    let e = read_case(&bad).unwrap_err().to_string();
    assert!(e.contains("force_avg") && e.contains("force_mean"), "{e}");
    std::fs::write(
        &bad,
        r#"{"description": "x", "scene": "s.toml", "quantities": {"steps": {"value": 1, "abs": 0, "rel": 0, "reason": " "}}}"#,
    )
    .unwrap();
    assert!(read_case(&bad).unwrap_err().to_string().contains("reason"));
}

#[test]
fn golden_cases_are_pinned_as_rounded_snapshots() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(golden())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    for path in files {
        let case = read_case(&path).unwrap();
        let out = run_case(&path, &case).unwrap();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        // 6 significant digits: far above round-off, far below any model change
        let sig = |x: f64| {
            if x == 0.0 || !x.is_finite() {
                return x;
            }
            let p = 10f64.powi(5 - x.abs().log10().floor() as i32);
            (x * p).round() / p
        };
        let stats: Vec<serde_json::Value> = out
            .stats
            .iter()
            .map(|s| {
                serde_json::json!({
                    "contact_switches": s.contact_switches,
                    "loss_intervals": s.loss_intervals.len(),
                    "loss_fraction": sig(s.loss_fraction),
                    "force_mean": sig(s.force.mean),
                    "force_min": sig(s.force.min),
                })
            })
            .collect();
        let pinned = serde_json::json!({
            "steps": out.steps,
            "dofs": out.dofs,
            "carriers": stats,
            "final_w": sig(quantity(&out, "final_w").unwrap()),
        });
        insta::with_settings!({
            snapshot_path => golden(),
            prepend_module_to_snapshot => false,
            description => format!("golden/{name}.json: rounded values (6 significant digits) and integer statistics"),
        }, {
            insta::assert_yaml_snapshot!(format!("case_{name}"), pinned);
        });
    }
}
