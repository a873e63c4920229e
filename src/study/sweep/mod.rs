//! `taut sweep`: parameter sweeps over any scene value and over the study's
//! dimensionless axes (TARGETS T3–T7), in parallel, deterministic, resumable
//! and shardable.
//!
//! * A sweep is a 1-D or 2-D grid of `--vary key=start:stop:count` axes,
//!   linear or (with `--log`) logarithmic. `key` is any dotted scene path
//!   (`beam.tension`, `carrier.0.mass`) or one of [`DIMENSIONLESS`]:
//!   `speed_ratio` = V0/c (every carrier's cruise speed), `tension_ratio` =
//!   T/EA, `mass_ratio` = m/M with M = ρAL (every mass carrier),
//!   `stiffness_ratio` = k/(T/L) (every mass carrier). Ratios are applied after
//!   the plain keys and `tension_ratio` first, so `speed_ratio` and
//!   `stiffness_ratio` use the swept tension.
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

pub mod folder;

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::{RunOutput, run};
use crate::scene::{CarrierKind, Discretization};

pub use folder::{FolderLock, claim, collect, merge, merge_into, read_spec};

/// The study's dimensionless axes.
pub const DIMENSIONLESS: [&str; 4] = [
    "speed_ratio",
    "tension_ratio",
    "mass_ratio",
    "stiffness_ratio",
];

/// Relative distance below which a grid value on an axis between whole
/// numbers is taken as the whole number it approximates: round-off of the
/// spacing formula is ~1e-15; a genuine grid value is further than 1e-9
/// from a whole number unless it is one.
pub const WHOLE_SNAP: f64 = 1e-9;

/// A grid value as a `--set` value: whole numbers as TOML integers (so an
/// integer key such as `mesh.elements` takes them, and a real key reads the
/// same number), anything else in exponent notation (exact round trip).
fn set_value(v: f64) -> String {
    /// Whole numbers below 2^53 are exact as both i64 and f64.
    const EXACT_WHOLE: f64 = 9_007_199_254_740_992.0;
    if v.fract() == 0.0 && v.abs() < EXACT_WHOLE {
        format!("{}", v as i64)
    } else {
        format!("{v:e}")
    }
}

/// Number of x_m/L bins of the per-run force and loss profiles.
pub const PROFILE_BINS: usize = 200;

/// One swept axis.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Axis {
    /// Scene path or dimensionless name.
    pub key: String,
    /// First value.
    pub start: f64,
    /// Last value.
    pub stop: f64,
    /// Number of values (≥ 1).
    pub count: usize,
    /// Logarithmic spacing.
    pub log: bool,
}

impl Axis {
    /// Parse `key=start:stop:count`.
    pub fn parse(spec: &str, log: bool) -> Result<Self> {
        let bad = |why: &str| Error::invalid("--vary", spec, why.to_string());
        let (key, range) = spec
            .split_once('=')
            .ok_or_else(|| bad("expected key=start:stop:count"))?;
        let parts: Vec<&str> = range.split(':').collect();
        let [a, b, n] = parts.as_slice() else {
            return Err(bad("expected key=start:stop:count"));
        };
        let num = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(start), Some(stop)) = (num(a), num(b)) else {
            return Err(bad("start and stop must be finite numbers"));
        };
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("count must be a whole number ≥ 1"))?;
        if count == 0 || count > 100_000 {
            return Err(bad("count must be in 1 ..= 100000"));
        }
        if log && (start <= 0.0 || stop <= 0.0) {
            return Err(bad("a logarithmic axis needs start and stop > 0"));
        }
        if key.trim().is_empty() {
            return Err(bad("the key is empty"));
        }
        Ok(Axis {
            key: key.trim().to_string(),
            start,
            stop,
            count,
            log,
        })
    }

    /// The i-th value: `start` and `stop` exactly at the ends. On an axis
    /// between whole numbers, a value within [`WHOLE_SNAP`] of a whole number
    /// is that number, so `mesh.elements=100:1600:5 --log` gives 200, 400, 800
    /// (integer keys take them) rather than 199.99999999999997.
    pub fn value(&self, i: usize) -> f64 {
        if i == 0 || self.count == 1 {
            return self.start;
        }
        if i + 1 == self.count {
            return self.stop;
        }
        let f = i as f64 / (self.count - 1) as f64;
        let v = if self.log {
            (self.start.ln() + f * (self.stop.ln() - self.start.ln())).exp()
        } else {
            self.start + f * (self.stop - self.start)
        };
        let whole_ends = self.start.fract() == 0.0 && self.stop.fract() == 0.0;
        if whole_ends && (v - v.round()).abs() <= WHOLE_SNAP * v.abs().max(1.0) {
            v.round()
        } else {
            v
        }
    }
}

