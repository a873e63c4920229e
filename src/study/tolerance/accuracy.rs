//! What an accuracy-targeted run returns (`accuracy` in `summary.json`,
//! `accuracy.csv`), made from the one-point sweep's record and detail, or
//! the refusal of a point that did not reach its tolerance.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::RunOutput;
use crate::study::sweep::{Detail, PointAccuracy, SweepRecord, SweepTolerance};

/// The u_num of one result of the reported run, from its own family.
#[derive(Debug, Clone, Serialize)]
pub struct ResultEstimate {
    /// The quantity's name (a column of `sweep.csv`).
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// The reported run's value (null when undefined, e.g. no loss).
    pub value: Option<f64>,
    /// Its u_num (null when none could be given).
    pub u_num: Option<f64>,
    /// The estimator (`gci`, `least_squares`, `exact`, …).
    pub estimator: &'static str,
    /// How the family's values behave (`monotone`, `scattered`, …).
    pub behaviour: &'static str,
}

/// Everything an accuracy-targeted run adds to `summary.json` (`accuracy`).
#[derive(Debug, Clone, Serialize)]
pub struct Accuracy {
    /// The quantity the tolerance is on.
    pub quantity: &'static str,
    /// Its unit (the tolerance's and u_num's).
    pub unit: &'static str,
    /// What it is.
    pub definition: &'static str,
    /// The requested tolerance EPS, absolute, in the quantity's unit.
    pub tolerance: f64,
    /// The budget: the most the run may cost, pilots included, as a
    /// multiple of the scene's own run (`--max-cost`).
    pub max_cost: f64,
    /// What the point reached: exactly a sweep point's accuracy (value,
    /// u_num, resolution, runs, estimator, every run made as the rows of
    /// `accuracy.csv`, …).
    #[serde(flatten)]
    pub point: PointAccuracy,
    /// Steps of the reported run.
    pub steps: usize,
    /// A u_num on every result a sweep can target, at the reported run.
    pub results: Vec<ResultEstimate>,
}

/// A finished accuracy-targeted run.
pub struct TolerantRun {
    /// The reported run's scene (N, J, Δt set).
    pub scene: Resolved,
    /// Its run.
    pub output: RunOutput,
    /// How it was reached and how accurate its results are.
    pub accuracy: Accuracy,
}

/// The run from the one-point sweep's record and detail; the point's error
/// when a run stopped it, and a refusal when it did not reach EPS.
pub(super) fn tolerant_run(
    tol: &SweepTolerance,
    record: SweepRecord,
    detail: Detail,
) -> Result<TolerantRun> {
    if let Some(e) = detail.error {
        return Err(e);
    }
    let q = crate::study::uncertainty::quantity::quantity(&tol.quantity)
        .expect("a target checked by SweepTolerance::new");
    let point = record
        .accuracy
        .expect("a finished point of an accuracy-targeted sweep has its accuracy");
    if !point.met {
        return Err(refusal(tol, &point, &detail));
    }
    let (scene, output) = detail.chosen.expect("a point met keeps its reported run");
    let results = detail
        .results
        .iter()
        .map(|(q, a)| ResultEstimate {
            name: q.name,
            unit: q.unit,
            value: a.value,
            u_num: a.u_num,
            estimator: a.estimator.name(),
            behaviour: a.behaviour.name(),
        })
        .collect();
    let accuracy = Accuracy {
        quantity: q.name,
        unit: q.unit,
        definition: q.definition,
        tolerance: tol.tolerance,
        max_cost: tol.budget,
        steps: output.steps,
        results,
        point,
    };
    Ok(TolerantRun {
        scene,
        output,
        accuracy,
    })
}

/// The refusal of a point that did not reach EPS: the quantity, the
/// tolerance, why the point stopped (the sweep's `not_met_because`) and
/// the smallest u_num it reached, where.
fn refusal(tol: &SweepTolerance, p: &PointAccuracy, detail: &Detail) -> Error {
    let why = p
        .not_met
        .clone()
        .unwrap_or_else(|| "no candidate reached it".to_string());
    let (sym, level) = match p.modes {
        Some(j) => ("J", j),
        None => ("N", p.elements),
    };
    let best = if p.u_num.is_finite() {
        format!("the smallest u_num reached is {:.3e}", p.u_num)
    } else {
        let how = detail
            .results
            .iter()
            .find(|(q, _)| q.name == tol.quantity)
            .map_or("", |(_, a)| a.behaviour.name());
        format!("no u_num could be given (the family's values are {how})")
    };
    let own = p.dof_steps
        / p.runs_made
            .iter()
            .find(|r| (r.mesh_exponent, r.step_exponent) == (0, 0))
            .map_or(f64::NAN, |r| r.dof_steps);
    Error::Tolerance {
        quantity: tol.quantity.clone(),
        tolerance: tol.tolerance,
        reason: format!(
            "not met: {why}; {best}, at {sym} = {level}, Δt = {:e} s (value {:.4e}), after {} runs costing {own:.1}× the scene's own run. The same point of `taut sweep --tolerance` is marked tolerance_met = no for this reason. Ask for a looser tolerance, give a larger --max-cost (now {}), or start from a finer scene (--set time.step=…, mesh.elements or mesh.modes)",
            p.dt, p.value, p.runs, tol.budget
        ),
    }
}
