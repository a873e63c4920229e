//! Where a carrier's contact loss is a number to quote, and where it is not.
//!
//! **The support zone.** A pinned or clamped end forces w = 0. A carrier
//! that arrives there with the beam under it still deflected is driven to
//! w = 0 over the beam's bending boundary layer, of width ℓ_b = sqrt(EI/T):
//! on a taut string (EI = 0) the trajectory of a moving mass is
//! discontinuous at the support (Smith 1964; Dyniewicz & Bajer), and on a
//! tensioned beam the same arrival is an impact whose loss does not converge
//! in Δt (`docs/contact_loss.md`). The zone is the part of the span within
//!
//! ```text
//! z = 4·ℓ_b                     (EI > 0, T > 0)
//! z = 4·V·m/Z,  Z = 2·sqrt(T·ρA) (a string, EI = 0)
//! z = 0                          (no tension: no boundary layer)
//! ```
//!
//! of a held (not free) end: a few bending lengths, or on a string, where
//! there is no boundary layer, the distance the carrier travels in a few of
//! its contact's relaxation times m/Z (the time a mass m takes to settle on
//! a string of drive-point impedance Z). Both are lengths of the physics,
//! never of the discretization: a zone that followed h or Δt would make
//! each level of a refinement study measure a different P_l (MODEL §7).
//! `[analysis] support_zone` sets z. P_l splits into an in-span part and a
//! support part over the same window: they add up to P_l.
//!
//! **Suspect losses.** A loss interval that lasts fewer than
//! `MIN_RESOLVED_LOSS_STEPS` steps, or less than the time the carrier
//! takes to cross one element (h/V), away from the support zone, is below
//! what the run resolves: a resolution artefact is likely
//! (`docs/convergence.md`). Such intervals are counted and warned about.

use serde::Serialize;

use crate::resolve::Resolved;
use crate::scene::Support;

/// Bending lengths ℓ_b = sqrt(EI/T) in the support zone: the boundary layer
/// decays like e^(−x/ℓ_b), to 2 % at 4 ℓ_b; measured on the reference case at
/// V0/c = 0.9 and N = 1600, the non-converging loss lies within the last
/// 0.25 m ≈ 3.8 ℓ_b (`docs/contact_loss.md`).
pub const SUPPORT_BENDING_LENGTHS: f64 = 4.0;

/// Relaxation times m/Z of travel in a string's support zone (EI = 0, no
/// bending length): the contact of a mass m on a string of impedance Z
/// settles as e^(−t·Z/m), to 2 % after 4 of them.
pub const SUPPORT_RELAXATION_TIMES: f64 = 4.0;

/// A loss interval shorter than this many steps is not resolved in time.
pub(crate) const MIN_RESOLVED_LOSS_STEPS: usize = 3;

/// Where a carrier's losses count as in the span or at a support, and what a
/// run resolves.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct LossGeometry {
    /// Span L, m.
    pub length: f64,
    /// Width z of the support zone at each held end, m (0: no zone).
    pub support_zone: f64,
    /// Whether each end (x = 0, x = L) is held (pinned or clamped).
    #[serde(skip)]
    pub held: (bool, bool),
    /// h/V, s: the time the carrier takes to cross one element (null for a
    /// carrier at rest).
    pub element_passing_time: Option<f64>,
}

impl LossGeometry {
    /// No support zone and no resolution criterion in time (statistics of a
    /// bare trace on a span of `length` m).
    pub fn span_only(length: f64) -> Self {
        LossGeometry {
            length,
            support_zone: 0.0,
            held: (false, false),
            element_passing_time: None,
        }
    }

