//! Stability at the extremes: runs the reference case (and other bundled
//! scenes where more apt) at extreme parameters and resolutions, for each
//! contact formulation where it makes sense, and writes `docs/stability.md`.
//!
//!     cargo run --release --example stability_report
//!
//! Every row is one `taut run` (its command is written next to it). Its
//! outcome is one of: ran, ran with warnings, stopped with a diagnosis, or
//! rejected as invalid input. Where a reference exists (a better-resolved
//! Lagrange run of the same physics, the bundled reference case, or the
//! analytic solution of a moving-force scene), the row is scored for accuracy;
//! a run that finishes without warning yet is clearly off its reference is
//! listed under "Findings" as silently wrong. Runs are sequential and take
//! a little over a minute on two cores.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::time::Instant;

use taut::scene::CarrierKind;
use taut::study::reference::analytic_w;
use taut::{Error, Resolved, RunOutput, resolve_scene, run};

const FORMULATIONS: [&str; 4] = ["lagrange", "penalty", "complementarity", "impact"];

/// P_l agrees with its reference when |ΔP_l| ≤ PL_ABS + PL_REL·P_l,ref. It is
/// clearly wrong when |ΔP_l| > 2·(PL_ABS + PL_REL·P_l,ref), or when a
/// reference loss of at least PL_ABS is more than halved.
const PL_ABS: f64 = 0.002;
const PL_REL: f64 = 0.25;
/// The mean contact force agrees within MEAN_OK of its reference and is
/// clearly wrong beyond MEAN_BAD.
const MEAN_OK: f64 = 0.02;
const MEAN_BAD: f64 = 0.05;
/// The displacement under a moving force agrees with the analytic solution
/// when max|w − w_a| ≤ W_OK of the deflection scale; clearly wrong beyond W_BAD.
const W_OK: f64 = 0.05;
const W_BAD: f64 = 0.10;
/// Largest number of samples at which an analytic reference is evaluated
/// (the series of a nearly flexible beam costs milliseconds per point).
const ANALYTIC_SAMPLES: usize = 400;

/// What a row is scored against.
#[derive(Clone)]
enum Check {
    /// No reference.
    None,
    /// P_l and the mean force (carrier 0) of another run. The `also` runs
    /// (a coarser level, a 1e-6 perturbation of g) measure how well that
    /// reference is itself determined.
    Run {
        scene: &'static str,
        sets: Vec<String>,
        name: String,
        also: Vec<(&'static str, Vec<String>)>,
    },
    /// The analytic displacement under a moving force (MODEL §8).
    Analytic,
}

/// How a run compares with its reference.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Agreement {
    Good,
    Marginal,
    Bad,
}

/// The verdict of a row.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Verdict {
    /// Ran without warning and agrees with its reference.
    Accurate,
    /// Ran with a warning, and agrees with its reference anyway.
    AccurateFlagged,
    /// Ran with a warning; the figures are indeed not a converged answer.
    Flagged,
    /// Stopped with a diagnosis.
    Stopped,
    /// Rejected as invalid input.
    Rejected,
    /// Ran without warning, outside the tolerance but not clearly wrong.
    Marginal,
    /// Ran without warning, yet clearly off its reference.
    SilentlyWrong,
    /// Ran without warning, but the reference itself moves beyond the
    /// tolerance under refinement or a 1e-6 perturbation: no run of this
    /// case determines P_l or the mean to the tolerance, and nothing says so.
    IllDetermined,
    /// Ran without warning; nothing to score it against.
    Unchecked,
}

impl Verdict {
    fn text(self) -> &'static str {
        match self {
            Verdict::Accurate => "accurate",
            Verdict::AccurateFlagged => "accurate, flagged",
            Verdict::Flagged => "inaccurate but flagged",
            Verdict::Stopped => "stopped",
            Verdict::Rejected => "rejected",
            Verdict::Marginal => "marginal",
            Verdict::SilentlyWrong => "**SILENTLY WRONG**",
            Verdict::IllDetermined => "*ill-determined*",
            Verdict::Unchecked => "unchecked",
        }
    }
}

/// One row of the report.
struct Case {
    label: String,
    /// The contact formulation, or "—" for a moving force (no contact).
    form: &'static str,
    scene: &'static str,
    sets: Vec<String>,
    check: Check,
    /// The verdict found when the explanation was written; a change is listed.
    expect: Verdict,
    /// Why it happens: the second half of the row's sentence.
    why: String,
}

/// A group of rows under one heading.
struct Section {
    title: &'static str,
    intro: String,
    cases: Vec<Case>,
}

/// Figures of a finished run (carrier 0).
#[derive(Clone)]
struct Figures {
    loss: f64,
    mean: f64,
    max: f64,
    /// x/L of the largest |λ|.
    max_at: f64,
    penetration: f64,
    switches: usize,
    /// Σ|λ_{n+1} − λ_n| / Σ|λ_n| over the steps.
    osc: f64,
    warnings: Vec<String>,
    /// (max|w − w_a| / scale, max|w − w_a| in m, scale in m) for a moving force.
    w_err: Option<(f64, f64, f64)>,
    mass_carrier: bool,
}

/// What happened to a row.
#[derive(Clone)]
enum Outcome {
    Rejected(String),
    Stopped(String),
    Ran(Box<Figures>),
}

fn scene_text(scene: &str) -> String {
    let path = format!("{}/scenes/{scene}.toml", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The error of the displacement under a moving force against MODEL §8,
/// relative to the larger of the analytic max|w| under the force and the
/// static midspan deflection of a string, F·L/(4T) (under a supersonic force
/// on a string the exact deflection under the force is zero).
fn analytic_error(sc: &Resolved, out: &RunOutput) -> Option<(f64, f64, f64)> {
    let wa = analytic_w(sc)?;
    let CarrierKind::Force { force } = sc.carriers[0].kind else {
        return None;
    };
    let tr = &out.history.carriers[0];
    let n = out.history.len();
    let stride = (n / ANALYTIC_SAMPLES).max(1);
    let (mut err, mut peak) = (0.0f64, 0.0f64);
    for i in (1..n).step_by(stride) {
        let a = wa(out.history.t[i]);
        err = err.max((tr.w[i] - a).abs());
        peak = peak.max(a.abs());
    }
    let b = &sc.beam;
    let string_scale = if b.tension > 0.0 {
        force * b.length / (4.0 * b.tension)
    } else {
        0.0
    };
    let scale = peak.max(string_scale);
    Some((err / scale, err, scale))
}

fn figures(sc: &Resolved, out: &RunOutput, analytic: bool) -> Figures {
    let st = &out.stats[0];
    let tr = &out.history.carriers[0];
    let f = &tr.force[1..];
    let total: f64 = f.iter().map(|x| x.abs()).sum();
    let jumps: f64 = f.windows(2).map(|p| (p[1] - p[0]).abs()).sum();
    let mut imax = 1;
    for i in 1..tr.force.len() {
        if tr.force[i].abs() > tr.force[imax].abs() {
            imax = i;
        }
    }
    Figures {
        loss: st.loss_fraction,
        mean: st.force.mean,
        max: st.force.max,
        max_at: tr.x[imax] / sc.beam.length,
        penetration: st.max_penetration,
        switches: st.contact_switches,
        osc: if total > 0.0 { jumps / total } else { 0.0 },
        warnings: out.warnings.clone(),
        w_err: if analytic {
            analytic_error(sc, out)
        } else {
            None
        },
        mass_carrier: matches!(sc.carriers[0].kind, CarrierKind::MassSpring { .. }),
    }
}

fn execute(scene: &str, sets: &[String], analytic: bool) -> Outcome {
    let sc = match resolve_scene(&scene_text(scene), sets) {
        Ok(sc) => sc,
        Err(e) => return Outcome::Rejected(e.to_string()),
    };
    match run(&sc, &mut |_, _| {}) {
        Ok(out) => Outcome::Ran(Box::new(figures(&sc, &out, analytic))),
        Err(e @ (Error::Diverged { .. } | Error::Contact { .. })) => {
            Outcome::Stopped(e.to_string())
        }
        Err(e) => Outcome::Stopped(format!("(an unexpected kind of error) {e}")),
    }
}

/// The `taut run` command of a row.
fn command(scene: &str, sets: &[String]) -> String {
    let mut s = format!("taut run scenes/{scene}.toml");
    for o in sets {
        if o.contains([' ', '{', '"']) {
            let _ = write!(s, " --set '{o}'");
        } else {
            let _ = write!(s, " --set {o}");
        }
    }
    s
}

fn fmt_g(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.2e}")
    } else if x.abs() >= 100.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.3}")
    }
}

