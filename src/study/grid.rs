//! Time grids and ladders shared by the studies (`converge`, `precision`,
//! `run --tolerance`): the one check that a coarse run's times are a
//! fine run's, the one resampling of a fine history onto the coarse grid,
//! and the one observed order from successive differences.

use std::ops::{Range, RangeInclusive};

use crate::error::{Error, Result};

/// Two steps are commensurate when m·Δt_f differs from Δt_c by less than
/// this fraction of Δt_c (both are decimal inputs or i·Δt computed in
/// floating point).
pub(crate) const SAME_TIME: f64 = 1e-6;

/// How far the fine run of [`nest`] must reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Reach {
    /// Exactly the coarse run's end: N_f = m·N_c (the levels of one study).
    SameEnd,
    /// At least the coarse run's end: N_f ≥ m·N_c (a run compared on
    /// another's grid, e.g. a finer run of a `carrier_leaves` scene, which
    /// stops at the last whole step before the carrier leaves).
    AtLeast,
}

/// The stride m of a fine run's time grid in a coarse one's (coarse row k
/// is fine row k·m), given each as (steps, Δt): Δt_c must be a whole
/// multiple m ≥ 1 of Δt_f and the fine run must reach the coarse end
/// ([`Reach`]). Otherwise the error names `time.end`, the one choice that
/// makes every level's times nest.
pub(crate) fn nest(coarse: (usize, f64), fine: (usize, f64), reach: Reach) -> Result<usize> {
    let ((nc, dtc), (nf, dtf)) = (coarse, fine);
    let m = (dtc / dtf).round() as usize;
    let whole = m >= 1 && ((m as f64 * dtf) - dtc).abs() <= SAME_TIME * dtc;
    let reaches = match reach {
        Reach::SameEnd => nf == nc * m,
        Reach::AtLeast => nf >= nc * m,
    };
    if whole && reaches {
        return Ok(m);
    }
    Err(Error::invalid(
        "time.end",
        format!("{nf} steps at Δt = {dtf:e} s against {nc} steps at Δt = {dtc:e} s"),
        format!(
            "must be a whole number of coarsest steps at every level, so the runs' times nest ({}): choose an end time that is a multiple of the coarsest step",
            if whole {
                format!("{nc} × {m} steps")
            } else {
                "the coarse Δt must be a whole multiple of the fine one".to_string()
            }
        ),
    ))
}

/// A fine history on a coarse grid: the fine row k·`stride` for every
/// coarse row k in `rows` (`0..n` with the initial row, `1..n` without).
pub fn resample(fine: &[f64], stride: usize, rows: Range<usize>) -> Vec<f64> {
    rows.map(|k| fine[k * stride]).collect()
}

/// `value` of option `key` if within `range`, else the error naming the
/// option, the value and the range (a study's `--levels`).
pub(crate) fn in_range(key: &str, value: usize, range: &RangeInclusive<usize>) -> Result<usize> {
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(Error::invalid(
            key,
            value,
            format!("must be in {} ..= {}", range.start(), range.end()),
        ))
    }
}

/// Roache's safety factor for a three-grid study (the grid convergence
/// index, GCI).
pub(crate) const GCI_SAFETY_FACTOR: f64 = 1.25;

/// Observed order p = ln(e_c/e_f)/ln r from two successive differences
/// (coarse, fine) of a ladder refined by r; NaN unless both are > 0 (a
/// zero, negative or NaN difference has no order).
pub fn observed_order(e_coarse: f64, e_fine: f64, r: f64) -> f64 {
    if e_coarse > 0.0 && e_fine > 0.0 {
        (e_coarse / e_fine).ln() / r.ln()
    } else {
        f64::NAN
    }
}

/// The observed order over a whole ladder refined by `r` at each level:
/// the least-squares slope of ln(error) against the level, over ln r (the
/// two-level [`observed_order`] for two errors). For a ladder whose single
/// halvings scatter (impacts that fall at different places within the
/// steps); NaN unless every error is > 0 and there are at least two.
pub fn fitted_order(errors: &[f64], r: f64) -> f64 {
    if errors.len() < 2 || !errors.iter().all(|e| *e > 0.0) {
        return f64::NAN;
    }
    let n = errors.len() as f64;
    let xm = (n - 1.0) / 2.0;
    let ym = errors.iter().map(|e| e.ln()).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, e) in errors.iter().enumerate() {
        let x = i as f64 - xm;
        sxy += x * (e.ln() - ym);
        sxx += x * x;
    }
    -sxy / sxx / r.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_of_a_second_order_sequence() {
        // u_ℓ = 1 + C h_ℓ², h halves: differences fall by 4
        assert!((observed_order(0.3, 0.075, 2.0) - 2.0).abs() < 1e-12);
        assert!(observed_order(0.0, 1.0, 2.0).is_nan());
        assert!(observed_order(1.0, 0.0, 2.0).is_nan());
        assert!(observed_order(f64::NAN, 1.0, 2.0).is_nan());
        // a fit through an exact sequence is its order; two errors give
        // the two-level order
        let e: Vec<f64> = (0..5).map(|l| 3.0 * 0.5f64.powi(3 * l)).collect();
        assert!((fitted_order(&e, 2.0) - 3.0).abs() < 1e-12);
        assert!((fitted_order(&[0.3, 0.075], 2.0) - 2.0).abs() < 1e-12);
        assert!(fitted_order(&[0.3], 2.0).is_nan());
        assert!(fitted_order(&[0.3, 0.0], 2.0).is_nan());
    }

    #[test]
    fn grids_nest_or_name_the_end() {
        assert_eq!(nest((10, 4e-4), (40, 1e-4), Reach::SameEnd).unwrap(), 4);
        assert_eq!(nest((10, 1e-4), (10, 1e-4), Reach::SameEnd).unwrap(), 1);
        assert_eq!(nest((10, 4e-4), (41, 1e-4), Reach::AtLeast).unwrap(), 4);
        for (fine, reach) in [
            ((41, 1e-4), Reach::SameEnd),
            ((39, 1e-4), Reach::AtLeast),
            ((30, 1.3e-4), Reach::AtLeast),
        ] {
            let e = nest((10, 4e-4), fine, reach).unwrap_err().to_string();
            assert!(e.contains("`time.end`"), "{e}");
        }
    }

    #[test]
    fn resampling_takes_every_stride_th_row() {
        let fine: Vec<f64> = (0..9).map(|i| i as f64).collect();
        assert_eq!(resample(&fine, 4, 0..3), [0.0, 4.0, 8.0]);
        assert_eq!(resample(&fine, 2, 1..5), [2.0, 4.0, 6.0, 8.0]);
    }
}
