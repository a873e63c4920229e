//! Damping of the wire (docs/lines.md §10.4): Rayleigh damping
//! `C = α M + β K` (`[beam] damping`) and dashpots on attachments
//! (`[[attachment]] damping`), in every method that carries them, each
//! checked against an independent closed form:
//!
//! * **Each mode's decay** (L12, L13): a tensioned string on the exact
//!   modes of the continuous string (`mesh.kind = "galerkin"`, 5 modes)
//!   under a standing force switched on at t = 0. Each modal coordinate
//!   is a damped oscillator `η̈ + 2ζ_jω_j η̇ + ω_j² η = f_j` with
//!   ζ_j = α/(2ω_j) + βω_j/2, whose step response is
//!   `η_j = (f_j/ω_j²)(1 − q(t))`, q the free vibration from (1, 0) of
//!   `analytic::DampedOscillator` (L13, a separate closed form). The
//!   damping is chosen so that the modes run from ζ = 0.27 to an
//!   over-damped ζ = 1.18. `modal_exact` matches it to round-off at two
//!   Δt; each step-based method converges to it at its order in Δt.
//! * **The banded C of a mesh** (off-diagonal, Hermite elements):
//!   generalized-α and Bathe on a 4-element tensioned beam converge at
//!   second order in Δt to `modal_exact` on the same model's full modal
//!   basis (every FE mode: the same spatial model, propagated exactly).
//! * **A dashpot on an attachment**: the one-dof string of
//!   `scenes/oscillator_one_dof.toml` (its middle node the only unknown)
//!   with a dashpot c_a there is the damped single oscillator
//!   `m ẅ + c_a ẇ + K w = F`; each method converges to its step response
//!   at its order. A dashpot between nodes (x = h/2) is `c_a r rᵀ` with
//!   r = ½: the same run as c_a/4 at the node.
//! * **The exact damped step** of `modal_exact` (`ModeSteps::damped`, the
//!   exponential of the augmented system) against L13 over one step, for
//!   ζ from 0 to 20 and ωΔt from 5e-4 to 100; and the assembled C against
//!   its equation (10.4a) entry by entry.
//! * The keys, their refusals (central difference, a dashpot on a modal
//!   basis, the undamped references), and that an undamped scene is
//!   untouched (no damping matrix, batches as before).

use taut::analytic::DampedOscillator;
use taut::integrate::{Integrator, ModeSteps, batch_key};
use taut::model::banded::SymBand;
use taut::model::beam::BeamModel;
use taut::scene::{Attachment, BeamProps, Rayleigh, Support};
use taut::{Resolved, resolve_scene};

const OSCILLATOR: &str = include_str!("../scenes/oscillator_one_dof.toml");
const REFERENCE: &str = include_str!("../scenes/reference.toml");

/// The string of the modal tests: L = 1 m, ρA = 1 kg/m, T = 100 N, so
/// c = 10 m/s and ω_j = 10πj rad/s; a standing force of 10 N at x = 0.3 m.
const STRING: &str = r#"
[beam]
length = 1.0
mass_per_length = 1.0
bending_stiffness = 0.0
tension = 100.0
left = "pinned"
right = "pinned"

[mesh]
elements = 8
kind = "galerkin"
modes = 5

[[carrier]]
force = 10.0
side = "below"
start = 0.3
speed = { profile = "constant", value = 0.0 }

[time]
step = 1.0e-3
end = 0.5
"#;

/// α, 1/s, and β, s, of the modal tests: ζ_j = 0.27, 0.49, 0.72, 0.95, 1.18.
const ALPHA: f64 = 2.0;
const BETA: f64 = 0.015;

/// The exact step of a damped mode against L13, over a run: the matrix
/// exponential's few ulps per step (`damped_modes.rs`) accumulated over
/// ≤ 1000 steps, relative to max |η_s|; measured 1.9e-15 (Δt = 1e-3 s)
/// and 6.3e-16 (7e-3 s).
const EXACT_ROUNDOFF: f64 = 1e-12;

/// The observed order of a second-order method, halving Δt three times in
/// the asymptotic range (ω_5 Δt ≤ 0.32): measured 1.996–2.05 across the
/// methods and tests; the band admits the next term of the error expansion.
const ORDER_BAND: f64 = 0.1;

