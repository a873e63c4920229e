//! The time integrators side by side (MODEL §9.1), each verified the same way.
//!
//! * **Amplification** of a one-dof oscillator (`scenes/oscillator_one_dof.toml`,
//!   ω = 60 rad/s): the spectral radius ρ and phase φ per step that taut's
//!   full run shows (an exact two-term recurrence fitted to its history)
//!   equal the principal eigenvalues of each method's amplification matrix,
//!   written here independently from MODEL's formulas in scalar form; and
//!   those matrices have the literature's closed forms (trapezoidal ρ = 1,
//!   φ = 2 atan(Ω/2); central difference φ = 2 asin(Ω/2); ρ(Ω → ∞) = ρ∞ for
//!   generalized-α, (1 − α)/(1 + α) for HHT, 0 for Bathe, (1 − θ)/θ for
//!   Moreau–Jean).
//! * **Energy** of a contact-free beam under a standing force: conserved by
//!   the trapezoidal members (ρ∞ = 1, Newmark, Moreau–Jean θ = ½),
//!   decaying for Bathe, HHT and ρ∞ < 1.
//! * **Observed time order** where Δt limits the error is in
//!   `tests/time_orders.rs` (2 for every second-order method); here
//!   Moreau–Jean θ = 1 on the oscillator (1) and Moreau–Jean θ = ½ through
//!   the impacts of a mass bouncing on it (1).
//! * **The explicit method's limit**: ω_max by Lanczos against a dense
//!   solve; runs just below 2/ω_max pass, just above are refused, and an
//!   unchecked run just above the true limit grows without bound.
//! * **The study's T1 and T2** under every method; the reference case's
//!   convergence across methods behind `--ignored` (cut-down by default).

use crate::common;

use nalgebra::DMatrix;
use taut::error::Error;
use taut::integrate::{
    CentralDifference, Initial, Integrator, MethodFactory, State, Stepper, System,
};
use taut::scene::{GenAlphaParams, Method};
use taut::{Resolved, resolve_scene, run};

const OSCILLATOR: &str = include_str!("../scenes/oscillator_one_dof.toml");
const MOVING_FORCE: &str = include_str!("../scenes/moving_force_beam.toml");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// ω of the oscillator scene: sqrt(3T/(ρA h²)) with T = 1200 N, ρA = 1 kg/m,
/// h = 1 m.
const OMEGA: f64 = 60.0;

/// A two-term recurrence fitted to an exact two-term sequence recovers its
/// coefficients to round-off times the fit's conditioning (measured ≤ 2e-12
/// for these runs); the margin covers the ill-conditioning at small Ω,
/// where successive samples are nearly equal.
const AMPLIFICATION_TOL: f64 = 1e-8;

/// A method under test: its scene overrides and its amplification map.
struct Case {
    label: &'static str,
    set: &'static str,
    map: fn(f64) -> DMatrix<f64>,
}

impl Case {
    /// Steps to skip before fitting: the map's extra roots must die out.
    fn transient(&self) -> usize {
        if (self.map)(0.5).nrows() > 2 {
            TRANSIENT_STEPS
        } else {
            0
        }
    }
}

/// The generalized-α family's map on (d, v, a) for ω = 1, Δt = h (MODEL §5).
fn gen_alpha_map(p: GenAlphaParams, h: f64) -> DMatrix<f64> {
    let GenAlphaParams {
        alpha_m,
        alpha_f,
        beta,
        gamma,
    } = p;
    let step = |x: [f64; 3]| -> [f64; 3] {
        let [d, v, a] = x;
        let pred = d + h * v + h * h * (0.5 - beta) * a;
        let a1 = -(alpha_m * a + (1.0 - alpha_f) * pred + alpha_f * d)
            / ((1.0 - alpha_m) + (1.0 - alpha_f) * beta * h * h);
        [
            pred + beta * h * h * a1,
            v + h * ((1.0 - gamma) * a + gamma * a1),
            a1,
        ]
    };
    columns(3, |x| step([x[0], x[1], x[2]]).to_vec())
}

/// Bathe's map on (d, v, a) for ω = 1 (MODEL §9.1).
fn bathe_map(g: f64, h: f64) -> DMatrix<f64> {
    let c0 = 2.0 / (g * h);
    let c1 = (1.0 - g) / (g * h);
    let c2 = -1.0 / ((1.0 - g) * g * h);
    let c3 = (2.0 - g) / ((1.0 - g) * h);
    columns(3, |x| {
        let (d, v, a) = (x[0], x[1], x[2]);
        let d1 = (c0 * c0 * d + 2.0 * c0 * v + a) / (1.0 + c0 * c0);
        let v1 = c0 * (d1 - d) - v;
        let d2 = -(c1 * v + c2 * v1 + c3 * (c1 * d + c2 * d1)) / (1.0 + c3 * c3);
        let v2 = c1 * d + c2 * d1 + c3 * d2;
        vec![d2, v2, c1 * v + c2 * v1 + c3 * v2]
    })
}

