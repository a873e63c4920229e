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
//!    successive differences ([`error_model`]). A ladder whose differences do not
//!    fall at order ≥ [`MIN_ORDER`] stops the run with an error that names
//!    the quantity, the differences and orders, and another quantity to try:
//!    nothing is extrapolated from a quantity that does not converge.
//! 3. **Choice.** If a pilot's estimate is already within the tolerance, the
//!    cheapest such pilot is the result (it is already run). Otherwise the
//!    model's cheapest (h, Δt) ([`ErrorModel::cheapest`]), with N rounded up
//!    and Δt rounded down to a whole number of steps to the run's end, and
//!    refused above [`MAX_DOF_STEPS`].
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

mod error_model;

pub use super::filter::{FORCE_BAND_HZ, design_cutoff_hz, lowpass_zero_phase};
pub use error_model::{
    ErrorModel, Estimate, LADDER_RATIO, LadderFit, LadderStatus, MAX_MESH_ORDER,
    MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER, MAX_STEP_ORDER_CONTACT, MIN_ORDER, ROUND_OFF,
};

use serde::Serialize;

use super::grid::{Reach, nest, resample};
use super::relative_rms;
use super::scalars::{self, Scalar};
use super::space::SpaceChoice;
use super::variant::RunVariant;
use crate::error::{Error, Result};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::{RunOutput, run};
use crate::scene::{CarrierKind, Discretization, MeshKind, STEP_COUNT_SLACK};

/// Largest run (unknowns × steps) an accuracy-targeted run will start, pilots
/// included: the bound every study shares ([`super::cost::MAX_DOF_STEPS`]).
/// Beyond it the tool says what the tolerance would take instead of starting
/// a run nobody waits for.
pub use super::cost::MAX_DOF_STEPS;

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
    /// ([`MAX_MESH_ORDER`], [`MAX_MESH_ORDER_FORCE`], [`MAX_STEP_ORDER`],
    /// [`MAX_STEP_ORDER_CONTACT`]); `switches`: some pilot's contact opens
    /// or closes.
    pub fn max_orders(self, switches: bool) -> (f64, f64) {
        match self {
            Quantity::Displacement if !switches => (MAX_MESH_ORDER, MAX_STEP_ORDER),
            Quantity::Displacement => (MAX_MESH_ORDER, MAX_STEP_ORDER_CONTACT),
            _ => (MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT),
        }
    }

    /// What to try when this one does not converge.
    fn instead(self) -> &'static str {
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

/// The smallest tolerance: [`ROUND_OFF`]. The pilots' differences are
/// relative (absolute for P_l, itself at most 1), and differences below
/// [`ROUND_OFF`] are counted as round-off, so a smaller tolerance could not
/// be told from round-off; it would also ask for a resolution beyond
/// [`MAX_DOF_STEPS`] (or one that underflows) on any scene that is not exact.
pub const MIN_TOLERANCE: f64 = ROUND_OFF;

/// The allowed tolerances: a relative error (absolute for P_l) in
/// [[`MIN_TOLERANCE`], 1].
pub const TOLERANCE_RANGE: &str = "must be a number in [1e-12, 1]: a relative error (absolute for loss_fraction), e.g. 1e-3; below 1e-12 differences are round-off";

/// Read `--tolerance`: a finite number in [[`MIN_TOLERANCE`], 1].
pub fn parse_tolerance(s: &str) -> Result<f64> {
    let bad = || Error::invalid("--tolerance", s, TOLERANCE_RANGE);
    let v: f64 = s.trim().parse().map_err(|_| bad())?;
    check_tolerance(v).map_err(|_| bad())
}

fn check_tolerance(v: f64) -> Result<f64> {
    if v.is_finite() && (MIN_TOLERANCE..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(Error::invalid("--tolerance", v, TOLERANCE_RANGE))
    }
}

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
    output: RunOutput,
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

/// The largest Δt ≤ `dt` that divides `t_end` into whole steps. A ratio that
/// scene validation counts as whole (within its [`STEP_COUNT_SLACK`]) keeps
/// its Δt; any other is rounded up to whole steps, so that every pilot of the
/// ladder, at Δt/2 and Δt/4, ends at the same time as the base pilot.
pub fn whole_step(t_end: f64, dt: f64) -> f64 {
    let n = t_end / dt;
    let counted = (n * (1.0 + STEP_COUNT_SLACK)).floor();
    if counted >= 1.0 && n <= counted * (1.0 + STEP_COUNT_SLACK) {
        dt
    } else {
        t_end / (n * (1.0 - STEP_COUNT_SLACK)).ceil()
    }
}