/// What a sweep is: the scene, its fixed overrides and the axes.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SweepSpec {
    /// The scene text (so shards and merges are sure to agree).
    pub scene_text: String,
    /// Fixed `--set` overrides.
    pub set: Vec<String>,
    /// One or two axes; the last varies fastest.
    pub axes: Vec<Axis>,
    /// Run each point a second time, refined (N × 2, Δt / 2; J × 2 on a
    /// modal basis), to show where P_l is converged (`--check-refinement`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub check_refinement: bool,
}

impl SweepSpec {
    /// Number of grid points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.count).product()
    }

    /// True for an empty grid (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Axis values of point `index` (last axis fastest).
    pub fn point(&self, index: usize) -> Vec<f64> {
        let mut rest = index;
        let mut idx = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            idx[k] = rest % a.count;
            rest /= a.count;
        }
        self.axes.iter().zip(idx).map(|(a, i)| a.value(i)).collect()
    }

    /// The resolved scene of point `index`, refined (`--check-refinement`):
    /// half the time step, and twice the space discretization's level
    /// parameter — the elements N of a Hermite mesh, the modes J of a
    /// `galerkin` basis, both N and J of a `modal` one (J may not exceed the
    /// FE unknowns).
    pub fn resolve_refined(&self, index: usize) -> Result<Resolved> {
        let (sc, mut o) = self.resolve_with_overrides(index)?;
        let modes = sc.discretization.modes();
        if !matches!(sc.discretization, Discretization::Galerkin { .. }) {
            o.push(format!("mesh.elements={}", 2 * sc.elements));
        }
        if let Some(j) = modes {
            o.push(format!("mesh.modes={}", 2 * j));
        }
        o.push(format!("time.step={:e}", sc.dt / 2.0));
        resolve_scene(&self.scene_text, &o)
    }

    /// The resolved scene of point `index`.
    pub fn resolve(&self, index: usize) -> Result<Resolved> {
        self.resolve_with_overrides(index).map(|(sc, _)| sc)
    }

    /// The resolved scene of point `index` and the overrides that make it.
    fn resolve_with_overrides(&self, index: usize) -> Result<(Resolved, Vec<String>)> {
        let values = self.point(index);
        let mut o = self.set.clone();
        let mut ratios: Vec<(&str, f64)> = Vec::new();
        for (a, v) in self.axes.iter().zip(&values) {
            if DIMENSIONLESS.contains(&a.key.as_str()) {
                ratios.push((a.key.as_str(), *v));
            } else {
                o.push(format!("{}={}", a.key, set_value(*v)));
            }
        }
        // tension first: the others depend on T
        ratios.sort_by_key(|(k, _)| *k != "tension_ratio");
        for (key, v) in ratios {
            let sc = resolve_scene(&self.scene_text, &o)?;
            match key {
                "tension_ratio" => {
                    let ea = sc.beam.ea.ok_or_else(|| {
                        Error::invalid(
                            "--vary tension_ratio",
                            v,
                            "needs EA: give beam.youngs_modulus and beam.area",
                        )
                    })?;
                    o.push(format!("beam.tension={:e}", v * ea));
                }
                "speed_ratio" => {
                    let c = sc.beam.wave_speed();
                    if c <= 0.0 {
                        return Err(Error::invalid(
                            "--vary speed_ratio",
                            v,
                            "needs a wave speed c = sqrt(T/ρA) > 0, and the scene has T = 0: \
                             vary the carrier's speed itself",
                        ));
                    }
                    for (i, car) in sc.carriers.iter().enumerate() {
                        let path = match car.motion.profile {
                            crate::scene::SpeedProfile::Constant { .. } => "value",
                            crate::scene::SpeedProfile::SmoothRamp { .. } => "cruise",
                        };
                        o.push(format!("carrier.{i}.speed.{path}={:e}", v * c));
                    }
                }
                "mass_ratio" | "stiffness_ratio" => {
                    let scale = if key == "mass_ratio" {
                        sc.beam.total_mass()
                    } else {
                        sc.beam.tension / sc.beam.length
                    };
                    let field = if key == "mass_ratio" {
                        "mass"
                    } else {
                        "stiffness"
                    };
                    if !sc
                        .carriers
                        .iter()
                        .any(|c| matches!(c.kind, CarrierKind::MassSpring { .. }))
                    {
                        return Err(Error::invalid(
                            format!("--vary {key}"),
                            v,
                            format!(
                                "sets the {field} of every mass–spring carrier, and the scene \
                                 has none (only moving forces): the axis would change nothing"
                            ),
                        ));
                    }
                    if scale <= 0.0 {
                        return Err(Error::invalid(
                            format!("--vary {key}"),
                            v,
                            "is k/(T/L), and the scene has T = 0: the axis would set k = 0 at \
                             every point; vary carrier.stiffness itself",
                        ));
                    }
                    for (i, car) in sc.carriers.iter().enumerate() {
                        if matches!(car.kind, CarrierKind::MassSpring { .. }) {
                            o.push(format!("carrier.{i}.{field}={:e}", v * scale));
                        }
                    }
                }
                _ => unreachable!("DIMENSIONLESS"),
            }
        }
        let sc = resolve_scene(&self.scene_text, &o)?;
        Ok((sc, o))
    }

    /// The resolved scene at per-axis indices `at`.
    fn resolve_at(&self, at: &[usize]) -> Result<Resolved> {
        let index = at
            .iter()
            .zip(&self.axes)
            .fold(0, |acc, (&i, a)| acc * a.count + i);
        self.resolve(index)
    }

    /// Check the grid before any run starts: one or two distinct axes, a
    /// bounded number of points, every point resolves, and every axis changes
    /// the scene (an axis that changes nothing would fill a map with one
    /// answer and call it a study).
    pub fn validate(&self) -> Result<()> {
        if self.axes.is_empty() || self.axes.len() > 2 {
            return Err(Error::invalid(
                "--vary",
                self.axes.len(),
                "give one or two axes",
            ));
        }
        if let [a, b] = self.axes.as_slice()
            && a.key == b.key
        {
            return Err(Error::invalid(
                "--vary",
                &a.key,
                "is given twice: give each axis once",
            ));
        }
        let points = self
            .axes
            .iter()
            .try_fold(1usize, |n, a| n.checked_mul(a.count))
            .filter(|&n| n <= MAX_POINTS);
        if points.is_none() {
            return Err(Error::invalid(
                "--vary",
                self.axes
                    .iter()
                    .map(|a| a.count.to_string())
                    .collect::<Vec<_>>()
                    .join(" × "),
                format!(
                    "a sweep has at most {MAX_POINTS} points: use fewer, or split the range into several sweeps"
                ),
            ));
        }
        for i in 0..self.len() {
            self.resolve(i)
                .map_err(|e| at_point(e, i, &self.point(i)))?;
            if self.check_refinement {
                self.resolve_refined(i).map_err(|e| {
                    at_point(e, i, &self.point(i)).in_run("the refined run of --check-refinement")
                })?;
            }
        }
        for (k, a) in self.axes.iter().enumerate() {
            if a.count < 2 {
                continue;
            }
            let first = vec![0; self.axes.len()];
            let mut last = first.clone();
            last[k] = a.count - 1;
            let (x, y) = (self.resolve_at(&first)?, self.resolve_at(&last)?);
            if a.value(0) == a.value(a.count - 1) || format!("{x:?}") == format!("{y:?}") {
                return Err(Error::invalid(
                    "--vary",
                    format!("{}={}:{}:{}", a.key, a.start, a.stop, a.count),
                    "changes nothing in this scene (the first and last points resolve to the \
                     same scene: equal ends, or a value another axis or the scene overrides): \
                     drop the axis or give it a range",
                ));
            }
        }
        Ok(())
    }
}

