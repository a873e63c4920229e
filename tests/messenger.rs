//! The messenger wire (docs/lines.md "Messenger wire", W1–W6):
//! a second tensioned line in the same banded model, coupled to the
//! contact wire by droppers with `anchor = "messenger"`, and the static
//! start `[time] initial = "static"`. Checked against
//!
//! * the coupled modes of two identical lines tied at every node: in-phase
//!   modes at the single line's frequencies, anti-phase modes at
//!   ω² = ω_j² + 2k/(sρA) (the exact discrete formula for strings, the
//!   continuum limit converging at second order for tensioned beams);
//! * the static start of two strings under gravity with one messenger
//!   dropper, against the superposition of point-load solutions
//!   (`analytic::StaticPointLoad`, nodally exact for string elements), and
//!   a static start that stays still;
//! * a tension-only messenger dropper that never slackens against its
//!   linear twin, to round-off (D6 for two wires);
//! * a tension-only messenger dropper going slack at the quasi-static
//!   uplift by hand, with the messenger's compliance in series;
//! * the keys' refusals.

use taut::analytic::StaticPointLoad;
use taut::model::beam::BeamModel;
use taut::model::eigen::lowest_eigenpairs;
use taut::scene::Support;
use taut::{RunOutput, resolve_scene};

use crate::common;

