//! What a case of the stability report (`out/xtask/stability.md`) is, how it runs, and how its outcome
//! is scored against its reference (imports shared by the report).

pub(super) use std::collections::HashMap;
pub(super) use std::fmt::Write as _;
pub(super) use std::time::Instant;

pub(super) use taut::error::Error;
pub(super) use taut::resolve::{Resolved, resolve_scene};
pub(super) use taut::run::{RunOutput, run};
pub(super) use taut::scene::CarrierKind;
pub(super) use taut::study::reference::analytic_w;

pub(super) const FORMULATIONS: [&str; 4] = ["lagrange", "penalty", "complementarity", "impact"];

/// P_l agrees with its reference when |ΔP_l| ≤ PL_ABS + PL_REL·P_l,ref. It is
/// clearly wrong when |ΔP_l| > 2·(PL_ABS + PL_REL·P_l,ref), or when a
/// reference loss of at least PL_ABS is more than halved.
pub(super) const PL_ABS: f64 = 0.002;
pub(super) const PL_REL: f64 = 0.25;
/// The mean contact force agrees within MEAN_OK of its reference and is
/// clearly wrong beyond MEAN_BAD.
pub(super) const MEAN_OK: f64 = 0.02;
pub(super) const MEAN_BAD: f64 = 0.05;
/// The displacement under a moving force agrees with the analytic solution
/// when max|w − w_a| ≤ W_OK of the deflection scale; clearly wrong beyond W_BAD.
pub(super) const W_OK: f64 = 0.05;
pub(super) const W_BAD: f64 = 0.10;
/// Largest number of samples at which an analytic reference is evaluated
/// (the series of a nearly flexible beam costs milliseconds per point).
pub(super) const ANALYTIC_SAMPLES: usize = 400;

/// What a row is scored against.
#[derive(Clone)]
pub(super) enum Check {
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
pub(super) enum Agreement {
    Good,
    Marginal,
    Bad,
}

/// The verdict of a row.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Verdict {
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
    pub(super) fn text(self) -> &'static str {
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
pub(super) struct Case {
    pub(super) label: String,
    /// The contact formulation, or "—" for a moving force (no contact).
    pub(super) form: &'static str,
    pub(super) scene: &'static str,
    pub(super) sets: Vec<String>,
    pub(super) check: Check,
    /// The verdict found when the explanation was written; a change is listed.
    pub(super) expect: Verdict,
    /// Why it happens: the second half of the row's sentence.
    pub(super) why: String,
}

/// A group of rows under one heading.
pub(super) struct Section {
    pub(super) title: &'static str,
    pub(super) intro: String,
    pub(super) cases: Vec<Case>,
}

/// Figures of a finished run (carrier 0).
#[derive(Clone)]
pub(super) struct Figures {
    pub(super) loss: f64,
    pub(super) mean: f64,
    pub(super) max: f64,
    /// x/L of the largest |λ|.
    pub(super) max_at: f64,
    pub(super) penetration: f64,
    pub(super) switches: usize,
    /// Σ|λ_{n+1} − λ_n| / Σ|λ_n| over the steps.
    pub(super) osc: f64,
    pub(super) warnings: Vec<String>,
    /// (max|w − w_a| / scale, max|w − w_a| in m, scale in m) for a moving force.
    pub(super) w_err: Option<(f64, f64, f64)>,
    pub(super) mass_carrier: bool,
}

/// What happened to a row.
#[derive(Clone)]
pub(super) enum Outcome {
    Rejected(String),
    Stopped(String),
    Ran(Box<Figures>),
}

pub(super) fn scene_text(scene: &str) -> String {
    let path = format!("{}/scenes/{scene}.toml", crate::ROOT);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The error of the displacement under a moving force against MODEL §8,
/// relative to the larger of the analytic max|w| under the force and the
/// static midspan deflection of a string, F·L/(4T) (under a supersonic force
/// on a string the exact deflection under the force is zero).
pub(super) fn analytic_error(sc: &Resolved, out: &RunOutput) -> Option<(f64, f64, f64)> {
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

pub(super) fn figures(sc: &Resolved, out: &RunOutput, analytic: bool) -> Figures {
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

pub(super) fn execute(scene: &str, sets: &[String], analytic: bool) -> Outcome {
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
pub(super) fn command(scene: &str, sets: &[String]) -> String {
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

pub(super) fn fmt_g(x: f64) -> String {
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
pub(super) struct Row {
    pub(super) outcome: Outcome,
    pub(super) verdict: Verdict,
    /// Short accuracy figure for the table.
    pub(super) accuracy: String,
    /// The automatic half of the sentence: what happened.
    pub(super) what: String,
}

pub(super) fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b.abs().max(f64::MIN_POSITIVE)
}

/// How the reference's own P_l and mean move across its `also` runs:
/// (largest |ΔP_l|, largest relative |Δmean|).
pub(super) fn spread(r: &Figures, also: &[(&str, Figures)]) -> (f64, f64) {
    also.iter().fold((0.0f64, 0.0f64), |(p, m), (_, a)| {
        (
            p.max((a.loss - r.loss).abs()),
            m.max(rel(a.mean, r.mean).abs()),
        )
    })
}

/// "by ΔP_l and Δmean % under X, and … under Y".
pub(super) fn spread_text(r: &Figures, also: &[(&str, Figures)]) -> String {
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
pub(super) fn determined(r: &Figures, (sp, sm): (f64, f64)) -> bool {
    sp <= PL_ABS + PL_REL * r.loss && sm <= MEAN_OK
}

/// Agreement of a run with a reference whose own spread is `(sp, sm)`: the
/// spread widens the "clearly wrong" bounds only.
pub(super) fn agreement_with_run(f: &Figures, r: &Figures, (sp, sm): (f64, f64)) -> Agreement {
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

pub(super) fn score(case: &Case, cache: &mut HashMap<String, Outcome>) -> Row {
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