impl SweepSpec {
    /// The sweep's estimated work ([`crate::study::cost`]): the points of
    /// `shard` (all without one) at their own resolution, and their refined
    /// runs with `--check-refinement`. Call after [`SweepSpec::validate`].
    pub fn estimate(&self, shard: Option<Shard>) -> Result<crate::study::cost::Estimate> {
        use crate::study::cost::{Estimate, run_dof_steps};
        let mut e = Estimate::new("taut sweep");
        for i in (0..self.len()).filter(|&i| shard.is_none_or(|s| s.owns(i))) {
            e.add(1, run_dof_steps(&self.resolve(i)?));
            if self.check_refinement {
                e.add(1, run_dof_steps(&self.resolve_refined(i)?));
            }
        }
        Ok(e)
    }
}

/// The most points a sweep may have: 100 000 runs is days of work at the
/// reference resolution and ~0.4 GB of records; a larger grid is several sweeps.
pub const MAX_POINTS: usize = 100_000;

/// Name the sweep point a resolution error happened at.
fn at_point(e: Error, i: usize, values: &[f64]) -> Error {
    match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::Invalid {
            field,
            value,
            allowed: format!("{allowed} (at sweep point {i}: {values:?})"),
        },
        Error::Parse { reason, field } => Error::Parse {
            reason: format!("{reason} (at sweep point {i}: {values:?})"),
            field,
        },
        other => other,
    }
}

