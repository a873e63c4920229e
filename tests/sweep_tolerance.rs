//! Accuracy-targeted sweeps (`taut sweep … --tolerance EPS --quantity Q`):
//! every point's u_num, the resolution it took, and the sweep's
//! promises kept (resume, shards and merge give the same bytes), through
//! the `taut` binary.

use crate::common;

use std::path::Path;

use common::{out_dir, taut_bin};

/// Three speeds of the reference case on a small modal basis (J = 100): at
/// 120 and 140 m/s the contact is lost in the span (outside the support
/// zones, 4ℓ_b = 0.26 m) and the points are refined, at 100 m/s the
/// in-span P_l is 0 at every pilot; 0.1 s in all.
const MAP: [&str; 8] = common::SMALL_MODAL;

/// `taut sweep scenes/reference.toml --vary … MAP --tolerance TOL ARGS
/// --out DIR`: its status, sweep.csv and stderr.
fn sweep_at(dir: &Path, tol: &str, args: &[&str]) -> (bool, String, String) {
    let mut all = vec![
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "carrier.speed.cruise=100,120,140",
    ];
    all.extend_from_slice(&MAP);
    all.extend_from_slice(&["--tolerance", tol]);
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", dir.to_str().unwrap(), "--quiet"]);
    let o = taut_bin(&all);
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap_or_default();
    (
        o.status.success(),
        csv,
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn sweep(dir: &Path, args: &[&str]) -> (bool, String, String) {
    sweep_at(dir, "0.01", args)
}

#[test]
fn each_point_reports_u_num_and_the_resolution_it_took() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "a");
    let (ok, csv, err) = sweep(&dir, &[]);
    assert!(ok, "{err}");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (u, met, modes, runs) = (
        col("u_num"),
        col("tolerance_met"),
        col("modes_used"),
        col("runs_used"),
    );
    let mut refined = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let un: f64 = cells[u].parse().unwrap();
        assert_eq!(cells[met] == "yes", un <= 0.01, "{line}");
        let j: usize = cells[modes].parse().unwrap();
        assert!(j >= 100 && j.is_multiple_of(100), "{line}");
        let r: usize = cells[runs].parse().unwrap();
        assert!(r >= 5, "{line}");
        refined += usize::from(r > 5);
    }
    // the pilots (5 runs) settle the point without in-span loss, the two
    // with it are refined (a point not met may report its pilots' candidate
    // when no finer one was worth its finest run)
    assert_eq!(refined, 2, "{csv}");
    // the records say the same, and the folder resumes to the same bytes
    let again = sweep(&dir, &[]);
    assert!(again.0, "{}", again.2);
    assert_eq!(again.1, csv);
    // one thread, every run alone: the same bytes (the queue's order and
    // its batches change nothing a point records)
    let alone = sweep(&out_dir(&tmp, "alone"), &["--threads", "1", "--batch", "1"]);
    assert!(alone.0, "{}", alone.2);
    assert_eq!(alone.1, csv);
    // two shards merged are the sweep
    for i in ["0/2", "1/2"] {
        let (ok, _, err) = sweep(&out_dir(&tmp, &format!("s{}", &i[..1])), &["--shard", i]);
        assert!(ok, "{err}");
    }
    let merged = out_dir(&tmp, "merged");
    let o = taut_bin(&[
        "merge",
        out_dir(&tmp, "s0").to_str().unwrap(),
        out_dir(&tmp, "s1").to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(merged.join("sweep.csv")).unwrap(),
        csv
    );
    // a 1-D sweep draws its value ± u_num
    assert!(dir.join("tolerance.svg").exists());
}

