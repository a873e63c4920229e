//! `[mesh]` resolved against the beam it discretizes and the model's
//! bounds (MODEL §9.2): the kind and its modes (a `modal` basis within the
//! dense eigenproblem's size, a `galerkin` one within the exact modes'
//! count and supports), the grading and its keys, one element per graded
//! segment and none too short for its matrices.

use crate::error::{Error, Result, compact_number};
use crate::model::eigen::MAX_MODAL_DOFS;
use crate::model::mesh::{MIN_ELEMENT_FRACTION, check_elements, shortest_element};
use crate::scene::{
    BeamProps, DEFAULT_GRADING_RATIO, Discretization, Grading, GradingKind, MAX_GRADING_RATIO,
    MeshKind, MeshSpec, Support, fe_unknowns,
};

/// Most modes a `galerkin` basis takes ([`crate::analytic::MAX_MODES`]:
/// the phase of mode J carries a relative error of about ε·Jπ, and 4000
/// modes resolve half-wavelengths of L/4000, finer than any bundled mesh).
pub(crate) const MAX_GALERKIN_MODES: usize = crate::analytic::MAX_MODES;

/// Resolve `[mesh]` (its `elements` already checked) for `beam`.
pub(crate) fn resolve_mesh(mesh: &MeshSpec, beam: &BeamProps) -> Result<(Discretization, Grading)> {
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
    check_elements(grading, mesh.elements)?;
    // no element too short for its matrices (a point at the very end)
    let h_min = shortest_element(beam.length, mesh.elements, grading);
    if h_min.is_nan() || h_min < MIN_ELEMENT_FRACTION * beam.length {
        let (field, value, what): (&str, String, &str) = match grading {
            Grading::Point { at, .. } => (
                "mesh.grading_at",
                compact_number(at),
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
                compact_number(h_min),
                compact_number(beam.length)
            ),
        ));
    }
    Ok(grading)
}
