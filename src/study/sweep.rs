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
//! * `--shard i/n` runs the points with index ≡ i (mod n); `merge` joins
//!   shard folders (same `sweep.json` spec) into one.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::run::run;
use crate::scene::{CarrierKind, Resolved, resolve_scene};

/// The study's dimensionless axes.
pub const DIMENSIONLESS: [&str; 4] = [
    "speed_ratio",
    "tension_ratio",
    "mass_ratio",
    "stiffness_ratio",
];

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

    /// The i-th value.
    pub fn value(&self, i: usize) -> f64 {
        if self.count == 1 {
            return self.start;
        }
        let f = i as f64 / (self.count - 1) as f64;
        if self.log {
            (self.start.ln() + f * (self.stop.ln() - self.start.ln())).exp()
        } else {
            self.start + f * (self.stop - self.start)
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

    /// The resolved scene of point `index`.
    pub fn resolve(&self, index: usize) -> Result<Resolved> {
        let values = self.point(index);
        let mut o = self.set.clone();
        let mut ratios: Vec<(&str, f64)> = Vec::new();
        for (a, v) in self.axes.iter().zip(&values) {
            if DIMENSIONLESS.contains(&a.key.as_str()) {
                ratios.push((a.key.as_str(), *v));
            } else {
                o.push(format!("{}={v:e}", a.key));
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
                    for (i, car) in sc.carriers.iter().enumerate() {
                        if matches!(car.kind, CarrierKind::MassSpring { .. }) {
                            o.push(format!("carrier.{i}.{field}={:e}", v * scale));
                        }
                    }
                }
                _ => unreachable!("DIMENSIONLESS"),
            }
        }
        resolve_scene(&self.scene_text, &o)
    }

    /// Check every point resolves (fail before any run starts).
    pub fn validate(&self) -> Result<()> {
        if self.axes.is_empty() || self.axes.len() > 2 {
            return Err(Error::invalid(
                "--vary",
                self.axes.len(),
                "give one or two axes",
            ));
        }
        for i in 0..self.len() {
            self.resolve(i).map_err(|e| match e {
                Error::Invalid {
                    field,
                    value,
                    allowed,
                } => Error::Invalid {
                    field,
                    value,
                    allowed: format!("{allowed} (at sweep point {i}: {:?})", self.point(i)),
                },
                other => other,
            })?;
        }
        Ok(())
    }
}

/// What a finished run contributes to the sweep.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SweepRecord {
    /// Grid index.
    pub index: usize,
    /// Axis values.
    pub values: Vec<f64>,
    /// V0/c of carrier 0 (null when c = 0).
    pub speed_ratio: Option<f64>,
    /// P_l (carrier 0).
    pub loss_fraction: f64,
    /// Force statistics (carrier 0), N.
    pub force_mean: f64,
    /// Standard deviation, N.
    pub force_std: f64,
    /// Minimum, N.
    pub force_min: f64,
    /// Maximum, N.
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
    /// The run's error, if it stopped (then the statistics are NaN/empty).
    pub error: Option<String>,
    /// Wall seconds (machine-dependent: written to timing.csv only).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub wall_seconds: Option<f64>,
}

