//! The `speed` key of a carrier (MODEL §3).

use serde::{Deserialize, Serialize};

use super::analysis::speed_unit;

/// A carrier's speed profile, `speed = { profile = "...", ... }`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(tag = "profile", rename_all = "snake_case", deny_unknown_fields)]
pub enum SpeedProfile {
    /// Constant speed V, m/s (≥ 0; 0 = a stationary carrier).
    Constant {
        /// V, m/s (or text with its unit, `"250 km/h"`).
        #[serde(deserialize_with = "speed_unit::value")]
        value: f64,
    },
    /// The study's smooth start: V0 reached after a ramp of length L/5
    /// with continuous acceleration (MODEL §3).
    SmoothRamp {
        /// Cruise speed V0, m/s (> 0; or text with its unit, `"250 km/h"`).
        #[serde(deserialize_with = "speed_unit::cruise")]
        cruise: f64,
    },
    /// A tabulated speed V(t), piecewise linear between the knots (so the
    /// position x_m(t) is piecewise quadratic, integrated exactly;
    /// [`super::Motion`]): `speed = { profile = "table", time = [...],
    /// speed = [...] }`. Times start at 0, rise strictly and reach the
    /// run's end; speeds are ≥ 0 (the carrier never backs up).
    Table {
        /// Knot times t_k, s.
        time: Vec<f64>,
        /// V(t_k), m/s (each may be text with its unit, `"250 km/h"`).
        #[serde(deserialize_with = "speed_unit::list")]
        speed: Vec<f64>,
    },
}

impl SpeedProfile {
    /// The speed the carrier cruises at, m/s (for a table, its largest
    /// speed: what V0/c and a stationary carrier are judged by).
    pub fn cruise_speed(&self) -> f64 {
        match self {
            SpeedProfile::Constant { value } => *value,
            SpeedProfile::SmoothRamp { cruise } => *cruise,
            SpeedProfile::Table { speed, .. } => speed.iter().copied().fold(0.0, f64::max),
        }
    }
}
