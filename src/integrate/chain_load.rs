//! The time-dependent forces on a multi-mass pantograph's masses during a
//! run (docs/lines.md P5): the aerodynamic part of its uplift,
//! `c_a·V(t)²` on the mass `uplift_mass` (V the carrier's speed profile),
//! and an `external_force` series on the mass `external_force.mass`.
//!
//! The chain starts at rest in its static state under these forces'
//! values at t = 0 ([`Chain::loaded`]), so its constant forces f₀ (P1) are
//! those of that state and a step adds what changed since:
//! `f₀(t) = f₀ + ΔF_u(t) e_a + s ΔF_ext(t) e_e` with
//! `ΔF_u = c_a (V(t)² − V(0)²)` (in z, toward the wire) and
//! `ΔF_ext = F_ext(t) − F_ext(0)` (in +v, so s times it in z). The methods
//! read f₀ at their load time within the step (`external_force.rs` lists
//! them: generalized-α t_{n+1−α_f}, Bathe each sub-step's end, central
//! difference t_n, Moreau–Jean t_{n+θ}), the load time of a single mass's
//! external force. A chain without either keeps its constant f₀ and its
//! arithmetic: no [`ChainLoad`] is made for it.

use crate::scene::{ChainProps, ForceSeries, MAX_CHAIN, Motion};

use super::chain::Chain;

/// One chain's time-dependent forces (module docs).
#[derive(Debug, Clone)]
pub(crate) struct ChainLoad {
    /// f₀ of the chain's static state at t = 0, N (in z).
    base: [f64; MAX_CHAIN],
    /// The carrier's motion (its speed V(t)).
    motion: Motion,
    /// c_a, N·s²/m², and the mass it acts on.
    coefficient: f64,
    uplift_mass: usize,
    /// V(0)², m²/s².
    v0_sq: f64,
    /// The external force series, the mass it acts on, and F_ext(0), N.
    series: Option<(ForceSeries, usize, f64)>,
    /// The carrier's side sign s.
    s: f64,
}

impl ChainLoad {
    /// The forces on the masses at t = 0 beyond F₀ (N, in z), for
    /// [`Chain::loaded`]: c_a V(0)² on the uplift mass and s F_ext(0) on
    /// the series' mass. `None` when the chain has no time-dependent force
    /// (c_a = 0 and no series): the constant uplift's arithmetic stands.
    pub(crate) fn initial_forces(
        p: &ChainProps,
        motion: &Motion,
        series: Option<&ForceSeries>,
        s: f64,
    ) -> Option<[f64; MAX_CHAIN]> {
        if p.uplift_coefficient == 0.0 && series.is_none() {
            return None;
        }
        let mut extra = [0.0; MAX_CHAIN];
        let v0 = motion.speed(0.0);
        extra[p.uplift_mass] += p.uplift_coefficient * v0 * v0;
        if let Some(f) = series {
            extra[f.mass()] += s * f.at(0.0);
        }
        Some(extra)
    }

    /// The time-dependent forces of a chain built by [`Chain::loaded`] from
    /// [`ChainLoad::initial_forces`].
    pub(crate) fn new(
        chain: &Chain,
        p: &ChainProps,
        motion: &Motion,
        series: Option<&ForceSeries>,
        s: f64,
    ) -> Self {
        let v0 = motion.speed(0.0);
        ChainLoad {
            base: chain.f0,
            motion: motion.clone(),
            coefficient: p.uplift_coefficient,
            uplift_mass: p.uplift_mass,
            v0_sq: v0 * v0,
            series: series.map(|f| (f.clone(), f.mass(), f.at(0.0))),
            s,
        }
    }

    /// Set the chain's f₀ at the load time `t` (module docs) and return
    /// its head's, which the head's mass dof takes. O(log n) in a table's
    /// or series' knots, no allocation.
    #[inline]
    pub(crate) fn apply(&self, t: f64, chain: &mut Chain) -> f64 {
        let mut f0 = self.base;
        if self.coefficient != 0.0 {
            let v = self.motion.speed(t);
            f0[self.uplift_mass] += self.coefficient * (v * v - self.v0_sq);
        }
        if let Some((series, mass, at0)) = &self.series {
            f0[*mass] += self.s * (series.at(t) - at0);
        }
        chain.f0 = f0;
        f0[0]
    }
}
