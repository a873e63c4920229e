//! Contact formulations (MODEL §6): each is a rule that, given the free gaps
//! `g_free` of a step and its Delassus matrix `W` (MODEL §5, g = g_free + Wλ),
//! returns the contact forces λ.
//!
//! Users pick a formulation through the serde enum
//! [`crate::scene::Formulation`]; the behaviour lives behind the crate-private
//! [`ContactLaw`] trait, so the integrator never knows which law it calls.

mod complementarity;
mod dense;
mod lagrange;
mod penalty;

pub use complementarity::{ContactProblem, replay};
pub(crate) use lagrange::Lagrange;
pub(crate) use penalty::{Kappa, Penalty};

use crate::scene::{ContactKind, ContactSpec, DEFAULT_PENALTY_RELATIVE, Formulation};
use complementarity::Complementarity;

/// A contact law: λ from (g_free, W).
pub(crate) trait ContactLaw {
    /// Compute the forces.
    ///
    /// * `g_free` — gaps of the step taken with λ = 0 (m, or m/s² for the
    ///   initial acceleration-level problem), one per contact;
    /// * `w` — Delassus matrix, row-major `w[i * nc + j]` = ∂g_i/∂λ_j (m/N);
    /// * `lambda` — output forces, N;
    /// * `active` — output: true where the contact is closed (λ from g = 0).
    ///
    /// Must not allocate: it runs once per step.
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), String>;

    /// The acceleration-level problem at t = 0 (MODEL §5: initial
    /// accelerations consistent with contact). `g_free` is then the free gap
    /// acceleration (m/s²) and `w` is r M⁻¹ rᵀ (1/kg). Defaults to `solve`.
    fn initial(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), String> {
        self.solve(g_free, w, lambda, active)
    }

    /// After a failed `solve`, the problem as JSON so it can be saved and
    /// replayed (laws backed by an external solver keep it).
    fn failed_problem(&mut self) -> Option<String> {
        None
    }

    /// True when the law works at velocity level (the `impact` formulation):
    /// the integrator then passes gap rates and the velocity Delassus matrix.
    fn velocity_level(&self) -> bool {
        false
    }
}

impl ContactLaw for Complementarity {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), String> {
        self.solve_qp(g_free, w, lambda, active)
    }

    fn failed_problem(&mut self) -> Option<String> {
        self.failed
            .take()
            .and_then(|p| serde_json::to_string_pretty(&p).ok())
    }
}

/// The velocity-level law: the Lagrange active set applied to gap rates.
struct Impact(Lagrange);

impl ContactLaw for Impact {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), String> {
        self.0.solve(g_free, w, lambda, active)
    }

    fn velocity_level(&self) -> bool {
        true
    }
}

/// Build the law a scene asks for, for `nc` contacts.
pub(crate) fn law_for(spec: &ContactSpec, nc: usize) -> Box<dyn ContactLaw> {
    match spec.formulation {
        Formulation::Lagrange => Box::new(Lagrange::new(spec.kind == ContactKind::Bilateral, nc)),
        Formulation::Penalty => {
            let kappa = match (spec.penalty.stiffness, spec.penalty.relative) {
                (Some(k), _) => Kappa::Absolute(k),
                (None, Some(r)) => Kappa::Relative(r),
                (None, None) => Kappa::Relative(DEFAULT_PENALTY_RELATIVE),
            };
            Box::new(Penalty::new(kappa, spec.kind == ContactKind::Bilateral, nc))
        }
        Formulation::Complementarity => Box::new(Complementarity::new(
            &spec.complementarity,
            spec.kind == ContactKind::Bilateral,
        )),
        Formulation::Impact => Box::new(Impact(Lagrange::new(
            spec.kind == ContactKind::Bilateral,
            nc,
        ))),
    }
}
