//! `taut replay`: a saved contact problem (`failed_contact_step_N.json`,
//! written by a failed run) solved again.

use std::path::PathBuf;

use crate::contact::{ContactProblem, ReplayOutcome, SIGNORINI_TOLERANCE};
use crate::error::{Error, Result};
use crate::scene::ComplementaritySolver;

/// A saved problem and what to change before solving it again.
#[derive(Debug, Clone)]
pub struct ReplayRequest {
    /// The saved problem (JSON).
    pub problem: PathBuf,
    /// Another iteration limit.
    pub max_iter: Option<u32>,
    /// Another complementarity solver.
    pub solver: Option<ComplementaritySolver>,
}

/// The problem as solved again.
pub struct Replay {
    /// The problem (with the request's changes).
    pub problem: ContactProblem,
    /// The forces and gaps, or why the solve failed.
    pub answer: Result<Solved>,
}

/// A solve that ended.
pub struct Solved {
    /// Forces and gaps.
    pub out: ReplayOutcome,
    /// The largest Signorini residual of the answer (relative), `None` for
    /// the penalty law (the gap closes only to λ/κ, by design); an error
    /// when it is above `SIGNORINI_TOLERANCE` (the answer is no solution).
    pub verdict: Result<Option<f64>>,
}

/// [`Solved::verdict`] of `out`.
fn verdict(out: &ReplayOutcome, path: &std::path::Path) -> Result<Option<f64>> {
    match out.violation {
        Some(v) if v > SIGNORINI_TOLERANCE => Err(Error::Replay {
            path: path.to_path_buf(),
            reason: format!(
                "the answer violates the contact conditions by {v:.3e} (relative; at most {SIGNORINI_TOLERANCE:e} is a solution)"
            ),
        }),
        v => Ok(v),
    }
}

/// Read, change and check the saved problem, and solve it again.
pub fn replay(req: &ReplayRequest) -> Result<Replay> {
    let path = &req.problem;
    let text = crate::input::read_text(
        path,
        "a saved contact problem",
        crate::input::MAX_REPLAY_BYTES,
    )?;
    crate::json_keys::reject_duplicate_keys(&text, path)?;
    if let Ok(not) = serde_json::from_str::<crate::contact::NotReplayable>(&text) {
        return Err(Error::Replay {
            path: path.clone(),
            reason: format!("not replayable: {}", not.not_replayable),
        });
    }
    let mut problem: ContactProblem = serde_json::from_str(&text)
        .map_err(|e| Error::parse(format!("{}: {e}", path.display())))?;
    if let Some(n) = req.max_iter {
        problem.contact.complementarity.max_iter = n;
    }
    if let Some(s) = req.solver {
        problem.contact.complementarity.solver = s;
    }
    crate::contact::validate(&problem)?;
    let answer = crate::contact::replay(&problem)
        .map(|out| Solved {
            verdict: verdict(&out, path),
            out,
        })
        .map_err(|f| Error::Replay {
            path: path.clone(),
            reason: f.to_string(),
        });
    Ok(Replay { problem, answer })
}
