//! A run's memory estimate is an upper bound of what the `taut` binary
//! holds: each case runs `taut run` in a child process
//! and compares its peak resident size (`wait4`'s `ru_maxrss`, the kernel's
//! high-water mark of the child alone) with the estimate validation checks
//! against the budget ([`taut::Resolved::memory_estimate`]), plus the
//! binary's own baseline. One case per term the estimate once left out or
//! undercounted: a long history (a copy of one of its columns was taken to
//! label the plot's axis), the modal eigenproblem (faer's workspace: ≈ 5 n²
//! doubles, counted as 4 n²), many probes over more rows than
//! `history.csv` formats at a time (that block is a second copy of its
//! rows), tension-only droppers (their dense responses and the contact
//! problem's rows were outside the estimate) and a large field (its table
//! took four copies while written). Linux only (the figures are the
//! kernel's).
//!
//! The kernel's figure for a child is the larger of its own peak and its
//! parent's at the moment it was started (exec records the memory it
//! replaces, which a child started by vfork shares with this process). This
//! process stays at a few MiB — unless a test panics and symbolizes a
//! backtrace (≈ 35 MiB) — so the cases run one after the other in one test,
//! which checks this process's own peak before each, and report every
//! failure at the end.

#![cfg(target_os = "linux")]

mod common;

use std::process::{Command, Stdio};

/// The binary's resident size before a run allocates anything of its own:
/// code and data pages, the C library, the main thread's stack and the
/// allocator's arenas. Measured 6.4–6.7 MiB for a 100-step run (the test
/// checks it stays under this); 12 MiB leaves
/// room for another C library or allocator without hiding any term of the
/// cases below (each at least 16 MiB).
const BASELINE_SLACK_BYTES: u64 = 12 << 20;

const MIB: f64 = 1024.0 * 1024.0;

