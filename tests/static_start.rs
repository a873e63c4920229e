//! The static start with its carriers (docs/lines.md W6–W8):
//! `[time] initial = "static"` puts each carrier's static contact force
//! into d₀ (mass–springs, multi-mass pantographs, moving forces), so a
//! scene of stationary carriers starts in equilibrium. Checked against
//!
//! * the closed form by superposition of point-load solutions
//!   (`analytic::StaticPointLoad`, nodally exact for string elements): two
//!   stationary mass–springs on either side of a string under its weight,
//!   their forces coupled through the wire (W8);
//! * a static start that stays still (a single mass, a three-mass
//!   pantograph away from the wire's ends, a penalty contact with its
//!   static penetration, a Galerkin basis), while the rest start moves;
//! * a carrier that would not press at rest refused by name.

use taut::analytic::StaticPointLoad;
use taut::scene::Support;
use taut::{RunOutput, resolve_scene};

use crate::common;

const L: f64 = 10.0;
const T: f64 = 1000.0;
const G: f64 = 9.81;

/// A 10 m string (T = 1000 N, ρA = 1 kg/m, self-weight) on 50 elements,
/// pinned at both ends, with `carriers` and `extra` (`[time]` keys after
/// `[time]`); probes at x = 2, 3, 7 m.
fn string(carriers: &str, time: &str, extra: &str) -> String {
    format!(
        r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 0.0
tension = 1000.0
left = "pinned"
right = "pinned"

[mesh]
elements = 50

[gravity]
g = 9.81
beam_self_weight = true

{carriers}

[[probe]]
name = "p2"
x = 2.0

[[probe]]
name = "p3"
x = 3.0

[[probe]]
name = "p7"
x = 7.0

{extra}

[time]
step = 1e-3
initial = "static"
{time}
"#
    )
}

/// A stationary mass–spring below at x = 3 m (m = 2 kg, k = 500 N/m,
/// δ0 = 0.3 m: λ₀ = kδ0 − m g = 130.38 N) and one above at x = 7 m (m =
/// 5 kg, k = 1000 N/m, δ0 = 0.01 m: λ₀ = kδ0 + m g = 59.05 N).
const TWO_MASSES: &str = r#"
[[carrier]]
mass = 2.0
stiffness = 500.0
preload = 0.3
side = "below"
start = 3.0
speed = { profile = "constant", value = 0.0 }

[[carrier]]
mass = 5.0
stiffness = 1000.0
preload = 0.01
side = "above"
start = 7.0
speed = { profile = "constant", value = 0.0 }
"#;

/// The static start against the closed form (relative to the largest
/// displacement or force): string elements with consistent loads are
/// nodally exact for point and uniform loads, so only the solves'
/// round-off remains (measured below 1e-14).
const STATIC_EXACT: f64 = 1e-11;

#[test]
fn two_carriers_start_at_the_superposed_point_load_solution() {
    let out = go(&string(TWO_MASSES, "end = 0.001", ""));
    let gs = StaticPointLoad::new(0.0, T, L, Support::Pinned, Support::Pinned).unwrap();
    let u = |x: f64| -G * x * (L - x) / (2.0 * T);
    // carriers (x_c, s, k, λ₀); v = u + Σ s_c λ_c G(x_c, ·),
    // λ_c = λ₀ − k s_c v(x_c): a 2 × 2 system
    let c = [
        (3.0, 1.0, 500.0, 500.0 * 0.3 - 2.0 * G),
        (7.0, -1.0, 1000.0, 1000.0 * 0.01 + 5.0 * G),
    ];
    let a = |i: usize, j: usize| {
        let (xi, si, ki, _) = c[i];
        let (xj, sj, _, _) = c[j];
        ki * si * sj * gs.deflection(xj, xi) + if i == j { 1.0 } else { 0.0 }
    };
    let b = |i: usize| c[i].3 - c[i].2 * c[i].1 * u(c[i].0);
    let det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
    let lam = [
        (b(0) * a(1, 1) - a(0, 1) * b(1)) / det,
        (a(0, 0) * b(1) - a(1, 0) * b(0)) / det,
    ];
    let v = |x: f64| {
        u(x) + c[0].1 * lam[0] * gs.deflection(c[0].0, x)
            + c[1].1 * lam[1] * gs.deflection(c[1].0, x)
    };
    let want = [v(2.0), v(3.0), v(7.0)];
    let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for ((name, col), w) in out.history.probes.iter().zip(want) {
        let err = (col[0] - w).abs() / scale;
        println!(
            "{name}: {:.9e} m, closed form {w:.9e} m, error {err:.1e}",
            col[0]
        );
        assert!(err < STATIC_EXACT, "{name}: {} vs {w}", col[0]);
    }
    for (tr, l) in out.history.carriers.iter().zip(lam) {
        let err = (tr.force[0] - l).abs() / l;
        println!(
            "force {:.9} N, closed form {l:.9} N, error {err:.1e}",
            tr.force[0]
        );
        assert!(err < STATIC_EXACT, "{} vs {l}", tr.force[0]);
        // the mass sits on the wire: gap 0
        assert!(tr.gap[0].abs() < STATIC_EXACT * scale, "{}", tr.gap[0]);
    }
}

