//! The errors that stop an accuracy-targeted run: a tolerance that would
//! cost too much, a quantity that does not converge.

use super::error_model::{LadderFit, LadderStatus, MIN_ORDER};
use super::quantity::Quantity;
use crate::error::Error;

/// The error for a tolerance no run within the limits can meet.
pub(super) fn too_costly(quantity: Quantity, tol: f64, reason: String) -> Error {
    Error::Tolerance {
        quantity: quantity.name().into(),
        tolerance: tol,
        reason,
    }
}

/// The error for a quantity whose pilot differences do not fall.
pub(super) fn not_converging(
    quantity: Quantity,
    tol: f64,
    mesh: &LadderFit,
    step: &LadderFit,
    (sym, n0): (&str, usize),
    dt0: f64,
) -> Error {
    let describe = |f: &LadderFit, what: &str, over: String| {
        format!(
            "{what}: {} ({over}): differences {:.3e}, {:.3e}, observed order {:.2}{}",
            match f.status {
                LadderStatus::NotConverging => "NOT converging",
                _ => "converging",
            },
            f.differences[0],
            f.differences[1],
            f.observed_order,
            if f.status == LadderStatus::NotConverging {
                format!(" (minimum {MIN_ORDER})")
            } else {
                String::new()
            }
        )
    };
    let which = match (mesh.usable(), step.usable()) {
        (false, false) => "in h and in Δt",
        (false, true) => "in h",
        _ => "in Δt",
    };
    Error::Tolerance {
        quantity: quantity.name().into(),
        tolerance: tol,
        reason: format!(
            "`{}` ({}) does not converge {which} on the pilot runs, so no resolution can be promised to meet the tolerance. {}; {}. Try {}, or start the pilots finer (--set mesh.elements=… --set time.step=…) if they may be pre-asymptotic",
            quantity.name(),
            quantity.description(),
            describe(
                mesh,
                "in h",
                format!("{sym} = {n0}, {}, {} at Δt = {dt0:e} s", 2 * n0, 4 * n0)
            ),
            describe(
                step,
                "in Δt",
                format!(
                    "Δt = {dt0:e}, {:e}, {:e} s at {sym} = {n0}",
                    dt0 / 2.0,
                    dt0 / 4.0
                )
            ),
            quantity.instead()
        ),
    }
}
