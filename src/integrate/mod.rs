//! Time integration with point contact (MODEL §5, §9.1): the methods users
//! compare, side by side behind one seam.
//!
//! * [`System`] (`system.rs`): what every method shares — the beam, the
//!   carriers and their contact kinematics, the mass dofs, and the contact
//!   problem of a step (free gaps, Delassus matrix, the law, at force or
//!   velocity level).
//! * [`State`] (`state.rs`): time, beam displacements and velocities, the
//!   mass dofs.
//! * [`Stepper`]: one method's step. A method is one file:
//!   `gen_alpha.rs` (generalized-α, Newmark, HHT, WBZ), `bathe.rs`,
//!   `central_difference.rs`, `moreau_jean.rs`, `modal_exact.rs` (with
//!   `oscillator.rs`, the exact step of one mode). [`stepper_for`] picks the
//!   one a scene asks for (`[integrator] method`, [`crate::scene::Method`]);
//!   a method written outside the crate implements [`Stepper`] and
//!   [`MethodFactory`] and runs through [`Integrator::with_method`],
//!   [`crate::run_with`] and the studies (`examples/custom_method.rs`).
//! * `diagnose.rs`: a run that goes unstable stops with a diagnosis;
//!   `energy.rs`: the discrete energy, for the checks.
//!
//! [`Integrator`] drives one run: it builds the system, the consistent
//! initial state and the stepper, and advances time.

mod batch;
mod batch_run;
mod bathe;
mod central_difference;
mod diagnose;
mod energy;
mod gen_alpha;
mod modal_batch;
mod modal_exact;
mod moreau_jean;
mod oscillator;
mod run_batch;
mod state;
mod system;

pub use batch::{Batch, Lane, MAX_LANES, max_lanes, scene_columns};
pub use batch_run::{NewBatch, batch_key, lanes_cap, new_batch};
pub use bathe::Bathe;
pub use central_difference::{
    CentralDifference, StabilityLimit, central_difference_limit, stability_limit,
};
pub use energy::Energy;
pub use gen_alpha::GenAlpha;
pub use modal_batch::{ModalBatch, modal_key};
pub use modal_exact::{ModalCoefs, ModalExact};
pub use moreau_jean::MoreauJean;
pub use oscillator::{MassStep, ModeSteps};
pub use run_batch::RunBatch;
pub use state::State;
pub use system::{
    Initial, MassDof, MassPrediction, Multipliers, StepMap, System, VelocityPrediction, combine,
    rhs_columns,
};

use crate::error::Result;
use crate::model::beam::{BeamModel, PointVector};
use crate::scene::{CarrierKind, IntegratorSpec, Method, Resolved, Scheme};

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
}

/// Builds a [`Stepper`] for a run: the built-in methods ([`Method`]) from
/// the scene's `[integrator]`, or a method of one's own.
pub trait MethodFactory: Sync {
    /// The name in tables and plots (`method` column of `compare.csv`).
    fn name(&self) -> String;

    /// `--set` overrides that select this method in a scene whose
    /// `[integrator]` is `base` (a built-in method sets `[integrator]`; a
    /// custom method needs none).
    fn overrides(&self, _base: &IntegratorSpec) -> Vec<String> {
        Vec::new()
    }

    /// Build the stepper for a validated scene, given its system and the
    /// consistent initial state (the accelerations in `init`; a method may
    /// adjust `st`, e.g. to a half-step velocity). A method that works with
    /// impulses says so with [`System::set_multipliers`].
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> Result<Box<dyn Stepper>>;

    /// True when this factory builds what the scene's own `[integrator]`
    /// builds (the built-in methods), so its runs may step in batches
    /// (`integrate::batch`); a method of one's own steps alone.
    fn is_scene_method(&self) -> bool {
        false
    }

    /// The method's formal order in Δt for the scene `sc` (the order of its
    /// local truncation error minus one, for smooth solutions), which
    /// `taut converge` and `taut verify` hold observed orders against;
    /// `None` when not declared.
    fn time_order(&self, _sc: &Resolved) -> Option<f64> {
        None
    }
}

impl MethodFactory for Method {
    fn name(&self) -> String {
        Method::name(*self).to_string()
    }

    /// `integrator = { method = "…" }` with the base scene's parameters that
    /// this method reads (a `rho_inf` of generalized-α is dropped for Bathe).
    fn overrides(&self, base: &IntegratorSpec) -> Vec<String> {
        let mut table = format!("integrator={{ method = \"{}\"", Method::name(*self));
        for (key, value) in [
            ("rho_inf", base.rho_inf),
            ("alpha", base.alpha),
            ("gamma", base.gamma),
            ("theta", base.theta),
        ] {
            if let Some(v) = value
                && self.parameters().contains(&key)
            {
                table.push_str(&format!(", {key} = {v:?}"));
            }
        }
        table.push_str(" }");
        vec![table]
    }

    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> Result<Box<dyn Stepper>> {
        stepper_for(sc, sys, st, init)
    }

