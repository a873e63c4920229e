//! Accuracy-targeted sweeps: `taut sweep … --tolerance EPS --quantity Q`
//! refines every point until the numerical uncertainty u_num of Q (a
//! column of `sweep.csv`) is at most EPS, each point only as far as it
//! must (docs/sweeps.md#accuracy-targeted-sweeps---tolerance).
//!
//! Per point, from its own resolution (N₀ or J₀, Δt₀), writing a run as
//! the exponents (a, b) of N₀·2^a, Δt₀/2^b:
//!
//! 1. **Pilots**: the family of `taut uncertainty` with three levels ending
//!    at the point's own resolution, coarsened — (−2, −2), (−1, −1), (0, 0)
//!    and the split runs (−1, −2), (0, −1), together 1.81 times the point's
//!    own run. Q's u_num at (0, 0) ([`assess`]; not smooth: at least the
//!    [split floor](crate::study::uncertainty::assess::split_floor));
//!    within EPS: done.
//! 2. **Plan**: the mesh-plus-step error model from the split's mesh and
//!    Δt differences ([`LadderFit`], [`ErrorModel::cheapest`]) gives the
//!    cheapest (h, Δt) whose modelled error is within [`PLAN_SHARE`] × EPS;
//!    the candidate is the coarsest (a, b) at or below it.
//! 3. **Check**: the candidate's own three-level family, (a − 2, b − 2),
//!    (a − 1, b − 1), (a, b), and its split (a − 1, b − 2), (a, b − 1)
//!    (runs made already are reused), gives its u_num. Within EPS: done;
//!    else one more level on both (a + 1, b + 1), up to [`MAX_CHECKS`]
//!    checks, each cut down to the point's budget (`budget` × its own run,
//!    in unknowns × steps) and to scenes the model takes; else the
//!    candidate of smallest u_num, not met. Not smooth: hopeless checks
//!    skip their finest run, a met candidate is confirmed one Δt finer
//!    (`confirm`, outside the budget); smooth: growing differences never meet.
//!
//! One queue runs every point's runs ([`run_points`]), the records the same
//! whatever the order or threads; `run --tolerance` is one point of it.

use std::sync::{Condvar, Mutex, MutexGuard};

use toml::Table;

use super::batch::{BatchWidth, auto_lanes, panic_message};
use super::record::{SweepRecord, record_of};
use super::spec::SweepSpec;
use super::tolerance_spec::{PointAccuracy, SweepTolerance};
use crate::error::{Error, Result};
use crate::integrate::batch_key;
use crate::quantity::{LOSS_FRACTION, LOSS_FRACTION_SPAN, Quantity};
use crate::resolve::Resolved;
use crate::run::{RunOutput, run_batch};
use crate::study::cost::run_dof_steps;
use crate::study::cpu_time::{shares, timed};
use crate::study::level::Level;
use crate::study::tolerance::{ErrorModel, LadderFit};
use crate::study::uncertainty::assess::{Estimator, split_floor};
use crate::study::uncertainty::{Assessment, FS_ASYMPTOTIC, FS_CAUTIOUS, RATIO, engine};

/// Checks after the pilots at most: with one more level on both each, a
/// point may end 2⁵ times finer in h and Δt than the plan's first guess.
pub(crate) const MAX_CHECKS: usize = 3;

/// The share of EPS the plan asks of the error model ([`ErrorModel`]): its
/// estimate carries Roache's 1.25, the check's u_num the 3 of a quantity
/// that is not smooth, and the check adds its fit's scatter, so the plan
/// aims at 1.25/3 of EPS and leaves a fifth of that for the scatter.
pub(crate) const PLAN_SHARE: f64 = FS_ASYMPTOTIC / FS_CAUTIOUS * 0.8;

/// The furthest a plan refines one variable: 2⁵ times the point's own.
pub(crate) const MAX_EXPONENT: i32 = 5;

/// Points admitted at a time when fewer jobs wait than workers: enough for
/// batches of runs that share a matrix or a basis (a 2-D map's row of 41
/// speeds is one tension), few enough that an interruption loses little.
pub const CHUNK: usize = 128;

type Key = (i32, i32);

const PILOTS: [Key; 5] = [(-2, -2), (-1, -1), (0, 0), (-1, -2), (0, -1)];

fn family(k: Key) -> [Key; 3] {
    [(k.0 - 2, k.1 - 2), (k.0 - 1, k.1 - 1), k]
}

/// A check's runs: the family ending at `k`, then its split (each level's
/// mesh at the previous level's Δt), as the pilots have.
fn check_runs(k: Key) -> [Key; 5] {
    let [a, b, c] = family(k);
    [a, b, c, (k.0 - 1, k.1 - 2), (k.0, k.1 - 1)]
}

/// One run of a point.
struct Ran {
    key: Key,
    value: Option<f64>,
    /// Every target's value ([`super::targets`]), for a point run alone
    /// (`run --tolerance`: a bar on every result); empty in a sweep.
    values: Vec<Option<f64>>,
    /// The run itself, kept for a candidate of a point run alone.
    output: Option<RunOutput>,
    dof_steps: f64,
    /// CPU seconds of the run (its share of its batch's).
    cpu: Option<f64>,
    loss: bool,
    /// The point's record from this run, kept for candidates only.
    record: Option<SweepRecord>,
}

enum Stage {
    Pilot,
    Check(Key),
    /// A met candidate of a quantity that is not smooth, confirmed by one
    /// run at half its Δt ([`confirm_key`]).
    Confirm(Key),
    Done,
}

/// The run that confirms candidate `k`: its mesh at half its Δt.
fn confirm_key(k: Key) -> Key {
    (k.0, k.1 + 1)
}

/// One point being worked.
struct Point {
    index: usize,
    base: Option<Resolved>,
    level: Option<Level>,
    runs: Vec<Ran>,
    stage: Stage,
    checks: usize,
    base_cost: f64,
    /// (key, assessment) of each candidate, in order.
    candidates: Vec<(Key, Assessment)>,
    record: Option<SweepRecord>,
    /// Runs queued or being stepped.
    queued: Vec<Key>,
    /// What the pilots' error model predicts of reaching EPS.
    prediction: Prediction,
    /// Why the point stopped short of EPS, once it has.
    not_met: Option<String>,
    /// The candidate reported, once finished.
    reported: Option<Key>,
    /// The error of a run (or scene) that stopped the point.
    error: Option<Error>,
    /// EPS when Q is not smooth: a check's finest run then waits for the
    /// family's other runs, and is not made when the mesh part they give
    /// already puts the candidate's u_num above EPS ([`Point::hopeless`]).
    staged: Option<f64>,
    /// The candidates confirmed by a run at half their Δt, in order.
    confirmed: Vec<Key>,
    /// The last check whose finest run was not made ([`Point::hopeless`]),
    /// with the least u_num its candidate could have had.
    unmade: Option<(Key, f64)>,
    /// Runs of the current stage that stopped, waiting for the stage's
    /// other runs: the error reported is then the coarsest run's, the same
    /// whatever order the workers ended them in.
    failed: Vec<(Key, Error)>,
}

