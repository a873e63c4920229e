//! `loss_fraction_span_map.svg`: P_l in span (outside the support zones)
//! over a 2-D sweep's grid, the part to quote (docs/contact_loss.md).

use std::path::Path;

use super::loss_fraction_map::{SPEED_RATIO_LEVELS, write_loss_fraction_map};
use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};

/// The in-span P_l of a 2-D sweep as a heat map with the V0/c iso-lines.
pub(super) fn write_loss_fraction_span_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<()> {
    let span: Vec<SweepRecord> = records
        .iter()
        .map(|r| r.with_loss_fraction(r.loss_fraction_span()))
        .collect();
    let title = "P_l in span (outside the support zones)";
    match &spec.tolerance {
        Some(t) if t.quantity == "loss_fraction_span" => super::write_value_map_hatched(
            path,
            spec,
            &span,
            &format!("{title}; crossed out: u_num above {:e}", t.tolerance),
        ),
        _ => write_loss_fraction_map(path, spec, &span, Some(title), &SPEED_RATIO_LEVELS),
    }
}