/// Central difference on (d_n, v_{n−1/2}) for ω = 1.
fn central_difference_map(h: f64) -> DMatrix<f64> {
    columns(2, |x| {
        let v = x[1] - h * x[0];
        vec![x[0] + h * v, v]
    })
}

/// Moreau–Jean's θ-scheme on (d, v) for ω = 1.
fn moreau_jean_map(theta: f64, h: f64) -> DMatrix<f64> {
    columns(2, |x| {
        let (d, v) = (x[0], x[1]);
        let v1 = (v - h * (d + theta * (1.0 - theta) * h * v)) / (1.0 + theta * theta * h * h);
        vec![d + h * ((1.0 - theta) * v + theta * v1), v1]
    })
}

/// The matrix of a linear map, column by column from unit vectors.
fn columns(n: usize, f: impl Fn(&[f64]) -> Vec<f64>) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(n, n);
    for j in 0..n {
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        for (i, v) in f(&e).into_iter().enumerate() {
            m[(i, j)] = v;
        }
    }
    m
}

/// The principal eigenvalue (largest positive imaginary part, else largest
/// modulus) as (ρ, φ).
fn principal(m: &DMatrix<f64>) -> (f64, f64) {
    let z = m
        .complex_eigenvalues()
        .iter()
        .copied()
        .max_by(|a, b| {
            (a.im, a.norm())
                .partial_cmp(&(b.im, b.norm()))
                .expect("finite")
        })
        .expect("a nonempty matrix");
    (z.norm(), z.im.atan2(z.re))
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            label: "generalized_alpha ρ∞ = 1",
            set: "integrator={ method = \"generalized_alpha\", rho_inf = 1.0 }",
            map: |h| gen_alpha_map(GenAlphaParams::from_rho_inf(1.0), h),
        },
        Case {
            label: "generalized_alpha ρ∞ = 0.5",
            set: "integrator={ method = \"generalized_alpha\", rho_inf = 0.5 }",
            map: |h| gen_alpha_map(GenAlphaParams::from_rho_inf(0.5), h),
        },
        Case {
            label: "newmark",
            set: "integrator={ method = \"newmark\" }",
            map: |h| gen_alpha_map(GenAlphaParams::newmark(), h),
        },
        Case {
            label: "hht α = 0.1",
            set: "integrator={ method = \"hht\", alpha = 0.1 }",
            map: |h| gen_alpha_map(GenAlphaParams::hht(0.1), h),
        },
        Case {
            label: "wbz ρ∞ = 0.5",
            set: "integrator={ method = \"wbz\", rho_inf = 0.5 }",
            map: |h| gen_alpha_map(GenAlphaParams::wbz(0.5), h),
        },
        Case {
            label: "bathe γ = 0.5",
            set: "integrator={ method = \"bathe\" }",
            map: |h| bathe_map(0.5, h),
        },
        Case {
            label: "central_difference",
            set: "integrator={ method = \"central_difference\" }",
            map: central_difference_map,
        },
        Case {
            label: "moreau_jean θ = 0.5",
            set: "integrator={ method = \"moreau_jean\", theta = 0.5 }",
            map: |h| moreau_jean_map(0.5, h),
        },
        Case {
            label: "moreau_jean θ = 1",
            set: "integrator={ method = \"moreau_jean\", theta = 1.0 }",
            map: |h| moreau_jean_map(1.0, h),
        },
    ]
}

/// Steps left out of the fit for a method with a third (spurious) root: the
/// start excites it and it must die out first (|λ₃| ≤ 0.5 for these
/// parameter sets, so 0.5⁶⁰ ≈ 1e-18); then a window of samples short enough
/// that a strongly damped oscillation (ρ = 0.55 for θ = 1 at Ω = 1.5) stays
/// far above round-off (0.55²⁴ ≈ 6e-7).
const TRANSIENT_STEPS: usize = 60;
const FIT_WINDOW: usize = 24;

/// (ρ, φ) of the node's oscillation about its static deflection in a taut
/// run at ωΔt = Ω: least squares e_{k+1} = c₁e_k + c₂e_{k−1} after the
/// transient, so ρ² = −c₂ and cos φ = c₁/(2ρ).
fn measured(set: &str, big_omega: f64, transient: usize) -> (f64, f64) {
    let dt = big_omega / OMEGA;
    let sc = resolve_scene(
        OSCILLATOR,
        &[
            set.to_string(),
            format!("time.step={dt:e}"),
            format!("time.end={:e}", (transient + FIT_WINDOW + 1) as f64 * dt),
        ],
    )
    .expect("the oscillator scene resolves");
    let out = run(&sc, &mut |_, _| {}).expect("the oscillator runs");
    let static_deflection = 10.0 / (2.0 * 1200.0 / 1.0);
    let e: Vec<f64> = out.history.probes[0]
        .1
        .iter()
        .map(|v| v - static_deflection)
        .collect();
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in transient + 2..e.len() {
        let (x1, x2, y) = (e[k - 1], e[k - 2], e[k]);
        a11 += x1 * x1;
        a12 += x1 * x2;
        a22 += x2 * x2;
        b1 += x1 * y;
        b2 += x2 * y;
    }
    let det = a11 * a22 - a12 * a12;
    let c1 = (b1 * a22 - b2 * a12) / det;
    let c2 = (a11 * b2 - a12 * b1) / det;
    let rho = (-c2).sqrt();
    (rho, (c1 / (2.0 * rho)).clamp(-1.0, 1.0).acos())
}

