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
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("golden")
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

/// `taut gate SUITE --out OUT --quiet`: (exit code, stdout + stderr).
fn gate_cli(suite: &Path, out: &Path) -> (Option<i32>, String) {
    let o = Command::new(BIN)
        .args([
            "gate",
            suite.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), text)
}

/// The reference case, its scene path made absolute, as JSON text.
fn reference_case_text() -> String {
    let tmp = tempfile::tempdir().unwrap();
    let suite = tampered_suite(tmp.path(), 1.0);
    std::fs::read_to_string(suite.join("reference.json")).unwrap()
}

#[test]
fn an_empty_suite_fails() {
    let tmp = tempfile::tempdir().unwrap();
    let suite = tmp.path().join("empty");
    std::fs::create_dir_all(&suite).unwrap();
    // a file that is not a case does not make the suite non-empty
    std::fs::write(suite.join("README.md"), "cases go here").unwrap();
    let e = gate(&suite, false, &mut |_, _, _| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("SUITE_DIR") && e.contains("at least one case"),
        "{e}"
    );
    let (code, text) = gate_cli(&suite, &tmp.path().join("out"));
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("at least one case file"), "{text}");
}

#[test]
fn a_case_with_no_quantities_fails() {
    let tmp = tempfile::tempdir().unwrap();
    let suite = tmp.path().join("suite");
    std::fs::create_dir_all(&suite).unwrap();
    let mut case: serde_json::Value = serde_json::from_str(&reference_case_text()).unwrap();
    case["quantities"] = serde_json::json!({});
    let file = suite.join("nothing.json");
    std::fs::write(&file, case.to_string()).unwrap();
    let e = read_case(&file).unwrap_err().to_string();
    assert!(
        e.contains("nothing.json: quantities") && e.contains("at least one quantity"),
        "{e}"
    );
    let out = tmp.path().join("out");
    let (code, text) = gate_cli(&suite, &out);
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("at least one quantity"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("gate.json")).unwrap()).unwrap();
    assert_eq!(json["passed"], false);
    assert!(
        std::fs::read_to_string(out.join("junit.xml"))
            .unwrap()
            .contains("<error message=")
    );
}

#[test]
fn a_duplicated_key_is_an_error_naming_the_key_and_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let suite = tmp.path().join("suite");
    std::fs::create_dir_all(&suite).unwrap();
    // a tampered first copy of force_mean's value, the true one after it:
    // serde_json alone keeps the second and the gate would pass
    let text = reference_case_text();
    let at = text.find("\"force_mean\": {").unwrap() + "\"force_mean\": {".len();
    let tampered = format!("{}\n      \"value\": 1e9,{}", &text[..at], &text[at..]);
    let file = suite.join("reference.json");
    std::fs::write(&file, tampered).unwrap();
    let e = read_case(&file).unwrap_err().to_string();
    assert!(
        e.contains("quantities.force_mean.value") && e.contains("reference.json"),
        "{e}"
    );
    let (code, text) = gate_cli(&suite, &tmp.path().join("out"));
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("quantities.force_mean.value"), "{text}");
    // a top-level key too
    let text = reference_case_text().replacen('{', "{\"scene\": \"x.toml\",", 1);
    std::fs::write(&file, text).unwrap();
    let e = read_case(&file).unwrap_err().to_string();
    assert!(e.contains("reference.json: scene`"), "{e}");
}

/// A case whose `scene` names a file that is not a scene: the file is named
/// and refused, its content in no message, gate.json or junit.xml.
#[test]
fn a_scene_that_is_not_a_scene_file_is_refused_and_never_reproduced() {
    let tmp = tempfile::tempdir().unwrap();
    let secrets = tmp.path().join("secrets");
    std::fs::create_dir_all(&secrets).unwrap();
    let files = [
        ("passwd", "root:x:0:0:SECRET_A:/root:/bin/bash\n"),
        ("passwd.toml", "root:x:0:0:SECRET_B:/root:/bin/bash\n"),
        ("env.toml", "SECRET_C = \"hunter2\"\n"),
    ];
    for (name, content) in files {
        std::fs::write(secrets.join(name), content).unwrap();
        let suite = tmp.path().join(format!("suite-{name}"));
        std::fs::create_dir_all(&suite).unwrap();
        let mut case: serde_json::Value = serde_json::from_str(&reference_case_text()).unwrap();
        let target = secrets.join(name);
        case["scene"] = serde_json::Value::String(target.to_string_lossy().into_owned());
        std::fs::write(suite.join("case.json"), case.to_string()).unwrap();
        let out = tmp.path().join(format!("out-{name}"));
        let (code, text) = gate_cli(&suite, &out);
        assert_eq!(code, Some(1), "{text}");
        assert!(text.contains(target.to_str().unwrap()), "{name}: {text}");
        let written = [
            text,
            std::fs::read_to_string(out.join("gate.json")).unwrap(),
            std::fs::read_to_string(out.join("junit.xml")).unwrap(),
        ];
        for w in written {
            for secret in ["SECRET", "hunter2", "root:x"] {
                assert!(!w.contains(secret), "{name}: content reproduced: {w}");
            }
        }
    }
}