/// What the pilots' error model predicts of a point reaching EPS.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Prediction {
    /// Not asked (the pilots met EPS) or a ladder that does not converge.
    Unknown,
    /// Reaching EPS costs this many times the point's own run, pilots
    /// included.
    Cost(f64),
    /// No scene the model takes reaches EPS (J beyond the exact modes'
    /// range, or a refinement beyond 2^PREDICT_EXPONENT).
    OutOfReach,
}

impl Point {
    fn value(&self, k: Key) -> Option<Option<f64>> {
        self.runs.iter().find(|r| r.key == k).map(|r| r.value)
    }

    fn spent(&self) -> f64 {
        self.runs.iter().map(|r| r.dof_steps).sum()
    }

    /// CPU seconds of the point's runs so far (none without a thread clock).
    fn cpu(&self) -> Option<f64> {
        self.runs.iter().map(|r| r.cpu).sum()
    }

    fn scene(&self, k: Key) -> Result<Resolved> {
        let (base, level) = (
            self.base
                .as_ref()
                .expect("a point being worked has its scene"),
            self.level.expect("and its level"),
        );
        let n = engine::level_parameter(level.start(), k.0).ok_or_else(|| {
            Error::invalid(
                "--tolerance",
                format!("{k:?}"),
                "a level parameter out of range",
            )
        })?;
        // as `taut uncertainty` makes its family's runs
        engine::member_scene(base, level, n, k.1)
    }

    /// The keys the point needs next that it has not run.
    fn wants(&self) -> Vec<Key> {
        let keys: Vec<Key> = match self.stage {
            Stage::Pilot => PILOTS.to_vec(),
            Stage::Check(k) if self.staged.is_some() => {
                // the finest run last, and only while it can still meet EPS
                let others: Vec<Key> = check_runs(k)
                    .into_iter()
                    .filter(|&f| f != k && self.value(f).is_none())
                    .collect();
                if !others.is_empty() {
                    others
                } else if self.hopeless(k) {
                    vec![]
                } else {
                    vec![k]
                }
            }
            Stage::Check(k) => check_runs(k).to_vec(),
            Stage::Confirm(k) => vec![confirm_key(k)],
            Stage::Done => vec![],
        };
        keys.into_iter()
            .filter(|&k| self.value(k).is_none())
            .collect()
    }

    /// True when candidate `k` cannot meet EPS whatever its finest run
    /// gives: Q is not smooth, so its u_num is at least the split floor
    /// ([`split_floor`]), whose mesh part, F_s·|Δ_h|/(2^p − 1) with
    /// Δ_h = φ(a − 1, b − 1) − φ(a, b − 1), is known from the family's
    /// other runs. The floor is computed as if the finest run gave
    /// φ(a, b − 1) (a Δt part of zero), the least it can be. Exact: a
    /// candidate this excludes is never met, so the skipped run (half the
    /// check's cost) changes no point's outcome. Only once a candidate has
    /// a u_num: a point not met still reports a bar.
    fn hopeless(&self, k: Key) -> bool {
        match (self.staged, self.least_u(k)) {
            (Some(eps), Some(least)) => least > eps,
            _ => false,
        }
    }

    /// The least u_num candidate `k` can have, from its family's runs but
    /// the finest ([`Point::hopeless`]); None before any candidate has a
    /// u_num, or when a run it needs is missing or undefined.
    fn least_u(&self, k: Key) -> Option<f64> {
        self.staged?;
        if !self.candidates.iter().any(|c| c.1.u_num.is_some()) {
            return None;
        }
        let v = |f: Key| self.value(f).flatten();
        let [c, m, _] = family(k);
        let ([Some(d0), Some(d1)], [Some(s0), Some(s1)]) =
            ([v(c), v(m)], [v((k.0 - 1, k.1 - 2)), v((k.0, k.1 - 1))])
        else {
            return None;
        };
        let least = [Some(d0), Some(d1), Some(s1)];
        split_floor(&least, &[Some(s0), Some(s1)], RATIO as f64)
    }
}

/// Run (or resume) the points `todo` of an accuracy-targeted sweep; each
/// finished record is handed to `save` (and counted by it).
///
/// A queue, not rounds: every worker takes the costliest job waiting (a
/// batch of runs that share their matrix or basis), and the moment a
/// point has the runs its stage needs it moves on and queues its next
/// ones. Points are admitted [`CHUNK`] at a time whenever fewer jobs wait
/// than there are workers, so no worker waits for a slow run of another
/// point (rounds of a chunk waited for each round's slowest run: the 9 × 9
/// subgrid of the Fig. 12 map kept 1.63 of 2 vCPUs busy, AMD EPYC).
///
/// The points' runs go through one queue ([`run_points`]): a worker takes
/// the costliest job waiting (runs that share their effective matrix or
/// modal basis, stepped together, `--batch`), and a point moves on the
/// moment its stage's runs are in, queuing its next ones; points are
/// admitted [`CHUNK`] at a time as the queue runs low. Each point's
/// numbers depend on its scene alone (a batch gives a run's own bits), so
/// the records are the same whatever the order, threads or batch width; a
/// finished point is saved at once (resumable).
pub(super) fn run_points(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    todo: &[usize],
    batch: BatchWidth,
    save: &(dyn Fn(SweepRecord) -> Result<()> + Sync),
) -> Result<()> {
    run_points_with(spec, base, id, todo, batch, false, &|f: Finished| {
        save(f.record)
    })
}

/// A finished point: its record and, for a point run alone, its detail.
pub(crate) struct Finished {
    /// The point's record (as `runs/NNNNNN.json` holds it).
    pub(crate) record: SweepRecord,
    /// What a point run alone adds (`run --tolerance`).
    pub(crate) detail: Option<Detail>,
}

/// What `run --tolerance` reports beyond a sweep point's record: the
/// reported run itself, every run made, a bar on every result, and the
/// error that stopped the point (if one did).
pub(crate) struct Detail {
    /// The reported run's scene and output (none when the point stopped).
    pub(crate) chosen: Option<(Resolved, RunOutput)>,
    /// Every target at the reported run, assessed on its family.
    pub(crate) results: Vec<(&'static Quantity, Assessment)>,
    /// The error of a run or scene that stopped the point.
    pub(crate) error: Option<Error>,
}

/// One run a point made (a row of `accuracy.csv`, an entry of a sweep
/// point's `runs_made`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunMade {
    /// a of N₀·2^a (J₀·2^a on a modal basis).
    pub mesh_exponent: i32,
    /// b of Δt₀/2^b.
    pub step_exponent: i32,
    /// Elements N.
    pub elements: usize,
    /// Modes J on a modal basis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Time step, s.
    pub dt: f64,
    /// The quantity's value (null when undefined).
    pub value: Option<f64>,
    /// Unknowns × steps.
    pub dof_steps: f64,
    /// u_num when the run ends a candidate's family (null otherwise, or
    /// when none could be given).
    pub u_num: Option<f64>,
    /// CPU seconds of the run (its share of its batch's; absent without a
    /// thread clock).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_seconds: Option<f64>,
    /// Why the run was made.
    pub role: RunRole,
}

