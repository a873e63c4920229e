//! A contact problem as data: what a law was given when it failed, carried
//! by [`crate::Error::Contact`], saved as JSON next to the run's outputs,
//! and solved again by [`super::replay`] (`taut replay FILE`). Plain data,
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
