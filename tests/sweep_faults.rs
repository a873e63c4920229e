//! Fault injection for `taut sweep` and `taut merge`: runs that stop, a
//! sweep killed mid-way, two sweeps on one folder, records that are not the
//! sweep's, and axes that change nothing. The promise checked: a sweep
//! always finishes its table (stopped points are rows with their error and
//! a non-zero exit), loses nothing when killed, and never mixes results.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use taut::study::sweep::{Axis, SweepSpec, claim, merge, sweep};

const BIN: &str = env!("CARGO_BIN_EXE_taut");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// Longest a test waits for a background sweep to reach a state; far above
/// the seconds these sweeps take, so only a hang reaches it.
const PATIENCE: Duration = Duration::from_secs(120);

fn scene_path() -> String {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join("scenes/reference.toml")
        .to_string_lossy()
        .into_owned()
}

/// Short runs: the first 0.2 s of the reference case on a coarse mesh.
fn spec(axes: &[&str]) -> SweepSpec {
    SweepSpec {
        scene_text: REFERENCE.to_string(),
        set: vec![
            "mesh.elements=60".into(),
            "time.step=2e-4".into(),
            "time.end=0.2".into(),
        ],
        axes: axes
            .iter()
            .map(|a| Axis::parse(a, false).unwrap())
            .collect(),
        check_refinement: false,
        paired: false,
        tolerance: None,
    }
}

fn tables(dir: &Path) -> Vec<Vec<u8>> {
    ["sweep.csv", "sweep_force.csv", "sweep_loss.csv"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect()
}

fn taut(args: &[&str]) -> std::process::Output {
    Command::new(BIN).args(args).output().unwrap()
}

/// The bilateral α-level contact diverges on a moving carrier (MODEL §5),
/// later the slower it moves: at 0.1 s the slowest point has finished and
/// the two faster ones have stopped.
fn stopping_sweep(out: &Path) -> std::process::Output {
    taut(&[
        "sweep",
        &scene_path(),
        "--vary",
        "speed_ratio=0.4:1.2:3",
        "--set",
        "contact.placement=alpha",
        "--set",
        "contact.kind=bilateral",
        "--set",
        "time.end=0.1",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ])
}

#[test]
fn a_sweep_whose_runs_stop_writes_its_tables_and_resume_keeps_the_stopped_points() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let o = stopping_sweep(&out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "some points failed: {stderr}");
    assert!(stderr.contains("2 of 3 points stopped"), "{stderr}");
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let error = header.iter().position(|h| *h == "error").unwrap();
    assert_eq!(
        rows[0].split(',').nth(error),
        Some(""),
        "point 0 finished: {}",
        rows[0]
    );
    for r in &rows[1..] {
        assert!(r.contains("run diverged at step"), "{r}");
    }
    for map in ["force_map.svg", "loss_map.svg"] {
        let svg = std::fs::read_to_string(out.join(map)).unwrap();
        assert!(svg.contains("stopped with an error"), "{map} marks them");
    }

    // resume: nothing is run again (the stops are deterministic), same tables
    let mtimes = || -> Vec<_> {
        (0..3)
            .map(|i| {
                std::fs::metadata(out.join(format!("runs/{i:06}.json")))
                    .unwrap()
                    .modified()
                    .unwrap()
            })
            .collect()
    };
    let before = mtimes();
    let first = tables(&out);
    std::thread::sleep(Duration::from_millis(20));
    let o = stopping_sweep(&out);
    assert_eq!(o.status.code(), Some(1));
    let after = mtimes();
    assert_eq!(before, after, "a resumed sweep reran a stopped point");
    assert_eq!(first, tables(&out));
}

