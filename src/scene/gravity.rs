//! `[gravity]`: gravity on the carriers and, optionally, the beam's
//! self-weight.

use serde::{Deserialize, Serialize};

fn standard_gravity() -> f64 {
    9.81
}

/// `[gravity]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GravitySpec {
    /// Gravitational acceleration g, m/s² (≥ 0, default 9.81). Acts on carrier masses.
    #[serde(default = "standard_gravity")]
    pub g: f64,
    /// Also load the beam with its self-weight −ρA g (default false, MODEL §1).
    #[serde(default)]
    pub beam_self_weight: bool,
}

impl Default for GravitySpec {
    fn default() -> Self {
        GravitySpec {
            g: standard_gravity(),
            beam_self_weight: false,
        }
    }
}
