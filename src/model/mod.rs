//! What a scene turns into: the discretized beam (Hermite, modal, Galerkin)
//! and its banded matrices, built from plain properties ([`crate::scene`]'s
//! `BeamProps` and `MeshPlan`), never from a scene.

pub mod banded;
pub mod beam;
pub(crate) mod damping;
pub mod eigen;
pub mod element;
pub mod mesh;
pub mod modal;
pub mod source;
pub mod spectrum;
