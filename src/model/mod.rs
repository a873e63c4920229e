//! What a scene turns into: the discretized beam, its banded matrices, and
//! the carriers' kinematics.

pub mod banded;
pub mod beam;
pub mod eigen;
pub mod element;
pub mod lanes;
pub mod mesh;
pub mod modal;
pub mod motion;
pub mod quadrature;
pub mod source;
pub mod spectrum;
