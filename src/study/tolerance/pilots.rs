//! Step 1 of an accuracy-targeted run (module docs): where the pilots
//! start (the scene's own level and a Δt that divides the run's end), and
//! the five pilot runs of the mesh and step ladders.

use super::MAX_DOF_STEPS;
use super::accuracy::PilotRun;
use super::error_model::Estimate;
use super::quantity::Quantity;
use super::refusal::too_costly;
use crate::error::{Error, Result};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::run;
use crate::scene::STEP_COUNT_SLACK;
use crate::study::grid::{Reach, nest};
use crate::study::level::Level;

/// Runs an accuracy-targeted run reports to `progress`: the five pilots and
/// the chosen run.
pub(super) const RUNS: usize = 6;

/// Where the pilots start: the scene at its own level and step.
pub(super) struct Start {
    /// The scene as given.
    pub(super) base: Resolved,
    /// The level parameter of its space discretization.
    pub(super) level: Level,
    /// The scene's own level (N₀ or J₀).
    pub(super) n0: usize,
    /// Pilot step Δt₀: the scene's, shortened when needed to a whole number
    /// of steps to the run's end, s.
    pub(super) dt0: f64,
    /// The run's end, s.
    pub(super) t_end: f64,
    /// Beam length L, m.
    pub(super) length: f64,
}

impl Start {
    /// Resolve the scene and its pilots' start; `notes` gains a line when
    /// Δt₀ is not the scene's step.
    pub(super) fn of(text: &str, overrides: &[String], notes: &mut Vec<String>) -> Result<Self> {
        let base = resolve_scene(text, overrides)?;
        base.require_every_step("taut run --tolerance")?;
        let t_end = base.t_end;
        // the level parameter of the space discretization: N of a Hermite
        // mesh, J of a modal basis (whose FE mesh, for `modal`, grows with J)
        let level = Level::of(&base);
        let n0 = level.start();
        let dt0 = whole_step(t_end, base.dt);
        let length = base.beam.length;
        if dt0 != base.dt {
            notes.push(format!(
                "pilot Δt₀ = {dt0:e} s instead of the scene's {:e} s, so the run's end ({t_end} s) is a whole number of steps and the pilots' times nest",
                base.dt
            ));
        }
        Ok(Start {
            base,
            level,
            n0,
            dt0,
            t_end,
            length,
        })
    }

    /// The scene at level `n` and step `dt`.
    pub(super) fn at(&self, n: usize, dt: f64) -> Result<Resolved> {
        // every run measures P_l over the scene's own support zone
        self.level
            .variant(n, dt)
            .keeping_zone_of(&self.base)
            .apply(&self.base)
    }
}

/// Run the five pilots (base, mesh x2, mesh x4, step /2, step /4), refusing
/// before the first refined one when all five would exceed
/// [`MAX_DOF_STEPS`]. `progress(done, RUNS)` after each.
pub(super) fn run_pilots(
    start: &Start,
    quantity: Quantity,
    tol: f64,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<PilotRun>> {
    let (level, n0, dt0) = (start.level, start.n0, start.dt0);
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
        let sc = start.at(n, dt).map_err(pilot)?;
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
        progress(k + 1, RUNS);
    }
    Ok(pilots)
}

/// The largest Δt ≤ `dt` that divides `t_end` into whole steps. A ratio that
/// scene validation counts as whole (within its [`STEP_COUNT_SLACK`]) keeps
/// its Δt; any other is rounded up to whole steps, so that every pilot of the
/// ladder, at Δt/2 and Δt/4, ends at the same time as the base pilot.
pub(crate) fn whole_step(t_end: f64, dt: f64) -> f64 {
    let n = t_end / dt;
    let counted = (n * (1.0 + STEP_COUNT_SLACK)).floor();
    if counted >= 1.0 && n <= counted * (1.0 + STEP_COUNT_SLACK) {
        dt
    } else {
        t_end / (n * (1.0 - STEP_COUNT_SLACK)).ceil()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
