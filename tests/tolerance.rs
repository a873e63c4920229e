//! Accuracy-targeted runs (`taut run SCENE --tolerance EPS`): one engine
//! with `taut sweep --tolerance`. A scene run alone and the same point of
//! a one-point sweep reach the same resolution, value and u_num, or the
//! same refusal for the same stated reason; the run's outputs carry a
//! u_num on every result; bad flags are refused by name (docs/accuracy.md).

use crate::common;

use std::path::Path;

use common::{out_dir, run_fails, taut_bin};

use serde_json::Value;

/// The reference case on a small modal basis ([`common::SMALL_MODAL`]). On
/// `force_mean` with EPS = 0.5 N the three speeds take the three paths:
/// 100 m/s met after one check, 120 m/s met, 140 m/s not met (its
/// differences grow: a 3·Δ_M bar wider than EPS).
const CHEAP: [&str; 8] = common::SMALL_MODAL;

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `taut run … --set carrier.speed.cruise=V --tolerance …`: Ok(summary's
/// `accuracy`) or Err(stderr).
fn run_at(dir: &Path, speed: &str, args: &[&str]) -> Result<Value, String> {
    let set = format!("carrier.speed.cruise={speed}");
    let mut all = vec!["run", "scenes/reference.toml", "--set", &set];
    all.extend_from_slice(&CHEAP);
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", dir.to_str().unwrap(), "--quiet"]);
    let o = taut_bin(&all);
    if o.status.success() {
        Ok(json(&dir.join("summary.json"))["accuracy"].clone())
    } else {
        Err(String::from_utf8_lossy(&o.stderr).into_owned())
    }
}

/// The same point as a one-point `taut sweep --points`: its record.
fn sweep_at(dir: &Path, speed: &str, args: &[&str]) -> Value {
    std::fs::create_dir_all(dir.parent().unwrap()).unwrap();
    let points = dir.with_extension("csv");
    std::fs::write(&points, format!("carrier.speed.cruise\n{speed}\n")).unwrap();
    let mut all = vec![
        "sweep",
        "scenes/reference.toml",
        "--points",
        points.to_str().unwrap(),
    ];
    all.extend_from_slice(&CHEAP);
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", dir.to_str().unwrap(), "--quiet"]);
    let o = taut_bin(&all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    json(&dir.join("runs/000000.json"))
}

#[test]
fn run_and_a_one_point_sweep_give_the_same_answer_or_the_same_refusal() {
    let tmp = tempfile::tempdir().unwrap();
    let args = ["--tolerance", "0.5", "--quantity", "force_mean"];
    let mut paths = Vec::new();
    for speed in ["100", "120", "140"] {
        let record = sweep_at(&out_dir(&tmp, &format!("s{speed}")), speed, &args);
        let point = record["accuracy"].as_object().unwrap();
        match run_at(&out_dir(&tmp, &format!("r{speed}")), speed, &args) {
            Ok(acc) => {
                // every field of the sweep point's accuracy, to the bit:
                // value, u_num, N, J, Δt, runs, estimator, checks, every
                // run made (but its CPU seconds, a measured time), …
                let timeless = |v: &serde_json::Value| -> serde_json::Value {
                    let mut v = v.clone();
                    for r in v.as_array_mut().into_iter().flatten() {
                        r.as_object_mut().map(|o| o.remove("cpu_seconds"));
                    }
                    v
                };
                for (k, v) in point {
                    let (a, v) = match k.as_str() {
                        "runs_made" => (timeless(&acc[k]), timeless(v)),
                        _ => (acc[k].clone(), v.clone()),
                    };
                    assert_eq!(a, v, "{speed} m/s: `{k}` differs");
                }
                assert_eq!(point["met"], true);
                // and the run's own summary is the reported run's
                let s = json(&out_dir(&tmp, &format!("r{speed}")).join("summary.json"));
                assert_eq!(
                    s["carriers"][0]["force"]["mean"], point["value"],
                    "{speed} m/s: the summary is of the reported run"
                );
                paths.push(if point["checks"] == 0 {
                    "pilots"
                } else {
                    "checks"
                });
            }
            Err(e) => {
                assert_eq!(point["met"], false, "{speed} m/s: the run refused: {e}");
                let why = point["not_met"].as_str().unwrap();
                for part in [
                    "--tolerance 5e-1 on --quantity force_mean",
                    "not met: ",
                    why,
                    "tolerance_met = no",
                    "--max-cost",
                ] {
                    assert!(e.contains(part), "{speed} m/s: lacks {part:?}: {e}");
                }
                paths.push("refused");
            }
        }
    }
    // the three paths are each taken (the scene's comment says which)
    assert_eq!(paths, ["checks", "checks", "refused"]);
}

#[test]
fn a_budget_too_small_is_the_same_refusal_in_both() {
    // --max-cost 2 leaves no check after the pilots (1.81 runs' worth)
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "--tolerance",
        "0.5",
        "--quantity",
        "force_mean",
        "--max-cost",
        "2",
    ];
    let record = sweep_at(&out_dir(&tmp, "s"), "100", &args);
    let why = record["accuracy"]["not_met"].as_str().unwrap();
    assert!(why.contains("--max-cost 2"), "{why}");
    assert!(!why.contains("bounces"), "no P_l hint on force_mean: {why}");
    let e = run_at(&out_dir(&tmp, "r"), "100", &args).unwrap_err();
    assert!(e.contains(why), "{e}");
    assert!(
        !out_dir(&tmp, "r").exists(),
        "a refused run leaves no folder"
    );
}

/// P_l in span not met where its error is mostly Δt's (T = 38190 N,
/// V0 = 149 m/s, J = 800 to 3200: the split gives Δt most of the last
/// check's error) names the bounces and the quantity that leaves them out.
#[test]
fn p_l_not_met_by_its_delta_t_part_points_to_its_sustained_part() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "r");
    let o = taut_bin(&[
        "run",
        "scenes/reference.toml",
        "--set",
        "mesh.kind=galerkin",
        "--set",
        "mesh.modes=800",
        "--set",
        "time.step=6.25e-5",
        "--set",
        "integrator={ method = \"modal_exact\" }",
        "--set",
        "beam.tension=38190",
        "--set",
        "carrier.speed.cruise=149",
        "--tolerance",
        "0.002",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{e}");
    for part in [
        "its error is mostly Δt's",
        "contact_loss.md §3",
        "--quantity loss_fraction_span_sustained",
    ] {
        assert!(e.contains(part), "lacks {part:?}: {e}");
    }
}

#[test]
fn tolerance_run_writes_a_u_num_next_to_every_result() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "a");
    let set = "carrier.speed.cruise=120";
    let mut all = vec!["run", "scenes/reference.toml", "--set", set];
    all.extend_from_slice(&CHEAP);
    all.extend_from_slice(&["--tolerance", "0.5", "--quantity", "force_mean"]);
    all.extend_from_slice(&["--out", dir.to_str().unwrap()]);
    let o = taut_bin(&all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for part in [
        "accuracy force_mean ≤ 5e-1 N requested",
        "chosen   J = ",
        "--max-cost 64",
        "force mean λ",
        "(u_num, ",
    ] {
        assert!(stdout.contains(part), "lacks {part:?}:\n{stdout}");
    }
    for f in ["history.csv", "summary.json", "force.svg", "accuracy.csv"] {
        assert!(dir.join(f).is_file(), "{f} written");
    }
    let s = json(&dir.join("summary.json"));
    let acc = &s["accuracy"];
    assert_eq!(acc["quantity"], "force_mean");
    assert_eq!(acc["tolerance"].as_f64(), Some(0.5));
    assert_eq!(acc["max_cost"].as_f64(), Some(64.0));
    assert!(acc["u_num"].as_f64().unwrap() <= 0.5);
    assert_eq!(
        acc["modes"], s["scene"]["mesh"]["modes"],
        "the summary's scene is the reported run's"
    );
    // every result a sweep can target has a u_num or says why not
    let results = acc["results"].as_array().unwrap();
    assert_eq!(results.len(), taut::study::tolerance::results().len());
    for r in results {
        assert!(r["u_num"].is_f64() || r["behaviour"].is_string(), "{r}");
    }
    // and the target's own is the run's u_num
    let own = results.iter().find(|r| r["name"] == "force_mean").unwrap();
    assert_eq!(own["u_num"], acc["u_num"]);
    let csv = std::fs::read_to_string(dir.join("accuracy.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        taut::report::ACCURACY_COLUMNS.join(",")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(
        rows.len() as u64,
        acc["runs"].as_u64().unwrap(),
        "a row per run"
    );
    assert_eq!(
        rows.iter().filter(|r| r.starts_with("reported,")).count(),
        1
    );
    // and `taut report` reads the run's u_num
    let page = tmp.path().join("report.html");
    taut::app::report(&taut::app::ReportRequest {
        dirs: vec![dir.clone()],
        out: Some(page.clone()),
    })
    .unwrap();
    let html = std::fs::read_to_string(page).unwrap();
    assert!(
        html.contains("accuracy target on force_mean") && html.contains("(u_num, "),
        "the report's accuracy line"
    );
}

// ---- bad input ------------------------------------------------------------

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "message lacks {p:?}:\n{msg}");
    }
}

