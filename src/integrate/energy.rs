//! The discrete energy of a state, J: the check that a method conserves or
//! dissipates what it should (MODEL §9.1; `tests/methods.rs`). A damping
//! matrix C (docs/lines.md §10.4) dissipates `∫ ḋᵀC ḋ dt`, which is not
//! accumulated here: with C this energy decreases by it.

use crate::scene::CarrierKind;

use super::state::State;
use super::system::System;

/// The parts of the discrete energy, J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    /// ½vᵀMv + Σ ½m q̇².
    pub kinetic: f64,
    /// ½dᵀKd + Σ ½k q².
    pub strain: f64,
    /// −(constant loads)ᵀd.
    pub load_potential: f64,
}

impl Energy {
    /// The total.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.load_potential
    }

    /// The size of its parts, for round-off bounds.
    pub fn scale(&self) -> f64 {
        self.kinetic.abs() + self.strain.abs() + self.load_potential.abs()
    }
}

/// ½vᵀMv + ½dᵀKd of the beam, ½m q̇² + ½k q² of each mass, minus the
/// potential of the constant loads (distributed load, preload and gravity on
/// the masses, standing forces). K and the load hold every tension-only
/// dropper's spring and preload (`dropper.rs`, D7), so a slack dropper's
/// strain and preload energy are counted too: the balance is the linear
/// twin's, for checks on runs whose droppers stay taut.
///
/// With ρ∞ = 1 generalized-α is the trapezoidal rule, for which
/// E_{n+1} − E_n = Δdᵀ f̄ exactly (linear system); a contact force whose
/// point does not move and that closes g_{n+1} = g_n = 0 does no work, so
/// E is conserved to round-off while contacts do not switch; with ρ∞ < 1
/// it does not grow. Newmark and Moreau–Jean with θ = ½ are the same
/// trapezoidal rule. Central difference keeps v_{n−1/2}, so this energy
/// oscillates for it (its conserved quantity is a shadow energy). Moving
/// loads do work, so E is not conserved then.
/// Allocates scratch vectors: for checks, not for the step loop.
pub(crate) fn energy(sys: &System, st: &State) -> Energy {
    let n = sys.physics.beam.n;
    let mut mv = vec![0.0; n];
    sys.physics.beam.mass.mul_acc(&st.v, 1.0, &mut mv);
    let mut kd = vec![0.0; n];
    sys.physics.beam.stiffness.mul_acc(&st.d, 1.0, &mut kd);
    let mut e = Energy::default();
    for i in 0..n {
        e.kinetic += 0.5 * st.v[i] * mv[i];
        e.strain += 0.5 * st.d[i] * kd[i];
        e.load_potential -= sys.physics.beam.load[i] * st.d[i];
    }
    for c in &sys.physics.carriers {
        match (c.props.kind, c.contact) {
            (_, Some(j)) => {
                let m = sys.physics.masses.heads[j];
                e.kinetic += 0.5 * m.m * st.q_dot[j] * st.q_dot[j];
                e.strain += 0.5 * m.k * st.q[j] * st.q[j];
                e.load_potential -= m.f0 * st.q[j];
            }
            (CarrierKind::Force { force }, None) => {
                e.load_potential -= c.s * force * c.pv_g.dot(&st.d)
            }
            _ => {}
        }
    }
    e
}
