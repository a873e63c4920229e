//! Manufactured solutions (MODEL §11) and the verification harness
//! (`taut verify`).
//!
//! * Bad input for `[manufactured]` and `[reference]`: each error names the
//!   field, the value and what is allowed.
//! * A manufactured run converges to its exact solution, and a scene
//!   without `[manufactured]` is untouched by the source machinery.
//! * The harness fails a method whose declared order is wrong (so its
//!   passes mean something) and the cut-down matrix passes; the full
//!   matrix runs behind `--ignored` (`taut verify` runs it too).
//! * `taut converge` says when a ladder is limited by what it does not
//!   refine, and reports ω_max·Δt.

use taut::integrate::{Initial, MethodFactory, State, Stepper, System};
use taut::scene::{Method, MethodInfo};
use taut::study::converge::{Refine, converge};
use taut::study::verify::cases::CASES;
use taut::study::verify::{Selection, Status, any_failed, selection, verify, verify_golden};
use taut::{Resolved, resolve_scene};

use crate::common;

const MMS_TIME: &str = include_str!("../scenes/verify/mms_beam_time.toml");
const MMS_LOSS: &str = include_str!("../scenes/verify/mms_loss.toml");
const REFERENCE: &str = include_str!("../scenes/reference.toml");
const MOVING_FORCE: &str = include_str!("../scenes/moving_force_beam.toml");
const RIDING_MASS: &str = include_str!("../scenes/riding_mass_pinned.toml");

fn assert_names(e: &str, field: &str, value: &str, allowed: &str) {
    assert!(
        e.contains(&format!("`{field}`")) && e.contains(value) && e.contains(allowed),
        "expected field {field}, value {value}, allowed {allowed:?} in: {e}"
    );
}

#[test]
fn bad_manufactured_terms_are_refused_by_name() {
    let t0 = "manufactured.term.0";
    for (set, field, value, allowed) in [
        (
            format!("{t0}.amplitude=0.0"),
            format!("{t0}.amplitude"),
            "0",
            "≠ 0",
        ),
        (
            format!("{t0}.amplitude=nan"),
            format!("{t0}.amplitude"),
            "NaN",
            "finite",
        ),
        (
            format!("{t0}.x=[{{ kind = \"sine\", half_waves = 1000 }}]"),
            format!("{t0}.x.0.half_waves"),
            "1000",
            "[−100, 100]",
        ),
        (
            format!("{t0}.x=[{{ kind = \"exponential\", rate = 90 }}]"),
            format!("{t0}.x.0.rate"),
            "90",
            "[−30, 30]",
        ),
        (
            format!("{t0}.x=[{{ kind = \"polynomial\", coefficients = [1,1,1,1,1,1,1,1,1,1] }}]"),
            format!("{t0}.x.0.coefficients"),
            "10 coefficients",
            "1 ..= 9",
        ),
        (
            format!("{t0}.t=[]"),
            format!("{t0}.t"),
            "[]",
            "at least one factor",
        ),
        (
            format!("{t0}.t=[{{ kind = \"sine\", frequency = -3 }}]"),
            format!("{t0}.t.0.frequency"),
            "-3",
            "[0, 10000] Hz",
        ),
        (
            format!("{t0}.t=[{{ kind = \"exponential\", rate = 500 }}]"),
            format!("{t0}.t.0.rate"),
            "500",
            "|rate|·time.end ≤ 30",
        ),
        (
            format!("{t0}.t=[{{ kind = \"polynomial\", coefficients = [1, 2] }}]"),
            format!("{t0}.t"),
            "linear in t",
            "curved in t",
        ),
        (
            format!("{t0}.x=[{{ kind = \"polynomial\", coefficients = [0, 1, -1] }}]"),
            format!("{t0}.x"),
            "degree ≤ 3",
            "removed entirely",
        ),
        (
            "manufactured.term=[]".into(),
            "manufactured.term".into(),
            "0 terms",
            "1 ..= 8",
        ),
    ] {
        let e = common::rejected(MMS_TIME, &[&set]);
        assert_names(&e, &field, value, allowed);
    }
    // an unknown key is named as in any table
    let e = common::rejected(MMS_TIME, &["manufactured.term.0.amplitud=1"]);
    assert!(e.contains("amplitud"), "{e}");
}

