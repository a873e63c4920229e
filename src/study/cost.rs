//! What a study will cost, estimated before it starts, and the bound above
//! which it does not start unless asked to (`--yes`).
//!
//! A study's runs are each a pure function of their resolved scene, so
//! their work is known before any runs: unknowns × steps (DOF-steps) per
//! run, summed. `taut converge --ratio 20 --levels 4` from 50 elements is
//! about 3·10¹² DOF-steps (days on one core) and used to start silently.
//! Every study (`compare`, `converge`, `precision`, `sweep`)
//! now builds an [`Estimate`] and calls [`Estimate::check`], which refuses
//! above `MAX_DOF_STEPS` with the estimate and what to change, unless
//! the caller said yes; `run --tolerance` refuses above the same bound
//! (its resolution is chosen, not given, so there is nothing to say yes to).

use crate::error::{Error, Result};
use crate::resolve::Resolved;

/// Largest study (or `run --tolerance`), in unknowns × steps summed over its
/// runs, started without `--yes`: 10¹¹ DOF-steps is about 9 minutes at the
/// [`RATE_DOF_STEPS_PER_S`] one core reaches at N ≤ 800, 15 minutes or more
/// on finer meshes (docs/performance.md).
pub(crate) const MAX_DOF_STEPS: f64 = 1e11;

/// DOF-steps per second one core steps the reference case at N ≤ 800
/// (docs/performance.md), for the time a refused estimate would take.
pub(crate) const RATE_DOF_STEPS_PER_S: f64 = 1.9e8;

/// The unknowns a run steps: (N + 1) × 2 for Hermite elements, N + 1 for
/// string elements (the FE mesh's; a modal or Galerkin basis steps fewer, so
/// this bounds it from above), plus one per carrier mass.
pub(crate) fn unknowns(sc: &Resolved) -> f64 {
    let per_node = if sc.beam.is_string() { 1.0 } else { 2.0 };
    (sc.elements as f64 + 1.0) * per_node + sc.carriers.len() as f64
}

/// A run's work: [`unknowns`] × steps.
pub(crate) fn run_dof_steps(sc: &Resolved) -> f64 {
    unknowns(sc) * sc.steps as f64
}

/// A study's estimated work.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The study, as a person calls it (`taut converge`).
    pub study: String,
    /// Runs it will make.
    pub runs: usize,
    /// DOF-steps over all its runs.
    pub dof_steps: f64,
    /// DOF-steps of its largest run.
    pub largest: f64,
}

impl Estimate {
    /// An estimate of nothing yet, for `study`.
    pub fn new(study: &str) -> Self {
        Estimate {
            study: study.to_string(),
            runs: 0,
            dof_steps: 0.0,
            largest: 0.0,
        }
    }

    /// Add `count` runs of `dof_steps` each.
    pub fn add(&mut self, count: usize, dof_steps: f64) {
        self.runs += count;
        self.dof_steps += count as f64 * dof_steps;
        if count > 0 {
            self.largest = self.largest.max(dof_steps);
        }
    }

    /// One line: the runs, the DOF-steps and the time on one core.
    pub fn describe(&self) -> String {
        format!(
            "{} would make {} runs of {:.2e} DOF-steps in all (the largest {:.2e}), about {} on one core at {RATE_DOF_STEPS_PER_S:.1e} DOF-steps/s",
            self.study,
            self.runs,
            self.dof_steps,
            self.largest,
            duration(self.dof_steps / RATE_DOF_STEPS_PER_S)
        )
    }

    /// Refuse a study above `MAX_DOF_STEPS` (or whose estimate is not a
    /// number) unless `yes`, naming the estimate, the bound and the way out.
    pub fn check(&self, yes: bool) -> Result<()> {
        let over = self.dof_steps.is_nan() || self.dof_steps > MAX_DOF_STEPS;
        if !over || yes {
            return Ok(());
        }
        Err(Error::invalid(
            "--yes",
            "not given",
            format!(
                "{}: above the bound of {MAX_DOF_STEPS:e} DOF-steps a study starts without being asked (docs/scene.md#study-cost). Give --yes to start it anyway, or make it smaller (fewer levels or runs, a smaller ratio, a coarser mesh or step, a shorter time.end)",
                self.describe()
            ),
        ))
    }

    /// Whether the estimate is above the bound (a front end says so when it
    /// starts such a study with `--yes`).
    pub fn over(&self) -> bool {
        self.dof_steps.is_nan() || self.dof_steps > MAX_DOF_STEPS
    }
}

/// Seconds as a person reads them: s, min, h or days.
fn duration(s: f64) -> String {
    if !s.is_finite() {
        "forever".into()
    } else if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.0} min", s / 60.0)
    } else if s < 2.0 * 86400.0 {
        format!("{:.1} h", s / 3600.0)
    } else if s < 1e4 * 86400.0 {
        format!("{:.0} days", s / 86400.0)
    } else {
        // a ratio of 1e23 gives 1e131 days: 132 digits in {:.0}
        format!("{:.1e} days", s / 86400.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_short_at_any_size() {
        assert_eq!(duration(30.0), "30 s");
        assert_eq!(duration(3.0 * 86400.0), "3 days");
        assert_eq!(duration(2.5e135), "2.9e130 days");
        assert_eq!(duration(f64::INFINITY), "forever");
    }

    #[test]
    fn a_study_above_the_bound_is_refused_unless_yes() {
        let mut e = Estimate::new("taut converge");
        e.add(3, 1e10);
        assert!(e.check(false).is_ok());
        e.add(1, 3e12);
        let msg = e.check(false).unwrap_err().to_string();
        assert!(
            msg.contains("taut converge would make 4 runs of 3.03e12 DOF-steps")
                && msg.contains("the largest 3.00e12")
                && msg.contains("4.4 h on one core")
                && msg.contains("Give --yes"),
            "{msg}"
        );
        assert!(e.check(true).is_ok());
        let mut nan = Estimate::new("x");
        nan.add(1, f64::NAN);
        assert!(nan.check(false).is_err());
    }
}
