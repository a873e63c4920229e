//! `taut sweep`: parameter sweeps over any scene value and over the study's
//! dimensionless axes (TARGETS T3–T7), in parallel, deterministic, resumable
//! and shardable.
//!
//! * A sweep is a 1-D or 2-D grid of `--vary key=start:stop:count` axes
//!   (linear, `--log`, or listed `key=v1,v2,...`), or a list of points
//!   (`--points FILE.csv`). `key` is a dotted scene path or a dimensionless
//!   axis ([`Ratio`]: `speed_ratio`, `tension_ratio`, `mass_ratio`,
//!   `stiffness_ratio`), applied after the plain keys, `tension_ratio` first.
//! * A point's scene is typed values set on the scene tree parsed once
//!   ([`SweepSpec::base_tree`], [`AxisTarget`]): no number is printed and
//!   parsed again.
//! * Runs are independent (rayon); each finished run is written at once to
//!   `runs/NNNNNN.json` and a restarted sweep skips those, so an interruption
//!   loses nothing. Outputs are assembled in grid order from those files: the
//!   same bytes whatever the thread count or interruption (wall times apart,
//!   in `timing.csv`). A run that stops is a finished point too: its record
//!   carries the error.
//! * The folder is claimed by one sweep at a time, every record stamped with
//!   its sweep, index and values ([`folder`]); `--shard i/n` runs the points
//!   with index ≡ i (mod n), `merge` joins shard folders.
//!
//! One concept a file: `axis`, `spec`, `points`, `resolve` (a point's scene),
//! `record`, `refine` (`--check-refinement`), `shard`, `batch` (points
//! stepped together), [`folder`], `accuracy` (`--tolerance`); this file runs
//! the sweep.

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

pub(crate) use accuracy::Detail;
pub use accuracy::{CHUNK, RunMade, RunRole};
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
pub(crate) use tolerance_spec::check_level;
pub use tolerance_spec::{DEFAULT_QUANTITY, PointAccuracy, SweepTolerance, targets};
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

/// One scene refined as the one point of an accuracy-targeted sweep
/// (`taut run --tolerance`): the same queue, runs and estimators as every
/// point of `taut sweep --tolerance`, so the scene alone and the same
/// point of a sweep get the same resolution, value and u_num. Nothing is
/// written; the point's record and its [`Detail`] are returned.
pub(crate) fn refine_alone(
    scene_text: &str,
    set: &[String],
    tolerance: SweepTolerance,
) -> Result<(SweepRecord, Detail)> {
    // no axes: a grid of one point, the scene with its overrides
    let spec = SweepSpec {
        scene_text: scene_text.to_string(),
        set: set.to_vec(),
        axes: Vec::new(),
        check_refinement: false,
        paired: false,
        tolerance: Some(tolerance),
    };
    let id = folder::sweep_id(&spec);
    let base = spec.base_tree().ok();
    let slot = std::sync::Mutex::new(None);
    accuracy::run_points_with(
        &spec,
        base.as_ref(),
        &id,
        &[0],
        BatchWidth::Auto,
        true,
        &|f| {
            *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(f);
            Ok(())
        },
    )?;
    let f = slot
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .expect("the one point is finished");
    Ok((f.record, f.detail.expect("kept for a point run alone")))
}
