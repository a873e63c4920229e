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
//! references are of the bare beam and are refused too;
//! `standing_force_modes` (the model's own eigenpairs) and Richardson
//! extrapolation hold. A manufactured solution carries attachments: its
//! source has each attachment's force of the manufactured motion
//! (`crate::manufactured`, `docs/verification.md` M4–M5).

use crate::error::{Error, Result};
use crate::scene::{BeamProps, Discretization, ReferenceKind, Scene};

/// Refuse the combinations an attachment breaks (module docs); nothing to
/// check without attachments.
pub(crate) fn check_attachments(scene: &Scene, beam: &BeamProps, d: Discretization) -> Result<()> {
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
    // a manufactured solution's source carries the attachments' forces
    closed_form_references(scene, &format!("the scene's {n} [[attachment]]"))
}

/// Refuse a closed-form reference of the bare beam (`moving_force_series`,
/// `riding_mass_galerkin`) beside something the bare beam does not have
/// (`what`: "the scene's 2 [[dropper]]"), since it does not include it;
/// `standing_force_modes` (the model's own eigenpairs) and Richardson
/// extrapolation hold. A manufactured solution holds too: attachments,
/// droppers and a messenger are in its source (`crate::manufactured`).
pub(super) fn closed_form_references(scene: &Scene, what: &str) -> Result<()> {
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
