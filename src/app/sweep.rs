//! `taut sweep` / `taut.sweep`: scene values or dimensionless axes swept
//! in parallel, resumable (sweep.csv, sweep_force.csv, sweep_loss.csv,
//! timing.csv, runs/, and the maps of a 1-D or 2-D sweep).

use std::path::PathBuf;
use std::sync::OnceLock;
use std::time::Instant;

use crate::error::Result;
use crate::report::{Outputs, Staged};
use crate::study::sweep::{
    Axis, BatchWidth, Shard, SweepRecord, SweepSpec, claim, folder, sweep_batched,
};

use super::{Frontend, Note, SceneSource, kept, started};

/// A sweep of one scene.
pub struct SweepRequest {
    /// The scene.
    pub scene: SceneSource,
    /// Fixed scene overrides, `key.path=value` (`--set`).
    pub set: Vec<String>,
    /// One or two axes; the last varies fastest. With `points`, the listed
    /// axes of a list of points (any number, one length).
    pub axes: Vec<Axis>,
    /// The axes are a list of points (`--points`), walked together.
    pub points: bool,
    /// Run each point a second time, refined (`--check-refinement`).
    pub check_refinement: bool,
    /// Refine each point until Q's u_num is within EPS (`--tolerance`,
    /// `--quantity`, `--max-cost`).
    pub tolerance: Option<crate::study::sweep::SweepTolerance>,
    /// The folder that holds the sweep's runs (resumable).
    pub out: PathBuf,
    /// Write the tables and maps into `out` too (the CLI always does).
    pub files: bool,
    /// Run only the points of one shard (`--shard i/n`).
    pub shard: Option<Shard>,
    /// Worker threads (none: one per core).
    pub threads: Option<usize>,
    /// Runs stepped together.
    pub batch: BatchWidth,
    /// Start even above the cost bound.
    pub yes: bool,
}

impl SweepRequest {
    /// A sweep of `scene` with overrides `set` as `study` gives it (the
    /// words of [`super::SweepArgs`]), resumable in `out`, its tables and
    /// maps written there.
    pub fn new(
        scene: SceneSource,
        set: Vec<String>,
        study: super::args::SweepStudy,
        out: PathBuf,
    ) -> SweepRequest {
        SweepRequest {
            scene,
            set,
            axes: study.axes,
            points: study.points,
            check_refinement: study.check_refinement,
            tolerance: study.tolerance,
            out,
            files: true,
            shard: study.shard,
            threads: study.threads,
            batch: study.batch,
            yes: study.yes,
        }
    }
}

/// What a sweep gives.
pub struct SweepOutcome {
    /// The sweep as run (its scene text, overrides and axes).
    pub spec: SweepSpec,
    /// One record a point (of the shard), in point order.
    pub records: Vec<SweepRecord>,
    /// The maps drawn (none for a shard or a partial grid).
    pub maps: Vec<PathBuf>,
    /// Points an earlier start had finished (kept, not run again).
    pub resumed: usize,
    /// Wall time, s.
    pub wall_seconds: f64,
    /// Worker threads the runs had.
    pub threads: usize,
}

impl SweepOutcome {
    /// Number of points whose run stopped with an error.
    pub fn stopped(&self) -> usize {
        self.records.iter().filter(|r| r.error.is_some()).count()
    }
}

/// Run the sweep (the points not finished by an earlier start) and write
/// its tables and maps. Everything is checked (the scene, the axes, the
/// cost, the threads, the folder's own sweep and shard) before a run
/// starts; the records of finished points go into `runs/` as they come
/// (the sweep's resumable state); the tables and maps are written beside
/// the folder's earlier ones and put in place once every point is done. A
/// sweep that stops leaves the earlier tables and maps as they were.
pub fn sweep(req: &SweepRequest, fe: &dyn Frontend) -> Result<SweepOutcome> {
    let dir = req.files.then_some(req.out.as_path());
    sweep_in(req, fe).map_err(|e| kept(dir, Outputs::Sweep, e, fe))
}

/// [`sweep`] but for the note of a sweep that stopped.
fn sweep_in(req: &SweepRequest, fe: &dyn Frontend) -> Result<SweepOutcome> {
    let start = Instant::now();
    let spec = SweepSpec {
        scene_text: req.scene.read()?,
        set: req.set.clone(),
        axes: req.axes.clone(),
        check_refinement: req.check_refinement,
        paired: req.points,
        tolerance: req.tolerance.clone(),
    };
    spec.validate().map_err(|e| req.scene.name(e))?;
    started(&spec.estimate(req.shard)?, req.yes, fe)?;
    if let Some(n) = req.threads {
        crate::study::threads::check_threads(n)?;
    }
    let dir = &req.out;
    crate::report::check_out_dir(dir)?;
    let claimed = claim(dir)?;
    // before anything is written: a shard into a folder holding the whole
    // sweep (or another shard's points) is refused, its tables kept
    folder::check_shard(dir, &spec, req.shard)?;
    let staged = if req.files {
        // tables and maps of this sweep only: a folder holding another
        // sweep is refused (by check_spec) with its tables left as they are
        folder::check_spec(dir, &spec)?;
        Some(Staged::open(&claimed, Outputs::Sweep, "taut sweep")?)
    } else {
        None
    };
    // the first report says how many points an earlier start had finished
    let resumed = OnceLock::new();
    let (records, threads) = crate::study::threads::in_pool(req.threads, || {
        let records = sweep_batched(&claimed, &spec, req.shard, req.batch, &|d, t| {
            resumed.get_or_init(|| d);
            fe.progress(d, t);
        });
        (records, rayon::current_num_threads())
    })?;
    let records = records?;
    let maps = match staged {
        Some(staged) => {
            let at = staged.path();
            crate::report::write_sweep(at, &spec, &records)?;
            let maps = crate::report::write_sweep_maps(at, &spec, &records)?;
            let maps = maps.iter().map(|m| staged.in_place(m)).collect();
            let removed = staged.commit()?;
            if let Some(note) = crate::report::replaced_note(dir, &removed) {
                fe.note(Note::Replaced(note));
            }
            maps
        }
        None => Vec::new(),
    };
    Ok(SweepOutcome {
        spec,
        records,
        maps,
        resumed: resumed.get().copied().unwrap_or(0),
        wall_seconds: start.elapsed().as_secs_f64(),
        threads,
    })
}