fn record(spec: &SweepSpec, index: usize) -> SweepRecord {
    let values = spec.point(index);
    let nan = SweepRecord {
        index,
        values: values.clone(),
        speed_ratio: None,
        loss_fraction: f64::NAN,
        force_mean: f64::NAN,
        force_std: f64::NAN,
        force_min: f64::NAN,
        force_max: f64::NAN,
        first_loss_position: None,
        contact_switches: 0,
        force_profile: vec![],
        loss_profile: vec![],
        warnings: vec![],
        error: None,
        wall_seconds: None,
    };
    let sc = match spec.resolve(index) {
        Ok(sc) => sc,
        Err(e) => {
            return SweepRecord {
                error: Some(e.to_string()),
                ..nan
            };
        }
    };
    let out = match run(&sc, &mut |_, _| {}) {
        Ok(o) => o,
        Err(e) => {
            return SweepRecord {
                error: Some(e.to_string()),
                ..nan
            };
        }
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
        index,
        values,
        speed_ratio: (c > 0.0).then(|| sc.carriers[0].motion.profile.cruise_speed() / c),
        loss_fraction: s.loss_fraction,
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
        error: None,
        wall_seconds: Some(out.wall_seconds),
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

fn run_file(dir: &Path, index: usize) -> PathBuf {
    dir.join("runs").join(format!("{index:06}.json"))
}

fn read_record(path: &Path) -> Option<SweepRecord> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

/// Run (or resume) a sweep into `dir`. `progress(done, total)` is called from
/// worker threads as runs finish. Returns the records of this shard, in grid
/// order.
pub fn sweep(
    spec: &SweepSpec,
    dir: &Path,
    shard: Option<Shard>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<SweepRecord>> {
    spec.validate()?;
    std::fs::create_dir_all(dir.join("runs")).map_err(|e| Error::io(dir, e))?;
    let spec_path = dir.join("sweep.json");
    let spec_text = serde_json::to_string_pretty(spec).expect("serializable") + "\n";
    if let Ok(existing) = std::fs::read_to_string(&spec_path) {
        if existing != spec_text {
            return Err(Error::invalid(
                "--out",
                dir.display(),
                "holds a different sweep (sweep.json differs): use another folder or remove it",
            ));
        }
    } else {
        std::fs::write(&spec_path, &spec_text).map_err(|e| Error::io(&spec_path, e))?;
    }
    let mine: Vec<usize> = (0..spec.len())
        .filter(|&i| shard.is_none_or(|s| s.owns(i)))
        .collect();
    let todo: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&i| read_record(&run_file(dir, i)).is_none())
        .collect();
    let done = AtomicUsize::new(mine.len() - todo.len());
    progress(done.load(Ordering::Relaxed), mine.len());
    todo.par_iter().try_for_each(|&i| -> Result<()> {
        let r = record(spec, i);
        let path = run_file(dir, i);
        // write then rename, so a killed sweep never leaves a half file
        let tmp = path.with_extension("json.tmp");
        let text = serde_json::to_string(&r).expect("serializable");
        std::fs::write(&tmp, text).map_err(|e| Error::io(&tmp, e))?;
        std::fs::rename(&tmp, &path).map_err(|e| Error::io(&path, e))?;
        let n = done.fetch_add(1, Ordering::Relaxed) + 1;
        progress(n, mine.len());
        Ok(())
    })?;
    collect(dir, &mine)
}

/// Read the records of the given indices from `dir/runs`.
pub fn collect(dir: &Path, indices: &[usize]) -> Result<Vec<SweepRecord>> {
    indices
        .iter()
        .map(|&i| {
            let p = run_file(dir, i);
            let r = read_record(&p).ok_or_else(|| {
                Error::invalid(
                    "runs",
                    p.display(),
                    "a finished run's record is missing or unreadable",
                )
            })?;
            // a record copied or edited into the wrong file is refused
            if r.index != i {
                return Err(Error::invalid(
                    format!("{}: index", p.display()),
                    r.index,
                    format!("must be {i}, the point this file holds"),
                ));
            }
            Ok(r)
        })
        .collect()
}

/// Read a sweep folder's spec.
pub fn read_spec(dir: &Path) -> Result<SweepSpec> {
    let p = dir.join("sweep.json");
    let text = std::fs::read_to_string(&p).map_err(|e| Error::io(&p, e))?;
    serde_json::from_str(&text).map_err(|e| Error::Parse(format!("{}: {e}", p.display())))
}

/// Join shard folders into `out`: same spec, every point present once.
pub fn merge(shards: &[PathBuf], out: &Path) -> Result<(SweepSpec, Vec<SweepRecord>)> {
    let first = shards
        .first()
        .ok_or_else(|| Error::invalid("merge", "(none)", "name at least one shard folder"))?;
    let spec = read_spec(first)?;
    // a spec read back is checked as a typed one is (one or two axes, every
    // point a valid scene)
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
    std::fs::create_dir_all(out.join("runs")).map_err(|e| Error::io(out, e))?;
    std::fs::write(
        out.join("sweep.json"),
        serde_json::to_string_pretty(&spec).expect("serializable") + "\n",
    )
    .map_err(|e| Error::io(out, e))?;
    let mut missing = Vec::new();
    for i in 0..spec.len() {
        let found = shards.iter().map(|s| run_file(s, i)).find(|p| p.is_file());
        match found {
            Some(p) if p != run_file(out, i) => {
                std::fs::copy(&p, run_file(out, i)).map_err(|e| Error::io(&p, e))?;
            }
            Some(_) => {}
            None => missing.push(i),
        }
    }
    if !missing.is_empty() {
        return Err(Error::invalid(
            "merge",
            format!(
                "{} of {} points missing (first: {})",
                missing.len(),
                spec.len(),
                missing[0]
            ),
            "every point must be in some shard: run the missing shards (or resume them) first",
        ));
    }
    let all: Vec<usize> = (0..spec.len()).collect();
    let records = collect(out, &all)?;
    Ok((spec, records))
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
