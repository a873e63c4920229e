//! Damping of the wire (issue 27; docs/lines.md §10.4): Rayleigh damping
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
//! * The keys, their refusals (central difference, a dashpot on a modal
//!   basis, the undamped references), and that an undamped scene is
//!   untouched (no damping matrix, batches as before).

use taut::analytic::DampedOscillator;
use taut::integrate::{Integrator, batch_key};
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
/// ≤ 1000 steps, relative to max |η_s|; measured ≤ 2e-14.
const EXACT_ROUNDOFF: f64 = 1e-12;

/// The observed order of a second-order method, halving Δt three times in
/// the asymptotic range (ω_5 Δt ≤ 0.32): measured 1.99–2.01 across the
/// methods; the band admits the next term of the error expansion.
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
        for q in &p {
            assert!(
                (q - order).abs() <= ORDER_BAND,
                "{method}: orders {p:?}, errors {errors:?}"
            );
        }
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
        for q in &p {
            assert!(
                (q - order).abs() <= ORDER_BAND,
                "{method}: orders {p:?}, errors {errors:?}"
            );
        }
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
