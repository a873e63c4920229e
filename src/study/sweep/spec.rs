//! What a sweep is ([`SweepSpec`]): the scene, its fixed overrides and the
//! axes; its grid, its checks before any run, and its estimated work.

use serde::{Deserialize, Serialize};

use super::axis::Axis;
use super::shard::Shard;
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
}

impl SweepSpec {
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
        // the scene text and the fixed overrides, once (an error there is
        // the first point's, as when each point parsed the text itself)
        let base = self
            .base_tree()
            .map_err(|e| at_point(e, 0, &self.point(0)))?;
        for i in 0..self.len() {
            self.resolve_on(&base, i)
                .map_err(|e| at_point(e, i, &self.point(i)))?;
            if self.check_refinement {
                self.resolve_refined_on(&base, i).map_err(|e| {
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
            let (x, y) = (
                self.resolve_at(&base, &first)?,
                self.resolve_at(&base, &last)?,
            );
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
        let base = self.base_tree()?;
        for i in (0..self.len()).filter(|&i| shard.is_none_or(|s| s.owns(i))) {
            e.add(1, run_dof_steps(&self.resolve_on(&base, i)?));
            if self.check_refinement {
                e.add(1, run_dof_steps(&self.resolve_refined_on(&base, i)?));
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