/// The quantity of carrier 0 at every recorded row (its P_l for
/// `loss_fraction`, as a one-element vector).
pub fn quantity_signal(q: Quantity, out: &RunOutput) -> Vec<f64> {
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

/// Every scalar result that gets an estimate, in print order (names and
/// units: [`Scalar`]).
pub const RESULTS: [Scalar; 13] = [
    Scalar::ForceMean,
    Scalar::ForceStd,
    Scalar::ForceMin,
    Scalar::ForceMax,
    Scalar::FilteredForceStd,
    Scalar::FilteredForceMin,
    Scalar::FilteredForceMax,
    Scalar::LossFraction,
    Scalar::LossFractionSpan,
    Scalar::LossFractionSupport,
    Scalar::LossIntervalCount,
    Scalar::FirstLossPosition,
    Scalar::ContactSwitches,
];

/// The values of [`RESULTS`] for one carrier of a run, in that order
/// (`None` where undefined, e.g. the first loss of a contact never lost).
pub fn result_values(out: &RunOutput, carrier: usize) -> Vec<Option<f64>> {
    scalars::values(out, carrier, &RESULTS)
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
    let base = resolve_scene(text, overrides)?;
    base.require_every_step("taut run --tolerance")?;
    let t_end = base.t_end;
    // the level parameter of the space discretization: N of a Hermite
    // mesh, J of a modal basis (whose FE mesh, for `modal`, grows with J)
    let level = Level::of(&base);
    let n0 = level.start();
    let dt0 = whole_step(t_end, base.dt);
    let length = base.beam.length;
    let mut notes = Vec::new();
    if dt0 != base.dt {
        notes.push(format!(
            "pilot Δt₀ = {dt0:e} s instead of the scene's {:e} s, so the run's end ({t_end} s) is a whole number of steps and the pilots' times nest",
            base.dt
        ));
    }
    let with = |n: usize, dt: f64| level.variant(n, dt).apply(&base);
    let total = 6;
    let ladder: [(&'static str, usize, f64); 5] = [
        ("base", n0, dt0),
        ("mesh x2", 2 * n0, dt0),
        ("mesh x4", 4 * n0, dt0),
        ("step /2", n0, dt0 / 2.0),
        ("step /4", n0, dt0 / 4.0),
    ];
    let mut pilots: Vec<PilotRun> = Vec::with_capacity(5);
    for (k, &(role, n, dt)) in ladder.iter().enumerate() {
        // a pilot the scene's own run is not refused for: say which, and why
        // it is run at all (a central-difference step stable on N elements
        // is not on 4N)
        let pilot = |e: Error| match e {
            Error::Invalid {
                field,
                value,
                allowed,
            } if k > 0 => Error::invalid(
                field,
                value,
                format!(
                    "{allowed} (for the pilot run `{role}`, N = {n}, Δt = {dt:e} s, which --tolerance makes to measure convergence: the scene's own run is accepted; every pilot must be too, so give values that hold for 2× and 4× mesh.elements and Δt/2, Δt/4)"
                ),
            ),
            other => other,
        };
        let sc = with(n, dt).map_err(pilot)?;
        if let Some(first) = pilots.first() {
            nest((first.steps, first.dt), (sc.steps, sc.dt), Reach::SameEnd)?;
            // all five pilots cost 13 base runs: refuse before running them
            let pilot_cost = 13.0 * first.dof_steps;
            if k == 1 && pilot_cost > MAX_DOF_STEPS {
                return Err(too_costly(
                    quantity,
                    tol,
                    format!(
                        "the pilot runs alone need {pilot_cost:.2e} DOF-steps (13 × the scene's own run), above the limit of {MAX_DOF_STEPS:e}: start from a coarser mesh or step (--set mesh.elements=… --set time.step=…)"
                    ),
                ));
            }
        }
        let out = run(&sc, &mut |_, _| {}).map_err(pilot).map_err(|e| {
            e.in_run(&format!(
                "pilot `{role}` ({} = {n}, Δt = {:e} s)",
                level.symbol(),
                sc.dt
            ))
        })?;
        pilots.push(PilotRun {
            role,
            elements: sc.elements,
            modes: level.modes(n),
            dt: sc.dt,
            steps: out.steps,
            dofs: out.dofs,
            dof_steps: out.dofs as f64 * out.steps as f64,
            wall_seconds: out.wall_seconds,
            ladder_difference: f64::NAN,
            estimate: Estimate {
                total: f64::NAN,
                mesh: f64::NAN,
                step: f64::NAN,
            },
            output: out,
        });
        progress(k + 1, total);
    }

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
            match base.carriers[0].kind {
                CarrierKind::Force { .. } if quantity.is_force() => " (a moving force's λ is its F)",
                _ => "",
            },
            if quantity == Quantity::Displacement { "another quantity" } else { "--quantity displacement" }
        ));
    }
    for (k, d) in [(1, dh[0]), (2, dh[1]), (3, dt_[0]), (4, dt_[1])] {
        pilots[k].ladder_difference = d;
    }
    for p in &mut pilots {
        p.estimate = model.estimate(length / level.of_pilot(p) as f64, p.dt);
    }

    // the cheapest pilot that meets the tolerance, else the model's optimum
    let met = pilots
        .iter()
        .enumerate()
        .filter(|(_, p)| p.estimate.total <= tol)
        .min_by(|a, b| a.1.dof_steps.total_cmp(&b.1.dof_steps))
        .map(|(k, _)| k);
    let (scene, output, met_by_pilot, run_wall) = match met {
        Some(k) => {
            let p = &pilots[k];
            notes.push(format!(
                "the pilot `{}` ({} = {}, Δt = {:e} s) already meets the tolerance (estimate {:.3e}): it is the result, no further run",
                p.role,
                level.symbol(),
                level.of_pilot(p),
                p.dt,
                p.estimate.total
            ));
            let sc = with(level.of_pilot(p), p.dt)?;
            (sc, p.output.clone(), Some(p.role), 0.0)
        }
        None => {
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
            let (la, lb) = (level.of_pilot(a), level.of_pilot(b));
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
            let sc = with(n as usize, dt).map_err(|e| {
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
            (sc, out, None, wall)
        }
    };
    progress(total, total);

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
    Ok(TolerantRun {
        scene,
        output,
        accuracy,
    })
}

/// Per-result ladder fits from the pilots and estimates at (h, dt).
fn estimate_results(
    pilots: &[PilotRun],
    chosen: &RunOutput,
    model: &ErrorModel,
    h: f64,
    dt: f64,
    h_fine: f64,
    dt_fine: f64,
) -> Vec<ResultEstimate> {
    let nc = chosen.stats.len();
    let mut out = Vec::new();
    for c in 0..nc {
        let at_pilots: Vec<Vec<Option<f64>>> =
            pilots.iter().map(|p| result_values(&p.output, c)).collect();
        let at_chosen = result_values(chosen, c);
        for (k, q) in RESULTS.iter().enumerate() {
            let (name, unit) = (q.name(), q.unit());
            let vals: Vec<Option<f64>> = at_pilots.iter().map(|v| v[k]).collect();
            let value = at_chosen[k];
            let defined = vals.iter().filter(|v| v.is_some()).count();
            if defined < vals.len() {
                out.push(ResultEstimate {
                    carrier: c,
                    name,
                    unit,
                    value,
                    estimated_error: None,
                    status: if defined == 0 {
                        "undefined".into()
                    } else {
                        "undefined at some pilots".into()
                    },
                    mesh: None,
                    step: None,
                });
                continue;
            }
            let v: Vec<f64> = vals.into_iter().flatten().collect();
            let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let mesh = LadderFit::new(
                [(v[0] - v[1]).abs(), (v[1] - v[2]).abs()],
                h_fine,
                scale,
                MAX_MESH_ORDER_FORCE,
            );
            let step = LadderFit::new(
                [(v[0] - v[3]).abs(), (v[3] - v[4]).abs()],
                dt_fine,
                scale,
                MAX_STEP_ORDER_CONTACT,
            );
            let (status, estimated_error) = match (mesh.usable(), step.usable()) {
                (true, true) => {
                    let m = ErrorModel {
                        mesh,
                        step,
                        safety_factor: model.safety_factor,
                    };
                    let exact =
                        mesh.status == LadderStatus::Exact && step.status == LadderStatus::Exact;
                    (
                        if exact { "exact" } else { "estimated" }.to_string(),
                        Some(m.estimate(h, dt).total),
                    )
                }
                (false, true) => ("not converging in h".to_string(), None),
                (true, false) => ("not converging in Δt".to_string(), None),
                (false, false) => ("not converging in h and Δt".to_string(), None),
            };
            out.push(ResultEstimate {
                carrier: c,
                name,
                unit,
                value,
                estimated_error,
                status,
                mesh: Some(mesh),
                step: Some(step),
            });
        }
    }
    out
}

fn too_costly(quantity: Quantity, tol: f64, reason: String) -> Error {
    Error::Tolerance {
        quantity: quantity.name().into(),
        tolerance: tol,
        reason,
    }
}

/// The level parameter the mesh ladder refines (module docs): the elements
/// N of a Hermite (or string) mesh, the modes J of a `galerkin` basis, and
/// the modes J of a `modal` basis with its FE mesh grown in proportion
/// (J may not exceed the FE unknowns). `h = L/level` either way.
#[derive(Debug, Clone, Copy)]
enum Level {
    Elements(usize),
    Galerkin(usize),
    /// (J₀, N₀) of the scene.
    Modal(usize, usize),
}

impl Level {
    fn of(sc: &Resolved) -> Self {
        match sc.discretization {
            Discretization::Hermite => Level::Elements(sc.elements),
            Discretization::Galerkin { modes } => Level::Galerkin(modes),
            Discretization::Modal { modes } => Level::Modal(modes, sc.elements),
        }
    }

    /// The scene's own level (N₀ or J₀).
    fn start(&self) -> usize {
        match *self {
            Level::Elements(n) | Level::Galerkin(n) | Level::Modal(n, _) => n,
        }
    }

    /// `N` or `J`, for messages.
    fn symbol(&self) -> &'static str {
        match self {
            Level::Elements(_) => "N",
            _ => "J",
        }
    }

    /// The run at level `n` and step `dt`.
    fn variant(&self, n: usize, dt: f64) -> RunVariant {
        let mut v = RunVariant {
            dt: Some(dt),
            ..RunVariant::default()
        };
        match *self {
            Level::Elements(_) => v.elements = Some(n),
            Level::Galerkin(_) => {
                v.space = Some((
                    SpaceChoice {
                        kind: MeshKind::Galerkin,
                        modes: Some(n),
                    },
                    1.0,
                ))
            }
            Level::Modal(j0, n0) => {
                v.elements = Some((n0 * n).div_ceil(j0));
                v.space = Some((
                    SpaceChoice {
                        kind: MeshKind::Modal,
                        modes: Some(n),
                    },
                    1.0,
                ));
            }
        }
        v
    }

    /// J on a modal basis (None for a Hermite mesh).
    fn modes(&self, n: usize) -> Option<usize> {
        match self {
            Level::Elements(_) => None,
            _ => Some(n),
        }
    }

    /// The level of a pilot.
    fn of_pilot(&self, p: &PilotRun) -> usize {
        p.modes.unwrap_or(p.elements)
    }

    /// The level of a resolved scene.
    fn of_scene(&self, sc: &Resolved) -> usize {
        sc.discretization.modes().unwrap_or(sc.elements)
    }
}

