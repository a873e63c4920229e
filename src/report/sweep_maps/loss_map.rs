//! `loss_map.svg`: contact loss over (x_m/L, parameter) of a 1-D sweep in
//! black and white.

use std::path::Path;

use super::axes::axis_label;
use super::colour::Paint;
use super::heat_map::{Map, draw_map};
use super::records::{failed_note, one_d_axes, profile_rows, sorted_by_index};
use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};
/// Contact loss over (x_m/L, parameter) of a 1-D sweep in black and white:
/// black where some step in the bin had the contact open (the study's
/// Figs 8–11, lower panels).
pub fn write_loss_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
) -> Result<()> {
    let (x_edges, y_edges) = one_d_axes(spec, records)?;
    let records = sorted_by_index(records);
    let cells = profile_rows(&records, |r| &r.loss_profile);
    let key = &spec.axes[0].key;
    let lost_runs = records.iter().filter(|r| r.loss_fraction() > 0.0).count();
    let map = Map {
        title: title.map_or_else(
            || format!("contact loss over (x_m/L, {key})"),
            str::to_string,
        ),
        x_desc: "carrier position x_m / L".into(),
        y_desc: axis_label(key),
        x_edges,
        y_edges,
        x_log: false,
        y_log: spec.axes[0].log,
        cells,
        paint: Paint::BlackWhite,
        overlays: vec![],
        labels: vec![],
        footer: format!(
            "black: contact lost in the bin (some step with λ = 0, gap open); white: kept; {lost_runs} of {} runs lose contact{}",
            records.len(),
            failed_note(&records)
        ),
    };
    draw_map(path, &map)
}
