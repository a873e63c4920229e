//! The one list of a run's scalar outputs that studies read, estimate or
//! gate: `taut gate` (any of them, by name), `run --tolerance` (an
//! estimated error for each of [`super::tolerance::RESULTS`]) and
//! `taut converge` (the loss quantities).
//!
//! A value a run does not have is `None`: the first loss position of a
//! contact that is never lost ([`ContactStats::first_loss_position`]), a
//! carrier the run does not have. It is written as an empty CSV cell or
//! JSON `null`, never as a stand-in number; a gate check on it fails
//! (docs/gating.md).

use super::filter::{FORCE_BAND_HZ, lowpass_zero_phase};
use crate::record::ContactStats;
use crate::run::RunOutput;

/// A scalar output of a run, of one carrier.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    /// Steps taken (of the run).
    Steps,
    /// Unknowns (of the run).
    Dofs,
    /// Contact switches.
    ContactSwitches,
    /// P_l.
    LossFraction,
    /// Its in-span part.
    LossFractionSpan,
    /// Its part in the support zones.
    LossFractionSupport,
    /// Loss intervals (all of them).
    LossIntervalCount,
    /// x_m/L where contact is first lost; `None` when it never is.
    FirstLossPosition,
    /// Mean contact force.
    ForceMean,
    /// Its standard deviation.
    ForceStd,
    /// Smallest contact force.
    ForceMin,
    /// Largest contact force.
    ForceMax,
    /// Standard deviation of the 0–20 Hz force (over the steps).
    FilteredForceStd,
    /// Smallest 0–20 Hz force.
    FilteredForceMin,
    /// Largest 0–20 Hz force.
    FilteredForceMax,
    /// Largest penetration max(0, −g).
    MaxPenetration,
    /// Beam displacement under the carrier at the last recorded row.
    FinalW,
}

impl Scalar {
    /// Every scalar, in the order documented.
    pub const ALL: [Scalar; 17] = [
        Scalar::Steps,
        Scalar::Dofs,
        Scalar::ContactSwitches,
        Scalar::LossFraction,
        Scalar::LossFractionSpan,
        Scalar::LossFractionSupport,
        Scalar::LossIntervalCount,
        Scalar::FirstLossPosition,
        Scalar::ForceMean,
        Scalar::ForceStd,
        Scalar::ForceMin,
        Scalar::ForceMax,
        Scalar::FilteredForceStd,
        Scalar::FilteredForceMin,
        Scalar::FilteredForceMax,
        Scalar::MaxPenetration,
        Scalar::FinalW,
    ];

