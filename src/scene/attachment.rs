//! `[[attachment]]`: point attachments along the beam (MODEL §10): a
//! spring k_a to a fixed anchor and a lumped mass m_a at x_a, which add
//! `k_a r_a r_aᵀ` to K and `m_a r_a r_aᵀ` to M (r_a the interpolation
//! vector at x_a, MODEL §4; assembled in `model::beam`). Plain data: the
//! scene's spelling ([`AttachmentSpec`]), each value's own range check, and
//! the property struct the model is built from ([`Attachment`], carried by
//! [`super::BeamProps`]).
//!
//! A dashpot c_a to the anchor (`damping`, N·s/m) adds `c_a r_a r_aᵀ` to
//! the damping matrix C (docs/lines.md §10.4), assembled with the wire's
//! Rayleigh damping in `model::damping`.

use serde::{Deserialize, Serialize};

use super::output::Wire;
use super::range::non_negative;
use crate::error::{Error, Result};

/// `[[attachment]]` as written in the scene.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AttachmentSpec {
    /// Position x_a, m (0 ≤ x_a ≤ L).
    pub x: f64,
    /// Spring stiffness k_a to a fixed anchor, N/m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub stiffness: f64,
    /// Lumped mass m_a, kg (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub mass: f64,
    /// Dashpot c_a to the fixed anchor, N·s/m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub damping: f64,
    /// The line it acts on: `"contact"` (default) or `"messenger"` (on the
    /// messenger wire at x_a, r_m(x_a) in place of r_b(x_a): a dropper's
    /// clamp; needs `[messenger]`, `docs/lines.md` eq. E1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wire: Option<Wire>,
    /// An optional label (for messages and the reader), any text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// A point attachment, resolved (SI units): what the model assembles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    /// Position x_a, m.
    pub x: f64,
    /// Spring stiffness k_a, N/m (≥ 0).
    pub stiffness: f64,
    /// Lumped mass m_a, kg (≥ 0).
    pub mass: f64,
    /// Dashpot c_a, N·s/m (≥ 0; 0: none).
    pub damping: f64,
}

impl AttachmentSpec {
    /// True when it acts on the messenger (`wire = "messenger"`).
    pub fn on_messenger(&self) -> bool {
        self.wire == Some(Wire::Messenger)
    }
}

/// The scene indices of the `[[attachment]]`s on the contact wire, in
/// order: the i-th contact attachment is `attachment.<own[i]>`.
pub(crate) fn contact_indices(specs: &[AttachmentSpec]) -> Vec<usize> {
    (0..specs.len())
        .filter(|&i| !specs[i].on_messenger())
        .collect()
}

/// Check each `[[attachment]]` on a beam of span `l`, m: x in [0, L],
/// stiffness, mass and damping finite and ≥ 0, at least one of them > 0;
/// the ones on the line `on_messenger` says, in scene order.
pub(crate) fn resolve_attachments(
    specs: &[AttachmentSpec],
    l: f64,
    on_messenger: bool,
) -> Result<Vec<Attachment>> {
    let mut out = Vec::with_capacity(specs.len());
    for (i, a) in specs.iter().enumerate() {
        if a.on_messenger() != on_messenger {
            continue;
        }
        if !(0.0..=l).contains(&a.x) {
            return Err(Error::invalid(
                format!("attachment.{i}.x"),
                a.x,
                format!("must be on the beam, in [0, {l}] m"),
            ));
        }
        let stiffness = non_negative(&format!("attachment.{i}.stiffness"), a.stiffness, "N/m")?;
        let mass = non_negative(&format!("attachment.{i}.mass"), a.mass, "kg")?;
        let damping = non_negative(&format!("attachment.{i}.damping"), a.damping, "N·s/m")?;
        if stiffness == 0.0 && mass == 0.0 && damping == 0.0 {
            return Err(Error::invalid(
                format!("attachment.{i}.stiffness"),
                0.0,
                "an attachment needs stiffness > 0 (N/m), mass > 0 (kg) or damping > 0 (N·s/m)",
            ));
        }
        out.push(Attachment {
            x: a.x,
            stiffness,
            mass,
            damping,
        });
    }
    Ok(out)
}