/// The error for a quantity whose pilot differences do not fall.
fn not_converging(
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerances_outside_zero_to_one_are_refused() {
        for ok in ["1e-3", "1", " 0.5 "] {
            assert!(parse_tolerance(ok).is_ok(), "{ok}");
        }
        assert!(parse_tolerance("1e-12").is_ok());
        for bad in [
            "0", "-1e-3", "1.0001", "NaN", "inf", "", "abc", "1e-200", "9e-13", "1e300",
        ] {
            let e = parse_tolerance(bad).unwrap_err().to_string();
            assert!(
                e.contains("`--tolerance`") && e.contains("[1e-12, 1]"),
                "{e}"
            );
        }
    }

    #[test]
    fn quantities_parse_by_name() {
        for q in Quantity::ALL {
            assert_eq!(q.name().parse::<Quantity>().unwrap(), q);
        }
        let e = "speed".parse::<Quantity>().unwrap_err().to_string();
        assert!(e.contains("`--quantity` = speed"), "{e}");
    }

    #[test]
    fn whole_step_divides_the_end() {
        // 0.6 s / 1e-4 s is 6000 steps up to round-off: kept
        assert_eq!(whole_step(0.6000000000000001, 1e-4), 1e-4);
        // 0.15 s / 4e-2 s = 3.75: shortened to 0.15/4
        let dt = whole_step(0.15, 4e-2);
        assert!((dt - 0.0375).abs() < 1e-15);
        assert!(dt <= 4e-2);
    }
}