/// What a finished run contributes to the sweep. A run that stopped is a
/// record too: its statistics are NaN (`null` in the file), its profiles
/// empty and `error` says why.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SweepRecord {
    /// The sweep this record belongs to ([`folder::sweep_id`]); empty in
    /// records of taut before stamping, which are refused.
    #[serde(default)]
    pub sweep_id: String,
    /// Grid index.
    pub index: usize,
    /// Axis values.
    pub values: Vec<f64>,
    /// V0/c of carrier 0 (null when c = 0).
    pub speed_ratio: Option<f64>,
    /// P_l (carrier 0).
    #[serde(with = "nan_as_null")]
    pub loss_fraction: f64,
    /// Its in-span part (outside the support zones): the part to quote.
    #[serde(with = "nan_as_null")]
    pub loss_fraction_span: f64,
    /// Its support part (the carrier's arrival at a support).
    #[serde(with = "nan_as_null")]
    pub loss_fraction_support: f64,
    /// Force statistics (carrier 0), N.
    #[serde(with = "nan_as_null")]
    pub force_mean: f64,
    /// Standard deviation, N.
    #[serde(with = "nan_as_null")]
    pub force_std: f64,
    /// Minimum, N.
    #[serde(with = "nan_as_null")]
    pub force_min: f64,
    /// Maximum, N.
    #[serde(with = "nan_as_null")]
    pub force_max: f64,
    /// x_m/L of the first loss (null if none).
    pub first_loss_position: Option<f64>,
    /// Contact switches.
    pub contact_switches: usize,
    /// Mean force per x_m/L bin (PROFILE_BINS bins over [0, 1]), N; null for
    /// a bin no step fell in.
    pub force_profile: Vec<Option<f64>>,
    /// Fraction of steps with contact lost per x_m/L bin.
    pub loss_profile: Vec<Option<f64>>,
    /// Warnings of the run.
    pub warnings: Vec<String>,
    /// The same point refined (N × 2, Δt / 2), with `--check-refinement`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refined: Option<Refined>,
    /// The run's error, if it stopped (then the statistics are NaN/empty).
    pub error: Option<String>,
    /// Wall seconds (machine-dependent: written to timing.csv only).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub wall_seconds: Option<f64>,
}

