//! The wire itself: snapshots of v(x) and the space–time
//! field (`[output] snapshots`, `field`), the modes of a scene (`taut
//! modes`), the 0–20 Hz filtered force statistics of every summary, and
//! tabulated speed profiles.

use crate::common;
use common::run;
use taut::analytic::{ClampedPinnedModes, PinnedPinnedModes, StaticPointLoad};

const T2_STRING: &str = include_str!("../scenes/t2_stationary_mass_string.toml");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// The T2 string with its carrier replaced by a 100 N force standing at
/// x = 20 m (`tests/carriers.rs`), and `extra` appended.
fn standing_force(extra: &str) -> String {
    let start = T2_STRING.find("[[carrier]]").unwrap();
    let end = T2_STRING.find("[contact]").unwrap();
    format!(
        "{}[[carrier]]\nforce = 100.0\nside = \"below\"\nstart = 20.0\nspeed = {{ profile = \"constant\", value = 0.0 }}\n\n{}\n{extra}",
        &T2_STRING[..start],
        &T2_STRING[end..]
    )
}

fn resolve(text: &str, set: &[&str]) -> taut::Resolved {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    taut::resolve_scene(text, &set).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_snapshot_is_the_state_the_history_and_probes_record() {
    // the T2 mass standing on the string at x = 1 m (a node of 400
    // elements on 50 m), a probe at the node x = 20 m: at the step a
    // snapshot takes, its values at those nodes are the history's, bit for bit
    let text = format!(
        "{}\n[[probe]]\nname = \"p20\"\nx = 20.0\n\n[output]\nsnapshots = [0.0, 0.05, 0.123, 0.3]\n",
        T2_STRING.replace("end = 5.0", "end = 0.3")
    );
    let sc = resolve(&text, &[]);
    let out = run(&sc);
    let s = &out.history.snapshots;
    assert_eq!(s.rows(), 4);
    assert_eq!(s.x.len(), sc.elements + 1, "default points: the mesh nodes");
    let node = |x: f64| s.x.iter().position(|&xi| xi == x).unwrap();
    let (i_mass, i_probe) = (node(1.0), node(20.0));
    let probe = &out.history.probes[0].1;
    let side = -1.0; // side = "above": w = −v
    for k in 0..s.rows() {
        // the step nearest the time asked for, and its time
        let n = (s.requested[k] / sc.dt).round() as usize;
        assert_eq!(s.t[k], out.history.t[n], "snapshot {k}'s step");
        assert!((s.t[k] - s.requested[k]).abs() <= 0.5 * sc.dt * (1.0 + 1e-9));
        let row = s.row(k);
        assert_eq!(row[i_probe], probe[n], "snapshot {k} at the probe");
        assert_eq!(
            side * row[i_mass],
            out.history.carriers[0].w[n],
            "snapshot {k} under the carrier"
        );
        // the supports hold v = 0
        assert_eq!(row[0], 0.0);
        assert_eq!(row[s.x.len() - 1], 0.0);
    }
    assert!(
        out.history.field.is_empty(),
        "no field asked for, none kept"
    );
}

/// The time average of an undamped string under a suddenly applied force
/// is the static deflection to amplitude·period/(π·t_end) ≈ 4 % of the peak
/// (`tests/carriers.rs`, MEAN_DEFLECTION_TOL: period 2L/c = 0.667 s, t_end =
/// 5 s); here over the whole span, relative to the static peak.
const FIELD_MEAN_TOL: f64 = 0.04;

#[test]
fn the_field_averages_to_the_static_deflection() {
    let sc = resolve(
        &standing_force("[output]\nfield = { every = 10, points = 51 }\n"),
        &[],
    );
    let out = run(&sc);
    let f = &out.history.field;
    assert_eq!(f.x.len(), 51);
    assert_eq!(f.rows(), sc.steps / 10 + 1, "steps 0, 10, 20, …");
    assert_eq!(f.t[1], out.history.t[10]);
    let beam = StaticPointLoad::new(
        0.0,
        sc.beam.tension,
        sc.beam.length,
        sc.beam.left,
        sc.beam.right,
    )
    .unwrap();
    let peak = 100.0 * beam.compliance(20.0);
    let mut worst = 0.0f64;
    for (i, &x) in f.x.iter().enumerate() {
        let mean = (1..f.rows()).map(|k| f.row(k)[i]).sum::<f64>() / (f.rows() - 1) as f64;
        let stat = 100.0 * beam.deflection(20.0, x);
        worst = worst.max((mean - stat).abs() / peak);
    }
    println!("field mean vs static deflection: max error {worst:.3e} of the peak {peak:.4e} m");
    assert!(worst <= FIELD_MEAN_TOL, "{worst}");
}

#[test]
fn snapshots_cost_nothing_when_absent_and_change_no_history() {
    let plain = resolve(REFERENCE, &["mesh.elements=100", "time.end=0.05"]);
    let with = resolve(
        &format!(
            "{REFERENCE}\n[output]\nsnapshots = [0.02]\nsnapshot_points = 11\nfield = {{ every = 50 }}\n"
        ),
        &["mesh.elements=100", "time.end=0.05"],
    );
    assert_eq!(plain.wire, Default::default());
    assert!(with.memory_estimate().total() > plain.memory_estimate().total());
    let (a, b) = (run(&plain), run(&with));
    assert_eq!(a.history.t, b.history.t);
    assert_eq!(a.history.carriers[0].force, b.history.carriers[0].force);
    assert_eq!(a.history.carriers[0].w, b.history.carriers[0].w);
    assert_eq!(b.history.snapshots.x.len(), 11);
    assert_eq!(b.history.field.x.len(), 101);
}

#[test]
fn bad_wire_keys_name_the_field_the_value_and_the_range() {
    let cases: [(&str, &str); 6] = [
        ("snapshots = [0.1, 9.0]", "output.snapshots.1"),
        ("snapshots = [-0.1]", "output.snapshots.0"),
        (
            "snapshots = [0.1]\nsnapshot_points = 1",
            "output.snapshot_points",
        ),
        ("snapshot_points = 5", "output.snapshot_points"),
        ("field = { every = 0 }", "output.field.every"),
        ("field = { every = 2, points = 1 }", "output.field.points"),
    ];
    for (keys, field) in cases {
        let text = format!("{REFERENCE}\n[output]\n{keys}\n");
        let e = taut::resolve_scene(&text, &[]).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains("must"), "{keys}: {e}");
    }
    let e = taut::resolve_scene(
        &format!("{REFERENCE}\n[output]\nfield = {{ every = 2, pts = 3 }}\n"),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("pts"), "an unknown key is named: {e}");
}

