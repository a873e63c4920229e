//! The filtered contact force's statistics (the filter itself is the
//! numerics' `crate::numeric::filter`, re-exported here).

pub use crate::numeric::filter::*;

use super::FilteredForce;

/// The statistics of a filtered force history `f` at rows of times `t`
/// (row 0 the initial state, filtered to 0–`band_hz` Hz): its time mean and
/// population standard deviation over the window [0, `t_end`]
/// (`super::window`, as the raw force's), its max and min over the steps
/// (rows 1 …), and the statistical max and min mean ± 3σ (EN 50367's
/// F_m ± 3σ). λ = 0 where contact is lost entered the filter like any
/// other sample.
pub(crate) fn stats_of_filtered(t: &[f64], f: &[f64], t_end: f64, band_hz: f64) -> FilteredForce {
    let (mean, std) = super::window::time_mean_std(t, f, t_end);
    let f = if f.len() > 1 { &f[1..] } else { f };
    FilteredForce {
        cutoff_hz: band_hz,
        mean,
        std,
        max: f.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        min: f.iter().copied().fold(f64::INFINITY, f64::min),
        statistical_max: mean + STATISTICAL_SIGMAS * std,
        statistical_min: mean - STATISTICAL_SIGMAS * std,
    }
}
