//! Which scenes have an analytic reference for `taut converge` (MODEL §8).
//!
//! A single moving constant force at constant speed, starting at x = 0, on a
//! pinned–pinned string (EI = 0) or pinned–pinned tensioned beam, with no
//! distributed load: the displacement under the force has the modal series of
//! MODEL §8 ([`crate::analytic::MovingForceString`],
//! [`crate::analytic::MovingForceBeam`]).
//!
//! A single riding mass (mass carrier with k = 0, no dashpot, bilateral
//! contact) at constant speed on a pinned–pinned tensioned beam (EI > 0),
//! with no distributed load: the Galerkin solution in the exact modes with
//! the convective terms (MODEL §9.2, [`crate::analytic::RidingMassBeam`]),
//! integrated once on the finest level's time grid with J from
//! [`riding_mass_modes`].
//!
//! Everything else returns `None` and is compared against a
//! Richardson-extrapolated reference.

use super::converge::AnalyticW;
use crate::analytic::{MovingForceBeam, MovingForceString, RidingMassBeam};
use crate::scene::{CarrierKind, ContactKind, Resolved, SpeedProfile, Support};

/// The analytic w(t) = s·v(x_m(t), t) under the carrier, when the scene has one.
///
/// The carrier pushes the beam with s·F (MODEL §2), so v = s·v_F where v_F is
/// the response to F in +v; w = s·v = v_F.
pub fn analytic_w(sc: &Resolved) -> Option<AnalyticW> {
    let [c] = sc.carriers.as_slice() else {
        return None;
    };
    let CarrierKind::Force { force } = c.kind else {
        return riding_mass_w(sc);
    };
    let SpeedProfile::Constant { value: speed } = c.motion.profile else {
        return None;
    };
    let b = &sc.beam;
    if c.motion.start != 0.0
        || speed <= 0.0
        || b.left != Support::Pinned
        || b.right != Support::Pinned
        || b.distributed_load != 0.0
    {
        return None;
    }
    if b.is_string() {
        let m = MovingForceString::new(b.tension, b.rho_a, b.length, force, speed).ok()?;
        Some(Box::new(move |t| m.deflection(speed * t, t)))
    } else {
        let m = MovingForceBeam::new(b.ei, b.tension, b.rho_a, b.length, force, speed).ok()?;
        Some(Box::new(move |t| m.deflection(speed * t, t)))
    }
}

/// Fewest Galerkin modes for a riding-mass reference: measured on
/// `scenes/riding_mass_pinned.toml`, w changes by 1.8e-5 m from J = 800 to
/// 1600 (about J^-2.3), so J = 800 is within ≈ 5e-6 m (2.5e-5 of max |w|),
/// ten times below the FE error at N = 200 (4.7e-5 m).
pub const RIDING_MASS_MIN_MODES: usize = 800;

/// Modes per element of the finest mesh: the Hermite model has 2N unknowns,
/// and J = 4N keeps the Galerkin truncation about ten times below the FE
/// error at every N measured (N = 200: 4.7e-5 vs 5e-6 m; N = 400: 8.7e-6
/// vs ≈ 1e-6 m at J = 1600).
pub const RIDING_MASS_MODES_PER_ELEMENT: usize = 4;

/// Cap on J: the RK4 step falls like 1/ω_J ∝ J⁻² in the bending range, so
/// the cost grows like J³ (J = 1600: a few seconds for 0.4 s of motion); beyond
/// this the reference would cost more than the FE ladder it checks.
pub const RIDING_MASS_MAX_MODES: usize = 3200;

/// J for a riding-mass reference against a mesh of `elements` elements:
/// `clamp(4N, 800, 3200)`.
pub fn riding_mass_modes(elements: usize) -> usize {
    (RIDING_MASS_MODES_PER_ELEMENT * elements).clamp(RIDING_MASS_MIN_MODES, RIDING_MASS_MAX_MODES)
}

/// The Galerkin riding mass of a scene, when `sc` is one (a single mass
/// without spring or dashpot, bilateral, at constant speed, on a
/// pinned–pinned beam without distributed load; module docs).
pub fn riding_mass_beam(sc: &Resolved) -> Option<RidingMassBeam> {
    let [c] = sc.carriers.as_slice() else {
        return None;
    };
    let CarrierKind::MassSpring {
        mass,
        stiffness,
        damping,
        ..
    } = c.kind
    else {
        return None;
    };
    let SpeedProfile::Constant { value: speed } = c.motion.profile else {
        return None;
    };
    let b = &sc.beam;
    if stiffness != 0.0
        || damping != 0.0
        || sc.contact.kind != ContactKind::Bilateral
        || b.left != Support::Pinned
        || b.right != Support::Pinned
        || b.distributed_load != 0.0
    {
        return None;
    }
    RidingMassBeam::new(
        b.ei,
        b.tension,
        b.rho_a,
        b.length,
        mass,
        sc.g,
        c.side,
        c.motion.start,
        speed,
    )
    .ok()
}

/// The riding-mass reference w(t), when `sc` is such a scene (module docs).
fn riding_mass_w(sc: &Resolved) -> Option<AnalyticW> {
    let r = riding_mass_beam(sc)?;
    let modes = riding_mass_modes(sc.elements);
    let h = r
        .solve(modes, r.max_step(modes), sc.dt, sc.steps as f64 * sc.dt)
        .ok()?;
    Some(Box::new(move |t| h.w_at(t)))
}
