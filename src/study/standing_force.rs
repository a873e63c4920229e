//! The exact time history of a *discretized* beam under standing forces
//! switched on at t = 0 (`[reference] kind = "standing_force_modes"`): with
//! the model's own eigenpairs (K φⱼ = ωⱼ² M φⱼ, φⱼᵀMφⱼ = 1) and the constant
//! load F (distributed load and the carriers' point forces), starting
//! straight and at rest,
//!
//! ```text
//!   d(t) = Σⱼ φⱼ (φⱼᵀF) (1 − cos ωⱼt)/ωⱼ²      ((1 − cos ωt)/ω² → t²/2 for a rigid mode)
//! ```
//!
//! This is what a time integrator should produce on that model with no
//! time error: a reference with no space error, for Δt orders alone. On the
//! one-dof oscillator scene it is d_s(1 − cos ωt) with d_s = F/K.

use crate::error::{Error, Result};
use crate::model::beam::{Basis, BeamModel};
use crate::model::eigen::{MAX_MODAL_DOFS, lowest_eigenpairs};
use crate::resolve::Resolved;
use crate::scene::CarrierKind;

/// The modal solution of one scene's model.
#[derive(Debug, Clone)]
pub(crate) struct StandingForce {
    beam: BeamModel,
    /// ωⱼ, rad/s.
    omega: Vec<f64>,
    /// φⱼ (n entries each, in the model's unknowns) times φⱼᵀF.
    weighted: Vec<Vec<f64>>,
}

impl StandingForce {
    /// Build the model of `sc` and its eigenpairs (dense: at most
    /// [`MAX_MODAL_DOFS`] unknowns).
    pub fn new(sc: &Resolved) -> Result<Self> {
        let beam = BeamModel::build(&sc.beam, &sc.mesh_plan())?;
        let n = beam.n;
        if n > MAX_MODAL_DOFS {
            return Err(Error::invalid(
                "reference.kind",
                "\"standing_force_modes\"",
                format!(
                    "needs the model's full eigenproblem, at most {MAX_MODAL_DOFS} unknowns; this mesh has {n}: use fewer elements"
                ),
            ));
        }
        let mut f = beam.load.clone();
        for c in &sc.carriers {
            if let CarrierKind::Force { force } = c.kind {
                beam.point_vector(c.motion.position(0.0)).scatter(
                    c.side.sign() * force,
                    &mut f,
                    1,
                    0,
                );
            }
        }
        let (omega, weighted) = match beam.basis {
            // mass-normalized diagonal bases: the unknowns are the modes
            Basis::Modal { .. } | Basis::Galerkin(_) => {
                let omega: Vec<f64> = (0..n).map(|j| beam.stiffness.get(j, j).sqrt()).collect();
                let weighted = (0..n)
                    .map(|j| {
                        let mut e = vec![0.0; n];
                        e[j] = f[j];
                        e
                    })
                    .collect();
                (omega, weighted)
            }
            Basis::Elements => {
                let pairs = lowest_eigenpairs(&beam.mass, &beam.stiffness, n)?;
                let omega = pairs.omega_sq.iter().map(|w| w.max(0.0).sqrt()).collect();
                let weighted = (0..n)
                    .map(|j| {
                        let phi = pairs.shape(j);
                        let p: f64 = phi.iter().zip(&f).map(|(a, b)| a * b).sum();
                        phi.iter().map(|v| v * p).collect()
                    })
                    .collect();
                (omega, weighted)
            }
        };
        Ok(StandingForce {
            beam,
            omega,
            weighted,
        })
    }

    /// v(x, t) = r(x)ᵀ d(t), m (positive up).
    pub fn v(&self, x: f64, t: f64) -> f64 {
        let r = self.beam.point_vector(x);
        self.omega
            .iter()
            .zip(&self.weighted)
            .map(|(&w, phi)| {
                let g = if w * t < 1e-4 {
                    // (1 − cos ωt)/ω² by its series: no cancellation
                    0.5 * t * t * (1.0 - (w * t).powi(2) / 12.0)
                } else {
                    (1.0 - (w * t).cos()) / (w * w)
                };
                g * r.dot(phi)
            })
            .sum()
    }
}
