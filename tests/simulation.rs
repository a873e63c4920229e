//! The step-by-step API (`taut::app::Simulation`) and the external force
//! on a carrier's mass (`[[carrier]] external_force`):
//! stepping k at a time gives `run`'s bytes; a constant series is a
//! preload change; a ramp on a stiff beam is the force law's; a force
//! held between steps goes through the series's hook; bad input is refused
//! naming the field.

use std::path::Path;

use taut::app::{self, RunRequest, SceneSource, Silent, Simulation};

use crate::common;

/// The scene files `run` writes, compared byte for byte (summary.json
/// without its wall time, which is the clock's).
fn same_outputs(a: &Path, b: &Path) {
    for f in ["history.csv", "force.svg"] {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(x == y, "{f} differs between run and the simulation");
    }
    let strip = |p: &Path| -> String {
        std::fs::read_to_string(p.join("summary.json"))
            .unwrap()
            .lines()
            .filter(|l| !l.contains("\"wall_seconds\""))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(strip(a), strip(b), "summary.json differs");
}

fn request(scene: &str, set: &[&str], out: Option<&Path>) -> RunRequest {
    RunRequest {
        scene: SceneSource::File(common::crate_root().join("scenes").join(scene)),
        set: set.iter().map(|s| s.to_string()).collect(),
        out: out.map(Path::to_path_buf),
        tolerance: None,
    }
}

/// Step `sim` to its end in groups of the sizes in `pattern`, cycled.
fn step_in_groups(sim: &mut Simulation, pattern: &[usize]) {
    let mut i = 0;
    while !sim.done() {
        let k = pattern[i % pattern.len()];
        let taken = sim.step(k).unwrap();
        assert!(
            taken == k || sim.done(),
            "{taken} of {k} steps before the end"
        );
        i += 1;
    }
    assert_eq!(sim.step(5).unwrap(), 0, "no step after the end");
}

/// With nothing applied, a simulation stepped k at a time (any k, mixed)
/// writes run's histories, plot and summary, bit for bit: one and two
/// carriers, a history kept every third step, each kind of method (an
/// implicit one, the explicit one, impulses, the modal propagation with
/// its lagged force record) and a probe.
#[test]
fn stepping_k_at_a_time_gives_the_bytes_of_run() {
    let tmp = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 5] = [
        (
            "reference.toml",
            &[
                "mesh.elements=100",
                "time.end=0.08",
                "output.record_every=3",
                "probe=[{name=\"mid\",x=25.0}]",
            ],
        ),
        (
            "two_pantographs.toml",
            &["mesh.elements=80", "time.end=0.05"],
        ),
        (
            "reference.toml",
            &[
                "mesh.elements=100",
                "time.end=0.05",
                "integrator={method=\"central_difference\"}",
                "time.step=2e-5",
            ],
        ),
        (
            "reference.toml",
            &[
                "mesh.elements=100",
                "time.end=0.05",
                "integrator={method=\"moreau_jean\"}",
            ],
        ),
        (
            "reference.toml",
            &[
                "mesh={kind=\"galerkin\",modes=60,elements=100}",
                "time.end=0.05",
                "integrator={method=\"modal_exact\"}",
            ],
        ),
    ];
    for (n, (scene, set)) in cases.iter().enumerate() {
        let a = tmp.path().join(format!("run{n}"));
        let b = tmp.path().join(format!("sim{n}"));
        app::run(&request(scene, set, Some(&a)), &Silent).unwrap();
        let mut sim = Simulation::new(&request(scene, set, Some(&b)), &Silent).unwrap();
        step_in_groups(&mut sim, &[1, 7, 2, 50, 3, 1, 13]);
        sim.finish().unwrap();
        same_outputs(&a, &b);
    }
}

/// The stationary reference carrier (t2) cut short: a scene to load.
const T2: [&str; 2] = ["mesh.elements=100", "time.end=0.2"];

/// Contact forces of a run of `sc`.
fn forces(scene: &str, set: &[&str]) -> Vec<f64> {
    let sc = common::scene(scene, set);
    common::run(&sc).history.carriers[0].force.clone()
}

