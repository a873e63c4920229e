//! Accuracy-targeted runs: `taut run SCENE --tolerance TOL [--quantity Q]`.
//!
//! Instead of running at the scene's (N, Δt), measure how the chosen
//! quantity converges, pick the cheapest (N, Δt) whose estimated error is
//! within `TOL`, run there, and report an estimated error next to every
//! result. One step a file:
//!
//! 1. `pilots`: five runs from the scene's (N₀, Δt₀), the mesh ladder N₀,
//!    2N₀, 4N₀ (modes J on a `galerkin` or `modal` basis) and the step ladder
//!    Δt₀/2, Δt₀/4, on one time grid (as [`crate::study::converge`] does);
//! 2. `fit`: e(h, Δt) ≈ F_s (C_h h^p + C_t Δt^q) from the ladders' successive
//!    differences (`error_model`); a ladder that does not fall at order ≥
//!    `MIN_ORDER` stops the run with an error naming the quantity and another
//!    to try: nothing is extrapolated from a quantity that does not converge;
//! 3. `choose`: the cheapest pilot already within the tolerance, or the
//!    model's cheapest (h, Δt) ([`ErrorModel::cheapest`]), refused above
//!    `MAX_DOF_STEPS`;
//! 4. `results`: every scalar result gets its own ladder fits and an
//!    estimated error at the chosen resolution, or "not converging".
//!
//! [`Quantity`]: `force` (default) is carrier 0's contact force low-pass
//! filtered to 0–20 Hz, as railway practice evaluates it (EN 50317/50318):
//! the raw force does not converge in Δt once contact is lost and re-made
//! (re-contact spikes grow as Δt falls), its impulse does. `force_raw`,
//! `loss_fraction` and `displacement` are the alternatives. Beside the steps:
//! `quantity`, `limits`, `accuracy` (what the run returns), `refusal`.

mod accuracy;
mod choose;
mod error_model;
mod fit;
mod limits;
mod pilots;
mod quantity;
mod refusal;
mod results;

pub use crate::study::filter::{FORCE_BAND_HZ, design_cutoff_hz, lowpass_zero_phase};
pub use accuracy::{Accuracy, PilotRun, ResultEstimate, TolerantRun};
pub use error_model::{ErrorModel, Estimate, LadderFit, LadderStatus};
pub(crate) use limits::parse_tolerance;
pub use quantity::{Quantity, quantity_difference};
pub use results::{result_values, results};

use crate::error::Result;
use choose::{Chosen, choose};
use fit::{Fit, fit_model};
use limits::check_tolerance;
use pilots::{RUNS, Start, run_pilots};
use results::estimate_results;

/// Largest run (unknowns × steps) an accuracy-targeted run will start, pilots
/// included: the bound every study shares ([`super::cost::MAX_DOF_STEPS`]).
/// Beyond it the tool says what the tolerance would take instead of starting
/// a run nobody waits for.
pub(crate) use super::cost::MAX_DOF_STEPS;

/// Check what [`tolerance_run`] checks before its first run (the
/// tolerance, the scene with its overrides), running nothing: a command
/// refuses bad input before it claims its output folder.
pub fn check_start(text: &str, overrides: &[String], tol: f64) -> Result<()> {
    check_tolerance(tol)?;
    Start::of(text, overrides, &mut Vec::new()).map(|_| ())
}

/// Run the scene at the resolution that meets `tol` on `quantity`.
/// `progress(done, total)` after each run (pilots, then the chosen run).
pub fn tolerance_run(
    text: &str,
    overrides: &[String],
    quantity: Quantity,
    tol: f64,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<TolerantRun> {
    let tol = check_tolerance(tol)?;
    let mut notes = Vec::new();
    let start = Start::of(text, overrides, &mut notes)?;
    let mut pilots = run_pilots(&start, quantity, tol, progress)?;
    let fit = fit_model(&start, quantity, tol, &mut pilots, &mut notes)?;
    let chosen = choose(&start, quantity, tol, &pilots, &fit.model, &mut notes)?;
    progress(RUNS, RUNS);
    Ok(tolerant_run(
        &start, quantity, tol, pilots, fit, chosen, notes,
    ))
}

/// The chosen run with its accuracy: the quantity's estimated error and
/// every result's (step 4).
fn tolerant_run(
    start: &Start,
    quantity: Quantity,
    tol: f64,
    pilots: Vec<PilotRun>,
    fit: Fit,
    chosen: Chosen,
    notes: Vec<String>,
) -> TolerantRun {
    let Fit {
        model,
        h_fine,
        dt_fine,
    } = fit;
    let Chosen {
        scene,
        output,
        met_by_pilot,
        run_wall,
    } = chosen;
    let (level, n0, dt0, length) = (start.level, start.n0, start.dt0, start.length);
    let h = length / level.of_scene(&scene) as f64;
    let estimated_error = model.estimate(h, scene.dt);
    let results = estimate_results(&pilots, &output, &model, h, scene.dt, h_fine, dt_fine);
    let accuracy = Accuracy {
        quantity,
        description: quantity.description(),
        filter_band_hz: (quantity == Quantity::Force).then_some(FORCE_BAND_HZ),
        tolerance: tol,
        elements: scene.elements,
        modes: scene.discretization.modes(),
        dt: scene.dt,
        steps: output.steps,
        dof_steps: output.dofs as f64 * output.steps as f64,
        met_by_pilot,
        estimated_error,
        p: model.mesh.order,
        q: model.step.order,
        c_h: model.mesh.constant,
        c_t: model.step.constant,
        model,
        pilot_start: (n0, dt0),
        pilot_wall_seconds: pilots.iter().map(|p| p.wall_seconds).sum(),
        pilot_dof_steps: pilots.iter().map(|p| p.dof_steps).sum(),
        pilots,
        run_wall_seconds: run_wall,
        notes,
        results,
    };
    TolerantRun {
        scene,
        output,
        accuracy,
    }
}
