//! The quantities `taut uncertainty` gives an error bar (MODEL §7, §12):
//! what a user reports of a run — P_l in the span and at the supports, the
//! contact force's mean, σ, max and min (raw and 0–20 Hz), the beam's
//! displacement under the carrier, the uplift at the supports, the loss
//! intervals and the first loss position — each with whether it is smooth
//! in the resolution and its formal order.

use serde::Serialize;

use crate::run::RunOutput;
use crate::study::formal_orders::{
    MAX_MESH_ORDER, MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER, MAX_STEP_ORDER_CONTACT,
};
use crate::study::scalars::{Scalar, values};

/// What a quantity is read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// A scalar of carrier 0 ([`Scalar`]).
    Scalar(Scalar),
    /// The largest displacement w under carrier 0 over the run (m; w is
    /// positive into the beam, MODEL §2): the largest sample refined by the
    /// parabola through it and its neighbours ([`peak`]).
    DisplacementMax,
    /// The smallest w under carrier 0 over the run, m (refined likewise).
    DisplacementMin,
    /// The RMS of w under carrier 0 over the run's steps, m.
    DisplacementRms,
    /// The largest v at any support of `[output] supports`, m (positive up).
    UpliftMax,
}

/// How a quantity depends on the discretization.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// The beam's displacement: Hermite O(h⁴), the method's order in Δt
    /// while no contact switches.
    Displacement,
    /// The contact force and what is counted from it: O(h²), O(Δt).
    Contact,
}

/// One quantity of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuantitySpec {
    /// Its name (a column of `sweep.csv` or a field of `summary.json`).
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Where it is read.
    pub measure: Measure,
    /// False for a count of events or an extreme of the raw force: it
    /// moves by whole steps and spikes, not smoothly, as the resolution
    /// changes (MODEL §12), so only the least-squares estimator with
    /// F_s = 3 is used on it.
    pub smooth: bool,
    /// Its formal orders.
    pub kind: Kind,
}

const fn q(measure: Measure, smooth: bool, kind: Kind) -> QuantitySpec {
    let (name, unit) = match measure {
        Measure::Scalar(s) => (s.name(), s.unit()),
        Measure::DisplacementMax => ("displacement_max", "m"),
        Measure::DisplacementMin => ("displacement_min", "m"),
        Measure::DisplacementRms => ("displacement_rms", "m"),
        Measure::UpliftMax => ("uplift_max", "m"),
    };
    QuantitySpec {
        name,
        unit,
        measure,
        smooth,
        kind,
    }
}

/// The quantities, in table order.
pub(crate) const QUANTITIES: [QuantitySpec; 16] = [
    q(
        Measure::Scalar(Scalar::LossFractionSpan),
        false,
        Kind::Contact,
    ),
    q(
        Measure::Scalar(Scalar::LossFractionSupport),
        false,
        Kind::Contact,
    ),
    q(Measure::Scalar(Scalar::LossFraction), false, Kind::Contact),
    q(Measure::Scalar(Scalar::ForceMean), true, Kind::Contact),
    q(Measure::Scalar(Scalar::ForceStd), false, Kind::Contact),
    q(Measure::Scalar(Scalar::ForceMax), false, Kind::Contact),
    q(Measure::Scalar(Scalar::ForceMin), false, Kind::Contact),
    q(
        Measure::Scalar(Scalar::FilteredForceStd),
        true,
        Kind::Contact,
    ),
    q(
        Measure::Scalar(Scalar::FilteredForceMax),
        true,
        Kind::Contact,
    ),
    q(
        Measure::Scalar(Scalar::FilteredForceMin),
        true,
        Kind::Contact,
    ),
    q(Measure::DisplacementMax, true, Kind::Displacement),
    q(Measure::DisplacementMin, true, Kind::Displacement),
    q(Measure::DisplacementRms, true, Kind::Displacement),
    q(Measure::UpliftMax, true, Kind::Displacement),
    q(
        Measure::Scalar(Scalar::LossIntervalCount),
        false,
        Kind::Contact,
    ),
    q(
        Measure::Scalar(Scalar::FirstLossPosition),
        false,
        Kind::Contact,
    ),
];

/// The quantity called `name`.
pub fn quantity(name: &str) -> Option<QuantitySpec> {
    QUANTITIES.into_iter().find(|q| q.name == name)
}

