//! Elastic messenger supports and point attachments on the messenger
//! (docs/lines.md "Elastic supports and clamp masses", E1):
//! `[messenger] support = { stiffness, damping, mass }` (every support) or
//! a list with one `"pinned"` or `{ … }` per support, and `[[attachment]]
//! wire = "messenger"`. Checked against
//!
//! * the static start of two strings with a linear messenger dropper and
//!   an elastic interior messenger support, against the superposed
//!   point-load solution with the support's spring force solved by hand
//!   (nodally exact for string elements);
//! * the fundamental of a messenger whose end sits on a spring and a mass
//!   (a free end on a spring), against the string's frequency equation
//!   m ω² − k = T κ cot(κ L), κ = ω/c: second order in h;
//! * the two-wire manufactured solution with an elastic interior support
//!   (spring, dashpot and mass) and a clamp mass on the messenger: order 4
//!   in h and 2 in Δt on both wires (its source has each attachment's
//!   force of the manufactured motion);
//! * the keys' refusals.

use taut::analytic::StaticPointLoad;
use taut::model::beam::BeamModel;
use taut::model::eigen::lowest_eigenpairs;
use taut::scene::Support;
use taut::study::uncertainty::observed_order;
use taut::{RunOutput, resolve_scene};

use crate::common;

const L: f64 = 10.0;
/// The contact wire's tension, N.
const T: f64 = 1000.0;

/// Two strings (contact T = 1000 N, ρA = 1; messenger T_m = 800 N,
/// ρA_m = 0.5) of 10 m on `n` elements, the messenger held at 0, 5 and
/// 10 m with `support`, and `extra` appended.
fn strings(n: usize, t: f64, support: &str, extra: &str) -> String {
    format!(
        r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 0.0
tension = {t:e}
left = "pinned"
right = "pinned"

[messenger]
tension = 800.0
mass_per_length = 0.5
bending_stiffness = 0.0
height = 1.0
supports = [0.0, 5.0, 10.0]
{support}

[mesh]
elements = {n}

[[carrier]]
force = 10.0
side = "below"
start = 0.0
speed = {{ profile = "constant", value = 0.0 }}

{extra}
"#
    )
}

/// The static scene: self-weight, one linear messenger dropper at x_d =
/// 4 m (k_d = 1e4 N/m, e₀ = 2 mm), probes on both lines.
fn static_scene(support: &str) -> String {
    strings(
        50,
        T,
        support,
        r#"
[gravity]
g = 9.81
beam_self_weight = true

[[dropper]]
name = "d"
x = 4.0
stiffness = 1.0e4
anchor = "messenger"
length = 0.998
linear = true

[[probe]]
name = "c4"
x = 4.0

[[probe]]
name = "c7"
x = 7.0

[[probe]]
name = "m4"
x = 4.0
wire = "messenger"

[[probe]]
name = "m5"
x = 5.0
wire = "messenger"

[[probe]]
name = "m7"
x = 7.0
wire = "messenger"

[time]
step = 1e-3
end = 0.01
initial = "static"
"#,
    )
}

/// The static start against the closed form (relative to the largest
/// displacement or force): string elements with consistent loads are
/// nodally exact for point and uniform loads, so only the banded solve's
/// round-off remains (measured 1e-15; `tests/messenger.rs` likewise).
const STATIC_EXACT: f64 = 1e-11;

/// The interior support's spring, N/m.
const KS: f64 = 2.0e4;

