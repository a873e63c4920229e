//! `[[carrier]]`: a mass–spring, a multi-mass pantograph or a moving
//! force, and the side of the beam it is on (MODEL §2, §3, §10).

use serde::{Deserialize, Serialize};

use super::external_force::ExternalForceSpec;
use super::speed::SpeedProfile;

/// Which side of the beam the carrier's mass sits on (MODEL §2).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// The mass is above the beam and pushes it down (s = −1).
    Above,
    /// The mass is below the beam and pushes it up (s = +1).
    Below,
}

impl Side {
    /// The sign `s` of MODEL §2: +1 below, −1 above.
    pub fn sign(self) -> f64 {
        match self {
            Side::Above => -1.0,
            Side::Below => 1.0,
        }
    }
}

/// `[[carrier]]`: a mass–spring (`mass`, `stiffness`, …) or a moving
/// constant force (`force`, no mass).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CarrierSpec {
    /// Mass m, kg (> 0). Absent for a moving force.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Spring stiffness k, N/m (≥ 0; 0 = a riding mass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Dashpot c_s, N·s/m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Spring preload δ0, m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<f64>,
    /// Moving constant force F, N (≥ 0, pressing into the beam from `side`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force: Option<f64>,
    /// A multi-mass pantograph's masses m₁ (head) … m_n, kg (2 or 3, each
    /// > 0; `scene/pantograph.rs`). Replaces `mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub masses: Option<Vec<f64>>,
    /// Its springs k₁ … k_n, N/m: k_i between m_i and m_{i+1}, k_n to the roof.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffnesses: Option<Vec<f64>>,
    /// Its dashpots c₁ … c_n, N·s/m, placed like the springs (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dampings: Option<Vec<f64>>,
    /// Its static uplift F₀, N (≥ 0, default 0), on the mass
    /// `uplift_mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uplift: Option<f64>,
    /// Its aerodynamic uplift coefficient c_a, N·s²/m² (finite, default 0):
    /// the uplift is F₀ + c_a·V(t)², V the carrier's speed
    /// (`scene/pantograph.rs`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uplift_coefficient: Option<f64>,
    /// The mass the uplift acts on, an index 0 (head) … n − 1 (frame; the
    /// default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uplift_mass: Option<usize>,
    /// Side of the beam the carrier is on.
    pub side: Side,
    /// Initial position x_m(0), m (0 ≤ start ≤ L).
    pub start: f64,
    /// Speed profile (MODEL §3).
    pub speed: SpeedProfile,
    /// An external force on the mass (a pantograph's: on its mass
    /// `external_force.mass`), N in +v, piecewise linear in t
    /// (`external_force.rs`; mass–spring carriers only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub external_force: Option<ExternalForceSpec>,
}

/// The source study's reference carrier (MODEL §2, §3,
/// `scenes/reference.toml`): a 1 kg mass on a 987 N/m spring preloaded by
/// 5 cm, above the beam, starting at x = 0 and ramping smoothly to
/// 100 m/s.
impl Default for CarrierSpec {
    fn default() -> Self {
        CarrierSpec {
            mass: Some(1.0),
            stiffness: Some(987.0),
            damping: None,
            preload: Some(0.05),
            force: None,
            masses: None,
            stiffnesses: None,
            dampings: None,
            uplift: None,
            uplift_coefficient: None,
            uplift_mass: None,
            side: Side::Above,
            start: 0.0,
            speed: SpeedProfile::SmoothRamp { cruise: 100.0 },
            external_force: None,
        }
    }
}
