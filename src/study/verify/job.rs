//! A job: one case under one combination (method, discretization,
//! formulation, supports).

use super::case::{Case, Space};
use crate::integrate::MethodFactory;
use crate::scene::{Formulation, Support};

/// A job: one case under one combination.
pub(super) struct Job<'a> {
    pub(super) case: &'a Case,
    pub(super) factory: &'a dyn MethodFactory,
    pub(super) space: Space,
    pub(super) formulation: Option<Formulation>,
    pub(super) supports: Option<(Support, Support)>,
}
