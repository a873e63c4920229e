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
    /// A refused combination (the method's or law's own error), or a
    /// measured share of the fixed variables above the dominance limit (the
    /// note gives it).
    Cannot,
    /// No expectation declared (a method of one's own without a formal
    /// order): reported.
    Reported,
    /// Declared to diverge (`Expect::Diverges`), and the error grows over
    /// the ladder as declared.
    Diverges,
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
            Status::Diverges => "diverges",
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
    /// the whole ratio).
    pub observed: f64,
    /// The expected (formal) order; NaN when none.
    pub expected: f64,
    /// Allowed |observed − expected|; NaN when none.
    pub tolerance: f64,
    /// The orders the finest pair was allowed (least, largest): the
    /// expectation's band widened by the shift the measured share can
    /// cause (`judge.rs`); NaN when none is judged.
    pub allowed: (f64, f64),
    /// A `known` row's bound on the finest error relative to the exact
    /// solution's largest value; NaN otherwise.
    pub error_bound: f64,
    /// The range of the refined variable the expectation is declared over
    /// (the ladder's coarsest and finest values).
    pub range: (f64, f64),
    /// Share of the finest error made by the fixed variables (module docs).
    pub other_share: f64,
    /// Penalty only: the share of the finest error made by the penalty's
    /// compliance, |e − e_κ|/e with e_κ the finest level's error at
    /// `PENALTY_STIFFEN` times κ; `None` where the law has no compliance
    /// (the share is not measured, and nothing is judged on it), NaN where
    /// its run failed (the judge then fails the row).
    pub penalty_share: Option<f64>,
    /// The share of the whole run's finest error made at the start,
    /// t ≤ `START_WINDOW` (|e − e_after|/e); NaN unless the row is
    /// judged after the start (`Expect::AfterStart`).
    pub start_share: f64,
    /// With a prescribed loss: the share of the finest error made from the
    /// loss's blend on (|e − e_before|/e); NaN otherwise.
    pub loss_share: f64,
    /// Loss intervals of each level's run (contact cases), for a note on
    /// bouncing reattachments.
    pub loss_intervals: Vec<usize>,
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

impl VerifyRow {
    /// A row with nothing measured yet: its names — case, method,
    /// discretization, formulation, supports, variable, quantity, in that
    /// order — a status and a note; every measure NaN or empty.
    pub(crate) fn unmeasured(names: [String; 7], status: Status, note: String) -> VerifyRow {
        let [
            case,
            method,
            discretization,
            formulation,
            supports,
            variable,
            quantity,
        ] = names;
        VerifyRow {
            case,
            method,
            discretization,
            formulation,
            supports,
            variable,
            quantity,
            levels: Vec::new(),
            errors: Vec::new(),
            relative_error: f64::NAN,
            orders: Vec::new(),
            observed: f64::NAN,
            expected: f64::NAN,
            tolerance: f64::NAN,
            allowed: (f64::NAN, f64::NAN),
            error_bound: f64::NAN,
            range: (f64::NAN, f64::NAN),
            other_share: f64::NAN,
            penalty_share: None,
            start_share: f64::NAN,
            loss_share: f64::NAN,
            loss_intervals: Vec::new(),
            omega_max_dt: f64::NAN,
            status,
            note,
            runs: 0,
            wall_seconds: 0.0,
        }
    }
}

/// True when any row failed.
pub fn any_failed(rows: &[VerifyRow]) -> bool {
    rows.iter().any(|r| r.status == Status::Fail)
}