#[test]
fn a_manufactured_contact_that_would_open_is_refused_naming_the_time() {
    // a 1 mm, 60 Hz motion: m ẅ ≈ 71 N against kδ0 + mg ≈ 15 N
    let e = common::rejected(MMS_TIME, &["manufactured.term.0.amplitude=1e-3"]);
    assert!(
        e.contains("`manufactured.term`")
            && e.contains("λ*")
            && e.contains("t = ")
            && e.contains("bilateral"),
        "{e}"
    );
    // the same motion with a bilateral contact is a valid case
    let o = vec![
        "manufactured.term.0.amplitude=1e-3".to_string(),
        "contact.kind=bilateral".to_string(),
    ];
    assert!(resolve_scene(MMS_TIME, &o).is_ok());
}

#[test]
fn bad_loss_intervals_are_refused_by_name() {
    let l = "manufactured.loss";
    for (set, field, value, allowed) in [
        (
            format!("{l}.start=0.02"),
            format!("{l}.start"),
            "0.02",
            "> manufactured.loss.blend",
        ),
        (
            format!("{l}.end=0.1"),
            format!("{l}.end"),
            "0.1",
            "> manufactured.loss.start",
        ),
        (
            format!("{l}.end=0.29"),
            format!("{l}.end"),
            "0.29",
            "before the run's end",
        ),
        (
            format!("{l}.gap=-1e-4"),
            format!("{l}.gap"),
            "-0.0001",
            "> 0 (m)",
        ),
        (format!("{l}.blend=0"), format!("{l}.blend"), "0", "> 0 (s)"),
        (
            "contact.kind=bilateral".into(),
            l.into(),
            "bilateral",
            "never opens",
        ),
    ] {
        let e = common::rejected(MMS_LOSS, &[&set]);
        assert_names(&e, &field, value, allowed);
    }
}

#[test]
fn a_declared_reference_that_does_not_fit_is_refused_naming_the_key() {
    let with = |kind: &str| format!("{REFERENCE}\n[reference]\nkind = \"{kind}\"\n");
    let e = common::rejected(&with("moving_force_series"), &[]);
    assert_names(
        &e,
        "reference.kind",
        "moving_force_series",
        "carrier.speed.profile",
    );
    let e = common::rejected(&with("riding_mass_galerkin"), &[]);
    assert_names(
        &e,
        "reference.kind",
        "riding_mass_galerkin",
        "carrier.speed.profile",
    );
    let e = common::rejected(RIDING_MASS, &["carrier.0.stiffness=5"]);
    assert_names(
        &e,
        "reference.kind",
        "riding_mass_galerkin",
        "carrier.stiffness = 5",
    );
    let e = common::rejected(MOVING_FORCE, &["beam.left=clamped"]);
    assert_names(&e, "reference.kind", "moving_force_series", "pinned–pinned");
    let e = common::rejected(&with("standing_force_modes"), &[]);
    assert_names(
        &e,
        "reference.kind",
        "standing_force_modes",
        "carrier.0.mass",
    );
    let e = common::rejected(MOVING_FORCE, &["reference.modes=100"]);
    assert_names(&e, "reference.modes", "100", "riding_mass_galerkin");
    let e = common::rejected(RIDING_MASS, &["reference.modes=0"]);
    let allowed = format!("1 ..= {}", taut::analytic::MAX_MODES * 4);
    assert_names(&e, "reference.modes", "0", &allowed);
    let e = common::rejected(MMS_TIME, &["reference.kind=richardson"]);
    assert_names(&e, "reference.kind", "richardson", "[manufactured]");
    let e = common::rejected(MOVING_FORCE, &["reference.kind=analytic"]);
    assert!(
        e.contains("reference.kind") && e.contains("analytic"),
        "{e}"
    );
}

/// Errors of one manufactured run against its exact solution: the largest
/// |w − w*| under the carrier and |λ − λ*| at the time λ acts.
fn run_errors(text: &str, overrides: &[String]) -> (f64, f64) {
    let sc = resolve_scene(text, overrides).unwrap();
    let out = taut::run(&sc, &mut |_, _| {}).unwrap();
    let m = sc.manufactured.as_ref().unwrap();
    let lag = out.force_lag * sc.dt;
    let h = &out.history;
    let (mut ew, mut ef) = (0.0f64, 0.0f64);
    for (i, &t) in h.t.iter().enumerate().skip(1) {
        ew = ew.max((h.carriers[0].w[i] - m.w(0, t)[0]).abs());
        ef = ef.max((h.carriers[0].force[i] - m.lambda(0, t - lag)).abs());
    }
    (ew, ef)
}

