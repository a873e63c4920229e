//! `[beam]`: the tensioned beam's geometry, material, tension and
//! supports (MODEL §1).

use serde::{Deserialize, Serialize};

use super::damping::RayleighSpec;

/// Support condition at a beam end (MODEL §1).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// v = 0 and v' = 0.
    Clamped,
    /// v = 0, moment free.
    Pinned,
    /// No constraint.
    Free,
}

/// `[beam]`: geometry, material, tension and supports.
///
/// Mass per length is either `mass_per_length` or `density`·`area`; bending
/// stiffness is either `bending_stiffness` or `youngs_modulus`·`second_moment`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BeamSpec {
    /// Span L, m (> 0).
    pub length: f64,
    /// Axial tension T, N (≥ 0).
    pub tension: f64,
    /// Support at x = 0.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
    /// Density ρ, kg/m³ (with `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// Cross-section area A, m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area: Option<f64>,
    /// Young's modulus E, Pa (with `second_moment`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<f64>,
    /// Second moment of area I, m⁴.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_moment: Option<f64>,
    /// Mass per length ρA, kg/m (instead of `density`·`area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_per_length: Option<f64>,
    /// Bending stiffness EI, N·m² (instead of `youngs_modulus`·`second_moment`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    /// Rayleigh damping `C = α M + β K` (`{ mass = α, stiffness = β }`,
    /// 1/s and s, each ≥ 0; absent: no damping).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<RayleighSpec>,
}

/// The source study's reference beam (MODEL §1, `scenes/reference.toml`):
/// a 50 m copper contact wire under 30 kN, clamped at x = 0 and pinned at
/// x = L, undamped.
impl Default for BeamSpec {
    fn default() -> Self {
        BeamSpec {
            length: 50.0,
            tension: 3.0e4,
            left: Support::Clamped,
            right: Support::Pinned,
            density: Some(8900.0),
            area: Some(1.5e-4),
            youngs_modulus: Some(1.34e11),
            second_moment: Some(9.64e-10),
            mass_per_length: None,
            bending_stiffness: None,
            damping: None,
        }
    }
}