/// Why a point made a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunRole {
    /// One of the five pilots around the point's own resolution.
    Pilot,
    /// A run of a check's family after the pilots.
    Check,
    /// A met candidate's run at half its Δt (a quantity that is not smooth).
    Confirm,
    /// The run whose results are reported.
    Reported,
}

impl RunRole {
    /// The role as written in `accuracy.csv`.
    pub fn name(self) -> &'static str {
        match self {
            RunRole::Pilot => "pilot",
            RunRole::Check => "check",
            RunRole::Confirm => "confirm",
            RunRole::Reported => "reported",
        }
    }
}

/// Run the points `todo` ([`run_points`]), each finished point handed to
/// `save`; with `keep`, each with its [`Detail`].
pub(crate) fn run_points_with(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    todo: &[usize],
    batch: BatchWidth,
    keep: bool,
    save: &(dyn Fn(Finished) -> Result<()> + Sync),
) -> Result<()> {
    let tol = spec.tolerance.as_ref().expect("an accuracy-targeted sweep");
    let workers = rayon::current_num_threads().max(1);
    let queue = Mutex::new(Queue {
        points: Vec::new(),
        pending: Vec::new(),
        running: 0,
        admitted: 0,
        stop: None,
    });
    let wake = Condvar::new();
    let ctx = Ctx {
        spec,
        base,
        id,
        todo,
        tol,
        batch,
        workers,
        keep,
        save,
    };
    rayon::scope(|s| {
        for _ in 0..workers {
            s.spawn(|_| work(&ctx, &queue, &wake));
        }
    });
    let q = queue.into_inner().unwrap_or_else(|e| e.into_inner());
    match q.stop {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// What every worker shares, read-only.
struct Ctx<'a> {
    spec: &'a SweepSpec,
    base: Option<&'a Table>,
    id: &'a str,
    todo: &'a [usize],
    tol: &'a SweepTolerance,
    batch: BatchWidth,
    workers: usize,
    /// A point run alone (`run --tolerance`): keep every target's value and
    /// the candidates' runs, and hand back the point's [`Detail`].
    keep: bool,
    save: &'a (dyn Fn(Finished) -> Result<()> + Sync),
}

/// Runs that may step together ([`crate::integrate::batch_key`]), waiting
/// or running: (point slot, key, scene) each.
struct Job {
    key: Option<crate::integrate::BatchKey>,
    cap: usize,
    members: Vec<(usize, Key, Resolved)>,
    cost: f64,
}

/// The sweep's state, behind one lock.
struct Queue {
    /// The admitted points by slot; `None` once saved.
    points: Vec<Option<Point>>,
    /// Jobs waiting for a worker.
    pending: Vec<Job>,
    /// Jobs being stepped.
    running: usize,
    /// Points of `todo` admitted so far.
    admitted: usize,
    /// Why the sweep stops early (an interruption, a record not saved).
    stop: Option<Error>,
}

impl Queue {
    /// Queue a run of point `slot`, in a waiting job of its batch key with
    /// room, or a job of its own.
    fn push(&mut self, ctx: &Ctx, slot: usize, key: Key, sc: Resolved) {
        let w = match ctx.batch {
            BatchWidth::Fixed(b) => b,
            BatchWidth::Auto => auto_lanes(&sc),
        };
        let bk = batch_key(&sc).filter(|_| w > 1);
        let cost = run_dof_steps(&sc);
        if let Some(k) = &bk
            && let Some(job) = self
                .pending
                .iter_mut()
                .find(|j| j.key.as_ref() == Some(k) && j.members.len() < j.cap)
        {
            job.members.push((slot, key, sc));
            job.cost += cost;
            return;
        }
        self.pending.push(Job {
            cap: if bk.is_some() { w } else { 1 },
            key: bk,
            members: vec![(slot, key, sc)],
            cost,
        });
    }

    /// Queue what point `slot` needs next; a point done is taken out and
    /// its record returned for saving.
    fn next_of(&mut self, ctx: &Ctx, slot: usize) -> Option<Finished> {
        let point = self.points[slot].as_mut().expect("a point in flight");
        if !point.failed.is_empty() {
            if !point.queued.is_empty() {
                return None;
            }
            let at = (0..point.failed.len())
                .min_by_key(|&i| coarsest_first(point.failed[i].0))
                .expect("a failed run");
            let (k, e) = point.failed.swap_remove(at);
            point.failed.clear();
            fail(point, ctx.spec, ctx.id, k, e);
        }
        advance(point, ctx.tol);
        let mut wants = Vec::new();
        let mut refused = Vec::new();
        for k in point.wants() {
            // a run already queued or running for this point is not asked twice
            if point.queued.contains(&k) {
                continue;
            }
            match point.scene(k) {
                Ok(sc) => wants.push((k, sc)),
                Err(e) => refused.push((k, e)),
            }
        }
        for (k, e) in refused {
            fail(point, ctx.spec, ctx.id, k, e);
        }
        if matches!(point.stage, Stage::Done) {
            if point.queued.is_empty() {
                let p = self.points[slot].take().expect("in flight");
                return finished(p, ctx);
            }
            return None;
        }
        point.queued.extend(wants.iter().map(|(k, _)| *k));
        for (k, sc) in wants {
            self.push(ctx, slot, k, sc);
        }
        None
    }

    /// Admit the next [`CHUNK`] points when fewer jobs wait than workers;
    /// the records of points that finish at once (a refused scene).
    fn admit(&mut self, ctx: &Ctx) -> Vec<Finished> {
        let mut done = Vec::new();
        while self.pending.len() < ctx.workers && self.admitted < ctx.todo.len() {
            let end = (self.admitted + CHUNK).min(ctx.todo.len());
            for &i in &ctx.todo[self.admitted..end] {
                let slot = self.points.len();
                self.points.push(Some(start(ctx.spec, ctx.base, ctx.id, i)));
                done.extend(self.next_of(ctx, slot));
            }
            self.admitted = end;
        }
        done
    }
}

/// One worker: take the costliest waiting job, step it, hand its runs to
/// their points and queue what they need next, until every point is saved.
fn work(ctx: &Ctx, queue: &Mutex<Queue>, wake: &Condvar) {
    let lock = || queue.lock().unwrap_or_else(|e| e.into_inner());
    let mut q = lock();
    loop {
        if q.stop.is_some() {
            break;
        }
        let saved = q.admit(ctx);
        if !saved.is_empty() {
            match save_unlocked(ctx, queue, wake, q, saved) {
                Some(g) => q = g,
                None => break,
            }
            continue;
        }
        let Some(at) =
            (0..q.pending.len()).max_by(|&a, &b| q.pending[a].cost.total_cmp(&q.pending[b].cost))
        else {
            if q.running == 0 {
                // nothing waits, nothing runs, every point admitted: done
                wake.notify_all();
                break;
            }
            q = wake.wait(q).unwrap_or_else(|e| e.into_inner());
            continue;
        };
        let job = q.pending.swap_remove(at);
        q.running += 1;
        let stages: Vec<bool> = job
            .members
            .iter()
            .map(|(slot, key, _)| {
                let p = q.points[*slot].as_ref().expect("in flight");
                is_candidate(p, *key)
            })
            .collect();
        let indices: Vec<usize> = job
            .members
            .iter()
            .map(|(slot, ..)| q.points[*slot].as_ref().expect("in flight").index)
            .collect();
        drop(q);
        let results = run_job(ctx, &job, &stages, &indices);
        q = lock();
        q.running -= 1;
        if crate::interrupt::requested() {
            q.stop.get_or_insert(Error::Interrupted);
            wake.notify_all();
            break;
        }
        let mut saved = Vec::new();
        for ((slot, key, _), result) in job.members.iter().zip(results) {
            let point = q.points[*slot].as_mut().expect("in flight");
            point.queued.retain(|k| k != key);
            match result {
                Ok(ran) => point.runs.push(ran),
                Err(e) => point.failed.push((*key, e)),
            }
        }
        let mut slots: Vec<usize> = job.members.iter().map(|m| m.0).collect();
        slots.sort_unstable();
        slots.dedup();
        for slot in slots {
            if q.points[slot].is_some() {
                saved.extend(q.next_of(ctx, slot));
            }
        }
        wake.notify_all();
        if !saved.is_empty() {
            match save_unlocked(ctx, queue, wake, q, saved) {
                Some(g) => q = g,
                None => break,
            }
        }
    }
}

/// Save finished records with the lock released; the lock again, or None
/// when a save failed (the sweep stops with that error, the workers woken).
fn save_unlocked<'a>(
    ctx: &Ctx,
    queue: &'a Mutex<Queue>,
    wake: &Condvar,
    q: MutexGuard<'a, Queue>,
    saved: Vec<Finished>,
) -> Option<MutexGuard<'a, Queue>> {
    drop(q);
    let r = saved.into_iter().try_for_each(|r| (ctx.save)(r));
    let mut q = queue.lock().unwrap_or_else(|e| e.into_inner());
    match r {
        Ok(()) => Some(q),
        Err(e) => {
            q.stop.get_or_insert(e);
            wake.notify_all();
            None
        }
    }
}

