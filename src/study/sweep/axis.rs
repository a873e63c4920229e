//! One swept axis: `--vary key=start:stop:count`, linear or logarithmic,
//! or `--vary key=v1,v2,...`, an explicit list of values.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
/// Relative distance below which a grid value on an axis between whole
/// numbers is taken as the whole number it approximates: round-off of the
/// spacing formula is ~1e-15; a genuine grid value is further than 1e-9
/// from a whole number unless it is one.
pub(crate) const WHOLE_SNAP: f64 = 1e-9;

/// The most values one axis may have (a sweep has at most
/// [`super::MAX_POINTS`] points in all).
const MAX_COUNT: usize = 100_000;

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
    /// The explicit values of a listed axis (`--vary key=v1,v2,...`,
    /// Python `vary={key: [...]}`, a column of `--points`), in order;
    /// `start`, `stop` and `count` are then its first, last and number.
    /// None for a `start:stop:count` range (and absent from its
    /// `sweep.json`, so a range sweep's spec and records keep their bytes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<f64>>,
}

/// One of the study's dimensionless axes (`speed_ratio`, `tension_ratio`, `mass_ratio`, `stiffness_ratio`): a
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

    /// An axis of explicit values (each finite; > 0 on a logarithmic axis),
    /// walked in the order given.
    pub fn list(key: &str, values: Vec<f64>, log: bool) -> Result<Self> {
        let spec = || {
            let v: Vec<String> = values.iter().map(|v| v.to_string()).collect();
            format!("{key}={}", v.join(","))
        };
        let bad =
            |why: &str| Error::invalid("--vary", crate::error::one_line(&spec()), why.to_string());
        if key.trim().is_empty() {
            return Err(bad("the key is empty"));
        }
        if values.is_empty() || values.len() > MAX_COUNT {
            return Err(bad("give 1 ..= 100000 values"));
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(bad("every value must be a finite number"));
        }
        if log && values.iter().any(|&v| v <= 0.0) {
            return Err(bad("a logarithmic axis needs values > 0"));
        }
        Ok(Axis {
            key: key.trim().to_string(),
            start: values[0],
            stop: values[values.len() - 1],
            count: values.len(),
            log,
            values: Some(values),
        })
    }

    /// Whether the axis can be drawn on a map: a range always (as before
    /// lists existed), a list when its values are strictly increasing or
    /// decreasing.
    pub fn monotone(&self) -> bool {
        if self.values.is_none() {
            return true;
        }
        let v: Vec<f64> = (0..self.count).map(|i| self.value(i)).collect();
        v.windows(2).all(|w| w[0] < w[1]) || v.windows(2).all(|w| w[0] > w[1])
    }

    /// Parse `key=start:stop:count`, or `key=v1,v2,...` (a list: text with
    /// no `:`; one value is a list of one).
    pub fn parse(spec: &str, log: bool) -> Result<Self> {
        let bad = |why: &str| Error::invalid("--vary", spec, why.to_string());
        let (key, range) = spec
            .split_once('=')
            .ok_or_else(|| bad("expected key=start:stop:count or key=v1,v2,..."))?;
        if !range.contains(':') {
            let values: Option<Vec<f64>> = range
                .split(',')
                .map(|s| s.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
                .collect();
            let values = values.ok_or_else(|| {
                bad("a list key=v1,v2,... takes finite numbers, separated by commas")
            })?;
            return Self::list(key, values, log);
        }
        let parts: Vec<&str> = range.split(':').collect();
        let [a, b, n] = parts.as_slice() else {
            return Err(bad("expected key=start:stop:count or key=v1,v2,..."));
        };
        let num = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(start), Some(stop)) = (num(a), num(b)) else {
            return Err(bad("start and stop must be finite numbers"));
        };
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("count must be a whole number ≥ 1"))?;
        if count == 0 || count > MAX_COUNT {
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
            values: None,
        })
    }

    /// The i-th value: `start` and `stop` exactly at the ends. On an axis
    /// between whole numbers, a value within `WHOLE_SNAP` of a whole number
    /// is that number, so `mesh.elements=100:1600:5 --log` gives 200, 400, 800
    /// (integer keys take them) rather than 199.99999999999997.
    pub fn value(&self, i: usize) -> f64 {
        if let Some(v) = &self.values {
            return v[i];
        }
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

    #[test]
    fn lists_parse_in_order() {
        let a = Axis::parse("beam.tension=3e4, 2e4,2.5e4", false).unwrap();
        assert_eq!(a.values, Some(vec![3e4, 2e4, 2.5e4]));
        assert_eq!((a.start, a.stop, a.count), (3e4, 2.5e4, 3));
        assert_eq!(a.value(1), 2e4);
        assert!(!a.monotone());
        assert!(Axis::parse("x=1,2,4", false).unwrap().monotone());
        assert_eq!(Axis::parse("x=7", false).unwrap().values, Some(vec![7.0]));
        for bad in ["x=1,,2", "x=1,a", "x=1,inf", "=1,2"] {
            assert!(Axis::parse(bad, false).is_err(), "{bad}");
        }
        assert!(Axis::parse("x=1,0", true).is_err());
        // a range has no list, and its spec file says nothing of one
        let r = Axis::parse("x=1:2:3", false).unwrap();
        assert!(!serde_json::to_string(&r).unwrap().contains("values"));
    }
}
