//! `[mesh]`: the space discretization as the scene gives it (MODEL §4,
//! §9.2).

use serde::{Deserialize, Serialize};

/// `[mesh]`: the space discretization (MODEL §4, §9.2).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Number of elements N (1 ..= 1 000 000): the Hermite (or string)
    /// mesh, and the mesh a `modal` basis is taken from; `galerkin` has no
    /// mesh and does not use it.
    pub elements: usize,
    /// The discretization: `hermite` (default), `galerkin`, `modal`.
    #[serde(default, skip_serializing_if = "MeshKind::is_default")]
    pub kind: MeshKind,
    /// Number of modes J for `galerkin` and `modal`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Where elements shrink toward: `uniform` (default), `supports`,
    /// `left`, `right`, `point` (Hermite and modal meshes).
    #[serde(default, skip_serializing_if = "GradingKind::is_default")]
    pub grading: GradingKind,
    /// Size ratio h_max/h_min of a graded mesh, in [1, 1000] (default 4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading_ratio: Option<f64>,
    /// The point x_p a `point` grading shrinks toward, m, in (0, L).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading_at: Option<f64>,
}

/// The reference case's mesh (`scenes/reference.toml`): 400 uniform
/// Hermite elements.
impl Default for MeshSpec {
    fn default() -> Self {
        MeshSpec {
            elements: 400,
            kind: MeshKind::Hermite,
            modes: None,
            grading: GradingKind::Uniform,
            grading_ratio: None,
            grading_at: None,
        }
    }
}

/// `mesh.kind` (MODEL §9.2).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum MeshKind {
    /// Hermite beam elements (string elements when EI = 0).
    #[default]
    Hermite,
    /// The J exact modes of the continuous beam.
    Galerkin,
    /// The J lowest modes of the Hermite model.
    Modal,
}

impl MeshKind {
    /// Every kind, in the order the help and the docs list them.
    pub const ALL: [MeshKind; 3] = [MeshKind::Hermite, MeshKind::Galerkin, MeshKind::Modal];

    fn is_default(&self) -> bool {
        *self == MeshKind::Hermite
    }

    /// The scene's name of this kind.
    pub fn name(&self) -> &'static str {
        match self {
            MeshKind::Hermite => "hermite",
            MeshKind::Galerkin => "galerkin",
            MeshKind::Modal => "modal",
        }
    }
}

/// `mesh.grading`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum GradingKind {
    /// Equal elements.
    #[default]
    Uniform,
    /// Toward both supports.
    Supports,
    /// Toward x = 0.
    Left,
    /// Toward x = L.
    Right,
    /// Toward `grading_at`.
    Point,
}

impl GradingKind {
    fn is_default(&self) -> bool {
        *self == GradingKind::Uniform
    }
}