fn string(set: &[&str]) -> Resolved {
    let mut o: Vec<String> = vec![format!(
        "beam.damping={{ mass = {ALPHA}, stiffness = {BETA} }}"
    )];
    o.extend(set.iter().map(|s| s.to_string()));
    resolve_scene(STRING, &o).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

/// Each mode's history η_j(t_n), n = 0 … N, of a run.
fn modal_history(sc: &Resolved) -> Vec<Vec<f64>> {
    let mut run = Integrator::new(sc).unwrap();
    let j = run.beam_dofs().len();
    let mut out = vec![vec![0.0]; j];
    for _ in 0..sc.steps {
        run.step().unwrap();
        for (h, d) in out.iter_mut().zip(run.beam_dofs()) {
            h.push(*d);
        }
    }
    out
}

/// The exact step response of each mode (module docs): η_s,j (1 − q_j(t)),
/// η_s,j = s F φ_j(x₀)/ω_j², ω_j² the model's K_jj, ζ_j from L12.
fn modal_exact_history(sc: &Resolved) -> Vec<Vec<f64>> {
    let sys = taut::integrate::System::new(sc).unwrap();
    let beam = sys.beam();
    let phi = beam.point_vector(0.3);
    (0..beam.n)
        .map(|j| {
            let w = beam.stiffness.get(j, j).sqrt();
            let zeta = ALPHA / (2.0 * w) + BETA * w / 2.0;
            let osc = DampedOscillator::new(w, zeta).unwrap();
            // side = below: s = +1, the force pushes up (MODEL §2)
            let eta_s = 10.0 * phi.dense()[j] / (w * w);
            (0..=sc.steps)
                .map(|n| eta_s * (1.0 - osc.free(1.0, 0.0, n as f64 * sc.dt).0))
                .collect()
        })
        .collect()
}

/// max over modes and steps of |η − exact|, over max |exact|.
fn modal_error(sc: &Resolved) -> f64 {
    let (run, exact) = (modal_history(sc), modal_exact_history(sc));
    let scale = exact.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    run.iter()
        .zip(&exact)
        .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
        / scale
}

/// `[a, b, …]` in scientific notation.
fn sci(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", s.join(", "))
}

/// A second-order method: every halving's order within [`ORDER_BAND`]
/// of 2. A first-order one (Moreau–Jean θ = 1) approaches 1 from below
/// (its error's next term, O(Δt²) against O(Δt), is large at ωΔt = 0.06:
/// measured 0.81, 0.90, 0.95 on the oscillator, as docs/methods.md's
/// undamped 0.94): the orders rise, and the last is within the band.
fn assert_order(method: &str, order: f64, p: &[f64], errors: &[f64]) {
    if order == 2.0 {
        for q in p {
            assert!(
                (q - order).abs() <= ORDER_BAND,
                "{method}: orders {p:?}, errors {errors:?}"
            );
        }
    } else {
        let last = p[p.len() - 1];
        assert!(
            (last - order).abs() <= ORDER_BAND,
            "{method}: orders {p:?}, errors {errors:?}"
        );
        assert!(p.windows(2).all(|w| w[1] > w[0]), "{method}: orders {p:?}");
    }
}

fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The methods that carry damping, with their formal order.
const METHODS: [(&str, f64); 7] = [
    (
        "integrator={ method = \"generalized_alpha\", rho_inf = 0.8 }",
        2.0,
    ),
    ("integrator={ method = \"newmark\" }", 2.0),
    ("integrator={ method = \"hht\", alpha = 0.1 }", 2.0),
    ("integrator={ method = \"wbz\", rho_inf = 0.5 }", 2.0),
    ("integrator={ method = \"bathe\" }", 2.0),
    ("integrator={ method = \"moreau_jean\", theta = 0.5 }", 2.0),
    ("integrator={ method = \"moreau_jean\", theta = 1.0 }", 1.0),
];

const STEPS: [&str; 4] = [
    "time.step=2.0e-3",
    "time.step=1.0e-3",
    "time.step=5.0e-4",
    "time.step=2.5e-4",
];

#[test]
fn modal_exact_propagates_every_damped_mode_exactly() {
    let exact = "integrator={ method = \"modal_exact\" }";
    // the modes' ratios span under- to over-damped (module docs)
    let sc = string(&[exact]);
    let sys = taut::integrate::System::new(&sc).unwrap();
    let zetas: Vec<f64> = (0..5)
        .map(|j| {
            let w = sys.beam().stiffness.get(j, j).sqrt();
            ALPHA / (2.0 * w) + BETA * w / 2.0
        })
        .collect();
    assert!(zetas[0] < 0.3 && zetas[4] > 1.0, "{zetas:?}");
    for dt in ["time.step=1.0e-3", "time.step=7.0e-3"] {
        let e = modal_error(&string(&[exact, dt]));
        eprintln!("modal_exact {dt}: {e:.2e}");
        assert!(e <= EXACT_ROUNDOFF, "{dt}: {e:e}");
    }
    // and the damping is there: the undamped run is far from it
    let undamped = resolve_scene(STRING, &[exact.to_string()]).unwrap();
    let (a, b) = (modal_history(&undamped), modal_exact_history(&sc));
    let far = a[0]
        .iter()
        .zip(&b[0])
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(far > 0.1 * b[0].iter().fold(0.0_f64, |m, v| m.max(v.abs())));
}

#[test]
fn each_method_converges_to_each_mode_s_damped_response_at_its_order() {
    for (method, order) in METHODS {
        let errors: Vec<f64> = STEPS
            .iter()
            .map(|dt| modal_error(&string(&[method, dt])))
            .collect();
        let p = orders(&errors);
        eprintln!("{method}: errors {}, orders {p:.3?}", sci(&errors));
        assert_order(method, order, &p, &errors);
    }
}

/// The 4-element tensioned beam of the mesh test: EI = 0.01 N·m², so the
/// Hermite elements' C = αM + βK is banded with off-diagonal entries in
/// both the displacement and rotation dofs; a probe at x = 0.3 m.
fn beam(set: &[&str]) -> Resolved {
    let text = STRING.replace("kind = \"galerkin\"\nmodes = 5\n", "")
        + "\n[[probe]]\nname = \"p\"\nx = 0.3\n";
    let mut o: Vec<String> = [
        "beam.bending_stiffness=0.01",
        "mesh.elements=4",
        "time.end=0.3",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    o.push(format!(
        "beam.damping={{ mass = {ALPHA}, stiffness = {BETA} }}"
    ));
    o.extend(set.iter().map(|s| s.to_string()));
    resolve_scene(&text, &o).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

fn probe(sc: &Resolved) -> Vec<f64> {
    common_run(sc).history.probes[0].1.clone()
}

fn common_run(sc: &Resolved) -> taut::RunOutput {
    taut::run(sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("run failed: {e}"))
}

#[test]
fn the_banded_damping_of_a_mesh_converges_to_its_exact_modal_propagation() {
    let n = {
        let sc = beam(&[]);
        taut::integrate::System::new(&sc).unwrap().beam().n
    };
    let all_modes = format!("mesh.modes={n}");
    for method in [METHODS[0].0, METHODS[4].0, METHODS[5].0] {
        let errors: Vec<f64> = STEPS[1..]
            .iter()
            .map(|dt| {
                let fe = probe(&beam(&[method, dt]));
                let exact = probe(&beam(&[
                    "integrator={ method = \"modal_exact\" }",
                    "mesh.kind=modal",
                    &all_modes,
                    dt,
                ]));
                let scale = exact.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                fe.iter()
                    .zip(&exact)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
                    / scale
            })
            .collect();
        let p = orders(&errors);
        eprintln!("mesh {method}: errors {}, orders {p:.3?}", sci(&errors));
        for q in &p {
            assert!(
                (q - 2.0).abs() <= ORDER_BAND,
                "{method}: orders {p:?}, errors {errors:?}"
            );
        }
    }
}

// --- a dashpot on an attachment: the damped single oscillator ---------------

/// The one-dof string without its undamped reference, with `extra` scene
/// text (attachments).
fn oscillator(extra: &str, set: &[&str]) -> Resolved {
    let text = OSCILLATOR.split("[reference]").next().unwrap().to_string() + extra;
    let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    resolve_scene(&text, &o).unwrap_or_else(|e| panic!("{set:?}: {e}"))
}

/// The node's mass m = 2ρA h/3 (kg), stiffness K = 2T/h (N/m) and the
/// force F = 10 N of the one-dof scene (its header).
const OSC_M: f64 = 2.0 / 3.0;
const OSC_K: f64 = 2400.0;
const OSC_F: f64 = 10.0;

/// The dashpot at the node, N·s/m: ζ = c/(2√(Km)) = 0.1.
const DASHPOT: f64 = 8.0;

/// max |w − exact| / (F/K) of a run with damping coefficient `c` (N·s/m)
/// on the node.
fn oscillator_error(sc: &Resolved, c: f64) -> f64 {
    let w = (OSC_K / OSC_M).sqrt();
    let osc = DampedOscillator::new(w, c / (2.0 * (OSC_K * OSC_M).sqrt())).unwrap();
    let w_s = OSC_F / OSC_K;
    let out = common_run(sc);
    out.history.probes[0]
        .1
        .iter()
        .zip(&out.history.t)
        .map(|(v, t)| (v - w_s * (1.0 - osc.free(1.0, 0.0, *t).0)).abs())
        .fold(0.0, f64::max)
        / w_s
}

const DASHPOT_AT_NODE: &str = "\n[[attachment]]\nx = 1.0\ndamping = 8.0\n";

#[test]
fn a_dashpot_on_an_attachment_is_the_damped_single_oscillator() {
    for (method, order) in METHODS {
        let errors: Vec<f64> = STEPS
            .iter()
            .map(|dt| oscillator_error(&oscillator(DASHPOT_AT_NODE, &[method, dt]), DASHPOT))
            .collect();
        let p = orders(&errors);
        eprintln!("dashpot {method}: errors {}, orders {p:.3?}", sci(&errors));
        assert_order(method, order, &p, &errors);
    }
    // Rayleigh on the same oscillator adds αm + βK to its c
    let (alpha, beta) = (3.0, 1e-3);
    let c = DASHPOT + alpha * OSC_M + beta * OSC_K;
    let set = format!("beam.damping={{ mass = {alpha}, stiffness = {beta} }}");
    let e: Vec<f64> = STEPS[2..]
        .iter()
        .map(|dt| oscillator_error(&oscillator(DASHPOT_AT_NODE, &[METHODS[1].0, dt, &set]), c))
        .collect();
    assert!((orders(&e)[0] - 2.0).abs() <= ORDER_BAND, "{e:?}");
}

#[test]
fn a_dashpot_between_nodes_acts_through_its_shape_functions() {
    // x = h/2: r = ½ on the middle node, so c r rᵀ = c/4 there
    let between = oscillator("\n[[attachment]]\nx = 0.5\ndamping = 32.0\n", &[]);
    let at_node = oscillator(DASHPOT_AT_NODE, &[]);
    let (a, b) = (probe(&between), probe(&at_node));
    assert_eq!(a, b, "c r rᵀ with r = ½ is c/4 exactly");
    let undamped = probe(&oscillator("", &[]));
    assert_ne!(a, undamped);
}

// --- the keys ---------------------------------------------------------------

fn reference(extra: &str, set: &[&str]) -> taut::Result<Resolved> {
    let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    resolve_scene(&format!("{REFERENCE}\n{extra}"), &o)
}

fn refused(extra: &str, set: &[&str], parts: &[&str]) {
    let msg = reference(extra, set)
        .expect_err("should be refused")
        .to_string();
    for p in parts {
        assert!(msg.contains(p), "{msg:?} should mention {p:?}");
    }
}

const RAYLEIGH: &str = "beam.damping={ mass = 0.5, stiffness = 1e-4 }";

#[test]
fn the_keys_reach_the_run_and_an_undamped_scene_is_untouched() {
    let bare = reference("", &[]).unwrap();
    assert!(!bare.is_damped());
    assert!(
        taut::integrate::System::new(&bare)
            .unwrap()
            .damping()
            .is_none()
    );
    assert!(batch_key(&bare).is_some(), "the reference case batches");
    let sc = reference("", &[RAYLEIGH]).unwrap();
    assert_eq!((sc.damping.alpha, sc.damping.beta), (0.5, 1e-4));
    assert!(sc.is_damped());
    assert!(batch_key(&sc).is_none(), "a damped run steps alone");
    assert!(
        taut::integrate::System::new(&sc)
            .unwrap()
            .damping()
            .is_some()
    );
    let sc = reference("[[attachment]]\nx = 12.0\ndamping = 50.0\n", &[]).unwrap();
    assert_eq!(sc.beam.attachments[0].damping, 50.0);
    assert!(sc.is_damped() && batch_key(&sc).is_none());
    // zero damping is no damping
    let zero = reference("", &["beam.damping={ mass = 0.0 }"]).unwrap();
    assert!(!zero.is_damped() && batch_key(&zero).is_some());
}

#[test]
fn bad_damping_is_refused_naming_the_field() {
    refused(
        "",
        &["beam.damping={ mass = -1.0 }"],
        &["beam.damping.mass", "-1", "≥ 0 (1/s)"],
    );
    refused(
        "",
        &["beam.damping={ stiffness = nan }"],
        &["beam.damping.stiffness", "NaN", "finite"],
    );
    refused(
        "",
        &["beam.damping={ alpha = 1.0 }"],
        &["unknown field `alpha`", "`mass`", "`stiffness`"],
    );
    refused(
        "[[attachment]]\nx = 1.0\ndamping = -2.0\n",
        &[],
        &["attachment.0.damping", "-2", "≥ 0 (N·s/m)"],
    );
    refused(
        "",
        &[RAYLEIGH, "integrator={ method = \"central_difference\" }"],
        &[
            "integrator.method",
            "central_difference",
            "beam.damping",
            "M + Δt/2·C",
        ],
    );
    refused(
        "[[attachment]]\nx = 1.0\ndamping = 2.0\n",
        &["integrator={ method = \"central_difference\" }"],
        &["integrator.method", "attachment.0.damping"],
    );
    refused(
        "[[attachment]]\nx = 1.0\ndamping = 2.0\n",
        &["mesh.kind=modal", "mesh.modes=10", "mesh.elements=40"],
        &["attachment.0.damping", "couples every mode", "\"hermite\""],
    );
    refused(
        "[reference]\nkind = \"moving_force_series\"\n",
        &[RAYLEIGH],
        &["reference.kind", "undamped", "richardson"],
    );
    // Rayleigh damping on a modal basis is diagonal, and accepted
    reference(
        "",
        &[
            RAYLEIGH,
            "mesh.kind=modal",
            "mesh.modes=10",
            "mesh.elements=40",
        ],
    )
    .unwrap();
    reference("", &[RAYLEIGH, "mesh.kind=galerkin", "mesh.modes=10"]).unwrap();
}

// --- the exact damped step and the assembled C --------------------------------

/// The Padé exponential against the closed form L13, relative to the
/// motion's scale: measured 1.2e-14 worst over the cases below (4.2e-16
/// for the held load); a few ulps times the squarings' growth.
const EXPM_ROUNDOFF: f64 = 1e-13;

/// Free vibration from (q₀, v₀) over one step, under-, critically
/// and over-damped, small and large ωΔt, against L13.
#[test]
fn the_free_step_is_the_closed_form_for_every_damping_ratio() {
    let dt = 1e-3;
    let mut worst: f64 = 0.0;
    for w in [0.5, 60.0, 3.0e3, 1.0e5] {
        for zeta in [0.0, 0.05, 0.7, 1.0, 1.3, 20.0] {
            let m = ModeSteps::damped(&[w], &[2.0 * zeta * w], dt);
            let osc = DampedOscillator::new(w, zeta).unwrap();
            for (q0, v0) in [(1.0, 0.0), (0.0, w)] {
                let (q, v) = osc.free(q0, v0, dt);
                let eq = m.cos[0] * q0 + m.sin_over_omega[0] * v0;
                let ev = m.minus_omega_sin[0] * q0 + m.cos_v[0] * v0;
                let scale = q0.abs() + v0.abs() / w;
                worst = worst
                    .max((eq - q).abs() / scale)
                    .max((ev - v).abs() / (scale * w));
                assert!(
                    (eq - q).abs() <= EXPM_ROUNDOFF * scale,
                    "ω {w} ζ {zeta}: η {eq} vs {q}"
                );
                assert!(
                    (ev - v).abs() <= EXPM_ROUNDOFF * scale * w,
                    "ω {w} ζ {zeta}: η̇ {ev} vs {v}"
                );
            }
        }
    }
    eprintln!("free step against L13: worst {worst:.2e}");
}

/// A held load's step is the step response `η_s + free(−η_s, 0)`,
/// η_s = f/ω², and with c = 0 the map is the undamped one.
#[test]
fn a_held_load_is_the_step_response_and_no_damping_is_the_undamped_map() {
    let dt = 2e-3;
    let mut worst: f64 = 0.0;
    for w in [1.0, 80.0, 4.0e3] {
        for zeta in [0.0, 0.3, 1.0, 4.0] {
            let m = ModeSteps::damped(&[w], &[2.0 * zeta * w], dt);
            let osc = DampedOscillator::new(w, zeta).unwrap();
            let eta_s = 1.0 / (w * w);
            let (q, v) = osc.free(-eta_s, 0.0, dt);
            let (eq, ev) = (m.a0[0] + m.a1[0], m.b0[0] + m.b1[0]);
            worst = worst
                .max((eq - (eta_s + q)).abs() / eta_s)
                .max((ev - v).abs() / (eta_s * w));
            assert!(
                (eq - (eta_s + q)).abs() <= EXPM_ROUNDOFF * eta_s,
                "ω {w} ζ {zeta}"
            );
            assert!(
                (ev - v).abs() <= EXPM_ROUNDOFF * eta_s * w,
                "ω {w} ζ {zeta}"
            );
        }
        let (d, u) = (
            ModeSteps::damped(&[w], &[0.0], dt),
            ModeSteps::new(&[w], dt),
        );
        for (x, y, what) in [
            (&d.cos, &u.cos, "cos"),
            (&d.cos_v, &u.cos_v, "cos_v"),
            (&d.sin_over_omega, &u.sin_over_omega, "sin/ω"),
            (&d.a0, &u.a0, "a0"),
            (&d.a1, &u.a1, "a1"),
            (&d.b0, &u.b0, "b0"),
            (&d.b1, &u.b1, "b1"),
        ] {
            let scale = match what {
                "a0" | "a1" => dt * dt,
                "b0" | "b1" | "sin/ω" => dt,
                _ => 1.0,
            };
            worst = worst.max((x[0] - y[0]).abs() / scale);
            assert!((x[0] - y[0]).abs() <= EXPM_ROUNDOFF * scale, "ω {w} {what}");
        }
    }
    eprintln!("held load and c = 0 against the closed forms: worst {worst:.2e}");
}

fn small_beam(attachments: Vec<Attachment>) -> BeamProps {
    BeamProps {
        length: 2.0,
        rho_a: 1.5,
        ei: 3.0,
        ea: None,
        tension: 10.0,
        left: Support::Pinned,
        right: Support::Clamped,
        distributed_load: 0.0,
        attachments,
        messenger: None,
    }
}

#[test]
fn no_damping_is_no_matrix() {
    let b = BeamModel::new(&small_beam(Vec::new()), 4);
    assert!(b.damping_matrix(Rayleigh::default(), &[]).is_none());
}

/// C = αM + βK entry by entry, and a dashpot between nodes adds
/// c r rᵀ (rᵀ C r over a vector grows by c (rᵀr)²) without widening
/// the band.
#[test]
fn rayleigh_and_a_dashpot_are_where_the_equation_puts_them() {
    let dash = Attachment {
        x: 0.7,
        stiffness: 0.0,
        mass: 0.0,
        damping: 5.0,
    };
    let b = BeamModel::new(&small_beam(vec![dash]), 4);
    let r = Rayleigh {
        alpha: 0.3,
        beta: 2e-3,
    };
    let c0 = b.damping_matrix(r, &[]).unwrap();
    for i in 0..b.n {
        for j in 0..b.n {
            let want = 0.3 * b.mass.get(i, j) + 2e-3 * b.stiffness.get(i, j);
            assert_eq!(c0.get(i, j), want);
        }
    }
    let c1 = b.damping_matrix(r, &[dash]).unwrap();
    assert_eq!(c1.bandwidth(), b.mass.bandwidth());
    let pv = b.point_vector(0.7);
    let mut rv = vec![0.0; b.n];
    pv.scatter(1.0, &mut rv, 1, 0);
    let quad = |c: &SymBand| {
        let mut y = vec![0.0; b.n];
        c.mul_acc(&rv, 1.0, &mut y);
        y.iter().zip(&rv).map(|(a, b)| a * b).sum::<f64>()
    };
    let rr: f64 = rv.iter().map(|x| x * x).sum();
    let grown = quad(&c1) - quad(&c0);
    assert!(
        (grown - 5.0 * rr * rr).abs() < 1e-12 * 5.0 * rr * rr,
        "{grown}"
    );
}
