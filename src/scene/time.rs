//! `[time]`: the step, the end time and the initial state (MODEL §5).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `[time]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Time step Δt, s (> 0).
    pub step: f64,
    /// End time, s, or `"carrier_leaves"`.
    pub end: EndTime,
    /// The initial state: `"rest"` (default, MODEL §5: d₀ = 0, ḋ₀ = 0) or
    /// `"static"` (d₀ solves K d₀ = f, `docs/lines.md` eq. W6).
    #[serde(default, skip_serializing_if = "Initial::is_rest")]
    pub initial: Initial,
}

/// The reference case's time grid (`scenes/reference.toml`): Δt = 10⁻⁴ s
/// until the carrier leaves the beam, from rest.
impl Default for TimeSpec {
    fn default() -> Self {
        TimeSpec {
            step: 1.0e-4,
            end: EndTime::CarrierLeaves,
            initial: Initial::Rest,
        }
    }
}

/// `[time] initial`: where the wire starts.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Initial {
    /// Straight and at rest (MODEL §5).
    #[default]
    Rest,
    /// At its static equilibrium under the constant loads, at rest.
    Static,
}

impl Initial {
    /// True for the default.
    pub fn is_rest(&self) -> bool {
        *self == Initial::Rest
    }
}

/// When a run stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndTime {
    /// At this time, s.
    Seconds(f64),
    /// When the first moving carrier reaches a beam end.
    CarrierLeaves,
}

impl Serialize for EndTime {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            EndTime::Seconds(t) => s.serialize_f64(*t),
            EndTime::CarrierLeaves => s.serialize_str("carrier_leaves"),
        }
    }
}

impl<'de> Deserialize<'de> for EndTime {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = EndTime;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a time in seconds or the string \"carrier_leaves\"")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<EndTime, E> {
                if v == "carrier_leaves" {
                    Ok(EndTime::CarrierLeaves)
                } else {
                    Err(E::invalid_value(serde::de::Unexpected::Str(v), &self))
                }
            }
        }
        d.deserialize_any(V)
    }
}
