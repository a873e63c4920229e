//! `[[dropper]]` against the rest of the scene (MODEL §10,
//! `docs/lines.md`): which bases, contact settings and references carry
//! droppers.
//!
//! * A **linear** dropper is a spring k_d to its anchor plus the constant
//!   preload k_d (z_a − ℓ_0): it is resolved into an `[[attachment]]`
//!   spring (K gains k_d r_d r_dᵀ) and a point load (`integrate::dropper`),
//!   so it goes wherever attachments go (`hermite`, `string`, `modal`,
//!   every method). Its dashpot c_d (`damping`) is the attachment's
//!   dashpot (eq. D11), carried and refused where those are
//!   (`super::damping`, which names the key `dropper.<i>.damping`).
//! * A **tension-only** dropper is a unilateral constraint solved with the
//!   contacts, in the same per-step problem (`integrate::dropper`). Its
//!   response A⁻¹r_d is formed once per run by the method, which only the
//!   generalized-α family does (checked when the run is built,
//!   `Integrator::with_method`). It needs a force-level law on a
//!   unilateral problem: `contact.kind = "bilateral"` would make every row
//!   of the problem two-sided (a dropper that pushes) and the `impact`
//!   formulation works with gap rates, so both are refused here.
//! * Either kind is refused by `galerkin` (the exact modes of the bare
//!   beam; a point spring couples them) and by the closed-form references,
//!   which are of the bare beam (as `[[attachment]]` is,
//!   `super::attachment`). A manufactured solution carries them: its source
//!   has each dropper's force of the manufactured motion
//!   (`crate::manufactured`).

use crate::error::{Error, Result};
use crate::scene::{Attachment, ContactKind, Discretization, Dropper, Formulation, Scene};

/// Refuse the combinations a dropper breaks (module docs); nothing to check
/// without droppers.
/// Each dropper's `design_height` within the small slopes every line of
/// the model takes (MODEL §2; `line.presag` is held to the same bound): a
/// contact wire designed a quarter of its length `length` or more above or
/// below its supports is no small-slope line, and form-finding towards it
/// would fail with a singular or unreachable design rather than name it.
pub(crate) fn check_design_heights(droppers: &[Dropper], length: f64) -> Result<()> {
    let bound = length / 4.0;
    for (i, d) in droppers.iter().enumerate() {
        if let Some(h) = d.design_height
            && h.abs() >= bound
        {
            return Err(Error::invalid(
                format!("dropper.{i}.design_height"),
                h,
                format!(
                    "must be within ± a quarter of the wire's length ({bound} m): the model takes small slopes (m, the contact wire's height at rest, positive up)"
                ),
            ));
        }
    }
    Ok(())
}

pub(crate) fn check_droppers(scene: &Scene, droppers: &[Dropper], d: Discretization) -> Result<()> {
    if droppers.is_empty() {
        return Ok(());
    }
    let n = droppers.len();
    if let Discretization::Galerkin { .. } = d {
        return Err(Error::invalid(
            "mesh.kind",
            "\"galerkin\"",
            format!(
                "cannot carry the scene's {n} [[dropper]] (the exact modes of the bare beam are diagonal; a dropper couples them): use mesh.kind = \"hermite\" (or \"modal\" for linear droppers)"
            ),
        ));
    }
    if let Some(i) = droppers.iter().position(|d| d.design_height.is_some())
        && scene.manufactured.is_some()
    {
        return Err(Error::invalid(
            format!("dropper.{i}.design_height"),
            droppers[i].design_height.unwrap_or(f64::NAN),
            "cannot be form-found in a [manufactured] scene (its lines start straight and its droppers' lengths are the solution's): give the length instead",
        ));
    }
    // a manufactured solution's source carries the droppers' forces
    super::attachment::closed_form_references(scene, &format!("the scene's {n} [[dropper]]"))?;
    let Some(i) = droppers.iter().position(|d| !d.linear) else {
        return Ok(());
    };
    if let Discretization::Modal { .. } = d {
        return Err(Error::invalid(
            "mesh.kind",
            "\"modal\"",
            format!(
                "cannot carry dropper {i} (tension-only): use mesh.kind = \"hermite\", or make every dropper linear = true (a spring, which a modal basis carries)"
            ),
        ));
    }
    if scene.contact.kind == ContactKind::Bilateral {
        return Err(Error::invalid(
            "contact.kind",
            "\"bilateral\"",
            format!(
                "would make dropper {i} two-sided too (the droppers are rows of the contact problem): use \"unilateral\", or linear = true on every dropper"
            ),
        ));
    }
    if scene.contact.formulation == Formulation::Impact {
        return Err(Error::invalid(
            "contact.formulation",
            "\"impact\"",
            format!(
                "works with gap rates and has no law for dropper {i}'s compliant slack (a spring, not an impact): use \"lagrange\", \"complementarity\" or \"penalty\", or linear = true on every dropper"
            ),
        ));
    }
    Ok(())
}

/// The attachment springs of the linear droppers to a fixed anchor (module
/// docs): k_d and the dashpot c_d at x_d, no mass.
pub(crate) fn linear_attachments(droppers: &[Dropper]) -> impl Iterator<Item = Attachment> + '_ {
    droppers
        .iter()
        .filter(|d| d.linear && !d.on_messenger())
        .map(|d| Attachment {
            x: d.x,
            stiffness: d.stiffness,
            mass: 0.0,
            damping: d.damping,
        })
}

/// The scene key of `beam.attachments[i]`'s dashpot (`attachment.<i>.damping`,
/// or `dropper.<j>.damping` for the attachment a linear dropper resolved
/// into, [`linear_attachments`]): `own` holds the scene index of each of
/// the scene's own contact-wire `[[attachment]]`, which come first.
pub(crate) fn dashpot_key(i: usize, own: &[usize], droppers: &[Dropper]) -> String {
    let scene_attachments = own.len();
    if i < scene_attachments {
        return format!("attachment.{}.damping", own[i]);
    }
    let j = droppers
        .iter()
        .enumerate()
        .filter(|(_, d)| d.linear && !d.on_messenger())
        .nth(i - scene_attachments)
        .map_or(i, |(j, _)| j);
    format!("dropper.{j}.damping")
}