/// Peak resident size, bytes, of `taut run SCENE --set … --out <tmp>`,
/// which must succeed.
fn peak_rss(scene: &str, sets: &[&str]) -> u64 {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let err_path = tmp.path().join("stderr");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_taut"));
    cmd.current_dir(common::crate_root())
        .args(["run", scene, "--quiet", "--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&err_path).unwrap());
    for s in sets {
        cmd.args(["--set", s]);
    }
    // reaped by wait4 below, which Child::wait cannot replace (it gives no
    // rusage)
    #[allow(clippy::zombie_processes)]
    let child = cmd.spawn().expect("taut runs");
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: a zeroed rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: pid is our own child, not waited for yet; the pointers are to
    // live locals.
    let r = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(r, pid, "wait4: {}", std::io::Error::last_os_error());
    assert!(
        libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
        "taut run {scene} {sets:?} failed (status {status}): {}",
        std::fs::read_to_string(&err_path).unwrap_or_default()
    );
    // Linux reports ru_maxrss in KiB
    usage.ru_maxrss as u64 * 1024
}

/// This process's own peak resident size, bytes (`VmHWM`).
fn own_peak() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = status.lines().find(|l| l.starts_with("VmHWM:")).unwrap();
    let kib: u64 = line
        .trim_start_matches("VmHWM:")
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .unwrap();
    kib * 1024
}

/// The estimate of `scene` with `sets`, from the library the binary uses.
fn estimate(scene: &str, sets: &[&str]) -> taut::resolve::MemoryEstimate {
    let path = common::crate_root().join(scene);
    let text = std::fs::read_to_string(&path).unwrap();
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    taut::resolve_scene(&text, &sets).unwrap().memory_estimate()
}

/// Run the case; a failure (peak above estimate + baseline) as text.
fn check(what: &str, scene: &str, sets: &[&str]) -> Option<String> {
    let e = estimate(scene, sets);
    assert!(
        e.total() > 4 * BASELINE_SLACK_BYTES,
        "{what}: a case of {} bytes says little beside the slack",
        e.total()
    );
    let parent = own_peak();
    assert!(
        parent <= BASELINE_SLACK_BYTES,
        "this test process holds {parent} bytes: the child's figure would be ours"
    );
    let peak = peak_rss(scene, sets);
    println!(
        "{what}: estimate {:.1} MiB (history {:.1}, history.csv block {:.1}, model {:.1}, droppers {:.1}, wire {:.1}, events and outputs {:.1}), measured peak {:.1} MiB, ratio {:.3}",
        e.total() as f64 / MIB,
        e.history as f64 / MIB,
        e.csv_block as f64 / MIB,
        e.model as f64 / MIB,
        e.droppers as f64 / MIB,
        e.wire as f64 / MIB,
        e.other() as f64 / MIB,
        peak as f64 / MIB,
        peak as f64 / e.total() as f64,
    );
    (peak > e.total() + BASELINE_SLACK_BYTES).then(|| {
        format!(
            "{what}: peak {:.1} MiB above the estimate {:.1} MiB + the baseline slack {:.1} MiB",
            peak as f64 / MIB,
            e.total() as f64 / MIB,
            BASELINE_SLACK_BYTES as f64 / MIB
        )
    })
}

#[test]
fn every_case_peaks_within_its_estimate_and_the_baseline() {
    // the baseline: a 100-step run holds next to nothing of its own
    let base = peak_rss(
        "scenes/t2_stationary_mass.toml",
        &["mesh.elements=10", "time.end=0.01"],
    );
    println!("baseline (100 steps): peak {:.1} MiB", base as f64 / MIB);
    assert!(base <= BASELINE_SLACK_BYTES, "baseline {base} bytes");

    // 150 probes (1249-byte rows) over 70 001 rows, more than history.csv
    // formats at a time
    let mut text =
        std::fs::read_to_string(common::crate_root().join("scenes/t2_stationary_mass.toml"))
            .unwrap();
    for i in 0..150 {
        text.push_str(&format!(
            "\n[[probe]]\nname = \"p{i}\"\nx = {}\n",
            0.1 + 0.3 * i as f64
        ));
    }
    let tmp = tempfile::tempdir().unwrap();
    let probes = tmp.path().join("probes.toml");
    std::fs::write(&probes, text).unwrap();
    let probes = probes.to_str().unwrap();
    let probe_sets = ["mesh.elements=10", "time.step=1e-6", "time.end=0.07"];
    assert!(estimate(probes, &probe_sets).rows > taut::report::HISTORY_ROWS_AT_A_TIME as u64);

    let failures: Vec<String> = [
        // 2.2·10⁶ rows of 49 bytes (a twentieth of the run that once aborted)
        (
            "long history",
            "scenes/t2_stationary_mass.toml",
            &["mesh.elements=10", "time.step=2.3e-8", "time.end=0.05"][..],
        ),
        // n = 1599 FE unknowns: the dense solve is the run's memory
        (
            "modal n = 1599",
            "scenes/reference.toml",
            &[
                "mesh.kind=modal",
                "mesh.modes=60",
                "mesh.elements=800",
                "time.end=0.01",
            ][..],
        ),
        ("150 probes", probes, &probe_sets[..]),
        // 180 tension-only droppers on a three-span line with its
        // messenger: a dense response over the unknowns each, the
        // contact problem's rows (droppers were once outside the
        // estimate)
        (
            "180 droppers",
            "scenes/line_10_spans.toml",
            &["line.spans=3", "line.droppers.count=60", "time.end=0.004"][..],
        ),
        // a field of 101 rows × 10⁵ points (its table once took four
        // copies of the values while field.csv was written)
        (
            "field 101 × 1e5",
            "scenes/reference.toml",
            &[
                "time.end=0.01",
                "output.field={ every = 1, points = 100000 }",
            ][..],
        ),
    ]
    .into_iter()
    .filter_map(|(what, scene, sets)| check(what, scene, sets))
    .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
