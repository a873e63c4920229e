//! Damping (`[beam] damping`, `[[attachment]] damping`; docs/lines.md
//! §10.4) against the rest of the scene: the methods and bases that carry
//! a damping matrix C, and the references that assume none.
//!
//! * The implicit methods carry C in their effective matrix (generalized-α
//!   family, Bathe's two sub-steps, Moreau–Jean's θ-step): still banded,
//!   factored once. `modal_exact` propagates each mode of a diagonal basis
//!   as an exact damped oscillator.
//! * `central_difference` is refused: its step is explicit with v kept at
//!   half steps, so a non-diagonal C needs a solve with `M + Δt/2 C` every
//!   step and its stable step shrinks to `Δt ≤ (2/ω)(√(1+ζ²) − ζ)`, which
//!   its ω_max-based step check does not know.
//! * A linear dropper's dashpot (`[[dropper]] damping`, docs/lines.md
//!   eq. D11) is an attachment's (fixed anchor) or couples the two lines
//!   (messenger): the same checks, the key named `dropper.<i>.damping`.
//! * A dashpot on a modal basis (`mesh.kind = "modal"`) is refused: its
//!   `c_a φ(x_a) φ(x_a)ᵀ` couples every mode, which a diagonal basis has
//!   no place for (the Rayleigh part stays diagonal there).
//! * A registered method is refused: it builds its own stepper, which
//!   does not read C.
//! * The closed-form references are of the undamped beam and are refused;
//!   `richardson` holds. A manufactured solution carries the point
//!   dashpots (an attachment's c_a, a dropper's c_d: its source has their
//!   forces of the manufactured motion, `crate::manufactured`) and refuses
//!   Rayleigh damping (its source is of the undamped lines).

use crate::error::{Error, Result};
use crate::scene::{
    BeamProps, Discretization, Dropper, Rayleigh, ReferenceKind, ResolvedMethod, Scene, Scheme,
};

/// The first dashpot on the messenger's own attachments (eq. E1): an
/// elastic support's (`messenger.support…damping`) or a `[[attachment]]
/// wire = "messenger"`'s; (key, c).
fn messenger_dashpot(scene: &Scene, beam: &BeamProps) -> Option<(String, f64)> {
    let m = beam.messenger.as_ref()?;
    let supports = m.elastic.iter().filter(|e| e.is_some()).count();
    let i = m.attachments.iter().position(|a| a.damping != 0.0)?;
    let c = m.attachments[i].damping;
    if i < supports {
        return Some(("messenger.support.damping".to_string(), c));
    }
    let j = (0..scene.attachments.len())
        .filter(|&j| scene.attachments[j].on_messenger())
        .nth(i - supports)
        .unwrap_or(i);
    Some((format!("attachment.{j}.damping"), c))
}

/// Refuse the combinations damping breaks (module docs); nothing to check
/// without damping.
pub(crate) fn check_damping(
    scene: &Scene,
    own: &[usize],
    beam: &BeamProps,
    droppers: &[Dropper],
    rayleigh: Rayleigh,
    d: Discretization,
    method: &ResolvedMethod,
) -> Result<()> {
    // the first dashpot: an attachment's (a linear dropper's to a fixed
    // anchor among them), else a linear messenger dropper's; (key, c)
    let dashpot = beam
        .attachments
        .iter()
        .position(|a| a.damping != 0.0)
        .map(|i| {
            (
                super::dropper::dashpot_key(i, own, droppers),
                beam.attachments[i].damping,
            )
        })
        .or_else(|| {
            droppers
                .iter()
                .position(|x| x.linear && x.on_messenger() && x.damping != 0.0)
                .map(|j| (format!("dropper.{j}.damping"), droppers[j].damping))
        })
        .or_else(|| messenger_dashpot(scene, beam));
    if rayleigh.is_zero() && dashpot.is_none() {
        return Ok(());
    }
    // the key that brought damping in, for the messages
    let (key, value) = match &dashpot {
        Some((k, c)) if rayleigh.is_zero() => (k.clone(), c.to_string()),
        _ => (
            "beam.damping".to_string(),
            format!(
                "{{ mass = {}, stiffness = {} }}",
                rayleigh.alpha, rayleigh.beta
            ),
        ),
    };
    match method.scheme {
        Scheme::CentralDifference => {
            return Err(Error::invalid(
                "integrator.method",
                "\"central_difference\"",
                format!(
                    "does not carry the damping of {key} = {value}: the explicit step keeps v at half steps, so a damping matrix needs a solve with M + Δt/2·C each step and lowers the stable step to (2/ω)(√(1+ζ²) − ζ); use generalized_alpha, newmark, hht, wbz, bathe, moreau_jean or modal_exact"
                ),
            ));
        }
        Scheme::Registered(_) => {
            return Err(Error::invalid(
                "integrator.method",
                format!("\"{}\"", method.name()),
                format!(
                    "is a registered method, whose stepper does not read the damping of {key} = {value}: remove the damping or use a built-in implicit method"
                ),
            ));
        }
        _ => {}
    }
    if let Some((k, c)) = dashpot
        && matches!(
            d,
            Discretization::Modal { .. } | Discretization::Galerkin { .. }
        )
    {
        return Err(Error::invalid(
            k,
            c,
            "a dashpot c_a φ(x_a)φ(x_a)ᵀ couples every mode of a diagonal basis (mesh.kind = \"modal\" or \"galerkin\"), which has no place for it: use mesh.kind = \"hermite\" (Rayleigh damping [beam] damping stays diagonal in a modal basis)",
        ));
    }
    // a manufactured source carries the dashpots' forces (an attachment's
    // c_a, a dropper's c_d: `crate::manufactured`), not Rayleigh damping
    if scene.manufactured.is_some() && !rayleigh.is_zero() {
        return Err(Error::invalid(
            "manufactured",
            "(present)",
            format!(
                "a manufactured solution's source is that of the undamped lines and does not include beam.damping = {{ mass = {}, stiffness = {} }} (its point dashpots are carried): remove one or the other",
                rayleigh.alpha, rayleigh.beta
            ),
        ));
    }
    if let Some(r) = &scene.reference
        && r.kind != ReferenceKind::Richardson
    {
        return Err(Error::invalid(
            "reference.kind",
            format!("\"{}\"", r.kind.name()),
            format!(
                "is a closed form of the undamped beam and does not include {key} = {value}: use \"richardson\""
            ),
        ));
    }
    Ok(())
}
