//! Droppers (MODEL §10; docs/lines.md "Droppers", D1–D10):
//! tension-only links to fixed anchors, solved as rows of the step's
//! contact problem while slack, checked against
//!
//! * the static uplift at which a dropper goes slack, by hand: a
//!   pinned–pinned tensioned beam with one pre-tensioned dropper and a
//!   point force moving slowly (quasi-statically) toward it, against the
//!   superposition of point-load solutions (`analytic::StaticPointLoad`);
//! * linear droppers: a tension-only dropper that never goes slack is the
//!   same step as a linear one (an attachment spring and its preload), to
//!   round-off;
//! * loss and re-tension in Δt: slack-interval start times and a
//!   dropper's force at a fixed time converge as Δt halves;
//! * the formulations: Lagrange, complementarity and penalty (as κ grows)
//!   give the same slack intervals;
//! * the law D3 read back from the state at every step, through the slack
//!   corrections that solve it (D7–D10: springs in the factored matrix, a
//!   row only for a slack dropper);
//! * the scene keys and their refusals.

use taut::analytic::StaticPointLoad;
use taut::record::DropperStats;
use taut::scene::Support;
use taut::{RunOutput, resolve_scene};

use crate::common;

/// A quasi-static lift: a 10 m pinned–pinned tensioned beam (c = 31.6 m/s,
/// bending length sqrt(EI/T) = 3.2 cm), one dropper at x_d = 6 m
/// pre-tensioned by N0 = k_d e₀ = 10 N and balanced at t = 0 by a 10 N
/// stationary force down at x_d (so the straight beam starts at rest in
/// equilibrium), and a 20 N force pushing up that moves in from x = 0 at
/// V0 = 0.2 m/s (smooth start). `extra` is added to the scene.
fn lift_scene(dt: f64, extra: &str) -> String {
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
speed = {{ profile = "smooth_ramp", cruise = 0.2 }}

[[carrier]]
force = 10.0
side = "above"
start = 6.0
speed = {{ profile = "constant", value = 0.0 }}

[time]
step = {dt:e}
end = 32.0

[gravity]
g = 0.0

[[dropper]]
x = 6.0
stiffness = 1.0e4
anchor_height = 0.5
length = 0.499
{extra}
"#
    )
}

const LIFT_L: f64 = 10.0;
const LIFT_T: f64 = 1000.0;
const LIFT_EI: f64 = 1.0;
const LIFT_XD: f64 = 6.0;
const LIFT_K: f64 = 1.0e4;
const LIFT_N0: f64 = 10.0;
const LIFT_F: f64 = 20.0;

