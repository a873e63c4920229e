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
//!    own run. Q's u_num at (0, 0) ([`assess`]); within EPS: done.
//! 2. **Plan**: `run --tolerance`'s error model from the split's mesh and
//!    Δt differences ([`LadderFit`], [`ErrorModel::cheapest`]) gives the
//!    cheapest (h, Δt) whose modelled error is within [`PLAN_SHARE`] × EPS;
//!    the candidate is the coarsest (a, b) at or below it.
//! 3. **Check**: the candidate's own three-level family, (a − 2, b − 2),
//!    (a − 1, b − 1), (a, b) (runs made already are reused), gives its
//!    u_num. Within EPS: done; else one more level on both (a + 1, b + 1),
//!    up to [`MAX_CHECKS`] checks. Every candidate is cut down, its larger
//!    refinement first, to what the point's budget (`budget` × its own
//!    run, in unknowns × steps) still allows and to scenes the model takes
//!    (J within the exact modes' range). A point that does not reach
//!    EPS keeps the candidate of smallest u_num, marked not met.
//!
//! Points are worked a chunk at a time ([`CHUNK`]): each round gathers
//! every run the chunk's points need next and steps those that share their
//! effective matrix or modal basis together (`--batch`), in parallel. Each
//! point's numbers depend on its scene alone (a batch gives a run's own
//! bits), so the records are the same whatever the chunking, threads or
//! batch width; a finished point is saved at once (resumable).

use rayon::prelude::*;
use toml::Table;

use super::batch::{BatchWidth, auto_lanes};
use super::record::{SweepRecord, record_of};
use super::spec::SweepSpec;
use super::tolerance_spec::{PointAccuracy, SweepTolerance};
use crate::error::{Error, Result};
use crate::integrate::{batch_key, scene_method};
use crate::resolve::Resolved;
use crate::run::{RunOutput, run_batch};
use crate::study::cost::run_dof_steps;
use crate::study::formal_orders::MAX_STEP_ORDER;
use crate::study::level::Level;
use crate::study::tolerance::{ErrorModel, LadderFit};
use crate::study::uncertainty::quantity::QuantitySpec;
use crate::study::uncertainty::{Assessment, FS_ASYMPTOTIC, FS_CAUTIOUS, Inputs, RATIO, assess};

/// Checks after the pilots at most: with one more level on both each, a
/// point may end 2⁵ times finer in h and Δt than the plan's first guess.
pub(crate) const MAX_CHECKS: usize = 3;

/// The share of EPS the plan asks of `run --tolerance`'s model: its
/// estimate carries Roache's 1.25, the check's u_num the 3 of a quantity
/// that is not smooth, and the check adds its fit's scatter, so the plan
/// aims at 1.25/3 of EPS and leaves a fifth of that for the scatter.
pub(crate) const PLAN_SHARE: f64 = FS_ASYMPTOTIC / FS_CAUTIOUS * 0.8;

/// The furthest a plan refines one variable: 2⁵ times the point's own.
pub(crate) const MAX_EXPONENT: i32 = 5;

/// Points worked together: enough for batches of runs that share a matrix
/// or a basis (a 2-D map's row of 41 speeds is one tension), few enough
/// that an interruption loses little.
pub const CHUNK: usize = 128;

type Key = (i32, i32);

const PILOTS: [Key; 5] = [(-2, -2), (-1, -1), (0, 0), (-1, -2), (0, -1)];

fn family(k: Key) -> [Key; 3] {
    [(k.0 - 2, k.1 - 2), (k.0 - 1, k.1 - 1), k]
}

/// One run of a point.
struct Ran {
    key: Key,
    value: Option<f64>,
    dof_steps: f64,
    loss: bool,
    /// The point's record from this run, kept for candidates only.
    record: Option<SweepRecord>,
}

enum Stage {
    Pilot,
    Check(Key),
    Done,
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
}

impl Point {
    fn value(&self, k: Key) -> Option<Option<f64>> {
        self.runs.iter().find(|r| r.key == k).map(|r| r.value)
    }

    fn spent(&self) -> f64 {
        self.runs.iter().map(|r| r.dof_steps).sum()
    }

    fn scene(&self, k: Key) -> Result<Resolved> {
        let (base, level) = (
            self.base
                .as_ref()
                .expect("a point being worked has its scene"),
            self.level.expect("and its level"),
        );
        let n0 = level.start();
        let n = if k.0 >= 0 {
            n0.checked_mul(RATIO.pow(k.0 as u32))
        } else {
            Some(n0 / RATIO.pow((-k.0) as u32))
        }
        .filter(|&n| n > 0)
        .ok_or_else(|| {
            Error::invalid(
                "--tolerance",
                format!("{k:?}"),
                "a level parameter out of range",
            )
        })?;
        let dt = base.dt * (RATIO as f64).powi(-k.1);
        level.variant(n, dt).apply(base)
    }

    /// The keys the point needs next that it has not run.
    fn wants(&self) -> Vec<Key> {
        let keys: Vec<Key> = match self.stage {
            Stage::Pilot => PILOTS.to_vec(),
            Stage::Check(k) => family(k).to_vec(),
            Stage::Done => vec![],
        };
        keys.into_iter()
            .filter(|&k| self.value(k).is_none())
            .collect()
    }
}