/// A static start at rest stays there: the drift of every probe and
/// contact force over 200 steps relative to its static value, round-off
/// of the static solve's residual (condition of K times ε), measured
/// below 1e-12.
const STILL: f64 = 1e-10;

/// The largest drift of the probes (relative to the largest
/// displacement) and of the contact forces (relative to each carrier's
/// largest force).
fn drift(out: &RunOutput) -> (f64, f64) {
    let scale = out
        .history
        .probes
        .iter()
        .flat_map(|(_, c)| c.iter().map(|v| v.abs()))
        .fold(0.0, f64::max);
    let probes = out
        .history
        .probes
        .iter()
        .flat_map(|(_, c)| c.iter().map(move |v| (v - c[0]).abs()))
        .fold(0.0, f64::max)
        / scale;
    let forces = out
        .history
        .carriers
        .iter()
        .flat_map(|tr| {
            let scale = tr.force.iter().fold(0.0, |m: f64, f| m.max(f.abs()));
            tr.force
                .iter()
                .map(move |f| (f - tr.force[0]).abs() / scale)
        })
        .fold(0.0, f64::max);
    (probes, forces)
}

/// `scene` started static stays still; started at rest it moves (the
/// check can fail).
fn stays_still(label: &str, scene: &str) {
    let (probes, forces) = drift(&go(scene));
    println!("{label}: static start drift {probes:.2e} (probes), {forces:.2e} (forces)");
    assert!(
        probes < STILL && forces < STILL,
        "{label}: {probes} {forces}"
    );
    let (probes, forces) = drift(&go(&scene.replace("initial = \"static\"", "")));
    println!("{label}: rest start drift {probes:.2e} (probes), {forces:.2e} (forces)");
    assert!(probes > 1e3 * STILL, "{label}: {probes}");
}

/// A three-mass pantograph below at x = 4 m (pantograph_3mass.toml's
/// masses and springs, 120.2 N static with a rigid roof spring 0).
const PANTOGRAPH: &str = r#"
[[carrier]]
masses = [7.2, 15.5, 15.0]
stiffnesses = [4200.0, 10400.0, 0.0]
dampings = [10.0, 0.0, 90.0]
uplift = 490.0
side = "below"
start = 4.0
speed = { profile = "constant", value = 0.0 }
"#;

#[test]
fn static_starts_with_carriers_stay_still() {
    stays_still("two masses", &string(TWO_MASSES, "end = 0.2", ""));
    stays_still(
        "three-mass pantograph",
        &string(PANTOGRAPH, "end = 0.2", ""),
    );
    // its roof spring > 0: S is then the whole chain's Schur complement
    stays_still(
        "pantograph on a roof spring",
        &string(
            &PANTOGRAPH.replace("10400.0, 0.0]", "10400.0, 3000.0]"),
            "end = 0.2",
            "",
        ),
    );
    stays_still(
        "penalty contact",
        &string(
            TWO_MASSES,
            "end = 0.2",
            "[contact]\nformulation = \"penalty\"\npenalty = { stiffness = 2.0e4 }\n",
        ),
    );
    stays_still(
        "galerkin basis",
        &string(TWO_MASSES, "end = 0.2", "").replace(
            "[mesh]\nelements = 50\n",
            "[mesh]\nelements = 50\nkind = \"galerkin\"\nmodes = 40\n",
        ),
    );
}