#[test]
fn one_dof_amplification_matches_each_method_s_closed_form() {
    for case in cases() {
        for big_omega in [0.1, 0.6, 1.5] {
            let (rho, phi) = measured(case.set, big_omega, case.transient());
            let (rho_x, phi_x) = principal(&(case.map)(big_omega));
            let period_elongation = big_omega / phi - 1.0;
            println!(
                "{:28} Ω = {big_omega:4}: ρ = {rho:.12} ({rho_x:.12}), period elongation {period_elongation:+.6e}",
                case.label
            );
            assert!(
                (rho - rho_x).abs() <= AMPLIFICATION_TOL,
                "{}: Ω = {big_omega}: ρ = {rho} vs closed form {rho_x}",
                case.label
            );
            assert!(
                (phi - phi_x).abs() <= AMPLIFICATION_TOL * phi_x,
                "{}: Ω = {big_omega}: φ = {phi} vs closed form {phi_x}",
                case.label
            );
        }
    }
}

/// The maps against the literature's closed forms (MODEL §9.1 references).
#[test]
fn the_maps_have_the_literature_s_closed_forms() {
    // exact expressions: round-off of a 3×3 eigenproblem
    const EXACT: f64 = 1e-12;
    for big_omega in [0.1, 0.6, 1.5] {
        let (rho, phi) = principal(&gen_alpha_map(GenAlphaParams::newmark(), big_omega));
        assert!((rho - 1.0).abs() < EXACT);
        assert!((phi - 2.0 * (big_omega / 2.0).atan()).abs() < EXACT);
        let (rho, phi) = principal(&moreau_jean_map(0.5, big_omega));
        assert!((rho - 1.0).abs() < EXACT);
        assert!((phi - 2.0 * (big_omega / 2.0).atan()).abs() < EXACT);
        let (rho, phi) = principal(&central_difference_map(big_omega));
        assert!((rho - 1.0).abs() < EXACT);
        assert!((phi - 2.0 * (big_omega / 2.0).asin()).abs() < EXACT);
    }
    // spectral radius at infinite frequency (ρ(Ω) − ρ(∞) falls like 1/Ω:
    // 1e-4 at Ω = 1e6, so Ω = 1e10 is within 1e-7 of the limit)
    const AT_INFINITY: f64 = 1e-6;
    let infinite = 1e10;
    let radius = |m: DMatrix<f64>| {
        m.complex_eigenvalues()
            .iter()
            .map(|z| z.norm())
            .fold(0.0, f64::max)
    };
    for rho_inf in [0.0, 0.5, 0.8] {
        let r = radius(gen_alpha_map(
            GenAlphaParams::from_rho_inf(rho_inf),
            infinite,
        ));
        assert!((r - rho_inf).abs() < AT_INFINITY, "ρ∞ = {rho_inf}: {r}");
    }
    for alpha in [0.05, 0.3] {
        let r = radius(gen_alpha_map(GenAlphaParams::hht(alpha), infinite));
        let exact = (1.0 - alpha) / (1.0 + alpha);
        assert!((r - exact).abs() < AT_INFINITY, "hht α = {alpha}: {r}");
    }
    assert!(radius(bathe_map(0.5, infinite)) < AT_INFINITY);
    for theta in [0.5, 0.75, 1.0] {
        let r = radius(moreau_jean_map(theta, infinite));
        assert!(
            (r - (1.0 - theta) / theta).abs() < AT_INFINITY,
            "θ = {theta}: {r}"
        );
    }
    // central difference: |z| > 1 beyond Ω = 2
    assert!(radius(central_difference_map(2.05)) > 1.2);
}

/// Energy round-off: each step adds O(n) operations of size |E parts|; over
/// a few hundred steps 1e3·n·ε of the largest part bounds the drift (as in
/// tests/invariants.rs; measured drift ≤ 1e-13 of the scale).
fn energy_tol(n: usize, scale: f64) -> f64 {
    1e3 * n as f64 * f64::EPSILON * scale
}

/// A decaying method must lose at least this fraction of the energy scale
/// over the run: far above round-off, far below the measured losses
/// (printed; 3e-4 for HHT α = 0.05 … 0.5 for Bathe at this coarse step).
const MIN_DECAY: f64 = 1e-5;

