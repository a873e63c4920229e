//! One command's outputs in a folder at a time, and never none.
//!
//! A folder holds the outputs of one command of a kind: the files a command
//! of its kind writes ([`Outputs::files`]) come from one run. A command
//! writes its new outputs into a staging folder inside the output folder
//! and puts them in place only once it has succeeded (`super::staging`):
//! then the earlier files of its kind and any saved failing contact
//! problem (`failed_contact_step_N.json`) are removed and the new files
//! renamed in ([`earlier_outputs`], [`replaced_note`]). A command that is
//! refused, fails or is interrupted leaves the earlier outputs as they were
//! and says so ([`kept_note`]). Other files in the folder are left alone. A
//! sweep's records and `sweep.json` are its resumable state, not outputs:
//! only its tables and maps, which it draws again from the records, are
//! replaced.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
pub(crate) use crate::study::lock::check_out_dir;

/// The kinds of command that write outputs, by the files they write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outputs {
    /// `taut run` (with or without `--tolerance`).
    Run,
    /// `taut compare`.
    Compare,
    /// `taut converge`.
    Converge,
    /// `taut precision`.
    Precision,
    /// `taut gate`.
    Gate,
    /// The tables and maps of `taut sweep` and `taut merge`.
    Sweep,
    /// `taut modes`.
    Modes,
    /// `taut uncertainty`.
    Uncertainty,
    /// `taut verify`.
    Verify,
    /// A study of one scene that declares its files itself (a
    /// `StudyCommand` of `app::each_study`): built-in kinds are listed
    /// here, a new study needs no line in this module.
    Declared(&'static Declared),
}

/// How `report.html` shows one file (`super::page`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Show {
    /// `summary.json` of a run.
    Summary,
    /// A CSV as a table: its title and the columns that hold verdicts.
    Table(&'static str, &'static [&'static str]),
    /// An SVG plot, embedded as an image, with its caption.
    Plot(&'static str),
    /// A JSON file the page reads for what its table lacks (warnings,
    /// skipped runs, notes, a gate's checks).
    Json,
    /// Not shown, for this reason (the page names it).
    Named(&'static str),
}

/// The outputs of a study that declares them: its command and each file
/// it writes with the way `report.html` shows it.
#[derive(Debug, PartialEq, Eq)]
pub struct Declared {
    /// The command, as the page names it (`taut compare`).
    pub command: &'static str,
    /// Each file and how the page shows it, in page order.
    pub files: &'static [(&'static str, Show)],
}

/// Prefix of a saved failing contact problem (`failed_contact_step_N.json`).
pub const FAILED_CONTACT_PREFIX: &str = "failed_contact_step_";

impl Outputs {
    /// The files this kind of command writes into its folder.
    pub fn files(self) -> Vec<&'static str> {
        let files: &[&str] = match self {
            Outputs::Run => &[
                "history.csv",
                "summary.json",
                "force.svg",
                "standard.csv",
                "standard.json",
                "accuracy.csv",
                "snapshots.csv",
                "field.csv",
                "spans.csv",
                "supports.csv",
                "envelope.csv",
                "line.svg",
                "static_heights.csv",
                "droppers_static.csv",
            ],
            Outputs::Compare => &["compare.csv", "compare.json", "compare.svg"],
            Outputs::Converge => &["converge.csv", "converge.json", "converge.svg"],
            Outputs::Precision => &["precision.csv", "precision.svg"],
            Outputs::Gate => &["gate.json", "junit.xml"],
            Outputs::Modes => &["modes.csv", "mode_shapes.csv"],
            Outputs::Uncertainty => &["uncertainty.csv", "uncertainty.json", "uncertainty.svg"],
            Outputs::Verify => &["verify.csv", "verify.json", "verify.md"],
            Outputs::Sweep => &[
                "sweep.csv",
                "sweep_force.csv",
                "sweep_loss.csv",
                "timing.csv",
                "merge.csv",
                "sweep.svg",
                "force_map.svg",
                "loss_map.svg",
                "refinement.svg",
                "loss_fraction_map.svg",
                "loss_fraction_span_map.svg",
                "refinement_map.svg",
                "u_num_map.svg",
                "tolerance.svg",
            ],
            Outputs::Declared(d) => return d.files.iter().map(|(f, _)| *f).collect(),
        };
        files.to_vec()
    }
}

/// The outputs an earlier command of this kind left in `dir`
/// ([`Outputs::files`], and with `failed` any `failed_contact_step_N.json`
/// too), sorted; none when `dir` does not exist.
pub(crate) fn earlier_outputs(dir: &Path, kind: Outputs, failed: bool) -> Result<Vec<PathBuf>> {
    check_out_dir(dir)?;
    let mut found = Vec::new();
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(found),
        Err(e) => return Err(Error::io(dir, e)),
    };
    for entry in entries {
        let entry = entry.map_err(|e| Error::io(dir, e))?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let ours = kind.files().contains(&name)
            || (failed
                && kind != Outputs::Sweep
                && name.starts_with(FAILED_CONTACT_PREFIX)
                && name.ends_with(".json"));
        if !ours || !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        found.push(entry.path());
    }
    found.sort();
    Ok(found)
}

/// The file names of `paths`, joined by `, `.
fn names(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a front end says when a command's new outputs replaced earlier
/// ones (`removed`): one line.
pub(crate) fn replaced_note(dir: &Path, removed: &[PathBuf]) -> Option<String> {
    if removed.is_empty() {
        return None;
    }
    Some(format!(
        "note: replaced the outputs of an earlier run in {} ({}): a folder holds one run's outputs",
        dir.display(),
        names(removed)
    ))
}

/// What a front end says when a command that names `dir` stopped without
/// writing it: the earlier outputs of its kind there, if any, are as they
/// were (one line). None when there are none, or when the folder is marked
/// partial (`INCOMPLETE`: its files are no result to keep).
pub(crate) fn kept_note(dir: &Path, kind: Outputs) -> Option<String> {
    if dir.as_os_str().is_empty() || dir.join(super::INCOMPLETE_FILE).exists() {
        return None;
    }
    let kept = earlier_outputs(dir, kind, false).ok()?;
    if kept.is_empty() {
        return None;
    }
    Some(format!(
        "note: {} keeps the outputs of an earlier run ({}), untouched: this command wrote none of its own",
        dir.display(),
        names(&kept)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_kinds_own_files_are_found() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        for f in [
            "history.csv",
            "summary.json",
            "failed_contact_step_12.json",
            "notes.txt",
            "compare.csv",
        ] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        let found = earlier_outputs(d, Outputs::Run, true).unwrap();
        assert_eq!(
            names(&found),
            "failed_contact_step_12.json, history.csv, summary.json"
        );
        let note = replaced_note(d, &found).unwrap();
        assert!(note.contains("history.csv, summary.json"), "{note}");
        let kept = kept_note(d, Outputs::Run).unwrap();
        assert!(
            kept.contains("(history.csv, summary.json), untouched"),
            "{kept}"
        );
        assert!(kept_note(d, Outputs::Modes).is_none());
        std::fs::write(d.join(super::super::INCOMPLETE_FILE), "x").unwrap();
        assert!(
            kept_note(d, Outputs::Run).is_none(),
            "a partial folder keeps no result"
        );
        assert!(
            earlier_outputs(&d.join("none"), Outputs::Run, true)
                .unwrap()
                .is_empty()
        );
        let e = earlier_outputs(Path::new(""), Outputs::Run, true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`--out`") && e.contains("current folder"), "{e}");
    }
}
