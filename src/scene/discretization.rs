//! The space discretization of a run as plain data (MODEL §9.2): the kind
//! and its modes, the mesh grading, the mesh plan the model is built from.
//! `[mesh]` is checked against the beam and the model's bounds by the
//! resolve layer (`crate::resolve::mesh`).

use super::beam::Support;
use super::mesh::MeshKind;
use super::props::BeamProps;

/// Size ratio h_max/h_min of a graded mesh when `grading_ratio` is not
/// given: elements at the graded end a quarter of the longest, a mild
/// grading that keeps the time step a uniform mesh of the same N needs
/// within a factor of about 2 for the implicit methods' accuracy.
pub(crate) const DEFAULT_GRADING_RATIO: f64 = 4.0;

/// Largest size ratio h_max/h_min accepted: beyond this the smallest
/// elements are so short that the time step would have to follow them
/// (and the mass matrix's conditioning, ∝ ratio⁴ for Hermite, degrades).
pub(crate) const MAX_GRADING_RATIO: f64 = 1000.0;

/// Where a mesh is graded toward (MODEL §9.2), with its size ratio
/// R = h_max/h_min (≥ 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Grading {
    /// Equal elements.
    Uniform,
    /// Toward both supports.
    Supports {
        /// h_max/h_min.
        ratio: f64,
    },
    /// Toward x = 0.
    Left {
        /// h_max/h_min.
        ratio: f64,
    },
    /// Toward x = L.
    Right {
        /// h_max/h_min.
        ratio: f64,
    },
    /// Toward a point x_p, m.
    Point {
        /// h_max/h_min.
        ratio: f64,
        /// x_p, m (0 < x_p < L).
        at: f64,
    },
}

impl Grading {
    /// The scene's name of this grading.
    pub fn name(&self) -> &'static str {
        match self {
            Grading::Uniform => "uniform",
            Grading::Supports { .. } => "supports",
            Grading::Left { .. } => "left",
            Grading::Right { .. } => "right",
            Grading::Point { .. } => "point",
        }
    }

    /// h_max/h_min of a graded mesh (None when uniform).
    pub fn ratio(&self) -> Option<f64> {
        match *self {
            Grading::Uniform => None,
            Grading::Supports { ratio }
            | Grading::Left { ratio }
            | Grading::Right { ratio }
            | Grading::Point { ratio, .. } => Some(ratio),
        }
    }

    /// Fewest elements the grading needs (one per graded segment).
    pub fn min_elements(&self) -> usize {
        match self {
            Grading::Supports { .. } | Grading::Point { .. } => 2,
            _ => 1,
        }
    }
}

/// The space discretization of a run (MODEL §9.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Discretization {
    /// Hermite elements (string elements when EI = 0), uniform or graded.
    Hermite,
    /// The J exact modes of the continuous beam.
    Galerkin {
        /// J.
        modes: usize,
    },
    /// The J lowest modes of the Hermite (or string) model.
    Modal {
        /// J.
        modes: usize,
    },
}

impl Discretization {
    /// The scene's name (`mesh.kind`).
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// `mesh.kind` of this discretization.
    pub fn kind(&self) -> MeshKind {
        match self {
            Discretization::Hermite => MeshKind::Hermite,
            Discretization::Galerkin { .. } => MeshKind::Galerkin,
            Discretization::Modal { .. } => MeshKind::Modal,
        }
    }

    /// J for the modal kinds.
    pub fn modes(&self) -> Option<usize> {
        match *self {
            Discretization::Hermite => None,
            Discretization::Galerkin { modes } | Discretization::Modal { modes } => Some(modes),
        }
    }

    /// A short label: `hermite`, `galerkin J=40`, `modal J=40`.
    pub fn label(&self) -> String {
        match self.modes() {
            None => self.name().to_string(),
            Some(j) => format!("{} J={j}", self.name()),
        }
    }
}

/// The space discretization of a run as plain data: what the model is
/// built from (`model::beam::BeamModel::build`) beside the beam's
/// properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshPlan {
    /// Number of elements N (`mesh.elements`): the Hermite mesh, or the
    /// mesh a `modal` basis is taken from.
    pub elements: usize,
    /// The discretization (`mesh.kind`, MODEL §9.2).
    pub discretization: Discretization,
    /// The mesh grading (`mesh.grading`).
    pub grading: Grading,
}

/// The FE unknowns of `elements` elements on `beam` (supported dofs
/// removed): the contact wire's, and a messenger's (one element family,
/// each pinned support on a node removing its w (an elastic one keeps it), `docs/lines.md` W1).
pub(crate) fn fe_unknowns(beam: &BeamProps, elements: usize) -> usize {
    let per_node = if beam.is_string() { 1 } else { 2 };
    let removed = |s: Support| match s {
        Support::Clamped => per_node,
        Support::Pinned => 1,
        Support::Free => 0,
    };
    let wire = (per_node * (elements + 1)).saturating_sub(removed(beam.left) + removed(beam.right));
    let messenger = beam.messenger.as_ref().map_or(0, |m| {
        (per_node * (elements + 1)).saturating_sub(m.pinned().count())
    });
    wire + messenger
}
