//! Why a contact law failed, as data, and the failure with the problem it
//! was given ([`ContactFailed`], carried by [`crate::Error::Contact`]).

use super::problem::ContactProblem;

/// A failed contact solve: why, and the problem the law was given (saved
/// next to the run's outputs and solved again by `taut replay`). Carried
/// boxed by [`crate::Error::Contact`] (the crate's error does not depend
/// on this layer); [`crate::Error::payload`] gets it back. Its message is
/// the failure's.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{failure}")]
pub struct ContactFailed {
    /// Why the law failed.
    pub failure: ContactFailure,
    /// The problem the law was given.
    pub problem: ContactProblem,
}

/// A contact law's failure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactFailure {
    /// The Delassus number of a single contact is not positive, so g = 0
    /// cannot be imposed with a finite force.
    #[error("Delassus W = {w:e} of contact {contact} is not positive")]
    NotPositive {
        /// The contact.
        contact: usize,
        /// Its diagonal entry W_cc.
        w: f64,
    },
    /// The Delassus matrix of the active contacts is singular.
    #[error("the Delassus matrix of the active contacts is singular")]
    Singular,
    /// A multiplier came out infinite or NaN: the Delassus number is too
    /// small (or the gaps too large) for the force to be represented.
    #[error(
        "the multiplier of contact {contact} is {lambda} (Delassus W_cc = {w:e}): the gap cannot be closed by a representable force"
    )]
    NotFinite {
        /// The contact.
        contact: usize,
        /// The multiplier.
        lambda: f64,
        /// Its Delassus diagonal entry.
        w: f64,
    },
    /// The active-set search did not settle.
    #[error("the active set did not settle in {passes} passes (contacts cycle)")]
    Cycling {
        /// Passes tried.
        passes: usize,
    },
    /// clarabel did not solve the QP.
    #[error(
        "clarabel returned {status} after {iterations} iterations (primal residual {r_prim:e}, dual residual {r_dual:e})"
    )]
    Solver {
        /// clarabel's status, e.g. `MaxIterations`.
        status: String,
        /// Iterations taken.
        iterations: u32,
        /// Primal residual.
        r_prim: f64,
        /// Dual residual.
        r_dual: f64,
    },
    /// clarabel refused the problem data.
    #[error("clarabel setup failed: {0}")]
    Setup(String),
    /// At velocity level the Delassus number V·r'ᵀz + rᵀz of a moving
    /// contact turned non-positive: the convective part outweighs the rest.
    #[error(
        "velocity-level Delassus W = {w:e} s/kg of contact {contact} is not positive: the convective term V·r'ᵀz outweighs rᵀz, the carrier moving V·Δt = {travel:.3e} m per step on elements of h = {h:.3e} m; reduce time.step (a velocity-level law needs V·Δt well below h)"
    )]
    VelocityDelassus {
        /// The contact.
        contact: usize,
        /// Its diagonal entry.
        w: f64,
        /// V·Δt, m.
        travel: f64,
        /// Element length, m.
        h: f64,
    },
}
