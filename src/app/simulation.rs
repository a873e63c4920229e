//! `taut.Simulation`: one run stepped on request, for co-simulation (an
//! active pantograph's controller, a force law of one's own). Built from a
//! scene as [`run`](fn@super::run) takes it; advanced `k` steps at a time
//! ([`Simulation::step`]); its state read between steps
//! ([`Simulation::state`], [`Simulation::w_at`]); a force applied to a
//! carrier's mass between steps ([`Simulation::apply_force`]); and, once
//! every step is taken, finished into what `run` gives
//! ([`Simulation::finish`]: the same [`RunOutcome`], the same files).
//!
//! With nothing applied, the steps are [`crate::run`](fn@crate::run)'s steps, recorded by
//! the same recorder ([`crate::run::SteppedRun`]): histories and summary
//! are bit-identical to `run`'s however the steps are grouped (only
//! `wall_seconds` differs: a simulation's wall time runs from its creation
//! to its end, the caller's time between steps included).
//!
//! A simulation is always one run stepping alone: a scene that `run` would
//! step in a batch with others (sweeps) is stepped alone here, which gives
//! the same bits (`run::run_batch`). Refused: a tolerance run (it chooses
//! mesh and Δt by running the scene several times, so there is no one run
//! to step).

use std::path::PathBuf;
use std::time::Instant;

use crate::error::{Error, Result};
use crate::integrate::Integrator;
use crate::model::beam::PointVector;
use crate::report::{Outputs, Summary};
use crate::resolve::Resolved;
use crate::run::SteppedRun;

use super::{Frontend, RunOutcome, RunRequest, Writing, kept};

/// One carrier's state between steps (MODEL §2 names and signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarrierState {
    /// Position x_m, m.
    pub x: f64,
    /// Beam displacement under the carrier, w = s·v(x_m), m (into the beam).
    pub w: f64,
    /// Mass displacement q = s·ξ, m (into the beam; = w for a moving force).
    pub q: f64,
    /// Mass velocity q̇, m/s (`None` for a moving force: no mass).
    pub q_dot: Option<f64>,
    /// Gap g = w − q, m.
    pub gap: f64,
    /// Contact force λ, N, as `history.csv` records it (the applied F for
    /// a moving force).
    pub force: f64,
    /// Contact closed.
    pub in_contact: bool,
    /// The external force held on the mass ([`Simulation::apply_force`]),
    /// N in +v (up); 0 for a moving force.
    pub applied: f64,
}

/// A probe's values between steps.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeState {
    /// Its name (`[[probe]] name`).
    pub name: String,
    /// Where it is, m.
    pub x: f64,
    /// Beam displacement v(x), m (+ up, as `history.csv`'s probe columns).
    pub v: f64,
    /// Beam velocity v̇(x), m/s (central difference keeps the half-step
    /// velocity v_{n−1/2}, MODEL §9.1).
    pub v_dot: f64,
}

/// The state of a simulation between steps.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationState {
    /// Time t_n, s.
    pub t: f64,
    /// Steps taken, n.
    pub step: usize,
    /// Each carrier's, in scene order.
    pub carriers: Vec<CarrierState>,
    /// Each probe's, in scene order.
    pub probes: Vec<ProbeState>,
}

/// One run stepped on request (module docs).
pub struct Simulation {
    sc: Resolved,
    /// `None` once a step has failed (the state is then undefined).
    run: Option<SteppedRun>,
    /// The step a failed run stopped at.
    failed_at: Option<usize>,
    probes: Vec<PointVector>,
    out: Option<PathBuf>,
    scene: super::SceneSource,
}

impl Simulation {
    /// Read and resolve the scene of `req` (overrides applied), build its
    /// integrator and the initial state, record t = 0. `req.out` is
    /// checked (another command holding it, or a folder that cannot be
    /// written, is refused here) but written only at [`Simulation::finish`],
    /// whose outputs replace an earlier call's as `run`'s do. A tolerance
    /// is refused (module docs).
    pub fn new(req: &RunRequest, fe: &dyn Frontend) -> Result<Self> {
        if let Some(t) = &req.tolerance {
            return Err(Error::invalid(
                "tolerance",
                t.tolerance,
                "is not for a simulation stepped on request: a tolerance run chooses mesh and Δt by running the scene several times (use run with a tolerance, then step a simulation with the mesh and step it reports)",
            ));
        }
        let dir = req.out.as_deref();
        Self::start(req).map_err(|e| kept(dir, Outputs::Run, e, fe))
    }

    /// [`Simulation::new`] but for the tolerance and the note of a
    /// simulation refused.
    fn start(req: &RunRequest) -> Result<Self> {
        if let Some(d) = req.out.as_deref() {
            crate::report::check_out_dir(d)?;
        }
        let text = req.scene.read()?;
        let sc = crate::resolve::resolve_scene(&text, &req.set).map_err(|e| req.scene.name(e))?;
        // a folder another command holds, or that cannot be written, is
        // refused now, not after the steps (it is claimed again to write)
        drop(Writing::open_some(
            req.out.as_deref(),
            Outputs::Run,
            "taut.Simulation",
        )?);
        let start = Instant::now();
        let it = Integrator::new(&sc)?;
        let probes = (0..sc.probes.len())
            .map(|i| sc.probe_vector(it.beam(), i))
            .collect();
        let run = SteppedRun::new(&sc, it, start)?;
        Ok(Simulation {
            sc,
            run: Some(run),
            failed_at: None,
            probes,
            out: req.out.clone(),
            scene: req.scene.clone(),
        })
    }

