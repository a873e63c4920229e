//! Sweeps over listed values (`--vary KEY=v1,v2,...`) and lists of points
//! (`--points FILE.csv`), and `--unset`, through the
//! `taut` binary.

use crate::common;

use std::path::Path;

use common::{out_dir, taut_bin};

/// The reference scene cut to 100 steps: enough to differ between points,
/// cheap enough for the default suite.
const SHORT: &str = "time.end=0.01";

/// `taut sweep scenes/reference.toml ARGS --set SHORT --out DIR --quiet`,
/// asserting success; returns sweep.csv's rows (header first).
fn sweep_rows(dir: &Path, args: &[&str]) -> Vec<String> {
    let mut all = vec!["sweep", "scenes/reference.toml"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--set", SHORT, "--out", dir.to_str().unwrap(), "--quiet"]);
    let o = taut_bin(&all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(dir.join("sweep.csv"))
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

/// A listed axis gives each value's row, in the list's order: the rows of
/// `60,50,55` are the rows of the range `50:60:3` reordered, byte for byte.
#[test]
fn a_listed_axis_runs_its_values_in_order() {
    let tmp = tempfile::tempdir().unwrap();
    let range = sweep_rows(
        &out_dir(&tmp, "range"),
        &["--vary", "carrier.speed.cruise=50:60:3"],
    );
    let list = sweep_rows(
        &out_dir(&tmp, "list"),
        &["--vary", "carrier.speed.cruise=60,50,55"],
    );
    assert_eq!(range.len(), 4);
    assert_eq!(list[0], range[0]);
    assert_eq!(
        list[1..],
        [range[3].clone(), range[1].clone(), range[2].clone()]
    );
    // no map for a list out of order; the range has its maps
    assert!(out_dir(&tmp, "range").join("force_map.svg").exists());
    assert!(!out_dir(&tmp, "list").join("force_map.svg").exists());
    // a range's spec has no list (earlier sweep folders keep their bytes)
    let spec = std::fs::read_to_string(out_dir(&tmp, "range").join("sweep.json")).unwrap();
    assert!(
        !spec.contains("values") && !spec.contains("paired"),
        "{spec}"
    );
}

/// A points file runs each row as one point: its results are those of
/// the same values on a grid, byte for byte; there is no map.
#[test]
fn a_points_file_runs_each_row() {
    let tmp = tempfile::tempdir().unwrap();
    let grid = sweep_rows(
        &out_dir(&tmp, "grid"),
        &[
            "--vary",
            "carrier.speed.cruise=50,60",
            "--vary",
            "beam.tension=2.5e4,3e4",
        ],
    );
    let file = tmp.path().join("points.csv");
    std::fs::write(
        &file,
        "# two proposals\ncarrier.speed.cruise,beam.tension\n60,2.5e4\n50,3e4\n",
    )
    .unwrap();
    let points = sweep_rows(
        &out_dir(&tmp, "points"),
        &["--points", file.to_str().unwrap()],
    );
    assert_eq!(points.len(), 3, "{points:?}");
    assert_eq!(points[0], grid[0]);
    // grid order: (50, 2.5e4), (50, 3e4), (60, 2.5e4), (60, 3e4)
    assert_eq!(points[1], grid[3]);
    assert_eq!(points[2], grid[2]);
    assert!(
        !out_dir(&tmp, "points")
            .join("loss_fraction_map.svg")
            .exists()
    );
    assert!(out_dir(&tmp, "grid").join("loss_fraction_map.svg").exists());
}

/// A bad points file is refused before any run, naming the flag, the line
/// and what is allowed; `--points` and `--vary` do not go together.
#[test]
fn a_bad_points_file_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("bad.csv");
    let cases = [
        ("beam.tension\n2e4\nabc\n", "line 3"),
        ("beam.tension,carrier.mass\n2e4\n", "2 keys"),
        ("beam.tension\n", "at least one point"),
        ("beam.tensoin\n2e4\n", "tensoin"),
    ];
    for (text, says) in cases {
        std::fs::write(&file, text).unwrap();
        let dir = out_dir(&tmp, "bad");
        let o = taut_bin(&[
            "sweep",
            "scenes/reference.toml",
            "--points",
            file.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
        ]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{text:?}: {e}");
        assert!(
            e.starts_with("error: ") && e.contains(says),
            "{text:?}: {e}"
        );
        assert!(!dir.join("sweep.csv").exists());
    }
    let o = taut_bin(&[
        "sweep",
        "scenes/reference.toml",
        "--points",
        file.to_str().unwrap(),
        "--vary",
        "beam.tension=1,2",
    ]);
    assert_eq!(o.status.code(), Some(2), "clap refuses both");
}

/// `--unset KEY` removes the key so that its default applies: a run
/// without the preload is the run with the default preload (0), byte for
/// byte, and not the preloaded run; a key that is not there is refused.
#[test]
fn unset_removes_a_key() {
    let tmp = tempfile::tempdir().unwrap();
    let history = |name: &str, args: &[&str]| {
        let dir = out_dir(&tmp, name);
        let mut all = vec!["run", "scenes/reference.toml", "--set", SHORT];
        all.extend_from_slice(args);
        all.extend_from_slice(&["--out", dir.to_str().unwrap(), "--quiet"]);
        let o = taut_bin(&all);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(dir.join("history.csv")).unwrap()
    };
    let unset = history("unset", &["--unset", "carrier.0.preload"]);
    let zero = history("zero", &["--set", "carrier.0.preload=0"]);
    let preloaded = history("preloaded", &[]);
    assert_eq!(unset, zero);
    assert_ne!(unset, preloaded);
    let o = taut_bin(&[
        "run",
        "scenes/reference.toml",
        "--unset",
        "integrator.rho_infinity",
        "--out",
        out_dir(&tmp, "absent").to_str().unwrap(),
        "--quiet",
    ]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("integrator.rho_infinity") && e.contains("not in the scene"),
        "{e}"
    );
}
