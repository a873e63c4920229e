//! External forces on the mass dofs during a run: a scene's series
//! (`external_force`, [`ForceSeries`]) and a force held from outside
//! between steps (`taut::app::Simulation::apply_force`), one hook for both.
//!
//! Sign (MODEL §2): `F_ext` acts on the mass in +v (up), so mass dof j of
//! carrier side s gets `f0_j(t) = k δ0 − s·m·g + s·(F_series(t) + F_held)`
//! in `m q̈ + c_s q̇ + k q = f0 − λ`. The methods read `f0` at their load
//! time within the step (`System::place` sets them, `mass_dofs.rs`: generalized-α
//! t_{n+1−α_f}, Bathe each sub-step's end, central difference t_n,
//! Moreau–Jean t_{n+θ}; `modal_exact` holds it at the step's midpoint), so
//! a held force, constant over the step, is the same whatever the method's
//! load time. A run without either costs one `Option` test per step.

use crate::scene::ForceSeries;

/// The external forces of a run's mass dofs (module docs).
#[derive(Debug, Clone)]
pub(crate) struct ExternalForces {
    /// Each mass dof's series, if any.
    pub(crate) series: Vec<Option<ForceSeries>>,
    /// Each mass dof's held force, N in +v (0 until set).
    pub(crate) held: Vec<f64>,
}

impl ExternalForces {
    /// No series and no force held, for `nc` mass dofs.
    pub(crate) fn new(nc: usize) -> Self {
        ExternalForces {
            series: vec![None; nc],
            held: vec![0.0; nc],
        }
    }

    /// The external force on mass dof `j` at `t`, N in +v.
    #[inline]
    pub(crate) fn force(&self, j: usize, t: f64) -> f64 {
        match &self.series[j] {
            Some(s) => s.at(t) + self.held[j],
            None => self.held[j],
        }
    }
}
