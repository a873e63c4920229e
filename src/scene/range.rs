//! A value's own range check, the one message every scene key's check
//! gives: the field, the value with its unit, the allowed range.

use crate::error::{Error, Result};

pub(crate) fn positive(field: &str, v: f64, unit: &str) -> Result<f64> {
    if !v.is_finite() {
        Err(Error::invalid(
            field,
            v,
            format!("must be a finite number > 0 ({unit})"),
        ))
    } else if v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, format!("must be > 0 ({unit})")))
    }
}

pub(crate) fn non_negative(field: &str, v: f64, unit: &str) -> Result<f64> {
    if !v.is_finite() {
        Err(Error::invalid(
            field,
            v,
            format!("must be a finite number ≥ 0 ({unit})"),
        ))
    } else if v >= 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, format!("must be ≥ 0 ({unit})")))
    }
}
