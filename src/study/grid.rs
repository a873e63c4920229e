//! Time grids and ladders shared by the studies (`converge`,
//! `precision`): the one check that a coarse run's times are a
//! fine run's and the one resampling of a fine history onto the coarse
//! grid (observed orders and error estimates: [`super::uncertainty`]).

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

#[cfg(test)]
mod tests {
    use super::*;

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
