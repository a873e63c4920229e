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

use crate::record::ContactStats;
use crate::record::filter::{lowpass_zero_phase, stats_of_filtered};
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
    /// Mean of the filtered force (0–20 Hz unless `[analysis] band`).
    FilteredForceMean,
    /// Standard deviation of the filtered force (over the steps).
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
    pub const ALL: [Scalar; 18] = [
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
        Scalar::FilteredForceMean,
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
            Scalar::FilteredForceMean => "filtered_force_mean",
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
            Scalar::FilteredForceMean => "0–20 Hz force mean",
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
            | Scalar::FilteredForceMean
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
            Scalar::FilteredForceMean
                | Scalar::FilteredForceStd
                | Scalar::FilteredForceMin
                | Scalar::FilteredForceMax
        )
    }

    fn read(self, out: &RunOutput, s: &ContactStats, w: &[f64], f: &[f64; 4]) -> Option<f64> {
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
            Scalar::FilteredForceMean => f[0],
            Scalar::FilteredForceStd => f[1],
            Scalar::FilteredForceMin => f[2],
            Scalar::FilteredForceMax => f[3],
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
        [f64::NAN; 4]
    };
    which.iter().map(|q| q.read(out, s, &tr.w, &f)).collect()
}

/// [mean, std, min, max] of the filtered force over the steps (rows 1 …),
/// N: the history's `force_filtered`, or, when the history does not hold
/// it (every K-th step kept), its rows filtered at the run's Δt.
fn filtered_stats(out: &RunOutput, carrier: usize) -> [f64; 4] {
    let tr = &out.history.carriers[carrier];
    let band = out.history.band_hz();
    let s = if tr.force_filtered.is_empty() {
        stats_of_filtered(&lowpass_zero_phase(&tr.force, out.dt, band), band)
    } else {
        stats_of_filtered(&tr.force_filtered, band)
    };
    [s.mean, s.std, s.min, s.max]
}

/// The filtered force's mean, σ, max and min of one run's carrier 0 (N;
/// NaN for a run that stopped): the four columns every study table carries
/// ([`FILTERED_COLUMNS`], docs/output.md#filtered-force).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FilteredColumns {
    /// Mean, N.
    #[serde(with = "super::sweep::nan_as_null", default = "nan")]
    pub filtered_force_mean: f64,
    /// Population standard deviation, N.
    #[serde(with = "super::sweep::nan_as_null", default = "nan")]
    pub filtered_force_std: f64,
    /// Maximum, N.
    #[serde(with = "super::sweep::nan_as_null", default = "nan")]
    pub filtered_force_max: f64,
    /// Minimum, N.
    #[serde(with = "super::sweep::nan_as_null", default = "nan")]
    pub filtered_force_min: f64,
}

fn nan() -> f64 {
    f64::NAN
}

/// The names of [`FilteredColumns`], in table order.
pub const FILTERED_COLUMNS: [&str; 4] = [
    "filtered_force_mean",
    "filtered_force_std",
    "filtered_force_max",
    "filtered_force_min",
];

impl FilteredColumns {
    /// All NaN: a run that stopped, or a record of a taut before them.
    pub const NONE: FilteredColumns = FilteredColumns {
        filtered_force_mean: f64::NAN,
        filtered_force_std: f64::NAN,
        filtered_force_max: f64::NAN,
        filtered_force_min: f64::NAN,
    };

    /// Carrier `carrier`'s, of `out`.
    pub fn of(out: &RunOutput, carrier: usize) -> Self {
        if out.history.carriers.get(carrier).is_none() {
            return Self::NONE;
        }
        let [mean, std, min, max] = filtered_stats(out, carrier);
        FilteredColumns {
            filtered_force_mean: mean,
            filtered_force_std: std,
            filtered_force_max: max,
            filtered_force_min: min,
        }
    }

    /// The four values in [`FILTERED_COLUMNS`] order.
    pub fn values(&self) -> [f64; 4] {
        [
            self.filtered_force_mean,
            self.filtered_force_std,
            self.filtered_force_max,
            self.filtered_force_min,
        ]
    }
}

impl Default for FilteredColumns {
    fn default() -> Self {
        Self::NONE
    }
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
            standard: vec![],
            dofs: 1,
            steps: 1,
            dt: 1.0,
            wall_seconds: 0.0,
            warnings: vec![],
            force_lag: 0.0,
            form: None,
        };
        out.history.carriers.push(Default::default());
        assert_eq!(Scalar::FirstLossPosition.of(&out, 0), None);
        assert_eq!(Scalar::Steps.of(&out, 0), Some(1.0));
        assert_eq!(Scalar::Steps.of(&out, 1), None);
    }
}