/// Largest |w − w*| relative to max |w*| at Δt = 2.5e-4 s, N = 64 on the
/// time case: measured 8.3e-5 (its second-order time error); the bound
/// leaves a factor 2.
const MMS_RELATIVE_W: f64 = 1.7e-4;

#[test]
fn a_manufactured_run_follows_its_exact_solution_and_halving_dt_quarters_the_error() {
    let set = |dt: f64| vec![format!("time.step={dt:e}"), "mesh.elements=64".to_string()];
    let (w1, f1) = run_errors(MMS_TIME, &set(5e-4));
    let (w2, f2) = run_errors(MMS_TIME, &set(2.5e-4));
    let sc = resolve_scene(MMS_TIME, &set(2.5e-4)).unwrap();
    let m = sc.manufactured.as_ref().unwrap();
    let scale = (0..=250)
        .map(|k| m.w(0, k as f64 * 1e-3)[0].abs())
        .fold(0.0, f64::max);
    println!(
        "manufactured: |w − w*| {w1:.3e} → {w2:.3e} m (max |w*| {scale:.3e}), |λ − λ*| {f1:.3e} → {f2:.3e} N"
    );
    assert!(w2 / scale < MMS_RELATIVE_W, "{w2} of {scale}");
    let order = taut::study::uncertainty::observed_order(w1, w2, 2.0);
    assert!((order - 2.0).abs() < 0.3, "displacement order {order}");
    let order = taut::study::uncertainty::observed_order(f1, f2, 2.0);
    assert!((order - 2.0).abs() < 0.3, "force order {order}");
}

/// Allowed |observed − 2| of Bathe's force order with a standing carrier
/// or the impact law (measured 2.00 and 2.04 at N = 128).
const BATHE_STANDING_TOL: f64 = 0.1;

/// Largest observed force order of Bathe at force level with the carrier
/// at 3 m/s, Δt 1.25e-4 → 6.25e-5 s, N = 128 (measured 1.31; the order
/// falls toward 1: 1.48, 1.40, 1.31, 1.19, 1.08 from 5e-4 s).
const BATHE_MOVING_MAX_ORDER: f64 = 1.5;

/// The force error at V = 6 m/s over that at 3 m/s, Δt = 6.25e-5 s
/// (measured 2.00: proportional to V); the band leaves ±15 % for the
/// second-order part, which does not scale with V.
const BATHE_SPEED_RATIO: (f64, f64) = (1.7, 2.3);

/// Bathe's contact force at force level under a moving contact (the
/// cause of its `known` rows). Its multiplier carries a first-order
/// term proportional to the carrier's speed: with a moving contact the gap
/// r(x_m(t))ᵀd − q is a time-dependent constraint, which the three-point
/// sub-step differentiates inconsistently with the beam's own velocities
/// (an O(Δt²) velocity-level residual, amplified by its 1/Δt
/// coefficients). With the carrier at rest, or with the velocity-level
/// impact law, the force is second order.
#[test]
fn bathe_force_at_force_level_has_a_first_order_term_proportional_to_the_speed() {
    let set = |v: f64, dt: f64, law: &str| {
        vec![
            "mesh.elements=128".to_string(),
            format!("time.step={dt:e}"),
            "integrator={ method = \"bathe\" }".to_string(),
            format!("carrier.0.speed={{ profile = \"constant\", value = {v} }}"),
            format!("contact.formulation={law}"),
        ]
    };
    let force = |v: f64, dt: f64, law: &str| run_errors(MMS_TIME, &set(v, dt, law)).1;
    let order = |v: f64, law: &str| {
        taut::study::uncertainty::observed_order(
            force(v, 1.25e-4, law),
            force(v, 6.25e-5, law),
            2.0,
        )
    };
    let (standing, moving, impact) = (
        order(0.0, "lagrange"),
        order(3.0, "lagrange"),
        order(3.0, "impact"),
    );
    let ratio = force(6.0, 6.25e-5, "lagrange") / force(3.0, 6.25e-5, "lagrange");
    println!(
        "bathe force order, Δt 1.25e-4 → 6.25e-5 s, N = 128: V = 0 {standing:.2}, V = 3 m/s {moving:.2}, impact law {impact:.2}; error at V = 6 over V = 3: {ratio:.2}"
    );
    assert!((standing - 2.0).abs() < BATHE_STANDING_TOL, "{standing}");
    assert!((impact - 2.0).abs() < BATHE_STANDING_TOL, "{impact}");
    assert!(moving < BATHE_MOVING_MAX_ORDER, "{moving}");
    assert!(
        ratio > BATHE_SPEED_RATIO.0 && ratio < BATHE_SPEED_RATIO.1,
        "{ratio}"
    );
}

