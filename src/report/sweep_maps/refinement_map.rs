//! `refinement_map.svg`: the change of the in-span P_l of a 2-D sweep
//! under one refinement (`--check-refinement`).

use std::path::Path;

use super::loss_fraction_map::{SPEED_RATIO_LEVELS, write_loss_fraction_map};
use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};
/// `--check-refinement` on a 2-D sweep: the change of the in-span P_l under
/// one refinement (N × 2, Δt / 2) as a heat map, so a reader sees where the
/// loss map is converged (title: the criterion) and where it is not.
pub fn write_refinement_map(path: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    use crate::study::sweep::{REFINEMENT_ABS, REFINEMENT_REL, refinement_converged};
    let changes: Vec<SweepRecord> = records
        .iter()
        .map(|r| {
            let d = r.refined.as_ref().map_or(f64::NAN, |f| {
                (f.loss_fraction_span - r.loss_fraction_span()).abs()
            });
            r.with_loss_fraction(d)
        })
        .collect();
    let converged = records
        .iter()
        .filter(|r| {
            r.refined.as_ref().is_some_and(|f| {
                refinement_converged(r.loss_fraction_span(), f.loss_fraction_span) == Some(true)
            })
        })
        .count();
    let title = format!(
        "|ΔP_l in span| under refinement (N×2, Δt/2): {converged} of {} points converged (≤ {:.0} % or {REFINEMENT_ABS:e})",
        records.len(),
        100.0 * REFINEMENT_REL
    );
    write_loss_fraction_map(path, spec, &changes, Some(&title), &SPEED_RATIO_LEVELS)
}
