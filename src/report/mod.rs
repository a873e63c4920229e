//! Plain-file outputs of a run: `history.csv`, `summary.json`, `force.svg`
//! (formats documented in `docs/output.md`).

mod axis_range;
mod compare;
mod converge;
mod csv;
mod form;
mod gate;
mod html;
mod incomplete;
#[cfg(test)]
mod legend_check;
mod line;
mod line_svg;
mod modes;
mod outputs;
mod page;
mod plot;
mod precision;
mod staging;
mod standard;
mod style;
mod summary;
mod sweep;
mod sweep_maps;
mod table;
mod tolerance;
mod uncertainty;
mod verify;
mod wire;

pub use crate::study::lock::{FolderLock, claim_folder};
pub use compare::{
    COMPARE_COLUMNS, NO_CHATTER, chatter_note, compare_rows, compare_table, write_compare,
};
pub(crate) use converge::write_converge;
pub use converge::{converge_methods_table, converge_rows, converge_table, write_converge_methods};
pub(crate) use csv::write_history;
pub use csv::{HISTORY_ROWS_AT_A_TIME, history_table};
pub use form::{droppers_static_table, static_heights_table};
pub use gate::gate_table;
pub(crate) use gate::write_gate;
pub use html::ReportSummary;
pub(crate) use html::write_report;
pub(crate) use incomplete::{INCOMPLETE_FILE, write_whole};
pub(crate) use line::write_line;
pub use line::{envelope_table, spans_table, supports_table};
pub(crate) use modes::write_modes;
pub use modes::{mode_shapes_table, modes_table};
pub use outputs::{Declared, Outputs, Show};
pub(crate) use outputs::{check_out_dir, kept_note, replaced_note};
pub(crate) use plot::write_force_plot;
pub(crate) use precision::write_precision;
pub use precision::{precision_rows, precision_table};
pub use staging::Staged;
pub use standard::standard_table;
pub(crate) use standard::write_standard;
pub(crate) use summary::write_summary;
pub use summary::{Derived, FormSummary, Summary, mesh_label};
pub(crate) use sweep::write_merge;
pub use sweep::{sweep_table, write_sweep};
pub(crate) use sweep_maps::write_sweep_maps;
pub use sweep_maps::{
    SPEED_RATIO_LEVELS, write_force_map, write_loss_fraction_map, write_loss_map,
};
pub use table::{Column, Table};
pub(crate) use tolerance::write_tolerant_run;
pub use tolerance::{
    ACCURACY_COLUMNS, WithAccuracy, accuracy_header, accuracy_table, result_lines,
};
pub(crate) use uncertainty::write_uncertainty;
pub use uncertainty::{family_table, uncertainty_lines, uncertainty_table};
pub use verify::verify_table;
pub(crate) use verify::write_verify;
pub(crate) use wire::write_wire;

use std::path::Path;

use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::run::RunOutput;

/// Save the contact problem of a failed contact solve ([`Error::Contact`])
/// as `dir/failed_contact_step_N.json`, which `taut replay` solves again;
/// returns the file, or None for another error or a folder that cannot be
/// written (the error itself is what the caller reports).
pub fn save_failed_contact(dir: &Path, e: &Error) -> Option<std::path::PathBuf> {
    let Error::Contact { step, .. } = e else {
        return None;
    };
    let failed = e.payload::<crate::contact::ContactFailed>()?;
    let path = dir.join(format!("failed_contact_step_{step}.json"));
    // a problem JSON cannot hold (NaN, ±inf would be nulls no replay
    // reads) is saved as the reason it cannot be replayed
    let json = match crate::contact::NotReplayable::of(&failed.problem) {
        Some(why) => serde_json::to_string_pretty(&why).ok()?,
        None => serde_json::to_string_pretty(&failed.problem).ok()?,
    };
    std::fs::create_dir_all(dir).ok()?;
    std::fs::write(&path, json).ok()?;
    Some(path)
}

/// Write a run's outputs into `dir` (created if missing): `history.csv`,
/// `force.svg`, `standard.csv`, `standard.json`, what the scene's
/// `[output]` asks for, and `summary.json` last, the folder marked
/// `INCOMPLETE_FILE` until every file is written (`write_whole`).
pub fn write_run(dir: &Path, sc: &Resolved, out: &RunOutput) -> Result<Summary> {
    write_whole(dir, "taut run", || {
        write_history(&dir.join("history.csv"), out)?;
        let summary = Summary::new(sc, out);
        write_force_plot(&dir.join("force.svg"), sc, out)?;
        write_standard(dir, sc, &summary.standard, &summary.supports)?;
        write_wire(dir, &out.history)?;
        write_line(dir, sc, out, &summary.spans)?;
        form::write_form(dir, sc, out.form.as_ref())?;
        write_summary(&dir.join("summary.json"), &summary)?;
        Ok(summary)
    })
}

/// Line colours of every plot, cycled (see [`style`]).
pub(crate) use style::PALETTE;

/// Write a value as pretty-printed JSON with a final newline.
pub(crate) fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    // streamed: a summary of 10⁴ events per carrier is megabytes of text
    // that need not be held (the memory estimate counts no JSON text)
    use std::io::Write;
    let io = |e| Error::io(path, e);
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).map_err(io)?);
    serde_json::to_writer_pretty(&mut w, value).map_err(|e| Error::Output {
        path: path.into(),
        reason: e.to_string(),
    })?;
    w.write_all(b"\n").map_err(io)?;
    w.flush().map_err(io)
}

/// Format a float compactly and exactly (shortest round-trip form).
pub(crate) fn fmt_f64(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".to_string()
    } else if (1e-4..1e6).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