#[test]
fn bad_tolerance_flags_name_the_flag_the_value_and_the_range() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = "scenes/moving_force_beam.toml";
    for bad in ["0", "-1", "NaN", "inf", "abc"] {
        let err = run_fails(scene, &out_dir(&tmp, "t"), &["--tolerance", bad]);
        assert_mentions(&err, &["`--tolerance`", &format!("= {bad}"), "> 0"]);
    }
    let err = run_fails(
        scene,
        &out_dir(&tmp, "q"),
        &["--tolerance", "1e-2", "--quantity", "speed"],
    );
    assert_mentions(
        &err,
        &["`--quantity` = speed", "loss_fraction_span", "force_mean"],
    );
    for bad in ["1", "-3", "x"] {
        let err = run_fails(
            scene,
            &out_dir(&tmp, "m"),
            &["--tolerance", "1e-2", "--max-cost", bad],
        );
        assert_mentions(&err, &["`--max-cost`", &format!("= {bad}"), "≥ 2"]);
    }
    // --quantity or --max-cost alone: clap says they need --tolerance
    for extra in [["--quantity", "force_mean"], ["--max-cost", "8"]] {
        let o = taut_bin(&["run", scene, "--quiet", extra[0], extra[1]]);
        assert!(!o.status.success());
        assert_mentions(&String::from_utf8_lossy(&o.stderr), &["--tolerance"]);
    }
}

#[test]
fn a_level_the_pilots_cannot_coarsen_is_refused_before_any_run() {
    // the pilots run the scene 2 and 4 times coarser: N = 402 is not a
    // multiple of 4
    let tmp = tempfile::tempdir().unwrap();
    let err = run_fails(
        "scenes/moving_force_beam.toml",
        &out_dir(&tmp, "n"),
        &["--tolerance", "1e-2", "--set", "mesh.elements=402"],
    );
    assert_mentions(&err, &["`mesh.elements` = 402", "multiple of 4"]);
}
