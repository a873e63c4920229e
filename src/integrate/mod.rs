//! Time integration with point contact (MODEL §5, §9.1): the methods users
//! compare, side by side behind one seam.
//!
//! * [`System`] (`system.rs`): what every method shares — the beam, the
//!   carriers (`carrier.rs`: their contact kinematics and mass dofs), a
//!   manufactured source's loads, and the run's contact law, which it calls
//!   with each step's problem.
//! * [`StepMap`] (`step_map.rs`): how a method hands its step to the
//!   contact problem; `contact_problem.rs` forms the pair (g_free, W) from
//!   it at the acceleration, position or velocity level (MODEL §5, §6).
//! * [`State`] (`state.rs`): time, beam displacements and velocities, the
//!   mass dofs.
//! * [`Stepper`]: one method's step. A method is one file:
//!   `gen_alpha.rs` (generalized-α, Newmark, HHT, WBZ), `bathe.rs`,
//!   `central_difference.rs`, `moreau_jean.rs`, `modal_exact.rs` (with
//!   `oscillator.rs`, the exact step of one mode). [`stepper_for`] builds a
//!   built-in method's ([`crate::scene::Method`], described in
//!   `scene/method.rs`) from its scheme.
//! * `method.rs`: the seam — [`MethodFactory`] (a method's description and
//!   the stepper it builds) and the registry by name ([`register`],
//!   [`method_named`]). A method written outside the crate implements
//!   [`Stepper`] and [`MethodFactory`], registers itself, and runs from a
//!   scene, `--methods`, [`crate::run_with`] and the studies alike
//!   (`examples/custom_method.rs`).
//! * `diagnose.rs`: a run that goes unstable stops with a diagnosis;
//!   `energy.rs`: the discrete energy, for the checks.
//!
//! [`Integrator`] drives one run: it builds the system, the consistent
//! initial state and the stepper, and advances time.

mod batch;
mod batch_key;
mod batch_run;
mod bathe;
mod carrier;
mod central_difference;
mod chain;
mod contact_problem;
mod damped_modes;
mod diagnose;
mod dropper;
mod energy;
mod external_force;
mod gen_alpha;
mod gen_alpha_kernel;
mod gen_alpha_update;
mod method;
mod modal_batch;
mod modal_cruise;
mod modal_exact;
mod moreau_jean;
mod oscillator;
mod run_batch;
mod state;
mod static_start;
mod step_map;
mod system;

/// Columns of a step's right-hand side (the model's banded solves carry them
/// side by side): defined with the model, where the memory plan reads it too.
pub use crate::model::banded::rhs_columns;
pub use batch::{Batch, Lane, MAX_LANES, max_lanes};
pub use batch_key::{
    BatchKey, GenAlphaKey, ModalKey, batch_key, gen_alpha_key, modal_key, scene_columns,
};
pub use batch_run::{NewBatch, lanes_cap, new_batch};
pub use bathe::Bathe;
pub use carrier::MassDof;
pub use central_difference::{
    CentralDifference, StabilityLimit, central_difference_limit, stability_limit,
};
pub use chain::{Chain, ChainGenAlpha};
pub use dropper::DropperSample;
pub use energy::Energy;
pub use gen_alpha::GenAlpha;
pub use method::{
    MethodFactory, factory_of, method_named, parse_methods, register, scene_method, stepper_for,
};
pub use modal_batch::ModalBatch;
pub use modal_cruise::RESYNC_STEPS as CRUISE_RESYNC_STEPS;
pub use modal_exact::{ModalCoefs, ModalExact};
pub use moreau_jean::MoreauJean;
pub use oscillator::{MassStep, ModeSteps};
pub use run_batch::RunBatch;
pub use state::State;
pub use step_map::{Lanes, MassPrediction, Multipliers, StepMap, VelocityPrediction, combine};
pub use system::{Initial, System};

use crate::error::{Error, Result};
use crate::model::beam::{BeamModel, PointVector};
use crate::resolve::Resolved;
use crate::scene::CarrierKind;

/// One time integrator's step. Implement it (with a [`MethodFactory`]) to
/// add a method: `examples/custom_method.rs` does, outside the crate.
///
/// A step advances `st` from t_n to t_{n+1}: place the carriers
/// ([`System::place`]), solve the step with the contact multipliers as
/// unknowns (the free solution and one solution per contact,
/// [`System::scatter_loads`]), hand the contact problem to
/// [`System::solve_contact`] as a [`StepMap`], and update `st.d`, `st.v`,
/// `st.q`, `st.q_dot` with the multipliers ([`System::multipliers`]). The
/// driver then sets `st.step` and `st.t`. A step must not allocate.
pub trait Stepper: Send {
    /// Advance one step.
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()>;

    /// True when the method steps multi-mass pantographs (`chain.rs`,
    /// MODEL §10) whole; a run with one is refused by every other method.
    fn carries_chains(&self) -> bool {
        false
    }
}