/// A point at its own resolution, or its record when its scene is refused.
fn start(spec: &SweepSpec, base: Option<&Table>, id: &str, index: usize) -> Point {
    let mut p = Point {
        index,
        base: None,
        level: None,
        runs: Vec::new(),
        stage: Stage::Pilot,
        checks: 0,
        base_cost: 0.0,
        candidates: Vec::new(),
        record: None,
        queued: Vec::new(),
        prediction: Prediction::Unknown,
        not_met: None,
        reported: None,
        error: None,
        staged: spec
            .tolerance
            .as_ref()
            .filter(|t| !t.spec().smooth)
            .map(|t| t.tolerance),
        confirmed: Vec::new(),
        unmade: None,
        failed: Vec::new(),
    };
    match spec.resolve_with(base, index) {
        Ok(sc) => {
            p.level = Some(Level::of(&sc));
            p.base_cost = run_dof_steps(&sc);
            p.base = Some(sc);
        }
        Err(e) => {
            p.record = Some(record_of(spec, base, id, index, None, Err(&e)));
            p.error = Some(e);
            p.stage = Stage::Done;
        }
    }
    p
}

/// The order of runs coarsest first: by the refinements' sum, then the mesh's.
fn coarsest_first(k: Key) -> (i32, i32) {
    (k.0 + k.1, k.0)
}

/// A point whose run (or its scene) failed: its record carries the error.
fn fail(p: &mut Point, spec: &SweepSpec, id: &str, key: Key, e: Error) {
    if matches!(p.stage, Stage::Done) {
        return;
    }
    let run = format!("--tolerance's run {}", describe(p, key));
    // a scene refused at a refined level: the scene's own run is accepted,
    // so say which run it is and why it is made
    let e = match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::invalid(
            field,
            value,
            format!(
                "{allowed} (in {run}, which --tolerance makes to measure convergence: every run of its families must be accepted, so give values that hold 2 and 4 times finer and coarser in mesh and step)"
            ),
        ),
        other => other.in_run(&run),
    };
    let mut record = record_of(spec, None, id, p.index, None, Err(&e));
    // the work the point took before it stopped
    record.dof_steps = Some(p.spent());
    record.cpu_seconds = p.cpu();
    p.record = Some(record);
    p.error = Some(e);
    p.stage = Stage::Done;
}

fn describe(p: &Point, k: Key) -> String {
    match (p.level, &p.base) {
        (Some(l), Some(b)) => format!(
            "at {} = {}·2^{}, Δt = {:e} s·2^{}",
            l.symbol(),
            l.start(),
            k.0,
            b.dt,
            -k.1
        ),
        _ => format!("{k:?}"),
    }
}

/// A run's record is kept when it may be reported: the point's own
/// resolution (0, 0) and the last run of a check's family.
fn is_candidate(p: &Point, key: Key) -> bool {
    key == (0, 0)
        || matches!(p.stage, Stage::Check(k) if k == key)
        || matches!(p.stage, Stage::Confirm(k) if confirm_key(k) == key)
}

/// Step a job's runs together (one batch; a run alone when the job has
/// one), each reduced at once to Q's value, its cost and (for a
/// candidate, `keep`) the point's record. A panic inside makes every run
/// of the job an error (none of them is trusted), never a stuck sweep.
fn run_job(ctx: &Ctx, job: &Job, keep: &[bool], indices: &[usize]) -> Vec<Result<Ran>> {
    let q = ctx.tol.spec();
    let go = || {
        let scenes: Vec<Resolved> = job.members.iter().map(|m| m.2.clone()).collect();
        let (outs, cpu) = timed(|| run_batch(&scenes, job.cap, &mut |_| {}));
        let work: Vec<f64> = outs
            .iter()
            .map(|o| o.as_ref().map_or(0.0, |o| o.dofs as f64 * o.steps as f64))
            .collect();
        job.members
            .iter()
            .zip(outs.into_iter().zip(shares(cpu, &work)))
            .enumerate()
            .map(|(m, ((_, key, sc), (out, cpu)))| {
                out.map(|out| {
                    let record = keep[m].then(|| {
                        record_of(ctx.spec, ctx.base, ctx.id, indices[m], Some(sc), Ok(&out))
                    });
                    let mut ran = reduce(q, *key, &out, cpu, record);
                    if ctx.keep {
                        ran.values = super::targets().iter().map(|t| t.of(&out, 0)).collect();
                        ran.output = keep[m].then_some(out);
                    }
                    ran
                })
            })
            .collect::<Vec<_>>()
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(go)).unwrap_or_else(|payload| {
        let what = panic_message(payload.as_ref());
        job.members
            .iter()
            .map(|_| {
                Err(Error::invalid(
                    "--tolerance",
                    "a run",
                    format!(
                        "internal error (a panic in taut, please report it), in a batch of {} runs: {what}",
                        job.members.len()
                    ),
                ))
            })
            .collect()
    })
}