/// On 200 elements of the 50 m clamped–pinned reference beam the FE
/// frequencies of modes 1–10 are measured +7.62e-5 above the exact ones,
/// the same for every mode: the clamped end's boundary layer sqrt(EI/T) =
/// 0.066 m is not resolved by h = 0.25 m, which acts as a slightly shorter
/// span. The bound is twice that.
const FE_FREQUENCY_REL: f64 = 1.5e-4;

/// The galerkin basis's frequencies are the characteristic equation's roots,
/// bisected to round-off (`analytic::mode_shapes`).
const EXACT_FREQUENCY_REL: f64 = 1e-12;

#[test]
fn modes_match_the_exact_frequencies_and_fe_matches_galerkin() {
    let exact = ClampedPinnedModes::new(1.34e11 * 9.64e-10, 3.0e4, 8900.0 * 1.5e-4, 50.0)
        .unwrap()
        .frequencies(10);
    let fe =
        taut::study::modes::modes(&resolve(REFERENCE, &["mesh.elements=200"]), Some(10)).unwrap();
    let gal = taut::study::modes::modes(
        &resolve(
            REFERENCE,
            &[
                "mesh.elements=200",
                "mesh.kind=\"galerkin\"",
                "mesh.modes=20",
            ],
        ),
        Some(10),
    )
    .unwrap();
    assert_eq!(fe.source.name(), "fe_eigen");
    assert_eq!(gal.source.name(), "exact");
    let two_pi = 2.0 * std::f64::consts::PI;
    for (j, w) in exact.iter().enumerate() {
        let f = w / two_pi;
        let (e_fe, e_gal) = (
            fe.frequencies_hz[j] / f - 1.0,
            gal.frequencies_hz[j] / f - 1.0,
        );
        println!(
            "mode {}: {f:.6} Hz, fe {e_fe:+.3e}, exact {e_gal:+.3e}",
            j + 1
        );
        assert!(
            e_fe.abs() <= FE_FREQUENCY_REL,
            "mode {}: fe {e_fe:e}",
            j + 1
        );
        assert!(
            e_gal.abs() <= EXACT_FREQUENCY_REL,
            "mode {}: exact {e_gal:e}",
            j + 1
        );
    }
    // the same shapes on the same nodes (mass-normalized, same sign rule):
    // at the nodes the FE shapes converge like the frequencies' square root
    assert_eq!(fe.x, gal.x);
    for j in 0..10 {
        let big = gal.shapes[j].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = fe.shapes[j]
            .iter()
            .zip(&gal.shapes[j])
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!("mode {} shape: {:.3e} of its peak", j + 1, diff / big);
        assert!(
            diff <= SHAPE_REL * big,
            "mode {}: {diff:e} of {big:e}",
            j + 1
        );
    }
    // T > 0, both ends held: the taut string's j c / 2L beside them
    let c = (3.0e4f64 / (8900.0 * 1.5e-4)).sqrt();
    assert_eq!(fe.string_hz.as_ref().unwrap()[2], 3.0 * c / 100.0);
}