#[test]
fn energy_is_conserved_or_decays_as_each_method_should() {
    // a standing force on a coarse beam, a step that leaves the top modes
    // unresolved (ω_max Δt ≈ 60): the dissipative methods damp them
    let base = [
        "carrier.start=17.0".to_string(),
        "carrier.speed={ profile = \"constant\", value = 0.0 }".to_string(),
        // a standing force: not the moving-force series the scene declares
        "reference.kind=richardson".to_string(),
        "mesh.elements=20".to_string(),
        "time.step=2e-3".to_string(),
        "time.end=0.6".to_string(),
    ];
    let conserving = [
        "integrator={ method = \"generalized_alpha\", rho_inf = 1.0 }",
        "integrator={ method = \"newmark\" }",
        "integrator={ method = \"moreau_jean\", theta = 0.5 }",
    ];
    let decaying = [
        "integrator={ method = \"generalized_alpha\", rho_inf = 0.5 }",
        "integrator={ method = \"hht\", alpha = 0.05 }",
        "integrator={ method = \"bathe\" }",
        "integrator={ method = \"moreau_jean\", theta = 0.75 }",
    ];
    for (set, conserves) in conserving
        .iter()
        .map(|s| (s, true))
        .chain(decaying.iter().map(|s| (s, false)))
    {
        let mut o = base.to_vec();
        o.push(set.to_string());
        let sc = resolve_scene(MOVING_FORCE, &o).expect("scene resolves");
        let mut it = Integrator::new(&sc).expect("integrator builds");
        let e0 = it.energy();
        let mut scale = e0.scale();
        let mut last = e0.total();
        for _ in 0..sc.steps {
            it.step().expect("step");
            let e = it.energy();
            scale = scale.max(e.scale());
            let tol = energy_tol(it.dofs(), scale);
            if conserves {
                assert!(
                    (e.total() - e0.total()).abs() <= tol,
                    "{set}: drift {:e} (scale {scale:e})",
                    e.total() - e0.total()
                );
            } else {
                assert!(
                    e.total() <= e0.total() + tol,
                    "{set}: grew by {:e}",
                    e.total() - e0.total()
                );
            }
            last = e.total();
        }
        let loss = (e0.total() - last) / scale;
        println!("{set}: energy lost {loss:.3e} of its scale");
        if !conserves {
            assert!(loss >= MIN_DECAY, "{set}: lost only {loss:e}");
        }
    }
}

/// Observed orders at the finest level of a step ladder: measured 1.00 for
/// θ = 1 on the oscillator and 1.02–1.04 for Moreau–Jean through the
/// reference case's impacts (printed); ±0.25 separates first from second
/// order with room for pre-asymptotic scatter. The second-order methods'
/// orders are measured where Δt limits the error, in `tests/time_orders.rs`.
const ORDER_TOL: f64 = 0.25;

