//! What an accuracy-targeted run returns: the pilots, the estimate of every
//! result, and how the resolution was chosen (`accuracy` in
//! `summary.json`, `accuracy.csv`).

use serde::Serialize;

use super::error_model::{ErrorModel, Estimate, LadderFit};
use super::quantity::Quantity;
use crate::resolve::Resolved;
use crate::run::RunOutput;

/// One pilot run (a row of `accuracy.csv`).
#[derive(Debug, Clone, Serialize)]
pub struct PilotRun {
    /// `base`, `mesh x2`, `mesh x4`, `step /2` or `step /4`.
    pub role: &'static str,
    /// Elements N.
    pub elements: usize,
    /// Modes J of a `galerkin` or `modal` basis (refined in J, not N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Time step, s.
    pub dt: f64,
    /// Steps.
    pub steps: usize,
    /// Unknowns.
    pub dofs: usize,
    /// dofs × steps.
    pub dof_steps: f64,
    /// Wall seconds (machine-dependent).
    pub wall_seconds: f64,
    /// The quantity's difference to the next coarser rung of its ladder
    /// (NaN, JSON null, for the base run).
    pub ladder_difference: f64,
    /// The model's estimated error of the quantity at this resolution.
    pub estimate: Estimate,
    #[serde(skip)]
    pub(super) output: RunOutput,
}

/// The estimated error of one scalar result of the chosen run.
#[derive(Debug, Clone, Serialize)]
pub struct ResultEstimate {
    /// Carrier index.
    pub carrier: usize,
    /// `force_mean`, `force_std`, …, `loss_fraction`, ….
    pub name: &'static str,
    /// Unit (`N`, `x/L` or `-`).
    pub unit: &'static str,
    /// The chosen run's value (null when undefined, e.g. no loss).
    pub value: Option<f64>,
    /// F_s·(mesh + step part) at the chosen resolution, in the result's unit;
    /// null when not converging or undefined.
    pub estimated_error: Option<f64>,
    /// `estimated`, `exact` (no change over the pilots), `not converging in
    /// h`, `not converging in Δt`, `not converging in h and Δt`, `undefined`
    /// (at every pilot) or `undefined at some pilots`.
    pub status: String,
    /// The mesh ladder's fit (null when undefined).
    pub mesh: Option<LadderFit>,
    /// The step ladder's fit (null when undefined).
    pub step: Option<LadderFit>,
}

impl PilotRun {
    /// Its level parameter: J on a modal basis, else N.
    pub(super) fn level(&self) -> usize {
        self.modes.unwrap_or(self.elements)
    }
}

/// Everything an accuracy-targeted run adds to `summary.json` (`accuracy`).
#[derive(Debug, Clone, Serialize)]
pub struct Accuracy {
    /// The quantity the tolerance is on.
    pub quantity: Quantity,
    /// What it is and how its error is measured.
    pub description: &'static str,
    /// The band of the filtered force, Hz (null for other quantities).
    pub filter_band_hz: Option<f64>,
    /// The requested tolerance.
    pub tolerance: f64,
    /// Chosen elements N.
    pub elements: usize,
    /// Chosen modes J of a `galerkin` or `modal` basis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Chosen time step, s.
    pub dt: f64,
    /// Steps of the chosen run.
    pub steps: usize,
    /// Unknowns × steps of the chosen run.
    pub dof_steps: f64,
    /// The pilot whose result this is when a pilot already met the
    /// tolerance, else null (a new run was made).
    pub met_by_pilot: Option<&'static str>,
    /// Estimated error of the quantity at the chosen resolution.
    pub estimated_error: Estimate,
    /// Mesh order p used.
    pub p: f64,
    /// Step order q used.
    pub q: f64,
    /// C_h (quantity's unit per m^p).
    pub c_h: f64,
    /// C_t (quantity's unit per s^q).
    pub c_t: f64,
    /// The full model: both ladder fits and F_s.
    pub model: ErrorModel,
    /// Pilot start (N₀, Δt₀): the scene's, Δt₀ shortened to a whole number
    /// of steps when needed.
    pub pilot_start: (usize, f64),
    /// The pilot runs, in the order run.
    pub pilots: Vec<PilotRun>,
    /// Sum of the pilots' wall seconds.
    pub pilot_wall_seconds: f64,
    /// Sum of the pilots' DOF-steps.
    pub pilot_dof_steps: f64,
    /// Wall seconds of the chosen run (0 when a pilot is reused).
    pub run_wall_seconds: f64,
    /// Things the user should know (Δt₀ adjusted, a pilot reused, …).
    pub notes: Vec<String>,
    /// Estimated errors of every scalar result, carrier by carrier.
    pub results: Vec<ResultEstimate>,
}

/// A finished accuracy-targeted run.
pub struct TolerantRun {
    /// The chosen scene (N, Δt set).
    pub scene: Resolved,
    /// Its run.
    pub output: RunOutput,
    /// How it was chosen and how accurate its results are.
    pub accuracy: Accuracy,
}
