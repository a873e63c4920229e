//! Regression tests of issue 25 (reliability, round two), one section per
//! failure class: each reproduces the class at a size the default suite can
//! afford and checks the fix, through the `taut` binary where the class was
//! seen there.

mod common;

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_taut");

fn scene(name: &str) -> String {
    common::crate_root()
        .join("scenes")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

/// Run taut with `args`, returning (exit code, stdout, stderr).
fn taut(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(BIN)
        .current_dir(common::crate_root())
        .args(args)
        .output()
        .expect("taut runs");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn ok(args: &[&str]) -> String {
    let (code, out, err) = taut(args);
    assert_eq!(code, 0, "{args:?}\n{out}\n{err}");
    out
}

// ---------------------------------------------------------------------------
// Class 3: the modal path gives the same bytes on any thread count.
// (Before the fix, faer's eigensolver followed the pool: this sweep's
// sweep.csv differed between 1 and 2 threads at 200 elements, 100 modes.)

#[test]
fn a_modal_sweep_is_the_same_bytes_on_1_2_and_4_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = scene("reference.toml");
    let csv = |threads: &str| {
        let out = tmp.path().join(format!("t{threads}"));
        ok(&[
            "sweep",
            &reference,
            "--vary",
            "carrier.speed.cruise=100:140:3",
            "--set",
            "mesh.elements=200",
            "--set",
            "mesh.kind=modal",
            "--set",
            "mesh.modes=100",
            "--set",
            "time.end=0.05",
            "--threads",
            threads,
            "--batch",
            "1",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        std::fs::read(out.join("sweep.csv")).unwrap()
    };
    let one = csv("1");
    assert_eq!(one, csv("2"), "2 threads");
    assert_eq!(one, csv("4"), "4 threads");
}
