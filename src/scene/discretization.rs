//! `[mesh]` resolved: which space discretization a run uses (MODEL §9.2),
//! with every key checked against its range and against the beam it
//! discretizes.

use super::{BeamProps, GradingKind, MeshKind, MeshSpec, Support};
use crate::error::{Error, Result};
use crate::model::eigen::MAX_MODAL_DOFS;

/// Size ratio h_max/h_min of a graded mesh when `grading_ratio` is not
/// given: elements at the graded end a quarter of the longest, a mild
/// grading that keeps the time step a uniform mesh of the same N needs
/// within a factor of about 2 for the implicit methods' accuracy.
pub const DEFAULT_GRADING_RATIO: f64 = 4.0;

/// Most modes a `galerkin` basis takes ([`crate::analytic::MAX_MODES`]:
/// the phase of mode J carries a relative error of about ε·Jπ, and 4000
/// modes resolve half-wavelengths of L/4000, finer than any bundled mesh).
pub const MAX_GALERKIN_MODES: usize = crate::analytic::MAX_MODES;

/// Largest size ratio h_max/h_min accepted: beyond this the smallest
/// elements are so short that the time step would have to follow them
/// (and the mass matrix's conditioning, ∝ ratio⁴ for Hermite, degrades).
pub const MAX_GRADING_RATIO: f64 = 1000.0;

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

/// The FE unknowns of `elements` elements on `beam` (supported dofs removed).
pub fn fe_unknowns(beam: &BeamProps, elements: usize) -> usize {
    let per_node = if beam.is_string() { 1 } else { 2 };
    let removed = |s: Support| match s {
        Support::Clamped => per_node,
        Support::Pinned => 1,
        Support::Free => 0,
    };
    (per_node * (elements + 1)).saturating_sub(removed(beam.left) + removed(beam.right))
}

/// Resolve `[mesh]` (its `elements` already checked) for `beam`.
pub(super) fn resolve(mesh: &MeshSpec, beam: &BeamProps) -> Result<(Discretization, Grading)> {
    let grading = resolve_grading(mesh, beam)?;
    let kind = mesh.kind;
    let modes = match (kind, mesh.modes) {
        (MeshKind::Hermite, Some(j)) => {
            return Err(Error::invalid(
                "mesh.modes",
                j,
                "applies only to mesh.kind = \"galerkin\" or \"modal\" (mesh.kind is \"hermite\": remove mesh.modes or choose a modal kind)",
            ));
        }
        (MeshKind::Hermite, None) => 0,
        (_, None) => {
            return Err(Error::invalid(
                "mesh.modes",
                "missing",
                format!(
                    "mesh.kind = \"{}\" needs the number of modes J, an integer ≥ 1",
                    kind.name()
                ),
            ));
        }
        (_, Some(0)) => {
            return Err(Error::invalid(
                "mesh.modes",
                0,
                "must be an integer ≥ 1 (the number of modes J)",
            ));
        }
        (_, Some(j)) => j,
    };
    let d = match kind {
        MeshKind::Hermite => Discretization::Hermite,
        MeshKind::Modal => {
            let n = fe_unknowns(beam, mesh.elements);
            if n > MAX_MODAL_DOFS {
                return Err(Error::invalid(
                    "mesh.elements",
                    mesh.elements,
                    format!(
                        "gives {n} FE unknowns; mesh.kind = \"modal\" solves a dense eigenproblem of at most {MAX_MODAL_DOFS} (n² memory, n³ time: model::eigen): use fewer elements, or galerkin"
                    ),
                ));
            }
            if modes > n {
                return Err(Error::invalid(
                    "mesh.modes",
                    modes,
                    format!(
                        "must be in 1 ..= {n}, the FE unknowns of mesh.elements = {} (a modal basis cannot have more modes than the model it is taken from)",
                        mesh.elements
                    ),
                ));
            }
            Discretization::Modal { modes }
        }
        MeshKind::Galerkin => {
            if modes > MAX_GALERKIN_MODES {
                return Err(Error::invalid(
                    "mesh.modes",
                    modes,
                    format!("must be in 1 ..= {MAX_GALERKIN_MODES} for mesh.kind = \"galerkin\""),
                ));
            }
            if grading != Grading::Uniform {
                return Err(Error::invalid(
                    "mesh.grading",
                    format!("\"{}\"", grading.name()),
                    "a galerkin basis has no mesh to grade: use mesh.grading = \"uniform\" (the default) or mesh.kind = \"hermite\" / \"modal\"",
                ));
            }
            check_galerkin_supports(beam)?;
            Discretization::Galerkin { modes }
        }
    };
    Ok((d, grading))
}