/// Scored result of a row.
struct Row {
    outcome: Outcome,
    verdict: Verdict,
    /// Short accuracy figure for the table.
    accuracy: String,
    /// The automatic half of the sentence: what happened.
    what: String,
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b.abs().max(f64::MIN_POSITIVE)
}

/// How the reference's own P_l and mean move across its `also` runs:
/// (largest |ΔP_l|, largest relative |Δmean|).
fn spread(r: &Figures, also: &[(&str, Figures)]) -> (f64, f64) {
    also.iter().fold((0.0f64, 0.0f64), |(p, m), (_, a)| {
        (
            p.max((a.loss - r.loss).abs()),
            m.max(rel(a.mean, r.mean).abs()),
        )
    })
}

/// "by ΔP_l and Δmean % under X, and … under Y".
fn spread_text(r: &Figures, also: &[(&str, Figures)]) -> String {
    let parts: Vec<String> = also
        .iter()
        .map(|(label, a)| {
            format!(
                "{:+.4} in P_l and {:+.1} % in the mean {label}",
                a.loss - r.loss,
                100.0 * rel(a.mean, r.mean)
            )
        })
        .collect();
    parts.join(", and ")
}

/// Whether the reference is determined to the tolerance.
fn determined(r: &Figures, (sp, sm): (f64, f64)) -> bool {
    sp <= PL_ABS + PL_REL * r.loss && sm <= MEAN_OK
}

/// Agreement of a run with a reference whose own spread is `(sp, sm)`: the
/// spread widens the "clearly wrong" bounds only.
fn agreement_with_run(f: &Figures, r: &Figures, (sp, sm): (f64, f64)) -> Agreement {
    let dpl = (f.loss - r.loss).abs();
    let pl_tol = PL_ABS + PL_REL * r.loss;
    let dmean = rel(f.mean, r.mean).abs();
    let missed = r.loss >= PL_ABS && f.loss < 0.5 * r.loss && sp < 0.5 * r.loss;
    if dpl > 2.0 * pl_tol + sp || missed || dmean > MEAN_BAD + sm {
        Agreement::Bad
    } else if dpl > pl_tol || dmean > MEAN_OK {
        Agreement::Marginal
    } else {
        Agreement::Good
    }
}

fn score(case: &Case, cache: &mut HashMap<String, Outcome>) -> Row {
    let outcome = execute(
        case.scene,
        &case.sets,
        matches!(case.check, Check::Analytic),
    );
    let mut cached = |scene: &str, sets: &[String]| -> Option<Figures> {
        let r = cache
            .entry(command(scene, sets))
            .or_insert_with(|| execute(scene, sets, false))
            .clone();
        match r {
            Outcome::Ran(f) => Some(*f),
            _ => None,
        }
    };
    let (reference, also) = match &case.check {
        Check::Run {
            scene, sets, also, ..
        } => (
            cached(scene, sets),
            also.iter()
                .filter_map(|(label, s)| cached(scene, s).map(|f| (*label, f)))
                .collect::<Vec<_>>(),
        ),
        _ => (None, Vec::new()),
    };
    let (verdict, accuracy, what) = match &outcome {
        Outcome::Rejected(m) => (
            Verdict::Rejected,
            "—".to_string(),
            format!("Rejected as invalid input, “{m}”"),
        ),
        Outcome::Stopped(m) => (
            Verdict::Stopped,
            "—".to_string(),
            format!("Stopped with a diagnosis, “{m}”"),
        ),
        Outcome::Ran(f) => {
            let warned = !f.warnings.is_empty();
            let mut ill = false;
            let (agrees, accuracy, against) = match (&case.check, &reference, f.w_err) {
                (Check::Analytic, _, Some((e, abs, scale))) => (
                    Some(if e <= W_OK {
                        Agreement::Good
                    } else if e <= W_BAD {
                        Agreement::Marginal
                    } else {
                        Agreement::Bad
                    }),
                    format!("w err {:.2} %", 100.0 * e),
                    format!(
                        "max|w − w_analytic| = {abs:.2e} m, {:.2} % of the deflection scale {scale:.2e} m",
                        100.0 * e
                    ),
                ),
                (Check::Run { name, .. }, Some(r), _) => {
                    let dmean = rel(f.mean, r.mean);
                    let sp = spread(r, &also);
                    ill = !determined(r, sp);
                    (
                        Some(agreement_with_run(f, r, sp)),
                        format!(
                            "P_l {:.4} vs {:.4}; mean {:+.1} % (ref. ±{:.1} %)",
                            f.loss,
                            r.loss,
                            100.0 * dmean,
                            100.0 * sp.1
                        ),
                        format!(
                            "P_l = {:.4} against {:.4} and mean force {} N against {} N ({:+.1} %) for {name}{}",
                            f.loss,
                            r.loss,
                            fmt_g(f.mean),
                            fmt_g(r.mean),
                            100.0 * dmean,
                            if ill {
                                format!(", which itself moves by {}", spread_text(r, &also))
                            } else {
                                String::new()
                            }
                        ),
                    )
                }
                (Check::Run { name, .. }, None, _) => (
                    None,
                    "reference did not run".into(),
                    format!("its reference, {name}, did not run"),
                ),
                _ => (None, "—".into(), String::new()),
            };
            let verdict = match (warned, agrees, ill) {
                (false, Some(Agreement::Bad), _) => Verdict::SilentlyWrong,
                (false, Some(_), true) => Verdict::IllDetermined,
                (false, Some(Agreement::Good), false) => Verdict::Accurate,
                (false, Some(Agreement::Marginal), false) => Verdict::Marginal,
                (false, None, _) => Verdict::Unchecked,
                (true, Some(Agreement::Good), false) => Verdict::AccurateFlagged,
                (true, _, _) => Verdict::Flagged,
            };
            let mut what = match verdict {
                Verdict::Accurate => "Accurate without warning",
                Verdict::Marginal => {
                    "Ran without warning, a little outside the tolerance"
                }
                Verdict::SilentlyWrong => "Ran without warning, yet clearly off its reference",
                Verdict::IllDetermined => {
                    "Ran without warning, though the case's P_l or mean is not determined to the tolerance even by its reference"
                }
                Verdict::Unchecked => "Ran without warning, with nothing to check it against",
                Verdict::AccurateFlagged => "Ran with a warning, yet agrees with its reference",
                _ => "Ran with a warning, and is indeed off its reference",
            }
            .to_string();
            if !against.is_empty() {
                let _ = write!(what, " ({against})");
            }
            (verdict, accuracy, what)
        }
    };
    Row {
        outcome,
        verdict,
        accuracy,
        what,
    }
}

