//! Histories and statistics of a run (MODEL §7).
//!
//! Row 0 of every history is the initial state at t = 0; rows 1..=steps are
//! the ends of the steps. Statistics and P_l are taken over the steps
//! (rows 1..), as MODEL §5 defines P_l: steps with λ = 0 over all steps.

use serde::Serialize;

use crate::integrate::CarrierSample;

/// One carrier's recorded history, a column per quantity.
#[derive(Debug, Clone, Default)]
pub struct CarrierTrace {
    /// x_m, m.
    pub x: Vec<f64>,
    /// w = s·v(x_m), m.
    pub w: Vec<f64>,
    /// q, m.
    pub q: Vec<f64>,
    /// g = w − q, m.
    pub gap: Vec<f64>,
    /// λ, N.
    pub force: Vec<f64>,
    /// Contact closed.
    pub in_contact: Vec<bool>,
}

impl CarrierTrace {
    fn with_capacity(n: usize) -> Self {
        CarrierTrace {
            x: Vec::with_capacity(n),
            w: Vec::with_capacity(n),
            q: Vec::with_capacity(n),
            gap: Vec::with_capacity(n),
            force: Vec::with_capacity(n),
            in_contact: Vec::with_capacity(n),
        }
    }

    /// Append one sample (no allocation while within capacity).
    pub fn push(&mut self, s: &CarrierSample) {
        self.x.push(s.x);
        self.w.push(s.w);
        self.q.push(s.q);
        self.gap.push(s.gap);
        self.force.push(s.force);
        self.in_contact.push(s.in_contact);
    }
}

/// Everything recorded during a run.
#[derive(Debug, Clone, Default)]
pub struct History {
    /// Time, s.
    pub t: Vec<f64>,
    /// One trace per carrier, in scene order.
    pub carriers: Vec<CarrierTrace>,
    /// Probe names and their beam displacement v (positive up), m.
    pub probes: Vec<(String, Vec<f64>)>,
    /// Rows are row 0 (t = 0), every `record_every`-th step and the last
    /// step (`output.record_every`; 0 in a default history means 1).
    pub record_every: usize,
}

