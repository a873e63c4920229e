//! `taut merge`: shard folders of one sweep joined into one result.

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::report::{Outputs, Staged};
use crate::study::sweep::{SweepRecord, SweepSpec, folder::claim_as, merge_into};

use super::{Frontend, Note, kept};

/// What a merge gives.
pub struct MergeOutcome {
    /// The sweep.
    pub spec: SweepSpec,
    /// One record a point of the whole grid.
    pub records: Vec<SweepRecord>,
    /// The maps drawn.
    pub maps: Vec<PathBuf>,
}

impl MergeOutcome {
    /// Number of points whose run stopped with an error.
    pub fn stopped(&self) -> usize {
        self.records.iter().filter(|r| r.error.is_some()).count()
    }
}

/// Join `shards` into `out` and write the sweep's tables and maps there:
/// written beside the folder's earlier ones and put in place once the
/// merge has succeeded; a merge that stops leaves them as they were.
pub fn merge(shards: &[PathBuf], out: &Path, fe: &dyn Frontend) -> Result<MergeOutcome> {
    merge_in(shards, out, fe).map_err(|e| kept(Some(out), Outputs::Sweep, e, fe))
}

/// [`merge`] but for the note of a merge that stopped.
fn merge_in(shards: &[PathBuf], out: &Path, fe: &dyn Frontend) -> Result<MergeOutcome> {
    crate::report::check_out_dir(out)?;
    let claimed = claim_as(out, "taut merge")?;
    let staged = Staged::open(&claimed, Outputs::Sweep, "taut merge")?;
    // a folder holding another sweep is refused here, its tables kept
    let (spec, records) = merge_into(&claimed, shards)?;
    crate::report::write_sweep(staged.path(), &spec, &records)?;
    crate::report::write_merge(staged.path(), shards)?;
    let maps = crate::report::write_sweep_maps(staged.path(), &spec, &records)?;
    let maps = maps.iter().map(|m| staged.in_place(m)).collect();
    let removed = staged.commit()?;
    if let Some(note) = crate::report::replaced_note(out, &removed) {
        fe.note(Note::Replaced(note));
    }
    Ok(MergeOutcome {
        spec,
        records,
        maps,
    })
}
