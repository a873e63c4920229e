//! Which scenes have an analytic reference for `taut converge` (MODEL §8).
//!
//! A single moving constant force at constant speed, starting at x = 0, on a
//! pinned–pinned string (EI = 0) or pinned–pinned tensioned beam, with no
//! distributed load: the displacement under the force has the modal series of
//! MODEL §8 ([`crate::analytic::MovingForceString`],
//! [`crate::analytic::MovingForceBeam`]). Everything else returns `None` and
//! is compared against a Richardson-extrapolated reference.

use super::converge::AnalyticW;
use crate::analytic::{MovingForceBeam, MovingForceString};
use crate::scene::{CarrierKind, Resolved, SpeedProfile, Support};

/// The analytic w(t) = s·v(x_m(t), t) under the carrier, when the scene has one.
///
/// The carrier pushes the beam with s·F (MODEL §2), so v = s·v_F where v_F is
/// the response to F in +v; w = s·v = v_F.
pub fn analytic_w(sc: &Resolved) -> Option<AnalyticW> {
    let [c] = sc.carriers.as_slice() else {
        return None;
    };
    let CarrierKind::Force { force } = c.kind else {
        return None;
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