    fn is_scene_method(&self) -> bool {
        true
    }

    /// 2 for the generalized-α family, Bathe and central difference; for
    /// Moreau–Jean 2 at θ = ½ (the trapezoidal rule) and 1 otherwise
    /// (MODEL §9.1). `sc` is a scene of this method (its `scheme`).
    fn time_order(&self, sc: &Resolved) -> Option<f64> {
        Some(match sc.scheme {
            Scheme::MoreauJean { theta } if theta != 0.5 => 1.0,
            _ => 2.0,
        })
    }
}

/// The stepper of the scene's own method (`sc.scheme`).
pub fn stepper_for(
    sc: &Resolved,
    sys: &mut System,
    st: &mut State,
    init: Initial,
) -> Result<Box<dyn Stepper>> {
    Ok(match sc.scheme {
        Scheme::GenAlpha(p) => Box::new(GenAlpha::new(p, sys, st, init)?),
        Scheme::Bathe { gamma } => Box::new(Bathe::new(gamma, sys, st, init)?),
        Scheme::CentralDifference => Box::new(CentralDifference::new(sc, sys, st, init)?),
        Scheme::MoreauJean { theta } => {
            sys.set_multipliers(Multipliers::Impulses);
            Box::new(MoreauJean::new(theta, sys, st)?)
        }
        Scheme::ModalExact => Box::new(ModalExact::new(sys)?),
    })
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
}

impl Integrator {
    /// Build the model for a validated scene with its own method, factor
    /// once, and set the initial state (MODEL §5: beam straight and at rest,
    /// masses touching, loads switched on at t = 0, accelerations consistent
    /// with contact).
    pub fn new(sc: &Resolved) -> Result<Self> {
        Self::build(sc, &|sc, sys, st, init| stepper_for(sc, sys, st, init))
    }

    /// As [`Integrator::new`], with the method `factory` builds.
    pub fn with_method(sc: &Resolved, factory: &dyn MethodFactory) -> Result<Self> {
        Self::build(sc, &|sc, sys, st, init| factory.build(sc, sys, st, init))
    }

    #[allow(clippy::type_complexity)]
    fn build(
        sc: &Resolved,
        make: &dyn Fn(&Resolved, &mut System, &mut State, Initial) -> Result<Box<dyn Stepper>>,
    ) -> Result<Self> {
        let mut sys = System::new(sc)?;
        let mut state = State::at_rest(sys.beam().n, sys.contacts());
        let init = sys.initial()?;
        let stepper = make(sc, &mut sys, &mut state, init)?;
        Ok(Integrator {
            sys,
            state,
            stepper,
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

    /// Number of unknowns: free beam dofs plus one per mass carrier.
    pub fn dofs(&self) -> usize {
        self.sys.beam.n + self.sys.contacts()
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

    /// Why this method may leave a moving contact's constraint undamped
    /// (Newmark, WBZ, HHT with small α), for warnings; `None` otherwise.
    pub fn constraint_damping_note(&self) -> Option<String> {
        damping_note_of(&self.sys)
    }

    /// True when x lies in the last element before a supported end.
    pub fn near_support(&self, x: f64) -> bool {
        near_support_lane(&self.sys, x)
    }

    /// Stop with a diagnosis if a recorded value is non-finite or absurd.
    pub fn check(&self, s: &CarrierSample, carrier: usize) -> Result<()> {
        check_lane(&self.sys, &self.state, s, carrier)
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
    let w = c.s * dot(pv);
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
/// a batch).
pub(crate) fn damping_note_of(sys: &System) -> Option<String> {
    let moving = sys
        .carriers
        .iter()
        .any(|c| c.contact.is_some() && !c.props.motion.is_stationary());
    moving
        .then(|| diagnose::weak_constraint_damping(sys))
        .flatten()
}

/// [`Integrator::near_support`] of a run's system.
pub(crate) fn near_support_lane(sys: &System, x: f64) -> bool {
    diagnose::near_support(sys, x)
}

/// [`Integrator::check`] of a run (alone or in a batch).
pub(crate) fn check_lane(
    sys: &System,
    st: &State,
    s: &CarrierSample,
    carrier: usize,
) -> Result<()> {
    diagnose::check(sys, st, s, carrier)
}
