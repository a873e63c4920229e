//! Numerical tools shared by the references and the model, and nothing of
//! the physics: Gauss–Legendre quadrature and the eight-lane fused sums of
//! the modal kernels. Imports nothing of the crate.

pub mod filter;
pub mod lanes;
pub mod quadrature;