/// A statistic that is NaN for a stopped run: written as `null` (JSON has
/// no NaN) and read back as NaN.
mod nan_as_null {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_nan() {
            s.serialize_none()
        } else {
            s.serialize_f64(*v)
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

impl SweepRecord {
    /// The record of a point that stopped before giving statistics (the
    /// caller sets `error`).
    fn stopped(sweep_id: &str, index: usize, values: Vec<f64>) -> Self {
        SweepRecord {
            sweep_id: sweep_id.to_string(),
            index,
            values,
            speed_ratio: None,
            loss_fraction: f64::NAN,
            loss_fraction_span: f64::NAN,
            loss_fraction_support: f64::NAN,
            force_mean: f64::NAN,
            force_std: f64::NAN,
            force_min: f64::NAN,
            force_max: f64::NAN,
            first_loss_position: None,
            contact_switches: 0,
            force_profile: vec![],
            loss_profile: vec![],
            warnings: vec![],
            refined: None,
            error: None,
            wall_seconds: None,
        }
    }
}

/// A sweep point run again refined (`--check-refinement`): twice the
/// elements (modes on a modal basis), half the step.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Refined {
    /// Elements of the refined run.
    pub elements: usize,
    /// Its modes J, on a `galerkin` or `modal` basis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Its time step, s.
    pub dt: f64,
    /// Its P_l (null when it stopped).
    #[serde(with = "nan_as_null")]
    pub loss_fraction: f64,
    /// Its in-span P_l (null when it stopped).
    #[serde(with = "nan_as_null")]
    pub loss_fraction_span: f64,
    /// Why it stopped, if it did.
    pub error: Option<String>,
}

/// Whether a P_l is converged under one refinement: the change is at most
/// [`REFINEMENT_REL`] of the refined value or [`REFINEMENT_ABS`] (None when
/// either run stopped).
pub fn refinement_converged(base: f64, refined: f64) -> Option<bool> {
    let d = (refined - base).abs();
    d.is_finite()
        .then(|| d <= (REFINEMENT_REL * refined.abs()).max(REFINEMENT_ABS))
}

/// Relative change of P_l under one refinement (N × 2, Δt / 2) taken as
/// converged: the in-span P_l of the reference case changes by 0.02–4 %
/// between its finest levels (`docs/contact_loss.md`), a non-converged one
/// by tens of per cent.
pub const REFINEMENT_REL: f64 = 0.05;

/// Absolute change of P_l taken as converged whatever its size: 5e-4 is
/// three steps of loss in the reference run's 6000, below what a loss map
/// resolves.
pub const REFINEMENT_ABS: f64 = 5e-4;

/// Run point `index` and reduce it to its record.
fn record(spec: &SweepSpec, id: &str, index: usize) -> SweepRecord {
    let sc = spec.resolve(index);
    let out = sc
        .as_ref()
        .map_err(|e| e.to_string())
        .and_then(|sc| run(sc, &mut |_, _| {}).map_err(|e| e.to_string()));
    record_of(spec, id, index, sc.as_ref().ok(), out)
}

/// Point `index`'s record from its scene and what its run gave.
fn record_of(
    spec: &SweepSpec,
    id: &str,
    index: usize,
    sc: Option<&Resolved>,
    out: std::result::Result<RunOutput, String>,
) -> SweepRecord {
    let values = spec.point(index);
    let nan = SweepRecord::stopped(id, index, values.clone());
    let (sc, out) = match (sc, out) {
        (Some(sc), Ok(o)) => (sc, o),
        (_, Err(e)) => {
            return SweepRecord {
                error: Some(e),
                ..nan
            };
        }
        (None, Ok(_)) => unreachable!("a run needs its scene"),
    };
    let s = &out.stats[0];
    let tr = &out.history.carriers[0];
    let l = sc.beam.length;
    let (mut fsum, mut lost, mut n) = (
        vec![0.0; PROFILE_BINS],
        vec![0usize; PROFILE_BINS],
        vec![0usize; PROFILE_BINS],
    );
    for i in 1..tr.x.len() {
        let b = ((tr.x[i] / l * PROFILE_BINS as f64) as usize).min(PROFILE_BINS - 1);
        fsum[b] += tr.force[i];
        lost[b] += usize::from(!tr.in_contact[i]);
        n[b] += 1;
    }
    let c = sc.beam.wave_speed();
    SweepRecord {
        sweep_id: id.to_string(),
        index,
        values,
        speed_ratio: (c > 0.0).then(|| sc.carriers[0].motion.profile.cruise_speed() / c),
        loss_fraction: s.loss_fraction,
        loss_fraction_span: s.loss_fraction_span,
        loss_fraction_support: s.loss_fraction_support,
        force_mean: s.force.mean,
        force_std: s.force.std,
        force_min: s.force.min,
        force_max: s.force.max,
        first_loss_position: s.first_loss_position,
        contact_switches: s.contact_switches,
        force_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| fsum[b] / n[b] as f64))
            .collect(),
        loss_profile: (0..PROFILE_BINS)
            .map(|b| (n[b] > 0).then(|| lost[b] as f64 / n[b] as f64))
            .collect(),
        warnings: out.warnings.clone(),
        refined: spec.check_refinement.then(|| refined(spec, index)),
        error: None,
        wall_seconds: Some(out.wall_seconds),
    }
}