    /// The zone and resolution of carrier `carrier` of a scene.
    pub fn of(sc: &Resolved, carrier: usize) -> Self {
        let b = &sc.beam;
        let h = sc.resolution();
        let bending_length = if b.tension > 0.0 {
            (b.ei / b.tension).sqrt()
        } else {
            0.0
        };
        let v = sc
            .carriers
            .get(carrier)
            .map_or(0.0, |c| c.motion.profile.cruise_speed().abs());
        let physical = if bending_length > 0.0 {
            SUPPORT_BENDING_LENGTHS * bending_length
        } else {
            // a string: the carrier's travel over its contact's relaxation
            let impedance = 2.0 * (b.tension.max(0.0) * b.rho_a).sqrt();
            let mass = sc.carriers.get(carrier).map_or(0.0, |c| match c.kind {
                crate::scene::CarrierKind::MassSpring { mass, .. } => mass,
                crate::scene::CarrierKind::Force { .. } => 0.0,
            });
            if impedance > 0.0 {
                SUPPORT_RELAXATION_TIMES * v * mass / impedance
            } else {
                0.0
            }
        };
        // a zone never covers more than half the span
        let zone = sc
            .analysis
            .support_zone
            .unwrap_or(physical.min(0.5 * b.length));
        let held = |s: Support| s != Support::Free;
        LossGeometry {
            length: b.length,
            support_zone: zone,
            held: (held(b.left), held(b.right)),
            element_passing_time: (v > 0.0).then(|| h / v),
        }
    }

    /// Whether position `x` (m) lies in a support zone.
    pub fn in_support_zone(&self, x: f64) -> bool {
        (self.held.0 && x < self.support_zone)
            || (self.held.1 && x > self.length - self.support_zone)
    }

    /// Whether a loss interval of `steps` steps lasting `duration` s is
    /// shorter than what the run resolves.
    pub fn unresolved(&self, steps: usize, duration: f64) -> bool {
        steps < MIN_RESOLVED_LOSS_STEPS || self.element_passing_time.is_some_and(|p| duration < p)
    }
}

/// The support zone of scene `sc`, m: `[analysis] support_zone` when
/// given, else the widest of its carriers' default zones (0 without a
/// carrier).
pub fn support_zone_of(sc: &Resolved) -> f64 {
    (0..sc.carriers.len())
        .map(|c| LossGeometry::of(sc, c).support_zone)
        .fold(sc.analysis.support_zone.unwrap_or(0.0), f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_in_the_zone_of_a_held_end_only() {
        let g = LossGeometry {
            length: 50.0,
            support_zone: 0.5,
            held: (true, false),
            element_passing_time: Some(1e-3),
        };
        assert!(g.in_support_zone(0.4) && !g.in_support_zone(0.6));
        assert!(!g.in_support_zone(49.9), "a free end has no zone");
        assert!(g.unresolved(2, 1.0) && g.unresolved(5, 5e-4) && !g.unresolved(5, 2e-3));
        assert!(!LossGeometry::span_only(50.0).unresolved(3, 0.0));
    }

    /// The default zone is a length of the physics: the same at every
    /// mesh and step, 4ℓ_b on a beam and 4·V·m/Z on a string.
    #[test]
    fn the_default_zone_does_not_move_with_the_resolution() {
        let scene = include_str!("../../scenes/reference.toml");
        let zone = |set: &[&str]| {
            let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
            let sc = crate::resolve::resolve_scene(scene, &set).unwrap();
            LossGeometry::of(&sc, 0).support_zone
        };
        let z = zone(&[]);
        for set in [
            &["mesh.elements=100"][..],
            &["mesh.elements=1600", "time.step=2.5e-5"],
            &["time.step=4e-4"],
        ] {
            assert_eq!(zone(set), z, "{set:?}");
        }
        assert!((z - 4.0 * (129.176f64 / 3.0e4).sqrt()).abs() < 1e-6, "{z}");
        // a string: the carrier's travel over 4 relaxation times m/Z
        let string = zone(&["beam.second_moment=0", "beam.left=\"pinned\""]);
        let (t, rho_a, v, m) = (3.0e4f64, 8900.0 * 1.5e-4, 100.0, 1.0);
        let want = SUPPORT_RELAXATION_TIMES * v * m / (2.0 * (t * rho_a).sqrt());
        assert!((string - want).abs() < 1e-12 * want, "{string} vs {want}");
    }
}
