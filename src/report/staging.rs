//! New outputs written beside the old ones and swapped in whole.
//!
//! A command that writes a folder claims it ([`crate::study::lock::claim_folder`]) and
//! opens a staging folder inside it ([`Staged::open`]:
//! `DIR/.taut-staging-<pid>/`, which also proves the folder writable
//! before any heavy work). Its outputs are written there. Only when the
//! command has succeeded are they put in place ([`Staged::commit`]): the
//! earlier files of the command's kind are removed and the new ones
//! renamed in, `summary.json` last. Renames within one folder are atomic
//! per file, so the only window in which the folder is neither the old
//! result nor the new is the swap itself, marked [`super::INCOMPLETE_FILE`]
//! as any partial folder is. A command that is refused, fails or is
//! interrupted drops its staging folder: the earlier outputs stay as they
//! were. A staging folder a killed command left is removed by the next
//! claim of the folder (it holds the lock, so no other command is writing).

use std::path::{Path, PathBuf};

use super::Outputs;
use crate::error::{Error, Result};
use crate::study::lock::FolderLock;

/// Prefix of a staging folder's name (`.taut-staging-<pid>`).
pub(crate) const STAGING_PREFIX: &str = ".taut-staging-";

/// The file a run writes last, and so is put in place last: a folder with
/// a summary and no `INCOMPLETE` is a finished run's.
const LAST: &str = "summary.json";

/// A command's outputs being written in a staging folder of its claimed
/// output folder (module docs). Dropped without [`Staged::commit`], the
/// staging folder is removed and the output folder is as it was.
#[derive(Debug)]
pub struct Staged {
    dir: PathBuf,
    stage: PathBuf,
    kind: Outputs,
    what: String,
}

impl Staged {
    /// Open a staging folder in the folder `lock` claims for the outputs of
    /// `kind`, `what` naming the command in the swap's marker (`taut run`);
    /// staging folders a killed command left there are removed first. An
    /// output folder that cannot be written is refused here.
    pub fn open(lock: &FolderLock, kind: Outputs, what: &str) -> Result<Staged> {
        let dir = lock.dir().to_path_buf();
        remove_stale_stages(&dir)?;
        let stage = dir.join(format!("{STAGING_PREFIX}{}", std::process::id()));
        std::fs::create_dir(&stage).map_err(|e| Error::io(&stage, e))?;
        Ok(Staged {
            dir,
            stage,
            kind,
            what: what.to_string(),
        })
    }

    /// The staging folder: where the command writes its outputs.
    pub fn path(&self) -> &Path {
        &self.stage
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Where a path inside the staging folder will be once the outputs are
    /// in place (a path elsewhere as it is).
    pub fn in_place(&self, path: &Path) -> PathBuf {
        match path.strip_prefix(&self.stage) {
            Ok(rest) => self.dir.join(rest),
            Err(_) => path.to_path_buf(),
        }
    }

    /// Put the staged outputs in place: mark the folder `INCOMPLETE`,
    /// remove the earlier outputs of this kind (and any saved failing
    /// contact problem), rename every staged file in (`summary.json`
    /// last), remove the marker. Returns the earlier files removed. A
    /// failure on the way leaves the marker with its error.
    pub fn commit(self) -> Result<Vec<PathBuf>> {
        super::write_whole(&self.dir, &self.what, || {
            let earlier = super::outputs::earlier_outputs(&self.dir, self.kind, true)?;
            for p in &earlier {
                std::fs::remove_file(p).map_err(|e| Error::io(p, e))?;
            }
            let mut staged = Vec::new();
            for entry in std::fs::read_dir(&self.stage).map_err(|e| Error::io(&self.stage, e))? {
                let entry = entry.map_err(|e| Error::io(&self.stage, e))?;
                let name = entry.file_name();
                if name == super::INCOMPLETE_FILE {
                    continue;
                }
                staged.push(name);
            }
            staged.sort_by_key(|n| (n == LAST, n.clone()));
            for name in staged {
                let (from, to) = (self.stage.join(&name), self.dir.join(&name));
                std::fs::rename(&from, &to).map_err(|e| Error::io(&to, e))?;
            }
            Ok(earlier)
        })
        // the staging folder goes with `self`
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.stage);
    }
}

/// Remove the staging folders in `dir` (the caller holds its lock: they
/// are killed commands').
fn remove_stale_stages(dir: &Path) -> Result<()> {
    for entry in std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))? {
        let entry = entry.map_err(|e| Error::io(dir, e))?;
        let stale = entry
            .file_name()
            .to_str()
            .is_some_and(|n| n.starts_with(STAGING_PREFIX))
            && entry.file_type().is_ok_and(|t| t.is_dir());
        if stale {
            let p = entry.path();
            std::fs::remove_dir_all(&p).map_err(|e| Error::io(&p, e))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(d: &Path, f: &str) -> String {
        std::fs::read_to_string(d.join(f)).unwrap()
    }

    #[test]
    fn outputs_are_swapped_in_whole_or_not_at_all() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("out");
        std::fs::create_dir_all(d.join(".taut-staging-1")).unwrap();
        for f in ["history.csv", "summary.json", "snapshots.csv", "mine.txt"] {
            std::fs::write(d.join(f), "old").unwrap();
        }
        let lock = super::super::claim_folder(&d, "taut run").unwrap();
        // dropped: nothing changes, the stale staging folder is gone too
        let staged = Staged::open(&lock, Outputs::Run, "taut run").unwrap();
        std::fs::write(staged.path().join("history.csv"), "new").unwrap();
        drop(staged);
        assert_eq!(read(&d, "history.csv"), "old");
        let left: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.starts_with(STAGING_PREFIX))
            .collect();
        assert!(left.is_empty(), "{left:?}");
        // committed: the kind's files replaced, the others kept
        let staged = Staged::open(&lock, Outputs::Run, "taut run").unwrap();
        for f in ["history.csv", "summary.json"] {
            std::fs::write(staged.path().join(f), "new").unwrap();
        }
        let at = staged.in_place(&staged.path().join("summary.json"));
        assert_eq!(at, d.join("summary.json"));
        let removed = staged.commit().unwrap();
        assert_eq!(removed.len(), 3, "{removed:?}");
        assert_eq!(read(&d, "history.csv"), "new");
        assert_eq!(read(&d, "summary.json"), "new");
        assert_eq!(read(&d, "mine.txt"), "old");
        assert!(!d.join("snapshots.csv").exists());
        assert!(!d.join(super::super::INCOMPLETE_FILE).exists());
        // a swap that fails is marked
        std::fs::create_dir(d.join("force.svg")).unwrap();
        let staged = Staged::open(&lock, Outputs::Run, "taut run").unwrap();
        std::fs::write(staged.path().join("force.svg"), "new").unwrap();
        std::fs::write(staged.path().join("summary.json"), "newer").unwrap();
        assert!(staged.commit().is_err());
        assert!(read(&d, super::super::INCOMPLETE_FILE).contains("force.svg"));
        assert!(!d.join("summary.json").exists(), "the summary goes in last");
    }
}
