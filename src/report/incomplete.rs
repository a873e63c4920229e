//! A folder being written says so until it is whole.
//!
//! A command puts several files into its folder, one after another; one
//! that stops between them (a full disk, a file it cannot create, an abort
//! or a kill) would leave the files put so far, `summary.json` among them,
//! looking like a complete result. So writing starts by putting
//! [`INCOMPLETE_FILE`] into the folder and ends by removing it, once the
//! last file is in: a folder holding it is partial, whatever else it
//! holds. A command that fails while writing leaves it with its error; one
//! that is killed leaves it as it was put there. The next command of any
//! kind that writes the folder removes it with the earlier outputs. A
//! command writes its files into a staging folder first and marks its
//! output folder only while it puts them in place (`super::staging`), so
//! the window is a few renames; a run puts `summary.json` in last, so a
//! folder with a summary and no marker is a finished run's.

use std::path::Path;

use crate::error::{Error, Result};

/// The marker of a folder whose outputs are being written, or were left
/// partial.
pub(crate) const INCOMPLETE_FILE: &str = "INCOMPLETE";

/// Write a command's outputs into `dir` with `write`, the folder marked
/// [`INCOMPLETE_FILE`] until `write` has finished (`what` names the
/// command in the marker: "taut run"). On an error the marker stays, with
/// the error; on success it is removed.
pub(crate) fn write_whole<T>(
    dir: &Path,
    what: &str,
    write: impl FnOnce() -> Result<T>,
) -> Result<T> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let marker = dir.join(INCOMPLETE_FILE);
    let text = |state: &str| {
        format!(
            "{what} {state}\nThe files of this folder are partial: do not read them as a result. \
             The next command writing this folder removes them and this file.\n"
        )
    };
    std::fs::write(
        &marker,
        text("was writing its outputs here and did not finish (it stopped or was killed)."),
    )
    .map_err(|e| Error::io(&marker, e))?;
    match write() {
        Ok(v) => {
            std::fs::remove_file(&marker).map_err(|e| Error::io(&marker, e))?;
            Ok(v)
        }
        Err(e) => {
            // the error is what the caller reports; the marker says it too
            let _ = std::fs::write(
                &marker,
                text(&format!("stopped while writing its outputs: {e}")),
            );
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_marker_stays_with_the_error_and_goes_on_success() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("out");
        let v = write_whole(&d, "taut run", || {
            assert!(d.join(INCOMPLETE_FILE).exists(), "marked while writing");
            Ok(7)
        })
        .unwrap();
        assert_eq!(v, 7);
        assert!(!d.join(INCOMPLETE_FILE).exists());
        let e = write_whole(&d, "taut run", || -> Result<()> {
            Err(Error::invalid("x", 1, "a test's failure"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("a test's failure"));
        let marker = std::fs::read_to_string(d.join(INCOMPLETE_FILE)).unwrap();
        assert!(
            marker.contains("a test's failure") && marker.contains("partial"),
            "{marker}"
        );
    }
}