/// A run reduced to what the point keeps.
fn reduce(
    q: &Quantity,
    key: Key,
    out: &RunOutput,
    cpu: Option<f64>,
    record: Option<SweepRecord>,
) -> Ran {
    Ran {
        key,
        value: q.of(out, 0),
        dof_steps: out.dofs as f64 * out.steps as f64,
        cpu,
        loss: engine::switches(out),
        record,
        values: Vec::new(),
        output: None,
    }
}

/// Move a point on once it has the runs its stage needs.
fn advance(p: &mut Point, tol: &SweepTolerance) {
    if matches!(p.stage, Stage::Done) || !p.wants().is_empty() {
        return;
    }
    let q = tol.spec();
    let key = match p.stage {
        Stage::Pilot => (0, 0),
        Stage::Check(k) => k,
        Stage::Confirm(k) => return confirm(p, tol, k),
        Stage::Done => return,
    };
    let formal = formal_of(p, q, key);
    // a check whose finest run was not made (`Point::hopeless`) missed
    // without an assessment
    if p.value(key).is_none() {
        p.unmade = p.least_u(key).map(|u| (key, u));
    } else {
        p.unmade = None;
        let a = assess_at(p, q, key, |r| r.value);
        let u = a.u_num.unwrap_or(f64::INFINITY);
        // a smooth quantity whose differences grow (3·Δ_M, `data_range`)
        // has not converged, and no confirmation follows a smooth one: a
        // bar within EPS does not end its refinement
        let growing = q.smooth && a.estimator == Estimator::DataRange;
        p.candidates.push((key, a));
        if u <= tol.tolerance && !growing {
            return met(p, tol, key);
        }
    }
    refine(p, tol, key, formal, matches!(p.stage, Stage::Pilot));
}

/// Candidate `key` missed EPS: the next check (the plan's after the
/// pilots, `from_pilots`; else one level on both), cut down to the budget,
/// or the point stops with its candidate of smallest u_num, not met.
fn refine(p: &mut Point, tol: &SweepTolerance, key: Key, formal: (f64, f64), from_pilots: bool) {
    let next = match from_pilots {
        true => {
            p.prediction = predict(p, tol, formal);
            // refinement that knows when to stop: a point the model puts
            // beyond its budget is not refined to find out (a smooth
            // quantity's: see `beyond_budget`)
            if let Some(why) = beyond_budget(p.prediction, tol) {
                p.not_met = Some(why);
                return finish_best(p, tol, key);
            }
            plan(p, tol, formal)
        }
        false => {
            // and a check that missed: the walk down the diagonal
            // predicted from how u_num fell since the last candidate
            p.prediction = predict_walk(p, tol, key);
            if let Some(why) = beyond_budget(p.prediction, tol) {
                p.not_met = Some(why);
                return finish_best(p, tol, key);
            }
            (key.0 + 1, key.1 + 1)
        }
    };
    let mut next = (next.0.min(MAX_EXPONENT), next.1.min(MAX_EXPONENT));
    let wanted = next;
    // within the budget: the plan cut down, the larger refinement first,
    // so a point out of reach still gets as close as its budget allows
    // a scene the model refuses (J beyond the exact modes' range) is out of
    // reach like one beyond the budget
    let fits = |p: &Point, k: Key| {
        p.spent() + check_cost(p, k) <= tol.budget * p.base_cost
            && check_runs(k)
                .iter()
                .all(|&f| p.value(f).is_some() || p.scene(f).is_ok())
    };
    while !fits(p, next) {
        if next.0 >= next.1 && next.0 > key.0 {
            next.0 -= 1;
        } else if next.1 > key.1 {
            next.1 -= 1;
        } else if next.0 > key.0 {
            next.0 -= 1;
        } else {
            break;
        }
    }
    let refines = next.0 > key.0 || next.1 > key.1;
    let affordable = fits(p, next);
    if !refines || !affordable || p.checks >= MAX_CHECKS {
        let mut why = if p.checks >= MAX_CHECKS {
            format!("{MAX_CHECKS} checks after the pilots did not reach it")
        } else {
            format!(
                "its budget (--max-cost {}) allows no further refinement",
                tol.budget
            )
        };
        why.push_str(&stopped_because(p, wanted));
        p.not_met = Some(why);
        return finish_best(p, tol, key);
    }
    p.checks += 1;
    p.stage = Stage::Check(next);
}

/// What a point not met adds to why it stopped: a finer level its scene
/// refuses (J beyond the exact modes' range, say) on the way to the check
/// it `wanted`, and the last check whose finest run was not made, with the
/// least u_num that check could have given.
fn stopped_because(p: &Point, wanted: Key) -> String {
    let mut s = String::new();
    if let Some(e) = check_runs(wanted)
        .iter()
        .filter(|&&f| p.value(f).is_none())
        .find_map(|&f| p.scene(f).err())
    {
        s.push_str(&match e {
            Error::Invalid {
                field,
                value,
                allowed,
            } => format!("; a finer level is out of range (`{field}` = {value}: {allowed})"),
            other => format!("; a finer level is refused ({other})"),
        });
    }
    if let Some((k, u)) = p.unmade {
        let at = match (p.level, p.scene(k)) {
            (Some(l), Ok(sc)) => format!(
                " ({} = {}, Δt = {:e} s)",
                l.symbol(),
                sc.discretization.modes().unwrap_or(sc.elements),
                sc.dt
            ),
            _ => String::new(),
        };
        s.push_str(&format!(
            "; its last check{at} did not make its finest run, as u_num is at least {u:.3e} without it"
        ));
    }
    s
}

/// A candidate within EPS: done, or, when Q is not smooth and the
/// candidate has something to confirm (u_num above zero, its family not
/// all 0), confirmed by one
/// run at half its Δt first ([`confirm`]).
fn met(p: &mut Point, tol: &SweepTolerance, key: Key) {
    let u = p.candidates.last().and_then(|c| c.1.u_num).unwrap_or(0.0);
    // a family all 0 has moved nowhere: its bar is the floor of what its
    // finest Δt cannot see ([`engine::unseen_loss_floor`]), not a change to confirm
    let runs = check_runs(key).map(|k| p.value(k).flatten());
    if p.staged.is_some() && u > 0.0 && !engine::all_zero(&runs, &[]) {
        p.stage = Stage::Confirm(key);
    } else {
        finish(p, tol, key);
    }
}