impl QuantitySpec {
    /// Formal orders (space, time) for a run of `method_order` in Δt whose
    /// contacts `switch` (open or close somewhere in the family), on string
    /// elements when `string` (MODEL §4, §5; the caps of `run --tolerance`).
    pub fn formal_orders(&self, method_order: f64, switch: bool, string: bool) -> (f64, f64) {
        match self.kind {
            Kind::Displacement => (
                if string { 2.0 } else { MAX_MESH_ORDER },
                if switch {
                    MAX_STEP_ORDER_CONTACT
                } else {
                    method_order.min(MAX_STEP_ORDER)
                },
            ),
            Kind::Contact => (MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT),
        }
    }

    /// Its value in `out` (`None` where undefined: no first loss, no
    /// supports).
    pub fn of(&self, out: &RunOutput) -> Option<f64> {
        let w = || out.history.carriers.first().map(|c| c.w.as_slice());
        match self.measure {
            Measure::Scalar(s) => values(out, 0, &[s]).pop().flatten(),
            Measure::DisplacementMax => peak(w()?, 1.0),
            Measure::DisplacementMin => peak(w()?, -1.0).map(|v| -v),
            Measure::DisplacementRms => {
                // over the steps (rows 1 …), as the force statistics
                let w = w()?.get(1..).filter(|w| !w.is_empty())?;
                Some((w.iter().map(|x| x * x).sum::<f64>() / w.len() as f64).sqrt())
            }
            Measure::UpliftMax => out
                .history
                .supports
                .iter()
                .map(|s| s.v_max)
                .reduce(f64::max),
        }
    }
}

/// The largest of `sign`·w (`sign` = ±1) over the samples, refined by the
/// parabola through the largest sample and its two neighbours (its vertex,
/// when it lies between them). A sampled maximum jumps as the sample grid
/// moves against the peak, by up to w''Δt²/8, so it converges irregularly
/// in Δt; the vertex of the parabola is a smooth function of the samples
/// and within O(Δt³) of the sampled curve's peak. At the first or last
/// sample the sample itself.
pub fn peak(w: &[f64], sign: f64) -> Option<f64> {
    let k = (0..w.len()).max_by(|&a, &b| (sign * w[a]).total_cmp(&(sign * w[b])))?;
    let y = |i: usize| sign * w[i];
    if k == 0 || k + 1 == w.len() {
        return Some(y(k));
    }
    let (a, b, c) = (y(k - 1), y(k), y(k + 1));
    let curvature = a - 2.0 * b + c;
    if curvature >= 0.0 {
        return Some(b);
    }
    // vertex of the parabola through (−1, a), (0, b), (1, c)
    let x = 0.5 * (a - c) / curvature;
    Some(b - 0.25 * (a - c) * x)
}

/// The value of every quantity in `out`, in [`QUANTITIES`]' order (the
/// 0–20 Hz force filtered once).
pub(crate) fn all_values(out: &RunOutput) -> Vec<Option<f64>> {
    let scalars: Vec<Scalar> = QUANTITIES
        .iter()
        .filter_map(|q| match q.measure {
            Measure::Scalar(s) => Some(s),
            _ => None,
        })
        .collect();
    let mut read = values(out, 0, &scalars).into_iter();
    QUANTITIES
        .iter()
        .map(|q| match q.measure {
            Measure::Scalar(_) => read.next().flatten(),
            _ => q.of(out),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_peak_between_samples_is_found_to_third_order() {
        // w = cos(t − 0.3) sampled every 0.1: the vertex is near 1, the
        // largest sample is cos(0.05)
        let w: Vec<f64> = (0..10).map(|i| (i as f64 * 0.1 - 0.35f64).cos()).collect();
        let p = peak(&w, 1.0).unwrap();
        assert!((p - 1.0).abs() < 2e-4, "{p}");
        assert!(p > w.iter().copied().fold(f64::MIN, f64::max));
        let m = peak(&w.iter().map(|x| -x).collect::<Vec<_>>(), -1.0).unwrap();
        assert!((m - 1.0).abs() < 2e-4, "{m}");
        // at an end, the sample
        assert_eq!(peak(&[1.0, 0.5, 0.2], 1.0), Some(1.0));
        assert_eq!(peak(&[], 1.0), None);
    }
}