/// Run point `index` refined.
fn refined(spec: &SweepSpec, index: usize) -> Refined {
    let stopped = |elements, modes, dt, e: Error| Refined {
        elements,
        modes,
        dt,
        loss_fraction: f64::NAN,
        loss_fraction_span: f64::NAN,
        error: Some(e.to_string()),
    };
    let sc = match spec.resolve_refined(index) {
        Ok(sc) => sc,
        Err(e) => return stopped(0, None, f64::NAN, e),
    };
    let modes = sc.discretization.modes();
    match run(&sc, &mut |_, _| {}) {
        Ok(o) => Refined {
            elements: sc.elements,
            modes,
            dt: sc.dt,
            loss_fraction: o.stats[0].loss_fraction,
            loss_fraction_span: o.stats[0].loss_fraction_span,
            error: None,
        },
        Err(e) => stopped(sc.elements, modes, sc.dt, e),
    }
}

/// Shard selector `i/n`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0-based.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// Parse `i/n` with 0 ≤ i < n.
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || Error::invalid("--shard", s, "expected i/n with 0 ≤ i < n (e.g. 0/4)");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// Whether this shard runs point `i`.
    pub fn owns(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

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

/// [`sweep_in`] with the batch width given (`--batch`): points that share
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
    let items = batches(spec, &todo, batch);
    items.par_iter().try_for_each(|item| -> Result<()> {
        let records = records_guarded(spec, &id, item);
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

/// How many runs a sweep steps together (`--batch`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BatchWidth {
    /// [`AUTO_BATCH_LANES`].
    Auto,
    /// At most this many (1: every run alone, the unbatched path).
    Fixed(usize),
}

/// The automatic batch width: four runs, one AVX2 vector of lanes.
/// Measured on the reference case (criterion group `batch`, N = 1600, and
/// `cargo run --release --example batch_profile -- B N` at N = 400, 800,
/// 1600), four lanes gave the best throughput at every size (2.2–2.6× the
/// runs alone), two little (0.94–1.35×: the half-width vectors barely pay
/// for the interleaving), eight less than four (the sweep's window of 3 × 16
/// columns no longer fits the sixteen vector registers).
pub const AUTO_BATCH_LANES: usize = 4;

/// The automatic batch width of a scene's runs: [`AUTO_BATCH_LANES`] for
/// generalized-α (SIMD lanes of one band sweep), the widest batch for
/// `modal_exact`, whose runs gain from sharing their basis and its tables
/// (built once per batch) and lose nothing by stepping in turn
/// (`integrate::modal_batch`).
pub fn auto_lanes(sc: &Resolved) -> usize {
    match sc.scheme {
        crate::scene::Scheme::ModalExact => crate::integrate::MAX_LANES,
        _ => AUTO_BATCH_LANES,
    }
}

/// The sweep's work items: points that share their effective matrix
/// ([`crate::integrate::batch_key`]), in grid order, grouped up to the
/// batch width; every other point alone.
fn batches(spec: &SweepSpec, todo: &[usize], width: BatchWidth) -> Vec<Vec<usize>> {
    if width == BatchWidth::Fixed(1) {
        return todo.iter().map(|&i| vec![i]).collect();
    }
    let mut open: Vec<(String, usize, Vec<usize>)> = Vec::new();
    let mut items: Vec<Vec<usize>> = Vec::new();
    for &i in todo {
        let key = spec.resolve(i).ok().and_then(|sc| {
            let key = crate::integrate::batch_key(&sc)?;
            let w = match width {
                BatchWidth::Fixed(b) => b,
                BatchWidth::Auto => auto_lanes(&sc),
            };
            Some((key, w))
        });
        let Some((key, w)) = key else {
            items.push(vec![i]);
            continue;
        };
        match open.iter_mut().position(|(k, ..)| *k == key) {
            Some(p) => {
                open[p].2.push(i);
                if open[p].2.len() >= open[p].1 {
                    items.push(open.remove(p).2);
                }
            }
            None => open.push((key, w, vec![i])),
        }
    }
    items.extend(open.into_iter().map(|(.., g)| g));
    items
}

/// The records of one work item, run together when it has several points
/// ([`crate::run::run_batch`]); a panic inside makes every point of the
/// item an error record (none of them is trusted), never the sweep's end.
fn records_guarded(spec: &SweepSpec, id: &str, item: &[usize]) -> Vec<SweepRecord> {
    if let [i] = item {
        return vec![record_guarded(spec, id, *i)];
    }
    let go = || {
        let scenes: Vec<Result<Resolved>> = item.iter().map(|&i| spec.resolve(i)).collect();
        let ok: Vec<Resolved> = scenes
            .iter()
            .filter_map(|s| s.as_ref().ok().cloned())
            .collect();
        let mut outs = crate::run::run_batch(&ok, item.len(), &mut |_| {}).into_iter();
        item.iter()
            .zip(&scenes)
            .map(|(&i, sc)| {
                let out = match sc {
                    Ok(_) => outs
                        .next()
                        .expect("one output per scene")
                        .map_err(|e| e.to_string()),
                    Err(e) => Err(e.to_string()),
                };
                record_of(spec, id, i, sc.as_ref().ok(), out)
            })
            .collect::<Vec<_>>()
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(go)).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        item.iter()
            .map(|&i| SweepRecord {
                error: Some(format!(
                    "internal error (a panic in taut, please report it), in a batch of {} runs: {what}",
                    item.len()
                )),
                ..SweepRecord::stopped(id, i, spec.point(i))
            })
            .collect()
    })
}

