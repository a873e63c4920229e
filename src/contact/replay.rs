//! Solving a saved [`ContactProblem`] again (`taut replay FILE`): the file
//! checked field by field, the law it names applied, and the answer checked
//! against the Signorini conditions.

use super::problem::{ContactProblem, Level};
use super::{ContactFailure, law_for};
use crate::error::{Error, Result};
use crate::scene::{ContactKind, Formulation};

/// Most contacts a saved problem may have: W has nc² entries, and no scene
/// has more than a few carriers (a larger file is not one taut wrote).
pub(crate) const MAX_REPLAY_CONTACTS: usize = 1024;

/// Signorini residual above which a replayed answer is reported as not a
/// contact solution: relative to the problem's gap and force scales, far
/// above round-off (1e-16) and the QP tolerance (1e-12 by default; at most
/// 1e-2 is accepted, so a loosened QP can exceed it and is then reported).
pub(crate) const SIGNORINI_TOLERANCE: f64 = 1e-6;

/// The answer to a replayed problem.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayOutcome {
    /// Multipliers: N (position, acceleration level) or N·s (velocity).
    pub lambda: Vec<f64>,
    /// Gaps after the solve, g = g_free + Wλ.
    pub gap: Vec<f64>,
    /// Which contacts the law closed.
    pub active: Vec<bool>,
    /// Largest Signorini residual (relative; see `SIGNORINI_TOLERANCE`),
    /// or `None` for the penalty law, which lets the gap close only to λ/κ
    /// by design.
    pub violation: Option<f64>,
}

/// Check a problem read from a file: sizes, finite numbers, settings.
pub(crate) fn validate(problem: &ContactProblem) -> Result<()> {
    problem.check()
}

impl ContactProblem {
    fn check(&self) -> Result<()> {
        let n = self.g_free.len();
        if n == 0 || n > MAX_REPLAY_CONTACTS {
            return Err(Error::invalid(
                "g_free",
                format!("{n} entries"),
                format!("must have 1 ..= {MAX_REPLAY_CONTACTS} entries, one per contact"),
            ));
        }
        if self.w.len() != n * n {
            return Err(Error::invalid(
                "w",
                format!("{} entries", self.w.len()),
                format!("must have nc² = {} entries (row-major, nc = {n})", n * n),
            ));
        }
        for (name, v) in [("g_free", &self.g_free), ("w", &self.w)] {
            if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(Error::invalid(
                    format!("{name}.{i}"),
                    x,
                    "must be a finite number",
                ));
            }
        }
        crate::scene::validate_contact(&self.contact)
    }
}

