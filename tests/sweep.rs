//! `taut sweep` and `taut merge`: dimensionless axes mean what TARGETS says,
//! results are the same bytes whatever the thread count, an interrupted sweep
//! resumes without redoing finished runs, and shards merge into the whole.

use std::path::Path;
use std::process::Command;

use taut::study::sweep::{Axis, SweepSpec, sweep};

const BIN: &str = env!("CARGO_BIN_EXE_taut");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// Short runs: the first 0.2 s of the reference case on a coarse mesh.
fn spec(axes: Vec<Axis>) -> SweepSpec {
    SweepSpec {
        scene_text: REFERENCE.to_string(),
        set: vec![
            "mesh.elements=60".into(),
            "time.step=2e-4".into(),
            "time.end=0.2".into(),
        ],
        axes,
        check_refinement: false,
        paired: false,
        tolerance: None,
    }
}

#[test]
fn dimensionless_axes_set_the_scene_values() {
    let s = spec(vec![
        Axis::parse("tension_ratio=0.001:0.002:2", false).unwrap(),
        Axis::parse("speed_ratio=0.5:0.5:1", false).unwrap(),
    ]);
    let sc = s.resolve(1).unwrap();
    let ea = 1.34e11 * 1.5e-4;
    assert!((sc.beam.tension - 0.002 * ea).abs() < 1e-6 * ea * 0.002);
    // speed_ratio uses the swept tension's wave speed
    let c = (0.002 * ea / sc.beam.rho_a).sqrt();
    assert!((sc.carriers[0].motion.profile.cruise_speed() - 0.5 * c).abs() < 1e-9 * c);
    let m = spec(vec![
        Axis::parse("mass_ratio=0.02:0.02:1", false).unwrap(),
        Axis::parse("stiffness_ratio=2:2:1", false).unwrap(),
    ])
    .resolve(0)
    .unwrap();
    match m.carriers[0].kind {
        taut::scene::CarrierKind::MassSpring {
            mass, stiffness, ..
        } => {
            assert!((mass - 0.02 * 1.335 * 50.0).abs() < 1e-12);
            assert!((stiffness - 2.0 * 3e4 / 50.0).abs() < 1e-9);
        }
        _ => panic!("a mass–spring"),
    }
    // T1-style check of the published figure: c = 122.7 m/s at T/EA = 0.001
    let t = spec(vec![
        Axis::parse("tension_ratio=0.001:0.001:1", false).unwrap(),
    ])
    .resolve(0)
    .unwrap();
    assert!(
        (t.beam.wave_speed() - 122.7).abs() < 0.05,
        "{}",
        t.beam.wave_speed()
    );
}

fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    ["sweep.csv", "sweep_force.csv", "sweep_loss.csv"]
        .iter()
        .map(|f| (f.to_string(), std::fs::read(dir.join(f)).unwrap()))
        .collect()
}

fn cli(args: &[&str]) {
    let o = Command::new(BIN).args(args).output().unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn same_bytes_for_any_thread_count_resume_and_shards() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("scenes/reference.toml");
    let scene = scene.to_str().unwrap();
    let base = |out: &Path, extra: &[&str]| {
        let mut a = vec![
            "sweep",
            scene,
            "--vary",
            "speed_ratio=0.5:1.2:3",
            "--vary",
            "carrier.mass=0.5:2:2",
            "--set",
            "mesh.elements=60",
            "--set",
            "time.step=2e-4",
            "--set",
            "time.end=0.2",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        a.extend_from_slice(extra);
        cli(&a);
    };
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    base(&one, &["--threads", "1", "--batch", "1"]);
    base(&two, &["--threads", "2"]);
    assert_eq!(files(&one), files(&two));
    // batched stepping (the runs of one speed ratio share a matrix): the
    // same bytes as every run alone
    let three = tmp.path().join("three");
    base(&three, &["--batch", "3"]);
    assert_eq!(files(&one), files(&three));
    let csv = String::from_utf8(std::fs::read(one.join("sweep.csv")).unwrap()).unwrap();
    assert!(
        csv.starts_with("speed_ratio,carrier.mass,loss_fraction,"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 1 + 6);
    // each point's work is its one run's unknowns × steps, the same bytes
    // on any thread count (its CPU seconds are in timing.csv)
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    for line in csv.lines().skip(1) {
        let c: Vec<f64> = line
            .split(',')
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        assert_eq!(
            c[col("dof_steps_used")],
            c[col("dofs")] * c[col("steps")],
            "{line}"
        );
    }

    // interrupt: drop two finished runs, then resume; the others are not redone
    let runs = two.join("runs");
    let kept = runs.join("000000.json");
    let before = std::fs::metadata(&kept).unwrap().modified().unwrap();
    std::fs::remove_file(runs.join("000003.json")).unwrap();
    std::fs::remove_file(runs.join("000005.json")).unwrap();
    std::fs::remove_file(two.join("sweep.csv")).unwrap();
    base(&two, &[]);
    assert_eq!(
        std::fs::metadata(&kept).unwrap().modified().unwrap(),
        before
    );
    assert_eq!(files(&one), files(&two));

    // shards, then merge
    let (s0, s1, merged) = (
        tmp.path().join("s0"),
        tmp.path().join("s1"),
        tmp.path().join("m"),
    );
    base(&s0, &["--shard", "0/2"]);
    base(&s1, &["--shard", "1/2"]);
    cli(&[
        "merge",
        s0.to_str().unwrap(),
        s1.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert_eq!(files(&one), files(&merged));
    // the merge names its shards; a sweep writes no merge.csv
    let shards = std::fs::read_to_string(merged.join("merge.csv")).unwrap();
    assert!(
        shards.starts_with("shard\n") && shards.contains("s1"),
        "{shards}"
    );
    assert!(!one.join("merge.csv").exists());
}

#[test]
fn a_folder_holding_another_sweep_is_refused_and_merge_needs_every_point() {
    let tmp = tempfile::tempdir().unwrap();
    let a = spec(vec![Axis::parse("speed_ratio=0.5:0.6:2", false).unwrap()]);
    sweep(&a, tmp.path(), None, &|_, _| {}).unwrap();
    let b = spec(vec![Axis::parse("speed_ratio=0.5:0.7:2", false).unwrap()]);
    let e = sweep(&b, tmp.path(), None, &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("different sweep"), "{e}");

    let half = tmp.path().join("half");
    let shard = taut::study::sweep::Shard::parse("0/2").unwrap();
    sweep(&a, &half, Some(shard), &|_, _| {}).unwrap();
    let e = taut::study::sweep::merge(std::slice::from_ref(&half), &tmp.path().join("m"))
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("missing"), "{e}");
}