/// Two lines of span `l` = 10 m on `n` elements, contact wire (T, ρA, EI)
/// and messenger (`tm`, `rm`, same EI), messenger held at both ends, a
/// 10 N force parked on the left support (it loads no unknown), and
/// `extra` appended (droppers, probes, `[time]`).
fn two_wires(ei: f64, n: usize, (tm, rm): (f64, f64), extra: &str) -> String {
    format!(
        r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = {ei:e}
tension = 1000.0
left = "pinned"
right = "pinned"

[messenger]
tension = {tm:e}
mass_per_length = {rm:e}
bending_stiffness = {ei:e}
height = 1.0
supports = [0.0, 10.0]

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

const L: f64 = 10.0;
const T: f64 = 1000.0;

/// Linear messenger droppers at every interior node, k_d = κ s ρA / 2 so
/// that the anti-phase shift is 2k_d/(sρA) = κ; e₀ = 0 (no preload).
fn ties_everywhere(n: usize, kappa: f64) -> String {
    let s = L / n as f64;
    let k = 0.5 * kappa * s;
    (1..n)
        .map(|i| {
            format!(
                "[[dropper]]\nx = {:e}\nstiffness = {k:e}\nanchor = \"messenger\"\nlength = 1.0\nlinear = true\n",
                i as f64 * s
            )
        })
        .collect()
}

const TIME: &str = "[time]\nstep = 1e-3\nend = 0.01\n";

/// ω² of the model's lowest `count` modes.
fn omega_sq(text: &str, count: usize) -> Vec<f64> {
    let sc = resolve_scene(text, &[]).unwrap_or_else(|e| panic!("{e}"));
    let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
    lowest_eigenpairs(&beam.mass, &beam.stiffness, count)
        .unwrap()
        .omega_sq
}

/// The anti-phase shift 2k/(sρA), 1/s²: four times the first string
/// mode's ω₁² = (πc/L)² ≈ 98.7, so the two families interleave.
const KAPPA: f64 = 400.0;

/// Eigenvalues of the coupled strings against the exact discrete formula
/// (ω² in 1/s², compared relative to the largest): the dense symmetric
/// eigensolver's round-off, measured 1e-13.
const DISCRETE_STRINGS: f64 = 1e-10;

#[test]
fn two_strings_tied_at_every_node_have_in_and_anti_phase_modes() {
    let n = 40;
    let text = two_wires(
        0.0,
        n,
        (T, 1.0),
        &format!("{}{TIME}", ties_everywhere(n, KAPPA)),
    );
    let got = omega_sq(&text, 2 * (n - 1));
    // a string of linear elements, consistent mass: mode j is the sampled
    // sine, θ = jπ/N, K → (T/h)(2 − 2cos θ), M → ρA h (2 + cos θ)/3; the
    // anti-phase ties add 2k_d at each node: 2k_d·3/(ρA h (2 + cos θ))
    let h = L / n as f64;
    let k = 0.5 * KAPPA * h;
    let mut want: Vec<f64> = (1..n)
        .flat_map(|j| {
            let c = (j as f64 * std::f64::consts::PI / n as f64).cos();
            let m = h * (2.0 + c) / 3.0;
            let w = T / h * (2.0 - 2.0 * c) / m;
            [w, w + 2.0 * k / m]
        })
        .collect();
    want.sort_by(f64::total_cmp);
    let top = want.last().copied().unwrap();
    let worst = got
        .iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / top;
    println!("coupled strings: worst eigenvalue error {worst:.2e} of ω²_max");
    assert!(worst < DISCRETE_STRINGS, "{worst}");
    // which family is which (the eigenvalue sets alone cannot tell a tie
    // on w_c − w_m from one on w_c + w_m): the lowest mode is in phase,
    // the messenger moving with the contact wire at mid-span
    let sc = resolve_scene(&text, &[]).unwrap();
    let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
    let pairs = lowest_eigenpairs(&beam.mass, &beam.stiffness, 1).unwrap();
    let (c, m) = (
        beam.point_vector(0.5 * L).dot(pairs.shape(0)),
        beam.messenger_point_vector(0.5 * L).dot(pairs.shape(0)),
    );
    assert!((c - m).abs() < DISCRETE_STRINGS * c.abs(), "{c} {m}");
}

/// The continuum limit of the anti-phase mode j = 1 of two tensioned
/// beams (EI = 10 N·m²) tied at every node: ω² = ω₁² + κ with ω₁² the
/// pinned–pinned beam's (EI k⁴ + T k²)/ρA, k = π/L. The nodal ties are the
/// trapezoidal rule of the distributed spring's ∫κ v w dx, spectrally
/// accurate on the sine modes, so what remains is the Hermite elements'
/// eigenvalue error (O(h⁴) for bending, O(h⁶) for tension): measured
/// relative errors 1.16e-5, 1.75e-7, 9.4e-10 at N = 20, 40, 80 (orders
/// 6.1, 7.5). The test asks order ≥ 4 (the bending term's asymptotic
/// rate) and the finest error below 1e-8. The in-phase modes equal the
/// single beam's FE modes (the messenger moves with the contact wire, the
/// ties unstretched): measured 1e-12, band as the strings'.
const TIE_ORDER_MIN: f64 = 4.0;
const TIE_FINEST: f64 = 1e-8;

#[test]
fn two_tensioned_beams_converge_to_the_continuum_anti_phase_shift() {
    let ei = 10.0;
    let k1 = std::f64::consts::PI / L;
    let exact = ei * k1.powi(4) + T * k1 * k1 + KAPPA;
    let mut errs = Vec::new();
    for n in [20, 40, 80] {
        let text = two_wires(
            ei,
            n,
            (T, 1.0),
            &format!("{}{TIME}", ties_everywhere(n, KAPPA)),
        );
        let got = omega_sq(&text, 6);
        // the single beam, same mesh
        let single = r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 10.0
tension = 1000.0
left = "pinned"
right = "pinned"

[[carrier]]
force = 10.0
side = "below"
start = 0.0
speed = { profile = "constant", value = 0.0 }

[time]
step = 1e-3
end = 0.01
"#;
        let one = omega_sq(&format!("{single}\n[mesh]\nelements = {n}\n"), 6);
        // in-phase modes 1..3 are the single beam's
        let in_phase = |g: f64| one.iter().any(|w| (g - w).abs() / w < DISCRETE_STRINGS);
        for w in &one[..3] {
            assert!(
                got.iter().any(|&g| (g - w).abs() / w < DISCRETE_STRINGS),
                "in-phase {w}"
            );
        }
        // the anti-phase j = 1: the lowest eigenvalue that is not in-phase
        let anti = got.iter().copied().find(|&g| !in_phase(g)).unwrap();
        errs.push((anti - exact).abs() / exact);
    }
    let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("anti-phase j=1 errors {errs:?}, orders {orders:.3?}");
    assert!(orders.iter().all(|&p| p >= TIE_ORDER_MIN), "{orders:?}");
    assert!(errs[2] < TIE_FINEST, "{errs:?}");
}

/// Two strings under their weight (p_c = −9.81, p_m = −4.905 N/m) with one
/// tension-only messenger dropper at x_d = 4 m (k = 1e4 N/m, e₀ = 2 mm),
/// started static; probes on both lines.
fn static_strings(extra_time: &str) -> String {
    two_wires(
        0.0,
        50,
        (800.0, 0.5),
        &format!(
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

[[probe]]
name = "c2"
x = 2.0

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
name = "m7"
x = 7.0
wire = "messenger"

[time]
step = 1e-3
{extra_time}
initial = "static"
"#
        ),
    )
}

/// The static start against the closed form (relative to the largest
/// displacement or force): string elements with consistent loads are
/// nodally exact for point and uniform loads, so only the banded solve's
/// round-off remains (measured 1e-15).
const STATIC_EXACT: f64 = 1e-11;

#[test]
fn the_static_start_is_the_superposed_point_load_solution() {
    let out = go(&static_strings("end = 0.001"));
    let (xd, k, e0, g) = (4.0, 1.0e4, 0.002, 9.81);
    let (pc, pm, tm) = (-g, -0.5 * g, 800.0);
    let gc = StaticPointLoad::new(0.0, T, L, Support::Pinned, Support::Pinned).unwrap();
    let gm = StaticPointLoad::new(0.0, tm, L, Support::Pinned, Support::Pinned).unwrap();
    let uniform = |p: f64, t: f64, x: f64| p * x * (L - x) / (2.0 * t);
    // N = k (e₀ + v_m(x_d) − v_c(x_d)), v_c = u_c + N G_c, v_m = u_m − N G_m
    let n = k * (e0 + uniform(pm, tm, xd) - uniform(pc, T, xd))
        / (1.0 + k * (gc.compliance(xd) + gm.compliance(xd)));
    let vc = |x: f64| uniform(pc, T, x) + n * gc.deflection(xd, x);
    let vm = |x: f64| uniform(pm, tm, x) - n * gm.deflection(xd, x);
    let want = [vc(2.0), vc(4.0), vc(7.0), vm(4.0), vm(7.0)];
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
}

/// A static start at rest stays there (its initial accelerations are
/// zero): the drift of every probe over 200 steps relative to the largest
/// static displacement, round-off of the static solve's residual
/// (condition of K times ε), measured 1e-13.
const STILL: f64 = 1e-10;

#[test]
fn a_static_start_stays_still() {
    let out = go(&static_strings("end = 0.2"));
    let scale = out
        .history
        .probes
        .iter()
        .map(|(_, c)| c[0].abs())
        .fold(0.0, f64::max);
    let drift = out
        .history
        .probes
        .iter()
        .flat_map(|(_, c)| c.iter().map(move |v| (v - c[0]).abs()))
        .fold(0.0, f64::max)
        / scale;
    println!("static start: drift {drift:.2e} of the largest displacement");
    assert!(drift < STILL, "{drift}");
    // the rest start of the same scene moves (the check can fail)
    let rest = go(&static_strings("end = 0.2").replace("initial = \"static\"", ""));
    let moved = rest.history.probes[0].1.last().unwrap().abs();
    assert!(moved > 1e3 * STILL * scale, "{moved}");
}

fn go(text: &str) -> RunOutput {
    let sc = resolve_scene(text, &[]).unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

/// The quasi-static lift with a messenger: two tensioned beams (EI = 1
/// N·m²; contact T = 1000 N, ρA = 1; messenger T_m = 800 N, ρA_m = 0.5),
/// no gravity, one messenger dropper at x_d = 6 m (k = 1e4 N/m, e₀ = 24
/// mm), started static (so it carries N0 < k e₀, the lines' compliance in
/// series), and a 20 N force pushing the contact wire up, moving in from
/// x = 0 at 0.2 m/s (smooth start). `extra` is added to the dropper.
fn lift(dt: f64, end: f64, force: f64, extra: &str) -> String {
    two_wires(
        1.0,
        100,
        (800.0, 0.5),
        &format!(
            r#"
[gravity]
g = 0.0

[[dropper]]
x = 6.0
stiffness = 1.0e4
anchor = "messenger"
length = 0.976
{extra}

[[probe]]
name = "c5"
x = 5.0

[[probe]]
name = "m5"
x = 5.0
wire = "messenger"

[time]
step = {dt:e}
end = {end:e}
initial = "static"
"#
        ),
    )
    .replace(
        "force = 10.0\nside = \"below\"\nstart = 0.0\nspeed = { profile = \"constant\", value = 0.0 }",
        &format!("force = {force:e}\nside = \"below\"\nstart = 0.0\nspeed = {{ profile = \"smooth_ramp\", cruise = 0.2 }}"),
    )
}

const XD: f64 = 6.0;

/// x_m at which the dropper goes slack, by hand: with compliances G_c,
/// G_m of the two beams, the static force is N0 = k e₀/(1 + k(G_c,dd +
/// G_m,dd)); the force F at x_m changes it by ΔN with ΔN (1/k + G_c,dd +
/// G_m,dd) = −F G_c(x_d, x_m) (both lines' compliance in series with the
/// dropper's), so N = 0 where F G_c(x_d, x_m) = N0 (1/k + G_c,dd + G_m,dd).
fn onset_by_hand() -> (f64, f64) {
    let (k, e0, f) = (1.0e4, 2.4e-2, 20.0);
    let gc = StaticPointLoad::new(1.0, T, L, Support::Pinned, Support::Pinned).unwrap();
    let gm = StaticPointLoad::new(1.0, 800.0, L, Support::Pinned, Support::Pinned).unwrap();
    let series = 1.0 / k + gc.compliance(XD) + gm.compliance(XD);
    let n0 = e0 / series;
    let target = n0 * series;
    let g = |x: f64| f * gc.deflection(x, XD) - target;
    let (mut lo, mut hi) = (0.0, XD);
    assert!(g(lo) < 0.0 && g(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi), n0)
}

/// As tests/droppers.rs: the onset is read at the end of the first slack
/// step, known to one step of travel V0 Δt = 4e-4 m (6.7e-5 of x_d); the
/// band is three steps of travel. The static force N0 is exact up to the
/// Hermite discretization of the two beams' compliances (N = 100, the
/// bending length sqrt(EI/T) = 3.2 cm unresolved by h = 10 cm): measured
/// 2.0e-4 relative; the band 1e-3.
const ONSET: f64 = 3.0 * 0.2 * 2e-3 / XD;
const STATIC_FORCE: f64 = 1e-3;

#[test]
fn a_messenger_dropper_goes_slack_at_the_uplift_by_hand() {
    let out = go(&lift(2e-3, 32.0, 20.0, ""));
    let d = &out.droppers[0];
    assert!(d.slack_interval_count >= 1, "{d:?}");
    let t0 = d.slack_intervals_time[0][0];
    let i = out.history.t.iter().position(|&t| t > t0).unwrap();
    let x = out.history.carriers[0].x[i];
    let (x_hand, n0) = onset_by_hand();
    let err = (x - x_hand).abs() / XD;
    let f0 = out.history.droppers[0].1[0];
    println!(
        "messenger dropper slack at x_m = {x:.5} m, by hand {x_hand:.5} m ({err:.2e} of x_d); N0 {f0:.6} N, by hand {n0:.6} N"
    );
    assert!(err < ONSET, "{x} vs {x_hand}");
    assert!((f0 - n0).abs() / n0 < STATIC_FORCE, "{f0} vs {n0}");
    // the messenger moved: the dropper's pull on it is released at the onset
    let m5 = &out.history.probes[1].1;
    assert!(m5[0] < 0.0 && m5[i] > m5[0], "{} {}", m5[0], m5[i]);
}

/// A tension-only messenger dropper that stays stretched and its linear
/// twin (a tie plus preload) are the same step, as for fixed anchors
/// (tests/droppers.rs LINEAR_TWIN: round-off of two eliminations, grown
/// over the run's steps; the tension-only force read at t_{n+1−α_f}).
const LINEAR_TWIN: f64 = 1.0e-11;

#[test]
fn a_messenger_dropper_that_never_slackens_is_the_linear_one() {
    let text = lift(2e-3, 6.0, 0.2, "");
    let uni = go(&text);
    let lin = go(&lift(2e-3, 6.0, 0.2, "linear = true"));
    assert_eq!(uni.droppers[0].slack_interval_count, 0);
    let (a, b) = (&uni.history.droppers[0].1, &lin.history.droppers[0].1);
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = (1..a.len())
        .map(|i| (a[i] - 0.5 * (b[i] + b[i - 1])).abs())
        .fold(0.0, f64::max)
        / scale;
    let mut wworst = 0.0f64;
    for p in 0..2 {
        let (wa, wb) = (&uni.history.probes[p].1, &lin.history.probes[p].1);
        let s = wb.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let e = wa
            .iter()
            .zip(wb)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        wworst = wworst.max(e / s);
    }
    println!("messenger: tension-only vs linear: force {worst:.2e}, displacement {wworst:.2e}");
    assert!(
        worst < LINEAR_TWIN && wworst < LINEAR_TWIN,
        "{worst} {wworst}"
    );
}

#[test]
fn messenger_keys_are_checked() {
    let ok = two_wires(1.0, 20, (800.0, 0.5), TIME);
    resolve_scene(&ok, &[]).unwrap();
    let fails = |text: &str, set: &[&str], what: &[&str]| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let e = resolve_scene(text, &set).unwrap_err().to_string();
        for w in what {
            assert!(e.contains(w), "{e:?} lacks {w:?}");
        }
    };
    fails(
        &ok,
        &["messenger.bending_stiffness=0.0"],
        &["messenger.bending_stiffness", "Hermite"],
    );
    fails(
        &ok,
        &["messenger.tension=-1.0"],
        &["messenger.tension", "> 0"],
    );
    fails(
        &ok,
        &["messenger.supports=[0.0, 5.1]"],
        &["messenger.supports.1", "node 10"],
    );
    fails(
        &ok,
        &["messenger.supports=[5.0, 2.0]"],
        &["messenger.supports.1", "increasing"],
    );
    fails(
        &ok,
        &["messenger.supports=[5.0]"],
        &["messenger.supports", "at least two"],
    );
    fails(&ok, &["messenger.colour=1"], &["colour"]);
    fails(
        &ok,
        &["mesh.kind=\"galerkin\"", "mesh.modes=5"],
        &["mesh.kind", "messenger"],
    );
    // a modal basis is taken from the two-line model: its unknowns bound J
    let n = resolve_scene(&ok, &[]).unwrap().beam_unknowns();
    resolve_scene(
        &ok,
        &["mesh.kind=\"modal\"".into(), format!("mesh.modes={n}")],
    )
    .unwrap();
    fails(
        &ok,
        &["mesh.kind=\"modal\"", &format!("mesh.modes={}", n + 1)],
        &["mesh.modes", &format!("1 ..= {n}")],
    );
    let dropper =
        "[[dropper]]\nx = 5.0\nstiffness = 1.0e4\nanchor = \"messenger\"\nlength = 0.999\n";
    fails(
        &format!("{ok}{dropper}anchor_height = 1.0\n"),
        &[],
        &["dropper.0.anchor_height", "exactly one"],
    );
    // a dropper that would hang slack at the static start: refused when
    // the run is built
    let slack = format!(
        "{ok}{}\n[gravity]\ng = 0.0\n",
        dropper.replace("0.999", "1.5")
    );
    let sc = resolve_scene(&slack, &["time.initial=\"static\"".to_string()]).unwrap();
    let e = taut::integrate::Integrator::new(&sc)
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("dropper.0") && e.contains("taut"), "{e}");
    fails(
        &format!("{ok}[[probe]]\nname = \"p\"\nx = 1.0\nwire = \"other\"\n"),
        &[],
        &["wire"],
    );
}

#[test]
fn a_messenger_anchor_needs_a_messenger() {
    let text = r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 1.0
tension = 1000.0
left = "pinned"
right = "pinned"

[mesh]
elements = 20

[[carrier]]
force = 10.0
side = "below"
start = 0.0
speed = { profile = "constant", value = 0.0 }

[time]
step = 1e-3
end = 0.01

[[dropper]]
x = 5.0
stiffness = 1.0e4
anchor = "messenger"
length = 0.999
"#;
    let e = resolve_scene(text, &[]).unwrap_err().to_string();
    assert!(
        e.contains("dropper.0.anchor") && e.contains("[messenger]"),
        "{e}"
    );
    let probe = text.replace(
        "[[dropper]]\nx = 5.0\nstiffness = 1.0e4\nanchor = \"messenger\"\nlength = 0.999\n",
        "[[probe]]\nname = \"p\"\nx = 1.0\nwire = \"messenger\"\n",
    );
    let e = resolve_scene(&probe, &[]).unwrap_err().to_string();
    assert!(
        e.contains("probe.0.wire") && e.contains("[messenger]"),
        "{e}"
    );
}

/// Central difference on two lines is held to 2/ω_max of the assembled
/// two-line model: with stiff messenger droppers (ties) and a light, taut
/// messenger, the model's ω_max is far above the contact wire's element
/// bound, and the element bound the run is held to
/// (`BeamModel::omega_bound`: each line's elements with every tie as a
/// grounded spring of 2k_d on both lines) must stay above it.
#[test]
fn central_difference_bound_covers_the_messenger_and_its_ties() {
    for (ties, tm, rm) in [
        (ties_everywhere(20, 1.0e7), 800.0, 0.5),
        (ties_everywhere(20, 10.0), 4.0e5, 0.05),
    ] {
        let text = two_wires(1.0, 20, (tm, rm), &format!("{ties}{TIME}"));
        let sc = resolve_scene(&text, &["integrator.method=\"central_difference\"".into()])
            .unwrap_or_else(|e| panic!("{e}"));
        let beam = BeamModel::build(&sc.beam, &sc.mesh_plan()).unwrap();
        let all = lowest_eigenpairs(&beam.mass, &beam.stiffness, beam.n).unwrap();
        let w_true = all.omega_sq.last().unwrap().sqrt();
        let wire =
            taut::model::element::omega_max(sc.beam.rho_a, sc.beam.ei, sc.beam.tension, beam.h);
        let limit = taut::integrate::central_difference_limit(&sc).unwrap();
        println!(
            "two lines: ω_max {w_true:.4e} rad/s, the contact wire's element bound {wire:.4e}, the two-line element bound {:.4e}, held to {:.4e}",
            limit.omega_element_bound, limit.omega_max
        );
        assert!(
            w_true > 1.5 * wire,
            "the ties or the messenger should dominate"
        );
        assert!(
            limit.omega_element_bound >= w_true * (1.0 - 1e-12),
            "element bound {} below ω_max {w_true}",
            limit.omega_element_bound
        );
        assert!(limit.dt_max <= 2.0 / w_true * (1.0 + 1e-9));
    }
}