/// [`record`], with a panic inside the run turned into that point's error,
/// so one bad point cannot take the sweep's other points down with it.
fn record_guarded(spec: &SweepSpec, id: &str, index: usize) -> SweepRecord {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| record(spec, id, index)))
        .unwrap_or_else(|payload| {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".into());
            SweepRecord {
                error: Some(format!(
                    "internal error (a panic in taut, please report it): {what}"
                )),
                ..SweepRecord::stopped(id, index, spec.point(index))
            }
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_parse_and_space() {
        let a = Axis::parse("speed_ratio=0.4:1.3:10", false).unwrap();
        assert_eq!(a.count, 10);
        assert!((a.value(9) - 1.3).abs() < 1e-15);
        let l = Axis::parse("carrier.mass=0.1:10:3", true).unwrap();
        assert!((l.value(1) - 1.0).abs() < 1e-12);
        for bad in ["x", "x=1:2", "x=a:2:3", "x=1:2:0", "=1:2:3"] {
            assert!(Axis::parse(bad, false).is_err(), "{bad}");
        }
        assert!(Axis::parse("x=0:1:3", true).is_err());
    }

    #[test]
    fn shards_partition_the_grid() {
        let s: Vec<Shard> = (0..3)
            .map(|i| Shard::parse(&format!("{i}/3")).unwrap())
            .collect();
        for i in 0..20 {
            assert_eq!(s.iter().filter(|sh| sh.owns(i)).count(), 1);
        }
        assert!(Shard::parse("3/3").is_err() && Shard::parse("1").is_err());
    }
}
