//! `[[attachment]]` against the rest of the scene (MODEL §10): the
//! discretizations and references that can carry point attachments.
//!
//! Attachments enter only the assembled M and K (`model::beam`), so every
//! discretization built from the finite elements carries them: `hermite`
//! (uniform or graded) and the string elements, and `modal`, whose basis is
//! the lowest eigenpairs of the assembled (K, M) with the attachments in
//! it. A `galerkin` basis is the exact modes of the bare continuous beam: an
//! attachment couples those modes (`k_a φ(x_a) φ(x_a)ᵀ` is dense), which
//! the diagonal basis has no place for, so it is refused. The closed-form
//! references and the manufactured solutions are of the bare beam and are
//! refused too; `standing_force_modes` (the model's own eigenpairs) and
//! Richardson extrapolation hold.

use crate::error::{Error, Result};
use crate::scene::{BeamProps, Discretization, ReferenceKind, Scene};

/// Refuse the combinations an attachment breaks (module docs); nothing to
/// check without attachments.
pub fn check_attachments(scene: &Scene, beam: &BeamProps, d: Discretization) -> Result<()> {
    if beam.attachments.is_empty() {
        return Ok(());
    }
    let n = beam.attachments.len();
    if let Discretization::Galerkin { .. } = d {
        return Err(Error::invalid(
            "mesh.kind",
            "\"galerkin\"",
            format!(
                "cannot carry the scene's {n} [[attachment]] (the exact modes of the bare beam are diagonal; an attachment couples them): use mesh.kind = \"hermite\" or \"modal\", which accept attachments"
            ),
        ));
    }
    bare_beam_references(scene, &format!("the scene's {n} [[attachment]]"))
}

/// Refuse a manufactured solution or a closed-form reference of the bare
/// beam (`moving_force_series`, `riding_mass_galerkin`) beside something
/// the bare beam does not have (`what`: "the scene's 2 [[dropper]]"), since
/// neither includes it; `standing_force_modes` (the model's own eigenpairs)
/// and Richardson extrapolation hold. Shared by attachments and droppers.
pub(super) fn bare_beam_references(scene: &Scene, what: &str) -> Result<()> {
    closed_form_references(scene, what, true)
}

/// [`bare_beam_references`], with the manufactured solution refused only
/// when `refuse_manufactured` (droppers and a messenger are in its source,
/// `crate::manufactured`; attachments are not).
pub(super) fn closed_form_references(
    scene: &Scene,
    what: &str,
    refuse_manufactured: bool,
) -> Result<()> {
    if refuse_manufactured && scene.manufactured.is_some() {
        return Err(Error::invalid(
            "manufactured",
            "(present)",
            format!(
                "a manufactured solution's source is that of the bare beam and does not include {what}: remove one or the other"
            ),
        ));
    }
    if let Some(r) = &scene.reference
        && matches!(
            r.kind,
            ReferenceKind::MovingForceSeries | ReferenceKind::RidingMassGalerkin
        )
    {
        return Err(Error::invalid(
            "reference.kind",
            format!("\"{}\"", r.kind.name()),
            format!(
                "is a closed form of the bare beam and does not include {what}: use \"standing_force_modes\" or \"richardson\""
            ),
        ));
    }
    Ok(())
}
