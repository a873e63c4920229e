//! Multi-mass pantograph carriers in whole runs (MODEL §10, docs/lines.md
//! P1–P4; the chain's step against the held closed form is in
//! `src/integrate/chain.rs`'s unit tests):
//!
//! * a three-mass chain whose two upper springs are very stiff runs as the
//!   single mass–spring carrier of the summed mass on the roof spring;
//! * the bundled `scenes/pantograph_3mass.toml` gives the same contact force
//!   with the Lagrange, complementarity and penalty formulations;
//! * bad chain keys, and `modal_exact` (which does not carry the chain),
//!   are refused naming the field.

use crate::common;
use common::{run, scene};
use taut::RunOutput;

const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// Stiffness ratio of the stiff upper springs to the roof spring.
const STIFF_RATIO: f64 = 1e6;

/// A chain with upper springs R = 1e6 times the roof spring differs from
/// the rigid (single-mass) limit by the upper springs' compliance, O(1/R),
/// carried by the run. Compared on the head's displacement q (relative to
/// its largest value) and on the mean contact force: measured 5.7e-6 and
/// 2.1e-5; at R = 1e4 they are 2.6e-4 and 1.9e-4, which 1e-4 rejects.
/// (The force itself is not compared step by step: at t = 0 a chain's
/// head accelerates alone, its springs not yet stretched, while the rigid
/// carrier accelerates whole, and ρ∞ = 1 keeps the different step-to-step
/// constraint oscillation this starts: measured 0.14 of the largest force
/// at R = 1e6, 0.13 at R = 1e8 — a difference of the limit, not of R.)
const STIFF_CHAIN_AGREEMENT: f64 = 1e-4;

/// Complementarity (direct principal pivoting) against Lagrange: both
/// solve one contact exactly; measured 0 N (bit-identical); 1e-9 of the
/// largest force allows for round-off.
const QP_AGREEMENT: f64 = 1e-9;

/// Penalty at its default κ = 1e3/W (MODEL §6) penetrates by λ/κ, about
/// 1e-3 of the step's contact compliance λW: the head's displacement
/// agrees with Lagrange to 1.2e-7 of its largest value (measured), checked
/// at 1e-5. Its force carries ρ∞ = 1's undamped step-to-step constraint
/// oscillation with another amplitude than Lagrange's (and starts from 0 at
/// t = 0, no penetration yet), so the force is compared by its mean:
/// measured 3.0e-4 over 0.4 s, nearly all of it the t = 0 sample (0 for
/// penalty, 120 N for Lagrange, over 4000 samples); checked at 1e-3.
const PENALTY_Q_AGREEMENT: f64 = 1e-5;
const PENALTY_MEAN_AGREEMENT: f64 = 1e-3;

fn reference_with(carrier: &str, overrides: &[&str]) -> taut::Resolved {
    let start = REFERENCE.find("[[carrier]]").unwrap();
    let end = REFERENCE.find("[contact]").unwrap();
    let text = format!(
        "{}{carrier}\nside = \"below\"\nstart = 0.0\nspeed = {{ profile = \"smooth_ramp\", cruise = 80.0 }}\n\n{}",
        &REFERENCE[..start],
        &REFERENCE[end..]
    );
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    taut::resolve_scene(&text, &o).unwrap_or_else(|e| panic!("{e}"))
}

fn max_force(a: &RunOutput) -> f64 {
    a.history.carriers[0]
        .force
        .iter()
        .fold(0.0, |m: f64, f| m.max(f.abs()))
}

fn max_force_difference(a: &RunOutput, b: &RunOutput) -> f64 {
    let (fa, fb) = (&a.history.carriers[0].force, &b.history.carriers[0].force);
    assert_eq!(fa.len(), fb.len());
    fa.iter()
        .zip(fb)
        .fold(0.0, |m: f64, (x, y)| m.max((x - y).abs()))
}

