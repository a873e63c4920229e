//! Contact formulations (MODEL §6): each is a rule that, given the free gaps
//! `g_free` of a step and its Delassus matrix `W` (MODEL §5, g = g_free + Wλ),
//! returns the contact forces λ.
//!
//! Users pick a formulation through the serde enum
//! [`crate::scene::Formulation`]; the behaviour lives behind the crate-private
//! [`ContactLaw`] trait, so the integrator never knows which law it calls.

mod dense;
mod lagrange;

pub(crate) use lagrange::Lagrange;

use crate::scene::{ContactKind, ContactSpec, Formulation};

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
}

/// Build the law a scene asks for, for `nc` contacts.
pub(crate) fn law_for(spec: &ContactSpec, nc: usize) -> Box<dyn ContactLaw> {
    match spec.formulation {
        Formulation::Lagrange => Box::new(Lagrange::new(spec.kind == ContactKind::Bilateral, nc)),
    }
}
