//! Dropper dashpots (issue 27; docs/lines.md eq. D11): a linear dropper's
//! `damping` c_d puts c_d r_d r_dᵀ in the damping matrix C, as an
//! `[[attachment]]` dashpot does (r_d = r_c − r_m on the messenger),
//! checked against
//!
//! * the equivalent attachment: a linear damped dropper at a node to a
//!   fixed anchor is an `[[attachment]]` spring k_d + dashpot c_d at x_d
//!   plus its preload k_d e₀ as a standing force: the same history to
//!   round-off;
//! * first-order modal damping: one damped dropper (a near-zero spring) at
//!   the middle of a string damps its first mode at the rate
//!   σ₁ = c_d φ₁(x_d)²/(2 M₁) (ζ₁ = σ₁/ω₁), read from the run's modal
//!   coordinate;
//! * a messenger dropper's dashpot couples the lines in C and damps the run;
//! * the key: negative, NaN and infinite damping refused by name, a
//!   tension-only dropper's dashpot refused, and a damped dropper refused
//!   where attachment dashpots are (central difference, a modal basis)
//!   with the key `dropper.<i>.damping`.

use taut::integrate::Integrator;
use taut::{RunOutput, resolve_scene};

use crate::common;

/// A 10 m pinned–pinned tensioned beam (100 elements: x = 6 m is a node)
/// with a 20 N force moving in from x = 0 at 0.2 m/s (smooth start) that
/// excites it; `extra` adds the link at x_d = 6 m.
fn beam(extra: &str) -> String {
    format!(
        r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 1.0
tension = 1000.0
left = "pinned"
right = "pinned"

[mesh]
elements = 100

[[carrier]]
force = 20.0
side = "below"
start = 0.0
speed = {{ profile = "smooth_ramp", cruise = 2.0 }}

[time]
step = 2.0e-3
end = 4.0

[gravity]
g = 0.0

[[probe]]
name = "p"
x = 3.0
{extra}
"#
    )
}

/// k_d = 1e4 N/m, e₀ = 1 mm (preload 10 N), c_d = 20 N·s/m (first mode
/// ζ₁ ≈ 0.09).
const DROPPER: &str = r#"
[[dropper]]
x = 6.0
stiffness = 1.0e4
anchor_height = 0.5
length = 0.499
damping = 20.0
linear = true
"#;

/// The same link as an attachment spring and dashpot plus its preload
/// k_d e₀ = 10 N up as a standing force.
const ATTACHMENT: &str = r#"
[[attachment]]
x = 6.0
stiffness = 1.0e4
damping = 20.0

[[carrier]]
force = 10.0
side = "below"
start = 6.0
speed = { profile = "constant", value = 0.0 }
"#;

/// The dropper and its attachment twin assemble the same K and C; the
/// preload enters the constant load in one and the standing force's load
/// in the other, so they differ by the round-off of those sums over the
/// run's 2000 steps, relative to the largest displacement.
const SAME_LINK: f64 = 1.0e-11;

