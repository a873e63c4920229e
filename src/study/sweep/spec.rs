//! What a sweep is ([`SweepSpec`]): the scene, its fixed overrides and the
//! axes; its grid, its checks before any run, and its estimated work.

use serde::{Deserialize, Serialize};

use super::axis::Axis;
use super::shard::Shard;
use super::tolerance_spec::SweepTolerance;
use crate::error::{Error, Result};
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
    /// A list of points (`--points FILE.csv`, Python `points=[...]`): the
    /// axes are listed axes of one length walked together, point i taking
    /// value i of every axis, instead of their grid. False (and absent from
    /// `sweep.json`) for a grid.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub paired: bool,
    /// `--tolerance EPS --quantity Q`: every point refined until Q's
    /// u_num is within EPS (`super::accuracy`); absent for a sweep at the
    /// scene's resolution.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<SweepTolerance>,
}

impl SweepSpec {
    /// Number of points: of the grid, or of the list of points.
    pub fn len(&self) -> usize {
        if self.paired {
            return self.axes.first().map_or(0, |a| a.count);
        }
        self.axes.iter().map(|a| a.count).product()
    }

    /// A list of points (`--points`) from its keys and rows (one value a
    /// key in each row): one listed axis a key, walked together.
    pub fn points_axes(keys: &[String], rows: &[Vec<f64>]) -> Result<Vec<Axis>> {
        if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != keys.len()) {
            return Err(Error::invalid(
                "--points",
                format!("point {i}: {} values", r.len()),
                format!(
                    "every point gives one value for each of the {} keys",
                    keys.len()
                ),
            ));
        }
        keys.iter()
            .enumerate()
            .map(|(k, key)| {
                Axis::list(key, rows.iter().map(|r| r[k]).collect(), false).map_err(|e| match e {
                    Error::Invalid { allowed, .. } => Error::invalid(
                        "--points",
                        key,
                        format!("{allowed} (column `{key}` of the points)"),
                    ),
                    other => other,
                })
            })
            .collect()
    }

    /// True for an empty grid (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Axis values of point `index` (last axis fastest; of a list of
    /// points, its row).
    pub fn point(&self, index: usize) -> Vec<f64> {
        if self.paired {
            return self.axes.iter().map(|a| a.value(index)).collect();
        }
        let mut rest = index;
        let mut idx = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            idx[k] = rest % a.count;
            rest /= a.count;
        }
        self.axes.iter().zip(idx).map(|(a, i)| a.value(i)).collect()
    }
}