/// Solve a saved problem again (after `ContactProblem::validate`) with the
/// law it names, and check the answer.
pub(crate) fn replay(
    problem: &ContactProblem,
) -> std::result::Result<ReplayOutcome, ContactFailure> {
    let n = problem.g_free.len();
    let mut law = law_for(&problem.contact, n);
    let mut lambda = vec![0.0; n];
    let mut active = vec![false; n];
    let (g, w) = (&problem.g_free, &problem.w);
    match problem.level {
        Level::Acceleration => law.initial(g, w, &mut lambda, &mut active)?,
        Level::Position | Level::Velocity => law.solve(g, w, &mut lambda, &mut active)?,
    }
    let gap: Vec<f64> = (0..n)
        .map(|i| g[i] + (0..n).map(|j| w[i * n + j] * lambda[j]).sum::<f64>())
        .collect();
    let violation = (problem.contact.formulation != Formulation::Penalty).then(|| {
        let g0 = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let w0 = (0..n).fold(0.0f64, |m, c| m.max(w[c * n + c].abs()));
        let l0 = if w0 > 0.0 { g0 / w0 } else { 0.0 };
        let rel = |x: f64, s: f64| if s > 0.0 { x / s } else { x.abs() };
        let bilateral = problem.contact.kind == ContactKind::Bilateral;
        (0..n)
            .map(|c| {
                if bilateral {
                    rel(gap[c].abs(), g0)
                } else {
                    rel((-gap[c]).max(0.0), g0)
                        .max(rel((-lambda[c]).max(0.0), l0))
                        .max(rel((gap[c] * lambda[c]).abs(), g0 * l0))
                }
            })
            .fold(0.0f64, f64::max)
    });
    // an overflowing force is no answer, whatever the law says
    if let Some((c, &l)) = lambda.iter().enumerate().find(|(_, l)| !l.is_finite()) {
        return Err(ContactFailure::NotFinite {
            contact: c,
            lambda: l,
            w: w[c * n + c],
        });
    }
    Ok(ReplayOutcome {
        lambda,
        gap,
        active,
        violation: violation.map(|v| if v.is_nan() { f64::INFINITY } else { v }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ComplementaritySolver, ComplementaritySpec, ContactSpec};

    fn problem(formulation: Formulation, g: Vec<f64>, w: Vec<f64>) -> ContactProblem {
        ContactProblem {
            level: Level::Position,
            g_free: g,
            w,
            contact: ContactSpec {
                formulation,
                ..ContactSpec::default()
            },
        }
    }

    #[test]
    fn a_lagrange_problem_replays_exactly() {
        let p = problem(Formulation::Lagrange, vec![-3e-7], vec![5e-9]);
        validate(&p).unwrap();
        let out = replay(&p).unwrap();
        assert!((out.lambda[0] - 60.0).abs() < 1e-12);
        assert!(out.violation.unwrap() < SIGNORINI_TOLERANCE);
    }

    #[test]
    fn a_failing_qp_is_kept_and_solves_with_a_sane_limit() {
        let mut p = problem(Formulation::Complementarity, vec![-3e-7], vec![5e-9]);
        p.contact.complementarity = ComplementaritySpec {
            solver: ComplementaritySolver::Clarabel,
            max_iter: 1,
            ..ComplementaritySpec::default()
        };
        let err = replay(&p).unwrap_err();
        assert!(matches!(err, ContactFailure::Solver { .. }), "{err}");
        let json = serde_json::to_string(&p).unwrap();
        let mut back: ContactProblem = serde_json::from_str(&json).unwrap();
        assert_eq!(back, p);
        back.contact.complementarity.max_iter = 100;
        let out = replay(&back).unwrap();
        assert!((out.lambda[0] - 60.0).abs() < 1e-6);
        // and the direct solver answers it exactly
        back.contact.complementarity.solver = ComplementaritySolver::Direct;
        let out = replay(&back).unwrap();
        assert!((out.lambda[0] - 60.0).abs() < 1e-12);
    }

    #[test]
    fn bad_files_are_refused_by_field() {
        let p = problem(Formulation::Lagrange, vec![-1.0, 2.0], vec![1.0; 3]);
        assert!(validate(&p).unwrap_err().to_string().contains("`w`"));
        let p = problem(Formulation::Lagrange, vec![f64::NAN], vec![1.0]);
        assert!(validate(&p).unwrap_err().to_string().contains("g_free.0"));
        let mut p = problem(Formulation::Complementarity, vec![-1.0], vec![1.0]);
        p.contact.complementarity.tol_feas = 0.5;
        assert!(validate(&p).unwrap_err().to_string().contains("tol_feas"));
        let unknown = r#"{"level":"position","g_free":[-1],"w":[1],"contact":{},"extra":1}"#;
        assert!(serde_json::from_str::<ContactProblem>(unknown).is_err());
    }

    #[test]
    fn a_tiny_delassus_number_is_no_answer() {
        // λ = 59/1e-308 overflows: reported, not printed as a force
        let p = problem(Formulation::Lagrange, vec![-59.0], vec![1e-308]);
        validate(&p).unwrap();
        assert!(replay(&p).is_err());
        // the QP path scales the problem, and refuses the overflow too
        let p = problem(Formulation::Complementarity, vec![-59.0], vec![1e-308]);
        let err = replay(&p).unwrap_err();
        assert!(matches!(err, ContactFailure::NotFinite { .. }), "{err}");
    }
}
