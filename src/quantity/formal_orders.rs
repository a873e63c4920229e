//! The formal orders the studies cap observed ones at, and the round-off
//! floor of a difference: shared by the accuracy-targeted sweep's error
//! model (`study::tolerance`), solution verification (`study::uncertainty`) and
//! `converge`, in a file of their own so that those modules import it and
//! not each other.

/// Largest mesh order used for a displacement: Hermite cubics converge
/// displacements and eigenvalues at O(h⁴) at best (MODEL §4, §8). A higher
/// observed order is a lucky cancellation; using the cap instead gives a
/// larger, safer error estimate.
pub(crate) const MAX_MESH_ORDER: f64 = 4.0;

/// Largest mesh order used for the contact force and what is counted from
/// it (P_l, loss intervals): the force balances the mass's acceleration,
/// which for a moving contact holds V²·v_xx(x_m), and cubic elements give
/// the curvature v_xx to O(h²) only (MODEL §2, §4).
pub(crate) const MAX_MESH_ORDER_FORCE: f64 = 2.0;

/// Largest step order used for a displacement of a run whose contacts never
/// switch: generalized-α is second order (MODEL §5).
pub(crate) const MAX_STEP_ORDER: f64 = 2.0;

/// Largest step order used for the contact force, for everything counted
/// from it, and for any quantity of a run whose contact opens or closes:
/// the Lagrange multiplier is first order in Δt even when the contact never
/// opens (T1 riding mass: 1.11, 1.02, 1.02, docs/convergence.md), and a
/// contact that opens or closes does so at a step boundary, an O(Δt) error
/// in the event's time that every later value inherits.
pub(crate) const MAX_STEP_ORDER_CONTACT: f64 = 1.0;

/// Differences below this (relative to the quantity's scale) are round-off
/// and count as zero: the integrator repeats bit-for-bit, and summation
/// order alone moves a norm by ~1e-15.
pub(crate) const ROUND_OFF: f64 = 1e-12;