#[test]
fn a_killed_sweep_resumes_to_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let args = |out: &Path| -> Vec<String> {
        [
            "sweep",
            &scene_path(),
            "--vary",
            "speed_ratio=0.5:1.0:24",
            "--set",
            "mesh.elements=200",
            "--set",
            "time.end=0.3",
            "--threads",
            "1",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect()
    };
    let whole = tmp.path().join("whole");
    assert!(
        Command::new(BIN)
            .args(args(&whole))
            .output()
            .unwrap()
            .status
            .success()
    );

    let killed = tmp.path().join("killed");
    let mut child = Command::new(BIN)
        .args(args(&killed))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let runs = killed.join("runs");
    let count = || {
        std::fs::read_dir(&runs)
            .map(|d| {
                d.filter(|e| {
                    e.as_ref()
                        .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "json"))
                })
                .count()
            })
            .unwrap_or(0)
    };
    while count() < 3 && start.elapsed() < PATIENCE {
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let finished = count();
    if killed.join("sweep.csv").exists() {
        // it won the race: take some of its points away as a kill would have
        std::fs::remove_file(killed.join("sweep.csv")).unwrap();
        for i in (1..24).step_by(2) {
            std::fs::remove_file(runs.join(format!("{i:06}.json"))).unwrap();
        }
    } else {
        assert!(finished < 24, "killed before the end");
    }
    assert!(
        Command::new(BIN)
            .args(args(&killed))
            .output()
            .unwrap()
            .status
            .success()
    );
    assert_eq!(tables(&whole), tables(&killed));
}

