//! `[beam] damping`: Rayleigh damping of the wire (docs/lines.md §10.4),
//! `C = α M + β K` with M and K the assembled mass and stiffness (the
//! attachments' masses and springs included, so that C is diagonal in the
//! model's own modes and each mode j has the damping ratio
//! `ζ_j = α/(2ω_j) + βω_j/2`, L12). Plain data: the scene's spelling
//! ([`RayleighSpec`]), its range check, and the resolved pair
//! ([`Rayleigh`]). A dashpot on an attachment is `[[attachment]] damping`
//! (`attachment.rs`).

use serde::{Deserialize, Serialize};

use super::range::non_negative;
use crate::error::Result;

/// `[beam] damping = { mass = α, stiffness = β }` as written in the scene.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct RayleighSpec {
    /// Mass-proportional coefficient α, 1/s (≥ 0, default 0).
    #[serde(default)]
    pub mass: f64,
    /// Stiffness-proportional coefficient β, s (≥ 0, default 0).
    #[serde(default)]
    pub stiffness: f64,
}

/// Rayleigh damping resolved: `C = α M + β K` (both 0: no damping).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rayleigh {
    /// α, 1/s.
    pub alpha: f64,
    /// β, s.
    pub beta: f64,
}

impl Rayleigh {
    /// True when the wire has no Rayleigh damping (α = β = 0).
    pub fn is_zero(&self) -> bool {
        self.alpha == 0.0 && self.beta == 0.0
    }

    /// The damping ratio of a mode of angular frequency ω (rad/s, > 0):
    /// ζ = α/(2ω) + βω/2 (L12).
    pub fn zeta(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + self.beta * omega / 2.0
    }
}

/// Check `[beam] damping`: α and β finite and ≥ 0. Absent is no damping.
pub(crate) fn resolve_rayleigh(spec: Option<&RayleighSpec>) -> Result<Rayleigh> {
    let Some(s) = spec else {
        return Ok(Rayleigh::default());
    };
    Ok(Rayleigh {
        alpha: non_negative("beam.damping.mass", s.mass, "1/s")?,
        beta: non_negative("beam.damping.stiffness", s.stiffness, "s")?,
    })
}
