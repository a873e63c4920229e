//! One run's integrator (MODEL §5): it builds the system, the consistent
//! initial state and the method's stepper, and advances time.

use crate::error::{Error, Result};
use crate::model::beam::{BeamModel, PointVector};
use crate::resolve::Resolved;

use super::chain;
use super::diagnose;
use super::dropper::DropperSample;
use super::energy::{self, Energy};
use super::method::{MethodFactory, scene_method};
use super::sample::{self, CarrierSample};
use super::state::State;
use super::static_start;
use super::stepper::Stepper;
use super::system::System;

/// One run's integrator: system, state and the method's stepper.
pub struct Integrator {
    sys: System,
    state: State,
    stepper: Box<dyn Stepper>,
    /// The method's name, for warnings.
    method: String,
    /// The method's likely cause of an instability with a moving contact
    /// ([`MethodFactory::constraint_note`]), for diagnoses.
    note: Option<String>,
    /// True after [`Integrator::step_deferred`]: the stepper may hold an
    /// update of the state not yet added ([`Stepper::settle`]).
    pending: bool,
}

impl Integrator {
    /// Build the model for a validated scene with its own method, factor
    /// once, and set the initial state (MODEL §5: beam straight and at rest,
    /// masses touching, loads switched on at t = 0, accelerations consistent
    /// with contact).
    pub fn new(sc: &Resolved) -> Result<Self> {
        Self::with_method(sc, scene_method(sc))
    }

    /// As [`Integrator::new`], with the method `factory` builds (whatever
    /// method the scene names; its contact settings and basis checked
    /// against this one, [`crate::scene::MethodInfo::accepts`]).
    pub fn with_method(sc: &Resolved, factory: &dyn MethodFactory) -> Result<Self> {
        factory.accepts(&sc.contact, sc.discretization)?;
        let mut sys = System::new(sc)?;
        let mut state = State::at_rest(sys.beam().n, sys.contacts());
        let init = if sc.scene.time.initial.is_rest() {
            sys.initial()?
        } else {
            // `[time] initial = "static"` (static_start.rs)
            static_start::static_start(&mut sys, sc, &mut state)?;
            sys.initial_at(Some((&state.d, &state.q)))?
        };
        let stepper = factory.build(sc, &mut sys, &mut state, init)?;
        if sys.has_chains() && !stepper.carries_chains() {
            return Err(chain::refusal(&factory.name()));
        }
        if !sys.physics.droppers.ready() {
            return Err(Error::invalid(
                "integrator.method",
                format!("\"{}\"", factory.name()),
                "cannot carry tension-only droppers (their responses A⁻¹r_d are formed once by a method with a constant step matrix): use generalized_alpha, newmark, hht or wbz, or linear = true on every [[dropper]]",
            ));
        }
        Ok(Integrator {
            sys,
            state,
            stepper,
            method: factory.name(),
            note: factory.constraint_note(sc),
            pending: false,
        })
    }

    /// Advance one step, t_n → t_{n+1}.
    pub fn step(&mut self) -> Result<()> {
        self.settle();
        self.stepper.step(&mut self.sys, &mut self.state)?;
        self.end_step();
        Ok(())
    }

    /// Advance one step whose last update of the state may stay pending
    /// ([`Stepper::step_deferred`]: one pass over the modes a step instead
    /// of two on `modal_exact`), for a whole run that reads the step only
    /// through [`Integrator::sample`] and [`Integrator::displacement_at`]
    /// (which account for it) until [`Integrator::settle`]. The same bits
    /// as [`Integrator::step`] once settled.
    pub(crate) fn step_deferred(&mut self) -> Result<()> {
        self.stepper.step_deferred(&mut self.sys, &mut self.state)?;
        self.pending = true;
        self.end_step();
        Ok(())
    }

    /// Add an update left pending by [`Integrator::step_deferred`].
    pub(crate) fn settle(&mut self) {
        if std::mem::take(&mut self.pending) {
            self.stepper.settle(&self.sys, &mut self.state);
        }
    }

    /// The driver's part of a step: time and the system's end of step.
    fn end_step(&mut self) {
        self.state.step += 1;
        self.state.t = self.state.step as f64 * self.sys.physics.dt;
        self.sys.end_step(&self.state);
    }

    /// Number of unknowns: free beam dofs plus one per mass (a multi-mass
    /// pantograph counts each of its masses).
    pub fn dofs(&self) -> usize {
        let lower: usize = self
            .sys
            .physics
            .masses
            .chains
            .iter()
            .flatten()
            .map(|c| c.n - 1)
            .sum();
        self.sys.physics.beam.n + self.sys.contacts() + lower
    }

    /// The beam model.
    pub fn beam(&self) -> &BeamModel {
        &self.sys.physics.beam
    }

    /// The shared system.
    pub fn system(&self) -> &System {
        &self.sys
    }

