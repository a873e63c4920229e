//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use taut::{Resolved, RunOutput};

/// The repository root (scenes/ and docs/ are relative to it).
pub fn crate_root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// The path of the bundled scene `name` (`scenes/<name>`), as text.
pub fn scene_path(name: &str) -> String {
    crate_root()
        .join("scenes")
        .join(name)
        .to_str()
        .expect("the repository's path is UTF-8")
        .to_string()
}

/// Run the `taut` binary from the repository root.
pub fn taut_bin(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_taut"))
        .current_dir(crate_root())
        .args(args)
        .output()
        .expect("the taut binary runs")
}

/// Run the `taut` binary from the repository root: (exit code, stdout,
/// stderr), the exit code -1 when a signal ended it.
pub fn taut_status(args: &[&str]) -> (i32, String, String) {
    let o = taut_bin(args);
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Run the `taut` binary, asserting success; returns stdout.
pub fn taut_ok(args: &[&str]) -> String {
    let o = taut_bin(args);
    assert!(
        o.status.success(),
        "taut {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).expect("stdout is UTF-8")
}

/// A run's summary.json without its wall time (the one field a rerun
/// changes).
pub fn summary_json(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).expect("summary.json reads");
    let mut v: serde_json::Value = serde_json::from_str(&text).expect("summary.json parses");
    v.as_object_mut().expect("an object").remove("wall_seconds");
    v
}

/// A not-yet-existing output folder `name` in `tmp`.
pub fn out_dir(tmp: &tempfile::TempDir, name: &str) -> PathBuf {
    tmp.path().join(name)
}

/// `taut run SCENE --out DIR --quiet EXTRA…`, asserting failure with an
/// `error: ` line and no output folder; returns stderr.
pub fn run_fails(scene: &str, out: &Path, extra: &[&str]) -> String {
    let mut args = vec!["run", scene, "--out", out.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    let o = taut_bin(&args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success(),
        "taut {args:?} should fail but exited 0"
    );
    assert!(
        stderr.starts_with("error: "),
        "stderr should start with `error: `:\n{stderr}"
    );
    assert!(
        !out.exists(),
        "a failed run must not create its output folder {}",
        out.display()
    );
    stderr
}

/// Load a bundled scene with overrides.
pub fn scene(name: &str, overrides: &[&str]) -> Resolved {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join("scenes")
        .join(name);
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    taut::load_scene(&path, &o).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Run a resolved scene without progress output.
pub fn run(sc: &Resolved) -> RunOutput {
    taut::run(sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("run failed: {e}"))
}

/// The period of a sampled signal: the lag in [min_lag, max_lag] (s) that
/// maximizes its normalized autocorrelation, refined by a parabola through
/// the peak and its neighbours. `dt` is the sample spacing (s).
pub fn period_by_autocorrelation(y: &[f64], dt: f64, min_lag: f64, max_lag: f64) -> f64 {
    let n = y.len();
    let mean = y.iter().sum::<f64>() / n as f64;
    let z: Vec<f64> = y.iter().map(|v| v - mean).collect();
    let corr = |lag: usize| -> f64 {
        let m = n - lag;
        let s: f64 = (0..m).map(|i| z[i] * z[i + lag]).sum();
        s / m as f64
    };
    let lo = (min_lag / dt).round() as usize;
    let hi = (max_lag / dt).round() as usize;
    let (mut best, mut best_lag) = (f64::NEG_INFINITY, lo);
    for lag in lo..=hi {
        let c = corr(lag);
        if c > best {
            best = c;
            best_lag = lag;
        }
    }
    let (cm, c0, cp) = (corr(best_lag - 1), best, corr(best_lag + 1));
    let shift = 0.5 * (cm - cp) / (cm - 2.0 * c0 + cp);
    (best_lag as f64 + shift) * dt
}

/// TARGETS T2's return time of the wave a standing carrier launches at
/// t = 0 (s): the force's plateau level between the launch transient and
/// the first return (0.3–0.5 s), then the first sample in 0.5–0.8 s whose
/// deviation from it reaches half the pulse's peak deviation (a
/// threshold-free pick that does not depend on the ringing level).
pub fn t2_return_time(out: &RunOutput, dt: f64) -> f64 {
    let f = &out.history.carriers[0].force;
    let t = &out.history.t;
    let idx = |time: f64| (time / dt).round() as usize;
    let plateau = &f[idx(0.3)..idx(0.5)];
    let level = plateau.iter().sum::<f64>() / plateau.len() as f64;
    let window = idx(0.5)..idx(0.8);
    let peak = window
        .clone()
        .map(|i| (f[i] - level).abs())
        .fold(0.0, f64::max);
    window
        .clone()
        .find(|&i| (f[i] - level).abs() >= 0.5 * peak)
        .map(|i| t[i])
        .expect("a returning pulse")
}

/// The error text of a scene `text` with `overrides` that must be
/// rejected when resolved (panics if it resolves).
pub fn rejected(text: &str, overrides: &[&str]) -> String {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    match taut::resolve_scene(text, &o) {
        Ok(_) => panic!("expected {overrides:?} to be rejected"),
        Err(e) => e.to_string(),
    }
}

/// `mesh.elements` and `time.step` overrides of a ladder level.
pub fn mesh_and_step(elements: usize, dt: f64) -> Vec<String> {
    vec![
        format!("mesh.elements={elements}"),
        format!("time.step={dt:e}"),
    ]
}

/// The largest |v_h − v*| of a manufactured run of `text` with
/// `overrides`, m, over the recorded t > 0: on the contact wire (its
/// probes and under carrier 0) and on the messenger (its probes; 0
/// without one).
pub fn manufactured_wire_errors(text: &str, overrides: &[String]) -> (f64, f64) {
    let sc = taut::resolve_scene(text, overrides).unwrap();
    let out = taut::run(&sc, &mut |_, _| {}).unwrap();
    let m = sc.manufactured.as_ref().unwrap();
    let h = &out.history;
    let (mut ec, mut em) = (0.0f64, 0.0f64);
    for (i, &t) in h.t.iter().enumerate().skip(1) {
        ec = ec.max((h.carriers[0].w[i] - m.w(0, t)[0]).abs());
        for (p, (_, col)) in h.probes.iter().enumerate() {
            let x = sc.probes[p].1;
            if sc.scene.probes[p].wire == Some(taut::scene::Wire::Messenger) {
                em = em.max((col[i] - m.v_m(x, t)).abs());
            } else {
                ec = ec.max((col[i] - m.v(x, t)).abs());
            }
        }
    }
    (ec, em)
}

/// The one case of `taut verify`'s matrix named `name`, as the slice
/// `verify` takes.
pub fn verify_case(name: &str) -> Vec<taut::study::verify::case::Case> {
    let case: Vec<_> = taut::study::verify::cases::CASES
        .iter()
        .filter(|c| c.name == name)
        .copied()
        .collect();
    assert_eq!(case.len(), 1, "one case named {name}");
    case
}

/// Run the `taut` binary from the repository root under a virtual-memory
/// cap of `kib` KiB (`ulimit -v`) and a time limit of `seconds` (then
/// SIGKILL: exit code 137), so that a regression to unbounded reading or
/// allocation, or a hang, fails a test (an abort, a refused allocation, a
/// kill) instead of taking the machine: (exit code, stdout, stderr).
pub fn taut_capped(kib: u64, seconds: u64, args: &[&str]) -> (i32, String, String) {
    let o = Command::new("bash")
        .current_dir(crate_root())
        .arg("-c")
        .arg(format!(
            "ulimit -v {kib}; exec timeout -s KILL {seconds} \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_taut"))
        .args(args)
        .output()
        .expect("bash runs");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Every file of `dir` (not its subfolders) by name, with its bytes: what
/// a folder held, to compare before and after a command.
pub fn folder_files(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| {
            (
                e.file_name().into_string().unwrap(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

/// The reference case on a small modal basis (J = 100, Δt = 2e-4 s),
/// as `--set` arguments: every run of an accuracy-targeted point takes
/// milliseconds.
pub const SMALL_MODAL: [&str; 8] = [
    "--set",
    "mesh.kind=galerkin",
    "--set",
    "mesh.modes=100",
    "--set",
    "time.step=2e-4",
    "--set",
    "integrator={ method = \"modal_exact\" }",
];
