//! Step 2 (module docs): the error model of the quantity from the
//! pilots' ladder differences, refused when a ladder does not converge.

use super::accuracy::PilotRun;
use super::error_model::{ErrorModel, LadderFit, LadderStatus};
use super::pilots::Start;
use super::quantity::{Quantity, quantity_difference};
use super::refusal::not_converging;
use crate::error::Result;
use crate::scene::CarrierKind;

/// The fitted error model and the finest rungs of its ladders.
pub(super) struct Fit {
    /// e(h, Δt) ≈ F_s (C_h h^p + C_t Δt^q).
    pub(super) model: ErrorModel,
    /// Finest h of the mesh ladder, L/(4 N₀), m.
    pub(super) h_fine: f64,
    /// Finest Δt of the step ladder, Δt₀/4, s.
    pub(super) dt_fine: f64,
}

/// Fit the model of `quantity` to the pilots' successive differences, set
/// each pilot's ladder difference and estimate; `notes` gains a line when
/// the quantity is the same at every pilot.
pub(super) fn fit_model(
    start: &Start,
    quantity: Quantity,
    tol: f64,
    pilots: &mut [PilotRun],
    notes: &mut Vec<String>,
) -> Result<Fit> {
    let (level, n0, dt0, length) = (start.level, start.n0, start.dt0, start.length);
    // the model of the quantity, on the base pilot's time grid
    let grid = &pilots[0].output;
    let diff = |a: usize, b: usize| {
        quantity_difference(quantity, &pilots[a].output, &pilots[b].output, grid)
    };
    let dh = [diff(0, 1)?, diff(1, 2)?];
    let dt_ = [diff(0, 3)?, diff(3, 4)?];
    let h_fine = length / (4 * n0) as f64;
    let dt_fine = dt0 / 4.0;
    let switches = pilots
        .iter()
        .any(|p| p.output.stats.iter().any(|s| s.contact_switches > 0));
    let (max_p, max_q) = quantity.max_orders(switches);
    let mesh = LadderFit::new(dh, h_fine, 1.0, max_p);
    let step = LadderFit::new(dt_, dt_fine, 1.0, max_q);
    if !(mesh.usable() && step.usable()) {
        return Err(not_converging(
            quantity,
            tol,
            &mesh,
            &step,
            (level.symbol(), n0),
            dt0,
        ));
    }
    let model = ErrorModel::new(mesh, step);
    if mesh.status == LadderStatus::Exact && step.status == LadderStatus::Exact {
        notes.push(format!(
            "`{}` is the same at every pilot{}: the tolerance is met at any resolution and says nothing about the rest of the solution; {} measures the beam",
            quantity.name(),
            match start.base.carriers[0].kind {
                CarrierKind::Force { .. } if quantity.is_force() => " (a moving force's λ is its F)",
                _ => "",
            },
            if quantity == Quantity::Displacement { "another quantity" } else { "--quantity displacement" }
        ));
    }
    for (k, d) in [(1, dh[0]), (2, dh[1]), (3, dt_[0]), (4, dt_[1])] {
        pilots[k].ladder_difference = d;
    }
    for p in pilots.iter_mut() {
        p.estimate = model.estimate(length / p.level() as f64, p.dt);
    }
    Ok(Fit {
        model,
        h_fine,
        dt_fine,
    })
}