fn go(text: &str) -> RunOutput {
    let sc = resolve_scene(text, &[]).unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

#[test]
fn an_elastic_support_settles_by_its_force_over_its_stiffness() {
    let elastic = format!(
        "support = [\"pinned\", {{ stiffness = {KS:e}, damping = 30.0, mass = 4.0 }}, \"pinned\"]"
    );
    let out = go(&static_scene(&elastic));
    let (xd, xs, kd, e0, g) = (4.0, 5.0, 1.0e4, 0.002, 9.81);
    let (pc, pm, tm) = (-g, -0.5 * g, 800.0);
    let gc = StaticPointLoad::new(0.0, T, L, Support::Pinned, Support::Pinned).unwrap();
    let gm = StaticPointLoad::new(0.0, tm, L, Support::Pinned, Support::Pinned).unwrap();
    let u = |p: f64, t: f64, x: f64| p * x * (L - x) / (2.0 * t);
    // unknowns: the dropper force N (up on the contact wire, down on the
    // messenger) and the support's force R = −k_s v_m(x_s) (up):
    //   N (1 + k_d(G_m,dd + G_c,dd)) − k_d G_m(x_s, x_d) R = k_d(e₀ + u_m(x_d) − u_c(x_d))
    //   −k_s G_m(x_d, x_s) N + (1 + k_s G_m,ss) R = −k_s u_m(x_s)
    let a11 = 1.0 + kd * (gm.compliance(xd) + gc.compliance(xd));
    let a12 = -kd * gm.deflection(xs, xd);
    let b1 = kd * (e0 + u(pm, tm, xd) - u(pc, T, xd));
    let a21 = -KS * gm.deflection(xd, xs);
    let a22 = 1.0 + KS * gm.compliance(xs);
    let b2 = -KS * u(pm, tm, xs);
    let det = a11 * a22 - a12 * a21;
    let n = (b1 * a22 - a12 * b2) / det;
    let r = (a11 * b2 - a21 * b1) / det;
    let vc = |x: f64| u(pc, T, x) + n * gc.deflection(xd, x);
    let vm = |x: f64| u(pm, tm, x) - n * gm.deflection(xd, x) + r * gm.deflection(xs, x);
    println!(
        "by hand: N = {n:.9} N, R = {r:.9} N, settlement v_m(5) = {:.6e} m (R/k_s = {:.6e})",
        vm(xs),
        -r / KS
    );
    assert!(
        (vm(xs) + r / KS).abs() < 1e-15,
        "the hand solution's own balance"
    );
    let want = [vc(4.0), vc(7.0), vm(4.0), vm(5.0), vm(7.0)];
    let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for ((name, col), w) in out.history.probes.iter().zip(want) {
        let err = (col[0] - w).abs() / scale;
        println!(
            "{name}: {:.9e} m, closed form {w:.9e} m, error {err:.1e}",
            col[0]
        );
        assert!(err < STATIC_EXACT, "{name}: {} vs {w}", col[0]);
    }
    let f0 = out.history.droppers[0].1[0];
    println!("dropper force {f0:.9} N, closed form {n:.9} N");
    assert!((f0 - n).abs() / n < STATIC_EXACT, "{f0} vs {n}");
    // the check can fail: the same scene with the support pinned sits
    // elsewhere (v_m(5) = 0 where the spring settles)
    let pinned = go(&static_scene(""));
    let m5 = pinned.history.probes[3].1[0];
    assert!(m5.abs() < 1e-15, "pinned: v_m(5) = {m5}");
    assert!((vm(xs) - m5).abs() > 1e3 * STATIC_EXACT * scale);
}

/// The fundamental of a string of length `l` (T_m, c = √(T_m/ρA_m)) pinned
/// at one end, its other end on a spring k and a mass m: v = sin(κs), and
/// the end's balance −T_m v'(l) − k v(l) = −m ω² v(l) gives g(κ) = m c²κ²
/// − k − T_m κ cot(κl) = 0, one root in (0, π/l) (g rises from −k − T_m/l
/// to +∞).
fn spring_mass_end(l: f64, tm: f64, rho: f64, k: f64, m: f64) -> f64 {
    let c = (tm / rho).sqrt();
    c * lowest_root(|q| m * c * c * q * q - k - tm * q / (q * l).tan(), l)
}

/// The root of `g` in (0, π/l), where it rises from < 0 to +∞, by
/// bisection to the last bit.
fn lowest_root(g: impl Fn(f64) -> f64, l: f64) -> f64 {
    let (mut lo, mut hi) = (1e-9, std::f64::consts::PI / l * (1.0 - 1e-12));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Allowed |observed − 2| of the fundamental's h order (linear elements,
/// a lumped mass at a node: Rayleigh–Ritz from above at second order;
/// `tests/attachments.rs` measures 2.00 for the interior mass).
const FREQ_ORDER_TOL: f64 = 0.1;

#[test]
fn a_messenger_end_on_a_spring_and_a_mass_has_the_string_s_fundamental() {
    // the messenger's span [5, 10] m, pinned at 5, its end at 10 on the
    // spring and mass: its fundamental lies below π c_m/5 = 25.1 rad/s, the
    // pinned span [0, 5]'s; the contact wire is stiff (T = 1e5 N: ω₁ = 99
    // rad/s), so the model's lowest mode is that span's
    let (k, m) = (300.0, 2.0);
    let want = spring_mass_end(5.0, 800.0, 0.5, k, m);
    let support =
        format!("support = [\"pinned\", \"pinned\", {{ stiffness = {k:e}, mass = {m:e} }}]");
    let mut errors = Vec::new();
    for n in [50, 100, 200] {
        let text = strings(n, 1.0e5, &support, "[time]\nstep = 1e-3\nend = 0.01\n");
        let sc = resolve_scene(&text, &[]).unwrap_or_else(|e| panic!("{e}"));
        let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
        let w = lowest_eigenpairs(&beam.mass, &beam.stiffness, 1)
            .unwrap()
            .omega_sq[0]
            .sqrt();
        let err = (w - want) / want;
        println!("N = {n}: ω₁ = {w:.9} rad/s, closed form {want:.9} rad/s, error {err:.3e}");
        assert!(err > 0.0, "Rayleigh–Ritz: from above");
        errors.push(err);
    }
    for e in errors.windows(2) {
        let order = observed_order(e[0], e[1], 2.0);
        println!("order {order:.3}");
        assert!((order - 2.0).abs() < FREQ_ORDER_TOL, "{order}");
    }
}

/// The two-wire manufactured scene with its interior messenger support
/// elastic (spring, dashpot and mass) and a clamp mass on the messenger at
/// dropper d2: v_m* no longer vanishes at x = 1 m (only pinned supports
/// enter its shapes), so the support's force −(m_s v̈_m* + c_s v̇_m* +
/// k_s v_m*) is in the source, which only the model's own spring, dashpot
/// and mass cancel.
fn mms_elastic() -> String {
    include_str!("../scenes/verify/mms_two_wires.toml")
        .replace(
            "supports = [0.0, 1.0, 2.0]   # m (pinned; on nodes of every mesh with N even)",
            "supports = [0.0, 1.0, 2.0]\nsupport = [\"pinned\", { stiffness = 2000.0, damping = 5.0, mass = 0.3 }, \"pinned\"]",
        )
        + "\n[[attachment]]\nname = \"clamp_d2\"\nx = 0.75\nmass = 0.1\ndamping = 0.5\nwire = \"messenger\"\n"
}

/// Allowed |observed − 4| of the h order from N = 8 → 32 and |observed − 2|
/// of the Δt order from 1e-3 → 5e-4 s: `tests/mms_two_wires.rs`'s bands
/// (H_ORDER_TOL, DT_ORDER_TOL) for the same scene.
const H_ORDER_TOL: f64 = 0.5;
const DT_ORDER_TOL: f64 = 0.3;

#[test]
fn two_wires_on_an_elastic_support_converge_at_orders_4_in_h_and_2_in_dt() {
    let scene = mms_elastic();
    let sc = resolve_scene(&scene, &[]).unwrap();
    let m = sc.manufactured.as_ref().unwrap();
    // the support moves in the manufactured motion (the check can fail)
    let moves = (0..50)
        .map(|i| m.v_m(1.0, 0.005 * i as f64).abs())
        .fold(0.0, f64::max);
    assert!(moves > 1e-3, "v_m*(1) up to {moves} m");
    let (c1, m1) = common::manufactured_wire_errors(&scene, &common::mesh_and_step(8, 1e-5));
    let (c2, m2) = common::manufactured_wire_errors(&scene, &common::mesh_and_step(32, 1e-5));
    let (oc, om) = (observed_order(c1, c2, 4.0), observed_order(m1, m2, 4.0));
    println!(
        "elastic support, h: contact {c1:.3e} → {c2:.3e} m (order {oc:.2}), messenger {m1:.3e} → {m2:.3e} m (order {om:.2})"
    );
    assert!((oc - 4.0).abs() < H_ORDER_TOL, "contact wire h order {oc}");
    assert!((om - 4.0).abs() < H_ORDER_TOL, "messenger h order {om}");
    let (c1, m1) = common::manufactured_wire_errors(&scene, &common::mesh_and_step(32, 1e-3));
    let (c2, m2) = common::manufactured_wire_errors(&scene, &common::mesh_and_step(32, 5e-4));
    let (oc, om) = (observed_order(c1, c2, 2.0), observed_order(m1, m2, 2.0));
    println!(
        "elastic support, Δt: contact {c1:.3e} → {c2:.3e} m (order {oc:.2}), messenger {m1:.3e} → {m2:.3e} m (order {om:.2})"
    );
    assert!(
        (oc - 2.0).abs() < DT_ORDER_TOL,
        "contact wire Δt order {oc}"
    );
    assert!((om - 2.0).abs() < DT_ORDER_TOL, "messenger Δt order {om}");
}

#[test]
fn elastic_support_keys_are_checked() {
    let base = |support: &str| static_scene(support);
    for (support, want) in [
        (
            "support = { stiffness = 0.0 }",
            &["messenger.support.stiffness", "0", "> 0"][..],
        ),
        (
            "support = { mass = 2.0 }",
            &["messenger.support.stiffness", "missing", "singular"],
        ),
        (
            "support = { stiffness = 1e5, damping = -1.0 }",
            &["messenger.support.damping", "-1", "≥ 0"],
        ),
        (
            "support = { stiffness = 1e5, inertia = 1.0 }",
            &["messenger.support.inertia", "not a key"],
        ),
        (
            "support = [\"pinned\", \"pinned\"]",
            &[
                "messenger.support",
                "a list of 2",
                "one entry per support (3)",
            ],
        ),
        (
            "support = [\"pinned\", \"rigid\", \"pinned\"]",
            &["messenger.support.1", "rigid", "\"pinned\""],
        ),
    ] {
        let e = resolve_scene(&base(support), &[]).unwrap_err().to_string();
        for w in want {
            assert!(e.contains(w), "{support}: {e} (wanted {w})");
        }
    }
    // a messenger attachment needs a messenger
    let text = include_str!("../scenes/span_droppers.toml").to_string()
        + "\n[[attachment]]\nx = 1.0\nmass = 1.0\nwire = \"messenger\"\n";
    let e = resolve_scene(&text, &[]).unwrap_err().to_string();
    assert!(
        e.contains("attachment.") && e.contains(".wire") && e.contains("[messenger]"),
        "{e}"
    );
    // a dashpot on an elastic support or a messenger clamp is refused by
    // central difference, naming it
    let damped = base("support = [\"pinned\", { stiffness = 1e5, damping = 3.0 }, \"pinned\"]");
    let e = resolve_scene(
        &damped,
        &["integrator={ method = \"central_difference\" }".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("messenger.support.damping") && e.contains("central_difference"),
        "{e}"
    );
    let clamp =
        base("") + "\n[[attachment]]\nx = 4.0\nmass = 1.0\ndamping = 2.0\nwire = \"messenger\"\n";
    let e = resolve_scene(
        &clamp,
        &["integrator={ method = \"central_difference\" }".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("attachment.0.damping"), "{e}");
    // an elastic support with a spring only, and none at all, run
    resolve_scene(&base("support = { stiffness = 1e5 }"), &[]).unwrap();
}

/// A `[line]` of two strings (EI = 0) on elastic interior messenger
/// supports, with per-dropper stiffnesses, a pre-sag, steady arm springs,
/// clamp and dropper masses, started static: the design (G2–G7 with E2 and E3, the
/// settlement E2) is exact for strings, so every dropper's contact-wire
/// height at t = 0 is the design's −4pξ(1 − ξ) to round-off.
fn designed_strings(support: &str) -> String {
    let probes: String = (0..3)
        .flat_map(|k| [4.0, 12.0, 20.0, 28.0].map(move |p| 32.0 * k as f64 + p))
        .map(|x| format!("[[probe]]\nname = \"c{x}\"\nx = {x:?}\n"))
        .collect();
    format!(
        r#"
[beam]
mass_per_length = 1.35
bending_stiffness = 0.0
tension = 2.0e4

[mesh]

[[carrier]]
force = 0.0
side = "below"
start = 0.0
speed = {{ profile = "constant", value = 0.0 }}

[time]
step = 1e-3
end = 0.002
initial = "static"

[gravity]
g = 9.81
beam_self_weight = true

[line]
spans = 3
span_length = 32.0
droppers = [4.0, 12.0, 20.0, 28.0]
presag = 0.032
dropper_stiffness = [[2.0e5, 1.0e5, 1.0e5, 2.0e5], [1.5e5, 1.0e5, 1.0e5, 1.5e5]]
dropper_mass = 0.4
clamp_mass = {{ contact = 0.2, messenger = 0.15 }}
element_length = 1.0
anchor = "messenger"
messenger = {{ tension = 1.6e4, mass_per_length = 1.07, bending_stiffness = 0.0, height = 1.2{support} }}
steady_arm = {{ stiffness = 3000.0, mass = 1.0, damping = 20.0 }}

{probes}
"#
    )
}

/// Heights at t = 0 against the design (m, relative to the pre-sag p):
/// string elements hold point and uniform loads nodally exactly, so the
/// static solve's round-off remains (measured 1e-13 of p).
const DESIGN_EXACT: f64 = 1e-10;

#[test]
fn a_designed_line_on_elastic_supports_starts_at_its_design_heights() {
    let p = 0.032;
    let height = |support: &str| {
        let sc = resolve_scene(&designed_strings(support), &[]).unwrap_or_else(|e| panic!("{e}"));
        let out = common::run(&sc);
        out.history
            .probes
            .iter()
            .zip(&sc.probes)
            .map(|((_, col), &(_, x))| {
                let xi = (x % 32.0) / 32.0;
                (col[0] - (-4.0 * p * xi * (1.0 - xi))) / p
            })
            .fold(0.0f64, |m, e| m.max(e.abs()))
    };
    let elastic = height(", support = { stiffness = 2.0e5, damping = 50.0, mass = 8.0 }");
    let pinned = height("");
    println!("design heights: elastic supports {elastic:.2e} of p, pinned {pinned:.2e} of p");
    assert!(elastic < DESIGN_EXACT, "{elastic}");
    assert!(pinned < DESIGN_EXACT, "{pinned}");
    // the settlement is in the design: the messenger sinks at the supports
    let sc = resolve_scene(
        &designed_strings(", support = { stiffness = 2.0e5 }"),
        &["probe=[{ name = \"m32\", x = 32.0, wire = \"messenger\" }]".into()],
    )
    .unwrap();
    let sink = common::run(&sc).history.probes[0].1[0];
    println!("messenger at the support x = 32 m: {sink:.6e} m");
    assert!(sink < -1e-3, "{sink}");
}

/// Two 10 m spans of a string (T = 1000 N, ρA = 1 kg/m, no weight) with
/// one nearly massless, nearly weightless dropper a span (linear, k_d =
/// 1e-6 N/m: a design force of 0 and a spring 1e-9 of the wire's) and a
/// steady arm at the middle support: `arm` is its `[line]` table.
fn arm_line(arm: &str, element_length: f64) -> String {
    format!(
        r#"
[beam]
mass_per_length = 1.0
bending_stiffness = 0.0
tension = 1000.0

[mesh]

[[carrier]]
force = 0.0
side = "below"
start = 0.0
speed = {{ profile = "constant", value = 0.0 }}

[time]
step = 1e-3
end = 0.002

[line]
spans = 2
span_length = 10.0
droppers = {{ count = 1 }}
dropper_stiffness = 1.0e-6
linear_droppers = true
element_length = {element_length:e}
anchor = "fixed"
messenger = {{ tension = 1.6e4, mass_per_length = 1.07, height = 1.2 }}
steady_arm = {arm}
"#
    )
}

/// A lumped mass m and spring k at x = a of a pinned–pinned string of
/// length a + b (docs/lines.md A1): m ω² − k = T κ (cot κa + cot κb), κ =
/// ω/c, its fundamental the one root in (0, π/max(a, b)).
fn string_with_point(t: f64, rho: f64, (a, b): (f64, f64), (k, m): (f64, f64)) -> f64 {
    let c = (t / rho).sqrt();
    let g = |q: f64| m * c * c * q * q - k - t * q * (1.0 / (q * a).tan() + 1.0 / (q * b).tan());
    c * lowest_root(g, a.max(b))
}

#[test]
fn a_pivoted_steady_arm_is_its_tip_mass_and_spring_by_hand() {
    // ℓ_a = 1.2 m, I_a = 2.16 kg·m² (a 4.5 kg bar about its end, m ℓ²/3),
    // k_φ = 720 N·m/rad, a 0.5 kg clamp and a 100 N/m registration spring:
    // S1–S2 by hand, m_tip = 0.5 + 2.16/1.44 = 2 kg, k_tip = 100 + 720/1.44
    // = 600 N/m
    let arm = "{ stiffness = 100.0, mass = 0.5, arm_length = 1.2, inertia = 2.16, pivot_stiffness = 720.0 }";
    let sc = resolve_scene(&arm_line(arm, 0.2), &[]).unwrap_or_else(|e| panic!("{e}"));
    let tip = sc.beam.attachments[0];
    assert_eq!(tip.x, 10.0);
    assert!(
        (tip.mass - 2.0).abs() < 1e-15 && (tip.stiffness - 600.0).abs() < 1e-12,
        "{tip:?}"
    );
    let want = string_with_point(1000.0, 1.0, (10.0, 10.0), (600.0, 2.0));
    // the arm's inertia and pivot left out: another frequency (the check
    // can fail)
    let bare = string_with_point(1000.0, 1.0, (10.0, 10.0), (100.0, 0.5));
    let mut errors = Vec::new();
    for h in [0.2, 0.1] {
        let sc = resolve_scene(&arm_line(arm, h), &[]).unwrap();
        let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
        let w = lowest_eigenpairs(&beam.mass, &beam.stiffness, 1)
            .unwrap()
            .omega_sq[0]
            .sqrt();
        let err = (w - want) / want;
        println!(
            "h = {h} m: ω₁ = {w:.9} rad/s, A1 with S1–S2 {want:.9} rad/s (error {err:.3e}); without the arm {bare:.6} rad/s"
        );
        assert!(err > 0.0, "Rayleigh–Ritz: from above");
        assert!(((w - bare) / bare).abs() > 100.0 * err, "{w} {bare}");
        errors.push(err);
    }
    let order = observed_order(errors[0], errors[1], 2.0);
    println!("order {order:.3}");
    assert!((order - 2.0).abs() < FREQ_ORDER_TOL, "{order}");
}