/// FE mode shapes at the nodes against the exact ones, relative to the
/// shape's peak, on 200 elements: measured 2.3e-4 (mode 1) rising to
/// 2.2e-3 (mode 10), the same boundary-layer span shift as the
/// frequencies; the bound is about twice the largest.
const SHAPE_REL: f64 = 4e-3;

#[test]
fn modes_of_a_string_are_the_string_limit() {
    // the T2 string: EI = 0, pinned–pinned: FE string elements converge to
    // j c / 2L at O(h²)
    let sc = resolve(T2_STRING, &[]);
    let m = taut::study::modes::modes(&sc, None).unwrap();
    assert_eq!(m.frequencies_hz.len(), 10);
    let pp = PinnedPinnedModes::new(0.0, sc.beam.tension, sc.beam.rho_a, sc.beam.length)
        .unwrap()
        .frequencies(10);
    for (j, w) in pp.iter().enumerate() {
        let s = m.string_hz.as_ref().unwrap()[j];
        assert!((w / (2.0 * std::f64::consts::PI) / s - 1.0).abs() < 1e-14);
        let e = m.frequencies_hz[j] / s - 1.0;
        println!("string mode {}: {e:+.3e}", j + 1);
        assert!(e.abs() < STRING_FE_REL, "mode {}: {e:e}", j + 1);
    }
}

/// Linear string elements with a consistent mass raise ω by (kh)²/24,
/// k = jπ/L: 2.57e-4 for mode 10 on 400 elements of 50 m, as measured;
/// the bound is twice that.
const STRING_FE_REL: f64 = 5e-4;

#[test]
fn an_attachment_lowers_the_fe_modes_and_drops_the_string_limit() {
    let bare =
        taut::study::modes::modes(&resolve(REFERENCE, &["mesh.elements=100"]), Some(3)).unwrap();
    let text = format!("{REFERENCE}\n[[attachment]]\nx = 25.0\nmass = 5.0\n");
    let with = taut::study::modes::modes(&resolve(&text, &["mesh.elements=100"]), Some(3)).unwrap();
    assert!(with.string_hz.is_none());
    // a mass at mid-span lowers the odd modes (non-zero there)
    assert!(with.frequencies_hz[0] < bare.frequencies_hz[0]);
    let e = taut::study::modes::modes(&resolve(REFERENCE, &["mesh.elements=10"]), Some(100))
        .unwrap_err()
        .to_string();
    // 10 clamped–pinned Hermite elements: 2·11 − 3 = 19 unknowns
    assert!(e.contains("--count") && e.contains("1 ..= 19"), "{e}");
}

