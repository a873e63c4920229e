//! Where a sweep's time went: its points' work (unknowns × steps, and CPU
//! seconds where the platform has a thread clock) split between points
//! that met the tolerance, points that did not, and points refused or
//! stopped with an error — the summary line of `taut sweep`.

use super::record::SweepRecord;

/// The work of one class of points.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Work {
    /// Points in the class.
    pub points: usize,
    /// Their unknowns × steps, every run made for them.
    pub dof_steps: f64,
    /// Their CPU seconds (records of an earlier taut, or of a platform
    /// without a thread clock, count none).
    pub cpu_seconds: f64,
}

impl Work {
    fn add(&mut self, r: &SweepRecord) {
        self.points += 1;
        self.dof_steps += r.dof_steps.unwrap_or(0.0);
        self.cpu_seconds += r.cpu_seconds.unwrap_or(0.0);
    }
}

/// A sweep's work split by how its points ended.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorkSplit {
    /// Points that ran to the end: with `--tolerance`, those that met it.
    pub met: Work,
    /// With `--tolerance`: points that ran but did not meet it.
    pub not_met: Work,
    /// Points refused (their scene) or stopped with an error.
    pub refused: Work,
}

impl WorkSplit {
    /// The split of `records`.
    pub fn of(records: &[SweepRecord]) -> Self {
        let mut s = WorkSplit::default();
        for r in records {
            if r.error.is_some() {
                s.refused.add(r);
            } else if r.accuracy.as_ref().is_some_and(|a| !a.met) {
                s.not_met.add(r);
            } else {
                s.met.add(r);
            }
        }
        s
    }

    /// All points' work.
    pub fn total(&self) -> Work {
        Work {
            points: self.met.points + self.not_met.points + self.refused.points,
            dof_steps: self.met.dof_steps + self.not_met.dof_steps + self.refused.dof_steps,
            cpu_seconds: self.met.cpu_seconds + self.not_met.cpu_seconds + self.refused.cpu_seconds,
        }
    }

    /// `part`'s share of the whole work (unknowns × steps), 0–1; 0 when
    /// nothing was counted.
    pub fn share(&self, part: &Work) -> f64 {
        let t = self.total().dof_steps;
        if t > 0.0 { part.dof_steps / t } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::sweep::PointAccuracy;

    fn record(met: Option<bool>, error: bool, dof_steps: f64, cpu: f64) -> SweepRecord {
        let mut r = SweepRecord::stopped("id", 0, vec![]);
        r.dof_steps = Some(dof_steps);
        r.cpu_seconds = Some(cpu);
        r.error = error.then(|| "refused".to_string());
        r.accuracy = met.map(|met| PointAccuracy {
            value: 0.0,
            u_num: 0.0,
            met,
            elements: 1,
            modes: None,
            dt: 1e-4,
            runs: 5,
            dof_steps,
            estimator: "gci".into(),
            checks: 0,
            predicted_cost: None,
            not_met: None,
            u_num_ladder: vec![],
            runs_made: vec![],
        });
        r
    }

    #[test]
    fn the_split_counts_each_point_once_by_how_it_ended() {
        let rs = [
            record(Some(true), false, 1.0, 0.5),
            record(Some(false), false, 6.0, 3.0),
            record(Some(false), false, 2.0, 1.0),
            record(None, true, 1.0, 0.25),
        ];
        let s = WorkSplit::of(&rs);
        assert_eq!(
            (s.met.points, s.not_met.points, s.refused.points),
            (1, 2, 1)
        );
        assert_eq!(s.not_met.dof_steps, 8.0);
        assert_eq!(s.not_met.cpu_seconds, 4.0);
        assert_eq!(s.total().dof_steps, 10.0);
        assert!((s.share(&s.not_met) - 0.8).abs() < 1e-15);
        // a plain sweep's points that ran are all "met"
        let plain = WorkSplit::of(&[record(None, false, 3.0, 1.0)]);
        assert_eq!(plain.met.points, 1);
    }
}
