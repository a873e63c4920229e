//! The maps of an accuracy-targeted sweep (`--tolerance`): u_num of the
//! targeted quantity over a 2-D grid, and a 1-D sweep's value ± u_num.

use std::path::Path;

use super::axes::axis_label;
use super::loss_fraction_map::{SPEED_RATIO_LEVELS, write_map_hatched};
use super::records::{own_span, sorted_by_index};
use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};

/// `u_num_map.svg`: each point's u_num of the targeted quantity as a heat
/// map, the points above EPS crossed out (the title counts them).
pub(crate) fn write_u_num_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<()> {
    let tol = spec.tolerance.as_ref().expect("an accuracy-targeted sweep");
    let u: Vec<SweepRecord> = records
        .iter()
        .map(|r| r.with_loss_fraction(r.accuracy.as_ref().map_or(f64::NAN, |a| a.u_num)))
        .collect();
    let met = records
        .iter()
        .filter(|r| r.accuracy.as_ref().is_some_and(|a| a.met))
        .count();
    let title = format!(
        "u_num of {} (tolerance {:e}): {met} of {} points within it (crossed out: above)",
        tol.quantity,
        tol.tolerance,
        records.len()
    );
    let bar = format!("u_num of {} (its unit)", tol.quantity);
    write_map_hatched(
        path,
        spec,
        &u,
        Some(&title),
        &SPEED_RATIO_LEVELS,
        true,
        Some(&bar),
    )
}

/// The value map of the targeted quantity with the points above EPS
/// crossed out (`--tolerance` on `loss_fraction` or `loss_fraction_span`).
pub(crate) fn write_value_map_hatched(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: &str,
) -> Result<()> {
    write_map_hatched(
        path,
        spec,
        records,
        Some(title),
        &SPEED_RATIO_LEVELS,
        true,
        None,
    )
}

/// `tolerance.svg` of a 1-D accuracy-targeted sweep: the targeted
/// quantity ± u_num along the axis, shaded where u_num is above EPS.
pub(crate) fn write_tolerance_plot(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<()> {
    use crate::report::plot::{Series, line_plot};
    let tol = spec.tolerance.as_ref().expect("an accuracy-targeted sweep");
    let records = sorted_by_index(records);
    let x: Vec<f64> = records.iter().map(|r| r.values[0]).collect();
    let half = |i: usize| own_span(&x, i);
    let acc = |r: &SweepRecord| r.accuracy.clone();
    let unmet: Vec<[f64; 2]> = records
        .iter()
        .enumerate()
        .filter(|(_, r)| acc(r).is_none_or(|a| !a.met))
        .map(|(i, _)| half(i))
        .collect();
    let band = |sign: f64| -> Vec<(f64, f64)> {
        records
            .iter()
            .filter_map(|r| {
                let a = acc(r)?;
                Some((r.values[0], a.value + sign * a.u_num))
            })
            .filter(|p| p.1.is_finite())
            .collect()
    };
    let value: Vec<(f64, f64)> = records
        .iter()
        .filter_map(|r| Some((r.values[0], acc(r)?.value)))
        .filter(|p| p.1.is_finite())
        .collect();
    let title = format!(
        "{} ± u_num (tolerance {:e}): {} of {} points within it",
        tol.quantity,
        tol.tolerance,
        records.len() - unmet.len(),
        records.len()
    );
    let series = [
        Series {
            label: tol.quantity.clone(),
            points: value,
            shaded: unmet,
            filtered: vec![],
        },
        Series {
            label: "+ u_num".into(),
            points: band(1.0),
            shaded: vec![],
            filtered: vec![],
        },
        Series {
            label: "− u_num".into(),
            points: band(-1.0),
            shaded: vec![],
            filtered: vec![],
        },
    ];
    line_plot(
        path,
        &title,
        (&axis_label(&spec.axes[0].key), &tol.quantity),
        &series,
        "u_num above the tolerance (shaded)",
    )
}
