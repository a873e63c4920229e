//! The impact law (MODEL §6, "an impact-capable velocity-level variant"):
//! Signorini–Newton at velocity level, `0 ≤ ġ_{n+1} + e ġ_n ⊥ λ ≥ 0`, solved
//! by the Lagrange active set on gap rates. The integrator's system forms the
//! rate problem (index set, restitution, the convective part of a moving
//! contact's gap rate) from any force-level method; this law only asks for it.

use super::{ContactFailure, ContactLaw, Lagrange, Level};

/// The velocity-level law: the Lagrange active set applied to gap rates.
pub(crate) struct Impact(Lagrange);

impl Impact {
    /// A law for `nc` contacts.
    pub(crate) fn new(bilateral: bool, nc: usize) -> Self {
        Impact(Lagrange::new(bilateral, nc))
    }
}

impl ContactLaw for Impact {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        self.0.solve(g_free, w, lambda, active)
    }

    fn level(&self) -> Level {
        Level::Velocity
    }
}
