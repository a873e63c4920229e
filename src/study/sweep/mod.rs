//! `taut sweep`: parameter sweeps over any scene value and over the study's
//! dimensionless axes (TARGETS T3–T7), in parallel, deterministic, resumable
//! and shardable.
//!
//! * A sweep is a 1-D or 2-D grid of `--vary key=start:stop:count` axes,
//!   linear or (with `--log`) logarithmic, or of listed axes `--vary
//!   key=v1,v2,...`; or a list of points (`--points FILE.csv`, `points`),
//!   whose keys are walked together rather than as a grid. `key` is any dotted scene path
//!   (`beam.tension`, `carrier.0.mass`) or one of the dimensionless axes:
//!   `speed_ratio` = V0/c (every carrier's cruise speed), `tension_ratio` =
//!   T/EA, `mass_ratio` = m/M with M = ρAL (every mass carrier),
//!   `stiffness_ratio` = k/(T/L) (every mass carrier). Ratios are applied after
//!   the plain keys and `tension_ratio` first, so `speed_ratio` and
//!   `stiffness_ratio` use the swept tension.
//! * A point's scene is typed values set on the scene tree: the text and
//!   the fixed `--set`s are parsed once ([`SweepSpec::base_tree`]), each
//!   axis is read as an [`AxisTarget`] (a key path or a [`Ratio`]) and its
//!   grid value, an f64, stored on a copy of that tree, as are the values a
//!   ratio fixes and the refined `mesh.elements` / `mesh.modes` /
//!   `time.step`; no number is printed and parsed again. The spec file keeps
//!   the axis key as text, so folders written by earlier binaries read back.
//! * Runs are independent; rayon spreads them over the cores. Each finished
//!   run is written at once to `runs/NNNNNN.json`; a sweep that is started
//!   again skips the runs already there, so an interrupted sweep loses
//!   nothing. The outputs are assembled in grid order from those files, so
//!   they are the same bytes whatever the thread count or interruption
//!   (wall times are kept apart, in `timing.csv`).
//! * A run that stops (divergence, failed contact solve, even a panic) is a
//!   finished point too: its record carries the error, the tables and maps
//!   mark it, and a resumed sweep does not run it again (the same scene and
//!   binary stop the same way).
//! * The folder is claimed by one sweep at a time and every record is
//!   stamped with its sweep, index and values ([`folder`]).
//! * `--shard i/n` runs the points with index ≡ i (mod n); `merge` joins
//!   shard folders (same `sweep.json` spec) into one.
//!
//! One concept a file: `axis` (one swept axis), `spec` (the grid and its
//! checks), `points` (a list of points), `resolve` (a grid point's scene), `record` (what a run
//! contributes), `refine` (`--check-refinement`), `shard` (`--shard`),
//! `batch` (points stepped together), [`folder`] (the sweep's folder),
//! `accuracy` (`--tolerance`: each point refined until its u_num is
//! within EPS); this file runs the sweep.

mod accuracy;
mod aliases;
mod axis;
mod batch;
pub mod folder;
pub(crate) mod nan_as_null;
mod points;
mod record;
mod refine;
mod resolve;
mod shard;
mod spec;
mod tolerance_spec;
mod work;

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::error::{Error, Result};

pub use accuracy::CHUNK;
pub use axis::{Axis, AxisTarget, Ratio};
pub(crate) use batch::AUTO_BATCH_LANES;
pub use batch::BatchWidth;
use batch::{batches, records_guarded};
pub(crate) use folder::merge_into;
pub use folder::{FolderLock, claim, merge};
pub(crate) use points::read_points;
pub use record::{PROFILE_BINS, SweepRecord};
pub use refine::Refined;
pub(crate) use refine::{REFINEMENT_ABS, REFINEMENT_REL, refinement_converged};
pub use shard::Shard;
pub use spec::{MAX_POINT_KEYS, SweepSpec};
pub use tolerance_spec::{PointAccuracy, SweepTolerance, targets};
pub use work::{Work, WorkSplit};

/// Run (or resume) a sweep into `dir`. `progress(done, total)` is called from
/// worker threads as runs finish. Returns the records of this shard, in grid
/// order; a run that stopped is a record with its error, not a failure of
/// the sweep. The folder is claimed for the duration ([`folder::claim`]).
pub fn sweep(
    spec: &SweepSpec,
    dir: &Path,
    shard: Option<Shard>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<SweepRecord>> {
    spec.validate()?;
    sweep_in(&folder::claim(dir)?, spec, shard, progress)
}

/// [`sweep`] into a folder the caller has claimed (and holds while it
/// writes the tables), for a spec the caller has validated
/// ([`SweepSpec::validate`]; a point that does not resolve would still only
/// be that point's error).
pub fn sweep_in(
    claimed: &FolderLock,
    spec: &SweepSpec,
    shard: Option<Shard>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<SweepRecord>> {
    sweep_batched(claimed, spec, shard, BatchWidth::Auto, progress)
}

/// `sweep_in` with the batch width given (`--batch`): points that share
/// their effective matrix step together, up to that many at a time; the
/// records are the same bytes whatever the width (their `wall_seconds`
/// aside).
pub fn sweep_batched(
    claimed: &FolderLock,
    spec: &SweepSpec,
    shard: Option<Shard>,
    batch: BatchWidth,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<SweepRecord>> {
    let dir = claimed.dir();
    let had_spec = folder::check_spec(dir, spec)?;
    folder::check_no_strays(dir, spec)?;
    folder::check_shard(dir, spec, shard)?;
    let id = folder::sweep_id(spec);
    let mine: Vec<usize> = (0..spec.len())
        .filter(|&i| shard.is_none_or(|s| s.owns(i)))
        .collect();
    let mut todo = Vec::new();
    for &i in &mine {
        if folder::load(dir, spec, &id, i)?.is_none() {
            todo.push(i);
        }
    }
    // only once the folder's records are known to be this sweep's
    if !had_spec {
        folder::write_spec(dir, spec)?;
    }
    let done = AtomicUsize::new(mine.len() - todo.len());
    progress(done.load(Ordering::Relaxed), mine.len());
    // the scene text and fixed overrides parsed once for every point (an
    // error there is each point's own, as resolving it again gives)
    let base = spec.base_tree().ok();
    if spec.tolerance.is_some() {
        accuracy::run_points(spec, base.as_ref(), &id, &todo, batch, &|r| {
            folder::save(dir, &r)?;
            let n = done.fetch_add(1, Ordering::Relaxed) + 1;
            progress(n, mine.len());
            Ok(())
        })?;
        return folder::collect(dir, spec, &mine);
    }
    let items = batches(spec, base.as_ref(), &todo, batch);
    // one item a task (`with_max_len(1)`): items differ in cost (a batch at
    // 50 m/s takes four times the steps of one at 230 m/s), and rayon's
    // default leaves hold runs of items that a thread, once started, steps
    // alone; on the 41 × 41 modal map that left one core idle for the last
    // ~6 s of 20
    items
        .par_iter()
        .with_max_len(1)
        .try_for_each(|item| -> Result<()> {
            let records = records_guarded(spec, base.as_ref(), &id, item);
            // a run stopped on request is no result: save none of the item's
            if crate::interrupt::requested() {
                return Err(Error::Interrupted);
            }
            for r in records {
                folder::save(dir, &r)?;
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress(n, mine.len());
            }
            Ok(())
        })?;
    folder::collect(dir, spec, &mine)
}