impl History {
    /// Empty history with room for `rows` rows, recording every
    /// `record_every`-th step.
    pub fn with_capacity(
        rows: usize,
        record_every: usize,
        carriers: usize,
        probes: &[(String, f64)],
    ) -> Self {
        History {
            record_every,
            t: Vec::with_capacity(rows),
            carriers: (0..carriers)
                .map(|_| CarrierTrace::with_capacity(rows))
                .collect(),
            probes: probes
                .iter()
                .map(|(n, _)| (n.clone(), Vec::with_capacity(rows)))
                .collect(),
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// True when nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}

/// Mean, standard deviation, min and max of the contact force, N.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ForceStats {
    /// Mean, N.
    pub mean: f64,
    /// Standard deviation (population), N.
    pub std: f64,
    /// Minimum, N.
    pub min: f64,
    /// Maximum, N.
    pub max: f64,
}

/// A carrier's contact statistics over the steps of a run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ContactStats {
    /// P_l: steps with the contact open over all steps.
    pub loss_fraction: f64,
    /// Loss intervals as [x_start/L, x_end/L]: a lost step covers
    /// [x_{i−1}, x_i], and adjacent lost steps merge.
    pub loss_intervals: Vec<[f64; 2]>,
    /// The same intervals in time, [t_start, t_end], s.
    pub loss_intervals_time: Vec<[f64; 2]>,
    /// x_m/L where contact is first lost (null if never).
    pub first_loss_position: Option<f64>,
    /// Number of contact state changes (closed → open and open → closed).
    pub contact_switches: usize,
    /// Force statistics over the steps, N (λ = 0 counts where contact is lost).
    pub force: ForceStats,
    /// Largest |gap| while in contact, m (round-off for the `end` placement).
    pub max_gap_in_contact: f64,
    /// Largest penetration max(0, −g), m (round-off for Lagrange; ≈ λ/κ for penalty).
    pub max_penetration: f64,
    /// Smallest gap over the steps, m.
    pub min_gap: f64,
    /// Largest |g·λ| over the steps, N·m (complementarity residual; 0 for exact Signorini).
    pub max_gap_force_product: f64,
}

impl ContactStats {
    /// Statistics of one trace; `length` is the span L (m). The same
    /// numbers, bit for bit, as [`ContactAccumulator`] fed row by row.
    /// Rows beyond the shortest column are ignored.
    pub fn from_trace(t: &[f64], tr: &CarrierTrace, length: f64) -> Self {
        let mut acc = ContactAccumulator::new(length);
        let n = [
            t.len(),
            tr.x.len(),
            tr.w.len(),
            tr.q.len(),
            tr.gap.len(),
            tr.force.len(),
            tr.in_contact.len(),
        ]
        .into_iter()
        .min()
        .unwrap_or(0);
        for i in 0..n {
            acc.push(
                t[i],
                &CarrierSample {
                    x: tr.x[i],
                    w: tr.w[i],
                    q: tr.q[i],
                    gap: tr.gap[i],
                    force: tr.force[i],
                    in_contact: tr.in_contact[i],
                },
            );
        }
        acc.finish()
    }
}

/// One carrier's contact statistics, accumulated a sample at a time over
/// every step, so that they do not depend on which rows the history keeps
/// (`output.record_every`). Row 0 (t = 0) is the initial state; statistics
/// are over the steps (rows 1..), as MODEL §5 defines P_l.
///
/// The force's standard deviation is Welford's running update, and its mean
/// the plain running sum over the steps divided by their number.
#[derive(Debug, Clone)]
pub struct ContactAccumulator {
    length: f64,
    /// Samples seen (row 0 included).
    rows: usize,
    prev_contact: bool,
    prev_x: f64,
    prev_t: f64,
    lost: usize,
    /// (x, t) at the row before the first lost step of the open interval.
    open: Option<(f64, f64)>,
    intervals: Vec<[f64; 2]>,
    intervals_t: Vec<[f64; 2]>,
    switches: usize,
    max_gap: f64,
    min_gap: f64,
    max_gap_force: f64,
    sum: f64,
    mean: f64,
    m2: f64,
    min: f64,
    max: f64,
    /// Row 0's force, used only when no step follows it.
    force0: f64,
    /// Largest |w| over every row (row 0 included), m.
    max_abs_w: f64,
}

impl ContactAccumulator {
    /// Empty statistics on a span of `length` m.
    pub fn new(length: f64) -> Self {
        ContactAccumulator {
            length,
            rows: 0,
            prev_contact: false,
            prev_x: 0.0,
            prev_t: 0.0,
            lost: 0,
            open: None,
            intervals: Vec::new(),
            intervals_t: Vec::new(),
            switches: 0,
            max_gap: 0.0,
            min_gap: f64::INFINITY,
            max_gap_force: 0.0,
            sum: -0.0,
            mean: 0.0,
            m2: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            force0: 0.0,
            max_abs_w: 0.0,
        }
    }

    /// Add the sample of the next row (row 0 first) at time `t`. Allocates
    /// only when a loss interval closes beyond the intervals' capacity.
    pub fn push(&mut self, t: f64, s: &CarrierSample) {
        self.max_abs_w = self.max_abs_w.max(s.w.abs());
        if self.rows == 0 {
            self.force0 = s.force;
        } else {
            let c = s.in_contact;
            if c != self.prev_contact {
                self.switches += 1;
            }
            if c {
                self.max_gap = self.max_gap.max(s.gap.abs());
                if let Some((x0, t0)) = self.open.take() {
                    self.intervals
                        .push([x0 / self.length, self.prev_x / self.length]);
                    self.intervals_t.push([t0, self.prev_t]);
                }
            } else {
                self.lost += 1;
                self.open.get_or_insert((self.prev_x, self.prev_t));
            }
            self.min_gap = self.min_gap.min(s.gap);
            self.max_gap_force = self.max_gap_force.max((s.gap * s.force).abs());
            let f = s.force;
            self.sum += f;
            let k = self.rows as f64; // steps so far, this one included
            let d = f - self.mean;
            self.mean += d / k;
            self.m2 += d * (f - self.mean);
            self.min = self.min.min(f);
            self.max = self.max.max(f);
        }
        self.prev_contact = s.in_contact;
        self.prev_x = s.x;
        self.prev_t = t;
        self.rows += 1;
    }

