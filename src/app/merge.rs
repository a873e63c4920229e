//! `taut merge`: shard folders of one sweep joined into one result.

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::report::Outputs;
use crate::study::sweep::{SweepRecord, SweepSpec, claim, folder, merge_into, read_spec};

use super::{Frontend, fresh};

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

/// Join `shards` into `out` and write the sweep's tables and maps there.
pub fn merge(shards: &[PathBuf], out: &Path, fe: &dyn Frontend) -> Result<MergeOutcome> {
    let claimed = claim(out)?;
    // clear the tables only of a folder that holds this sweep (or none):
    // merge_into refuses any other, which then keeps its tables
    if let Some(first) = shards.first()
        && let Ok(spec) = read_spec(first)
        && folder::check_spec(out, &spec).is_ok()
    {
        fresh(out, Outputs::Sweep, fe)?;
    }
    let (spec, records) = merge_into(&claimed, shards)?;
    let maps = crate::report::write_whole(out, "taut merge", || {
        crate::report::write_sweep(out, &spec, &records)?;
        crate::report::write_sweep_maps(out, &spec, &records)
    })?;
    Ok(MergeOutcome {
        spec,
        records,
        maps,
    })
}