/// Without impacts Moreau–Jean is the θ-method: second order at θ = ½
/// (`tests/time_orders.rs`), first at θ = 1. Measured on the oscillator's step
/// response d_s(1 − cos ωt), exact: the moving force's many modes keep
/// θ = 1 pre-asymptotic over any practical ladder (its damping
/// e^{−ω²Δt t/2} of the mesh's top modes; 0.5–0.8 measured there).
#[test]
fn moreau_jean_theta_one_is_first_order_without_impacts() {
    let errors: Vec<f64> = [2e-3, 1e-3, 5e-4, 2.5e-4]
        .iter()
        .map(|dt| {
            let sc = resolve_scene(
                OSCILLATOR,
                &[
                    "integrator={ method = \"moreau_jean\", theta = 1.0 }".to_string(),
                    format!("time.step={dt:e}"),
                    "time.end=0.2".to_string(),
                ],
            )
            .expect("scene");
            let out = run(&sc, &mut |_, _| {}).expect("runs");
            // the scene's declared reference: the model's exact d_s(1 − cos ωt)
            let exact = taut::study::reference::exact(&sc)
                .expect("reference")
                .and_then(|e| e.field)
                .expect("the oscillator declares standing_force_modes");
            let x = sc.probes[0].1;
            out.history
                .t
                .iter()
                .zip(&out.history.probes[0].1)
                .map(|(&t, v)| (v - exact(x, t)).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let order = taut::study::uncertainty::observed_order(errors[2], errors[3], 2.0);
    println!("moreau_jean θ = 1 on the oscillator: errors {errors:?}, order {order:.2}");
    assert!((order - 1.0).abs() <= ORDER_TOL, "order {order}");
}

/// The oscillator with a light mass (0.05 kg, no spring) resting on its
/// node under gravity: the node's oscillation about its static deflection
/// (amplitude 4.2 mm at 60 rad/s, peak acceleration 15 m/s² > g) throws the
/// mass off, and it lands again: 15 loss intervals and re-contacts in 1 s,
/// plastic impacts (e = 0). The carrier stands still, so nothing but the
/// impacts separates Moreau–Jean from the trapezoidal rule here.
fn bouncing_mass(theta: f64, dt: f64) -> Resolved {
    let toml = format!(
        "{OSCILLATOR}
[[carrier]]
mass = 0.05
stiffness = 0.0
side = \"above\"
start = 1.0
speed = {{ profile = \"constant\", value = 0.0 }}

[gravity]
g = 9.81
"
    );
    resolve_scene(
        &toml,
        &[
            format!("integrator={{ method = \"moreau_jean\", theta = {theta:?} }}"),
            format!("time.step={dt:e}"),
            // the oscillator declares its standing force's exact solution;
            // with a mass on it that reference no longer applies
            "reference.kind=\"richardson\"".to_string(),
        ],
    )
    .expect("the bouncing-mass scene resolves")
}

/// Observed order of Moreau–Jean through impacts, over the whole ladder:
/// measured 1.03 with θ = ½ (single halvings scatter from 0.77 to 1.29, as
/// the impact instants fall at different places within the steps);
/// ±0.25 separates it from second order.
const IMPACT_ORDER_TOL: f64 = 0.25;

/// Where impacts occur Moreau–Jean is first order however small Δt, even
/// with θ = ½: the bouncing mass's displacement q against θ = ½ at
/// Δt = 1.953125e-6 s, Δt = 1e-3 … 3.125e-5 s.
#[test]
fn moreau_jean_is_first_order_through_impacts() {
    let dts = [1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5];
    let reference = run(&bouncing_mass(0.5, 1.953125e-6), &mut |_, _| {}).expect("runs");
    let stride = (dts[0] / 1.953125e-6f64).round() as usize;
    let q_ref: Vec<f64> = reference.history.carriers[1]
        .q
        .iter()
        .step_by(stride)
        .copied()
        .collect();
    let peak = q_ref.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    let mut errors = Vec::new();
    for dt in dts {
        let out = run(&bouncing_mass(0.5, dt), &mut |_, _| {}).expect("runs");
        let stats = &out.stats[1];
        assert!(
            stats.loss_fraction > 0.1,
            "Δt = {dt}: the mass must leave the node and land again (P_l {})",
            stats.loss_fraction
        );
        let k = (dts[0] / dt).round() as usize;
        let q: Vec<f64> = out.history.carriers[1]
            .q
            .iter()
            .step_by(k)
            .copied()
            .collect();
        let e = q
            .iter()
            .zip(&q_ref)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        errors.push(e / peak);
    }
    let order = taut::study::uncertainty::fitted_order(&errors, 2.0);
    println!(
        "moreau_jean θ = ½ through impacts: q errors {errors:?}, order over the ladder {order:.2}"
    );
    assert!(
        (order - 1.0).abs() <= IMPACT_ORDER_TOL,
        "order {order}: {errors:?}"
    );
}

/// Lanczos against a dense solve: θ ≤ ω_max² ≤ θ + r, and θ within this of
/// ω_max² after 100 steps (measured 3e-5 on the reference beam at N = 400,
/// 6e-5 at N = 200, 4e-5 for the string at N = 200).
const LANCZOS_REL: f64 = 1e-4;

#[test]
fn central_difference_omega_max_is_the_assembled_model_s() {
    for (text, n) in [
        (REFERENCE, 50usize),
        (REFERENCE, 200),
        (
            include_str!("../scenes/t2_stationary_mass_string.toml"),
            200,
        ),
    ] {
        let sc = resolve_scene(text, &[format!("mesh.elements={n}")]).expect("scene");
        let dense = taut::model::modal::fe_frequencies(&sc.beam, n, usize::MAX)
            .expect("dense solve")
            .last()
            .copied()
            .expect("frequencies")
            .powi(2);
        let beam = taut::model::beam::BeamModel::new(&sc.beam, n);
        let mf = taut::model::banded::BandedLdlt::factor(&beam.mass).expect("M factors");
        let (theta, r) = taut::model::spectrum::lanczos_max(&beam, &mf, 100);
        let bound = taut::model::spectrum::element_bound(&sc.beam, beam.h).powi(2);
        println!(
            "N = {n}: dense ω_max² {dense:.8e}, Lanczos θ {theta:.8e} + r {r:.2e}, element bound {bound:.4e}"
        );
        // Ritz values are below ω_max², θ + r above, up to round-off
        const ROUND_OFF: f64 = 1e-12;
        assert!(theta <= dense * (1.0 + ROUND_OFF), "{theta} > {dense}");
        assert!(
            dense <= (theta + r) * (1.0 + ROUND_OFF),
            "{dense} > {theta} + {r}"
        );
        assert!((dense - theta) / dense <= LANCZOS_REL);
        assert!(bound >= dense * (1.0 - ROUND_OFF));
    }
}

/// A factory for central difference without its stability check, to show
/// what the check prevents.
struct Unchecked;

impl taut::scene::MethodInfo for Unchecked {
    fn name(&self) -> String {
        "central_difference (unchecked)".into()
    }
}

impl MethodFactory for Unchecked {
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> taut::Result<Box<dyn Stepper>> {
        Ok(Box::new(CentralDifference::unchecked(sc, sys, st, init)))
    }
}

#[test]
fn central_difference_runs_below_its_limit_and_is_refused_above() {
    let base = ["mesh.elements=100".to_string(), "time.end=0.2".to_string()];
    let sc = resolve_scene(REFERENCE, &base).expect("scene");
    let limit = taut::integrate::central_difference_limit(&sc).expect("M factors");
    let with_dt = |factor: f64| {
        let mut o = base.to_vec();
        o.push("integrator={ method = \"central_difference\" }".into());
        o.push(format!("time.step={:e}", factor * limit.dt_max));
        resolve_scene(REFERENCE, &o).expect("scene")
    };
    // just below: runs to the end, bounded
    let below = run(&with_dt(0.99), &mut |_, _| {}).expect("a step below the limit runs");
    assert!(below.history.carriers[0].w.iter().all(|w| w.abs() < 1.0));
    // just above: refused before the run, naming ω_max and the largest step
    let e = run(&with_dt(1.01), &mut |_, _| {}).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, Error::Invalid { .. }), "{msg}");
    assert!(
        msg.contains("time.step")
            && msg.contains(&format!("{:.4e}", limit.dt_max))
            && msg.contains("ω_max"),
        "{msg}"
    );
    // and unchecked, a step 2 % above the assembled model's true limit
    // (2/ω_max by dense solve) diverges: the check is not conservative theatre
    let dense = taut::model::modal::fe_frequencies(&sc.beam, 100, usize::MAX)
        .expect("dense")
        .last()
        .copied()
        .expect("ω_max");
    let mut o = base.to_vec();
    o.push("integrator={ method = \"central_difference\" }".into());
    o.push(format!("time.step={:e}", 1.02 * 2.0 / dense));
    let sc = resolve_scene(REFERENCE, &o).expect("scene");
    let e = taut::run_with(&sc, &Unchecked, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, Error::Diverged { .. }), "{e}");
}

#[test]
fn combinations_that_mean_nothing_are_refused_naming_both_keys() {
    for (sets, words) in [
        (
            ["integrator.method=bathe", "contact.placement=alpha"],
            ["contact.placement", "bathe"],
        ),
        (
            [
                "integrator.method=moreau_jean",
                "contact.formulation=penalty",
            ],
            ["contact.formulation", "moreau_jean"],
        ),
        (
            [
                "integrator.method=moreau_jean",
                "contact.formulation=impact",
            ],
            ["contact.formulation", "moreau_jean"],
        ),
        (
            [
                "integrator.method=central_difference",
                "contact.placement=alpha",
            ],
            ["contact.placement", "central_difference"],
        ),
    ] {
        // the reference scene sets rho_inf: select the method as a table
        let method = sets[0].trim_start_matches("integrator.method=");
        let o = vec![
            format!("integrator={{ method = \"{method}\" }}"),
            sets[1].to_string(),
        ];
        let e = resolve_scene(REFERENCE, &o).unwrap_err().to_string();
        for w in words {
            assert!(e.contains(w), "{sets:?}: {e}");
        }
    }
    // a parameter of another method
    let e = resolve_scene(REFERENCE, &["integrator.method=bathe".to_string()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("integrator.rho_inf") && e.contains("bathe"),
        "{e}"
    );
}

/// T2 under every method: the wave launched at t = 0 returns from the far
/// support after 2(L − x0)/c within 1 % (the acceptance band of
/// tests/verification_t2_wave_travel.rs), and T1's tip deflection at
/// 0.15 s lies in the published band for every method.
#[test]
fn the_study_s_t1_and_t2_hold_under_every_method() {
    const RETURN_TIME_TOL: f64 = 0.01;
    const PUBLISHED_TIP: f64 = -0.06;
    const PLOT_READING: f64 = 0.005;
    let t2 = include_str!("../scenes/t2_stationary_mass_string.toml");
    let t1 = include_str!("../scenes/t1_cantilever_riding_mass.toml");
    for m in [
        Method::GeneralizedAlpha,
        Method::Newmark,
        Method::Bathe,
        Method::CentralDifference,
        Method::MoreauJean,
    ] {
        let mut o = vec![format!("integrator={{ method = \"{}\" }}", m.name())];
        o.push("time.end=1.0".into());
        if m == Method::CentralDifference {
            o.push("time.step=5e-5".into());
        }
        let sc = resolve_scene(t2, &o).expect("T2 resolves");
        let out = run(&sc, &mut |_, _| {}).expect("T2 runs");
        let arrival = common::t2_return_time(&out, sc.dt);
        let theory = 2.0 * (sc.beam.length - 1.0) / sc.beam.wave_speed();
        println!(
            "T2 {}: return {arrival:.4} s (theory {theory:.4} s)",
            m.name()
        );
        assert!(
            (arrival - theory).abs() <= RETURN_TIME_TOL * theory,
            "{}: {arrival}",
            m.name()
        );

        let mut o = vec![format!("integrator={{ method = \"{}\" }}", m.name())];
        o.extend(["mesh.elements=40".into(), "time.step=1e-5".into()]);
        if m == Method::CentralDifference {
            // the stiff cantilever's ω_max = 7.5e5 rad/s: Δt ≤ 2.67e-6 s
            o.push("time.step=2.5e-6".into());
        }
        let sc = resolve_scene(t1, &o).expect("T1 resolves");
        let out = run(&sc, &mut |_, _| {});
        if m == Method::Newmark {
            // the riding mass is a moving bilateral constraint, which
            // Newmark's α_f = 0 leaves undamped: it must stop and say why
            let e = out.expect_err("Newmark on T1 diverges").to_string();
            assert!(
                e.contains("integrator.method = newmark") && e.contains("α_f"),
                "{e}"
            );
            continue;
        }
        let out = out.expect("T1 runs");
        let tip = *out.history.probes[0].1.last().expect("a tip history");
        println!("T1 {}: tip at 0.15 s {tip:.5} m", m.name());
        assert!(
            (tip - PUBLISHED_TIP).abs() <= PLOT_READING,
            "{}: tip {tip}",
            m.name()
        );
    }
}

/// The method added outside the crate (`examples/custom_method.rs`):
/// backward Euler, through the public trait, is first order on the exact
/// one-dof case where generalized-α is second (measured 0.94 and 2.00).
use crate::custom_method;

#[test]
fn a_method_added_outside_the_crate_runs_with_its_own_order() {
    let be = custom_method::oscillator_order(&custom_method::BackwardEulerFactory).unwrap();
    let ga = custom_method::oscillator_order(&Method::GeneralizedAlpha).unwrap();
    println!("backward Euler {be:.2}, generalized-α {ga:.2}");
    assert!((be - 1.0).abs() <= ORDER_TOL, "backward Euler: {be}");
    assert!((ga - 2.0).abs() <= ORDER_TOL, "generalized-α: {ga}");
    // and with contact, through the shared system: the reference case runs
    let sc = resolve_scene(REFERENCE, &["time.end=0.2".to_string()]).unwrap();
    let out = taut::run_with(&sc, &custom_method::BackwardEulerFactory, &mut |_, _| {}).unwrap();
    assert!(out.stats[0].max_penetration < 1e-12);
}

// The reference case's measures (in-span P_l, the 0–20 Hz force error in
// span, the force's step-to-step component), shared with the report.
use xtask::methods as methods_report;

/// The reference case under every method converges to the same in-span
/// 0–20 Hz contact force as Δt falls: the error against generalized-α at a
/// 4× finer step falls under every method from one step to the next
/// (cut-down: Δt = 1e-4 → 5e-5 s; central difference 5e-5 → 2.5e-5 s).
#[test]
fn every_method_converges_to_the_same_in_span_force() {
    let reference = run(
        &methods_report::scene("method = \"generalized_alpha\"", 1.25e-5, &[]),
        &mut |_, _| {},
    )
    .expect("reference");
    for (label, m) in methods_report::METHODS {
        let steps = if label.starts_with("central") {
            [5e-5, 2.5e-5]
        } else {
            [1e-4, 5e-5]
        };
        let errors: Vec<f64> = steps
            .iter()
            .map(|&dt| {
                let sc = methods_report::scene(m, dt, &[]);
                let out = run(&sc, &mut |_, _| {}).expect(label);
                methods_report::force_error(&out, &reference, sc.beam.length)
            })
            .collect();
        println!("{label}: 0–20 Hz in-span force error {errors:?}");
        assert!(errors[1] < errors[0], "{label}: {errors:?}");
    }
}

/// The full ladder (docs/methods.md, section 2): at Δt = 1.25e-5 s every
/// method's in-span 0–20 Hz force is within this of generalized-α's at
/// 6.25e-6 s (measured 2.4e-6 … 8.6e-5, Bathe the largest: its damping of
/// the resolved modes at the coarse steps).
const LADDER_AGREEMENT: f64 = 2e-4;

/// In-span P_l at V0/c = 0.9 (N = 1600, docs/methods.md section 3): the
/// methods' values at Δt = 1.25e-5 s spread over 0.0182 … 0.0187 around
/// generalized-α's converged 0.0186 (a step is 3e-5 of the run).
const IN_SPAN_LOSS_AGREEMENT: f64 = 6e-4;

#[test]
#[ignore = "the full ladder: about a minute in release; cargo test --release -- --ignored"]
fn every_method_agrees_at_the_finest_step_of_the_ladder() {
    let reference = run(
        &methods_report::scene("method = \"generalized_alpha\"", 6.25e-6, &[]),
        &mut |_, _| {},
    )
    .expect("reference");
    let fast_ref = run(
        &methods_report::scene(
            "method = \"generalized_alpha\"",
            1.25e-5,
            methods_report::FAST,
        ),
        &mut |_, _| {},
    )
    .expect("reference at V0/c = 0.9");
    let pl_ref = methods_report::in_span_loss(&fast_ref, 50.0);
    for (label, m) in methods_report::METHODS {
        // central difference at N = 1600 needs Δt ≤ 2/ω_max ≈ 3.9e-6 s
        let (dt, dt_fast) = if label.starts_with("central") {
            (1.25e-5, 1.5625e-6)
        } else {
            (1.25e-5, 1.25e-5)
        };
        let sc = methods_report::scene(m, dt, &[]);
        let out = run(&sc, &mut |_, _| {}).expect(label);
        let e = methods_report::force_error(&out, &reference, sc.beam.length);
        let sc = methods_report::scene(m, dt_fast, methods_report::FAST);
        let out = run(&sc, &mut |_, _| {}).expect(label);
        let pl = methods_report::in_span_loss(&out, sc.beam.length);
        println!(
            "{label}: force error {e:.2e}, in-span P_l at V0/c = 0.9 {pl:.4} (generalized-α {pl_ref:.4})"
        );
        assert!(e < LADDER_AGREEMENT, "{label}: {e}");
        assert!(
            (pl - pl_ref).abs() < IN_SPAN_LOSS_AGREEMENT,
            "{label}: {pl} vs {pl_ref}"
        );
    }
}

/// A built-in method value builds the method it is:
/// `run_with(&scene, &Method::Newmark)` on the reference scene, whose own
/// method is generalized-α, steps Newmark — bit-identical to the scene
/// that names newmark, and not the scene's generalized-α (their forces
/// differ by about 6e-3 N on this case).
#[test]
fn a_built_in_method_value_runs_that_method_whatever_the_scene_names() {
    let short = "time.end=0.02".to_string();
    let own = resolve_scene(REFERENCE, std::slice::from_ref(&short)).unwrap();
    assert_eq!(own.method.name(), "generalized_alpha");
    let named = resolve_scene(
        REFERENCE,
        &[short, "integrator={ method = \"newmark\" }".to_string()],
    )
    .unwrap();
    let quiet = &mut |_: usize, _: usize| {};
    let via_value = taut::run_with(&own, &Method::Newmark, quiet).unwrap();
    let newmark = run(&named, quiet).unwrap();
    let alpha = run(&own, quiet).unwrap();
    // Debug prints each f64 exactly (shortest round trip): equal text is
    // equal bits
    let bits = |o: &taut::RunOutput| format!("{:?} {:?}", o.history, o.stats);
    assert_eq!(bits(&via_value), bits(&newmark));
    assert_ne!(bits(&via_value), bits(&alpha));
    // and a method refuses a scene it does not go with, as validation does
    let alpha_level = resolve_scene(
        REFERENCE,
        &[
            "time.end=0.02".to_string(),
            "contact.placement=\"alpha\"".to_string(),
        ],
    )
    .unwrap();
    let e = taut::run_with(&alpha_level, &Method::Bathe, quiet)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("contact.placement") && e.contains("integrator.method = bathe"),
        "{e}"
    );
}

/// A method of one's own registered by name is reached as a built-in one
/// is: a scene naming it runs it (bit-identical to `run_with`
/// its factory), `--methods` parses it, and a key it does not read is
/// refused naming both methods.
#[test]
fn a_registered_method_is_reached_by_name() {
    custom_method::register().unwrap();
    let named = resolve_scene(
        OSCILLATOR,
        &[
            "integrator={ method = \"backward_euler\" }".to_string(),
            "time.end=0.05".to_string(),
        ],
    )
    .unwrap();
    let own = resolve_scene(OSCILLATOR, &["time.end=0.05".to_string()]).unwrap();
    let quiet = &mut |_: usize, _: usize| {};
    let by_name = run(&named, quiet).unwrap();
    let by_value = taut::run_with(&own, &custom_method::BACKWARD_EULER, quiet).unwrap();
    let bits = |o: &taut::RunOutput| format!("{:?} {:?}", o.history, o.stats);
    assert_eq!(bits(&by_name), bits(&by_value));
    assert_ne!(bits(&by_name), bits(&run(&own, quiet).unwrap()));
    let listed = taut::integrate::parse_methods("newmark,backward_euler")
        .map(|l| l.iter().map(|m| m.name()).collect::<Vec<_>>())
        .unwrap();
    assert_eq!(listed, ["newmark", "backward_euler"]);
    let e = resolve_scene(
        OSCILLATOR,
        &["integrator={ method = \"backward_euler\", theta = 0.7 }".to_string()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("integrator.theta") && e.contains("moreau_jean") && e.contains("backward_euler"),
        "{e}"
    );
}
