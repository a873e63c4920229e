//! Contact formulations (MODEL §6): each is a rule that, given the free gaps
//! `g_free` of a step and its Delassus matrix `W` (MODEL §5, g = g_free + Wλ),
//! returns the contact forces λ (or impulses, at velocity level).
//!
//! Users pick a formulation through the serde enum
//! [`crate::scene::Formulation`]; the behaviour lives behind the crate-private
//! `ContactLaw` trait, one file per law with its `impl`. The velocity-level
//! law (`Impact`, `impact.rs`: Moreau's index set, restitution, the memory
//! of gap rates) sits beside them and solves its rate problem with one of
//! them. A run holds its law as a `RunLaw`, which says the level it works
//! at. The integrator forms `(g_free, W)` at that level
//! (`integrate::contact_problem`) and calls the law; a law never reaches into
//! an integrator. A law that fails returns a typed [`ContactFailure`], and
//! the system saves the problem it was given as a [`ContactProblem`] that
//! `replay` solves again.

mod complementarity;
mod dense;
pub mod failure;
mod impact;
mod lagrange;
mod penalty;
pub mod problem;
mod replay;

pub use failure::{ContactFailed, ContactFailure};
pub(crate) use problem::NotReplayable;
pub use problem::{ContactProblem, Level};
pub use replay::ReplayOutcome;
pub(crate) use replay::{SIGNORINI_TOLERANCE, replay, validate};

pub(crate) use impact::Impact;
pub(crate) use lagrange::Lagrange;

use crate::scene::{ContactKind, ContactSpec, DEFAULT_PENALTY_RELATIVE, Formulation};
use complementarity::Complementarity;
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
}

/// The rule a scene's formulation solves a pair (g_free, W) with, for
/// `nc` contacts: the law itself for a force-level formulation, and for
/// `impact` the Lagrange active set its rate problems are solved with (a
/// saved velocity-level problem is replayed by it, [`replay`]).
pub(crate) fn law_for(spec: &ContactSpec, nc: usize) -> Box<dyn ContactLaw> {
    let bilateral = spec.kind == ContactKind::Bilateral;
    match spec.formulation {
        Formulation::Lagrange | Formulation::Impact => Box::new(Lagrange::new(bilateral, nc)),
        Formulation::Penalty => Box::new(Penalty::new(kappa(spec), bilateral, nc)),
        Formulation::Complementarity => {
            Box::new(Complementarity::new(&spec.complementarity, bilateral, nc))
        }
    }
}

/// The penalty stiffness `[contact.penalty]` asks for: κ in N/m, or
/// relative to the step's 1/W (default `relative = 1000`).
fn kappa(spec: &ContactSpec) -> Kappa {
    match (spec.penalty.stiffness, spec.penalty.relative) {
        (Some(k), _) => Kappa::Absolute(k),
        (None, Some(r)) => Kappa::Relative(r),
        (None, None) => Kappa::Relative(DEFAULT_PENALTY_RELATIVE),
    }
}

/// [`law_for`] of a problem with `nc` contacts followed by `nd`
/// tension-only dropper rows (`integrate::dropper`): the same law on all
/// nc + nd rows, except that penalty leaves the dropper rows as they are —
/// a dropper's compliance 1/k_d is already on its diagonal, so the dropper
/// is its own penalty spring (κ = k_d), and the law is then exact on it.
pub(crate) fn law_with_droppers(spec: &ContactSpec, nc: usize, nd: usize) -> Box<dyn ContactLaw> {
    if nd == 0 {
        return law_for(spec, nc);
    }
    match spec.formulation {
        Formulation::Penalty => {
            let bilateral = spec.kind == ContactKind::Bilateral;
            Box::new(Penalty::new(kappa(spec), bilateral, nc + nd).penalize_first(nc))
        }
        _ => law_for(spec, nc + nd),
    }
}

/// A run's contact law at the level it works at: a force-level law on
/// position gaps, or the velocity-level [`Impact`] law.
pub(crate) enum RunLaw {
    /// Forces from gaps (m) and W (m/N).
    Force(Box<dyn ContactLaw>),
    /// Forces or impulses from gap rates (m/s) over Moreau's index set.
    Velocity(Box<Impact>),
}

impl RunLaw {
    /// The law a scene's `[contact]` asks for, for `nc` contacts: the
    /// impact law for `formulation = "impact"`, else the force-level law.
    pub(crate) fn new(spec: &ContactSpec, nc: usize) -> Self {
        let law = law_for(spec, nc);
        match spec.formulation {
            Formulation::Impact => RunLaw::at_velocity(law, spec, nc),
            _ => RunLaw::Force(law),
        }
    }

    /// [`RunLaw::new`] for `nc` contacts and `nd` tension-only droppers
    /// ([`law_with_droppers`]; droppers are refused with the `impact`
    /// formulation, `resolve::dropper`).
    pub(crate) fn with_droppers(spec: &ContactSpec, nc: usize, nd: usize) -> Self {
        if nd == 0 {
            return RunLaw::new(spec, nc);
        }
        RunLaw::Force(law_with_droppers(spec, nc, nd))
    }

    /// Make this law work at velocity level (a method that works with
    /// impulses, Moreau–Jean; once, before the run): a force-level law
    /// becomes the rule of an [`Impact`] law with the scene's restitution.
    pub(crate) fn make_velocity(&mut self, spec: &ContactSpec, nc: usize) {
        if let RunLaw::Force(rule) = self {
            // a placeholder with no scratch takes the rule's place while it moves
            let rule = std::mem::replace(rule, Box::new(Lagrange::new(false, 0)));
            *self = RunLaw::at_velocity(rule, spec, nc);
        }
    }

    fn at_velocity(rule: Box<dyn ContactLaw>, spec: &ContactSpec, nc: usize) -> Self {
        let bilateral = spec.kind == ContactKind::Bilateral;
        RunLaw::Velocity(Box::new(Impact::new(
            rule,
            spec.impact.restitution,
            bilateral,
            nc,
        )))
    }

    /// The level of the problems the law solves during the run.
    pub(crate) fn level(&self) -> Level {
        match self {
            RunLaw::Force(_) => Level::Position,
            RunLaw::Velocity(_) => Level::Velocity,
        }
    }

    /// The acceleration-level problem at t = 0 (MODEL §5).
    pub(crate) fn initial(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        match self {
            RunLaw::Force(law) => law.initial(g_free, w, lambda, active),
            RunLaw::Velocity(law) => law.initial(g_free, w, lambda, active),
        }
    }
}