/// The per-carrier values recorded after each step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CarrierSample {
    /// Position x_m, m.
    pub x: f64,
    /// Beam displacement under the carrier, w = s·v(x_m), m (positive into the beam).
    pub w: f64,
    /// Mass displacement q = s·ξ, m (positive into the beam; = w for a force).
    pub q: f64,
    /// Gap g = w − q, m.
    pub gap: f64,
    /// Contact force λ, N (the applied F for a moving force; P/Δt for a
    /// method working with impulses).
    pub force: f64,
    /// Contact closed this step.
    pub in_contact: bool,
}

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
        if !sys.droppers.ready() {
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
        })
    }

    /// Advance one step, t_n → t_{n+1}.
    pub fn step(&mut self) -> Result<()> {
        self.stepper.step(&mut self.sys, &mut self.state)?;
        self.state.step += 1;
        self.state.t = self.state.step as f64 * self.sys.dt;
        self.sys.end_step(&self.state);
        Ok(())
    }

    /// Number of unknowns: free beam dofs plus one per mass (a multi-mass
    /// pantograph counts each of its masses).
    pub fn dofs(&self) -> usize {
        let lower: usize = self.sys.chains.iter().flatten().map(|c| c.n - 1).sum();
        self.sys.beam.n + self.sys.contacts() + lower
    }

    /// The beam model.
    pub fn beam(&self) -> &BeamModel {
        &self.sys.beam
    }

    /// The shared system.
    pub fn system(&self) -> &System {
        &self.sys
    }

    /// The state at the current time.
    pub fn state(&self) -> &State {
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
        &self.state.d
    }

    /// Beam displacement v(x) (positive up), m, for a precomputed point vector.
    pub fn displacement_at(&self, pv: &PointVector) -> f64 {
        pv.dot(&self.state.d)
    }

    /// Each dropper's force and slack state now, in scene order
    /// ([`System::dropper_samples_into`]).
    pub fn dropper_samples_into(&self, out: &mut [DropperSample]) {
        self.sys
            .dropper_samples_into(&self.state.d, &self.state.v, out)
    }

    /// Number of carriers.
    pub fn carriers(&self) -> usize {
        self.sys.carriers.len()
    }

    /// The values of carrier `i` at the current time.
    pub fn sample(&self, i: usize) -> CarrierSample {
        sample_of(&self.sys, &self.state, i, |pv| pv.dot(&self.state.d))
    }

    /// The discrete energy, J ([`Energy`]; allocates: for checks).
    pub fn energy(&self) -> Energy {
        energy::energy(&self.sys, &self.state)
    }

    /// After a step: the recorded contact force acts at t − lag·Δt
    /// ([`System::force_lag`]).
    pub fn force_lag(&self) -> f64 {
        self.sys.force_lag(self.state.t)
    }

    /// Largest |λ| accepted before a run is taken as diverged, N.
    pub fn force_bound(&self) -> f64 {
        self.sys.force_bound
    }

    /// The method's name ([`crate::scene::MethodInfo::name`]).
    pub fn method(&self) -> &str {
        &self.method
    }

    /// Why this method may leave a moving contact's constraint undamped
    /// (Newmark, WBZ, HHT with small α), for warnings; `None` otherwise.
    pub fn constraint_damping_note(&self) -> Option<String> {
        damping_note_of(&self.sys, self.note.as_deref())
    }

    /// True when x lies in the last element before a supported end.
    pub fn near_support(&self, x: f64) -> bool {
        near_support_lane(&self.sys, x)
    }

    /// Hold `newtons` (N in +v, MODEL §2: up) on carrier `carrier`'s mass
    /// from the next step on, until changed, on top of its scene series if
    /// any (`external_force.rs`: the force enters the mass equation as
    /// `s·F`; constant over each step, so whatever the method's load time).
    /// Refused for a moving force (no mass) or a carrier that does not
    /// exist, and for a non-finite force.
    pub fn hold_external_force(&mut self, carrier: usize, newtons: f64) -> Result<()> {
        let n = self.sys.carriers.len();
        let Some(c) = self.sys.carriers.get(carrier) else {
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
        if self.sys.chains[j].is_some() {
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
        check_lane(&self.sys, &self.state, s, carrier, self.note.as_deref())
    }
}

/// The values of carrier `i` of a run: its system, its state, and `dot`,
/// which takes rᵀd of the run's beam displacements (its own vector, or its
/// lane of a batch's).
pub(crate) fn sample_of(
    sys: &System,
    st: &State,
    i: usize,
    dot: impl Fn(&PointVector) -> f64,
) -> CarrierSample {
    let c = &sys.carriers[i];
    let x = c.props.motion.position(st.t);
    let pv = if st.step == 0 { &c.pv_f } else { &c.pv_g };
    // r_gᵀd as the step computed it (modal_exact: from its pass's sums,
    // within round-off of the dot; `modal_exact.rs` tests)
    let rd = match c.gap_dot {
        Some((n, rd)) if n == st.step && n != 0 => rd,
        _ => dot(pv),
    };
    let w = c.s * rd;
    match (c.props.kind, c.contact) {
        (CarrierKind::Force { force }, _) => CarrierSample {
            x,
            w,
            q: w,
            gap: 0.0,
            force,
            in_contact: true,
        },
        (_, Some(j)) => {
            let force = sys.reported_force(j, st.step);
            CarrierSample {
                x,
                w,
                q: st.q[j],
                gap: w - st.q[j],
                force,
                in_contact: sys.active[j],
            }
        }
        _ => unreachable!("a mass carrier always has a contact"),
    }
}

/// [`Integrator::constraint_damping_note`] of a run's system (alone or in
/// a batch) whose method notes `note` ([`MethodFactory::constraint_note`]).
pub(crate) fn damping_note_of(sys: &System, note: Option<&str>) -> Option<String> {
    let moving = sys
        .carriers
        .iter()
        .any(|c| c.contact.is_some() && !c.props.motion.is_stationary());
    moving.then(|| note.map(str::to_string)).flatten()
}

/// [`Integrator::near_support`] of a run's system.
pub(crate) fn near_support_lane(sys: &System, x: f64) -> bool {
    diagnose::near_support(sys, x)
}

/// [`Integrator::check`] of a run (alone or in a batch) whose method
/// notes `note` ([`MethodFactory::constraint_note`]).
pub(crate) fn check_lane(
    sys: &System,
    st: &State,
    s: &CarrierSample,
    carrier: usize,
    note: Option<&str>,
) -> Result<()> {
    diagnose::check(sys, st, s, carrier, note)
}