/// Forces agree to round-off: f0 = kδ0 − s·m·g + s·F against
/// k(δ0 + Δδ0) − s·m·g, at most a few roundings apart in a force of about
/// 60 N, carried through linear solves that may amplify them by their
/// condition (measured: equal bits for every method here, as the two sums
/// happen to round alike; the bound is for other values).
const PRELOAD_ROUND_OFF: f64 = 1e-11;

/// A constant external force is the same as a preload change k Δδ0 =
/// s·F (MODEL §2), for each way a method samples its loads (generalized-α
/// at t_{n+1−α_f}, central difference at t_n, Moreau–Jean at t_{n+θ},
/// Bathe at its sub-steps, modal_exact held over the step).
#[test]
fn a_constant_series_is_a_preload_change() {
    // above the beam: s = −1, so F = s·k·Δδ0 = −987·0.01 N presses down
    let (k, d_delta, s) = (987.0, 0.01, -1.0);
    let f = s * k * d_delta;
    let series = format!("carrier.0.external_force={{time=[0.0,10.0],force=[{f},{f}]}}");
    for method in [
        &[][..],
        &[
            "integrator={method=\"central_difference\"}",
            "time.step=2e-5",
        ][..],
        &["integrator={method=\"moreau_jean\"}"][..],
        &["integrator={method=\"bathe\"}"][..],
        &[
            "mesh={kind=\"galerkin\",modes=60,elements=100}",
            "integrator={method=\"modal_exact\"}",
        ][..],
    ] {
        let mut with_series: Vec<&str> = T2.to_vec();
        with_series.extend_from_slice(method);
        with_series.push(&series);
        let mut with_preload: Vec<&str> = T2.to_vec();
        with_preload.extend_from_slice(method);
        with_preload.push("carrier.0.preload=0.06");
        let (a, b) = (
            forces("t2_stationary_mass.toml", &with_series),
            forces("t2_stationary_mass.toml", &with_preload),
        );
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let worst = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(
            worst <= PRELOAD_ROUND_OFF * scale,
            "{method:?}: series and preload differ by {worst:e} N of {scale} N"
        );
    }
}

/// How far the contact force's response to a ramp on a stiff beam
/// (tension 3·10⁸ N, 10⁴ times the reference's) leaves the force law
/// Δλ = s·F(t): the beam's point compliance under the carrier makes it
/// Δλ = s·F/(1 + k/k_b), k/k_b about 10⁻⁴, and the ramp's kink at t = 0
/// excites the carrier on the beam's stiffness (measured: 1.1e-2 N of the
/// ramp's 100 N, with the recorded force's lag α_f·Δt accounted for).
const STIFF_BEAM_RELATIVE: f64 = 3e-4;

/// A ramp F(t) = −r·t on the mass of a stationary carrier on a very stiff
/// beam: the mass can hardly move, so the change the ramp makes to the
/// contact force (against the same run without it: the model is linear
/// while in contact) is the force law's Δλ(t) = s·F(t) = −s·r·t (MODEL §2
/// with q ≈ 0) at every step. A sign error in the hook (−s·F) would leave
/// it by 2·r·t.
#[test]
fn a_ramp_on_a_stiff_beam_follows_the_force_law() {
    let s = -1.0; // the t2 carrier is above the beam
    // F(t) = −r·t: down, pressing the carrier above into the beam
    let (r, t_end) = (500.0, 0.2); // N/s, s: 100 N at the end
    let series = format!(
        "carrier.0.external_force={{time=[0.0,{t_end}],force=[0.0,{}]}}",
        -r * t_end
    );
    let base = [
        "mesh.elements=100",
        "time.end=0.2",
        "beam.tension=3e8",
        "integrator.rho_inf=0.8",
    ];
    let mut set = base.to_vec();
    set.push(&series);
    let sc = common::scene("t2_stationary_mass.toml", &set);
    let out = common::run(&sc);
    let plain = common::run(&common::scene("t2_stationary_mass.toml", &base));
    let lag = out.force_lag;
    let mut worst = 0.0f64;
    for ((t, lambda), lambda0) in out
        .history
        .t
        .iter()
        .zip(&out.history.carriers[0].force)
        .zip(&plain.history.carriers[0].force)
    {
        // the recorded force acts at t − lag·Δt
        let tf = (t - lag * sc.dt).max(0.0);
        let law = s * (-r * tf);
        worst = worst.max((lambda - lambda0 - law).abs());
    }
    assert!(
        worst <= STIFF_BEAM_RELATIVE * r * t_end,
        "the contact force's change leaves the force law by {worst:e} N"
    );
}

