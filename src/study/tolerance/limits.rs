//! The tolerance itself: its allowed range and how `--tolerance` is read.

use super::error_model::ROUND_OFF;
use crate::error::{Error, Result};
/// The smallest tolerance: [`ROUND_OFF`]. The pilots' differences are
/// relative (absolute for P_l, itself at most 1), and differences below
/// [`ROUND_OFF`] are counted as round-off, so a smaller tolerance could not
/// be told from round-off; it would also ask for a resolution beyond
/// [`MAX_DOF_STEPS`] (or one that underflows) on any scene that is not exact.
pub(crate) const MIN_TOLERANCE: f64 = ROUND_OFF;

/// The allowed tolerances: a relative error (absolute for P_l) in
/// [[`MIN_TOLERANCE`], 1].
pub(crate) const TOLERANCE_RANGE: &str = "must be a number in [1e-12, 1]: a relative error (absolute for loss_fraction), e.g. 1e-3; below 1e-12 differences are round-off";

/// Read `--tolerance`: a finite number in [[`MIN_TOLERANCE`], 1].
pub(crate) fn parse_tolerance(s: &str) -> Result<f64> {
    let bad = || Error::invalid("--tolerance", s, TOLERANCE_RANGE);
    let v: f64 = s.trim().parse().map_err(|_| bad())?;
    check_tolerance(v).map_err(|_| bad())
}

pub(super) fn check_tolerance(v: f64) -> Result<f64> {
    if v.is_finite() && (MIN_TOLERANCE..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(Error::invalid("--tolerance", v, TOLERANCE_RANGE))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn tolerances_outside_zero_to_one_are_refused() {
        for ok in ["1e-3", "1", " 0.5 "] {
            assert!(parse_tolerance(ok).is_ok(), "{ok}");
        }
        assert!(parse_tolerance("1e-12").is_ok());
        for bad in [
            "0", "-1e-3", "1.0001", "NaN", "inf", "", "abc", "1e-200", "9e-13", "1e300",
        ] {
            let e = parse_tolerance(bad).unwrap_err().to_string();
            assert!(
                e.contains("`--tolerance`") && e.contains("[1e-12, 1]"),
                "{e}"
            );
        }
    }
}
