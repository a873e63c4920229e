//! Dropper dashpots (docs/lines.md eq. D11, D12): a linear dropper's
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
//!   tension-only dropper's dashpot accepted, and a damped dropper refused
//!   where attachment dashpots are (central difference, a modal basis)
//!   with the key `dropper.<i>.damping`;
//! * a **tension-only** dropper's dashpot (eq. D12, the Kelvin–Voigt link
//!   N_d = max(0, k_d e + c_d ė)): against an independent RK4 integration
//!   of the same semi-discrete law (second order in Δt through slack and
//!   re-tension), the law read back from the state at every step (three
//!   laws, HHT on the messenger), the linear damped dropper when taut and
//!   nothing at all when slack.

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
            std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
                .join("scenes/span_messenger.toml"),
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
    // a tension-only dropper carries one too (D12)
    let tension_only = beam(
        &DROPPER
            .replace("linear = true\n", "")
            .replace("damping = 20.0\n", ""),
    );
    let sc = resolve_scene(&format!("{tension_only}damping = 3.0\n"), &[])
        .unwrap_or_else(|e| panic!("a tension-only dashpot is accepted: {e}"));
    assert!(!sc.droppers[0].linear && sc.droppers[0].damping == 3.0);
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
    // and on the tension-only line (D12)
    let sc = common::scene("line_10_spans.toml", &["line.dropper_damping=5.0"]);
    assert!(sc.droppers.iter().all(|d| d.damping == 5.0 && !d.linear));
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("scenes");
    for (scene, set, parts) in [(
        "line_10_spans_linear.toml",
        "line.dropper_damping=-1.0",
        &["line.dropper_damping", "-1", "≥ 0"][..],
    )] {
        let e = taut::load_scene(&path.join(scene), &[set.to_string()])
            .err()
            .unwrap_or_else(|| panic!("{scene} {set}"))
            .to_string();
        for p in parts {
            assert!(e.contains(p), "{scene} {set}: {e}");
        }
    }
}

// ------------------------------------------------------------------------
// Tension-only dashpots: the Kelvin–Voigt link N_d = max(0, k_d e + c_d ė)
// (docs/lines.md eq. D12)
// ------------------------------------------------------------------------