#[test]
fn the_summary_filters_the_force_as_the_sweep_columns_do() {
    let sc = resolve(REFERENCE, &["mesh.elements=100", "time.end=0.3"]);
    let out = run(&sc);
    let s = taut::report::Summary::new(&sc, &out);
    let taut::record::Filtered::Stats(f) = s.carriers[0].force_filtered else {
        panic!("a summary of a run at every step has the filtered force");
    };
    assert_eq!(s.contact.force_filtered, s.carriers[0].force_filtered);
    // an independent filter of history.csv's force (the study's filter,
    // the statistics written out here): the same numbers
    // mean and σ over the window [0, T] (MODEL §7), max and min over the
    // steps
    let y = taut::study::filter::lowpass_zero_phase(&out.history.carriers[0].force, sc.dt, 20.0);
    let (mean, std) = taut::record::window::time_mean_std(&out.history.t, &y, out.window_end);
    let y = &y[1..];
    assert_eq!(f.cutoff_hz, 20.0);
    assert_eq!(f.mean, mean);
    assert_eq!(f.std, std);
    assert_eq!(f.max, y.iter().copied().fold(f64::NEG_INFINITY, f64::max));
    assert_eq!(f.min, y.iter().copied().fold(f64::INFINITY, f64::min));
    // the sweep's filtered columns are the same statistic
    use taut::quantity::{FILTERED_FORCE_MAX, FILTERED_FORCE_STD};
    assert_eq!(FILTERED_FORCE_STD.of(&out, 0), Some(f.std));
    assert_eq!(FILTERED_FORCE_MAX.of(&out, 0), Some(f.max));
    // filtering smooths: the filtered spread is below the raw one
    assert!(f.std < s.carriers[0].force.std && f.max <= s.carriers[0].force.max);
    let json = serde_json::to_value(&s).unwrap();
    assert_eq!(json["carriers"][0]["force_filtered"]["std"], f.std);
    // a history of every 10th step cannot be filtered at 20 Hz: null
    let sc10 = resolve(
        REFERENCE,
        &[
            "mesh.elements=100",
            "time.end=0.3",
            "output.record_every=10",
        ],
    );
    let s10 = taut::report::Summary::new(&sc10, &run(&sc10));
    let json = serde_json::to_value(&s10).unwrap();
    assert!(json["carriers"][0]["force_filtered"].is_null());
}

#[test]
fn a_constant_speed_table_is_the_constant_profile_bit_for_bit() {
    let constant = "speed = { profile = \"constant\", value = 80.0 }";
    // one segment: X_0 + V τ + 0·τ²/2 = V t exactly (across knots, X_k +
    // V (t − t_k) rounds differently from V t: round-off, not bits)
    let table = "speed = { profile = \"table\", time = [0.0, 1.0], speed = [80.0, 80.0] }";
    let base = REFERENCE.replace(
        "speed = { profile = \"smooth_ramp\", cruise = 100.0 }   # m/s",
        constant,
    );
    let set = ["mesh.elements=100", "time.end=0.3"];
    let a = run(&resolve(&base, &set));
    let b = run(&resolve(&base.replace(constant, table), &set));
    assert_eq!(a.history.carriers[0].x, b.history.carriers[0].x);
    assert_eq!(a.history.carriers[0].force, b.history.carriers[0].force);
    assert_eq!(a.history.carriers[0].w, b.history.carriers[0].w);
}

/// A linear ramp integrated in closed form, x = a t²/2, against the table's
/// segment sums X_k + V_k τ + a τ²/2: round-off of a few additions.
const RAMP_POSITION_REL: f64 = 1e-14;

#[test]
fn a_ramp_table_moves_as_the_ramp_written_analytically() {
    let table = "speed = { profile = \"table\", time = [0.0, 0.1, 0.25, 0.6], speed = [0.0, 20.0, 50.0, 120.0] }";
    let text = REFERENCE.replace(
        "speed = { profile = \"smooth_ramp\", cruise = 100.0 }   # m/s",
        table,
    );
    let sc = resolve(&text, &["mesh.elements=100", "time.end=0.5"]);
    let m = &sc.carriers[0].motion;
    for &t in &[0.0, 0.05, 0.1, 0.17, 0.25, 0.4, 0.5] {
        let x = 100.0 * t * t; // V = 200 t: a = 200 m/s²
        assert!(
            (m.position(t) - x).abs() <= RAMP_POSITION_REL * x.max(1.0),
            "{t}"
        );
        assert!((m.speed(t) - 200.0 * t).abs() <= 1e-12, "{t}");
        if t > 0.0 {
            assert_eq!(m.acceleration(t), 200.0, "{t}");
        }
    }
    let out = run(&sc);
    let tr = &out.history.carriers[0];
    for (i, &t) in out.history.t.iter().enumerate() {
        assert!(
            (tr.x[i] - 100.0 * t * t).abs() <= RAMP_POSITION_REL * 25.0,
            "{t}"
        );
    }
}