/// The supports a `galerkin` basis has closed-form modes for.
fn check_galerkin_supports(beam: &BeamProps) -> Result<()> {
    let (l, r) = (beam.left, beam.right);
    let held = |s: Support| s != Support::Free;
    let ok = if beam.is_string() {
        l == Support::Pinned && r == Support::Pinned
    } else {
        held(l) && held(r)
    };
    if ok {
        return Ok(());
    }
    let name = |s: Support| match s {
        Support::Clamped => "clamped",
        Support::Pinned => "pinned",
        Support::Free => "free",
    };
    let allowed = if beam.is_string() {
        "a string (EI = 0) galerkin basis needs beam.left = beam.right = \"pinned\" (sin(jπx/L))"
    } else {
        "galerkin has the exact modes of clamped and pinned ends (any pair); a free end has rigid-body modes it does not build: use mesh.kind = \"hermite\" or \"modal\""
    };
    Err(Error::invalid(
        "mesh.kind, beam.left, beam.right",
        format!("\"galerkin\", \"{}\", \"{}\"", name(l), name(r)),
        allowed,
    ))
}

fn resolve_grading(mesh: &MeshSpec, beam: &BeamProps) -> Result<Grading> {
    let g = mesh.grading;
    if g == GradingKind::Uniform {
        for (field, given) in [
            ("mesh.grading_ratio", mesh.grading_ratio.is_some()),
            ("mesh.grading_at", mesh.grading_at.is_some()),
        ] {
            if given {
                return Err(Error::invalid(
                    field,
                    "given",
                    "applies only to a graded mesh: set mesh.grading = \"supports\", \"left\", \"right\" or \"point\"",
                ));
            }
        }
        return Ok(Grading::Uniform);
    }
    let ratio = mesh.grading_ratio.unwrap_or(DEFAULT_GRADING_RATIO);
    if !(1.0..=MAX_GRADING_RATIO).contains(&ratio) {
        return Err(Error::invalid(
            "mesh.grading_ratio",
            ratio,
            format!(
                "must be in [1, {MAX_GRADING_RATIO}] (h_max/h_min; 1 is a uniform mesh, above {MAX_GRADING_RATIO} the smallest elements would dictate the step)"
            ),
        ));
    }
    if g != GradingKind::Point && mesh.grading_at.is_some() {
        return Err(Error::invalid(
            "mesh.grading_at",
            "given",
            "applies only to mesh.grading = \"point\"",
        ));
    }
    let grading = match g {
        GradingKind::Uniform => Grading::Uniform,
        GradingKind::Supports => Grading::Supports { ratio },
        GradingKind::Left => Grading::Left { ratio },
        GradingKind::Right => Grading::Right { ratio },
        GradingKind::Point => {
            let l = beam.length;
            let at = mesh.grading_at.ok_or_else(|| {
                Error::invalid(
                    "mesh.grading_at",
                    "missing",
                    format!("mesh.grading = \"point\" needs the point x_p, m, in (0, {l})"),
                )
            })?;
            if !(at > 0.0 && at < l) {
                return Err(Error::invalid(
                    "mesh.grading_at",
                    at,
                    format!("must be in (0, {l}) m, strictly inside the span"),
                ));
            }
            Grading::Point { ratio, at }
        }
    };
    // the mesh builder's own check: one element per graded segment
    crate::model::mesh::check_elements(grading, mesh.elements)?;
    // no element too short for its matrices (a point at the very end)
    use crate::model::mesh::{MIN_ELEMENT_FRACTION, shortest_element};
    let h_min = shortest_element(beam.length, mesh.elements, grading);
    if h_min.is_nan() || h_min < MIN_ELEMENT_FRACTION * beam.length {
        let (field, value, what): (&str, String, &str) = match grading {
            Grading::Point { at, .. } => (
                "mesh.grading_at",
                crate::error::compact_number(at),
                "move the point away from the end",
            ),
            _ => (
                "mesh.elements",
                mesh.elements.to_string(),
                "use fewer elements or a smaller mesh.grading_ratio",
            ),
        };
        return Err(Error::invalid(
            field,
            value,
            format!(
                "gives a shortest element of {} m, below {MIN_ELEMENT_FRACTION:e} of the span L = {} m, where the element matrices (∝ 1/h³) lose their precision: {what}",
                crate::error::compact_number(h_min),
                crate::error::compact_number(beam.length)
            ),
        ));
    }
    Ok(grading)
}
