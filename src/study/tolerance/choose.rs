//! Step 3 (module docs): the resolution of the result, either the cheapest
//! pilot that already meets the tolerance or a new run at the model's
//! cheapest (h, Δt).

use super::MAX_DOF_STEPS;
use super::accuracy::PilotRun;
use super::error_model::ErrorModel;
use super::pilots::Start;
use super::quantity::Quantity;
use super::refusal::too_costly;
use crate::error::Result;
use crate::resolve::Resolved;
use crate::run::{RunOutput, run};
use crate::scene::STEP_COUNT_SLACK;

/// The run whose results are reported.
pub(super) struct Chosen {
    /// Its scene (N, Δt set).
    pub(super) scene: Resolved,
    /// Its output.
    pub(super) output: RunOutput,
    /// The pilot it is, when a pilot already met the tolerance.
    pub(super) met_by_pilot: Option<&'static str>,
    /// Its wall seconds (0 for a reused pilot).
    pub(super) run_wall: f64,
}

/// Choose (and, unless a pilot is reused, make) the run that meets `tol`.
pub(super) fn choose(
    start: &Start,
    quantity: Quantity,
    tol: f64,
    pilots: &[PilotRun],
    model: &ErrorModel,
    notes: &mut Vec<String>,
) -> Result<Chosen> {
    // the cheapest pilot that meets the tolerance, else the model's optimum
    let met = pilots
        .iter()
        .enumerate()
        .filter(|(_, p)| p.estimate.total <= tol)
        .min_by(|a, b| a.1.dof_steps.total_cmp(&b.1.dof_steps))
        .map(|(k, _)| k);
    match met {
        Some(k) => reuse_pilot(start, &pilots[k], notes),
        None => run_cheapest(start, quantity, tol, pilots, model),
    }
}

/// The pilot `p`, which already meets the tolerance, as the result.
fn reuse_pilot(start: &Start, p: &PilotRun, notes: &mut Vec<String>) -> Result<Chosen> {
    let level = start.level;
    notes.push(format!(
        "the pilot `{}` ({} = {}, Δt = {:e} s) already meets the tolerance (estimate {:.3e}): it is the result, no further run",
        p.role,
        level.symbol(),
        p.level(),
        p.dt,
        p.estimate.total
    ));
    let sc = start.at(p.level(), p.dt)?;
    Ok(Chosen {
        scene: sc,
        output: p.output.clone(),
        met_by_pilot: Some(p.role),
        run_wall: 0.0,
    })
}

/// A new run at the model's cheapest (h, Δt), N rounded up and Δt down to
/// whole steps, refused above [`MAX_DOF_STEPS`].
fn run_cheapest(
    start: &Start,
    quantity: Quantity,
    tol: f64,
    pilots: &[PilotRun],
    model: &ErrorModel,
) -> Result<Chosen> {
    let (level, n0, dt0, t_end, length) =
        (start.level, start.n0, start.dt0, start.t_end, start.length);
    // `None` when the tolerance asks for an h or Δt that is not a
    // positive finite number (it underflows): no run can meet it
    let (h, dt) = model.cheapest(tol, length / n0 as f64, dt0).ok_or_else(|| {
            too_costly(
                quantity,
                tol,
                format!(
                    "the model (C_h = {:.3e}, p = {}, C_t = {:.3e}, q = {}) gives no representable mesh and step for it. Ask for a looser tolerance; the best pilot's estimate is {:.3e}",
                    model.mesh.constant,
                    model.mesh.order,
                    model.step.constant,
                    model.step.order,
                    pilots
                        .iter()
                        .map(|p| p.estimate.total)
                        .fold(f64::INFINITY, f64::min)
                ),
            )
        })?;
    // N up, Δt down to whole steps: the estimate only falls (a ratio
    // that is whole up to round-off is not rounded up past itself)
    let n = ((length / h) * (1.0 - STEP_COUNT_SLACK))
        .ceil()
        .max(n0 as f64);
    let steps = ((t_end / dt) * (1.0 - STEP_COUNT_SLACK)).ceil().max(1.0);
    let dt = t_end / steps;
    // unknowns grow linearly in N (2 per node for Hermite elements)
    let (a, b) = (&pilots[0], &pilots[1]);
    let (la, lb) = (a.level(), b.level());
    let per_element = (b.dofs as f64 - a.dofs as f64) / (lb - la) as f64;
    let dofs = a.dofs as f64 + per_element * (n - la as f64);
    let cost = dofs * steps;
    // a NaN cost is refused too
    if cost.is_nan() || cost > MAX_DOF_STEPS {
        let rate = pilots
            .iter()
            .map(|p| p.dof_steps / p.wall_seconds.max(1e-12))
            .fold(0.0, f64::max);
        return Err(too_costly(
            quantity,
            tol,
            format!(
                "it needs {} = {n}, Δt = {dt:.4e} s ({steps} steps): {cost:.2e} DOF-steps, about {:.0} s at the pilots' {rate:.2e} DOF-steps/s, above the limit of {MAX_DOF_STEPS:e} DOF-steps. Ask for a looser tolerance; the best pilot's estimate is {:.3e}",
                level.symbol(),
                cost / rate.max(1.0),
                pilots
                    .iter()
                    .map(|p| p.estimate.total)
                    .fold(f64::INFINITY, f64::min)
            ),
        ));
    }
    let sc = start.at(n as usize, dt).map_err(|e| {
        too_costly(
            quantity,
            tol,
            format!(
                "it needs {} = {n}, Δt = {dt:.4e} s, outside what a scene may ask for: {e}",
                level.symbol()
            ),
        )
    })?;
    let out = run(&sc, &mut |_, _| {})?;
    let wall = out.wall_seconds;
    Ok(Chosen {
        scene: sc,
        output: out,
        met_by_pilot: None,
        run_wall: wall,
    })
}
