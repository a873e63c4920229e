//! A sweep's records as map rows: profiles in axis order, the 1-D map's
//! cell edges, and the note on runs that stopped with an error.

use super::axes::{axis_values, edges};
use crate::error::{Error, Result};
use crate::study::sweep::{PROFILE_BINS, SweepRecord, SweepSpec};
pub(super) fn failed_note(records: &[SweepRecord]) -> String {
    let failed = records.iter().filter(|r| r.error.is_some()).count();
    if failed == 0 {
        String::new()
    } else {
        format!("; {failed} run(s) stopped with an error (grey)")
    }
}

/// Rows of a 1-D sweep's profiles, one per record in axis order.
pub(super) fn profile_rows(
    records: &[SweepRecord],
    pick: fn(&SweepRecord) -> &Vec<Option<f64>>,
) -> Vec<Vec<Option<f64>>> {
    records
        .iter()
        .map(|r| {
            let p = pick(r);
            (0..PROFILE_BINS)
                .map(|b| p.get(b).copied().flatten().filter(|v| v.is_finite()))
                .collect()
        })
        .collect()
}

pub(super) fn one_d_axes(
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<(Vec<f64>, Vec<f64>)> {
    if spec.axes.len() != 1 || records.len() != spec.len() {
        return Err(Error::invalid(
            "sweep maps",
            format!("{} axes, {} records", spec.axes.len(), records.len()),
            "a 1-D map needs a one-axis sweep with every point present",
        ));
    }
    let x: Vec<f64> = (0..=PROFILE_BINS)
        .map(|b| b as f64 / PROFILE_BINS as f64)
        .collect();
    let a = &spec.axes[0];
    Ok((x, edges(&axis_values(a), a.log)))
}

pub(super) fn sorted_by_index(records: &[SweepRecord]) -> Vec<SweepRecord> {
    let mut r = records.to_vec();
    r.sort_by_key(|r| r.index);
    r
}

/// The stretch of a 1-D plot's axis that point `i` of the sorted values `x`
/// owns: half-way to each neighbour (to the end of the axis at either end).
pub(super) fn own_span(x: &[f64], i: usize) -> [f64; 2] {
    let lo = if i > 0 { 0.5 * (x[i - 1] + x[i]) } else { x[i] };
    let hi = if i + 1 < x.len() {
        0.5 * (x[i] + x[i + 1])
    } else {
        x[i]
    };
    [lo, hi]
}