/// Candidate `k` confirmed by its run at half its Δt, `c` = (a, b + 1):
/// the point reports `c`'s value with u_num at least [`FS_CAUTIOUS`] times
/// the change |φ(c) − φ(k)| ([`confirmed`]). Measured on the Fig. 12 map
/// (9 × 9 subgrid against J = 3200, Δt = 3.9e-6 s): P_l,span keeps moving
/// below a family's finest Δt, one way (it rises as Δt falls), and the
/// family's u_num missed that at 7 of the 33 points met; the run one Δt
/// finer moved 15 of 15 met points towards the reference, and the bar so
/// widened covered each. Still within EPS: met at `c`; else the walk goes
/// on from `k` as from a check that missed ([`refine`]).
fn confirm(p: &mut Point, tol: &SweepTolerance, k: Key) {
    let c = confirm_key(k);
    let at = p
        .candidates
        .iter()
        .rposition(|x| x.0 == k)
        .expect("a confirmed candidate");
    let a = confirmed(
        &p.candidates[at].1,
        p.value(k).flatten(),
        p.value(c).flatten(),
    );
    let u = a.u_num.unwrap_or(f64::INFINITY);
    p.candidates[at] = (c, a);
    p.confirmed.push(k);
    if u <= tol.tolerance {
        return finish(p, tol, c);
    }
    // moved beyond EPS: the candidate missed, and the walk goes on as from
    // any check that missed (the plan when it was the pilots'), so a point
    // a finer family meets is met
    let formal = formal_of(p, tol.spec(), k);
    refine(p, tol, k, formal, k == (0, 0))
}

/// A candidate's assessment `a` (value `at`) carried to its run at half
/// its Δt (value `half`): that run's value, u_num at least [`FS_CAUTIOUS`]
/// × |half − at| (the split floor's Δt part for the last halving, carried
/// at order 1: what is left below that Δt is no smaller than the change
/// the halving made, and F_s = 3 as for any part of a quantity that is
/// not smooth). None when either value is undefined.
fn confirmed(a: &Assessment, at: Option<f64>, half: Option<f64>) -> Assessment {
    let mut a = a.clone();
    let (Some(at), Some(half), Some(u)) = (at, half, a.u_num) else {
        a.value = half;
        a.u_num = None;
        a.note = "undefined at half the candidate's Δt".to_string();
        return a;
    };
    let change = (half - at).abs();
    a.value = Some(half);
    a.u_num = Some(u.max(FS_CAUTIOUS * change));
    a.extrapolated = None;
    a.error = None;
    let why = format!(
        "at half the candidate's Δt, which moved it by {change:.3e}: u_num at least {FS_CAUTIOUS} times that"
    );
    a.add_note(why);
    a
}

/// Q's formal orders in space and time on the point's scene, for the
/// family ending at `key` ([`engine::formal_on`]).
fn formal_of(p: &Point, q: &Quantity, key: Key) -> (f64, f64) {
    let base = p.base.as_ref().expect("a point being worked has its scene");
    engine::formal_on(base, q, family_switches(p, key))
}

/// Whether a contact opens or closes in a run of the family ending at
/// `key`: the same family `taut uncertainty` would run from its start.
fn family_switches(p: &Point, key: Key) -> bool {
    let keys = check_runs(key);
    p.runs.iter().any(|r| r.loss && keys.contains(&r.key))
}

/// `q`'s assessment on the family ending at `key` ([`check_runs`]: the
/// pilots at (0, 0)), its values read off each run by `value`.
fn assess_at(p: &Point, q: &Quantity, key: Key, value: impl Fn(&Ran) -> Option<f64>) -> Assessment {
    let at = |keys: &[Key]| -> Vec<Option<f64>> {
        keys.iter()
            .map(|&k| p.runs.iter().find(|r| r.key == k).and_then(&value))
            .collect()
    };
    let keys = check_runs(key);
    let (diag, split) = (at(&keys[..3]), at(&keys[3..]));
    let base = p.base.as_ref().expect("a point being worked has its scene");
    // the one assessment `taut uncertainty` makes of the same family
    let a = engine::assess_family(base, q, &diag, &split, family_switches(p, key));
    match p.scene(key) {
        Ok(sc) => engine::unseen_loss_floor(a, q, &diag, &split, sc.dt, sc.t_end),
        _ => a,
    }
}

/// A finished point as handed to `save`; with `ctx.keep`, its [`Detail`].
fn finished(mut p: Point, ctx: &Ctx) -> Option<Finished> {
    let record = p.record.take()?;
    let detail = ctx.keep.then(|| detail(&mut p));
    Some(Finished { record, detail })
}

/// What a point run alone reports beyond its record.
fn detail(p: &mut Point) -> Detail {
    let reported = p.reported;
    let chosen = reported.and_then(|k| {
        let out = p.runs.iter_mut().find(|r| r.key == k)?.output.take()?;
        Some((p.scene(k).ok()?, out))
    });
    let results = match reported {
        Some(k) => super::targets()
            .into_iter()
            .enumerate()
            .map(|(i, q)| {
                let of = |r: &Ran| r.values.get(i).copied().flatten();
                let val = |k: Key| p.runs.iter().find(|r| r.key == k).and_then(of);
                // a confirmed point: every result carried to the run at half
                // the candidate's Δt as Q's is
                let a = match p.confirmed.iter().find(|&&f| confirm_key(f) == k) {
                    Some(&from) => confirmed(&assess_at(p, q, from, of), val(from), val(k)),
                    None => assess_at(p, q, k, of),
                };
                (q, a)
            })
            .collect(),
        None => Vec::new(),
    };
    Detail {
        chosen,
        results,
        error: p.error.take(),
    }
}

/// Every run point `p` made, coarsest first (the queue's order is the
/// workers' and not the point's), each with its role and, when it ends a
/// candidate's family, that candidate's u_num.
fn runs_made(p: &Point) -> Vec<RunMade> {
    let u_of = |k: Key| {
        p.candidates
            .iter()
            .rfind(|c| c.0 == k)
            .and_then(|c| c.1.u_num)
    };
    let mut runs: Vec<RunMade> = p
        .runs
        .iter()
        .map(|r| {
            let sc = p.scene(r.key).ok();
            RunMade {
                mesh_exponent: r.key.0,
                step_exponent: r.key.1,
                elements: sc.as_ref().map_or(0, |s| s.elements),
                modes: sc.as_ref().and_then(|s| s.discretization.modes()),
                dt: sc.as_ref().map_or(f64::NAN, |s| s.dt),
                value: r.value,
                dof_steps: r.dof_steps,
                u_num: u_of(r.key),
                cpu_seconds: r.cpu,
                role: if Some(r.key) == p.reported {
                    RunRole::Reported
                } else if PILOTS.contains(&r.key) {
                    RunRole::Pilot
                } else if p.confirmed.iter().any(|&k| confirm_key(k) == r.key) {
                    RunRole::Confirm
                } else {
                    RunRole::Check
                },
            }
        })
        .collect();
    runs.sort_by_key(|r| coarsest_first((r.mesh_exponent, r.step_exponent)));
    runs
}

