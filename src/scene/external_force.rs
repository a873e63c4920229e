//! `[carrier.external_force]`: a time series of an external force on a
//! mass–spring carrier's mass (an aerodynamic uplift, a controller's
//! command written down), piecewise linear in t.
//!
//! Sign (MODEL §2): the force `F_ext(t)` acts on the mass in +v (up,
//! the beam's positive displacement), so the mass equation in
//! `q = s·ξ` becomes `m q̈ + c_s q̇ + k q = k δ0 − s·m·g + s·F_ext(t) − λ`.
//! For a pantograph below the wire (s = +1) a positive uplift presses the
//! mass into the wire. A constant `F_ext` is the same as a preload change
//! `k Δδ0 = s·F_ext`.
//!
//! The series must cover the run, `time[0] ≤ 0` and `time[last] ≥ t_end`:
//! outside it there is no value to take, and the scene is refused rather
//! than the force silently set to zero or held (a method's load time may
//! pass `t_end` by the round-off of the step count; [`ForceSeries::at`]
//! holds the end values there).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Most points a series may have: a dense 10⁶-point record is ample, and a
/// bound keeps a mistyped scene from asking for gigabytes.
pub(crate) const MAX_SERIES_POINTS: usize = 1_000_000;

/// `external_force = { time = [...], force = [...] }` as written.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ExternalForceSpec {
    /// Sample times, s (strictly increasing, finite).
    pub time: Vec<f64>,
    /// The force at each sample time, N (+v, up; finite).
    pub force: Vec<f64>,
}

/// A checked series: `force` linear between the samples `time`.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceSeries {
    time: Vec<f64>,
    force: Vec<f64>,
}

impl ForceSeries {
    /// Samples of the series.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True for a series without samples (never, once checked).
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Check carrier `i`'s series `spec` against a run of end time
    /// `t_end`, s: equal lengths (≥ 2), finite values, strictly increasing
    /// times covering `[0, t_end]`.
    pub fn new(i: usize, spec: &ExternalForceSpec, t_end: f64) -> Result<Self> {
        let f = |name: &str| format!("carrier.{i}.external_force.{name}");
        let (t, v) = (&spec.time, &spec.force);
        if t.len() < 2 || t.len() > MAX_SERIES_POINTS {
            return Err(Error::invalid(
                f("time"),
                format!("{} points", t.len()),
                format!("must have 2 ..= {MAX_SERIES_POINTS} points"),
            ));
        }
        if v.len() != t.len() {
            return Err(Error::invalid(
                f("force"),
                format!("{} values", v.len()),
                format!("must have one value per time ({} times)", t.len()),
            ));
        }
        if let Some((k, x)) = t.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::invalid(
                format!("{}.{k}", f("time")),
                x,
                "must be a finite number (s)",
            ));
        }
        if let Some((k, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::invalid(
                format!("{}.{k}", f("force")),
                x,
                "must be a finite number (N)",
            ));
        }
        if let Some(k) = (1..t.len()).find(|&k| t[k] <= t[k - 1]) {
            return Err(Error::invalid(
                format!("{}.{k}", f("time")),
                t[k],
                format!(
                    "must be > the time before it ({} s): strictly increasing",
                    t[k - 1]
                ),
            ));
        }
        if t[0] > 0.0 {
            return Err(Error::invalid(
                format!("{}.0", f("time")),
                t[0],
                "must be ≤ 0 s: the series must cover the run from its start",
            ));
        }
        let last = t[t.len() - 1];
        if last < t_end {
            return Err(Error::invalid(
                format!("{}.{}", f("time"), t.len() - 1),
                last,
                format!("must be ≥ the run's end time {t_end} s: the series must cover the run"),
            ));
        }
        Ok(ForceSeries {
            time: t.clone(),
            force: v.clone(),
        })
    }

    /// F_ext(t), N: linear between the samples; the end values held
    /// beyond them (reached only by round-off, [`ForceSeries::new`]
    /// checks the run is covered). O(log n), no allocation.
    pub fn at(&self, t: f64) -> f64 {
        let (ts, fs) = (&self.time, &self.force);
        // first sample strictly after t
        let k = ts.partition_point(|&x| x <= t);
        if k == 0 {
            return fs[0];
        }
        if k == ts.len() {
            return fs[k - 1];
        }
        let (t0, t1) = (ts[k - 1], ts[k]);
        let r = (t - t0) / (t1 - t0);
        fs[k - 1] + r * (fs[k] - fs[k - 1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(time: &[f64], force: &[f64]) -> ExternalForceSpec {
        ExternalForceSpec {
            time: time.to_vec(),
            force: force.to_vec(),
        }
    }

    #[test]
    fn linear_between_samples_and_exact_at_them() {
        let s = ForceSeries::new(0, &spec(&[0.0, 1.0, 3.0], &[0.0, 10.0, -10.0]), 3.0).unwrap();
        assert_eq!(s.at(0.0), 0.0);
        assert_eq!(s.at(0.5), 5.0);
        assert_eq!(s.at(1.0), 10.0);
        assert_eq!(s.at(2.0), 0.0);
        assert_eq!(s.at(3.0), -10.0);
        assert_eq!(s.at(3.0 + 1e-15), -10.0);
    }

    #[test]
    fn bad_series_are_refused_naming_the_field() {
        let e = |t: &[f64], f: &[f64], end: f64| {
            ForceSeries::new(2, &spec(t, f), end)
                .unwrap_err()
                .to_string()
        };
        let m = e(&[0.0], &[1.0], 1.0);
        assert!(
            m.contains("carrier.2.external_force.time") && m.contains("2 ..="),
            "{m}"
        );
        let m = e(&[0.0, 1.0], &[1.0], 1.0);
        assert!(
            m.contains("external_force.force") && m.contains("one value per time"),
            "{m}"
        );
        let m = e(&[0.0, 0.0, 1.0], &[1.0, 1.0, 1.0], 1.0);
        assert!(
            m.contains("time.1") && m.contains("strictly increasing"),
            "{m}"
        );
        let m = e(&[0.1, 1.0], &[1.0, 1.0], 1.0);
        assert!(m.contains("time.0") && m.contains("cover"), "{m}");
        let m = e(&[0.0, 0.5], &[1.0, 1.0], 1.0);
        assert!(m.contains("time.1") && m.contains("end time 1"), "{m}");
        let m = e(&[0.0, 1.0], &[1.0, f64::NAN], 1.0);
        assert!(m.contains("force.1") && m.contains("finite"), "{m}");
    }
}