/// Bars that hold at the wave speed: a point of P_l (not smooth) met at
/// V0/c = 1.0 is reported at half its family's finest Δt, its u_num at
/// least 3 times what that halving moved it, and covers a run one Δt finer
/// still; no warning says its bar was measured to miss. (Before, the point
/// reported its family's finest run and carried that warning.)
#[test]
fn a_point_met_at_the_wave_speed_is_confirmed_one_step_finer() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "fast");
    let mut all = vec![
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "carrier.speed.cruise=150,170",
    ];
    all.extend_from_slice(&MAP);
    all.extend_from_slice(&[
        "--tolerance",
        "0.02",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    let o_sweep = taut_bin(&all);
    assert!(
        o_sweep.status.success(),
        "{}",
        String::from_utf8_lossy(&o_sweep.stderr)
    );
    let record = |i: usize| -> serde_json::Value {
        let text = std::fs::read_to_string(dir.join(format!("runs/{i:06}.json"))).unwrap();
        serde_json::from_str(&text).unwrap()
    };
    // 150 m/s = 1.0006 c: met
    let v = record(0);
    let a = &v["accuracy"];
    assert!(v["speed_ratio"].as_f64().unwrap() >= 1.0, "{v}");
    assert!(a["met"].as_bool().unwrap(), "{a}");
    let (value, u) = (a["value"].as_f64().unwrap(), a["u_num"].as_f64().unwrap());
    let (modes, dt) = (a["modes"].as_u64().unwrap(), a["dt"].as_f64().unwrap());
    assert!(
        !v["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w.as_str().unwrap().contains("wave speed (V0/c")),
        "{v}"
    );
    // the reported run at (J, Δt), the family's finest at 2Δt, and Δt/2
    let points = tmp.path().join("points.csv");
    std::fs::write(
        &points,
        format!(
            "carrier.speed.cruise,mesh.modes,time.step\n150,{modes},{dt:e}\n150,{modes},{:e}\n150,{modes},{:e}\n",
            2.0 * dt,
            dt / 2.0
        ),
    )
    .unwrap();
    let plain = out_dir(&tmp, "plain");
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--points",
        points.to_str().unwrap(),
        "--set",
        "mesh.kind=galerkin",
        "--set",
        "integrator={ method = \"modal_exact\" }",
        "--out",
        plain.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(plain.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "loss_fraction_span")
        .unwrap();
    let p: Vec<f64> = lines
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect();
    assert_eq!(p[0], value, "the reported run is the run at (J, Δt)");
    // the halving from the family's finest moved it, and the bar holds that
    // three times over and a run one Δt finer still
    assert!(p[1] != p[0], "{p:?}");
    assert!(u >= 3.0 * (p[0] - p[1]).abs(), "u {u}, {p:?}");
    assert!((p[2] - value).abs() <= u, "u {u}, {p:?}");
    // the summary counts points and their runs, not records as runs
    let runs: u64 = (0..2)
        .map(|i| record(i)["accuracy"]["runs"].as_u64().unwrap())
        .sum();
    let stdout = String::from_utf8_lossy(&o_sweep.stdout);
    assert!(
        stdout.contains(&format!("2 points ({runs} runs, 1 within the tolerance)")),
        "{stdout}"
    );
}

#[test]
fn bad_tolerance_flags_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    for (k, (tol, args, names)) in [
        ("-1", vec![], "`--tolerance` = -1"),
        ("x", vec![], "`--tolerance` = x"),
        ("0.01", vec!["--quantity", "speed"], "`--quantity` = speed"),
        ("0.01", vec!["--max-cost", "1"], "`--max-cost` = 1"),
        ("0.01", vec!["--check-refinement"], "`--check-refinement`"),
        ("0.01", vec!["--set", "mesh.modes=98"], "`mesh.modes` = 98"),
    ]
    .into_iter()
    .enumerate()
    {
        let dir = out_dir(&tmp, &format!("bad{k}"));
        let (ok, _, err) = sweep_at(&dir, tol, &args);
        assert!(!ok, "{args:?} was accepted");
        assert!(err.contains(names), "{args:?}: {err}");
    }
}

/// Refinement that knows when to stop: a tolerance no budget reaches is
/// not refined until the budget is spent to find out. Once the error model
/// can say (from the pilots, or from how u_num fell at the first check),
/// the point stops; its record says why (`not_met_because`) and its work is
/// the pilots' and at most one check's; the summary line splits the sweep's
/// work between points met and not met.
#[test]
fn a_point_predicted_beyond_its_budget_stops_when_the_model_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "beyond");
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--vary",
        "carrier.speed.cruise=60,80",
        "--set",
        "mesh.elements=40",
        "--set",
        "time.step=4e-4",
        "--tolerance",
        "1e-9",
        "--quantity",
        "force_mean",
        "--max-cost",
        "8",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
    };
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[col("tolerance_met")], "no", "{line}");
        // the five pilots and at most one check's two new runs
        let runs: usize = cells[col("runs_used")].parse().unwrap();
        assert!(runs <= 7, "{line}");
        let why = &line[line.find("predicted").unwrap_or(line.len())..];
        assert!(
            why.starts_with("predicted cost") || why.starts_with("predicted out of reach"),
            "{line}"
        );
        let used: f64 = cells[col("dof_steps_used")].parse().unwrap();
        assert!(used > 0.0, "{line}");
    }
    assert!(
        stdout.contains("not met 2 (100 %"),
        "the work line splits the time: {stdout}"
    );
    // CPU seconds per point are in timing.csv, beside its work
    let timing = std::fs::read_to_string(dir.join("timing.csv")).unwrap();
    assert!(
        timing.starts_with("index,wall_seconds,cpu_seconds,dof_steps_used\n"),
        "{timing}"
    );
    for line in timing.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        if cfg!(unix) {
            assert!(cells[2].parse::<f64>().unwrap() >= 0.0, "{timing}");
        }
        assert!(cells[3].parse::<f64>().unwrap() > 0.0, "{timing}");
    }
}

