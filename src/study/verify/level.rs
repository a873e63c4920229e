//! A case's scene at one ladder level: N, Δt and J set, and the
//! discretization's keys.

use super::case::Space;
use crate::error::Result;
use crate::resolve::Resolved;
use crate::scene::{GradingKind, MeshKind, Scene};
/// `scene` at one level: N, Δt and J set, the discretization's keys.
pub(super) fn level(scene: &Scene, space: Space, n: usize, dt: f64, j: usize) -> Result<Resolved> {
    let mut s = scene.clone();
    s.mesh.elements = n;
    s.time.step = dt;
    s.mesh.grading = GradingKind::Uniform;
    s.mesh.grading_ratio = None;
    s.mesh.grading_at = None;
    match space {
        Space::Hermite => {
            s.mesh.kind = MeshKind::Hermite;
            s.mesh.modes = None;
        }
        Space::Graded => {
            s.mesh.kind = MeshKind::Hermite;
            s.mesh.modes = None;
            s.mesh.grading = GradingKind::Supports;
        }
        Space::Galerkin => {
            s.mesh.kind = MeshKind::Galerkin;
            s.mesh.modes = Some(j);
        }
        Space::Modal => {
            s.mesh.kind = MeshKind::Modal;
            s.mesh.modes = Some(j);
        }
    }
    s.validate()
}

/// A scene's end time in seconds (a carrier-leaves end taken as 1 s: the
/// cases give seconds).
pub(super) fn scene_end(scene: &Scene) -> f64 {
    match scene.time.end {
        crate::scene::EndTime::Seconds(t) => t,
        crate::scene::EndTime::CarrierLeaves => 1.0,
    }
}