/// Run (or resume) the points `todo` of an accuracy-targeted sweep; each
/// finished record is handed to `save` (and counted by it).
pub(super) fn run_points(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    todo: &[usize],
    batch: BatchWidth,
    save: &(dyn Fn(SweepRecord) -> Result<()> + Sync),
) -> Result<()> {
    let tol = spec.tolerance.as_ref().expect("an accuracy-targeted sweep");
    for chunk in todo.chunks(CHUNK) {
        let mut points: Vec<Point> = chunk.iter().map(|&i| start(spec, base, id, i)).collect();
        loop {
            // every run the chunk's points need next, batched and in parallel
            let mut requests: Vec<(usize, Key, Resolved)> = Vec::new();
            let mut refused: Vec<(usize, Key, Error)> = Vec::new();
            for (p, point) in points.iter().enumerate() {
                for k in point.wants() {
                    match point.scene(k) {
                        Ok(sc) => requests.push((p, k, sc)),
                        Err(e) => refused.push((p, k, e)),
                    }
                }
            }
            for (p, k, e) in refused {
                fail(&mut points[p], spec, id, k, e);
            }
            if requests.is_empty() && points.iter().all(|p| matches!(p.stage, Stage::Done)) {
                for point in points.iter_mut() {
                    if let Some(r) = point.record.take() {
                        save(r)?;
                    }
                }
                break;
            }
            let results = run_requests(spec, base, id, tol, &points, &requests, batch);
            if crate::interrupt::requested() {
                return Err(Error::Interrupted);
            }
            for ((p, key, _), result) in requests.iter().zip(results) {
                match result {
                    Ok(ran) => points[*p].runs.push(ran),
                    Err(e) => fail(&mut points[*p], spec, id, *key, e),
                }
            }
            for point in points.iter_mut() {
                advance(point, tol);
                if let (Stage::Done, Some(r)) = (&point.stage, point.record.take()) {
                    save(r)?;
                }
            }
        }
    }
    Ok(())
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
    };
    match spec.resolve_with(base, index) {
        Ok(sc) => {
            p.level = Some(Level::of(&sc));
            p.base_cost = run_dof_steps(&sc);
            p.base = Some(sc);
        }
        Err(e) => {
            p.record = Some(record_of(spec, base, id, index, None, Err(&e)));
            p.stage = Stage::Done;
        }
    }
    p
}

