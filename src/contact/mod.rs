//! Contact formulations (MODEL §6): each is a rule that, given the free gaps
//! `g_free` of a step and its Delassus matrix `W` (MODEL §5, g = g_free + Wλ),
//! returns the contact forces λ (or impulses, at velocity level).
//!
//! Users pick a formulation through the serde enum
//! [`crate::scene::Formulation`]; the behaviour lives behind the crate-private
//! [`ContactLaw`] trait, one file per law with its `impl`. The integrator's
//! [`System`](crate::integrate::System) forms `(g_free, W)` at the level the
//! law asks for ([`Level`]) and calls it; a law never reaches into an
//! integrator. A law that fails returns a typed [`ContactFailure`], and the
//! system saves the problem it was given as a [`ContactProblem`] that
//! [`replay`] solves again.

mod complementarity;
mod dense;
pub mod failure;
mod impact;
mod lagrange;
mod penalty;
pub mod problem;
mod replay;

pub use failure::{ContactFailed, ContactFailure};
pub use problem::{ContactProblem, Level};
pub use replay::{MAX_REPLAY_CONTACTS, ReplayOutcome, SIGNORINI_TOLERANCE, replay, validate};

pub(crate) use lagrange::Lagrange;

use crate::scene::{ContactKind, ContactSpec, DEFAULT_PENALTY_RELATIVE, Formulation};
use complementarity::Complementarity;
use impact::Impact;
use penalty::{Kappa, Penalty};

/// A contact law: λ from (g_free, W).
pub(crate) trait ContactLaw: Send {
    /// Compute the forces.
    ///
    /// * `g_free` — gaps of the step taken with λ = 0, one per contact: m at
    ///   position level, m/s at velocity level, m/s² for the initial
    ///   acceleration-level problem;
    /// * `w` — Delassus matrix, row-major `w[i * nc + j]` = ∂g_i/∂λ_j;
    /// * `lambda` — output forces (N) or impulses (N·s at velocity level);
    /// * `active` — output: true where the contact is closed (λ from g = 0).
    ///
    /// Must not allocate: it runs once per step.
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure>;

    /// The acceleration-level problem at t = 0 (MODEL §5: initial
    /// accelerations consistent with contact). `g_free` is then the free gap
    /// acceleration (m/s²) and `w` is r M⁻¹ rᵀ (1/kg). Defaults to `solve`.
    fn initial(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        self.solve(g_free, w, lambda, active)
    }

    /// The level of the problem the law solves during the run.
    fn level(&self) -> Level {
        Level::Position
    }
}

/// Build the law a scene asks for, for `nc` contacts.
pub(crate) fn law_for(spec: &ContactSpec, nc: usize) -> Box<dyn ContactLaw> {
    let bilateral = spec.kind == ContactKind::Bilateral;
    match spec.formulation {
        Formulation::Lagrange => Box::new(Lagrange::new(bilateral, nc)),
        Formulation::Penalty => {
            let kappa = match (spec.penalty.stiffness, spec.penalty.relative) {
                (Some(k), _) => Kappa::Absolute(k),
                (None, Some(r)) => Kappa::Relative(r),
                (None, None) => Kappa::Relative(DEFAULT_PENALTY_RELATIVE),
            };
            Box::new(Penalty::new(kappa, bilateral, nc))
        }
        Formulation::Complementarity => {
            Box::new(Complementarity::new(&spec.complementarity, bilateral, nc))
        }
        Formulation::Impact => Box::new(Impact::new(bilateral, nc)),
    }
}