/// max |q_a − q_b| / max |q_b| of the first carrier's mass (head) displacement.
fn q_difference(a: &RunOutput, b: &RunOutput) -> f64 {
    let (qa, qb) = (&a.history.carriers[0].q, &b.history.carriers[0].q);
    assert_eq!(qa.len(), qb.len());
    let d = qa
        .iter()
        .zip(qb)
        .fold(0.0, |m: f64, (x, y)| m.max((x - y).abs()));
    d / qb.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// |mean λ_a − mean λ_b| / mean λ_b.
fn mean_force_difference(a: &RunOutput, b: &RunOutput) -> f64 {
    let mean = |o: &RunOutput| {
        let f = &o.history.carriers[0].force;
        f.iter().sum::<f64>() / f.len() as f64
    };
    (mean(a) - mean(b)).abs() / mean(b).abs()
}

#[test]
fn a_chain_with_stiff_upper_springs_is_the_single_carrier_of_its_mass() {
    let (m, k3, c3, f0) = ([2.0, 3.0, 5.0], 1000.0, 40.0, 250.0);
    let stiff = STIFF_RATIO * k3;
    let overrides = ["mesh.elements=200", "time.end=0.5"];
    let chain = reference_with(
        &format!(
            "[[carrier]]\nmasses = [{}, {}, {}]\nstiffnesses = [{stiff}, {stiff}, {k3}]\n\
             dampings = [0.0, 0.0, {c3}]\nuplift = {f0}",
            m[0], m[1], m[2]
        ),
        &overrides,
    );
    let single = reference_with(
        &format!(
            "[[carrier]]\nmass = {}\nstiffness = {k3}\ndamping = {c3}\npreload = {}",
            m.iter().sum::<f64>(),
            f0 / k3
        ),
        &overrides,
    );
    let (a, b) = (run(&chain), run(&single));
    let (dq, dmean) = (q_difference(&a, &b), mean_force_difference(&a, &b));
    println!(
        "stiff chain (R = {STIFF_RATIO:e}) vs single carrier: q {dq:.3e}, mean λ {dmean:.3e}; \
         step-by-step λ {:.3e} of max λ = {:.3} N",
        max_force_difference(&a, &b) / max_force(&b),
        max_force(&b)
    );
    assert!(dq <= STIFF_CHAIN_AGREEMENT, "{dq}");
    assert!(dmean <= STIFF_CHAIN_AGREEMENT, "{dmean}");
    // both start from the static force F₀ − g Σm, the chain's less the
    // roof spring's share k₃ζ₃ = O(F₀/R) (its frame is held up by the
    // stiff springs)
    let (la, lb) = (
        a.history.carriers[0].force[0],
        b.history.carriers[0].force[0],
    );
    assert!((la - lb).abs() <= STIFF_CHAIN_AGREEMENT * lb, "{la} {lb}");
}

#[test]
fn formulations_agree_on_the_bundled_pantograph() {
    let base = ["mesh.elements=200", "time.end=0.4"];
    let with = |f: &str| {
        let mut o = base.to_vec();
        o.push(f);
        run(&scene("pantograph_3mass.toml", &o))
    };
    let lagrange = with("contact.formulation=\"lagrange\"");
    let qp = with("contact.formulation=\"complementarity\"");
    let penalty = with("contact.formulation=\"penalty\"");
    let scale = max_force(&lagrange);
    let d_qp = max_force_difference(&lagrange, &qp) / scale;
    let (dq_pen, dmean_pen) = (
        q_difference(&penalty, &lagrange),
        mean_force_difference(&penalty, &lagrange),
    );
    println!(
        "pantograph_3mass, max λ = {scale:.3} N: complementarity λ {d_qp:.2e}; \
         penalty q {dq_pen:.2e}, mean λ {dmean_pen:.2e}"
    );
    assert!(d_qp <= QP_AGREEMENT, "{d_qp}");
    assert!(dq_pen <= PENALTY_Q_AGREEMENT, "{dq_pen}");
    assert!(dmean_pen <= PENALTY_MEAN_AGREEMENT, "{dmean_pen}");
    // the static contact force at t = 0: uplift − g Σm (no roof spring)
    let lambda0 = lagrange.history.carriers[0].force[0];
    let want = 490.0 - 9.81 * (7.2 + 15.5 + 15.0);
    assert!((lambda0 - want).abs() <= 1e-9 * want, "{lambda0} {want}");
}

#[test]
fn bad_chain_keys_are_refused_naming_the_field() {
    let good = "masses = [7.2, 15.5, 15.0]\nstiffnesses = [4200.0, 10400.0, 0.0]";
    let cases: [(String, &str); 9] = [
        (format!("{good}\nmass = 1.0"), "carrier.0.mass"),
        (format!("{good}\nforce = 1.0"), "carrier.0.force"),
        (format!("{good}\npreload = 0.1"), "carrier.0.preload"),
        (
            "masses = [7.2]\nstiffnesses = [1.0]".into(),
            "carrier.0.masses",
        ),
        (
            "masses = [7.2, 1.0]\nstiffnesses = [1.0]".into(),
            "carrier.0.stiffnesses",
        ),
        (
            "masses = [7.2, 1.0]\nstiffnesses = [0.0, 1.0]".into(),
            "carrier.0.stiffnesses.0",
        ),
        (
            "masses = [7.2, -1.0]\nstiffnesses = [1.0, 1.0]".into(),
            "carrier.0.masses.1",
        ),
        (format!("{good}\nuplift = -3.0"), "carrier.0.uplift"),
        (
            "mass = 1.0\nstiffness = 1.0\ndampings = [1.0]".into(),
            "carrier.0.dampings",
        ),
    ];
    for (carrier, field) in cases {
        let start = REFERENCE.find("[[carrier]]").unwrap();
        let end = REFERENCE.find("[contact]").unwrap();
        let text = format!(
            "{}[[carrier]]\n{carrier}\nside = \"below\"\nstart = 0.0\nspeed = {{ profile = \"constant\", value = 10.0 }}\n\n{}",
            &REFERENCE[..start],
            &REFERENCE[end..]
        );
        let e = taut::resolve_scene(&text, &[])
            .err()
            .unwrap_or_else(|| panic!("accepted: {carrier}"))
            .to_string();
        assert!(e.contains(&format!("`{field}`")), "{field}: {e}");
    }
}

#[test]
fn modal_exact_refuses_the_chain_and_the_others_carry_it() {
    let with = |method: &str| {
        scene(
            "pantograph_3mass.toml",
            &[
                "mesh.elements=50",
                "time.end=0.05",
                &format!("integrator.method=\"{method}\""),
            ],
        )
    };
    let modal_exact = scene(
        "pantograph_3mass.toml",
        &[
            "mesh.kind=\"galerkin\"",
            "mesh.modes=50",
            "time.end=0.05",
            "integrator.method=\"modal_exact\"",
        ],
    );
    let e = taut::run(&modal_exact, &mut |_, _| {})
        .err()
        .map(|e| e.to_string())
        .expect("modal_exact ran a chain");
    assert!(
        e.contains("`integrator.method`") && e.contains("modal_exact"),
        "{e}"
    );
    // every other method runs it, and starts from the static force
    let want = 490.0 - 9.81 * (7.2 + 15.5 + 15.0);
    for method in [
        "generalized_alpha",
        "newmark",
        "hht",
        "wbz",
        "bathe",
        "central_difference",
        "moreau_jean",
    ] {
        let out = run(&with(method));
        let f = &out.history.carriers[0].force;
        assert!(
            (f[0] - want).abs() <= 1e-9 * want,
            "{method}: λ(0) = {}",
            f[0]
        );
        assert!(f.iter().all(|x| x.is_finite()), "{method}");
    }
}
