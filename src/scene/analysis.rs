//! `[analysis]`: how a run's contact force is evaluated the way the
//! railway standards do (docs/output.md#the-standards-statistics): the band
//! of the low-pass filtered force (0–`band` Hz, default 20) and the analysis
//! section, a range of each carrier's own position x_m, given in metres
//! (`x`) or as spans between the line's supports (`spans`), and the width
//! of the support zones that split P_l (`support_zone`).

use serde::{Deserialize, Serialize};

/// `[analysis]` as written in a scene.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// Upper edge of the filtered force's band, Hz (> 0; default 20): the
    /// force is low-pass filtered to 0–`band` Hz (`record::filter`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub band: Option<f64>,
    /// The analysis section as carrier positions `[x_start, x_end]`, m
    /// (0 ≤ x_start < x_end ≤ L). Default: the whole beam, [0, L].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<[f64; 2]>,
    /// The analysis section as spans `[first, last]` between the line's
    /// supports, 0-based and inclusive as in `spans.csv` (instead of `x`;
    /// needs supports: `[output] supports`, a `[line]` or a `[messenger]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spans: Option<[usize; 2]>,
    /// Width z of the support zone at each held end, m (> 0, at most L/2;
    /// default 4ℓ_b, ℓ_b = sqrt(EI/T) the bending length, or on a string
    /// 4·V·m/Z, `record::zone`: lengths of the physics, never of h or Δt;
    /// none without tension):
    /// where P_l counts as at a support rather than in the span.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support_zone: Option<f64>,
}

impl AnalysisSpec {
    /// True when nothing is given (the key is left out of `summary.json`).
    pub fn is_default(&self) -> bool {
        *self == AnalysisSpec::default()
    }
}

/// A speed as a user writes it: a number in m/s, or a string with its
/// unit, `"250 km/h"` or `"69.4 m/s"` (docs/scene.md#speeds-in-kmh). The
/// value is held in m/s; a string without a unit, or with another, is
/// refused naming the unit it lacks (the key's path is added by the scene
/// reader).
pub mod speed_unit {
    use serde::{Deserialize, Deserializer};

    /// km/h in m/s.
    pub const KMH: f64 = 1.0 / 3.6;

    /// Parse `"250 km/h"`, `"250km/h"`, `"69.4 m/s"` into m/s.
    pub fn parse(text: &str) -> Result<f64, String> {
        let t = text.trim();
        let (number, factor) = if let Some(n) = t.strip_suffix("km/h") {
            (n, KMH)
        } else if let Some(n) = t.strip_suffix("m/s") {
            (n, 1.0)
        } else {
            return Err(format!(
                "{text:?}: a speed as text needs its unit, \"km/h\" or \"m/s\" (e.g. \"250 km/h\"); a bare number is m/s"
            ));
        };
        let v: f64 = number.trim().parse().map_err(|_| {
            format!("{text:?}: expected a number before the unit, e.g. \"250 km/h\"")
        })?;
        if !v.is_finite() {
            return Err(format!("{text:?}: the speed must be finite"));
        }
        Ok(v * factor)
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Written {
        Number(f64),
        Text(String),
    }

    fn one<'de, D: Deserializer<'de>>(key: &str, w: Written) -> Result<f64, D::Error> {
        match w {
            Written::Number(v) => Ok(v),
            Written::Text(t) => {
                parse(&t).map_err(|e| serde::de::Error::custom(format!("{key} = {e}")))
            }
        }
    }

    /// One speed under `key` (named in a message: the speed table is
    /// internally tagged, so the reader's path stops at `speed`), m/s.
    fn speed<'de, D: Deserializer<'de>>(key: &str, d: D) -> Result<f64, D::Error> {
        let w = Written::deserialize(d).map_err(|_| {
            serde::de::Error::custom(format!(
                "{key}: expected a speed: a number (m/s) or text with its unit, \"250 km/h\" or \"69.4 m/s\""
            ))
        })?;
        one::<D>(key, w)
    }

    /// `value` of a constant speed, m/s.
    pub fn value<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        speed(d_key::VALUE, d)
    }

    /// `cruise` of a smooth ramp, m/s.
    pub fn cruise<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        speed(d_key::CRUISE, d)
    }

    /// `speed` of a table, a list of speeds, m/s.
    pub fn list<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<Written>::deserialize(d)
            .map_err(|_| {
                serde::de::Error::custom("speed: expected a list of speeds: numbers (m/s) or texts with their unit, \"250 km/h\"")
            })?
            .into_iter()
            .enumerate()
            .map(|(i, w)| one::<D>(&format!("speed.{i}"), w))
            .collect()
    }

    mod d_key {
        pub const VALUE: &str = "value";
        pub const CRUISE: &str = "cruise";
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        #[test]
        fn km_per_hour_and_metres_per_second() {
            assert_eq!(parse("250 km/h").unwrap(), 250.0 / 3.6);
            assert_eq!(parse(" 90km/h ").unwrap(), 90.0 / 3.6);
            assert_eq!(parse("69.4 m/s").unwrap(), 69.4);
        }

        #[test]
        fn ambiguous_text_is_refused_naming_the_unit() {
            for bad in ["250", "250 kmh", "250 mph", "fast km/h", "inf km/h"] {
                let e = parse(bad).unwrap_err();
                assert!(e.contains(bad.trim()) || e.contains("finite"), "{e}");
            }
            assert!(parse("250").unwrap_err().contains("km/h"));
        }
    }
}
