//! The rows of `verify.csv`: a ladder's quantity under one combination,
//! and its status.

use serde::Serialize;
/// A combination's row status.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Observed order within tolerance, refined variable dominant.
    Pass,
    /// Outside tolerance, not dominant, or a run failed.
    Fail,
    /// A known deviation, reported (not failed).
    Known,
    /// Cannot show an order in this variable (the note says why).
    Cannot,
    /// No expectation declared: reported.
    Reported,
}

impl Status {
    /// `pass`, `fail`, `known`, `cannot`, `reported`.
    pub fn name(self) -> &'static str {
        match self {
            Status::Pass => "pass",
            Status::Fail => "fail",
            Status::Known => "known",
            Status::Cannot => "cannot",
            Status::Reported => "reported",
        }
    }
}

/// One row of `verify.csv`: a ladder's quantity under one combination.
#[derive(Debug, Clone, Serialize)]
pub struct VerifyRow {
    /// Case name.
    pub case: String,
    /// Method.
    pub method: String,
    /// Discretization (`string` for string elements).
    pub discretization: String,
    /// Contact formulation (`none` for a case without contact).
    pub formulation: String,
    /// Supports, `left-right`.
    pub supports: String,
    /// Refined variable: `h`, `dt`, `J`.
    pub variable: String,
    /// `displacement` or `force`.
    pub quantity: String,
    /// The refined variable's value per level: h (m), Δt (s) or J.
    pub levels: Vec<f64>,
    /// Absolute error per level (m or N).
    pub errors: Vec<f64>,
    /// The finest error relative to the exact solution's largest value.
    pub relative_error: f64,
    /// Orders between successive levels (`observed_order`).
    pub orders: Vec<f64>,
    /// The ladder's order, first to last level (`observed_order` over
    /// the whole ratio): what the expectation is checked against.
    pub observed: f64,
    /// The expected (formal) order; NaN when none.
    pub expected: f64,
    /// Allowed |observed − expected|; NaN when none.
    pub tolerance: f64,
    /// The range of the refined variable the expectation is declared over
    /// (the ladder's coarsest and finest values).
    pub range: (f64, f64),
    /// Share of the finest error made by the fixed variables (module docs).
    pub other_share: f64,
    /// ω_max·Δt at the finest level.
    pub omega_max_dt: f64,
    /// Status.
    pub status: Status,
    /// Why, for anything but a pass.
    pub note: String,
    /// Runs made for this ladder (levels and the dominance run).
    pub runs: usize,
    /// Their wall time, s.
    pub wall_seconds: f64,
}

/// True when any row failed.
pub fn any_failed(rows: &[VerifyRow]) -> bool {
    rows.iter().any(|r| r.status == Status::Fail)
}
