//! Space discretizations side by side (MODEL §9.2), each verified the same
//! way:
//!
//! * `modal` with every mode (J = the FE unknowns) reproduces the Hermite
//!   run to round-off;
//! * `galerkin` on a pinned–pinned beam is exactly the moving-force series'
//!   basis: against the series truncated at the same J, only the time
//!   integrator's error remains, and it falls at second order in Δt;
//! * on a riding mass, the `galerkin` run (generalized-α, a Lagrange
//!   constraint at position level) agrees with the independent RK4 solution
//!   of `analytic::riding_mass` (the convective terms written out) in the
//!   same modes, and with the Hermite run as J and N grow;
//! * modal truncation converges in J toward the FE run;
//! * graded meshes keep the observed order in h;
//! * every time integrator and contact formulation runs on every kind;
//! * bad input is a clear error naming the field, the value and the range.

use taut::analytic::{MovingForceBeam, Rider, RidingMassBeam};
use taut::run::RunOutput;
use taut::scene::Side;
use taut::{Resolved, resolve_scene, run};

const MOVING_FORCE: &str = include_str!("../scenes/moving_force_beam.toml");
const RIDING_MASS: &str = include_str!("../scenes/riding_mass_pinned.toml");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

fn scene(text: &str, set: &[&str]) -> Resolved {
    let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    resolve_scene(text, &o).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

fn go(text: &str, set: &[&str]) -> RunOutput {
    run(&scene(text, set), &mut |_, _| {}).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

fn err(text: &str, set: &[&str]) -> String {
    let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    match resolve_scene(text, &o).and_then(|sc| run(&sc, &mut |_, _| {})) {
        Ok(_) => panic!("{set:?} ran; expected an error"),
        Err(e) => e.to_string(),
    }
}

/// `modal` with every mode is the FE model in other coordinates: the
/// transformation and the eigenvectors carry round-off (measured: 3e-13 of
/// max |w| on the moving force, 6e-11 on the riding mass, whose contact
/// multiplier amplifies it).
const FULL_MODAL_TOL: f64 = 1e-9;

/// Galerkin against the series truncated at the same J: what remains is
/// generalized-α's O(Δt²) error, measured 7.0e-7 m at Δt = 1e-4 s
/// (1e-5 of max |w|), falling by 4.0 per halving. The bound on the ratio of
/// successive errors: second order is 4; a first-order (or no) convergence
/// would give ≤ 2.
const SECOND_ORDER_RATIO_MIN: f64 = 3.5;

/// The same bound on the error itself at Δt = 1e-4 s (relative to max |w|).
const SERIES_AGREEMENT_TOL: f64 = 3e-5;

/// Galerkin (generalized-α, position-level Lagrange constraint) against the
/// RK4 riding-mass solution in the same J modes: measured 8.7e-8 m of
/// 0.19 m (J = 20) and 1.9e-7 m (J = 40) at Δt = 1e-4 s, relative ≤ 1e-6;
/// the bound leaves a factor 5 for the two integrators' different errors.
const RIDING_MASS_AGREEMENT_TOL: f64 = 5e-6;

/// Graded meshes keep the order in h: the observed orders of
/// displacement_history_l2 on the moving-force ladder N = 20 … 160 differ from the
/// uniform mesh's by at most 0.2 (measured 0.09–0.20; the ladder is
/// pre-asymptotic, orders 1.1–1.5), bounded here by 0.3.
const GRADED_ORDER_TOL: f64 = 0.3;

/// Mean contact force of the galerkin and modal runs (J = 40 each; exact
/// modes against those of 100 Hermite elements) over 0.05 s of the
/// reference case: the bases differ in their highest modes (measured
/// 3.8e-4 relative for every pair but penalty under newmark and wbz, whose
/// undamped stiff penalty spring amplifies the difference to 1.1e-2).
const GALERKIN_MODAL_MEAN_FORCE_TOL: f64 = 0.03;

#[test]
fn modal_with_every_mode_reproduces_the_hermite_run() {
    for (text, n) in [(MOVING_FORCE, 100), (RIDING_MASS, 100)] {
        let h = go(text, &[]);
        let m = go(text, &["mesh.kind=modal", &format!("mesh.modes={n}")]);
        let (a, b) = (&h.history.carriers[0], &m.history.carriers[0]);
        let d = max_diff(&a.w, &b.w) / max_abs(&a.w);
        assert!(d < FULL_MODAL_TOL, "w differs by {d:e} of max |w|");
        let f = max_diff(&a.force, &b.force) / max_abs(&a.force);
        assert!(f < FULL_MODAL_TOL, "force differs by {f:e} of max |λ|");
        assert_eq!(a.in_contact, b.in_contact);
    }
}

#[test]
fn galerkin_is_the_moving_force_series_up_to_the_time_error() {
    let j = 20;
    let sc = scene(MOVING_FORCE, &[]);
    let b = &sc.beam;
    let series = MovingForceBeam::new(b.ei, b.tension, b.rho_a, b.length, 100.0, 75.0).unwrap();
    let mut errors = Vec::new();
    for dt in ["1e-4", "5e-5", "2.5e-5"] {
        let o = go(
            MOVING_FORCE,
            &[
                "mesh.kind=galerkin",
                &format!("mesh.modes={j}"),
                &format!("time.step={dt}"),
            ],
        );
        let exact: Vec<f64> = o
            .history
            .t
            .iter()
            .map(|&t| series.deflection_series(75.0 * t, t, j))
            .collect();
        errors.push(max_diff(&o.history.carriers[0].w, &exact) / max_abs(&exact));
    }
    assert!(errors[0] < SERIES_AGREEMENT_TOL, "{errors:?}");
    for k in 1..errors.len() {
        let ratio = errors[k - 1] / errors[k];
        assert!(ratio > SECOND_ORDER_RATIO_MIN, "{errors:?}: ratio {ratio}");
    }
}

#[test]
fn galerkin_riding_mass_agrees_with_the_rk4_solution_in_the_same_modes() {
    let sc = scene(RIDING_MASS, &[]);
    let b = &sc.beam;
    let rider = Rider {
        mass: 30.0,
        gravity: 9.81,
        side: Side::Above,
        start: 0.0,
        speed: 75.0,
    };
    let r = RidingMassBeam::new(b.ei, b.tension, b.rho_a, b.length, rider).unwrap();
    for j in [20usize, 40] {
        let o = go(
            RIDING_MASS,
            &[
                "mesh.kind=galerkin",
                &format!("mesh.modes={j}"),
                "time.step=1e-4",
            ],
        );
        let h = r.solve(j, r.max_step(j).min(1e-5), 1e-4, 0.4).unwrap();
        let rk: Vec<f64> = o.history.t.iter().map(|&t| h.w_at(t)).collect();
        let d = max_diff(&o.history.carriers[0].w, &rk) / max_abs(&rk);
        assert!(d < RIDING_MASS_AGREEMENT_TOL, "J = {j}: {d:e}");
    }
}

#[test]
fn galerkin_and_hermite_approach_each_other_on_a_moving_mass() {
    // as J and N grow together the two independent discretizations meet
    let mut gaps = Vec::new();
    for (n, j) in [(25, 25), (50, 50), (100, 100)] {
        let h = go(
            RIDING_MASS,
            &[&format!("mesh.elements={n}"), "time.step=1e-4"],
        );
        let g = go(
            RIDING_MASS,
            &[
                "mesh.kind=galerkin",
                &format!("mesh.modes={j}"),
                "time.step=1e-4",
            ],
        );
        let (a, b) = (&h.history.carriers[0], &g.history.carriers[0]);
        gaps.push(max_diff(&a.w, &b.w) / max_abs(&a.w));
    }
    assert!(
        gaps.windows(2).all(|w| w[1] < w[0]),
        "the gap must shrink: {gaps:?}"
    );
}

#[test]
fn modal_truncation_converges_toward_the_fe_run() {
    let fe = go(MOVING_FORCE, &[]);
    let mut errors = Vec::new();
    for j in [5, 10, 20, 40] {
        let m = go(
            MOVING_FORCE,
            &["mesh.kind=modal", &format!("mesh.modes={j}")],
        );
        errors.push(
            max_diff(&fe.history.carriers[0].w, &m.history.carriers[0].w)
                / max_abs(&fe.history.carriers[0].w),
        );
    }
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}

#[test]
fn graded_meshes_keep_the_order_in_h() {
    use taut::study::converge::{Refine, converge};
    let order = |set: &[&str]| -> Vec<f64> {
        let mut o: Vec<String> = vec!["time.step=2.5e-5".into(), "mesh.elements=20".into()];
        o.extend(set.iter().map(|s| s.to_string()));
        let c = converge(
            MOVING_FORCE,
            &o,
            Refine::Mesh,
            4,
            2.0,
            &taut::study::reference::analytic_w,
            &mut |_, _| {},
        )
        .unwrap();
        c.rows
            .iter()
            .filter(|r| r.quantity == "displacement_history_l2" && r.level >= 2)
            .map(|r| r.observed_order)
            .collect()
    };
    let uniform = order(&[]);
    for graded in [
        &["mesh.grading=supports", "mesh.grading_ratio=4"][..],
        &[
            "mesh.grading=point",
            "mesh.grading_at=20",
            "mesh.grading_ratio=8",
        ],
    ] {
        let p = order(graded);
        for (a, b) in uniform.iter().zip(&p) {
            assert!(
                (a - b).abs() < GRADED_ORDER_TOL,
                "{graded:?}: {p:?} vs {uniform:?}"
            );
        }
    }
}

#[test]
fn every_method_and_formulation_runs_on_every_discretization() {
    let methods = [
        "generalized_alpha",
        "newmark",
        "hht",
        "wbz",
        "bathe",
        "central_difference",
        "moreau_jean",
    ];
    let formulations = ["lagrange", "penalty", "complementarity", "impact"];
    let kinds: [&[&str]; 4] = [
        &[],
        &["mesh.grading=supports"],
        &["mesh.kind=galerkin", "mesh.modes=40"],
        &["mesh.kind=modal", "mesh.modes=40"],
    ];
    let text = REFERENCE.replace("rho_inf = 1.0", "");
    let mut ran = 0;
    for m in methods {
        for f in formulations {
            let mut means = Vec::new();
            for k in kinds {
                let mut set = vec![
                    format!("integrator.method={m}"),
                    format!("contact.formulation={f}"),
                    "mesh.elements=100".to_string(),
                    "time.step=2e-5".to_string(),
                    "time.end=0.05".to_string(),
                ];
                set.extend(k.iter().map(|s| s.to_string()));
                match resolve_scene(&text, &set) {
                    // a pair that means nothing is refused naming both keys,
                    // whatever the discretization (docs/methods.md)
                    Err(e) => {
                        assert!(
                            m == "moreau_jean" && matches!(f, "penalty" | "impact"),
                            "{set:?}: {e}"
                        );
                        continue;
                    }
                    Ok(sc) => {
                        let o = run(&sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("{set:?}: {e}"));
                        let s = &o.stats[0];
                        assert!(
                            s.force.mean.is_finite() && s.force.max.is_finite(),
                            "{set:?}"
                        );
                        means.push(s.force.mean);
                        ran += 1;
                    }
                }
            }
            // galerkin and modal (same J) tell the same story
            if means.len() == 4 {
                let (g, md) = (means[2], means[3]);
                let rel = (g - md).abs() / g.abs();
                assert!(rel < GALERKIN_MODAL_MEAN_FORCE_TOL, "{m}/{f}: {means:?}");
            }
        }
    }
    assert_eq!(ran, (7 * 4 - 2) * 4);
}

#[test]
fn bad_discretization_input_names_the_field_value_and_range() {
    let cases: [(&[&str], &[&str]); 10] = [
        (
            &["mesh.kind=modal", "mesh.modes=0"],
            &["mesh.modes", "0", "≥ 1"],
        ),
        (&["mesh.kind=galerkin"], &["mesh.modes", "missing"]),
        (
            &["mesh.kind=modal", "mesh.modes=100000"],
            &["mesh.modes", "100000", "1 ..= 799"],
        ),
        (
            &["mesh.kind=galerkin", "mesh.modes=5000"],
            &["mesh.modes", "5000", "1 ..= 4000"],
        ),
        (&["mesh.modes=10"], &["mesh.modes", "10", "galerkin"]),
        (
            &["mesh.grading=supports", "mesh.grading_ratio=0.5"],
            &["mesh.grading_ratio", "0.5", "[1, 1000]"],
        ),
        (
            &["mesh.grading=supports", "mesh.grading_ratio=1e6"],
            &["mesh.grading_ratio", "1000000", "[1, 1000]"],
        ),
        (
            &["mesh.grading=point"],
            &["mesh.grading_at", "missing", "(0, 50)"],
        ),
        (
            &["mesh.grading=point", "mesh.grading_at=60"],
            &["mesh.grading_at", "60", "(0, 50)"],
        ),
        (
            &["mesh.kind=galerkin", "mesh.modes=10", "beam.right=\"free\""],
            &["mesh.kind", "free", "clamped and pinned"],
        ),
    ];
    for (set, want) in cases {
        let e = err(REFERENCE, set);
        for w in want {
            assert!(e.contains(w), "{set:?}: `{w}` missing from: {e}");
        }
    }
    // an unknown kind or grading is named with the allowed values
    let e = err(REFERENCE, &["mesh.kind=\"fourier\""]);
    assert!(e.contains("fourier") && e.contains("galerkin"), "{e}");
    let e = err(REFERENCE, &["mesh.gradient=3"]);
    assert!(e.contains("gradient"), "{e}");
}