#[test]
fn a_carrier_that_would_not_press_is_refused() {
    // 2 kg riding below on no spring: λ = −m g < 0
    let scene = string(
        &TWO_MASSES.replace(
            "stiffness = 500.0\npreload = 0.3",
            "stiffness = 0.0\npreload = 0.0",
        ),
        "end = 0.01",
        "",
    );
    let sc = resolve_scene(&scene, &[]).unwrap_or_else(|e| panic!("{e}"));
    let Err(err) = taut::run(&sc, &mut |_, _| {}) else {
        panic!("a carrier pulling the wire down was accepted")
    };
    let err = err.to_string();
    println!("{err}");
    assert!(
        err.contains("carrier.0") && err.contains("static contact force"),
        "{err}"
    );
}

fn go(text: &str) -> RunOutput {
    let sc = resolve_scene(text, &[]).unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

/// A penalty relative to the step (κ = ρ/W, default ρ = 1000) started
/// static: the head starts at the rigid equilibrium with its static force,
/// and the penetration λW/ρ the penalty needs builds over the first steps.
/// The force's share of that is of order 1/ρ, and an undamped step
/// response overshoots to twice its static value: 2/ρ = 2e-3, measured
/// 2.0e-3 (forces) and 4.9e-6 (probes); bound 4/ρ (a rest start drifts
/// by 1).
const RELATIVE_PENALTY_TRANSIENT: f64 = 4.0 / 1000.0;

#[test]
fn a_relative_penalty_starts_near_static() {
    let scene = string(
        TWO_MASSES,
        "end = 0.2",
        "[contact]\nformulation = \"penalty\"\n",
    );
    let (probes, forces) = drift(&go(&scene));
    println!("relative penalty: static start drift {probes:.2e} (probes), {forces:.2e} (forces)");
    assert!(
        probes < RELATIVE_PENALTY_TRANSIENT && forces < RELATIVE_PENALTY_TRANSIENT,
        "{probes} {forces}"
    );
}

/// A mass–spring's external force series (`external_force`) is in the
/// static start at its value at t = 0: the mass's free force is
/// kδ0 − s m g + s F_ext(0) (`System::new` sets it before the static
/// start reads it), so a constant 15 N series is the same start as the
/// preload raised by F_ext/k — the same d₀ and the same static force to
/// round-off ([`STATIC_EXACT`]) — and the run stays still; without the
/// series in the start the force would be 15 N (of 45) off.
#[test]
fn an_external_force_series_is_in_the_static_start_at_its_first_value() {
    let one = |preload: f64, series: &str| {
        format!(
            "[[carrier]]\nmass = 2.0\nstiffness = 500.0\npreload = {preload:e}\nside = \"below\"\nstart = 3.0\nspeed = {{ profile = \"constant\", value = 0.0 }}\n{series}\n"
        )
    };
    let series = "external_force = { time = [0.0, 1.0], force = [15.0, 15.0] }";
    let with = go(&string(&one(0.3, series), "end = 0.2", ""));
    let raised = go(&string(&one(0.3 + 15.0 / 500.0, ""), "end = 0.2", ""));
    let (fw, fr) = (
        with.history.carriers[0].force[0],
        raised.history.carriers[0].force[0],
    );
    let dp = with
        .history
        .probes
        .iter()
        .zip(&raised.history.probes)
        .map(|((_, a), (_, b))| (a[0] - b[0]).abs() / b[0].abs())
        .fold(0.0, f64::max);
    println!(
        "static force {fw:.9} N with the series, {fr:.9} N with the raised preload; probes {dp:.2e}"
    );
    assert!((fw - fr).abs() <= STATIC_EXACT * fr.abs(), "{fw} {fr}");
    assert!(dp <= STATIC_EXACT, "{dp}");
    let plain = go(&string(&one(0.3, ""), "end = 0.2", ""));
    assert!((fw - plain.history.carriers[0].force[0]).abs() > 1.0);
    stays_still(
        "external force series",
        &string(&one(0.3, series), "end = 0.2", ""),
    );
}