/// Why a point is not refined further: the model puts reaching EPS above
/// its budget, or out of any scene it takes; `None` to go on.
///
/// Only a smooth quantity's prediction stops a point. Measured on the
/// accuracy-targeted Fig. 12 map (41 × 41, P_l,span, EPS = 0.002): stopping
/// every point the pilots' model or the u_num walk put beyond the budget
/// saved 31 % of the DOF-steps but lost 41 of the 700 points met, each met
/// at the next check. P_l's coarse families are pre-asymptotic and its
/// u_num can fall 25× in one level once its family turns monotone, so a
/// prediction from them is too pessimistic to act on: it is recorded
/// (`predicted_cost`), and the point is refined within its budget.
fn beyond_budget(prediction: Prediction, tol: &SweepTolerance) -> Option<String> {
    if !tol.spec().smooth {
        return None;
    }
    match prediction {
        Prediction::Cost(c) if c > tol.budget => Some(format!(
            "predicted cost {c:.0}× its own run to reach the tolerance, above --max-cost {}",
            tol.budget
        )),
        Prediction::OutOfReach => Some(
            "predicted out of reach: no resolution the model takes (J within the exact modes' range, 2^20 times the point's own at most) reaches the tolerance"
                .to_string(),
        ),
        _ => None,
    }
}

/// Finish a point with its candidate of smallest u_num (`key` when it has
/// none measured).
fn finish_best(p: &mut Point, tol: &SweepTolerance, key: Key) {
    let best = p
        .candidates
        .iter()
        .min_by(|x, y| {
            let u = |a: &Assessment| a.u_num.unwrap_or(f64::INFINITY);
            u(&x.1).total_cmp(&u(&y.1))
        })
        .map(|c| c.0)
        .unwrap_or(key);
    finish(p, tol, best)
}

/// The error model of the pilots' split: the mesh ladder at a fixed Δt and
/// the Δt ladder on a fixed mesh, relative h and Δt (the point's own are 1).
fn pilot_model(p: &Point, tol: &SweepTolerance, formal: (f64, f64)) -> ErrorModel {
    let v = |k: Key| p.value(k).flatten().unwrap_or(f64::NAN);
    // mesh refined at a fixed Δt, Δt refined on a fixed mesh
    let dx = [v((-2, -2)) - v((-1, -2)), v((-1, -1)) - v((0, -1))];
    let dt = [v((-1, -2)) - v((-1, -1)), v((0, -1)) - v((0, 0))];
    let scale = [v((0, 0)), v((-1, -1))]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(tol.tolerance);
    let mesh = LadderFit::new(dx.map(f64::abs), 1.0, scale, formal.0);
    let step = LadderFit::new(dt.map(f64::abs), 1.0, scale, formal.1);
    ErrorModel::new(mesh, step)
}

/// The coarsest (a, b) at or below relative (h, Δt).
fn key_at(h: f64, dt: f64) -> Key {
    let up = |x: f64| (-x.log2() - 1e-9).ceil().max(0.0) as i32;
    (up(h), up(dt))
}

/// The cost of a check at `k` still to be run, in unknowns × steps.
fn check_cost(p: &Point, k: Key) -> f64 {
    check_runs(k)
        .iter()
        .filter(|&&f| p.value(f).is_none())
        .map(|f| p.base_cost * (RATIO as f64).powi(f.0 + f.1))
        .sum()
}

/// The furthest exponent a prediction looks: 2²⁰ times the point's own
/// resolution in one variable is beyond any budget.
const PREDICT_EXPONENT: i32 = 20;

/// What the pilots' error model predicts it costs the point to reach EPS,
/// as a multiple of its own run, pilots included: the cheapest (h, Δt)
/// whose modelled error is within EPS × F_s,asymptotic / F_s,cautious (a
/// quantity that is not smooth gets the cautious factor on its u_num),
/// and its check family. Infinite when that scene is not one the model
/// takes (J beyond the exact modes' range); unknown when a ladder does
/// not converge (the model cannot say).
fn predict(p: &Point, tol: &SweepTolerance, formal: (f64, f64)) -> Prediction {
    let model = pilot_model(p, tol, formal);
    let Some((h, d)) = model.cheapest(tol.tolerance * FS_ASYMPTOTIC / FS_CAUTIOUS, 1.0, 1.0) else {
        return Prediction::Unknown;
    };
    let k = key_at(h, d);
    let k = if k == (0, 0) { (1, 1) } else { k };
    if k.0 > PREDICT_EXPONENT
        || k.1 > PREDICT_EXPONENT
        || !check_runs(k)
            .iter()
            .all(|&f| p.value(f).is_some() || p.scene(f).is_ok())
    {
        return Prediction::OutOfReach;
    }
    Prediction::Cost((p.spent() + check_cost(p, k)) / p.base_cost)
}

/// What walking on down the diagonal from a check at `key` that missed
/// costs to reach EPS, predicted from the last two candidates: u_num fell
/// by r per diagonal level between them, so m = ⌈ln(EPS/u)/ln r⌉ more
/// levels reach it, each a check family (runs made already reused).
/// Unknown when u_num did not fall (or was not measured): the walk goes on
/// one level as before; out of reach when the walk leaves the scenes the
/// model takes.
fn predict_walk(p: &Point, tol: &SweepTolerance, key: Key) -> Prediction {
    let [.., (k0, a0), (k1, a1)] = p.candidates.as_slice() else {
        return Prediction::Unknown;
    };
    let (Some(u0), Some(u1)) = (a0.u_num, a1.u_num) else {
        return Prediction::Unknown;
    };
    let levels = (k1.0 - k0.0).max(k1.1 - k0.1).max(1);
    let r = (u1 / u0).powf(1.0 / levels as f64);
    let eps = tol.tolerance;
    if !(r < 1.0 && r > 0.0 && u1 > eps) {
        return Prediction::Unknown;
    }
    let m = ((eps / u1).ln() / r.ln()).ceil().max(1.0);
    if m > PREDICT_EXPONENT as f64 {
        return Prediction::OutOfReach;
    }
    let mut run: Vec<Key> = p.runs.iter().map(|r| r.key).collect();
    let mut cost = p.spent();
    for j in 1..=m as i32 {
        let k = (key.0 + j, key.1 + j);
        for f in check_runs(k) {
            if run.contains(&f) {
                continue;
            }
            if p.scene(f).is_err() {
                return Prediction::OutOfReach;
            }
            cost += p.base_cost * (RATIO as f64).powi(f.0 + f.1);
            run.push(f);
        }
    }
    Prediction::Cost(cost / p.base_cost)
}