fn go(text: &str) -> RunOutput {
    let sc = resolve_scene(text, &[]).unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

fn lift_onset_by_hand() -> f64 {
    // With the force F at x_m < x_d and the dropper stretched, the beam at
    // x_d carries F up at x_m, N0 down and N up at x_d (superposition of
    // point loads, G the static point-load solution): v_d = F G(x_d, x_m) +
    // (N − N0) G_dd with N = k(e₀ − v_d), e₀ = N0/k. N reaches 0 where
    // v_d = e₀, i.e. F G(x_d, x_m) = N0 (1/k + G_dd).
    let g =
        StaticPointLoad::new(LIFT_EI, LIFT_T, LIFT_L, Support::Pinned, Support::Pinned).unwrap();
    let target = LIFT_N0 * (1.0 / LIFT_K + g.compliance(LIFT_XD));
    let f = |x: f64| LIFT_F * g.deflection(x, LIFT_XD) - target;
    let (mut lo, mut hi) = (0.0, LIFT_XD);
    assert!(f(lo) < 0.0 && f(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The carrier's position when the dropper first went slack: x_m at the
/// end of the first slack step.
fn first_slack_position(out: &RunOutput, d: &DropperStats) -> f64 {
    let t0 = d.slack_intervals_time[0][0];
    let i = out
        .history
        .t
        .iter()
        .position(|&t| t > t0)
        .expect("a row after the slack start");
    out.history.carriers[0].x[i]
}

/// The quasi-static onset's tolerance, as a fraction of x_d: the onset is
/// read at the end of the first slack step, so it is known to one step of
/// carrier travel, V0 Δt = 4e-4 m = 6.7e-5 of x_d; measured 7.3e-5 of x_d
/// (the dynamics at V0/c = 6.3e-3 add little). The band is three steps of
/// travel.
const QUASI_STATIC_ONSET: f64 = 3.0 * 0.2 * 2e-3 / LIFT_XD;

#[test]
fn a_dropper_goes_slack_at_the_static_uplift_by_hand() {
    let out = go(&lift_scene(2e-3, ""));
    let d = &out.droppers[0];
    assert!(d.slack_interval_count >= 1, "{d:?}");
    let x = first_slack_position(&out, d);
    let x_hand = lift_onset_by_hand();
    let err = (x - x_hand).abs() / LIFT_XD;
    println!("slack onset x_m = {x:.5} m, by hand {x_hand:.5} m, error {err:.2e} of x_d");
    assert!(err < QUASI_STATIC_ONSET, "{x} vs {x_hand}");
    // before the onset the dropper carries N = N0 − k v_d > 0, after it 0
    let f = &out.history.droppers[0].1;
    assert!((f[0] - LIFT_N0).abs() < 1e-12, "{}", f[0]);
    let last = *f.last().unwrap();
    assert_eq!(last, 0.0, "slack while the force lifts beyond x_d");
}

/// A tension-only dropper that never slackens and a linear one are the
/// same step (docs/lines.md D6: imposed at the force level, where the
/// method's K acts): the two runs differ by the round-off of two
/// eliminations of one linear system, the Schur complement on the
/// dropper's row and the factor with k_d r_d r_dᵀ in it. Measured 1.1e-14
/// of the largest displacement; the band allows round-off growth over the
/// run's 3000 steps. The linear dropper's force is recorded at the step's
/// end, the tension-only one's at the force level t_{n+1−α_f}: with
/// α_f = ½ the latter is the mean of the former at t_n and t_{n+1}.
const LINEAR_TWIN: f64 = 1.0e-11;

#[test]
fn a_dropper_that_never_slackens_is_the_linear_dropper() {
    // no moving force: the dropper stays stretched (pre-tension 10 N plus the
    // static force's pull, never below 10 N)
    let base = lift_scene(2e-3, "").replace("force = 20.0", "force = 2.0");
    let short = base.replace("end = 32.0", "end = 6.0");
    let uni = go(&short);
    let lin = go(&format!("{short}linear = true\n"));
    assert_eq!(uni.droppers[0].slack_interval_count, 0);
    let (a, b) = (&uni.history.droppers[0].1, &lin.history.droppers[0].1);
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = (1..a.len())
        .map(|i| (a[i] - 0.5 * (b[i] + b[i - 1])).abs())
        .fold(0.0, f64::max)
        / scale;
    let wa = &uni.history.carriers[0].w;
    let wb = &lin.history.carriers[0].w;
    let wscale = wb.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let wworst = wa
        .iter()
        .zip(wb)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / wscale;
    println!("unilateral vs linear: force {worst:.2e}, displacement {wworst:.2e}");
    assert!(
        worst < LINEAR_TWIN && wworst < LINEAR_TWIN,
        "{worst} {wworst}"
    );
}

/// The bundled span, cut to its first 0.4 s (the pantograph passes the
/// first two droppers), at step `dt`, with `extra` overrides.
fn span(dt: f64, extra: &[&str]) -> RunOutput {
    let mut o = vec![format!("time.step={dt:e}"), "time.end=0.4".to_string()];
    o.extend(extra.iter().map(|s| s.to_string()));
    let refs: Vec<&str> = o.iter().map(String::as_str).collect();
    common::run(&common::scene("span_droppers.toml", &refs))
}

/// The lift scene made dynamic: the force moves in at V0 = 2 m/s
/// (V0/c = 0.063) and on past the dropper, which goes slack and
/// re-tensions behind it; no contact, so Δt alone sets the error.
fn dynamic_lift(dt: f64, formulation: &str) -> RunOutput {
    let text = lift_scene(dt, "")
        .replace("cruise = 0.2", "cruise = 2.0")
        .replace("end = 32.0", "end = 5.5");
    let sc = resolve_scene(&text, &[format!("contact.formulation=\"{formulation}\"")])
        .unwrap_or_else(|e| panic!("{e}"));
    common::run(&sc)
}

/// Where Δt dominates: the span's first 0.4 s at Δt = 4e-4 … 5e-5 s (the
/// coarsest 2 % of the pantograph's passage of a 7.5 m bay). The first
/// dropper's first slack start converges at measured orders 2.26, 1.74;
/// an event time is read from the step grid, so the band asks first order
/// (0.8 allows pre-asymptotic scatter). Its re-tension times land on the
/// grid (0.3004, 0.3008, 0.3010, 0.3010 s): they must agree to two of the
/// coarsest steps. (The coarsest step merges a short slack–re-tension–slack
/// sequence at 0.235–0.239 s into one interval: it is resolved from
/// Δt = 2e-4 s on.)
const EVENT_ORDER_MIN: f64 = 0.8;

#[test]
fn slack_and_re_tension_converge_in_dt() {
    let dts = [4e-4, 2e-4, 1e-4, 5e-5];
    let runs: Vec<RunOutput> = dts.iter().map(|&dt| span(dt, &[])).collect();
    let starts: Vec<f64> = runs
        .iter()
        .map(|o| o.droppers[0].slack_intervals_time[0][0])
        .collect();
    let ends: Vec<f64> = runs
        .iter()
        .map(|o| o.droppers[0].slack_intervals_time.last().unwrap()[1])
        .collect();
    let order = |v: &[f64]| -> Vec<f64> {
        (0..v.len() - 2)
            .map(|i| ((v[i] - v[i + 1]) / (v[i + 1] - v[i + 2])).abs().log2())
            .collect()
    };
    let os = order(&starts);
    println!("slack starts {starts:?} orders {os:?}");
    println!("re-tension {ends:?}");
    assert!(os.iter().all(|&p| p > EVENT_ORDER_MIN), "{os:?}");
    for e in &ends {
        assert!(
            (e - ends[3]).abs() <= 2.0 * dts[0] * (1.0 + 1e-9),
            "{ends:?}"
        );
    }
}

/// Complementarity (its default direct pivoting) and penalty against
/// Lagrange on the dynamic lift (droppers only): one problem, solved
/// exactly by each, so the dropper forces agree to the round-off of
/// different eliminations (relative to the largest force). Penalty leaves
/// the dropper rows alone (a dropper is its own penalty spring), so this
/// holds whatever κ: a penalty that softened them by 1/κ would be off by
/// 1/(1 + ρ) ≈ 9 % at ρ = 10.
const FORMULATION_ROUNDOFF: f64 = 1.0e-9;

/// On the span (first 0.4 s) the same slack steps: measured identical
/// slack fractions for complementarity and for penalty at ρ = 10, 100,
/// 1000, whose contact converges to Lagrange's as κ grows.
const SLACK_FRACTION_AGREE: f64 = 0.0;

#[test]
fn formulations_agree_on_slack_intervals() {
    let force_diff = |p: &RunOutput, q: &RunOutput| -> f64 {
        let mut scale = 0.0f64;
        let mut worst = 0.0f64;
        for ((_, x), (_, y)) in p.history.droppers.iter().zip(&q.history.droppers) {
            for (u, v) in x.iter().zip(y) {
                scale = scale.max(v.abs());
                worst = worst.max((u - v).abs());
            }
        }
        worst / scale
    };
    let lagrange = dynamic_lift(2e-3, "lagrange");
    assert!(lagrange.droppers[0].slack_interval_count >= 1);
    let comp = dynamic_lift(2e-3, "complementarity");
    let text = lift_scene(2e-3, "")
        .replace("cruise = 0.2", "cruise = 2.0")
        .replace("end = 32.0", "end = 5.5");
    let pen = common::run(
        &resolve_scene(
            &text,
            &[
                "contact.formulation=\"penalty\"".to_string(),
                "contact.penalty.relative=10.0".to_string(),
            ],
        )
        .unwrap(),
    );
    let (fc, fp) = (force_diff(&comp, &lagrange), force_diff(&pen, &lagrange));
    println!("dropper forces against lagrange: complementarity {fc:.2e}, penalty {fp:.2e}");
    assert!(
        fc < FORMULATION_ROUNDOFF && fp < FORMULATION_ROUNDOFF,
        "{fc} {fp}"
    );

    let fr = |o: &RunOutput| -> Vec<f64> { o.droppers.iter().map(|d| d.slack_fraction).collect() };
    let a = fr(&span(2e-4, &[]));
    assert!(a.iter().any(|&f| f > 0.0), "some dropper slackens");
    let mut others = vec![(
        "complementarity".to_string(),
        fr(&span(2e-4, &["contact.formulation=\"complementarity\""])),
    )];
    for rel in [1e1, 1e2, 1e3] {
        let o = span(
            2e-4,
            &[
                "contact.formulation=\"penalty\"",
                &format!("contact.penalty.relative={rel:e}"),
            ],
        );
        others.push((format!("penalty ρ = {rel:e}"), fr(&o)));
    }
    println!("lagrange {a:?}");
    for (name, b) in &others {
        println!("{name} {b:?}");
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= SLACK_FRACTION_AGREE, "{name}: {a:?} {b:?}");
        }
    }
}

/// D3 checked from the state alone, in units of the largest force k_d|e|
/// seen: the run's forces come from affine relations solved to round-off
/// (the dense rows' solve and the banded one), 1e-9 of the scale leaves
/// room for the line's conditioning (k_d = 1e5 N/m against W ≈ 1e-7 m/N)
/// while a dropper that pushed, or one left slack while stretched, is off
/// by its own force (≥ 1e-3 of the scale on these runs).
const LAW_ROUNDOFF: f64 = 1.0e-9;

/// The complementarity law solves the symmetric part of W
/// (docs/formulations.md "Complementarity"): at the `end` placement a
/// contact's row reads a dropper with c_d and the dropper's row the
/// contact with (1 − α_f)c_d (D5), so near a dropper its forces are off
/// the exact law by the mean it takes; measured 6.6e-9 of the scale on
/// the span (α_f = 0.5), the same early departure from Lagrange as the
/// build that made every dropper a row (4e-8 by 0.2 s, both builds).
const SYMMETRIZED_LAW: f64 = 1.0e-7;

/// Every step keeps the dropper law (D3) at the force level: each
/// tension-only dropper's recorded force is k_d max(e_d, 0) with e_d =
/// e₀ − r_dᵀ((1 − α_f) d_{n+1} + α_f d_n) read from the state, and it is
/// recorded slack exactly when e_d ≤ 0 (to round-off). This is what the
/// slack corrections (D7–D10) must deliver whichever droppers get rows:
/// a taut dropper left without a row that pushes, or a slack one whose
/// correction is wrong, breaks it. On the bundled span (fixed anchors:
/// three laws) and the span with a messenger (HHT, α_f = 0.2, a
/// pantograph pushing harder), first 0.6 s, through slack and re-tension.
#[test]
fn every_step_keeps_the_dropper_law() {
    let droppers = include_str!("../scenes/span_droppers.toml");
    let messenger = include_str!("../scenes/span_messenger.toml");
    let ga = "integrator={ method = \"generalized_alpha\", rho_inf = 1.0 }";
    let hht = "integrator={ method = \"hht\", alpha = 0.2 }";
    for (text, formulation, method, alpha_f, band) in [
        (droppers, "lagrange", ga, 0.5, LAW_ROUNDOFF),
        (droppers, "complementarity", ga, 0.5, SYMMETRIZED_LAW),
        (droppers, "penalty", ga, 0.5, LAW_ROUNDOFF),
        (messenger, "lagrange", hht, 0.2, LAW_ROUNDOFF),
    ] {
        // the messenger span's droppers slacken under a pantograph pushing
        // with 530 N (preload 0.15 m) instead of 100 N
        let lift = if std::ptr::eq(text, messenger) {
            "0.15"
        } else {
            "0.0357"
        };
        let o = [
            format!("contact.formulation=\"{formulation}\""),
            method.to_string(),
            "time.end=0.6".to_string(),
            format!("carrier.0.preload={lift}"),
        ];
        let sc = resolve_scene(text, &o).unwrap();
        let mut it = taut::integrate::Integrator::new(&sc).unwrap();
        let links: Vec<_> = sc
            .droppers
            .iter()
            .enumerate()
            .filter(|(_, d)| !d.linear)
            .map(|(i, d)| {
                let pv = it.beam().point_vector(d.x);
                let pm = d
                    .on_messenger()
                    .then(|| it.beam().messenger_point_vector(d.x));
                (i, pv, pm, d.stiffness, d.rest_extension())
            })
            .collect();
        assert!(!links.is_empty());
        let mut samples = vec![taut::integrate::DropperSample::default(); sc.droppers.len()];
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        let (mut slack_steps, mut flips) = (0usize, 0usize);
        let mut was = vec![false; sc.droppers.len()];
        for _ in 0..sc.steps {
            let d_n = it.beam_dofs().to_vec();
            it.step().unwrap();
            it.dropper_samples_into(&mut samples);
            let d1 = it.beam_dofs();
            for (i, pv, pm, k, e0) in &links {
                let r = |x: &[f64]| pv.dot(x) - pm.as_ref().map_or(0.0, |m| m.dot(x));
                let e = e0 - ((1.0 - alpha_f) * r(d1) + alpha_f * r(&d_n));
                let expect = k * e.max(0.0);
                let s = samples[*i];
                scale = scale.max((k * e).abs());
                // a slack dropper has e ≤ 0, a taut one e ≥ 0 (to round-off)
                let wrong_side = if s.slack {
                    (k * e).max(0.0)
                } else {
                    (-k * e).max(0.0)
                };
                worst = worst.max((s.force - expect).abs()).max(wrong_side);
                slack_steps += usize::from(s.slack);
                flips += usize::from(s.slack != was[*i]);
                was[*i] = s.slack;
            }
        }
        println!(
            "{formulation}, α_f = {alpha_f}: worst {:.2e} of {scale:.3e} N, {slack_steps} slack dropper-steps, {flips} flips",
            worst / scale
        );
        assert!(
            slack_steps > 0 && flips >= 2,
            "through slack and re-tension"
        );
        assert!(
            worst <= band * scale,
            "{formulation}: {worst:e} N of {scale:e}"
        );
    }
}

#[test]
fn dropper_keys_are_checked() {
    let base = lift_scene(2e-3, "");
    let refused = |extra: &str, field: &str| {
        let e = resolve_scene(&format!("{base}{extra}\n"), &[])
            .err()
            .unwrap_or_else(|| panic!("{extra} should be refused"))
            .to_string();
        assert!(e.contains(field), "{extra}: {e}");
    };
    refused("damping = nan", "dropper.0.damping");
    refused("damping = -3.0", "dropper.0.damping");
    refused("colour = 3.0", "colour");
    refused("name = \"a b\"", "dropper.0.name");
    let bad = |from: &str, to: &str, field: &str| {
        let e = resolve_scene(&base.replace(from, to), &[])
            .err()
            .unwrap_or_else(|| panic!("{to} should be refused"))
            .to_string();
        assert!(e.contains(field), "{to}: {e}");
    };
    bad(
        "stiffness = 1.0e4",
        "stiffness = 0.0",
        "dropper.0.stiffness",
    );
    bad("x = 6.0\nstiffness", "x = 11.0\nstiffness", "dropper.0.x");
    bad("length = 0.499", "length = -1.0", "dropper.0.length");
    // a dropper's combinations
    let with = |o: &str| resolve_scene(&base, &[o.to_string()]);
    for (o, field) in [
        ("contact.kind=\"bilateral\"", "contact.kind"),
        ("contact.formulation=\"impact\"", "contact.formulation"),
        ("mesh.kind=\"galerkin\"", "mesh.kind"),
    ] {
        let e = with(o).err().unwrap_or_else(|| panic!("{o}")).to_string();
        assert!(e.contains(field), "{o}: {e}");
    }
    // a method that cannot form the responses once is refused when built
    let sc = resolve_scene(&base, &["integrator={ method = \"bathe\" }".to_string()]).unwrap();
    let e = taut::run(&sc, &mut |_, _| {}).err().unwrap().to_string();
    assert!(
        e.contains("integrator.method") && e.contains("droppers"),
        "{e}"
    );
    // linear droppers go everywhere attachments go
    let sc = resolve_scene(
        &format!("{base}linear = true\n"),
        &["integrator={ method = \"bathe\" }".to_string()],
    )
    .unwrap();
    assert!(taut::run(&sc, &mut |_, _| {}).is_ok());
}

/// A tension-only dropper that hangs slack for the whole run carries no
/// force, so with stiffness-proportional Rayleigh damping (βK) the run
/// equals the run without it to round-off: the dropper's spring sits in
/// the step matrix (D7) but not in C = αM + βK (its slack correction
/// cancels only the spring; a β k_d r_d r_dᵀ dashpot in C would act on a
/// slack dropper). Round-off of the correction over 1000 steps, relative
/// to the largest displacement.
const SLACK_IS_ABSENT: f64 = 1e-9;

#[test]
fn a_slack_dropper_adds_no_rayleigh_dashpot() {
    let scene = |dropper: &str| {
        format!(
            r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 1.0
tension = 1000.0
left = "pinned"
right = "pinned"
damping = {{ stiffness = 1.0e-3 }}

[mesh]
elements = 100

[[carrier]]
force = 20.0
side = "below"
start = 1.0
speed = {{ profile = "constant", value = 5.0 }}

[[probe]]
name = "p"
x = 4.0

[time]
step = 1e-3
end = 1.0

{dropper}
"#
        )
    };
    // anchored 0.5 m above, 0.6 m long: slack by 0.1 m, far beyond the
    // run's displacements (a few mm)
    let with = go(&scene(
        "[[dropper]]\nx = 4.0\nstiffness = 1.0e5\nanchor_height = 0.5\nlength = 0.6\n",
    ));
    let without = go(&scene(""));
    let col = |o: &RunOutput| o.history.probes[0].1.clone();
    let (a, b) = (col(&with), col(&without));
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale;
    let force = with.history.droppers[0]
        .1
        .iter()
        .fold(0.0f64, |m, f| m.max(f.abs()));
    println!("slack dropper under βK: {diff:.2e} of the largest displacement, force {force:e} N");
    assert_eq!(force, 0.0, "the dropper must stay slack");
    assert!(diff < SLACK_IS_ABSENT, "{diff}");
}