#[test]
fn bad_speed_tables_name_the_field_the_value_and_the_range() {
    let cases = [
        ("time = [0.0], speed = [1.0]", "carrier.0.speed.time"),
        ("time = [0.0, 1.0], speed = [1.0]", "carrier.0.speed.speed"),
        (
            "time = [0.1, 1.0], speed = [1.0, 1.0]",
            "carrier.0.speed.time.0",
        ),
        (
            "time = [0.0, 0.5, 0.5], speed = [1.0, 1.0, 1.0]",
            "carrier.0.speed.time.2",
        ),
        (
            "time = [0.0, nan], speed = [1.0, 1.0]",
            "carrier.0.speed.time.1",
        ),
        (
            "time = [0.0, 1.0], speed = [1.0, -1.0]",
            "carrier.0.speed.speed.1",
        ),
        // the run (to 0.5 s) outlasts the table
        (
            "time = [0.0, 0.2], speed = [10.0, 10.0]",
            "carrier.0.speed.time.1",
        ),
    ];
    for (keys, field) in cases {
        let text = REFERENCE.replace(
            "speed = { profile = \"smooth_ramp\", cruise = 100.0 }   # m/s",
            &format!("speed = {{ profile = \"table\", {keys} }}"),
        );
        let e = taut::resolve_scene(&text, &["time.end=0.5".to_string()])
            .unwrap_err()
            .to_string();
        assert!(e.contains(field) && e.contains("must"), "{keys}: {e}");
    }
}

#[test]
fn runs_with_different_tables_batch_as_they_run_alone() {
    let scenes: Vec<taut::Resolved> = [60.0, 90.0]
        .iter()
        .map(|v| {
            let table = format!(
                "speed = {{ profile = \"table\", time = [0.0, 0.05, 1.0], speed = [0.0, {v}, {v}] }}"
            );
            let text = REFERENCE.replace(
                "speed = { profile = \"smooth_ramp\", cruise = 100.0 }   # m/s",
                &table,
            );
            resolve(&text, &["mesh.elements=100", "time.end=0.1"])
        })
        .collect();
    let together = taut::run_batch(&scenes, 2, &mut |_| {});
    for (sc, r) in scenes.iter().zip(together) {
        let (alone, batched) = (run(sc), r.unwrap());
        assert_eq!(alone.history.carriers[0].x, batched.history.carriers[0].x);
        assert_eq!(
            alone.history.carriers[0].force,
            batched.history.carriers[0].force
        );
    }
}

/// A speed table and an external force series read from CSV files beside
/// the scene (`file = ...`) are the inline tables they hold: the same run,
/// bit for bit; a file without its column is refused naming the field.
#[test]
fn table_files_are_the_inline_tables_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("profile.csv"),
        "# V(t), m/s\ntime,speed\n0.0,0.0\n0.1,20.0\n0.25,50.0\n0.6,120.0\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("uplift.csv"),
        "time,force\n0.0,0.0\n0.3,-15.5\n0.6,4.0\n",
    )
    .unwrap();
    let original = "speed = { profile = \"smooth_ramp\", cruise = 100.0 }   # m/s";
    let inline = REFERENCE.replace(
        original,
        "speed = { profile = \"table\", time = [0.0, 0.1, 0.25, 0.6], speed = [0.0, 20.0, 50.0, 120.0] }\nexternal_force = { time = [0.0, 0.3, 0.6], force = [0.0, -15.5, 4.0] }",
    );
    let from_files = REFERENCE.replace(
        original,
        "speed = { file = \"profile.csv\" }\nexternal_force = { file = \"uplift.csv\" }",
    );
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, &from_files).unwrap();
    let set: Vec<String> = ["mesh.elements=100", "time.end=0.5"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let a = run(&taut::resolve::load_scene(&scene, &set).unwrap_or_else(|e| panic!("{e}")));
    let b = run(&resolve(&inline, &["mesh.elements=100", "time.end=0.5"]));
    assert_eq!(a.history.t.len(), b.history.t.len());
    for (ta, tb) in a.history.carriers.iter().zip(&b.history.carriers) {
        for (x, y) in ta.x.iter().zip(&tb.x) {
            assert_eq!(x.to_bits(), y.to_bits());
        }
        for (x, y) in ta.force.iter().zip(&tb.force) {
            assert_eq!(x.to_bits(), y.to_bits());
        }
    }
    // a file without the value column names the field and the column
    std::fs::write(
        dir.path().join("uplift.csv"),
        "time,lift\n0.0,0.0\n0.6,1.0\n",
    )
    .unwrap();
    let e = taut::resolve::load_scene(&scene, &set).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("carrier.0.external_force.file") && msg.contains("`force` column"),
        "{msg}"
    );
}
