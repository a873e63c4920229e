//! `force_map.svg`: the mean contact force over (x_m/L, parameter) of a
//! 1-D sweep.

use std::path::Path;

use super::axes::axis_label;
use super::colour::{Paint, Ramp};
use super::heat_map::{Map, draw_map};
use super::records::{failed_note, one_d_axes, profile_rows, sorted_by_index};
use crate::error::Result;
use crate::study::sweep::{PROFILE_BINS, SweepRecord, SweepSpec};
/// The force colour scale ends at this quantile of the cell values, so the
/// re-contact spikes near the supports (no impact law: TARGETS; bin means
/// of 10⁴ N and more where the level is 50 N) do not wash out the map; larger
/// cells take the top colour and the bar says so.
pub(super) const FORCE_CLIP_QUANTILE: f64 = 0.98;

/// The mean contact force over (x_m/L, parameter) of a 1-D sweep, with a
/// colour bar (the study's Figs 8–11, upper panels). `title` replaces the
/// default title when given.
pub fn write_force_map(
    path: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
    title: Option<&str>,
) -> Result<()> {
    let (x_edges, y_edges) = one_d_axes(spec, records)?;
    let records = sorted_by_index(records);
    let cells = profile_rows(&records, |r| &r.force_profile);
    let mut all: Vec<f64> = cells.iter().flatten().flatten().copied().collect();
    all.sort_by(f64::total_cmp);
    let (lo, max) = (
        all.first().copied().unwrap_or(0.0),
        all.last().copied().unwrap_or(1.0),
    );
    let q = all
        .get(((all.len().max(1) - 1) as f64 * FORCE_CLIP_QUANTILE).round() as usize)
        .copied()
        .unwrap_or(max);
    // clip only when the tail is a few spikes, not the bulk
    let hi = if max > 1.05 * q && q > lo { q } else { max };
    let key = &spec.axes[0].key;
    let map = Map {
        title: title.map_or_else(
            || format!("mean contact force over (x_m/L, {key})"),
            str::to_string,
        ),
        x_desc: "carrier position x_m / L".into(),
        y_desc: axis_label(key),
        x_edges,
        y_edges,
        x_log: false,
        y_log: spec.axes[0].log,
        cells,
        paint: Paint::Scale {
            ramp: Ramp::Viridis,
            lo,
            hi,
            zero_white: false,
            log: false,
            bar_label: "mean contact force λ in the bin (N)".into(),
            clipped_max: (hi < max).then_some(max),
        },
        overlays: vec![],
        labels: vec![],
        footer: format!(
            "{PROFILE_BINS} bins in x_m/L × {} values of {key}; each cell: mean λ over the steps with x_m in the bin{}",
            spec.axes[0].count,
            failed_note(&records)
        ),
    };
    draw_map(path, &map)
}