impl SweepSpec {
    /// Check the grid before any run starts: one or two distinct axes, a
    /// bounded number of points, every point resolves, and every axis changes
    /// the scene (an axis that changes nothing would fill a map with one
    /// answer and call it a study).
    pub fn validate(&self) -> Result<()> {
        if self.tolerance.is_some() && self.check_refinement {
            return Err(Error::invalid(
                "--check-refinement",
                "given",
                "does not go with --tolerance, which refines every point as far as it needs and reports u_num: give one of the two",
            ));
        }
        if self.paired {
            return self.validate_points();
        }
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
        if self.axes.len() == 2
            && let Ok(base) = self.base_tree()
        {
            // two keys that set one scene value (an error in the base is
            // the first point's, below)
            super::aliases::check_one_value_per_key(&self.axes, &base, "--vary")?;
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
        let base = self.resolve_every_point()?;
        for (k, a) in self.axes.iter().enumerate() {
            if a.count < 2 {
                continue;
            }
            let first = vec![0; self.axes.len()];
            let mut last = first.clone();
            last[k] = a.count - 1;
            let (x, mut y) = (
                self.resolve_at(&base, &first)?,
                self.resolve_at(&base, &last)?,
            );
            // a list's ends may agree (1, 2, 1): compare its first value
            // with the first that differs from it
            let last_index = match &a.values {
                Some(v) => v.iter().position(|&x| x != v[0]).unwrap_or(a.count - 1),
                None => a.count - 1,
            };
            if last_index != a.count - 1 {
                last[k] = last_index;
                y = self.resolve_at(&base, &last)?;
            }
            if a.value(0) == a.value(last_index) || format!("{x:?}") == format!("{y:?}") {
                let shown = match &a.values {
                    Some(v) => {
                        let v: Vec<String> = v.iter().map(|x| x.to_string()).collect();
                        crate::error::one_line(&format!("{}={}", a.key, v.join(",")))
                    }
                    None => format!("{}={}:{}:{}", a.key, a.start, a.stop, a.count),
                };
                return Err(Error::invalid(
                    "--vary",
                    shown,
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
    /// [`SweepSpec::validate`] for a list of points: at least one key,
    /// each once, every key a listed axis of the same length, at most
    /// [`MAX_POINTS`] points, and every point resolves. (A key whose
    /// column changes nothing is the list's own choice: not refused.)
    fn validate_points(&self) -> Result<()> {
        let Some(first) = self.axes.first() else {
            return Err(Error::invalid(
                "--points",
                "no keys",
                "give at least one key (a column of the points file)",
            ));
        };
        if self.axes.len() > MAX_POINT_KEYS {
            return Err(Error::invalid(
                "--points",
                format!("{} keys", self.axes.len()),
                format!(
                    "a list of points sets at most {MAX_POINT_KEYS} keys: vary fewer scene values"
                ),
            ));
        }
        let mut seen = std::collections::HashSet::new();
        for a in &self.axes {
            if !seen.insert(a.key.as_str()) {
                return Err(Error::invalid(
                    "--points",
                    &a.key,
                    "is given twice: give each key once",
                ));
            }
            if a.values.is_none() || a.count != first.count {
                return Err(Error::invalid(
                    "--points",
                    &a.key,
                    "every key of a list of points needs one value a point",
                ));
            }
        }
        if first.count > MAX_POINTS {
            return Err(Error::invalid(
                "--points",
                first.count,
                format!("a sweep has at most {MAX_POINTS} points: split the list"),
            ));
        }
        if let Ok(base) = self.base_tree() {
            super::aliases::check_one_value_per_key(&self.axes, &base, "--points")?;
        }
        self.resolve_every_point().map(drop)
    }
}

impl SweepSpec {
    /// The sweep's estimated work ([`crate::study::cost`]): the points of
    /// `shard` (all without one) at their own resolution, and their refined
    /// runs with `--check-refinement`. Call after [`SweepSpec::validate`].
    pub fn estimate(&self, shard: Option<Shard>) -> Result<crate::study::cost::Estimate> {
        use crate::study::cost::{Estimate, run_dof_steps};
        let mut e = Estimate::new("taut sweep");
        let base = self.base_tree()?;
        for i in (0..self.len()).filter(|&i| shard.is_none_or(|s| s.owns(i))) {
            // with --tolerance: the pilots (1.81 runs' worth); refinements
            // beyond them are each point's budget, not known before
            let own = run_dof_steps(&self.resolve_on(&base, i)?);
            e.add(
                1,
                if self.tolerance.is_some() {
                    1.81 * own
                } else {
                    own
                },
            );
            if self.check_refinement {
                e.add(1, run_dof_steps(&self.resolve_refined_on(&base, i)?));
            }
        }
        Ok(e)
    }
}

/// The most keys a list of points may set (columns of a `--points` file,
/// keys of Python's points): each is set on every point's scene, and no
/// study varies more than a few dozen scene values; a wider file is not a
/// list of scene keys (40 000 columns took minutes to refuse).
pub const MAX_POINT_KEYS: usize = 1000;

/// The most points a sweep may have: 100 000 runs is days of work at the
/// reference resolution and ~0.4 GB of records; a larger grid is several sweeps.
pub(crate) const MAX_POINTS: usize = 100_000;

impl SweepSpec {
    /// Resolve every point (and its refined run with `--check-refinement`)
    /// before any runs, naming the first point that fails. The scene text
    /// and the fixed overrides are parsed once (an error there is the first
    /// point's, as when each point parsed the text itself); that parsed
    /// base is returned for further checks.
    fn resolve_every_point(&self) -> Result<toml::Table> {
        let base = self
            .base_tree()
            .map_err(|e| at_point(e, 0, &self.point(0)))?;
        for i in 0..self.len() {
            let sc = self
                .resolve_on(&base, i)
                .map_err(|e| at_point(e, i, &self.point(i)))?;
            if self.tolerance.is_some() {
                super::tolerance_spec::check_level(&sc)
                    .map_err(|e| at_point(e, i, &self.point(i)))?;
            }
            if self.check_refinement {
                self.resolve_refined_on(&base, i).map_err(|e| {
                    at_point(e, i, &self.point(i)).in_run("the refined run of --check-refinement")
                })?;
            }
        }
        Ok(base)
    }
}

/// A point's values for a message: the first few and how many there are
/// (a list of points may set up to [`MAX_POINT_KEYS`] keys).
fn shown(values: &[f64]) -> String {
    const SHOWN: usize = 8;
    if values.len() <= SHOWN {
        format!("{values:?}")
    } else {
        format!("{:?} … ({} values)", &values[..SHOWN], values.len())
            .replacen("]", ", …]", 1)
            .replacen(" … (", " (", 1)
    }
}

/// Name the sweep point a resolution error happened at.
fn at_point(e: Error, i: usize, values: &[f64]) -> Error {
    e.explained(&format!(" (at sweep point {i}: {})", shown(values)))
}