// ---------------------------------------------------------------------------
// The cases
// ---------------------------------------------------------------------------

/// The reference wire's second moment of area (9.64e-10 m⁴) × 1e-6 and × 1e4,
/// as override values.
const I_SMALL: &str = "beam.second_moment=9.64e-16";
const I_BIG: &str = "beam.second_moment=9.64e-6";
/// Tension of the reference wire, N.
const T_REF: f64 = 3.0e4;
/// Spring stiffness and preload of the reference carrier.
const K_REF: f64 = 987.0;
const PRELOAD_REF: f64 = 0.05;

fn sets(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

fn with(base: &[String], more: &[&str]) -> Vec<String> {
    let mut v = base.to_vec();
    v.extend(more.iter().map(|s| s.to_string()));
    v
}

/// g changed by 1e-6 of itself: a perturbation far below any physical
/// meaning, to see whether a case's figures are determined at all.
const PERTURBED_G: &str = "gravity.g=9.81000981";

/// A Lagrange reference run with `resolution` on top of `physics`; its
/// spread is measured against `coarser` and against a 1e-6 change of g.
fn reference_run(
    scene: &'static str,
    physics: &[String],
    resolution: &[&str],
    coarser: Option<(&'static str, &[&str])>,
    name: String,
) -> Check {
    let base = with(physics, &["contact.formulation=lagrange"]);
    let sets = with(&base, resolution);
    let mut also = vec![("under a 1e-6 change of g", with(&sets, &[PERTURBED_G]))];
    if let Some((label, c)) = coarser {
        also.push((label, with(&base, c)));
    }
    Check::Run {
        scene,
        sets,
        name,
        also,
    }
}

/// Lagrange, two refinements finer than the bundled resolution; spread
/// against one refinement finer and against a perturbation.
fn finest(scene: &'static str, physics: &[String]) -> Check {
    reference_run(
        scene,
        physics,
        &["mesh.elements=1600", "time.step=2.5e-5"],
        Some((
            "at N = 800, Δt = 5e-5 s",
            &["mesh.elements=800", "time.step=5e-5"],
        )),
        "Lagrange at N = 1600, Δt = 2.5e-5 s".into(),
    )
}

/// Lagrange with a step that resolves the carrier's 0.2 ms period; spread
/// against twice that step and against a perturbation.
fn fine_step(scene: &'static str, physics: &[String]) -> Check {
    reference_run(
        scene,
        physics,
        &["time.step=1e-5"],
        Some(("at Δt = 2e-5 s", &["time.step=2e-5"])),
        "Lagrange at N = 400, Δt = 1e-5 s".into(),
    )
}

/// Lagrange at the bundled resolution (N = 400, Δt = 1e-4 s); spread
/// against a perturbation (its convergence is the baseline section's).
fn bundled(scene: &'static str, physics: &[String], what: &str) -> Check {
    reference_run(
        scene,
        physics,
        &[],
        None,
        format!("the bundled Lagrange run (N = 400, Δt = 1e-4 s{what})"),
    )
}

/// Rows for every formulation: scene, physics, reference, expected verdicts
/// and explanations per formulation.
fn all_forms(
    label: &str,
    scene: &'static str,
    physics: &[String],
    check: &Check,
    expect: [Verdict; 4],
    why: [&str; 4],
) -> Vec<Case> {
    FORMULATIONS
        .iter()
        .zip(expect)
        .zip(why)
        .map(|((&form, expect), why)| Case {
            label: label.into(),
            form,
            scene,
            sets: with(physics, &[&format!("contact.formulation={form}")]),
            check: check.clone(),
            expect,
            why: why.into(),
        })
        .collect()
}

fn one(
    label: &str,
    form: &'static str,
    scene: &'static str,
    sets: Vec<String>,
    check: Check,
    expect: Verdict,
    why: &str,
) -> Case {
    Case {
        label: label.into(),
        form,
        scene,
        sets,
        check,
        expect,
        why: why.into(),
    }
}

fn force_case(label: &str, scene: &'static str, s: &[&str], expect: Verdict, why: &str) -> Case {
    one(label, "—", scene, sets(s), Check::Analytic, expect, why)
}

use Verdict::*;

fn sections() -> Vec<Section> {
    let reference = resolve_scene(&scene_text("reference"), &[]).expect("bundled scene");
    let c = reference.beam.wave_speed();
    let ea = reference.beam.ea.unwrap_or(f64::NAN);
    let none: Vec<String> = vec![];
    let mut out = Vec::new();

    // 0. Baseline
    let mut cases = all_forms(
        "bundled",
        "reference",
        &none,
        &finest("reference", &none),
        [Accurate; 4],
        [
            "the study's scheme at the bundled resolution already has P_l and the mean force; only the re-contact peaks near the far support are unconverged",
            "the default relative stiffness ρ = 1000 makes each step's force 0.1 % softer than Lagrange's, which barely moves P_l or the mean",
            "the QP solves Lagrange's per-step problem to solver tolerance",
            "the velocity-level law lets the gap drift by micrometres and softens re-contact, which loses a few loss steps but not the mean",
        ],
    );
    cases.push(force_case(
        "moving force on a beam, bundled",
        "moving_force_beam",
        &[],
        Accurate,
        "50 Hermite elements resolve the nearly quasi-static deflection of the tensioned beam",
    ));
    cases.push(force_case(
        "moving force on a string, bundled",
        "moving_force_string",
        &[],
        Accurate,
        "linear string elements smear the kink under the load over one 1 m element, a first-order error that is still small",
    ));
    out.push(Section {
        title: "Baseline: the bundled scenes",
        intro: "The rows every extreme is measured against: the reference case under each formulation, scored against Lagrange two refinements finer, and the two moving-force scenes scored against their analytic solutions.".into(),
        cases,
    });

    // 1. EI → 0
    let ei_small = sets(&[I_SMALL]);
    let string = sets(&["beam.second_moment=0", "beam.left=pinned"]);
    let chatter_why = "a mass on an almost bendless wire chatters on and off contact, its force alternating from step to step (osc ≈ 0.5), and P_l and the mean move with refinement; the chatter warning says so";
    let mut cases = all_forms(
        "EI × 1e-6",
        "reference",
        &ei_small,
        &finest("reference", &ei_small),
        [Flagged, Flagged, Flagged, Stopped],
        [
            chatter_why,
            chatter_why,
            chatter_why,
            "the velocity-level Delassus number turns negative on the very last step, as the carrier arrives at the far support over the wire's steep slope there (V·Δt is only 0.08 h; with Δt = 1e-5 s the run completes)",
        ],
    );
    cases.push(one(
        "EI = 0, clamped left end",
        "lagrange",
        "reference",
        sets(&["beam.second_moment=0", "contact.formulation=lagrange"]),
        Check::None,
        Rejected,
        "a string has no rotational dof, so it cannot be clamped, and taut names the field",
    ));
    let string_why = "on linear string elements the mass switches contact on about a fifth of the steps at every resolution, a numerical on/off oscillation rather than physical loss, and the chatter warning says so";
    cases.extend(all_forms(
        "EI = 0, string elements (pinned–pinned)",
        "reference",
        &string,
        &finest("reference", &string),
        [Flagged; 4],
        [string_why; 4],
    ));
    cases.push(force_case(
        "moving force, EI × 1e-6",
        "moving_force_beam",
        &[I_SMALL],
        Accurate,
        "with the tension carrying the load the C¹ Hermite elements still match the analytic series; without a mass there is nothing to chatter",
    ));
    cases.push(force_case(
        "moving force, EI = 0 (string elements)",
        "moving_force_string",
        &[],
        Accurate,
        "this is the bundled string scene: the first-order kink error of linear elements, a few per cent at 1 m elements",
    ));
    out.push(Section {
        title: "Bending stiffness EI → 0",
        intro: "EI × 1e-6 keeps Hermite beam elements and the clamped–pinned supports; EI = 0 switches to linear string elements, which need pinned ends. The moving-force rows isolate the wire from the contact.".into(),
        cases,
    });

    // 2. EI large
    let ei_big = sets(&[I_BIG]);
    let stiff_why = "the 1e4 times stiffer beam barely deflects under the carrier, so the force stays near its preload, contact is never lost and every law gives the same smooth force";
    let mut cases = all_forms(
        "EI × 1e4",
        "reference",
        &ei_big,
        &finest("reference", &ei_big),
        [Accurate; 4],
        [stiff_why; 4],
    );
    cases.push(force_case(
        "moving force, EI × 1e4",
        "moving_force_beam",
        &[I_BIG],
        Accurate,
        "a stiff beam's response is quasi-static and easily resolved",
    ));
    out.push(Section {
        title: "Bending stiffness EI large (× 1e4)",
        intro: String::new(),
        cases,
    });

    // 3. T → 0
    let t0 = sets(&["beam.tension=0"]);
    let t0_scene = resolve_scene(&scene_text("reference"), &t0).expect("T = 0 is valid");
    let c0 = t0_scene.beam.wave_speed();
    let ell =
        |v: f64| 2.0 * std::f64::consts::PI * (reference.beam.ei / reference.beam.rho_a).sqrt() / v;
    let mut cases = all_forms(
        "T = 0 (pure beam)",
        "reference",
        &t0,
        &finest("reference", &t0),
        [Accurate, SilentlyWrong, Marginal, Accurate],
        [
            "the untensioned wire is so soft that the mass bounces (P_l ≈ 0.69, re-contact peaks of 10⁴ N), yet P_l and the mean converge within a few per cent; the peaks do not",
            "with the default relative stiffness ρ = 1000 every one of the many re-contacts is slightly cushioned, which lowers the mean force by about a tenth (ρ = 1e9 brings it within 2 % of the bundled Lagrange run); nothing warns",
            "the bouncing amplifies round-off-level differences (a 1e-12 m change of preload moves the bundled Lagrange mean by almost 1 %), and the QP lands a few per cent from Lagrange",
            "the velocity-level law softens the re-contacts but keeps the mean and P_l of this bouncing regime",
        ],
    );
    cases.push(one(
        "T = 0 on a string (EI = 0)",
        "lagrange",
        "reference",
        sets(&[
            "beam.second_moment=0",
            "beam.left=pinned",
            "beam.tension=0",
            "contact.formulation=lagrange",
        ]),
        Check::None,
        Rejected,
        "a string without tension has no stiffness, and taut names the field",
    ));
    cases.push(force_case(
        "moving force, T = 0 (pure beam), bundled N = 50",
        "moving_force_beam",
        &["beam.tension=0"],
        SilentlyWrong,
        &format!(
            "without tension the load excites the flexural wave whose phase speed equals V, of length ℓ* = 2π·sqrt(EI/ρA)/V = {:.2} m, which 1 m elements cannot carry; nothing in the run notices",
            ell(75.0)
        ),
    ));
    cases.push(force_case(
        "moving force, T = 0, N = 800, Δt = 2.5e-5 s",
        "moving_force_beam",
        &["beam.tension=0", "mesh.elements=800", "time.step=2.5e-5"],
        Accurate,
        "with 6.25 cm elements (ℓ*/13) the same case converges to the analytic solution, so the bundled mesh, not the scheme, was at fault",
    ));
    out.push(Section {
        title: "Tension T → 0",
        intro: format!(
            "With T = 0 the string wave speed c = sqrt(T/ρA) is {c0} m/s, so V0/c is undefined: `summary.json` writes `speed_ratio: null` and the terminal `V0/c = n/a`. A pure beam's flexural waves are dispersive, with phase speeds from 0 upwards, so every moving load meets a wave of its own speed, of length ℓ* = 2π·sqrt(EI/ρA)/V ({:.2} m at the reference's 100 m/s, five elements of the bundled mesh).",
            ell(100.0)
        ),
        cases,
    });

    // 4. T large
    let t_big = vec![format!("beam.tension={:e}", T_REF * 1e3)];
    let taut_why = "the wire becomes a very stiff string (V0/c = 0.02), so the force stays within a few newtons of its static 59 N; no warning either that T/EA > 1, a strain beyond the model's small-strain premise";
    let mut cases = all_forms(
        "T × 1e3",
        "reference",
        &t_big,
        &finest("reference", &t_big),
        [Accurate; 4],
        [taut_why; 4],
    );
    cases.push(force_case(
        "moving force, T × 1e3",
        "moving_force_beam",
        &[&format!("beam.tension={:e}", T_REF * 1e3)],
        Accurate,
        "the deflection is quasi-static and small",
    ));
    out.push(Section {
        title: "Tension T very large (× 1e3)",
        intro: format!(
            "T = 3e7 N gives c = {:.0} m/s and V0/c = {:.3}. It is also T/EA = {:.2} (EA = {ea:.3e} N): the axial strain the model assumes small is 149 %, a physical absurdity that taut reports in `summary.json` (`tension_ratio`) but does not warn about; the numerics are unaffected.",
            c * (1e3f64).sqrt(),
            100.0 / (c * (1e3f64).sqrt()),
            T_REF * 1e3 / ea
        ),
        cases,
    });

    // 5. m → 0
    let m0 = sets(&["carrier.mass=1e-6"]);
    let m0_why = "with no inertia the contact point follows the wire, the force is k(δ0 − w) every step and is smoother (osc ≈ 0) than the bundled 1 kg mass's (0.18): the unresolved 0.2 ms mass–spring mode is never excited and no multiplier oscillates";
    let m0_pen = "as for Lagrange, with W dominated by the spring (1/A_q), so the relative κ = 1000/W is only about 5e5 N/m and the penetration is 0.07 mm";
    let mut cases = all_forms(
        "m = 1e-6 kg",
        "reference",
        &m0,
        &fine_step("reference", &m0),
        [Accurate; 4],
        [m0_why, m0_pen, m0_why, m0_why],
    );
    let m0_t2 = sets(&["carrier.mass=1e-6", "time.end=1.0"]);
    let t2_why = "the standing massless contact point feels the returning waves as a smooth change of k(δ0 − w), with no step-to-step oscillation";
    cases.extend(all_forms(
        "m = 1e-6 kg, stationary (T2, 1 s)",
        "t2_stationary_mass",
        &m0_t2,
        &fine_step("t2_stationary_mass", &m0_t2),
        [Accurate; 4],
        [t2_why, m0_pen, t2_why, t2_why],
    ));
    out.push(Section {
        title: "Carrier mass m → 0 (1e-6 kg)",
        intro: "A massless contact point: the mass–spring's own period 2π·sqrt(m/k) is 0.2 ms, two steps of 1e-4 s, so its mode is not resolved and a Lagrange multiplier might ring from step to step. The `osc` column measures that: Σ|λ_{n+1} − λ_n| / Σ|λ_n| is 0.18 for the bundled 1 kg case (its force is rough at re-contacts) and would exceed 1 for a multiplier alternating in sign. The reference is Lagrange at Δt = 1e-5 s, which resolves the 0.2 ms period.".into(),
        cases,
    });

    // 6. k → ∞
    let k_big = sets(&["carrier.stiffness=1e9"]);
    let k_same_force = vec![
        "carrier.stiffness=1e9".to_string(),
        format!("carrier.preload={:e}", K_REF * PRELOAD_REF / 1e9),
    ];
    let k_why = "the carrier starts at the clamped end, where the support takes the whole 5e7 N preload force k·δ0 (that dominates the mean); off the support the spring punches the wire almost a metre deep and the mass then bounces, out of contact 41 % of the time; the figures hold as Δt falls tenfold to resolve the 0.2 ms spring";
    let k_imp = "the velocity-level Delassus number turns negative on the last step, at the far support; the advice works (with Δt = 1e-5 s the run completes)";
    let k_rigid = "a rigid carrier whose 49 N preload is relieved by a 5e-8 m deflection keeps only 2.9 N on average and loses contact 41 % of the time, converged in Δt";
    let mut cases = all_forms(
        "k = 1e9 N/m, δ0 = 0.05 m",
        "reference",
        &k_big,
        &fine_step("reference", &k_big),
        [Accurate, Accurate, Accurate, Stopped],
        [k_why, k_why, k_why, k_imp],
    );
    cases.extend(all_forms(
        "k = 1e9 N/m, k·δ0 = 49.35 N",
        "reference",
        &k_same_force,
        &fine_step("reference", &k_same_force),
        [Accurate, Accurate, Accurate, Stopped],
        [k_rigid, k_rigid, k_rigid, k_imp],
    ));
    out.push(Section {
        title: "Spring stiffness k → ∞ (1e9 N/m)",
        intro: "Two readings: the bundled preload δ0 = 0.05 m (so the preload force k·δ0 is 5e7 N), and the bundled preload force k·δ0 = 49.35 N (δ0 = 4.9e-8 m), the limit of a rigid carrier. Either way the mass–spring period is 0.2 ms (two steps), so the reference is Lagrange at Δt = 1e-5 s.".into(),
        cases,
    });

    // 7. V0 > c
    let mut cases = Vec::new();
    let supersonic_uni = "above c the mass outruns its own waves and bounces (P_l ≈ 0.13); P_l and the mean agree with the finest run, the peaks do not";
    let bil_12 = "a mass held on the wire above c is physically unstable (anomalous Doppler waves), and at 1.2c the growth is slow enough to reach the far support before the 1e3 × force bound would stop the run: the force grows from 60 N to 10⁴ N over the last fifth of the span, alternates sign from step to step there (osc > 1.5), and its mean changes by 15 % between N = 800 and 1600; the instability the 2c run diagnoses goes unmentioned here";
    let bil_12_imp = "the velocity-level law lets the held mass drift (0.7 mm) and keeps the force smoother, but the case is the same undiagnosed, unconverged instability as for Lagrange, and the agreement of the mean is a coincidence (at N = 800, Δt = 5e-5 s impact gives 51 N)";
    let fast_uni = "at 2c the mass is airborne 70 % of the time and its bouncing is sensitive to tiny changes (changing V0 by 7e-7 of itself moves the bundled Lagrange mean from 60.5 N to 69.3 N), so P_l and the mean are meaningful only to about 10 %, which nothing reports";
    let bil_2 = "a held mass at 2c is unstable and its force reaches the 1e3 × bound within 0.08 s; the message names the physical instability";
    for (factor, name) in [(1.2, "1.2c"), (2.0, "2c")] {
        for kind in ["unilateral", "bilateral"] {
            let physics = vec![
                format!("carrier.speed.cruise={:.4}", factor * c),
                format!("contact.kind={kind}"),
            ];
            let (expect, why) = match (name, kind) {
                ("1.2c", "unilateral") => ([Accurate; 4], [supersonic_uni; 4]),
                ("1.2c", _) => ([IllDetermined; 4], [bil_12, bil_12, bil_12, bil_12_imp]),
                ("2c", "unilateral") => ([IllDetermined; 4], [fast_uni; 4]),
                _ => ([Stopped; 4], [bil_2; 4]),
            };
            cases.extend(all_forms(
                &format!("V0 = {name}, {kind}"),
                "reference",
                &physics,
                &finest("reference", &physics),
                expect,
                why,
            ));
        }
    }
    for (factor, name) in [(1.2, "1.2c"), (2.0, "2c")] {
        for n in [50, 400] {
            let (expect, why) = match (name, n) {
                ("1.2c", 50) => (
                    SilentlyWrong,
                    "under a supersonic force the exact deflection under the load is zero (the wake trails behind with slope F/(ρA(V² − c²))), and 1 m linear elements smear that kink into millimetres of error; it shrinks with h, but nothing warns at this mesh",
                ),
                (_, 50) => (
                    Accurate,
                    "at 2c the wake's slope F/(ρA(V² − c²)) is seven times smaller than at 1.2c, and the kink error of 1 m elements smaller still",
                ),
                _ => (
                    Accurate,
                    "with elements eight times shorter the kink error all but vanishes",
                ),
            };
            cases.push(force_case(
                &format!("moving force on a string, V = {name}, N = {n}"),
                "moving_force_string",
                &[
                    &format!("carrier.speed.value={:.4}", factor * c),
                    "time.end=carrier_leaves",
                    &format!("mesh.elements={n}"),
                ],
                expect,
                why,
            ));
        }
    }
    out.push(Section {
        title: "Carrier speed above the wave speed (V0 > c)",
        intro: format!(
            "c = sqrt(T/ρA) = {c:.2} m/s for the reference wire; V0 = 1.2c = {:.2} m/s and 2c = {:.2} m/s (the runs end sooner, as the carrier leaves sooner). A mass held on the wire (bilateral) above c can be physically unstable; a moving force cannot.",
            1.2 * c,
            2.0 * c
        ),
        cases,
    });

    // 8. Δt
    let mut cases = Vec::new();
    let dt2 = "steps that move the carrier 1 m (8 elements), twelve times the time a wave takes to cross an element, filter out the wire's waves: the force is smooth, the 9 loss intervals of the bundled run are all missed, and nothing warns that the step is far above the element-crossing time";
    let dt3 = "10 cm steps (0.8 element) still miss the reflected waves that lift the wire off the mass near the far support: no loss at all, and nothing warns";
    let dt3_imp = "with V·Δt = 0.8 h the convective term outweighs the velocity-level Delassus number and the law stops, telling the user to reduce Δt";
    let dt6 =
        "over the ramp (no loss) every law agrees with the bundled step to four digits in the mean";
    for (dt, expect, why) in [
        ("1e-2", [SilentlyWrong; 4], [dt2; 4]),
        (
            "1e-3",
            [SilentlyWrong, SilentlyWrong, SilentlyWrong, Stopped],
            [dt3, dt3, dt3, dt3_imp],
        ),
    ] {
        cases.extend(all_forms(
            &format!("Δt = {dt} s"),
            "reference",
            &[format!("time.step={dt}")],
            &bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    let short = sets(&["time.end=0.05"]);
    cases.extend(all_forms(
        "Δt = 1e-6 s, t_end = 0.05 s",
        "reference",
        &with(&short, &["time.step=1e-6"]),
        &bundled("reference", &short, ", t_end = 0.05 s"),
        [Accurate; 4],
        [dt6; 4],
    ));
    cases.push(one(
        "Δt = 1e-6 s, whole run",
        "lagrange",
        "reference",
        sets(&["time.step=1e-6", "contact.formulation=lagrange"]),
        bundled("reference", &none, ""),
        Accurate,
        "P_l and the mean hold at a hundredth of the bundled step, while the re-contact peak near the far support grows to about 4.5e4 N, the documented Δt-dependence of the study's model (formulations.md)",
    ));
    for (dt, why) in [
        (
            "1e-2",
            "the deflection under a force at half the wave speed is nearly quasi-static, so even 60 steps follow it",
        ),
        ("1e-3", "a quasi-static response, well followed"),
        (
            "1e-6",
            "the time error vanishes and the small mesh error remains",
        ),
    ] {
        cases.push(force_case(
            &format!("moving force on a beam, Δt = {dt} s"),
            "moving_force_beam",
            &[&format!("time.step={dt}")],
            Accurate,
            why,
        ));
    }
    out.push(Section {
        title: "Time step Δt far above and below the accuracy and stability scales",
        intro: "The bundled Δt = 1e-4 s moves the carrier 1 cm (0.08 element) per step at cruise, and a wave crosses an element in 0.83 ms. Δt = 1e-2 s moves the carrier 1 m (8 elements) per step, though it still resolves the 0.2 s mass–spring period; Δt = 1e-3 s moves it 0.8 element per step. Generalized-α with ρ∞ = 1 is unconditionally stable, so nothing can blow up from the step alone; the question is whether a too-coarse step is noticed. Δt = 1e-6 s is run over the ramp (0.05 s) for every law, and once over the whole run with Lagrange.".into(),
        cases,
    });

    // 9. Mesh
    let mut cases = Vec::new();
    let n4 = "12.5 m elements cannot carry the short waves that lift the wire off the mass: the force is smooth, no loss is found, and nothing warns";
    let n40 = "1.25 m elements distort the reflected waves and add a spurious excitation at each node crossing: P_l is two to four times the converged value, and nothing warns";
    let n1e4 = "5 mm elements and 20 000 unknowns raise no difficulty over the ramp (no loss), and agree with the bundled mesh";
    for (n, expect, why) in [
        ("4", [SilentlyWrong; 4], [n4; 4]),
        (
            "40",
            [SilentlyWrong, SilentlyWrong, SilentlyWrong, Marginal],
            [
                n40,
                n40,
                n40,
                "the velocity-level law softens the spurious re-contacts, so P_l is less than twice the converged value; nothing warns",
            ],
        ),
    ] {
        cases.extend(all_forms(
            &format!("N = {n}"),
            "reference",
            &[format!("mesh.elements={n}")],
            &bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    cases.extend(all_forms(
        "N = 10⁴, t_end = 0.05 s",
        "reference",
        &with(&short, &["mesh.elements=10000"]),
        &bundled("reference", &short, ", t_end = 0.05 s"),
        [Accurate; 4],
        [n1e4; 4],
    ));
    cases.push(one(
        "N = 10⁴, whole run",
        "lagrange",
        "reference",
        sets(&["mesh.elements=10000", "contact.formulation=lagrange"]),
        bundled("reference", &none, ""),
        Accurate,
        "over the whole run the fine mesh confirms the bundled P_l and mean",
    ));
    cases.push(force_case(
        "moving force on a beam, N = 4",
        "moving_force_beam",
        &["mesh.elements=4"],
        Marginal,
        "four cubic elements still carry the quasi-static bulge under the load, to several per cent",
    ));
    cases.push(force_case(
        "moving force on a beam, N = 10⁴",
        "moving_force_beam",
        &["mesh.elements=10000"],
        Accurate,
        "the mesh error vanishes; what remains is the time error of Δt = 4e-4 s",
    ));
    out.push(Section {
        title: "Meshes from 4 to 10⁴ elements",
        intro: "N = 4 gives 12.5 m elements on the 50 m span; N = 10⁴ gives 5 mm elements and 20 000 unknowns. 10⁴ elements are run over the ramp (0.05 s) for every law, and once over the whole run with Lagrange.".into(),
        cases,
    });

    // 10. Penalty κ
    let mut cases = Vec::new();
    let kappas = [
        (
            "stiffness=1e2",
            "κ = 1e2 N/m",
            SilentlyWrong,
            "a penalty spring softer than the carrier spring (k = 987 N/m) lets the mass sink 11 cm into the wire, more than the preload, so the force is that of two springs in series, a tenth of the true one; only the reported max penetration betrays it",
        ),
        (
            "stiffness=1e4",
            "κ = 1e4 N/m",
            SilentlyWrong,
            "1 cm of penetration (a fifth of the preload) cushions every re-contact, removes all contact loss and lowers the mean; only the max penetration betrays it",
        ),
        (
            "stiffness=1e8",
            "κ = 1e8 N/m",
            Accurate,
            "κ is five times the contact's own stiffness 1/W ≈ 2e7 N/m, so the peaks soften but P_l and the mean hold",
        ),
        (
            "stiffness=1e12",
            "κ = 1e12 N/m",
            Accurate,
            "the penetration is 0.6 nm and the force Lagrange's to four digits",
        ),
        (
            "stiffness=1e16",
            "κ = 1e16 N/m",
            Accurate,
            "no ill-conditioning appears: for one contact the law only adds 1/κ = 1e-16 m/N to the scalar W ≈ 5e-8 m/N, and the penetration is λ/κ",
        ),
        (
            "relative=1e14",
            "relative ρ = 1e14 (κ = ρ/W)",
            Accurate,
            "1/κ = W/ρ changes W by 1e-14 of itself, so the run is Lagrange's to the digits shown",
        ),
    ];
    for (set, label, expect, why) in kappas {
        cases.push(one(
            label,
            "penalty",
            "reference",
            sets(&[
                "contact.formulation=penalty",
                &format!("contact.penalty.{set}"),
            ]),
            bundled("reference", &none, ""),
            expect,
            why,
        ));
    }
    out.push(Section {
        title: "Penalty stiffness κ from soft to ill-conditioned",
        intro: "W_cc ≈ 5e-8 m/N at the bundled resolution, so the contact's own stiffness 1/W is about 2e7 N/m. κ = 1e16 N/m and ρ = 1e14 are 1e9 and 1e14 times stiffer than that; κ = 1e2 N/m is softer than the carrier spring (k = 987 N/m).".into(),
        cases,
    });

    // 11. alpha placement
    let mut cases = Vec::new();
    let a_uni = "the α-level constraint leaves an undamped step-to-step gap mode that the moving contact point feeds, so the contact chatters (P_l ≈ 0.66–0.69 instead of 0.006), and the chatter warning says so";
    let a_imp = "the velocity-level law imposes ġ at t_{n+1}; `alpha` changes only its index set, so the answer stays that of `end`";
    let a_bil = "the undamped step-to-step mode grows without bound, and the message names the placement as the cause";
    for kind in ["unilateral", "bilateral"] {
        let physics = vec![format!("contact.kind={kind}")];
        let (expect, why) = if kind == "unilateral" {
            (
                [Flagged, Flagged, Flagged, Accurate],
                [a_uni, a_uni, a_uni, a_imp],
            )
        } else {
            (
                [Stopped, Stopped, Stopped, Accurate],
                [a_bil, a_bil, a_bil, a_imp],
            )
        };
        for ((form, expect), why) in FORMULATIONS.iter().zip(expect).zip(why) {
            let base = with(&physics, &[&format!("contact.formulation={form}")]);
            cases.push(one(
                &format!("alpha, {kind}, moving"),
                form,
                "reference",
                with(&base, &["contact.placement=alpha"]),
                Check::Run {
                    scene: "reference",
                    sets: base.clone(),
                    name: format!("the same {form} run with placement `end`"),
                    also: vec![("under a 1e-6 change of g", with(&base, &[PERTURBED_G]))],
                },
                expect,
                why,
            ));
        }
    }
    let t2 = sets(&["time.end=1.0", "contact.formulation=lagrange"]);
    cases.push(one(
        "alpha, unilateral, stationary (T2, 1 s)",
        "lagrange",
        "t2_stationary_mass",
        with(&t2, &["contact.placement=alpha"]),
        Check::Run {
            scene: "t2_stationary_mass",
            sets: t2.clone(),
            name: "the same run with placement `end`".into(),
            also: vec![("under a 1e-6 change of g", with(&t2, &[PERTURBED_G]))],
        },
        Accurate,
        "a standing carrier has r_f = r_g, so both placements impose the same condition",
    ));
    out.push(Section {
        title: "The `alpha` constraint placement with a moving carrier",
        intro: "`alpha` imposes the gap at t_{n+1−α_f}; with ρ∞ = 1 any gap error alternates in sign undamped, and a moving contact point feeds it ([numerics.md](numerics.md) §4). Each row is scored against the same formulation with placement `end`, so the column isolates the placement.".into(),
        cases,
    });
    out
}

// ---------------------------------------------------------------------------
// The page
// ---------------------------------------------------------------------------

fn outcome_cell(o: &Outcome) -> String {
    match o {
        Outcome::Rejected(_) => "rejected as invalid input".into(),
        Outcome::Stopped(_) => "stopped with a diagnosis".into(),
        Outcome::Ran(f) if f.warnings.is_empty() => "ran".into(),
        Outcome::Ran(f) => format!(
            "ran with {} warning{}",
            f.warnings.len(),
            if f.warnings.len() == 1 { "" } else { "s" }
        ),
    }
}

fn main() {
    let started = Instant::now();
    let sections = sections();
    let mut cache: HashMap<String, Outcome> = HashMap::new();
    let total: usize = sections.iter().map(|s| s.cases.len()).sum();
    let mut results: Vec<Vec<Row>> = Vec::new();
    let mut done = 0;
    for s in &sections {
        let mut rows = Vec::new();
        for case in &s.cases {
            let t = Instant::now();
            let row = score(case, &mut cache);
            done += 1;
            eprintln!(
                "[{done:3}/{total}] {:6.2} s  {}, {}: {}",
                t.elapsed().as_secs_f64(),
                case.label,
                case.form,
                row.verdict.text()
            );
            rows.push(row);
        }
        results.push(rows);
    }
    let elapsed = started.elapsed().as_secs_f64();
    let page = render(&sections, &results, cache.len());
    let path = format!("{}/docs/stability.md", env!("CARGO_MANIFEST_DIR"));
    std::fs::write(&path, page).unwrap_or_else(|e| panic!("{path}: {e}"));
    eprintln!(
        "wrote {path}: {total} rows and {} reference runs in {elapsed:.1} s",
        cache.len()
    );
}

/// Rows of one case in the findings: section, label, (row index, case, row).
type Group<'a> = (usize, &'a str, Vec<(usize, &'a Case, &'a Row)>);

/// List the rows with `verdict`, grouped by case (formulations together),
/// numbered from `first`; returns how many groups were listed.
fn findings(
    w: &mut String,
    sections: &[Section],
    results: &[Vec<Row>],
    verdict: Verdict,
    first: usize,
) -> usize {
    let mut groups: Vec<Group> = Vec::new();
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            if row.verdict != verdict {
                continue;
            }
            match groups
                .iter_mut()
                .find(|(gi, label, _)| *gi == i && *label == case.label)
            {
                Some(g) => g.2.push((j, case, row)),
                None => groups.push((i, case.label.as_str(), vec![(j, case, row)])),
            }
        }
    }
    for (n, (i, label, members)) in groups.iter().enumerate() {
        let (_, case, row) = members[0];
        let rows: Vec<String> = members
            .iter()
            .map(|(j, c, _)| match c.form {
                "—" => format!("{i}.{}", j + 1),
                form => format!("{i}.{} {form}", j + 1),
            })
            .collect();
        let _ = writeln!(
            w,
            "{}. **{label}** ({}; rows {}). {}: {}.\n\n   ```sh\n   {}\n   ```",
            first + n,
            sections[*i].title,
            rows.join(", "),
            row.what,
            case.why,
            command(case.scene, &case.sets)
        );
        if let Check::Run { scene, sets, .. } = &case.check {
            let _ = writeln!(
                w,
                "\n   Reference:\n\n   ```sh\n   {}\n   ```",
                command(scene, sets)
            );
        }
        let _ = writeln!(w);
    }
    groups.len()
}

fn render(sections: &[Section], results: &[Vec<Row>], references: usize) -> String {
    let mut w = String::new();
    let rows_total: usize = results.iter().map(Vec::len).sum();
    let _ = writeln!(w, "# Stability at the extremes\n");
    let _ = writeln!(
        w,
        "*This page is generated, in full, by*\n\n\
         ```sh\ncargo run --release --example stability_report\n```\n\n\
         *(`examples/stability_report.rs`; {rows_total} runs plus {references} reference runs, \
         one after another, a little over a minute on two cores). \
         Do not edit it by hand: change the example and run the command again.*\n"
    );
    let _ = writeln!(
        w,
        "Each row is one `taut run` of a bundled scene at an extreme parameter or resolution, \
         for each contact formulation where it makes sense (a moving force has no contact, \
         hence no formulation). The requirement: every run is either **accurate** or \
         **stopped with a diagnosis** (impossible input is **rejected**), never silently wrong. \
         The outcome is what the run returned: it ran, ran with warnings (quoted below the \
         table), stopped with a diagnosis (quoted), or was rejected as invalid input (quoted). \
         The verdict:\n"
    );
    let _ = writeln!(
        w,
        "| verdict | meaning |\n|---|---|\n\
         | accurate | ran without warning, and agrees with its reference within the tolerances |\n\
         | accurate, flagged | ran with a warning, yet agrees with its reference |\n\
         | inaccurate but flagged | ran with a warning, and the figures are indeed off |\n\
         | stopped | stopped with a diagnosis (`run diverged …` or `contact solve failed …`) |\n\
         | rejected | refused as invalid input, naming the field |\n\
         | marginal | ran without warning, outside the tolerance but not clearly wrong |\n\
         | *ill-determined* | ran without warning, but the case's P_l or mean is not determined to the tolerance even by its reference (it moves under refinement or a 1e-6 change of g) |\n\
         | **SILENTLY WRONG** | ran without warning, yet clearly off its reference (beyond the reference's own spread) |\n\
         | unchecked | ran without warning, with no reference to score it against |\n"
    );
    let _ = writeln!(
        w,
        "**References.** For an extreme of the physics (EI, T, V0) the reference is a Lagrange \
         run of the same physics two refinements finer (N = 1600, Δt = 2.5e-5 s); for m and k, \
         whose extremes put the carrier's own period at 0.2 ms, Lagrange at Δt = 1e-5 s; for an \
         extreme of the numerics (Δt, N, κ) the bundled reference case itself (Lagrange, \
         N = 400, Δt = 1e-4 s, same end time); for the `alpha` placement the same formulation \
         with placement `end`; for a moving force the analytic solution of MODEL §8.\n"
    );
    let _ = writeln!(
        w,
        "**Tolerances.** A run agrees when |ΔP_l| ≤ {PL_ABS} + {PL_REL}·P_l,ref and its mean \
         force is within {:.0} %; it is clearly wrong when |ΔP_l| exceeds twice that, when a \
         reference loss of at least {PL_ABS} is more than halved, or when the mean is off by more \
         than {:.0} % (both widened by the reference's own spread). The spread is how far the \
         reference's P_l and mean move under a 1e-6 change of g and, for the refined references, \
         one level coarser (N = 800, Δt = 5e-5 s; or Δt = 2e-5 s); a reference that moves \
         beyond the agreement tolerance makes its case *ill-determined*. A moving force agrees when max|w − w_a| under the force is within \
         {:.0} % of the deflection scale (the larger of max|w_a| and the static string \
         deflection F·L/(4T)), clearly wrong beyond {:.0} %. The peak force is shown but not \
         scored: re-contact peaks are not converged in Δt for any formulation even in the \
         bundled case ([formulations.md](formulations.md)), and the arrival at the far support \
         is an impact the model has no law for.\n",
        100.0 * MEAN_OK,
        100.0 * MEAN_BAD,
        100.0 * W_OK,
        100.0 * W_BAD
    );
    let _ = writeln!(
        w,
        "**Columns.** P_l: contact-loss fraction. λ mean, λ max: contact force, N, with the \
         x/L of the largest |λ|. pen.: largest penetration, m. sw.: contact switches. osc: \
         Σ|λ_{{n+1}} − λ_n| / Σ|λ_n|, the step-to-step change of the force relative to the \
         force. In the commands `taut` is `cargo run --release --`.\n"
    );

    // Findings
    let _ = writeln!(w, "## Findings\n");
    let wrong = findings(&mut w, sections, results, Verdict::SilentlyWrong, 1);
    if wrong == 0 {
        let _ = writeln!(
            w,
            "No run finished without warning while clearly off its reference.\n"
        );
    }
    let _ = writeln!(
        w,
        "**Not determined, and not flagged.** In these cases the Lagrange reference itself \
         moves beyond the tolerance under refinement or a 1e-6 change of g, so no single run \
         gives P_l or the mean force to the tolerance; the runs finish without a warning that \
         says so.\n"
    );
    let ill = findings(&mut w, sections, results, Verdict::IllDetermined, wrong + 1);
    if ill == 0 {
        let _ = writeln!(w, "None.\n");
    }
    let changed: Vec<String> = sections
        .iter()
        .zip(results)
        .enumerate()
        .flat_map(|(i, (s, rows))| {
            s.cases
                .iter()
                .zip(rows)
                .enumerate()
                .filter(|(_, (c, r))| c.expect != r.verdict)
                .map(move |(j, (c, r))| {
                    format!(
                        "- {i}.{} {}, {}: written for “{}”, now “{}”.",
                        j + 1,
                        c.label,
                        c.form,
                        c.expect.text(),
                        r.verdict.text()
                    )
                })
        })
        .collect();
    if !changed.is_empty() {
        let _ = writeln!(
            w,
            "**Changed since the explanations were written.** These rows' verdicts differ \
             from the ones their sentences explain; re-examine them:\n\n{}\n",
            changed.join("\n")
        );
    }

    // Summary
    let _ = writeln!(w, "## Summary\n");
    let order = [
        Accurate,
        AccurateFlagged,
        Flagged,
        Stopped,
        Rejected,
        Marginal,
        IllDetermined,
        SilentlyWrong,
        Unchecked,
    ];
    let _ = write!(w, "| extreme | rows |");
    for v in order {
        let _ = write!(w, " {} |", v.text());
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "|---|---|{}", "---|".repeat(order.len()));
    let mut totals = [0usize; 9];
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        let _ = write!(w, "| {i}. {} | {} |", s.title, rows.len());
        for (k, v) in order.iter().enumerate() {
            let n = rows.iter().filter(|r| r.verdict == *v).count();
            totals[k] += n;
            if n == 0 {
                let _ = write!(w, " |");
            } else {
                let _ = write!(w, " {n} |");
            }
        }
        let _ = writeln!(w);
    }
    let _ = write!(w, "| all | {rows_total} |");
    for t in totals {
        let _ = write!(w, " {t} |");
    }
    let _ = writeln!(w, "\n");

    // Sections
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        let _ = writeln!(w, "## {i}. {}\n", s.title);
        if !s.intro.is_empty() {
            let _ = writeln!(w, "{}\n", s.intro);
        }
        let _ = writeln!(
            w,
            "| # | case | formulation | outcome | P_l | λ mean | λ max (x/L) | pen. | sw. | osc | accuracy | verdict |\n\
             |---|---|---|---|---|---|---|---|---|---|---|---|"
        );
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            let figs = match &row.outcome {
                Outcome::Ran(f) if f.mass_carrier => format!(
                    "{:.4} | {} | {} ({:.3}) | {:.1e} | {} | {:.3}",
                    f.loss,
                    fmt_g(f.mean),
                    fmt_g(f.max),
                    f.max_at,
                    f.penetration,
                    f.switches,
                    f.osc
                ),
                _ => "— | — | — | — | — | —".into(),
            };
            let _ = writeln!(
                w,
                "| {i}.{} | {} | {} | {} | {figs} | {} | {} |",
                j + 1,
                case.label,
                case.form,
                outcome_cell(&row.outcome),
                row.accuracy,
                row.verdict.text()
            );
        }
        let _ = writeln!(w);
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            let mut sentence = row.what.clone();
            if !case.why.is_empty() {
                let _ = write!(sentence, ": {}", case.why);
            }
            let _ = writeln!(
                w,
                "- **{i}.{}** {}, {}. {}.  \n  `{}`",
                j + 1,
                case.label,
                case.form,
                sentence,
                command(case.scene, &case.sets)
            );
            if let Outcome::Ran(f) = &row.outcome {
                for m in &f.warnings {
                    let _ = writeln!(w, "  > warning: {m}");
                }
            }
        }
        let _ = writeln!(w);
    }
    w
}