    /// Largest |w| seen (row 0 included), m.
    pub fn max_abs_w(&self) -> f64 {
        self.max_abs_w
    }

    /// The statistics of every sample pushed.
    pub fn finish(mut self) -> ContactStats {
        if let Some((x0, t0)) = self.open.take() {
            self.intervals
                .push([x0 / self.length, self.prev_x / self.length]);
            self.intervals_t.push([t0, self.prev_t]);
        }
        let steps = self.rows.saturating_sub(1);
        let min_gap = if self.min_gap.is_finite() {
            self.min_gap
        } else {
            0.0
        };
        let force = if steps == 0 {
            // no step: the initial state's force alone (or nothing)
            let f = if self.rows == 0 { 0.0 } else { self.force0 };
            let (min, max) = if self.rows == 0 {
                (f64::INFINITY, f64::NEG_INFINITY)
            } else {
                (f, f)
            };
            ForceStats {
                mean: f,
                std: 0.0,
                min,
                max,
            }
        } else {
            ForceStats {
                mean: self.sum / steps as f64,
                std: (self.m2 / steps as f64).sqrt(),
                min: self.min,
                max: self.max,
            }
        };
        ContactStats {
            loss_fraction: self.lost as f64 / steps.max(1) as f64,
            first_loss_position: self.intervals.first().map(|iv| iv[0]),
            loss_intervals: self.intervals,
            loss_intervals_time: self.intervals_t,
            contact_switches: self.switches,
            force,
            max_gap_in_contact: self.max_gap,
            max_penetration: (-min_gap).max(0.0),
            min_gap,
            max_gap_force_product: self.max_gap_force,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(contact: &[bool]) -> (Vec<f64>, CarrierTrace) {
        let n = contact.len();
        let t: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let tr = CarrierTrace {
            x: t.clone(),
            w: vec![0.0; n],
            q: vec![0.0; n],
            gap: vec![0.0; n],
            force: contact.iter().map(|&c| if c { 2.0 } else { 0.0 }).collect(),
            in_contact: contact.to_vec(),
        };
        (t, tr)
    }

    #[test]
    fn loss_fraction_and_intervals_agree() {
        // steps 1..=8; lost at steps 3,4 and 8
        let (t, tr) = trace(&[true, true, true, false, false, true, true, true, false]);
        let s = ContactStats::from_trace(&t, &tr, 8.0);
        assert_eq!(s.loss_fraction, 3.0 / 8.0);
        assert_eq!(
            s.loss_intervals,
            vec![[2.0 / 8.0, 4.0 / 8.0], [7.0 / 8.0, 1.0]]
        );
        let measure: f64 = s.loss_intervals_time.iter().map(|iv| iv[1] - iv[0]).sum();
        assert_eq!(measure / 8.0, s.loss_fraction);
        assert_eq!(s.contact_switches, 3);
        assert_eq!(s.first_loss_position, Some(0.25));
        assert_eq!(s.force.min, 0.0);
        assert_eq!(s.force.max, 2.0);
    }

    #[test]
    fn no_loss_gives_no_interval() {
        let (t, tr) = trace(&[true; 5]);
        let s = ContactStats::from_trace(&t, &tr, 4.0);
        assert_eq!(s.loss_fraction, 0.0);
        assert!(s.loss_intervals.is_empty());
        assert_eq!(s.first_loss_position, None);
        assert_eq!(s.force.std, 0.0);
    }
}
