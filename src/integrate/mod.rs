//! Time integration with point contact (MODEL §5, §9.1): the methods users
//! compare, side by side behind one seam.
//!
//! * [`System`] (`system.rs`): what every method shares — what a run steps
//!   (`physics.rs`: the beam, the carriers `carrier.rs`, their mass dofs
//!   `mass_dofs.rs`, the droppers `dropper.rs`, a manufactured source), the
//!   contact law's state (`law_state.rs`), and the step's contact problem.
//! * [`StepMap`] (`step_map.rs`): how a method hands its step to the contact
//!   problem; `contact_problem.rs` forms (g_free, W) at the acceleration,
//!   position or velocity level (MODEL §5, §6). [`State`]: t, d, v, mass dofs.
//! * [`Stepper`] (`stepper.rs`): one method's step, one file each:
//!   `gen_alpha.rs` (generalized-α, Newmark, HHT, WBZ; `gen_alpha_kernel.rs`),
//!   `bathe.rs`, `central_difference.rs`, `moreau_jean.rs`, `modal_exact.rs`
//!   (`oscillator.rs`, `modal_kernels.rs`); each steps the mass dofs with a
//!   `Stage` that `mass_step.rs` applies to a mass or a chain (`chain.rs`).
//! * `method.rs`: the seam — [`MethodFactory`], [`register`], `factory_of`
//!   over the scene layer's registry (`scene/method_registry.rs`). A method
//!   written outside the crate implements [`Stepper`] and [`MethodFactory`],
//!   registers itself, and runs from a scene, `--methods`, [`crate::run_with`]
//!   and the studies alike (`examples/custom_method.rs`).
//! * `diagnose.rs` (a diagnosis when a run goes unstable), `energy.rs`,
//!   `sample.rs` (what a run records of each carrier).
//!
//! [`Integrator`] (`integrator.rs`) drives one run: it builds the system, the
//! consistent initial state and the stepper, and advances time. This file only
//! declares the layer's files and re-exports its public face.

mod batch;
mod batch_key;
mod batch_run;
mod bathe;
mod carrier;
mod central_difference;
mod chain;
mod chain_load;
#[cfg(test)]
mod chain_steps;
mod contact_problem;
mod damped_modes;
mod diagnose;
mod dropper;
mod energy;
mod external_force;
mod form_finding;
mod gen_alpha;
mod gen_alpha_kernel;
mod gen_alpha_update;
mod integrator;
mod law_state;
mod mass_dofs;
mod mass_step;
mod method;
mod modal_batch;
mod modal_cruise;
mod modal_exact;
mod modal_impact;
mod modal_kernels;
#[cfg(target_arch = "x86_64")]
mod modal_table_avx512;
mod moreau_jean;
mod oscillator;
mod physics;
mod run_batch;
mod sample;
mod state;
mod static_start;
mod step_map;
mod stepper;
mod system;

pub(crate) use batch::MAX_LANES;
pub use batch::{Batch, Lane, max_lanes};
pub use batch_key::{BatchKey, GenAlphaKey, ModalKey, batch_key};
pub(crate) use batch_run::lanes_cap;
pub use batch_run::new_batch;
pub use central_difference::{CentralDifference, StabilityLimit, central_difference_limit};
pub(crate) use diagnose::{
    check_near as check_near_lane, damping_note as damping_note_of,
    near_support as near_support_lane,
};
pub use dropper::DropperSample;
pub use energy::Energy;
pub use form_finding::{FORM_TOLERANCE, FormFound, MAX_FORM_DROPPERS, StaticDropper};
pub use integrator::Integrator;
pub use mass_dofs::MassDof;
pub(crate) use method::scene_method;
pub use method::{MethodFactory, parse_methods, register};
pub use modal_cruise::RESYNC_STEPS as CRUISE_RESYNC_STEPS;
pub use oscillator::ModeSteps;
pub use run_batch::RunBatch;
pub use sample::CarrierSample;
pub use state::State;
pub use step_map::{MassPrediction, StepMap, VelocityPrediction, combine};
pub use stepper::Stepper;
pub use system::{Initial, System};