/// A force held between steps goes through the series's hook: holding,
/// before each step, the series's value at the method's load time gives
/// the series's run bit for bit (central difference samples at t_n,
/// `modal_exact` at the step's midpoint).
#[test]
fn apply_force_is_the_series_hook() {
    let tmp = tempfile::tempdir().unwrap();
    let ramp = |t: f64| 50.0 * t / 0.2 - 30.0 * (t / 0.2) * (t / 0.2);
    // samples at every 1e-3 s: the held value is the series's own interpolation
    let times: Vec<f64> = (0..=200).map(|i| i as f64 * 1e-3).collect();
    let values: Vec<f64> = times.iter().map(|&t| ramp(t)).collect();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:e}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    let series = format!(
        "carrier.0.external_force={{time=[{}],force=[{}]}}",
        list(&times),
        list(&values)
    );
    let sc_series = |method: &[&str]| {
        let mut set: Vec<&str> = T2.to_vec();
        set.extend_from_slice(method);
        set.push(&series);
        common::scene("t2_stationary_mass.toml", &set)
    };
    for (n, (method, load_time)) in [
        (
            &[
                "integrator={method=\"central_difference\"}",
                "time.step=2e-5",
            ][..],
            0.0,
        ),
        (
            &[
                "mesh={kind=\"galerkin\",modes=60,elements=100}",
                "integrator={method=\"modal_exact\"}",
            ][..],
            0.5,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let sc = sc_series(method);
        let mut set: Vec<&str> = T2.to_vec();
        set.extend_from_slice(method);
        let dir = tmp.path().join(format!("sim{n}"));
        let mut sim = Simulation::new(
            &request("t2_stationary_mass.toml", &set, Some(&dir)),
            &Silent,
        )
        .unwrap();
        let dt = sim.dt();
        let mut step = 0usize;
        while !sim.done() {
            let (t0, t1) = (step as f64 * dt, (step + 1) as f64 * dt);
            let t = if load_time == 0.0 {
                t0
            } else {
                0.5 * (t0 + t1)
            };
            let series = sc.external_forces[0].as_ref().unwrap();
            sim.apply_force(0, series.at(t)).unwrap();
            assert_eq!(sim.step(1).unwrap(), 1);
            step += 1;
        }
        let held = sim.finish().unwrap().output;
        let run = common::run(&sc);
        assert!(
            held.history.carriers[0].force == run.history.carriers[0].force,
            "{method:?}: held forces differ from the series"
        );
        assert!(held.history.carriers[0].q == run.history.carriers[0].q);
        // and the force acts (20 N at the end): not two runs without it
        let mut plain: Vec<&str> = T2.to_vec();
        plain.extend_from_slice(method);
        let without = forces("t2_stationary_mass.toml", &plain);
        let moved = (run.history.carriers[0].force.last().unwrap() - without.last().unwrap()).abs();
        assert!(
            moved > 10.0,
            "{method:?}: the series moved the force by {moved} N only"
        );
    }
}

