//! One writer per folder.
//!
//! Every command that writes a folder (`run`, the studies, `modes`, `gate`,
//! `verify`, `sweep`, `merge`, Python's functions and `Simulation`) first
//! claims it ([`claim_folder`]) with an operating-system lock on the file
//! `sweep.lock` in it, and holds the claim until its outputs are in place.
//! A second writer of the same folder, of any kind, is refused at once,
//! naming the holder (its process, command and start time, which the lock
//! file holds as text), instead of splicing its files with the first's.
//! The lock is the operating system's: it dies with its process, so a
//! writer killed with `kill -9` leaves no claim to clear (the file it leaves
//! is text, not a lock: the next claim takes it).
//!
//! The file is named `sweep.lock` for every command: the sweep's lock came
//! first, and one name means a sweep and a run on one folder exclude each
//! other too.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

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

/// The lock file a command writing a folder holds in it.
pub(crate) const LOCK_FILE: &str = "sweep.lock";

/// A claimed folder; the claim ends when this is dropped (or the process
/// dies). Dropped, it removes `sweep.lock` while still holding it, so a
/// finished command leaves no lock file behind; a claim that waited on the
/// removed file finds it gone and takes a new one ([`claim_folder`]).
#[derive(Debug)]
pub struct FolderLock {
    dir: PathBuf,
    /// The folder's canonical path, held in [`CLAIMED`] until dropped.
    canonical: PathBuf,
    _file: File,
}

/// The folders claimed by this process, by canonical path: a claim is
/// refused here first, whatever the file system makes of two locks taken
/// by one process (on NFS and other file systems that emulate `flock`
/// with POSIX record locks, a process's second lock on a file succeeds:
/// two sweeps of one Python process would share a folder).
static CLAIMED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Give back this process's claim of `canonical` ([`CLAIMED`]).
fn unclaim(canonical: &Path) {
    let mut held = CLAIMED.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(i) = held.iter().position(|p| p == canonical) {
        held.swap_remove(i);
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        // removed before the descriptor (and so the lock) is closed
        let _ = std::fs::remove_file(self.dir.join(LOCK_FILE));
        unclaim(&self.canonical);
    }
}

/// True when `path` still names the file `file` has open (a lock taken on a
/// file another claim has since removed is no claim of the folder).
fn still_named(file: &File, path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (file.metadata(), std::fs::metadata(path)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = (file, path);
        true
    }
}

impl FolderLock {
    /// The claimed folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

/// How long a claim waits for a lock that looks held before refusing the
/// folder ([`claim_folder`]): a fork–exec window is microseconds to
/// milliseconds even on a loaded machine; a command holding the folder
/// holds it for its whole run.
pub(crate) const LOCK_WAIT: std::time::Duration = std::time::Duration::from_millis(500);

/// The refusal of a folder another command holds.
fn in_use(dir: &Path, holder: &str) -> Error {
    Error::invalid(
        "--out",
        dir.display(),
        format!(
            "is in use by another command writing it now ({holder}): wait for it to finish, \
             or use another folder"
        ),
    )
}

/// Claim `dir` for one command (creating it), `command` naming it in the
/// lock file (`taut run`), or refuse if another claim holds it: first in
/// this process (`CLAIMED`), then the operating system's lock on
/// `sweep.lock`.
pub fn claim_folder(dir: &Path, command: &str) -> Result<FolderLock> {
    check_out_dir(dir)?;
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let canonical = dir.canonicalize().map_err(|e| Error::io(dir, e))?;
    {
        let mut held = CLAIMED.lock().unwrap_or_else(|p| p.into_inner());
        if held.contains(&canonical) {
            return Err(in_use(
                dir,
                &format!("in this process, {}", std::process::id()),
            ));
        }
        held.push(canonical.clone());
    }
    // from here the claim is this process's: a failure below gives it back
    let path = dir.join(LOCK_FILE);
    // a lock taken on a file its holder removed as it let go: open anew
    for _ in 0..CLAIM_TRIES {
        let file = claim_once(dir, &path, command).inspect_err(|_| unclaim(&canonical))?;
        if still_named(&file, &path) {
            return Ok(FolderLock {
                dir: dir.to_path_buf(),
                canonical,
                _file: file,
            });
        }
        // the file was removed under us: closing it lets go of nothing
    }
    unclaim(&canonical);
    Err(Error::invalid(
        "--out",
        dir.display(),
        "its sweep.lock keeps being replaced by other commands writing it: wait for them to finish, or use another folder",
    ))
}

/// Claims [`claim_folder`] makes before giving up on a folder whose lock
/// file keeps being removed under it (each removal is a claim that
/// finished).
const CLAIM_TRIES: usize = 20;

/// Open [`LOCK_FILE`] and take its lock (one try of [`claim_folder`]).
fn claim_once(dir: &Path, path: &Path, command: &str) -> Result<File> {
    let path = path.to_path_buf();
    let mut file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .read(true)
        .write(true)
        .open(&path)
        .map_err(|e| Error::io(&path, e))?;
    // A lock just released can look held for a moment: a thread of this
    // process that forks a child (std::process::Command) duplicates every
    // open descriptor until the child's exec closes it, and the lock lives
    // while any duplicate does. Waiting up to LOCK_WAIT for that to pass
    // tells such a moment from a command that really holds the folder (a
    // run takes far longer).
    let deadline = std::time::Instant::now() + LOCK_WAIT;
    let mut attempt = file.try_lock();
    while matches!(attempt, Err(TryLockError::WouldBlock)) && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(10));
        attempt = file.try_lock();
    }
    match attempt {
        Ok(()) => {}
        Err(TryLockError::WouldBlock) => {
            // a line ("process N: taut run, started …"): read no more than a line's worth
            let holder = crate::input::read_text(&path, "a lock file", 256).unwrap_or_default();
            return Err(in_use(
                dir,
                holder.trim().lines().next().unwrap_or("its lock is held"),
            ));
        }
        Err(TryLockError::Error(e)) => return Err(Error::io(&path, e)),
    }
    // who holds it, for the refusal of a second writer and for a person
    // looking at the folder (the lock itself is the OS's)
    file.set_len(0).map_err(|e| Error::io(&path, e))?;
    writeln!(
        file,
        "process {}: {command}, started {}",
        std::process::id(),
        utc_now()
    )
    .map_err(|e| Error::io(&path, e))?;
    Ok(file)
}

/// The time now as `2026-11-29 07:31:06 UTC` (the clock's; a clock before
/// 1970 reads as 1970).
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let (y, m, d) = civil_from_days(days as i64);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02} UTC",
        rest / 3600,
        rest % 3600 / 60,
        rest % 60
    )
}

/// The proleptic Gregorian date of `days` since 1970-01-01 (Howard
/// Hinnant's `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_the_calendars() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(civil_from_days(20_786), (2026, 11, 29));
    }

    #[test]
    fn a_second_claim_is_refused_naming_the_holder_and_the_first_one_lets_go() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("out");
        let held = claim_folder(&d, "taut run").unwrap();
        let text = std::fs::read_to_string(d.join(LOCK_FILE)).unwrap();
        assert!(
            text.starts_with(&format!(
                "process {}: taut run, started ",
                std::process::id()
            )) && text.trim_end().ends_with(" UTC"),
            "{text}"
        );
        let e = claim_folder(&d, "taut compare").unwrap_err().to_string();
        assert!(e.contains("in use by another command"), "{e}");
        drop(held);
        assert!(
            !d.join(LOCK_FILE).exists(),
            "a finished claim leaves no lock file"
        );
        drop(claim_folder(&d, "taut compare").unwrap());
    }
}