    /// The state at the current time.
    pub fn state(&self) -> &State {
        debug_assert!(!self.pending, "the state read with an update pending");
        &self.state
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.state.t
    }

    /// Steps taken.
    pub fn steps_taken(&self) -> usize {
        self.state.step
    }

    /// Current beam dofs d_b.
    pub fn beam_dofs(&self) -> &[f64] {
        debug_assert!(!self.pending, "the state read with an update pending");
        &self.state.d
    }

    /// Beam displacement v(x) (positive up), m, for a precomputed point vector.
    pub fn displacement_at(&self, pv: &PointVector) -> f64 {
        self.stepper.displacement_at(&self.sys, &self.state, pv)
    }

    /// Each dropper's force and slack state now, in scene order
    /// ([`System::dropper_samples_into`]).
    pub fn dropper_samples_into(&self, out: &mut [DropperSample]) {
        debug_assert!(!self.pending, "the state read with an update pending");
        self.sys
            .dropper_samples_into(&self.state.d, &self.state.v, out)
    }

    /// Number of carriers.
    pub fn carriers(&self) -> usize {
        self.sys.physics.carriers.len()
    }

    /// The values of carrier `i` at the current time.
    #[inline]
    pub fn sample(&self, i: usize) -> CarrierSample {
        sample::sample_of(&self.sys, &self.state, i, |pv| self.displacement_at(pv))
    }

    /// The discrete energy, J ([`Energy`]; allocates: for checks).
    pub fn energy(&self) -> Energy {
        debug_assert!(!self.pending, "the state read with an update pending");
        energy::energy(&self.sys, &self.state)
    }

    /// After a step: the recorded contact force acts at t − lag·Δt
    /// ([`System::force_lag`]).
    pub fn force_lag(&self) -> f64 {
        self.sys.force_lag(self.state.t)
    }

    /// Largest |λ| accepted before a run is taken as diverged, N.
    pub fn force_bound(&self) -> f64 {
        self.sys.law.force_bound
    }

    /// The method's name ([`crate::scene::MethodInfo::name`]).
    pub fn method(&self) -> &str {
        &self.method
    }

    /// Why this method may leave a moving contact's constraint undamped
    /// (Newmark, WBZ, HHT with small α), for warnings; `None` otherwise.
    pub fn constraint_damping_note(&self) -> Option<String> {
        diagnose::damping_note(&self.sys, self.note.as_deref())
    }

    /// True when x lies in the last element before a supported end.
    #[inline]
    pub fn near_support(&self, x: f64) -> bool {
        diagnose::near_support(&self.sys, x)
    }

    /// Hold `newtons` (N in +v, MODEL §2: up) on carrier `carrier`'s mass
    /// from the next step on, until changed, on top of its scene series if
    /// any (`external_force.rs`: the force enters the mass equation as
    /// `s·F`; constant over each step, so whatever the method's load time).
    /// Refused for a moving force (no mass) or a carrier that does not
    /// exist, and for a non-finite force.
    pub fn hold_external_force(&mut self, carrier: usize, newtons: f64) -> Result<()> {
        let n = self.sys.physics.carriers.len();
        let Some(c) = self.sys.physics.carriers.get(carrier) else {
            return Err(crate::error::Error::invalid(
                "carrier",
                carrier,
                format!("must name a carrier of the scene, 0 ..= {}", n - 1),
            ));
        };
        let Some(j) = c.contact else {
            return Err(crate::error::Error::invalid(
                format!("carrier.{carrier}"),
                "a moving force",
                "takes no external force: it has no mass to act on (apply forces to mass–spring carriers)",
            ));
        };
        if self.sys.physics.masses.chains[j].is_some() {
            return Err(crate::error::Error::invalid(
                format!("carrier.{carrier}"),
                "a multi-mass pantograph (carrier.masses)",
                "takes no external force yet: its chain is stepped by its own scheme (chain.rs), which does not read held forces (apply forces to single mass–spring carriers)",
            ));
        }
        if !newtons.is_finite() {
            return Err(crate::error::Error::invalid(
                "newtons",
                newtons,
                "must be a finite force (N, + up)",
            ));
        }
        self.sys.hold_external_force(j, newtons);
        Ok(())
    }

    /// Stop with a diagnosis if a recorded value is non-finite or absurd.
    pub fn check(&self, s: &CarrierSample, carrier: usize) -> Result<()> {
        diagnose::check(&self.sys, &self.state, s, carrier, self.note.as_deref())
    }

    /// [`Integrator::check`] with `near` = [`Integrator::near_support`] at
    /// `s.x` already known.
    #[inline]
    pub(crate) fn check_near(&self, s: &CarrierSample, carrier: usize, near: bool) -> Result<()> {
        diagnose::check_near(
            &self.sys,
            &self.state,
            s,
            carrier,
            self.note.as_deref(),
            near,
        )
    }
}