fn go(text: &str, set: &[&str]) -> RunOutput {
    let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let sc = resolve_scene(text, &o).unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn a_damped_linear_dropper_is_an_attachment_spring_dashpot_and_preload() {
    for method in [
        "integrator={ method = \"generalized_alpha\", rho_inf = 0.8 }",
        "integrator={ method = \"bathe\" }",
    ] {
        let d = go(&beam(DROPPER), &[method]);
        let a = go(&beam(ATTACHMENT), &[method]);
        let undamped = go(&beam(&DROPPER.replace("damping = 20.0\n", "")), &[method]);
        let (pd, pa) = (&d.history.probes[0].1, &a.history.probes[0].1);
        let (wd, wa) = (&d.history.carriers[0].w, &a.history.carriers[0].w);
        let (e_p, e_w) = (worst(pd, pa), worst(wd, wa));
        let e_u = worst(&undamped.history.probes[0].1, pa);
        println!(
            "{method}: dropper vs attachment {e_p:.2e} (probe) {e_w:.2e} (force); undamped {e_u:.2e}"
        );
        assert!(e_p < SAME_LINK && e_w < SAME_LINK, "{e_p} {e_w}");
        // the dashpot matters: without it the run is far from the twin
        assert!(e_u > 1e3 * SAME_LINK, "{e_u}");
        // the recorded force is the spring's and the dashpot's, k e + c ė
        let f = &d.history.droppers[0].1;
        assert!(f.iter().all(|v| v.is_finite()));
        let fu = &undamped.history.droppers[0].1;
        assert!(worst(f, fu) > 1e3 * SAME_LINK);
    }
}

/// The string of the modal-damping check: L = 1 m, ρA = 1 kg/m, T = 100 N
/// (ω₁ = 10π rad/s on the continuum), 20 linear elements, a standing 10 N
/// force at the middle switched on at t = 0, and one linear dropper at the
/// middle with a near-zero spring (1e-6 N/m: it shifts ω₁² by 2e-9
/// relative) and the dashpot c_d.
fn string(c: f64) -> taut::Resolved {
    let text = format!(
        r#"
[beam]
length = 1.0
mass_per_length = 1.0
bending_stiffness = 0.0
tension = 100.0
left = "pinned"
right = "pinned"

[mesh]
elements = 20

[[carrier]]
force = 10.0
side = "below"
start = 0.5
speed = {{ profile = "constant", value = 0.0 }}

[time]
step = 1.0e-4
end = 1.0

[gravity]
g = 0.0

[[dropper]]
x = 0.5
stiffness = 1.0e-6
anchor_height = 0.1
length = 0.1
damping = {c:e}
linear = true
"#
    );
    resolve_scene(&text, &["integrator={ method = \"newmark\" }".to_string()])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// c_d, N·s/m: σ₁ = c_d φ₁(½)²/(2M₁) = 0.5 1/s, ζ₁ = 0.016.
const MODAL_C: f64 = 0.5;

/// The decay rate of mode 1 against the first-order σ₁ = c_d φ₁²/(2M₁)
/// (φ₁, M₁ the model's own discrete sine mode, so no mesh error): the
/// neglected terms are the dashpot's coupling of mode 1 to modes 3, 5, …
/// (even modes vanish at the middle). Its second order shifts only the
/// frequency; the coupled modes' forced motion in η̇₁ has relative size
/// ~ ζ₁ω₁ω₃/(ω₃² − ω₁²)·(η₃/η₁)·(ω₃/ω₁) ≈ 0.25 ζ₁ ≈ 4e-3 of a peak, which
/// in the slope over the 0.95 s fitted (σ₁·0.95 ≈ 0.48 of decay) is up to
/// ~1e-2 relative; trapezoidal Newmark adds O((ω₁Δt)²) = 1e-5. Measured
/// 7.9e-3 (9 peaks of |η̇₁|); the band is the estimate with 1.5× margin.
const MODAL_FIRST_ORDER: f64 = 1.5e-2;

#[test]
fn one_damped_dropper_damps_a_string_mode_at_the_first_order_rate() {
    let sc = string(MODAL_C);
    let mut run = Integrator::new(&sc).unwrap();
    let beam = run.beam();
    let n = beam.n;
    // mode 1 of the linear-element string: the discrete sine at the nodes
    // (exact for a uniform mesh with consistent mass)
    let mut phi = vec![0.0; n];
    let ne = 20;
    for i in 1..ne {
        let x = i as f64 / ne as f64;
        beam.point_vector(x)
            .scatter((std::f64::consts::PI * x).sin(), &mut phi, 1, 0);
    }
    let mut m_phi = vec![0.0; n];
    beam.mass.mul_acc(&phi, 1.0, &mut m_phi);
    let m1: f64 = phi.iter().zip(&m_phi).map(|(a, b)| a * b).sum();
    // φ₁(x_d) = sin(π/2) = 1 at the node x_d = ½
    let sigma = MODAL_C / (2.0 * m1);
    // η̇₁ = φᵀMv / M₁ each step; its peaks |η̇₁| decay as e^{−σt}
    let mut rate = Vec::with_capacity(sc.steps + 1);
    rate.push(0.0);
    for _ in 0..sc.steps {
        run.step().unwrap();
        let v = &run.state().v;
        rate.push(m_phi.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / m1);
    }
    let (mut ts, mut ls) = (Vec::new(), Vec::new());
    for i in 1..rate.len() - 1 {
        let a = rate[i].abs();
        if a > rate[i - 1].abs() && a >= rate[i + 1].abs() && i as f64 * sc.dt > 0.05 {
            ts.push(i as f64 * sc.dt);
            ls.push(a.ln());
        }
    }
    // least-squares slope of ln|peak| against t
    let k = ts.len() as f64;
    let (mt, ml) = (ts.iter().sum::<f64>() / k, ls.iter().sum::<f64>() / k);
    let slope = ts
        .iter()
        .zip(&ls)
        .map(|(t, l)| (t - mt) * (l - ml))
        .sum::<f64>()
        / ts.iter().map(|t| (t - mt) * (t - mt)).sum::<f64>();
    let rel = (-slope - sigma).abs() / sigma;
    println!(
        "mode 1 decay: run {:.6} 1/s, first order {sigma:.6} 1/s, rel {rel:.2e} ({} peaks)",
        -slope,
        ts.len()
    );
    assert!(ts.len() >= 8, "{} peaks", ts.len());
    assert!(rel < MODAL_FIRST_ORDER, "{rel}");
}

#[test]
fn a_messenger_dropper_s_dashpot_couples_the_lines_and_damps() {
    let cut = ["time.end=0.3"];
    let base = common::scene("span_messenger.toml", &cut);
    assert!(!base.is_damped());
    let lin = common::scene("span_messenger.toml", &cut);
    let i = lin
        .droppers
        .iter()
        .position(|d| d.on_messenger())
        .expect("a messenger dropper");
    let o = format!("dropper.{i}.damping=50.0");
    let lin_o = format!("dropper.{i}.linear=true");
    let und = common::scene("span_messenger.toml", &[cut[0], &lin_o]);
    let damped = common::scene("span_messenger.toml", &[cut[0], &lin_o, &o]);
    assert!(damped.is_damped());
    let m = damped.beam.messenger.as_ref().unwrap();
    assert_eq!(m.tie_dashpots.len(), 1);
    let (a, b) = (common::run(&und), common::run(&damped));
    assert!(a.history.carriers[0].w != b.history.carriers[0].w);
    // a messenger dropper's dashpot is refused where attachment dashpots are
    let e = taut::resolve_scene(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/span_messenger.toml"),
        )
        .unwrap(),
        &[
            lin_o.clone(),
            o.clone(),
            "integrator={ method = \"central_difference\" }".to_string(),
        ],
    )
    .err()
    .unwrap_or_else(|| panic!("central difference refuses the dashpot"))
    .to_string();
    assert!(e.contains(&format!("dropper.{i}.damping")), "{e}");
}

#[test]
fn dropper_damping_is_checked_by_name() {
    let base = beam(&DROPPER.replace("damping = 20.0\n", ""));
    let refused = |extra: &str, set: &[&str], parts: &[&str]| {
        let o: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let e = resolve_scene(&format!("{base}{extra}\n"), &o)
            .err()
            .unwrap_or_else(|| panic!("{extra} {set:?} should be refused"))
            .to_string();
        for p in parts {
            assert!(e.contains(p), "{extra} {set:?}: {e}");
        }
    };
    refused("damping = -1.0", &[], &["dropper.0.damping", "-1", "≥ 0"]);
    refused(
        "damping = nan",
        &[],
        &["dropper.0.damping", "NaN", "finite"],
    );
    refused("damping = inf", &[], &["dropper.0.damping", "finite"]);
    // a tension-only dropper's dashpot is not built
    let tension_only = beam(
        &DROPPER
            .replace("linear = true\n", "")
            .replace("damping = 20.0\n", ""),
    );
    let e = resolve_scene(&format!("{tension_only}damping = 3.0\n"), &[])
        .err()
        .unwrap_or_else(|| panic!("tension-only dashpot refused"))
        .to_string();
    for p in [
        "dropper.0.damping",
        "3",
        "tension-only",
        "linear = true",
        "[[attachment]]",
    ] {
        assert!(e.contains(p), "{e}");
    }
    // refused where attachment dashpots are, named as the dropper's key
    // (after the scene's own attachments: the index is the dropper's)
    let att = "\n[[attachment]]\nx = 2.0\nstiffness = 5.0\n";
    for set in [
        "integrator={ method = \"central_difference\" }",
        "mesh={ kind = \"modal\", modes = 8, elements = 100 }",
    ] {
        refused(
            &format!("{att}{DROPPER}"),
            &[set],
            &["dropper.1.damping", "20"],
        );
    }
    // 0 is no dashpot: the undamped run, byte for byte
    let zero = resolve_scene(&format!("{base}damping = 0.0\n"), &[]).unwrap();
    let none = resolve_scene(&base, &[]).unwrap();
    assert!(!zero.is_damped() && !none.is_damped());
    assert_eq!(
        common::run(&zero).history.probes[0].1,
        common::run(&none).history.probes[0].1
    );
}

#[test]
fn the_line_generator_puts_the_dashpot_on_every_dropper() {
    let sc = common::scene("line_10_spans_linear.toml", &["line.dropper_damping=5.0"]);
    assert!(!sc.droppers.is_empty());
    assert!(sc.droppers.iter().all(|d| d.damping == 5.0));
    assert!(sc.is_damped());
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for (scene, set, parts) in [
        (
            "line_10_spans.toml",
            "line.dropper_damping=5.0",
            &["line.dropper_damping", "5", "tension-only"][..],
        ),
        (
            "line_10_spans_linear.toml",
            "line.dropper_damping=-1.0",
            &["line.dropper_damping", "-1", "≥ 0"][..],
        ),
    ] {
        let e = taut::load_scene(&path.join(scene), &[set.to_string()])
            .err()
            .unwrap_or_else(|| panic!("{scene} {set}"))
            .to_string();
        for p in parts {
            assert!(e.contains(p), "{scene} {set}: {e}");
        }
    }
}
