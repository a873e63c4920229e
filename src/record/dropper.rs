//! A dropper's recorded statistics (`docs/output.md`, `docs/lines.md`):
//! its force range and its slack intervals, the dropper's counterpart of a
//! contact's loss intervals (`stats.rs`).
//!
//! A tension-only dropper is slack on a step when the contact law leaves
//! it open (N_d = 0, the row inactive). As with contact loss (MODEL §5),
//! a slack step covers [t_{i−1}, t_i], adjacent slack steps merge into one
//! interval, and the slack fraction is slack steps over all steps (rows
//! 1..; row 0 is the initial state). A linear dropper is never slack (it
//! may push: its force may be negative).

use serde::Serialize;

pub use crate::integrate::DropperSample;
use crate::resolve::MAX_STORED_EVENTS;

/// A dropper's statistics over a run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct DropperStats {
    /// The dropper's name (`[[dropper]] name`, default its index).
    pub name: String,
    /// Position x_d, m.
    pub x: f64,
    /// Declared never slack (`linear = true`).
    pub linear: bool,
    /// Steps slack over all steps.
    pub slack_fraction: f64,
    /// Total slack time, s (slack steps · Δt).
    pub slack_time: f64,
    /// Number of slack intervals (all of them, listed or not).
    pub slack_interval_count: usize,
    /// Slack intervals [t_start, t_end], s (at most `MAX_STORED_EVENTS`).
    pub slack_intervals_time: Vec<[f64; 2]>,
    /// Force statistics over the steps, N (0 while slack).
    pub force: crate::record::ForceStats,
}

/// Accumulates a [`DropperStats`] step by step (no allocation until an
/// interval is stored).
#[derive(Debug, Clone)]
pub(crate) struct DropperAccumulator {
    name: String,
    x: f64,
    linear: bool,
    rows: usize,
    slack: usize,
    slack_time: f64,
    prev_t: f64,
    open: Option<f64>,
    count: usize,
    intervals: Vec<[f64; 2]>,
    sum: f64,
    sum2: f64,
    min: f64,
    max: f64,
}

impl DropperAccumulator {
    /// For the dropper `name` at `x` (m).
    pub fn new(name: &str, x: f64, linear: bool) -> Self {
        DropperAccumulator {
            name: name.to_string(),
            x,
            linear,
            rows: 0,
            slack: 0,
            slack_time: 0.0,
            prev_t: 0.0,
            open: None,
            count: 0,
            intervals: Vec::new(),
            sum: 0.0,
            sum2: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
        }
    }

    /// Add the row at time t (row 0 is the initial state: only its time is kept).
    pub fn push(&mut self, t: f64, s: DropperSample) {
        if self.rows > 0 {
            let f = s.force;
            self.sum += f;
            self.sum2 += f * f;
            self.min = self.min.min(f);
            self.max = self.max.max(f);
            if s.slack {
                self.slack += 1;
                self.slack_time += t - self.prev_t;
                if self.open.is_none() {
                    self.open = Some(self.prev_t);
                }
            } else {
                self.close(self.prev_t);
            }
        }
        self.rows += 1;
        self.prev_t = t;
    }

    fn close(&mut self, end: f64) {
        if let Some(start) = self.open.take() {
            self.count += 1;
            if self.intervals.len() < MAX_STORED_EVENTS {
                self.intervals.push([start, end]);
            }
        }
    }

    /// The statistics of the rows pushed.
    pub fn finish(mut self) -> DropperStats {
        self.close(self.prev_t);
        let steps = self.rows.saturating_sub(1);
        let n = steps.max(1) as f64;
        let mean = self.sum / n;
        let var = (self.sum2 / n - mean * mean).max(0.0);
        let empty = steps == 0;
        DropperStats {
            name: self.name,
            x: self.x,
            linear: self.linear,
            slack_fraction: self.slack as f64 / n,
            slack_time: self.slack_time,
            slack_interval_count: self.count,
            slack_intervals_time: self.intervals,
            force: crate::record::ForceStats {
                mean,
                std: var.sqrt(),
                min: if empty { 0.0 } else { self.min },
                max: if empty { 0.0 } else { self.max },
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adjacent_slack_steps_merge_into_one_interval() {
        let mut acc = DropperAccumulator::new("a", 1.0, false);
        let rows = [
            (0.0, false),
            (1.0, false),
            (2.0, true),
            (3.0, true),
            (4.0, false),
            (5.0, true),
        ];
        for (t, slack) in rows {
            let force = if slack { 0.0 } else { 10.0 };
            acc.push(t, DropperSample { force, slack });
        }
        let s = acc.finish();
        assert_eq!(s.slack_interval_count, 2);
        assert_eq!(s.slack_intervals_time, vec![[1.0, 3.0], [4.0, 5.0]]);
        assert_eq!(s.slack_time, 3.0);
        assert_eq!(s.slack_fraction, 3.0 / 5.0);
        assert_eq!((s.force.min, s.force.max), (0.0, 10.0));
    }
}
