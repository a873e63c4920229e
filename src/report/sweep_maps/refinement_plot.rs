//! `refinement.svg`: the in-span P_l of a 1-D sweep at its resolution and
//! refined (`--check-refinement`).

use std::path::Path;

use super::axes::axis_label;
use super::records::{own_span, sorted_by_index};
use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};
/// `--check-refinement` on a 1-D sweep: the in-span P_l at the sweep's
/// resolution and refined (N × 2, Δt / 2) along the axis, the axis shaded
/// where the two differ by more than the convergence criterion.
pub fn write_refinement_plot(path: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    use crate::report::plot::{Series, line_plot};
    use crate::study::sweep::{REFINEMENT_ABS, REFINEMENT_REL, refinement_converged};
    let records = sorted_by_index(records);
    let x: Vec<f64> = records.iter().map(|r| r.values[0]).collect();
    // each point owns the axis up to halfway to its neighbours
    let half = |i: usize| own_span(&x, i);
    let unconverged: Vec<[f64; 2]> = records
        .iter()
        .enumerate()
        .filter(|(_, r)| {
            r.refined.as_ref().is_none_or(|f| {
                refinement_converged(r.loss_fraction_span(), f.loss_fraction_span) != Some(true)
            })
        })
        .map(|(i, _)| half(i))
        .collect();
    let base: Vec<(f64, f64)> = records
        .iter()
        .map(|r| (r.values[0], r.loss_fraction_span()))
        .filter(|p| p.1.is_finite())
        .collect();
    let refined: Vec<(f64, f64)> = records
        .iter()
        .filter_map(|r| Some((r.values[0], r.refined.as_ref()?.loss_fraction_span)))
        .filter(|p| p.1.is_finite())
        .collect();
    let title = format!(
        "P_l in span under refinement (N×2, Δt/2): {} of {} points converged (≤ {:.0} % or {REFINEMENT_ABS:e})",
        records.len() - unconverged.len(),
        records.len(),
        100.0 * REFINEMENT_REL
    );
    let series = [
        Series {
            label: "at the sweep's N, Δt".into(),
            points: base,
            shaded: unconverged,
            filtered: vec![],
        },
        Series {
            label: "refined: 2N, Δt/2".into(),
            points: refined,
            shaded: vec![],
            filtered: vec![],
        },
    ];
    line_plot(
        path,
        &title,
        (&axis_label(&spec.axes[0].key), "P_l in span (–)"),
        &series,
        "not converged (shaded)",
    )
}