#[test]
fn a_prescribed_loss_is_found_and_left() {
    let sc = resolve_scene(MMS_LOSS, &["time.step=2.5e-4".to_string()]).unwrap();
    let out = taut::run(&sc, &mut |_, _| {}).unwrap();
    let h = &out.history;
    // open inside (0.125, 0.175) s, closed outside [0.11, 0.19] s
    for (i, &t) in h.t.iter().enumerate() {
        let open = !h.carriers[0].in_contact[i];
        if t > 0.125 && t < 0.175 {
            assert!(open, "closed at t = {t}");
        }
        if !(0.11..=0.19).contains(&t) {
            assert!(!open, "open at t = {t}");
        }
    }
    let st = &out.stats[0];
    println!("loss fraction {:.4} (exact 0.2)", st.loss_fraction);
    assert!(
        (st.loss_fraction - 0.2).abs() < 0.01,
        "{}",
        st.loss_fraction
    );
}

/// Backward Euler declaring whatever order it is told (the test's lie).
struct Declares(f64);

impl MethodInfo for Declares {
    fn name(&self) -> String {
        format!("backward_euler_declaring_{}", self.0)
    }
}

impl MethodFactory for Declares {
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> taut::Result<Box<dyn Stepper>> {
        custom_method::BackwardEulerFactory.build(sc, sys, st, init)
    }
    fn time_order(&self, _: &Resolved) -> Option<f64> {
        Some(self.0)
    }
}

use crate::custom_method;

#[test]
fn the_harness_fails_a_method_that_declares_the_wrong_order() {
    let oscillator = &CASES[..1];
    let (lie, truth) = (Declares(2.0), Declares(1.0));
    for (m, status) in [(&lie, Status::Fail), (&truth, Status::Pass)] {
        let sel = Selection {
            methods: vec![m as &dyn MethodFactory],
            spaces: vec![taut::study::verify::case::Space::Hermite],
            formulations: vec![taut::scene::Formulation::Lagrange],
            quick: true,
        };
        let rows = verify(oscillator, &sel, &|_, _| {}).unwrap();
        assert_eq!(rows.len(), 1);
        println!(
            "{}: observed {:.2}, {:?}",
            m.name(),
            rows[0].observed,
            rows[0].status
        );
        assert_eq!(rows[0].status, status, "{}", rows[0].note);
    }
}

/// The cut-down matrix of the default suite: the quick cases (the
/// oscillator and the moving-mass Δt and space cases on their first two
/// support pairs), every method with the quick matrix's parameter sets,
/// three discretizations, three formulations (the runs' own wall time
/// over the quick matrix: 452 s without the generalized-α sets
/// `generalized_alpha(rho_inf=0.5)` and `hht(alpha=1/3)`, 550 s with them).
#[test]
fn the_cut_down_verification_matrix_passes() {
    let sel = selection(
        None,
        Some("hermite,galerkin,modal"),
        Some("lagrange,penalty,impact"),
        true,
    )
    .unwrap();
    let start = std::time::Instant::now();
    let (rows, golden) = verify_golden(&CASES, &sel, false, &|_, _| {}).unwrap();
    println!(
        "cut-down matrix: {} rows in {:.1} s",
        rows.len(),
        start.elapsed().as_secs_f64()
    );
    // every pass row is held to its golden error (a row above it fails,
    // below); the file has one for each, or it is stale
    assert_eq!(
        golden.missing, 0,
        "pass rows without a golden error: `taut verify --quick --update-golden`"
    );
    for r in rows.iter().filter(|r| r.status == Status::Fail) {
        println!(
            "FAIL {} {} {} {} {} {}: {}",
            r.case, r.method, r.discretization, r.formulation, r.variable, r.quantity, r.note
        );
    }
    assert!(!any_failed(&rows));
    assert!(rows.iter().filter(|r| r.status == Status::Pass).count() > 40);
    // a `cannot` is a refusal or a measured share, never a rule
    for r in rows.iter().filter(|r| r.status == Status::Cannot) {
        assert!(
            r.note.starts_with("refused: ") || r.note.starts_with("measured: "),
            "{} {} {} {} {} {}: {}",
            r.case,
            r.method,
            r.discretization,
            r.formulation,
            r.variable,
            r.quantity,
            r.note
        );
    }
    // every built-in method declares its order: nothing only reported
    assert!(rows.iter().all(|r| r.status != Status::Reported));
    // the penalty force is judged: its κ ladder converges to the exact
    // contact's force as the penalty stiffens where κ makes the error
    // (generalized-α, Bathe); elsewhere the row is a measured `cannot`
    // (HHT and WBZ: their first-order Δt error at the ladder's step, the
    // κ run moving nothing), a refusal or Newmark's `diverges`, and none
    // fails (above)
    let kappa: Vec<_> = rows
        .iter()
        .filter(|r| r.variable == "kappa" && r.quantity == "force")
        .collect();
    assert!(!kappa.is_empty());
    for method in ["generalized_alpha", "bathe"] {
        assert!(
            kappa
                .iter()
                .any(|r| r.method == method && r.status == Status::Pass),
            "{method}: no κ ladder passes"
        );
    }
    // WBZ runs at ρ∞ = 0.5, not only at Newmark's ρ∞ = 1
    let errors_of = |method: &str| -> Vec<Vec<f64>> {
        rows.iter()
            // the standing case runs Newmark alone (a witness of its moving rows)
            .filter(|r| r.method == method && r.formulation == "impact")
            .filter(|r| r.case != "mms_beam_standing")
            .map(|r| r.errors.clone())
            .collect()
    };
    let (wbz, newmark) = (errors_of("wbz(rho_inf=0.5)"), errors_of("newmark"));
    assert!(!wbz.is_empty() && wbz.len() == newmark.len());
    assert_ne!(wbz, newmark, "WBZ at ρ∞ = 0.5 is not Newmark");
}

