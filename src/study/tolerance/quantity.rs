//! What the tolerance is on ([`Quantity`]) and how its error between two
//! runs is measured.

use serde::Serialize;

use super::error_model::{
    MAX_MESH_ORDER, MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER, MAX_STEP_ORDER_CONTACT,
};
use crate::error::{Error, Result};
use crate::run::RunOutput;
use crate::study::filter::{FORCE_BAND_HZ, lowpass_zero_phase};
use crate::study::grid::{Reach, nest, resample};
use crate::study::relative_rms;
/// What the tolerance is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Carrier 0's contact force low-pass filtered to 0–20 Hz, relative RMS.
    Force,
    /// Carrier 0's contact force as computed, relative RMS.
    ForceRaw,
    /// P_l of carrier 0, absolute.
    LossFraction,
    /// The in-span part of P_l of carrier 0 (outside the support zones),
    /// absolute: the part that converges (`docs/contact_loss.md`).
    LossFractionSpan,
    /// w under carrier 0, relative RMS.
    Displacement,
}

impl Quantity {
    /// Every quantity, in the order the CLI lists them.
    pub const ALL: [Quantity; 5] = [
        Quantity::Force,
        Quantity::ForceRaw,
        Quantity::LossFraction,
        Quantity::LossFractionSpan,
        Quantity::Displacement,
    ];

    /// A part of P_l (absolute error, one number per run).
    pub fn is_loss(self) -> bool {
        matches!(self, Quantity::LossFraction | Quantity::LossFractionSpan)
    }

    /// A contact force (filtered or raw).
    pub fn is_force(self) -> bool {
        matches!(self, Quantity::Force | Quantity::ForceRaw)
    }

    /// The name used by `--quantity`.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Force => "force",
            Quantity::ForceRaw => "force_raw",
            Quantity::LossFraction => "loss_fraction",
            Quantity::LossFractionSpan => "loss_fraction_span",
            Quantity::Displacement => "displacement",
        }
    }

    /// What it is and how its error is measured.
    pub fn description(self) -> &'static str {
        match self {
            Quantity::Force => {
                "contact force of carrier 0 low-pass filtered to 0–20 Hz (zero-phase Butterworth), relative RMS error over the run"
            }
            Quantity::ForceRaw => "contact force of carrier 0, relative RMS error over the run",
            Quantity::LossFraction => "P_l of carrier 0, absolute error",
            Quantity::LossFractionSpan => {
                "P_l of carrier 0 in the span (outside the support zones), absolute error"
            }
            Quantity::Displacement => {
                "beam displacement w under carrier 0, relative RMS error over the run"
            }
        }
    }

    /// The largest (mesh, step) orders the method gives this quantity
    /// (`MAX_MESH_ORDER`, `MAX_MESH_ORDER_FORCE`, `MAX_STEP_ORDER`,
    /// `MAX_STEP_ORDER_CONTACT`); `switches`: some pilot's contact opens
    /// or closes.
    pub fn max_orders(self, switches: bool) -> (f64, f64) {
        match self {
            Quantity::Displacement if !switches => (MAX_MESH_ORDER, MAX_STEP_ORDER),
            Quantity::Displacement => (MAX_MESH_ORDER, MAX_STEP_ORDER_CONTACT),
            _ => (MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT),
        }
    }

    /// What to try when this one does not converge.
    pub(super) fn instead(self) -> &'static str {
        match self {
            Quantity::Force => "--quantity displacement",
            Quantity::ForceRaw => {
                "--quantity force (the 0–20 Hz force, which sees a re-contact spike by its impulse)"
            }
            Quantity::LossFraction => {
                "--quantity loss_fraction_span (the in-span part of P_l; the support part, the carrier's arrival at a support, does not converge in Δt)"
            }
            Quantity::LossFractionSpan => {
                "--quantity force (P_l counts the short bounces after a re-contact, whose number grows as Δt falls)"
            }
            Quantity::Displacement => "--quantity force",
        }
    }
}

impl std::str::FromStr for Quantity {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Quantity::ALL
            .into_iter()
            .find(|q| q.name() == s)
            .ok_or_else(|| {
                Error::invalid(
                    "--quantity",
                    s,
                    "must be force, force_raw, loss_fraction, loss_fraction_span or displacement",
                )
            })
    }
}

/// The quantity of carrier 0 at every recorded row (its P_l for
/// `loss_fraction`, as a one-element vector).
pub(crate) fn quantity_signal(q: Quantity, out: &RunOutput) -> Vec<f64> {
    let tr = &out.history.carriers[0];
    match q {
        Quantity::Force => lowpass_zero_phase(&tr.force, out.dt, FORCE_BAND_HZ),
        Quantity::ForceRaw => tr.force.clone(),
        Quantity::Displacement => tr.w.clone(),
        Quantity::LossFraction => vec![out.stats[0].loss_fraction],
        Quantity::LossFractionSpan => vec![out.stats[0].loss_fraction_span],
    }
}

/// Rows of `out` at the times of a grid with step `grid_dt` and `steps`
/// steps (rows 1 … steps of that grid), or an error when they do not nest
/// (`out` may run on past the grid's end: a finer run of a
/// `carrier_leaves` scene).
fn sample(values: &[f64], out: &RunOutput, grid_dt: f64, steps: usize) -> Result<Vec<f64>> {
    let stride = nest((steps, grid_dt), (out.steps, out.dt), Reach::AtLeast)?;
    Ok(resample(values, stride, 1..steps + 1))
}

/// The error measure of `q` between two runs on the time grid of `grid`
/// (whose times both contain): relative RMS ‖a − b‖/‖b‖ over that grid's
/// steps for histories (b is taken as the better run), |P_a − P_b| for P_l.
pub fn quantity_difference(
    q: Quantity,
    a: &RunOutput,
    b: &RunOutput,
    grid: &RunOutput,
) -> Result<f64> {
    if q.is_loss() {
        let (pa, pb) = (quantity_signal(q, a), quantity_signal(q, b));
        return Ok((pa[0] - pb[0]).abs());
    }
    let sa = sample(&quantity_signal(q, a), a, grid.dt, grid.steps)?;
    let sb = sample(&quantity_signal(q, b), b, grid.dt, grid.steps)?;
    Ok(relative_rms(&sa, &sb))
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn quantities_parse_by_name() {
        for q in Quantity::ALL {
            assert_eq!(q.name().parse::<Quantity>().unwrap(), q);
        }
        let e = "speed".parse::<Quantity>().unwrap_err().to_string();
        assert!(e.contains("`--quantity` = speed"), "{e}");
    }
}