/// The Kelvin–Voigt check's scene: the 10 m beam above on 20 Hermite
/// elements (x_d = 6 m is a node), the 20 N force moving up from x = 4 m
/// at a constant 2 m/s for 2 s (it passes x_d at t = 1 s), and one
/// tension-only dropper at x_d (k_d = 1e4 N/m, unstretched `length` below
/// its 0.5 m anchor, c_d = `c` N·s/m, τ = c_d/k_d) whose preload
/// N0 = k_d(0.5 − length), when positive, is balanced by a standing force
/// N0 down at x_d, so the straight beam starts in equilibrium (as in
/// `droppers::lift_scene`); with `length` = [`KV_LENGTH`] the force lifts
/// the dropper slack and it re-tensions behind it. Newmark's average
/// acceleration (α_f = 0: the dropper's force is recorded at t_{n+1},
/// where the reference is read).
fn kelvin_voigt(c: f64, dt: f64, length: f64) -> taut::Resolved {
    let text = kelvin_voigt_text(c, length, false);
    resolve_scene(
        &text,
        &[
            format!("time.step={dt:e}"),
            "integrator={ method = \"newmark\" }".to_string(),
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The preload N0 = k_d(0.5 − length) of the Kelvin–Voigt dropper, N.
fn kv_preload(length: f64) -> f64 {
    1.0e4 * (0.5 - length)
}

/// [`kelvin_voigt`]'s scene text, the dropper `linear` or tension-only.
fn kelvin_voigt_text(c: f64, length: f64, linear: bool) -> String {
    let n0 = kv_preload(length);
    let balance = if n0 > 0.0 {
        format!(
            "\n[[carrier]]\nforce = {n0:e}\nside = \"above\"\nstart = 6.0\nspeed = {{ profile = \"constant\", value = 0.0 }}\n"
        )
    } else {
        String::new()
    };
    beam(&format!(
        "\n[[dropper]]\nx = 6.0\nstiffness = 1.0e4\nanchor_height = 0.5\nlength = {length:e}\ndamping = {c:e}\nlinear = {linear}\n{balance}"
    ))
    .replace("elements = 100", "elements = 20")
    .replace("start = 0.0", "start = 4.0")
    .replace(
        "speed = { profile = \"smooth_ramp\", cruise = 2.0 }",
        "speed = { profile = \"constant\", value = 2.0 }",
    )
    .replace("end = 4.0", "end = 2.0")
}

/// c_d of the Kelvin–Voigt checks, N·s/m: τ = c_d/k_d = 5 ms; without
/// the dashpot the run is 0.31 (of the largest force) away from the
/// reference, 100× the finest run's error (measured below).
const KV_C: f64 = 50.0;

/// The unstretched length of the Kelvin–Voigt dropper, m: anchor 0.5 m,
/// e₀ = 1 mm, preload 10 N.
const KV_LENGTH: f64 = 0.499;

/// The reference step of the Kelvin–Voigt check, s: RK4 on the
/// semi-discrete equations, whose right-hand side is Lipschitz (the law
/// max(0, ·) is continuous); the fastest mode (ω ≈ 3e2 rad/s) has
/// ωh = 6e-3, so RK4's error is far below the Newmark runs' (checked by
/// the observed order, which a poor reference would flatten).
const KV_REF_STEP: f64 = 2.0e-5;

/// The same semi-discrete equations as the run, integrated independently:
/// M ẍ + C ẋ + K x = f + F r_f(x_c(t)) − N0 r_d + μ r_d with the model's own M, K,
/// C and constant load f (the dropper's spring, dashpot and preload in
/// them, D7/D12) and the slack correction μ = max(0, −(k_d e + c_d ė)),
/// e = e₀ − r_dᵀx, ė = −r_dᵀẋ, so that N_d = k_d e + c_d ė + μ =
/// max(0, k_d e + c_d ė) by construction. Classical RK4 at
/// [`KV_REF_STEP`]; returns (N_d, probe) at every `every`-th reference
/// step.
fn kelvin_voigt_reference(sc: &taut::Resolved, every: usize, t_end: f64) -> Vec<(f64, f64)> {
    use nalgebra::{DMatrix, DVector};
    let it = Integrator::new(sc).unwrap();
    let beam = it.beam();
    let n = beam.n;
    let dense = |b: &taut::model::banded::SymBand| {
        DMatrix::from_fn(n, n, |i, j| {
            if i.abs_diff(j) <= b.bandwidth() {
                b.get(i, j)
            } else {
                0.0
            }
        })
    };
    let m_inv = dense(&beam.mass).try_inverse().unwrap();
    let mk = &m_inv * dense(&beam.stiffness);
    let mc = &m_inv * dense(it.system().damping().expect("the dashpot is in C"));
    let mf = &m_inv * DVector::from_column_slice(&beam.load);
    let d = &sc.droppers[0];
    let vec_of = |x: f64| {
        let pv = beam.point_vector(x);
        let mut r = DVector::zeros(n);
        for (i, v) in pv.idx.iter().zip(pv.val) {
            r[*i] += v;
        }
        r
    };
    let r_d = vec_of(d.x);
    let m_r = &m_inv * &r_d;
    let probe = vec_of(3.0);
    let (k, c, e0) = (d.stiffness, d.damping, d.rest_extension());
    // the standing force N0 down at x_d that balances the preload
    let balance = &m_inv * (vec_of(d.x) * -kv_preload(d.length).max(0.0));
    let force = |x: &DVector<f64>, y: &DVector<f64>| k * (e0 - r_d.dot(x)) - c * r_d.dot(y);
    let accel = |t: f64, x: &DVector<f64>, y: &DVector<f64>| {
        let mu = (-force(x, y)).max(0.0);
        let f = &m_inv * (vec_of(4.0 + 2.0 * t) * 20.0);
        &mf + &balance + f - &mk * x - &mc * y + &m_r * mu
    };
    let (mut x, mut y) = (DVector::zeros(n), DVector::zeros(n));
    let h = KV_REF_STEP;
    let steps = (t_end / h).round() as usize;
    let mut out = vec![(force(&x, &y).max(0.0), probe.dot(&x))];
    for s in 0..steps {
        let t = s as f64 * h;
        let (k1x, k1y) = (y.clone(), accel(t, &x, &y));
        let (x2, y2) = (&x + &k1x * (h / 2.0), &y + &k1y * (h / 2.0));
        let (k2x, k2y) = (y2.clone(), accel(t + h / 2.0, &x2, &y2));
        let (x3, y3) = (&x + &k2x * (h / 2.0), &y + &k2y * (h / 2.0));
        let (k3x, k3y) = (y3.clone(), accel(t + h / 2.0, &x3, &y3));
        let (x4, y4) = (&x + &k3x * h, &y + &k3y * h);
        let (k4x, k4y) = (y4.clone(), accel(t + h, &x4, &y4));
        x += (k1x + k2x * 2.0 + k3x * 2.0 + k4x) * (h / 6.0);
        y += (k1y + k2y * 2.0 + k3y * 2.0 + k4y) * (h / 6.0);
        if (s + 1) % every == 0 {
            out.push((force(&x, &y).max(0.0), probe.dot(&x)));
        }
    }
    out
}

/// The observed order of the Newmark runs' error against the reference
/// over Δt = 4e-4, 2e-4, 1e-4 s: the average-acceleration rule is second
/// order, and the law's kinks (slack, re-tension) keep it so because the
/// force is continuous (the corrections solve the law within each step).
/// Measured 1.92 and 1.99 (dropper force), 2.11 and 1.98 (probe); the band
/// is that of the other Δt orders (±0.3 around 2).
const KV_ORDER: (f64, f64) = (1.7, 2.3);

/// The undamped link's distance from the reference against the finest
/// run's error: the dashpot's effect must stand far above the Δt error for
/// the convergence to say anything about it (measured ≈ 100×).
const KV_DASHPOT_EFFECT: f64 = 20.0;

/// Kelvin–Voigt droppers converge in Δt to an independent integration of
/// the same semi-discrete law, at second order, through slack and
/// re-tension; the dashpot's part of the force is a large share of it.
#[test]
fn a_kelvin_voigt_dropper_converges_to_an_independent_integration() {
    let t_end = 2.0;
    let coarse = 4.0e-4;
    let every = (coarse / KV_REF_STEP).round() as usize;
    let reference = kelvin_voigt_reference(&kelvin_voigt(KV_C, coarse, KV_LENGTH), every, t_end);
    let scale_f = reference.iter().fold(0.0f64, |m, r| m.max(r.0));
    let scale_p = reference.iter().fold(0.0f64, |m, r| m.max(r.1.abs()));
    let slack_ref = reference.iter().filter(|r| r.0 == 0.0).count();
    assert!(slack_ref > 0, "the reference dropper goes slack");
    let mut errors = Vec::new();
    for dt in [4.0e-4, 2.0e-4, 1.0e-4] {
        let sc = kelvin_voigt(KV_C, dt, KV_LENGTH);
        let out = common::run(&sc);
        let stride = (coarse / dt).round() as usize;
        let f = &out.history.droppers[0].1;
        let p = &out.history.probes[0].1;
        let (mut ef, mut ep) = (0.0f64, 0.0f64);
        for (j, r) in reference.iter().enumerate() {
            ef = ef.max((f[j * stride] - r.0).abs());
            ep = ep.max((p[j * stride] - r.1).abs());
        }
        let slack = out.droppers[0].slack_intervals_time.len();
        println!(
            "Δt = {dt:e}: force {:.3e}, probe {:.3e} (relative), {slack} slack intervals",
            ef / scale_f,
            ep / scale_p
        );
        assert!(slack > 0);
        errors.push((ef / scale_f, ep / scale_p));
    }
    for w in errors.windows(2) {
        for (a, b, what) in [(w[0].0, w[1].0, "force"), (w[0].1, w[1].1, "probe")] {
            let order = (a / b).log2();
            println!("{what}: order {order:.2}");
            assert!(
                (KV_ORDER.0..=KV_ORDER.1).contains(&order),
                "{what}: order {order}"
            );
        }
    }
    // the dashpot matters: the undamped link is far from the reference
    let undamped = common::run(&kelvin_voigt(0.0, coarse, KV_LENGTH));
    let f = &undamped.history.droppers[0].1;
    let off = reference
        .iter()
        .enumerate()
        .fold(0.0f64, |m, (j, r)| m.max((f[j] - r.0).abs()))
        / scale_f;
    println!("undamped link against the reference: {off:.3e}");
    assert!(off > KV_DASHPOT_EFFECT * errors[2].0, "{off}");
}

/// D12 checked from the state, in units of the largest |k_d e + c_d ė|
/// seen: as `droppers::every_step_keeps_the_dropper_law` (its bands and
/// their reasons: affine relations solved to round-off; complementarity
/// solves the symmetrized problem).
const KV_LAW_ROUNDOFF: f64 = 1.0e-9;
/// See [`KV_LAW_ROUNDOFF`]: complementarity's symmetrized problem.
/// Here it is larger than without dashpots (6.6e-9, measured): within a
/// step the dropper answers with k_eff = k_d + c_d γ/(βΔt) = 21 k_d at
/// Δt = 2e-4 s, so the contact–dropper coupling whose asymmetry the law
/// averages is that much stronger; measured 7.05e-7 (lagrange and penalty
/// stay at round-off, 1.2e-16).
const KV_SYMMETRIZED_LAW: f64 = 3.0e-6;

/// c_d of every dropper in the law check, N·s/m (k_d = 1e5 N/m: τ = 2 ms);
/// the dashpot's part is then a sizeable share of the force (the test
/// asks for at least [`KV_DASHPOT_SHARE`]).
const KV_SPAN_C: f64 = 200.0;

/// The least share max|c_d ė| / max|k_d e + c_d ė| for the law check to
/// mean something about the dashpot (measured in the test's output).
const KV_DASHPOT_SHARE: f64 = 0.05;

/// Every step keeps the Kelvin–Voigt law (D12) at the force level: each
/// tension-only dropper's recorded force is max(0, k_d e + c_d ė) with
/// e = e₀ − r_dᵀ d_α and ė = −r_dᵀ v_α, d_α = (1 − α_f) d_{n+1} + α_f d_n
/// (v_α the same), read from the state, and it is recorded slack exactly
/// when k_d e + c_d ė ≤ 0. On the bundled span with every dropper damped
/// (three laws, α_f = ½) and on the span with a messenger (HHT,
/// α_f = 0.2), through slack and re-tension.
#[test]
fn every_step_keeps_the_kelvin_voigt_law() {
    let droppers = include_str!("../scenes/span_droppers.toml");
    let messenger = include_str!("../scenes/span_messenger.toml");
    let ga = "integrator={ method = \"generalized_alpha\", rho_inf = 1.0 }";
    let hht = "integrator={ method = \"hht\", alpha = 0.2 }";
    for (text, formulation, method, alpha_f, band) in [
        (droppers, "lagrange", ga, 0.5, KV_LAW_ROUNDOFF),
        (droppers, "complementarity", ga, 0.5, KV_SYMMETRIZED_LAW),
        (droppers, "penalty", ga, 0.5, KV_LAW_ROUNDOFF),
        (messenger, "lagrange", hht, 0.2, KV_LAW_ROUNDOFF),
    ] {
        let lift = if std::ptr::eq(text, messenger) {
            "0.15"
        } else {
            "0.0357"
        };
        let mut o = vec![
            format!("contact.formulation=\"{formulation}\""),
            method.to_string(),
            "time.end=0.6".to_string(),
            format!("carrier.0.preload={lift}"),
        ];
        o.extend((0..7).map(|i| format!("dropper.{i}.damping={KV_SPAN_C:e}")));
        let sc = resolve_scene(text, &o).unwrap_or_else(|e| panic!("{e}"));
        let mut it = Integrator::new(&sc).unwrap();
        let links: Vec<_> = sc
            .droppers
            .iter()
            .map(|d| {
                assert!(!d.linear && d.damping == KV_SPAN_C);
                let pv = it.beam().point_vector(d.x);
                let pm = d
                    .on_messenger()
                    .then(|| it.beam().messenger_point_vector(d.x));
                (pv, pm, d.stiffness, d.damping, d.rest_extension())
            })
            .collect();
        let mut samples = vec![taut::integrate::DropperSample::default(); links.len()];
        let (mut worst, mut scale, mut dashpot) = (0.0f64, 0.0f64, 0.0f64);
        let (mut slack_steps, mut flips) = (0usize, 0usize);
        let mut was = vec![false; links.len()];
        for _ in 0..sc.steps {
            let (d_n, v_n) = (it.state().d.clone(), it.state().v.clone());
            it.step().unwrap();
            it.dropper_samples_into(&mut samples);
            let (d1, v1) = (&it.state().d, &it.state().v);
            for (i, (pv, pm, k, c, e0)) in links.iter().enumerate() {
                let r = |x: &[f64]| pv.dot(x) - pm.as_ref().map_or(0.0, |m| m.dot(x));
                let e = e0 - ((1.0 - alpha_f) * r(d1) + alpha_f * r(&d_n));
                let rate = -((1.0 - alpha_f) * r(v1) + alpha_f * r(&v_n));
                let kv = k * e + c * rate;
                let s = samples[i];
                scale = scale.max(kv.abs());
                dashpot = dashpot.max((c * rate).abs());
                let wrong_side = if s.slack { kv.max(0.0) } else { (-kv).max(0.0) };
                worst = worst.max((s.force - kv.max(0.0)).abs()).max(wrong_side);
                slack_steps += usize::from(s.slack);
                flips += usize::from(s.slack != was[i]);
                was[i] = s.slack;
            }
        }
        println!(
            "{formulation}, α_f = {alpha_f}: worst {:.2e} of {scale:.3e} N, dashpot share {:.3}, {slack_steps} slack dropper-steps, {flips} flips",
            worst / scale,
            dashpot / scale
        );
        assert!(
            slack_steps > 0 && flips >= 2,
            "through slack and re-tension"
        );
        assert!(dashpot >= KV_DASHPOT_SHARE * scale, "{dashpot} of {scale}");
        assert!(
            worst <= band * scale,
            "{formulation}: {worst:e} N of {scale:e}"
        );
    }
}

/// A Kelvin–Voigt dropper that stays taut is the linear damped dropper
/// (D6 with the dashpot: its row's Schur complement is the elimination of
/// k_d r_d r_dᵀ and c_d r_d r_dᵀ from the step matrix); one slack from the
/// start has no dashpot either (the correction cancels spring and dashpot
/// together), so it is the beam without the dropper. Both to round-off of
/// the two eliminations over the run's steps ([`SAME_LINK`]).
#[test]
fn a_taut_kelvin_voigt_dropper_is_the_linear_one_and_a_slack_one_is_absent() {
    // preload 100 N (e₀ = 1 cm): the 20 N force never slackens it
    let taut_len = 0.49;
    let dt = 2.0e-4;
    let tension_only = common::run(&kelvin_voigt(KV_C, dt, taut_len));
    assert_eq!(tension_only.droppers[0].slack_interval_count, 0);
    let text = kelvin_voigt_text(KV_C, taut_len, true);
    let linear = go(
        &text,
        &["time.step=2e-4", "integrator={ method = \"newmark\" }"],
    );
    let (pt, pl) = (
        &tension_only.history.probes[0].1,
        &linear.history.probes[0].1,
    );
    let (ft, fl) = (
        &tension_only.history.droppers[0].1,
        &linear.history.droppers[0].1,
    );
    let (e_p, e_f) = (worst(pt, pl), worst(ft, fl));
    println!("taut Kelvin–Voigt against linear damped: probe {e_p:.2e}, force {e_f:.2e}");
    assert!(e_p < SAME_LINK && e_f < SAME_LINK, "{e_p} {e_f}");
    // slack throughout (anchor 1 cm below the unstretched end) with and
    // without the dashpot: the same run
    let slack_len = 0.51;
    let damped = common::run(&kelvin_voigt(KV_C, dt, slack_len));
    let bare = common::run(&kelvin_voigt(0.0, dt, slack_len));
    assert_eq!(damped.droppers[0].slack_fraction, 1.0);
    let e_s = worst(&damped.history.probes[0].1, &bare.history.probes[0].1);
    println!("slack Kelvin–Voigt with and without its dashpot: {e_s:.2e}");
    assert!(e_s < SAME_LINK, "{e_s}");
}