#[test]
fn two_sweeps_on_one_folder_never_mix() {
    let tmp = tempfile::tempdir().unwrap();
    let a = spec(&["speed_ratio=0.5:0.6:2"]);
    // a sweep holding the folder refuses any other, the same spec included
    {
        let _held = claim(tmp.path()).unwrap();
        for other in [&a, &spec(&["speed_ratio=0.5:0.7:2"])] {
            let e = sweep(other, tmp.path(), None, &|_, _| {})
                .unwrap_err()
                .to_string();
            assert!(e.contains("in use by another command"), "{e}");
        }
        let e = merge(&[tmp.path().to_path_buf()], tmp.path())
            .unwrap_err()
            .to_string();
        assert!(e.contains("in use by another command"), "{e}");
    }
    // released with its holder: now the folder is free
    sweep(&a, tmp.path(), None, &|_, _| {}).unwrap();

    // two processes started together on one folder: at most one writes it,
    // and what it writes is its own sweep's, whole
    let out = tmp.path().join("race");
    let run = |range: &str| {
        Command::new(BIN)
            .args([
                "sweep",
                &scene_path(),
                "--vary",
                range,
                "--set",
                "mesh.elements=100",
                "--set",
                "time.end=0.3",
                "--quiet",
                "--out",
                out.to_str().unwrap(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (p, q) = (run("speed_ratio=0.5:0.9:8"), run("speed_ratio=0.5:1.0:8"));
    let (p, q) = (p.wait_with_output().unwrap(), q.wait_with_output().unwrap());
    let ok: Vec<bool> = [&p, &q].iter().map(|o| o.status.success()).collect();
    assert!(ok.iter().any(|&s| s), "one of them runs");
    for o in [&p, &q] {
        if !o.status.success() {
            let e = String::from_utf8_lossy(&o.stderr);
            assert!(
                e.contains("in use by another command") || e.contains("holds a different sweep"),
                "{e}"
            );
        }
    }
    let winner = if ok[0] { "0.9" } else { "1.0" };
    let json = std::fs::read_to_string(out.join("sweep.json")).unwrap();
    assert!(json.contains(&format!("\"stop\": {winner}")), "{json}");
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 9);
}

#[test]
fn records_that_are_not_the_sweeps_are_refused_on_resume_and_merge() {
    let tmp = tempfile::tempdir().unwrap();
    let a = spec(&["speed_ratio=0.5:0.7:3"]);
    let dir = tmp.path().join("a");
    let whole = sweep(&a, &dir, None, &|_, _| {}).unwrap();
    let runs = dir.join("runs");

    // a record under the wrong index
    std::fs::copy(runs.join("000001.json"), runs.join("000000.json")).unwrap();
    let e = sweep(&a, &dir, None, &|_, _| {}).unwrap_err().to_string();
    assert!(
        e.contains("000000.json") && e.contains("holds point 1"),
        "{e}"
    );

    // a folder whose sweep.json is gone, holding another sweep's records
    std::fs::remove_file(runs.join("000000.json")).unwrap();
    std::fs::remove_file(dir.join("sweep.json")).unwrap();
    let b = spec(&["speed_ratio=0.5:0.8:3"]);
    let e = sweep(&b, &dir, None, &|_, _| {}).unwrap_err().to_string();
    assert!(e.contains("belongs to sweep"), "{e}");

    // its own records are taken back, and an empty one (a crash's leftover)
    // is run again
    std::fs::write(runs.join("000002.json"), "").unwrap();
    let again = sweep(&a, &dir, None, &|_, _| {}).unwrap();
    let strip = |r: &[taut::study::sweep::SweepRecord]| -> Vec<_> {
        r.iter().map(|r| r.without_timing()).collect()
    };
    assert_eq!(strip(&whole), strip(&again));

    // merge checks every shard's records the same way
    let (s0, s1) = (tmp.path().join("s0"), tmp.path().join("s1"));
    for (i, s) in [&s0, &s1].iter().enumerate() {
        let shard = taut::study::sweep::Shard::parse(&format!("{i}/2")).unwrap();
        sweep(&a, s, Some(shard), &|_, _| {}).unwrap();
    }
    std::fs::copy(s1.join("runs/000001.json"), s0.join("runs/000001.json")).unwrap();
    let mut tampered: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(s0.join("runs/000001.json")).unwrap())
            .unwrap();
    tampered["force_max"] = serde_json::json!(1e6);
    std::fs::write(s0.join("runs/000001.json"), tampered.to_string()).unwrap();
    let e = merge(&[s0.clone(), s1.clone()], &tmp.path().join("m"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("point 1 differs"), "{e}");
    std::fs::remove_file(s0.join("runs/000001.json")).unwrap();
    std::fs::copy(runs.join("000000.json"), s0.join("runs/000002.json")).unwrap();
    let e = merge(&[s0, s1], &tmp.path().join("m2"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("holds point 0"), "{e}");
}

#[test]
fn integer_keys_sweep_on_whole_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    for (axis, log, want) in [
        (
            "mesh.elements=40:100:4",
            false,
            vec![40.0, 60.0, 80.0, 100.0],
        ),
        (
            "mesh.elements=25:400:5",
            true,
            vec![25.0, 50.0, 100.0, 200.0, 400.0],
        ),
    ] {
        let mut s = spec(&[]);
        s.set.retain(|o| !o.starts_with("mesh.elements"));
        s.set.push("time.end=0.02".into());
        s.axes = vec![Axis::parse(axis, log).unwrap()];
        let dir = tmp.path().join(if log { "log" } else { "lin" });
        let r = sweep(&s, &dir, None, &|_, _| {}).unwrap();
        let got: Vec<f64> = r.iter().map(|r| r.values[0]).collect();
        assert_eq!(got, want);
        assert!(r.iter().all(|r| r.error.is_none()), "{:?}", r[0].error);
    }
    // a value between whole numbers is named with its point
    let mut s = spec(&["mesh.elements=100:101:3"]);
    s.set.retain(|o| !o.starts_with("mesh.elements"));
    let e = s.validate().unwrap_err().to_string();
    assert!(
        e.contains("mesh.elements") && e.contains("100.5") && e.contains("sweep point 1"),
        "{e}"
    );
}

#[test]
fn axes_that_change_nothing_are_refused() {
    let cases: [(&[&str], &[&str], &str); 6] = [
        (
            &["speed_ratio=0.4:1.2:3", "speed_ratio=0.5:1:2"],
            &[],
            "is given twice",
        ),
        (&["beam.length=50:50:3"], &[], "changes nothing"),
        // the ratio and the plain key set one value (before, the
        // ratio overrode it, and the plain axis changed nothing)
        (
            &["carrier.0.mass=1:2:2", "mass_ratio=0.01:0.02:2"],
            &[],
            "both set `carrier.0.mass`",
        ),
        (
            &["mass_ratio=0.01:0.02:2"],
            &[
                "carrier.0={ force = 100.0, side = \"below\", start = 0.0, speed = { profile = \"constant\", value = 75.0 } }",
            ],
            "has none (only moving forces)",
        ),
        (&["stiffness_ratio=1:2:2"], &["beam.tension=0"], "T = 0"),
        (&["speed_ratio=0.5:1:2"], &["beam.tension=0"], "T = 0"),
    ];
    for (axes, set, want) in cases {
        let mut s = spec(axes);
        s.set.extend(set.iter().map(|x| x.to_string()));
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains(want), "{axes:?} {set:?}: {e}");
    }
    let e = spec(&["speed_ratio=0:1:100000", "time.end=0.1:0.2:2"])
        .validate()
        .unwrap_err()
        .to_string();
    assert!(e.contains("at most 100000 points"), "{e}");
}