    /// The resolved scene.
    pub fn scene(&self) -> &Resolved {
        &self.sc
    }

    /// The run's number of steps.
    pub fn steps(&self) -> usize {
        self.sc.steps
    }

    /// Time step Δt, s.
    pub fn dt(&self) -> f64 {
        self.sc.dt
    }

    /// True once the run has ended: every step taken, or a step failed.
    pub fn done(&self) -> bool {
        self.run.as_ref().is_none_or(|r| r.done(&self.sc))
    }

    fn running(&self) -> Result<&SteppedRun> {
        self.run.as_ref().ok_or_else(|| self.stopped())
    }

    fn stopped(&self) -> Error {
        Error::invalid(
            "simulation",
            format!("stopped at step {}", self.failed_at.unwrap_or(0)),
            "has no state after a failed step: build a new simulation",
        )
    }

    /// Advance up to `k` steps, stopping early at the run's end; the
    /// number taken. A failed step ends the simulation with its error;
    /// a stop request ([`crate::interrupt`]) returns
    /// [`Error::Interrupted`] between steps and leaves it usable.
    pub fn step(&mut self, k: usize) -> Result<usize> {
        let sc = &self.sc;
        let Some(run) = self.run.as_mut() else {
            return Err(self.stopped());
        };
        let mut taken = 0;
        while taken < k && !run.done(sc) {
            if crate::interrupt::requested() {
                return Err(Error::Interrupted);
            }
            if let Err(e) = run.step(sc) {
                self.failed_at = Some(run.integrator().steps_taken());
                self.run = None;
                return Err(e);
            }
            taken += 1;
        }
        Ok(taken)
    }

    /// Hold `newtons` on carrier `carrier`'s mass, in +v (up, MODEL §2:
    /// the mass equation gets `s·F`, so for a pantograph below the wire a
    /// positive force presses it up into the wire), from the next step on
    /// until changed, on top of the scene's `external_force` series if
    /// any. The force is constant over each step, so it does not matter at
    /// which time within the step the method samples its loads. Refused
    /// for a moving force, a carrier index out of range, a non-finite
    /// force.
    pub fn apply_force(&mut self, carrier: usize, newtons: f64) -> Result<()> {
        if self.run.is_none() {
            return Err(self.stopped());
        }
        let run = self.run.as_mut().expect("checked above");
        run.integrator_mut().hold_external_force(carrier, newtons)
    }

    /// The state at the current time (allocates: between steps).
    pub fn state(&self) -> Result<SimulationState> {
        let run = self.running()?;
        let it = run.integrator();
        let st = it.state();
        let sys = it.system();
        let mut contact = 0;
        let carriers = (0..it.carriers())
            .map(|i| {
                let s = it.sample(i);
                let is_mass = matches!(
                    self.sc.carriers[i].kind,
                    crate::scene::CarrierKind::MassSpring { .. }
                );
                let (q_dot, applied) = if is_mass {
                    let j = contact;
                    contact += 1;
                    (Some(st.q_dot[j]), sys.held_external_force(j))
                } else {
                    (None, 0.0)
                };
                CarrierState {
                    x: s.x,
                    w: s.w,
                    q: s.q,
                    q_dot,
                    gap: s.gap,
                    force: s.force,
                    in_contact: s.in_contact,
                    applied,
                }
            })
            .collect();
        let probes = self
            .sc
            .probes
            .iter()
            .zip(&self.probes)
            .map(|((name, x), pv)| ProbeState {
                name: name.clone(),
                x: *x,
                v: pv.dot(&st.d),
                v_dot: pv.dot(&st.v),
            })
            .collect();
        Ok(SimulationState {
            t: st.t,
            step: st.step,
            carriers,
            probes,
        })
    }

    /// The beam displacement v(x) at the current time, m (+ up, as the
    /// probes), for any x on the beam (0 ≤ x ≤ L).
    pub fn w_at(&self, x: f64) -> Result<f64> {
        let l = self.sc.beam.length;
        if !(0.0..=l).contains(&x) {
            return Err(Error::invalid(
                "x",
                x,
                format!("must be on the beam, in [0, {l}] m"),
            ));
        }
        let it = self.running()?.integrator();
        Ok(it.displacement_at(&it.beam().point_vector(x)))
    }

    /// Once every step is taken: the run's statistics, warnings and
    /// histories, and its files written into the request's `out` folder —
    /// what [`run`](fn@super::run) gives. Refused before the end (the statistics
    /// of a part of a run are not the run's).
    pub fn finish(self) -> Result<RunOutcome> {
        let Some(run) = self.run else {
            return Err(Error::invalid(
                "simulation",
                format!("stopped at step {}", self.failed_at.unwrap_or(0)),
                "has no result after a failed step",
            ));
        };
        if !run.done(&self.sc) {
            let left = self.sc.steps - run.integrator().steps_taken();
            return Err(Error::invalid(
                "simulation",
                format!("{left} steps before its end"),
                "gives its result once every step is taken: step it to the end first",
            ));
        }
        let output = run.finish(&self.sc);
        let summary = match self.out.as_deref() {
            Some(d) => {
                let w = Writing::open(d, Outputs::Run, "taut.Simulation")?;
                let summary = crate::report::write_run(w.stage(), &self.sc, &output)
                    .map_err(|e| self.scene.name(e))?;
                w.finish(&super::Silent)?;
                summary
            }
            None => Summary::new(&self.sc, &output),
        };
        Ok(RunOutcome {
            summary,
            output,
            accuracy: None,
        })
    }
}
