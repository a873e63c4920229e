//! SVG maps of a sweep (`taut sweep` / `taut merge`; the study's Figs 8–12).
//!
//! * 1-D sweep: `sweep.svg`, P_l and the filtered force against the axis
//!   as line charts (error bars from an uncertainty column), `force_map.svg`, the mean contact force over
//!   (x_m/L, parameter) as a heat map with a colour bar (the upper panels of
//!   the study's Figs 8–11), and `loss_map.svg`, contact loss in black and
//!   white over the same axes (black where some step in the x_m/L bin had
//!   the contact open; the lower panels).
//! * 2-D sweep: `loss_fraction_map.svg`, P_l over the grid as a heat map
//!   (white where P_l = 0) with iso-lines of V0/c drawn by marching squares
//!   from each run's `speed_ratio` (the study's Fig. 12 and its band borders
//!   at V0/c ≈ 0.64 and 0.96, TARGETS T7).
//!
//! Each cell is drawn over its own extent: bin edges in x_m/L, midpoints
//! between grid values (geometric ones on a `--log` axis) in a parameter.
//! A cell with no value (a run that stopped with an error, a bin no step fell
//! in) is light grey. A shard holds only part of the grid, so it draws no
//! maps; `taut merge` draws them for the whole.
//!
//! One concept a file: [`axes`] (axis labels, ticks, cell edges),
//! [`colour`] (colour ramps and how values become colours), [`heat_map`]
//! (a map of cells with overlays, drawn to SVG), [`colour_bar`], [`contour`]
//! (marching squares), [`records`] (a sweep's records as map rows), and one
//! file per figure.

mod axes;
mod colour;
mod colour_bar;
mod contour;
mod force_map;
mod heat_map;
mod line_chart;
mod loss_fraction_map;
mod loss_map;
mod records;
mod refinement_map;
mod refinement_plot;
mod span_map;
mod tolerance_map;

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::study::sweep::{SweepRecord, SweepSpec};

pub use force_map::write_force_map;
pub use line_chart::write_sweep_chart;
pub use loss_fraction_map::{SPEED_RATIO_LEVELS, write_loss_fraction_map};
pub use loss_map::write_loss_map;
pub use refinement_map::write_refinement_map;
pub use refinement_plot::write_refinement_plot;
use span_map::write_loss_fraction_span_map;
pub(crate) use tolerance_map::{write_tolerance_plot, write_u_num_map, write_value_map_hatched};
/// Draw the maps of a finished sweep into `dir` (none for a shard, which
/// holds only part of the grid, for a list of points, and for an axis
/// whose listed values are not in increasing or decreasing order). Returns the files written.
pub(crate) fn write_sweep_maps(
    dir: &Path,
    spec: &SweepSpec,
    records: &[SweepRecord],
) -> Result<Vec<PathBuf>> {
    // a list of points has no grid, and a list out of order no cells
    if records.len() != spec.len() || spec.paired || !spec.axes.iter().all(|a| a.monotone()) {
        return Ok(vec![]);
    }
    match spec.axes.len() {
        1 => {
            let (f, l) = (dir.join("force_map.svg"), dir.join("loss_map.svg"));
            write_force_map(&f, spec, records, None)?;
            write_loss_map(&l, spec, records, None)?;
            let c = dir.join("sweep.svg");
            write_sweep_chart(
                &c,
                &spec.axes[0].key,
                &crate::report::sweep_table(spec, records),
            )?;
            let mut maps = vec![c, f, l];
            if spec.tolerance.is_some() {
                let t = dir.join("tolerance.svg");
                write_tolerance_plot(&t, spec, records)?;
                maps.push(t);
            }
            if spec.check_refinement {
                let r = dir.join("refinement.svg");
                write_refinement_plot(&r, spec, records)?;
                maps.push(r);
            }
            Ok(maps)
        }
        2 => {
            let p = dir.join("loss_fraction_map.svg");
            write_loss_fraction_map(&p, spec, records, None, &SPEED_RATIO_LEVELS)?;
            // the in-span part, the one to quote (docs/contact_loss.md)
            let s = dir.join("loss_fraction_span_map.svg");
            write_loss_fraction_span_map(&s, spec, records)?;
            let mut maps = vec![p, s];
            if spec.tolerance.is_some() {
                let u = dir.join("u_num_map.svg");
                write_u_num_map(&u, spec, records)?;
                maps.push(u);
            }
            if spec.check_refinement {
                let r = dir.join("refinement_map.svg");
                write_refinement_map(&r, spec, records)?;
                maps.push(r);
            }
            Ok(maps)
        }
        _ => Ok(vec![]),
    }
}