/// A point whose run (or its scene) failed: its record carries the error.
fn fail(p: &mut Point, spec: &SweepSpec, id: &str, key: Key, e: Error) {
    if matches!(p.stage, Stage::Done) {
        return;
    }
    let e = e.in_run(&format!("--tolerance's run {}", describe(p, key)));
    p.record = Some(record_of(spec, None, id, p.index, None, Err(&e)));
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

/// Run the requested runs: those that share a batch key stepped together,
/// every batch in parallel; each run reduced at once to Q's value, its
/// cost and (for a candidate) the point's record.
fn run_requests(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    tol: &SweepTolerance,
    points: &[Point],
    requests: &[(usize, Key, Resolved)],
    width: BatchWidth,
) -> Vec<Result<Ran>> {
    // groups of requests that share their matrix or basis, at most the
    // batch width each
    let mut groups: Vec<(Option<crate::integrate::BatchKey>, usize, Vec<usize>)> = Vec::new();
    for (r, (_, _, sc)) in requests.iter().enumerate() {
        let w = match width {
            BatchWidth::Fixed(b) => b,
            BatchWidth::Auto => auto_lanes(sc),
        };
        let key = batch_key(sc).filter(|_| w > 1).map(|k| (k, w));
        match key {
            Some((k, w)) => match groups
                .iter_mut()
                .find(|(g, cap, m)| g.as_ref() == Some(&k) && m.len() < *cap)
            {
                Some(g) => g.2.push(r),
                None => groups.push((Some(k), w, vec![r])),
            },
            None => groups.push((None, 1, vec![r])),
        }
    }
    let q = tol.spec();
    let reduced: Vec<Vec<(usize, Result<Ran>)>> = groups
        .par_iter()
        .with_max_len(1)
        .map(|(_, w, members)| {
            let scenes: Vec<Resolved> = members.iter().map(|&r| requests[r].2.clone()).collect();
            let outs = run_batch(&scenes, *w, &mut |_| {});
            members
                .iter()
                .zip(outs)
                .map(|(&r, out)| {
                    let (p, key, sc) = &requests[r];
                    let ran =
                        out.map(|out| reduce(spec, base, id, &q, &points[*p], *key, sc, &out));
                    (r, ran)
                })
                .collect()
        })
        .collect();
    let mut out: Vec<Option<Result<Ran>>> = (0..requests.len()).map(|_| None).collect();
    for (r, ran) in reduced.into_iter().flatten() {
        out[r] = Some(ran);
    }
    out.into_iter()
        .map(|r| r.expect("every request ran"))
        .collect()
}

/// A run reduced to what the point keeps.
#[allow(clippy::too_many_arguments)]
fn reduce(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    q: &QuantitySpec,
    point: &Point,
    key: Key,
    sc: &Resolved,
    out: &RunOutput,
) -> Ran {
    // a candidate's record is kept: (0, 0) and the last of a check family
    let candidate = key == (0, 0) || matches!(point.stage, Stage::Check(k) if k == key);
    Ran {
        key,
        value: q.of(out),
        dof_steps: out.dofs as f64 * out.steps as f64,
        loss: out.stats.first().is_some_and(|s| s.loss_interval_count > 0),
        record: candidate.then(|| record_of(spec, base, id, point.index, Some(sc), Ok(out))),
    }
}

/// Move a point on once it has the runs its stage needs.
fn advance(p: &mut Point, tol: &SweepTolerance) {
    if matches!(p.stage, Stage::Done) || !p.wants().is_empty() {
        return;
    }
    let q = tol.spec();
    let base = p.base.as_ref().expect("a point being worked has its scene");
    let method_order = scene_method(base)
        .time_order(base)
        .unwrap_or(MAX_STEP_ORDER);
    let switch = p.runs.iter().any(|r| r.loss);
    let string =
        base.beam.is_string() && base.discretization == crate::scene::Discretization::Hermite;
    let formal = q.formal_orders(method_order, switch, string);
    let at =
        |keys: &[Key]| -> Vec<Option<f64>> { keys.iter().map(|&k| p.value(k).flatten()).collect() };
    let (key, a) = match p.stage {
        Stage::Pilot => {
            let (diag, split) = (at(&PILOTS[..3]), at(&PILOTS[3..]));
            let a = assess(&Inputs {
                diagonal: &diag,
                space: &split,
                ratio: RATIO as f64,
                formal,
                smooth: q.smooth,
            });
            ((0, 0), a)
        }
        Stage::Check(k) => {
            let diag = at(&family(k));
            let a = assess(&Inputs {
                diagonal: &diag,
                space: &[],
                ratio: RATIO as f64,
                formal,
                smooth: q.smooth,
            });
            (k, a)
        }
        Stage::Done => return,
    };
    let u = a.u_num.unwrap_or(f64::INFINITY);
    p.candidates.push((key, a));
    if u <= tol.tolerance {
        return finish(p, tol, key);
    }
    let next = match p.stage {
        Stage::Pilot => plan(p, tol, formal),
        _ => (key.0 + 1, key.1 + 1),
    };
    let mut next = (next.0.min(MAX_EXPONENT), next.1.min(MAX_EXPONENT));
    // within the budget: the plan cut down, the larger refinement first,
    // so a point out of reach still gets as close as its budget allows
    let cost = |p: &Point, k: Key| -> f64 {
        family(k)
            .iter()
            .filter(|&&f| p.value(f).is_none())
            .map(|f| p.base_cost * (RATIO as f64).powi(f.0 + f.1))
            .sum()
    };
    // a scene the model refuses (J beyond the exact modes' range) is out of
    // reach like one beyond the budget
    let fits = |p: &Point, k: Key| {
        p.spent() + cost(p, k) <= tol.budget * p.base_cost
            && family(k)
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
        let best = p
            .candidates
            .iter()
            .min_by(|x, y| {
                let u = |a: &Assessment| a.u_num.unwrap_or(f64::INFINITY);
                u(&x.1).total_cmp(&u(&y.1))
            })
            .map(|c| c.0)
            .unwrap_or(key);
        return finish(p, tol, best);
    }
    p.checks += 1;
    p.stage = Stage::Check(next);
}

/// The first check's (a, b): `run --tolerance`'s cheapest (h, Δt) for
/// [`PLAN_SHARE`] × EPS from the split's differences, as the coarsest
/// powers of two at or below it; one level on both when a ladder does not
/// converge.
fn plan(p: &Point, tol: &SweepTolerance, formal: (f64, f64)) -> Key {
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
    let model = ErrorModel::new(mesh, step);
    match model.cheapest(PLAN_SHARE * tol.tolerance, 1.0, 1.0) {
        // relative h and Δt: the point's own are 1
        Some((h, d)) => {
            let up = |x: f64| (-x.log2() - 1e-9).ceil().max(0.0) as i32;
            let k = (up(h), up(d));
            if k == (0, 0) { (1, 1) } else { k }
        }
        None => (1, 1),
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
    record.accuracy = Some(PointAccuracy {
        value: a.value.unwrap_or(f64::NAN),
        u_num: u,
        met: u <= tol.tolerance,
        elements: sc.as_ref().map_or(0, |s| s.elements),
        modes: sc.as_ref().and_then(|s| s.discretization.modes()),
        dt: sc.as_ref().map_or(f64::NAN, |s| s.dt),
        runs: p.runs.len(),
        dof_steps: p.spent(),
        estimator: a.estimator.name().to_string(),
        checks: p.checks,
    });
    record.wall_seconds = None;
    p.record = Some(record);
    p.stage = Stage::Done;
}
