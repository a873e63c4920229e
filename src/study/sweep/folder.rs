//! A sweep's folder: who may write it, and which records belong to it.
//!
//! * **One writer at a time.** A sweep or merge claims its folder with the
//!   operating-system lock every command that writes a folder takes
//!   (`sweep.lock`, [`FolderLock`], `crate::study::lock::claim_folder`), held
//!   until it finishes. A second writer of the same folder is refused at once
//!   instead of mixing its records with the first's. The lock dies with its
//!   process, so a sweep killed with `kill -9` leaves nothing stale to clear:
//!   resuming it just works.
//! * **Every record stamped.** Each `runs/NNNNNN.json` carries the identity of
//!   its sweep (`sweep_id`, a hash of `sweep.json` and the quantities' definitions), its grid index and its
//!   axis values. A record is used only when all three match the folder's
//!   sweep and the file it sits in; anything else (a record of another sweep,
//!   of an older taut, under the wrong index) is refused with its path, on
//!   resume and on merge alike, never silently reused or overwritten.
//! * **Nothing half-written.** Records are written to a temporary file and
//!   renamed. An empty or unparsable record (what a machine crash can leave)
//!   is not evidence of anything: its point is run again.

use std::path::{Path, PathBuf};

use super::{SweepRecord, SweepSpec};
use crate::error::{Error, Result};
pub use crate::study::lock::FolderLock;

/// Claim `dir` for one sweep (creating it and its `runs/`), or refuse if
/// another command holds it (`crate::study::lock::claim_folder`).
pub fn claim(dir: &Path) -> Result<FolderLock> {
    claim_as(dir, "taut sweep")
}

/// [`claim`] for the command `command` (`taut merge` claims its folder as a
/// sweep's).
pub(crate) fn claim_as(dir: &Path, command: &str) -> Result<FolderLock> {
    std::fs::create_dir_all(dir.join("runs")).map_err(|e| Error::io(dir, e))?;
    crate::study::lock::claim_folder(dir, command)
}

/// The text of `sweep.json` for a spec.
pub(crate) fn spec_text(spec: &SweepSpec) -> String {
    serde_json::to_string_pretty(spec).expect("a sweep spec is plain data") + "\n"
}

/// A sweep's identity: FNV-1a (64 bit) of its `sweep.json` text and the
/// generation of the quantities' definitions
/// ([`crate::quantity::DEFINITIONS`]), in hex. It tells records of
/// different sweeps apart, and records made under other definitions (a
/// folder resumed by a newer taut: they are refused by name, never mixed
/// in); not a defence against forgery.
pub(crate) fn sweep_id(spec: &SweepSpec) -> String {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0100_0000_01b3;
    let text = format!(
        "{}definitions {}\n",
        spec_text(spec),
        crate::quantity::DEFINITIONS
    );
    let h = text
        .bytes()
        .fold(OFFSET, |h, b| (h ^ u64::from(b)).wrapping_mul(PRIME));
    format!("{h:016x}")
}

/// Check that the folder's `sweep.json`, if any, is this sweep's; `Ok(false)`
/// when there is none yet (write it with [`write_spec`] once the records
/// already in the folder have been checked).
pub(crate) fn check_spec(dir: &Path, spec: &SweepSpec) -> Result<bool> {
    let path = dir.join("sweep.json");
    match read_json(&path, "a sweep's sweep.json") {
        Ok(existing) if existing == spec_text(spec) => Ok(true),
        Ok(_) => Err(Error::invalid(
            "--out",
            dir.display(),
            "holds a different sweep (sweep.json differs): use another folder or remove it",
        )),
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => Ok(false),
        Err(e) => Err(e),
    }
}

/// A sweep folder's JSON file (spec or record), read with the input cap.
fn read_json(path: &Path, what: &str) -> Result<String> {
    crate::input::read_text(path, what, crate::input::MAX_INPUT_BYTES)
}

/// Write the folder's `sweep.json`.
pub(crate) fn write_spec(dir: &Path, spec: &SweepSpec) -> Result<()> {
    write_atomic(&dir.join("sweep.json"), &spec_text(spec))
}

/// Path of point `index`'s record.
pub(crate) fn run_file(dir: &Path, index: usize) -> PathBuf {
    dir.join("runs").join(format!("{index:06}.json"))
}

/// Write `text` to `path` through a temporary file and a rename, so a killed
/// process never leaves half a file.
pub(crate) fn write_atomic(path: &Path, text: &str) -> Result<()> {
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
}

