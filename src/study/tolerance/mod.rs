//! Accuracy-targeted runs: `taut run SCENE --tolerance TOL [--quantity Q]`.
//!
//! Instead of running at the scene's (N, Δt), measure how the chosen
//! quantity converges, pick the cheapest (N, Δt) whose estimated error is
//! within `TOL`, run there, and report an estimated error next to every
//! result. The steps:
//!
//! 1. **Pilots.** Five runs from the scene's own (N₀, Δt₀): the mesh ladder
//!    N₀, 2N₀, 4N₀ at Δt₀ and the step ladder Δt₀/2, Δt₀/4 at N₀ (on a
//!    `galerkin` or `modal` basis the ladder doubles the modes J instead,
//!    with a `modal` basis's FE mesh grown in proportion; h = L/J) (the
//!    (N₀, Δt₀) run serves both). Δt₀ is first shortened, if needed, so the
//!    run's end is a whole number of steps, so every pilot's times contain
//!    the base pilot's and histories compare sample by sample on that grid
//!    (as [`crate::study::converge`] does).
//! 2. **Model.** e(h, Δt) ≈ F_s (C_h h^p + C_t Δt^q) from the ladders'
//!    successive differences (`error_model`). A ladder whose differences do not
//!    fall at order ≥ `MIN_ORDER` stops the run with an error that names
//!    the quantity, the differences and orders, and another quantity to try:
//!    nothing is extrapolated from a quantity that does not converge.
//! 3. **Choice.** If a pilot's estimate is already within the tolerance, the
//!    cheapest such pilot is the result (it is already run). Otherwise the
//!    model's cheapest (h, Δt) ([`ErrorModel::cheapest`]), with N rounded up
//!    and Δt rounded down to a whole number of steps to the run's end, and
//!    refused above `MAX_DOF_STEPS`.
//! 4. **Estimates.** Every scalar result (force mean, std, min, max, the
//!    0–20 Hz force's std, min, max, P_l, loss intervals, first loss
//!    position, switches, per carrier) gets its own ladder fits from the same
//!    pilots and an estimated error at the chosen resolution, or the verdict
//!    "not converging in h / Δt".
//!
//! Quantities ([`Quantity`]): `force` (default) is carrier 0's contact force
//! low-pass filtered to 0–20 Hz, as railway practice evaluates it (EN
//! 50317/50318), compared as a relative RMS. The raw force does not converge
//! in Δt once contact is lost and re-made: re-contact spikes grow as Δt falls
//! (docs/convergence.md §4, MODEL §6 has no impact law); the filter sees a
//! spike by its impulse, which does converge. `force_raw`, `loss_fraction`
//! (P_l, absolute error) and `displacement` (w under carrier 0, relative RMS)
//! are the alternatives. See docs/accuracy.md for what this measures on the
//! reference case.
//!
//! One step a file: `pilots` (1), `fit` (2), `choose` (3),
//! `results` (4); beside them `quantity` (what the tolerance is on and
//! its error measure), `limits` (the tolerance's range), `accuracy` (what the run returns), `refusal` (the errors that
//! stop it) and `error_model`.

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