/// Where a point's time went: its record lists every run it made, with
/// its role, resolution, work and CPU seconds, summing to the point's own
/// totals; a point not met says why it stopped where it did.
#[test]
fn each_point_records_the_runs_it_made() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = out_dir(&tmp, "runs");
    // 1e-5 is out of reach at --max-cost 16: every point stops not met
    let (ok, _, err) = sweep_at(&dir, "1e-5", &["--max-cost", "16"]);
    assert!(ok, "{err}");
    let mut roles = std::collections::BTreeSet::new();
    for i in 0..3 {
        let text = std::fs::read_to_string(dir.join(format!("runs/{i:06}.json"))).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let a = &v["accuracy"];
        let made = a["runs_made"].as_array().unwrap();
        assert_eq!(made.len() as u64, a["runs"].as_u64().unwrap(), "{a}");
        let work: f64 = made.iter().map(|r| r["dof_steps"].as_f64().unwrap()).sum();
        assert_eq!(work, a["dof_steps"].as_f64().unwrap(), "{a}");
        if let Some(cpu) = v["cpu_seconds"].as_f64() {
            let sum: f64 = made
                .iter()
                .map(|r| r["cpu_seconds"].as_f64().unwrap())
                .sum();
            assert!((sum - cpu).abs() <= 1e-9 * cpu.max(1.0), "{sum} {cpu}");
        }
        let pilots = made.iter().filter(|r| r["role"] == "pilot").count();
        let reported: Vec<_> = made.iter().filter(|r| r["role"] == "reported").collect();
        assert!(pilots >= 4, "{a}");
        assert_eq!(reported.len(), 1, "{a}");
        assert_eq!(reported[0]["dt"], a["dt"]);
        assert_eq!(reported[0]["modes"], a["modes"]);
        roles.extend(made.iter().map(|r| r["role"].as_str().unwrap().to_string()));
        assert!(!a["met"].as_bool().unwrap(), "{a}");
        let why = a["not_met"].as_str().unwrap();
        assert!(
            why.contains("--max-cost 16") || why.contains("checks"),
            "{why}"
        );
    }
    assert!(roles.contains("check"), "{roles:?}");
}