    /// The name in tables, case files and `summary.json`.
    pub const fn name(self) -> &'static str {
        match self {
            Scalar::Steps => "steps",
            Scalar::Dofs => "dofs",
            Scalar::ContactSwitches => "contact_switches",
            Scalar::LossFraction => "loss_fraction",
            Scalar::LossFractionSpan => "loss_fraction_span",
            Scalar::LossFractionSupport => "loss_fraction_support",
            Scalar::LossIntervalCount => "loss_interval_count",
            Scalar::FirstLossPosition => "first_loss_position",
            Scalar::ForceMean => "force_mean",
            Scalar::ForceStd => "force_std",
            Scalar::ForceMin => "force_min",
            Scalar::ForceMax => "force_max",
            Scalar::FilteredForceStd => "filtered_force_std",
            Scalar::FilteredForceMin => "filtered_force_min",
            Scalar::FilteredForceMax => "filtered_force_max",
            Scalar::MaxPenetration => "max_penetration",
            Scalar::FinalW => "final_w",
        }
    }

    /// Its label in terminal output.
    pub fn label(self) -> &'static str {
        match self {
            Scalar::Steps => "steps",
            Scalar::Dofs => "unknowns",
            Scalar::ContactSwitches => "switches",
            Scalar::LossFraction => "contact loss P_l",
            Scalar::LossFractionSpan => "P_l in span",
            Scalar::LossFractionSupport => "P_l at supports",
            Scalar::LossIntervalCount => "loss intervals",
            Scalar::FirstLossPosition => "first loss x/L",
            Scalar::ForceMean => "force mean λ",
            Scalar::ForceStd => "force std",
            Scalar::ForceMin => "force min",
            Scalar::ForceMax => "force max",
            Scalar::FilteredForceStd => "0–20 Hz force std",
            Scalar::FilteredForceMin => "0–20 Hz force min",
            Scalar::FilteredForceMax => "0–20 Hz force max",
            Scalar::MaxPenetration => "max penetration",
            Scalar::FinalW => "final w",
        }
    }

    /// Unit: `N`, `m`, `x/L` or `-`.
    pub const fn unit(self) -> &'static str {
        match self {
            Scalar::ForceMean
            | Scalar::ForceStd
            | Scalar::ForceMin
            | Scalar::ForceMax
            | Scalar::FilteredForceStd
            | Scalar::FilteredForceMin
            | Scalar::FilteredForceMax => "N",
            Scalar::MaxPenetration | Scalar::FinalW => "m",
            Scalar::FirstLossPosition => "x/L",
            _ => "-",
        }
    }

    /// The scalar called `name`.
    pub fn from_name(name: &str) -> Option<Scalar> {
        Scalar::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Its value for `carrier` of `out` (module docs for `None`).
    pub fn of(self, out: &RunOutput, carrier: usize) -> Option<f64> {
        values(out, carrier, &[self]).pop().flatten()
    }

    fn filtered(self) -> bool {
        matches!(
            self,
            Scalar::FilteredForceStd | Scalar::FilteredForceMin | Scalar::FilteredForceMax
        )
    }

    fn read(self, out: &RunOutput, s: &ContactStats, w: &[f64], f: &[f64; 3]) -> Option<f64> {
        Some(match self {
            Scalar::Steps => out.steps as f64,
            Scalar::Dofs => out.dofs as f64,
            Scalar::ContactSwitches => s.contact_switches as f64,
            Scalar::LossFraction => s.loss_fraction,
            Scalar::LossFractionSpan => s.loss_fraction_span,
            Scalar::LossFractionSupport => s.loss_fraction_support,
            Scalar::LossIntervalCount => s.loss_interval_count as f64,
            Scalar::FirstLossPosition => return s.first_loss_position,
            Scalar::ForceMean => s.force.mean,
            Scalar::ForceStd => s.force.std,
            Scalar::ForceMin => s.force.min,
            Scalar::ForceMax => s.force.max,
            Scalar::FilteredForceStd => f[0],
            Scalar::FilteredForceMin => f[1],
            Scalar::FilteredForceMax => f[2],
            Scalar::MaxPenetration => s.max_penetration,
            Scalar::FinalW => return w.last().copied(),
        })
    }
}

/// The values of `which` for `carrier` of `out`, in that order; all `None`
/// when the run has no such carrier. The 0–20 Hz force is filtered once,
/// only when asked for.
pub fn values(out: &RunOutput, carrier: usize, which: &[Scalar]) -> Vec<Option<f64>> {
    let (Some(s), Some(tr)) = (out.stats.get(carrier), out.history.carriers.get(carrier)) else {
        return vec![None; which.len()];
    };
    let f = if which.iter().any(|q| q.filtered()) {
        filtered_stats(out, carrier)
    } else {
        [f64::NAN; 3]
    };
    which.iter().map(|q| q.read(out, s, &tr.w, &f)).collect()
}

/// [std, min, max] of the 0–20 Hz force over the steps (rows 1 …), N.
fn filtered_stats(out: &RunOutput, carrier: usize) -> [f64; 3] {
    let f = lowpass_zero_phase(&out.history.carriers[carrier].force, out.dt, FORCE_BAND_HZ);
    let f = if f.len() > 1 { &f[1..] } else { &f[..] };
    let m = f.len().max(1) as f64;
    let mean = f.iter().sum::<f64>() / m;
    let std = (f.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / m).sqrt();
    let min = f.iter().copied().fold(f64::INFINITY, f64::min);
    let max = f.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    [std, min, max]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for s in Scalar::ALL {
            assert_eq!(Scalar::from_name(s.name()), Some(s));
        }
        assert_eq!(Scalar::from_name("final_probe"), None);
    }

    #[test]
    fn a_contact_never_lost_has_no_first_loss() {
        let mut out = crate::run::RunOutput {
            history: Default::default(),
            stats: vec![ContactStats::from_trace(
                &[0.0],
                &Default::default(),
                crate::record::LossGeometry::span_only(1.0),
            )],
            droppers: vec![],
            spans: vec![],
            dofs: 1,
            steps: 1,
            dt: 1.0,
            wall_seconds: 0.0,
            warnings: vec![],
            force_lag: 0.0,
        };
        out.history.carriers.push(Default::default());
        assert_eq!(Scalar::FirstLossPosition.of(&out, 0), None);
        assert_eq!(Scalar::Steps.of(&out, 0), Some(1.0));
        assert_eq!(Scalar::Steps.of(&out, 1), None);
    }
}
