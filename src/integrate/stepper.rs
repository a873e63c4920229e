//! The seam a time integrator's step stands behind (MODEL §5, §9.1): one
//! method's step of the shared [`System`].

use crate::error::Result;
use crate::model::beam::PointVector;

use super::state::State;
use super::system::System;

/// One time integrator's step. Implement it (with a [`MethodFactory`](super::MethodFactory)) to
/// add a method: `examples/custom_method.rs` does, outside the crate.
///
/// A step advances `st` from t_n to t_{n+1}: place the carriers
/// ([`System::place`]), solve the step with the contact multipliers as
/// unknowns (the free solution and one solution per contact,
/// [`System::scatter_loads`]), hand the contact problem to
/// [`System::solve_contact`] as a [`StepMap`](super::StepMap), and update `st.d`, `st.v`,
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

    /// Advance one step, possibly leaving the step's last update of `st.d`
    /// and `st.v` pending, to be added by the next step's pass over the
    /// unknowns (one pass a step instead of two: `modal_exact` with one
    /// contact). `st` is the step's state only after [`Stepper::settle`];
    /// [`Stepper::displacement_at`] reads it as settled without settling.
    /// By default a whole [`Stepper::step`], nothing left pending.
    fn step_deferred(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        self.step(sys, st)
    }

    /// Add an update left pending by [`Stepper::step_deferred`] into `st`
    /// (the operations the step would have taken: the same bits). By
    /// default there is none.
    fn settle(&mut self, _sys: &System, _st: &mut State) {}

    /// `pvᵀd` of `st` as [`Stepper::settle`] would leave it, the same bits
    /// as the dot on the settled state. By default `pv · st.d`.
    fn displacement_at(&self, _sys: &System, st: &State, pv: &PointVector) -> f64 {
        pv.dot(&st.d)
    }
}