/// Save point `record.index`'s record.
pub(crate) fn save(dir: &Path, record: &SweepRecord) -> Result<()> {
    let text = serde_json::to_string(record).expect("a sweep record is plain data");
    write_atomic(&run_file(dir, record.index), &text)
}

/// The record of point `index` in `dir`, checked against the sweep:
/// `Ok(None)` when the point has not finished (no file, or an empty or
/// unparsable one), an error when the file holds a record that is not this
/// sweep's point `index`.
pub(crate) fn load(
    dir: &Path,
    spec: &SweepSpec,
    id: &str,
    index: usize,
) -> Result<Option<SweepRecord>> {
    let path = run_file(dir, index);
    let text = match read_json(&path, "a sweep's run record") {
        Ok(t) => t,
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            return Ok(None);
        }
        // a record of binary junk (what a crash can leave) proves nothing: run again
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::InvalidData => {
            return Ok(None);
        }
        Err(e) => return Err(e),
    };
    let Ok(record) = serde_json::from_str::<SweepRecord>(&text) else {
        return Ok(None);
    };
    let foreign = |why: String| {
        Error::invalid(
            "runs",
            path.display(),
            format!(
                "{why}: it is not this sweep's record of point {index} (remove it to run the \
                 point again, or use another folder)"
            ),
        )
    };
    if record.sweep_id != id {
        return Err(foreign(format!(
            "belongs to sweep {} (this sweep is {id})",
            if record.sweep_id.is_empty() {
                "(unstamped: an older taut)"
            } else {
                &record.sweep_id
            }
        )));
    }
    if record.index != index {
        return Err(foreign(format!("holds point {}", record.index)));
    }
    let values = spec.point(index);
    let same = record.values.len() == values.len()
        && record
            .values
            .iter()
            .zip(&values)
            .all(|(a, b)| a.to_bits() == b.to_bits());
    if !same {
        return Err(foreign(format!(
            "holds axis values {:?}, the point is at {values:?}",
            record.values
        )));
    }
    Ok(Some(record))
}

/// Refuse a folder whose `runs/` holds a record file (`<digits>.json`)
/// outside the sweep's grid, naming it: it is another sweep's, or a grid's
/// that has since changed, and silently leaving it out would hide that (a
/// `000008.json` among a 7-point grid's records). Other files are not
/// records and are left alone.
pub(crate) fn check_no_strays(dir: &Path, spec: &SweepSpec) -> Result<()> {
    let runs = dir.join("runs");
    let entries = match std::fs::read_dir(&runs) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(Error::io(&runs, e)),
    };
    let mut strays: Vec<(usize, PathBuf)> = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| Error::io(&runs, e))?.path();
        let Some(stem) = path
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix(".json"))
        else {
            continue;
        };
        if stem.is_empty() || !stem.bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        let index = stem.parse::<usize>().unwrap_or(usize::MAX);
        if index >= spec.len() {
            strays.push((index, path));
        }
    }
    strays.sort();
    match strays.first() {
        None => Ok(()),
        Some((index, path)) => Err(Error::invalid(
            "runs",
            path.display(),
            format!(
                "is the record of point {}, outside this sweep's grid of {} points (0 ..= {}){}: \
                 it is not this sweep's (remove it, or use another folder)",
                if *index == usize::MAX {
                    "(an index too large to read)".to_string()
                } else {
                    index.to_string()
                },
                spec.len(),
                spec.len().saturating_sub(1),
                if strays.len() > 1 {
                    format!(", as are {} more", strays.len() - 1)
                } else {
                    String::new()
                }
            ),
        )),
    }
}

/// Refuse a shard (`--shard i/n`) into a folder holding records of points
/// the shard does not run: the whole sweep (a merged folder, an unsharded
/// run) or another shard's points. The shard would clear the folder's
/// tables and maps and write tables of its own points only, with nothing
/// to say they are a part. A shard's own folder, fresh or
/// holding its own points (a resumed shard), is accepted.
pub(crate) fn check_shard(dir: &Path, spec: &SweepSpec, shard: Option<super::Shard>) -> Result<()> {
    let Some(shard) = shard else {
        return Ok(());
    };
    let runs = dir.join("runs");
    let entries = match std::fs::read_dir(&runs) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(Error::io(&runs, e)),
    };
    let mut foreign: Vec<usize> = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| Error::io(&runs, e))?.path();
        let Some(index) = path
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix(".json"))
            .filter(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|s| s.parse::<usize>().ok())
        else {
            continue;
        };
        if index < spec.len() && !shard.owns(index) {
            foreign.push(index);
        }
    }
    foreign.sort_unstable();
    match foreign.first() {
        None => Ok(()),
        Some(first) => Err(Error::invalid(
            "--shard",
            format!("{}/{}", shard.index, shard.count),
            format!(
                "{} holds the records of {} points this shard does not run (the first: point {first}){}: a shard writes the tables of its own points only, and would replace that folder's: run the shard into a folder of its own (taut merge joins shard folders), or resume the whole sweep there without --shard",
                dir.display(),
                foreign.len(),
                if foreign.len() == (0..spec.len()).filter(|&i| !shard.owns(i)).count() {
                    ": every point of the other shards, the whole sweep with this shard's"
                } else {
                    ""
                }
            ),
        )),
    }
}

