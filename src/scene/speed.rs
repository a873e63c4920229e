//! The `speed` key of a carrier (MODEL §3).

use serde::{Deserialize, Serialize};

/// A carrier's speed profile, `speed = { profile = "...", ... }`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
#[serde(tag = "profile", rename_all = "snake_case", deny_unknown_fields)]
pub enum SpeedProfile {
    /// Constant speed V, m/s (≥ 0; 0 = a stationary carrier).
    Constant {
        /// V, m/s.
        value: f64,
    },
    /// The study's smooth start: V0 reached after a ramp of length L/5
    /// with continuous acceleration (MODEL §3).
    SmoothRamp {
        /// Cruise speed V0, m/s (> 0).
        cruise: f64,
    },
}

impl SpeedProfile {
    /// The speed the carrier cruises at, m/s.
    pub fn cruise_speed(&self) -> f64 {
        match *self {
            SpeedProfile::Constant { value } => value,
            SpeedProfile::SmoothRamp { cruise } => cruise,
        }
    }
}