/// The first check's (a, b): the error model's cheapest (h, Δt) for
/// [`PLAN_SHARE`] × EPS from the split's differences, as the coarsest
/// powers of two at or below it; one level on both when a ladder does not
/// converge.
fn plan(p: &Point, tol: &SweepTolerance, formal: (f64, f64)) -> Key {
    match pilot_model(p, tol, formal).cheapest(PLAN_SHARE * tol.tolerance, 1.0, 1.0) {
        // relative h and Δt: the point's own are 1
        Some((h, d)) => {
            let k = key_at(h, d);
            if k == (0, 0) { (1, 1) } else { k }
        }
        None => (1, 1),
    }
}

/// A candidate's error is mostly Δt's when its split gives space less than
/// this share of it (the rest is Δt's).
const SPACE_SHARE_MINORITY: f64 = 0.5;

/// What a point of P_l (or its in-span part) not met adds to why, when
/// its candidate's error is mostly Δt's ([`SPACE_SHARE_MINORITY`]) under a
/// force-level law: the bounces after a re-contact move P_l with Δt
/// (docs/contact_loss.md §3), which its sustained part leaves out. Under
/// the impact law (`sc`'s formulation) a re-contact does not bounce by the
/// step's timing, so the hint would mislead.
fn bounce_hint(q: &Quantity, space_share: Option<f64>, sc: Option<&Resolved>) -> &'static str {
    let loss = [&LOSS_FRACTION, &LOSS_FRACTION_SPAN]
        .iter()
        .any(|l| l.name == q.name);
    let impact = sc.is_some_and(|s| s.contact.formulation == crate::scene::Formulation::Impact);
    if loss && !impact && space_share.is_some_and(|s| s < SPACE_SHARE_MINORITY) {
        "; its error is mostly Δt's: the bounces after a re-contact move P_l with Δt (docs/contact_loss.md §3), which --quantity loss_fraction_span_sustained leaves out"
    } else {
        ""
    }
}

/// Finish a point with candidate `key`: its record and accuracy.
fn finish(p: &mut Point, tol: &SweepTolerance, key: Key) {
    let a = p
        .candidates
        .iter()
        .rfind(|c| c.0 == key)
        .map(|c| c.1.clone())
        .expect("a candidate");
    let run = p
        .runs
        .iter()
        .find(|r| r.key == key && r.record.is_some())
        .expect("a candidate's run keeps its record");
    let mut record = run.record.clone().expect("kept");
    let sc = p.scene(key).ok();
    let u = a.u_num.unwrap_or(f64::NAN);
    let met = u <= tol.tolerance;
    record.accuracy = Some(PointAccuracy {
        value: a.value.unwrap_or(f64::NAN),
        u_num: u,
        met,
        elements: sc.as_ref().map_or(0, |s| s.elements),
        modes: sc.as_ref().and_then(|s| s.discretization.modes()),
        dt: sc.as_ref().map_or(f64::NAN, |s| s.dt),
        runs: p.runs.len(),
        dof_steps: p.spent(),
        estimator: a.estimator.name().to_string(),
        checks: p.checks,
        predicted_cost: match p.prediction {
            Prediction::Cost(c) => Some(c),
            _ => None,
        },
        not_met: (!met)
            .then(|| {
                let hint = bounce_hint(tol.spec(), a.space_share, sc.as_ref());
                p.not_met.clone().map(|w| w + hint)
            })
            .flatten(),
        u_num_ladder: p.candidates.iter().map(|c| c.1.u_num).collect(),
        runs_made: Vec::new(),
    });
    record.wall_seconds = None;
    record.dof_steps = Some(p.spent());
    record.cpu_seconds = p.cpu();
    p.record = Some(record);
    p.reported = Some(key);
    let runs = runs_made(p);
    if let Some(a) = p.record.as_mut().and_then(|r| r.accuracy.as_mut()) {
        a.runs_made = runs;
    }
    p.stage = Stage::Done;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::uncertainty::assess::{Inputs, assess};

    /// P_l not met, its error mostly Δt's: the bounces are named under the
    /// study's law, not under the impact law (no bounce by the step's
    /// timing there), nor for a quantity other than P_l or a space-led error.
    #[test]
    fn the_bounce_hint_is_the_force_level_laws_only() {
        let scene = |f: &str| {
            let o = [
                "mesh.kind=galerkin".to_string(),
                "mesh.modes=40".to_string(),
                "integrator={ method = \"modal_exact\" }".to_string(),
                format!("contact.formulation={f}"),
            ];
            crate::resolve::resolve_scene(include_str!("../../../scenes/reference.toml"), &o)
                .unwrap()
        };
        let (held, impact) = (scene("lagrange"), scene("impact"));
        let dt_led = Some(SPACE_SHARE_MINORITY / 2.0);
        assert!(bounce_hint(&LOSS_FRACTION_SPAN, dt_led, Some(&held)).contains("bounces"));
        assert_eq!(bounce_hint(&LOSS_FRACTION_SPAN, dt_led, Some(&impact)), "");
        assert_eq!(bounce_hint(&LOSS_FRACTION_SPAN, Some(0.9), Some(&held)), "");
        assert_eq!(
            bounce_hint(&crate::quantity::FORCE_MEAN, dt_led, Some(&held)),
            ""
        );
    }

    /// A family all 0 gets the unseen-loss floor 3 × Δt / t_end; one that
    /// saw a loss keeps its own bar.
    #[test]
    fn a_zero_family_gets_the_unseen_loss_floor() {
        let zero = [Some(0.0); 3];
        let split = [Some(0.0); 2];
        assert!(engine::all_zero(&zero, &split));
        let a = assess(&Inputs {
            diagonal: &zero,
            space: &split,
            ratio: 2.0,
            formal: (2.0, 1.0),
            smooth: false,
        });
        assert_eq!(a.u_num, Some(0.0), "the family alone: no bar");
        let f = engine::unseen_floor(a, 6.25e-5, 0.8276);
        let want = FS_CAUTIOUS * 6.25e-5 / 0.8276;
        assert!((f.u_num.unwrap() - want).abs() < 1e-15 * want.max(1.0));
        assert!(f.note.contains("unseen"));
        // the scene's own bar (level 0) covers as the finest's does
        assert!(
            f.u_levels.iter().all(|u| u.is_some_and(|x| x >= want)),
            "{:?}",
            f.u_levels
        );
        let seen = [Some(0.0), Some(1e-3), Some(1.2e-3)];
        assert!(!engine::all_zero(&seen, &split));
        assert!(!engine::all_zero(&[None, Some(0.0), Some(0.0)], &split));
    }
}
