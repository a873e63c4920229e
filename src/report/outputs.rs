//! One command's outputs in a folder at a time.
//!
//! A run that failed used to leave the previous run's `summary.json`,
//! `history.csv` and `force.svg` in its `--out` folder beside its own exit
//! status 1, with nothing to say they were stale (issue 25): a script, or a
//! person, would read an old result as the new one. So every command that
//! writes outputs first removes the files a command of its kind writes
//! ([`Outputs::files`]) and any saved failing contact problem
//! (`failed_contact_step_N.json`), and says so ([`clear_earlier`]); what is
//! in the folder afterwards is this command's, or nothing. Other files in
//! the folder are left alone. A sweep's records and `sweep.json` are its
//! resumable state, not outputs: only its tables and maps, which it draws
//! again from the records, are cleared.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

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
}

/// Prefix of a saved failing contact problem (`failed_contact_step_N.json`).
pub const FAILED_CONTACT_PREFIX: &str = "failed_contact_step_";

impl Outputs {
    /// The files this kind of command writes into its folder.
    pub fn files(self) -> &'static [&'static str] {
        match self {
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
            Outputs::Sweep => &[
                "sweep.csv",
                "sweep_force.csv",
                "sweep_loss.csv",
                "timing.csv",
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
        }
    }
}

/// Refuse an empty output folder path: it would write into the current
/// folder (the CLI's `--out ""` is refused by its parser; Python's
/// `out=""` reaches here).
pub(crate) fn check_out_dir(dir: &Path) -> Result<()> {
    if dir.as_os_str().is_empty() {
        return Err(Error::invalid(
            "--out",
            "\"\"",
            "must name a folder (an empty path would write into the current folder; use \".\" for that)",
        ));
    }
    Ok(())
}

/// Remove from `dir` the outputs an earlier command of this kind left
/// ([`Outputs::files`], and `failed_contact_step_N.json`), before the
/// command runs; returns the files removed (none when `dir` does not exist).
pub(crate) fn clear_earlier(dir: &Path, kind: Outputs) -> Result<Vec<PathBuf>> {
    check_out_dir(dir)?;
    let mut removed = Vec::new();
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(removed),
        Err(e) => return Err(Error::io(dir, e)),
    };
    for entry in entries {
        let entry = entry.map_err(|e| Error::io(dir, e))?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let ours = kind.files().contains(&name)
            || name == super::INCOMPLETE_FILE
            || (kind != Outputs::Sweep
                && name.starts_with(FAILED_CONTACT_PREFIX)
                && name.ends_with(".json"));
        if !ours || !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let path = entry.path();
        std::fs::remove_file(&path).map_err(|e| Error::io(&path, e))?;
        removed.push(path);
    }
    removed.sort();
    Ok(removed)
}

/// What a front end says when [`clear_earlier`] removed files: one line.
pub(crate) fn cleared_note(dir: &Path, removed: &[PathBuf]) -> Option<String> {
    if removed.is_empty() {
        return None;
    }
    let names: Vec<String> = removed
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    Some(format!(
        "note: removed the outputs of an earlier run from {} ({}): a folder holds one run's outputs",
        dir.display(),
        names.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_kinds_own_files_are_removed() {
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
        let removed = clear_earlier(d, Outputs::Run).unwrap();
        let names: Vec<_> = removed
            .iter()
            .map(|p| p.file_name().unwrap().to_str().unwrap().to_string())
            .collect();
        assert_eq!(
            names,
            ["failed_contact_step_12.json", "history.csv", "summary.json"]
        );
        assert!(d.join("notes.txt").exists() && d.join("compare.csv").exists());
        let note = cleared_note(d, &removed).unwrap();
        assert!(note.contains("history.csv, summary.json"), "{note}");
        assert!(
            clear_earlier(&d.join("none"), Outputs::Run)
                .unwrap()
                .is_empty()
        );
        let e = clear_earlier(Path::new(""), Outputs::Run)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`--out`") && e.contains("current folder"), "{e}");
    }
}