/// Read the records of the given indices, every one present and checked.
pub(crate) fn collect(dir: &Path, spec: &SweepSpec, indices: &[usize]) -> Result<Vec<SweepRecord>> {
    let id = sweep_id(spec);
    indices
        .iter()
        .map(|&i| {
            load(dir, spec, &id, i)?.ok_or_else(|| {
                Error::invalid(
                    "runs",
                    run_file(dir, i).display(),
                    "a finished run's record is missing or unreadable: resume the sweep to run \
                     the point",
                )
            })
        })
        .collect()
}

/// Read a sweep folder's spec.
pub(crate) fn read_spec(dir: &Path) -> Result<SweepSpec> {
    let p = dir.join("sweep.json");
    let text = read_json(&p, "a sweep's sweep.json")?;
    serde_json::from_str(&text).map_err(|e| Error::parse(format!("{}: {e}", p.display())))
}

/// Join shard folders into `out`: same spec, every point present, each
/// record checked against the sweep, a point run in two shards the same in
/// both. `out` is claimed for the merge.
pub fn merge(shards: &[PathBuf], out: &Path) -> Result<(SweepSpec, Vec<SweepRecord>)> {
    merge_into(&claim_as(out, "taut merge")?, shards)
}

/// [`merge`] into a folder the caller has claimed (and holds while it
/// writes the tables).
pub(crate) fn merge_into(
    out: &FolderLock,
    shards: &[PathBuf],
) -> Result<(SweepSpec, Vec<SweepRecord>)> {
    let out = out.dir();
    let first = shards
        .first()
        .ok_or_else(|| Error::invalid("merge", "(none)", "name at least one shard folder"))?;
    let spec = read_spec(first)?;
    // a spec read back is checked as a typed one is (one or two axes, every
    // point a valid scene, every axis changing something)
    spec.validate()?;
    for s in &shards[1..] {
        if read_spec(s)? != spec {
            return Err(Error::invalid(
                "merge",
                s.display(),
                "holds a different sweep than the first shard",
            ));
        }
    }
    for s in shards {
        check_no_strays(s, &spec)?;
    }
    let had_spec = check_spec(out, &spec)?;
    check_no_strays(out, &spec)?;
    let id = sweep_id(&spec);
    let mut missing = Vec::new();
    for i in 0..spec.len() {
        let mut found: Option<(PathBuf, SweepRecord)> = None;
        for s in shards {
            let Some(r) = load(s, &spec, &id, i)? else {
                continue;
            };
            match &found {
                None => found = Some((s.clone(), r)),
                Some((first, f)) => {
                    if !same_result(f, &r) {
                        return Err(Error::invalid(
                            "merge",
                            s.display(),
                            format!(
                                "point {i} differs from its record in {}: the shards were not \
                                 run by the same binary, or a record was edited",
                                first.display()
                            ),
                        ));
                    }
                }
            }
        }
        match found {
            Some((shard, r)) => {
                if run_file(&shard, i) != run_file(out, i) {
                    save(out, &r)?;
                }
            }
            None => missing.push(i),
        }
    }
    if !had_spec {
        write_spec(out, &spec)?;
    }
    if let Some(first_missing) = missing.first() {
        return Err(Error::invalid(
            "merge",
            format!(
                "{} of {} points missing (first: {first_missing})",
                missing.len(),
                spec.len(),
            ),
            "every point must be in some shard: run the missing shards (or resume them) first",
        ));
    }
    let all: Vec<usize> = (0..spec.len()).collect();
    let records = collect(out, &spec, &all)?;
    Ok((spec, records))
}

/// Two records of one point agree on everything but wall and CPU time.
fn same_result(a: &SweepRecord, b: &SweepRecord) -> bool {
    let strip = |r: &SweepRecord| serde_json::to_string(&r.without_timing()).expect("plain data");
    strip(a) == strip(b)
}
