//! One swept axis: `--vary key=start:stop:count`, linear or logarithmic.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
/// Relative distance below which a grid value on an axis between whole
/// numbers is taken as the whole number it approximates: round-off of the
/// spacing formula is ~1e-15; a genuine grid value is further than 1e-9
/// from a whole number unless it is one.
pub const WHOLE_SNAP: f64 = 1e-9;

/// One swept axis.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Axis {
    /// Scene path or dimensionless name.
    pub key: String,
    /// First value.
    pub start: f64,
    /// Last value.
    pub stop: f64,
    /// Number of values (≥ 1).
    pub count: usize,
    /// Logarithmic spacing.
    pub log: bool,
}

/// One of the study's dimensionless axes ([`super::DIMENSIONLESS`]): a
/// ratio that fixes scene values through the scene itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ratio {
    /// v/c: every carrier's (cruise) speed, c = sqrt(T/ρA).
    Speed,
    /// T/EA: the beam's tension.
    Tension,
    /// m/(ρAL): every mass–spring carrier's mass.
    Mass,
    /// k/(T/L): every mass–spring carrier's stiffness.
    Stiffness,
}

impl Ratio {
    /// The ratio named `key` (its `--vary` spelling), if any.
    pub fn from_key(key: &str) -> Option<Self> {
        match key {
            "speed_ratio" => Some(Ratio::Speed),
            "tension_ratio" => Some(Ratio::Tension),
            "mass_ratio" => Some(Ratio::Mass),
            "stiffness_ratio" => Some(Ratio::Stiffness),
            _ => None,
        }
    }

    /// Its `--vary` spelling.
    pub fn key(self) -> &'static str {
        match self {
            Ratio::Speed => "speed_ratio",
            Ratio::Tension => "tension_ratio",
            Ratio::Mass => "mass_ratio",
            Ratio::Stiffness => "stiffness_ratio",
        }
    }
}

/// What an axis sets at each point: a scene key path (`beam.tension`,
/// `carrier.0.mass`), or a dimensionless ratio.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisTarget<'a> {
    /// A key path of the scene tree, as `--set` spells it.
    Path(&'a str),
    /// One of the study's ratios.
    Ratio(Ratio),
}

impl Axis {
    /// What the axis sets. The spec file stores the key as text (so a
    /// sweep folder written by an earlier binary reads back); this is its
    /// typed reading.
    pub fn target(&self) -> AxisTarget<'_> {
        match Ratio::from_key(&self.key) {
            Some(r) => AxisTarget::Ratio(r),
            None => AxisTarget::Path(&self.key),
        }
    }

    /// Parse `key=start:stop:count`.
    pub fn parse(spec: &str, log: bool) -> Result<Self> {
        let bad = |why: &str| Error::invalid("--vary", spec, why.to_string());
        let (key, range) = spec
            .split_once('=')
            .ok_or_else(|| bad("expected key=start:stop:count"))?;
        let parts: Vec<&str> = range.split(':').collect();
        let [a, b, n] = parts.as_slice() else {
            return Err(bad("expected key=start:stop:count"));
        };
        let num = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(start), Some(stop)) = (num(a), num(b)) else {
            return Err(bad("start and stop must be finite numbers"));
        };
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("count must be a whole number ≥ 1"))?;
        if count == 0 || count > 100_000 {
            return Err(bad("count must be in 1 ..= 100000"));
        }
        if log && (start <= 0.0 || stop <= 0.0) {
            return Err(bad("a logarithmic axis needs start and stop > 0"));
        }
        if key.trim().is_empty() {
            return Err(bad("the key is empty"));
        }
        Ok(Axis {
            key: key.trim().to_string(),
            start,
            stop,
            count,
            log,
        })
    }

    /// The i-th value: `start` and `stop` exactly at the ends. On an axis
    /// between whole numbers, a value within [`WHOLE_SNAP`] of a whole number
    /// is that number, so `mesh.elements=100:1600:5 --log` gives 200, 400, 800
    /// (integer keys take them) rather than 199.99999999999997.
    pub fn value(&self, i: usize) -> f64 {
        if i == 0 || self.count == 1 {
            return self.start;
        }
        if i + 1 == self.count {
            return self.stop;
        }
        let f = i as f64 / (self.count - 1) as f64;
        let v = if self.log {
            (self.start.ln() + f * (self.stop.ln() - self.start.ln())).exp()
        } else {
            self.start + f * (self.stop - self.start)
        };
        let whole_ends = self.start.fract() == 0.0 && self.stop.fract() == 0.0;
        if whole_ends && (v - v.round()).abs() <= WHOLE_SNAP * v.abs().max(1.0) {
            v.round()
        } else {
            v
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn axes_parse_and_space() {
        let a = Axis::parse("speed_ratio=0.4:1.3:10", false).unwrap();
        assert_eq!(a.count, 10);
        assert!((a.value(9) - 1.3).abs() < 1e-15);
        let l = Axis::parse("carrier.mass=0.1:10:3", true).unwrap();
        assert!((l.value(1) - 1.0).abs() < 1e-12);
        for bad in ["x", "x=1:2", "x=a:2:3", "x=1:2:0", "=1:2:3"] {
            assert!(Axis::parse(bad, false).is_err(), "{bad}");
        }
        assert!(Axis::parse("x=0:1:3", true).is_err());
    }
}