/// The whole matrix (`taut verify` runs the same): every method ×
/// discretization × formulation × support pair on every case.
#[test]
#[ignore = "the full matrix: a few minutes in release (cargo test --release -- --ignored)"]
fn the_full_verification_matrix_passes() {
    let sel = selection(None, None, None, false).unwrap();
    let rows = verify(&CASES, &sel, &|_, _| {}).unwrap();
    for r in rows.iter().filter(|r| r.status == Status::Fail) {
        println!(
            "FAIL {} {} {} {} {} {} {}: {}",
            r.case,
            r.method,
            r.discretization,
            r.formulation,
            r.supports,
            r.variable,
            r.quantity,
            r.note
        );
    }
    assert!(!any_failed(&rows));
}

#[test]
fn converge_flags_a_ladder_limited_by_the_mesh_and_reports_omega_dt() {
    // the moving force on its 50-element mesh: the error against the series
    // does not move with Δt
    let c = converge(
        MOVING_FORCE,
        &[],
        Refine::Step,
        3,
        2.0,
        &taut::study::reference::analytic_w,
        &mut |_, _| {},
    )
    .unwrap();
    let last = c
        .rows
        .iter()
        .find(|r| r.level == 2 && r.quantity == "displacement_history_l2")
        .unwrap();
    println!("moving force, Δt ladder at N = 50: {last:?}");
    assert_eq!(last.reference, "moving_force_series");
    assert_eq!(last.regime, "limited by the mesh");
    // ω_max·Δt halves with Δt (this mesh's top mode is resolved: 0.11)
    let first = c
        .rows
        .iter()
        .find(|r| r.level == 0 && r.quantity == "displacement_history_l2")
        .unwrap();
    assert!((first.omega_max_dt / last.omega_max_dt - 4.0).abs() < 1e-9);
    // the manufactured Δt ladder on a fine mesh is asymptotic at order 2
    let c = converge(
        MMS_TIME,
        &["mesh.elements=64".to_string()],
        Refine::Step,
        3,
        2.0,
        &taut::study::reference::analytic_w,
        &mut |_, _| {},
    )
    .unwrap();
    let last = c
        .rows
        .iter()
        .find(|r| r.level == 2 && r.quantity == "displacement_history_max")
        .unwrap();
    assert_eq!(last.reference, "manufactured");
    assert_eq!(last.regime, "asymptotic");
    assert!((last.error_order - 2.0).abs() < 0.1, "{}", last.error_order);
    assert_eq!(last.formal_order, 2.0);
    // the force has an exact reference too
    let f = c
        .rows
        .iter()
        .find(|r| r.level == 2 && r.quantity == "force_history_max")
        .unwrap();
    assert_eq!(f.reference, "manufactured");
    assert!(f.error_order > 1.7, "{}", f.error_order);
    let _ = Method::GeneralizedAlpha;
}