/// The state between steps: time, the carrier's values as history.csv
/// records them, the held force, w at any point.
#[test]
fn the_state_reads_what_the_history_records() {
    let set = [
        "mesh.elements=100",
        "time.end=0.02",
        "probe=[{name=\"p\",x=1.0}]",
    ];
    let mut sim =
        Simulation::new(&request("t2_stationary_mass.toml", &set, None), &Silent).unwrap();
    sim.step(10).unwrap();
    sim.apply_force(0, -3.0).unwrap();
    let st = sim.state().unwrap();
    assert_eq!(st.step, 10);
    assert_eq!(st.t, 10.0 * sim.dt());
    let c = st.carriers[0];
    assert_eq!(c.x, 1.0);
    assert_eq!(c.applied, -3.0);
    assert!(c.q_dot.is_some() && c.in_contact && c.force > 0.0, "{c:?}");
    // the probe at the carrier: v = s·w = −w for a carrier above
    assert_eq!(st.probes[0].v, -c.w);
    assert_eq!(sim.w_at(1.0).unwrap(), st.probes[0].v);
    sim.step(usize::MAX).unwrap();
    let out = sim.finish().unwrap().output;
    assert_eq!(out.history.carriers[0].force[10], c.force);
}

/// Bad requests are refused naming what is wrong.
#[test]
fn bad_requests_are_refused_naming_the_field() {
    let e = |r: taut::Result<()>| r.unwrap_err().to_string();
    let set = ["mesh.elements=50", "time.end=0.01"];
    let mut sim =
        Simulation::new(&request("t2_stationary_mass.toml", &set, None), &Silent).unwrap();
    let m = e(sim.apply_force(3, 1.0));
    assert!(m.contains("carrier") && m.contains("0 ..= 0"), "{m}");
    let m = e(sim.apply_force(0, f64::NAN));
    assert!(m.contains("newtons") && m.contains("finite"), "{m}");
    let m = e(sim.w_at(51.0).map(|_| ()));
    assert!(m.contains("x") && m.contains("[0, 50]"), "{m}");
    sim.step(3).unwrap();
    let m = e(sim.finish().map(|_| ()));
    assert!(m.contains("97 steps before its end"), "{m}");
    // a moving force has no mass
    let mut sim = Simulation::new(
        &request("moving_force_beam.toml", &["time.end=0.01"], None),
        &Silent,
    )
    .unwrap();
    let m = e(sim.apply_force(0, 1.0));
    assert!(m.contains("carrier.0") && m.contains("no mass"), "{m}");
    // a tolerance run is not one run
    let mut req = request("t2_stationary_mass.toml", &set, None);
    req.tolerance = Some(app::Tolerance::new("force_mean", 1e-2, None).unwrap());
    let m = e(Simulation::new(&req, &Silent).map(|_| ()));
    assert!(m.contains("tolerance"), "{m}");
    // a series on a moving force, one that does not cover the run
    let m = e(taut::resolve_scene(
        &std::fs::read_to_string(common::crate_root().join("scenes/moving_force_beam.toml"))
            .unwrap(),
        &["carrier.0.external_force={time=[0.0,9.0],force=[1.0,1.0]}".into()],
    )
    .map(|_| ()));
    assert!(
        m.contains("carrier.0.external_force") && m.contains("mass–spring"),
        "{m}"
    );
    let sc = std::fs::read_to_string(common::crate_root().join("scenes/t2_stationary_mass.toml"))
        .unwrap();
    let m = e(taut::resolve_scene(
        &sc,
        &["carrier.0.external_force={time=[0.0,1.0],force=[1.0,1.0]}".into()],
    )
    .map(|_| ()));
    assert!(
        m.contains("external_force.time.1") && m.contains("end time 5"),
        "{m}"
    );
    let m = e(taut::resolve_scene(
        &sc,
        &["carrier.0.external_force={time=[0.0,9.0],force=[1.0,1.0],scale=2}".into()],
    )
    .map(|_| ()));
    assert!(m.contains("scale"), "{m}");
}

/// A run with a series steps alone: its batch key is none, so a sweep
/// never shares a batch's matrices or mass forces with it.
#[test]
fn a_series_keeps_a_run_out_of_batches() {
    let plain = common::scene("reference.toml", &["mesh.elements=100"]);
    assert!(taut::integrate::batch_key(&plain).is_some());
    let with = common::scene(
        "reference.toml",
        &[
            "mesh.elements=100",
            "carrier.0.external_force={time=[0.0,9.0],force=[1.0,1.0]}",
        ],
    );
    assert!(taut::integrate::batch_key(&with).is_none());
}
