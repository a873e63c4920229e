//! The generalized-α family (Chung & Hulbert 1993; MODEL §5): the study's
//! method, and Newmark, HHT and WBZ as named parameter sets of it.
//!
//! A run alone steps with the same kernel as a batch of runs
//! (`gen_alpha_kernel.rs`: the effective matrix factored once, the
//! one-product residual h − Kũ, the fused banded sweep, the contact
//! problem through the [`System`], the update pass), as one lane. The step
//! allocates nothing and does O(n) work.

use crate::error::Result;
use crate::scene::GenAlphaParams;

use super::gen_alpha_kernel::Kernel;
use super::state::State;
use super::stepper::Stepper;
use super::system::{Initial, System};

/// A generalized-α stepper for one run.
pub(crate) struct GenAlpha {
    kernel: Kernel,
}

impl GenAlpha {
    /// Factor A once and form the first predictors from the initial state.
    /// With tension-only droppers, form their responses A⁻¹r_d and W block
    /// once (`dropper.rs`: the rows imposed at the force level t_{n+1−α_f}).
    pub fn new(p: GenAlphaParams, sys: &mut System, st: &State, init: Initial) -> Result<Self> {
        let mut kernel = Kernel::new(p, sys.beam(), sys.damping(), sys.dt(), sys.columns(), 1)?;
        kernel.start(sys, &st.d, &st.v, init);
        if sys.physics.droppers.rows() > 0 {
            let c_d = p.beta * sys.dt() * sys.dt();
            let c_v = p.gamma * sys.dt();
            sys.physics
                .droppers
                .prepare(|x| kernel.solve_one(x), c_d, c_v, p.alpha_f);
        }
        Ok(GenAlpha { kernel })
    }
}

impl Stepper for GenAlpha {
    /// Advance one step, t_n → t_{n+1} (MODEL §5, "One step, spelled out"):
    /// the kernel's phases for the one lane.
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let kernel = &mut self.kernel;
        kernel.clear();
        kernel.load(0, sys, st);
        kernel.damp(&st.v);
        kernel.solve(sys.beam());
        kernel.contact(0, sys, st)?;
        kernel.add_dropper_responses(sys);
        kernel.update(&sys.beam().load, &mut st.d, &mut st.v, &[sys.multipliers()]);
        kernel.finish(0, sys, st);
        Ok(())
    }

    /// The chain's dofs step with the same rule (`mass_step.rs`).
    fn carries_chains(&self) -> bool {
        true
    }
}
