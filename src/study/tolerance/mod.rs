//! Accuracy-targeted runs: `taut run SCENE --tolerance EPS [--quantity Q]
//! [--max-cost F]`.
//!
//! One engine for every accuracy target: the scene is refined as the one
//! point of an accuracy-targeted sweep ([`crate::study::sweep`]'s
//! `refine_alone`), with the same pilots, checks, budget and uncertainty
//! estimators ([`crate::study::uncertainty::assess()`]) as each point of
//! `taut sweep --tolerance`. So a scene run alone and the same point of a
//! sweep get the same resolution, value and u_num, and what one refuses
//! the other marks not met for the same stated reason
//! (docs/accuracy.md, docs/sweeps.md#accuracy-targeted-sweeps---tolerance).
//!
//! What a run adds to the sweep's record: the reported run's own outputs
//! (history, summary, plots), every run the point made (`accuracy.csv`),
//! and a u_num on every result the sweep can target, each assessed on the
//! reported run's own family of runs. A point that does not reach EPS is
//! refused ([`crate::Error::Tolerance`]) naming the quantity, the
//! tolerance, why it stopped and the best u_num it reached.
//!
//! `error_model` is the mesh-plus-step model the sweep's plan and its
//! predictions use ([`ErrorModel::cheapest`]).

mod accuracy;
mod error_model;

pub use crate::study::filter::{FORCE_BAND_HZ, design_cutoff_hz, lowpass_zero_phase};
pub use accuracy::{Accuracy, ResultEstimate, TolerantRun};
pub use error_model::{ErrorModel, Estimate, LadderFit, LadderStatus};

use crate::error::{Error, Result};
use crate::quantity::Quantity;
use crate::resolve::resolve_scene;
use crate::study::cost::{MAX_DOF_STEPS, run_dof_steps};
use crate::study::sweep::{SweepTolerance, check_level, refine_alone, targets};

/// The pilots' work as a multiple of the scene's own run: the family
/// (−2, −2), (−1, −1), (0, 0) and its split (−1, −2), (0, −1) of the
/// accuracy-targeted sweep, 1/16 + 1/4 + 1 + 1/8 + 1/2 = 1.94 at most
/// (1.81 with the coarse runs' fewer unknowns, as the sweep's estimate
/// counts them).
const PILOT_SHARE: f64 = 1.81;

/// The results a tolerance run gives a u_num: those a sweep can target.
pub fn results() -> Vec<&'static Quantity> {
    targets()
}

/// Check what [`tolerance_run`] checks before its first run (the scene with
/// its overrides, its level parameter, the pilots' cost), running nothing:
/// a command refuses bad input before it claims its output folder.
pub fn check_start(text: &str, overrides: &[String], tol: &SweepTolerance) -> Result<()> {
    let sc = resolve_scene(text, overrides)?;
    check_level(&sc)?;
    let pilots = PILOT_SHARE * run_dof_steps(&sc);
    // a NaN cost is refused too
    if pilots.is_nan() || pilots > MAX_DOF_STEPS {
        return Err(Error::Tolerance {
            quantity: tol.quantity.clone(),
            tolerance: tol.tolerance,
            reason: format!(
                "the pilot runs alone need {pilots:.2e} DOF-steps ({PILOT_SHARE} × the scene's own run), above the limit of {MAX_DOF_STEPS:e}: start from a coarser mesh or step (--set mesh.elements=… --set time.step=…)"
            ),
        });
    }
    Ok(())
}

/// Run the scene at the resolution whose u_num of the tolerance's quantity
/// is within its EPS: the one point of an accuracy-targeted sweep.
/// `progress(done, total)`: 0 of 1 at the start, 1 of 1 at the end.
pub fn tolerance_run(
    text: &str,
    overrides: &[String],
    tol: &SweepTolerance,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<TolerantRun> {
    check_start(text, overrides, tol)?;
    progress(0, 1);
    let (record, detail) = refine_alone(text, overrides, tol.clone())?;
    let r = accuracy::tolerant_run(tol, record, detail)?;
    progress(1, 1);
    Ok(r)
}
