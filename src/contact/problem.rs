//! A contact problem as data: what a law was given when it failed, carried
//! by [`crate::Error::Contact`], saved as JSON next to the run's outputs,
//! and solved again by `super::replay` (`taut replay FILE`). Plain data,
//! so that the error type can carry it without depending on the laws.

use serde::{Deserialize, Serialize};

use crate::scene::ContactSpec;

/// What the numbers of a problem are.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// Gap accelerations (m/s²) and W in 1/kg: the initial problem at t = 0.
    Acceleration,
    /// Gaps (m) and W in m/N: force-level laws during a run.
    Position,
    /// Gap rates (m/s) and W in m/(N·s): velocity-level laws (impact,
    /// Moreau–Jean); the multipliers are impulses (N·s) for Moreau–Jean.
    Velocity,
}

/// One step's contact problem: find λ from `g = g_free + W λ` by the law of
/// `contact`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ContactProblem {
    /// The units of `g_free` and `w`.
    pub level: Level,
    /// Free gaps (units by `level`).
    pub g_free: Vec<f64>,
    /// Delassus matrix, row-major, `w[i·nc + j]` = ∂g_i/∂λ_j.
    pub w: Vec<f64>,
    /// The contact settings: kind, formulation and its parameters.
    pub contact: ContactSpec,
}

impl ContactProblem {
    /// The first value that is not a finite number, as `name.index = value`
    /// (`None` when every value is finite). JSON has no NaN or infinity:
    /// such a problem written as it is reads back with nulls that no
    /// replay can take.
    pub fn first_non_finite(&self) -> Option<String> {
        [("g_free", &self.g_free), ("w", &self.w)]
            .into_iter()
            .find_map(|(name, v)| {
                v.iter()
                    .position(|x| !x.is_finite())
                    .map(|i| format!("{name}.{i} = {}", v[i]))
            })
    }
}

/// What is saved as `failed_contact_step_N.json` in place of a problem that
/// cannot be solved again (one whose numbers are not all finite, which
/// JSON cannot hold): why, and what the problem was. `taut replay` of it
/// says why rather than failing to read it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct NotReplayable {
    /// Why the problem is not saved to be solved again.
    pub not_replayable: String,
    /// The units the problem's numbers were in.
    pub level: Level,
    /// Its rows (contacts, and slack droppers' rows).
    pub rows: usize,
    /// The contact settings it was given.
    pub contact: ContactSpec,
}

impl NotReplayable {
    /// The record of `p`, when `p` cannot be replayed (a non-finite value).
    pub fn of(p: &ContactProblem) -> Option<Self> {
        p.first_non_finite().map(|what| NotReplayable {
            not_replayable: format!(
                "the problem holds a value that is not a finite number ({what}): the run's state had already left the finite numbers when its contact solve failed (it diverged, or a matrix was singular), so there is no problem to solve again; the run's error names the step, and a smaller time step or a stiffer or softer element named there is where to look"
            ),
            level: p.level,
            rows: p.g_free.len(),
            contact: p.contact.clone(),
        })
    }
}
