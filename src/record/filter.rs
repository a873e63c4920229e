//! The filtered contact force's statistics (the filter itself is the
//! numerics' `crate::numeric::filter`, re-exported here).

pub use crate::numeric::filter::*;

use super::FilteredForce;

/// The statistics of a filtered force history `f` (row 0 the initial
/// state, filtered to 0–`band_hz` Hz): its mean, population standard
/// deviation, max and min over the steps (rows 1 …, as the raw force
/// statistics and P_l, MODEL §5), and the statistical max and min
/// mean ± 3σ (EN 50367's F_m ± 3σ). λ = 0 where contact is lost entered
/// the filter like any other sample.
pub(crate) fn stats_of_filtered(f: &[f64], band_hz: f64) -> FilteredForce {
    let f = if f.len() > 1 { &f[1..] } else { f };
    let (mean, std) = mean_std(f);
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
