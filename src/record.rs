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
}

impl History {
    /// Empty history with room for `rows` rows.
    pub fn with_capacity(rows: usize, carriers: usize, probes: &[(String, f64)]) -> Self {
        History {
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
    /// Statistics of one trace; `length` is the span L (m).
    pub fn from_trace(t: &[f64], tr: &CarrierTrace, length: f64) -> Self {
        let n = t.len();
        let steps = n.saturating_sub(1).max(1);
        let mut lost = 0usize;
        let mut intervals = Vec::new();
        let mut intervals_t = Vec::new();
        let mut open: Option<usize> = None;
        let mut switches = 0;
        let mut max_gap = 0.0f64;
        for i in 1..n {
            let c = tr.in_contact[i];
            if c != tr.in_contact[i - 1] {
                switches += 1;
            }
            if c {
                max_gap = max_gap.max(tr.gap[i].abs());
                if let Some(s) = open.take() {
                    intervals.push([tr.x[s - 1] / length, tr.x[i - 1] / length]);
                    intervals_t.push([t[s - 1], t[i - 1]]);
                }
            } else {
                lost += 1;
                open.get_or_insert(i);
            }
        }
        if let Some(s) = open {
            intervals.push([tr.x[s - 1] / length, tr.x[n - 1] / length]);
            intervals_t.push([t[s - 1], t[n - 1]]);
        }
        let min_gap = tr.gap.iter().skip(1).copied().fold(f64::INFINITY, f64::min);
        let min_gap = if min_gap.is_finite() { min_gap } else { 0.0 };
        let f = if n > 1 { &tr.force[1..] } else { &tr.force[..] };
        let m = f.len().max(1) as f64;
        let mean = f.iter().sum::<f64>() / m;
        let var = f.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / m;
        ContactStats {
            loss_fraction: lost as f64 / steps as f64,
            first_loss_position: intervals.first().map(|iv| iv[0]),
            loss_intervals: intervals,
            loss_intervals_time: intervals_t,
            contact_switches: switches,
            force: ForceStats {
                mean,
                std: var.sqrt(),
                min: f.iter().copied().fold(f64::INFINITY, f64::min),
                max: f.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            },
            max_gap_in_contact: max_gap,
            max_penetration: (-min_gap).max(0.0),
            min_gap,
            max_gap_force_product: (1..n)
                .map(|i| (tr.gap[i] * tr.force[i]).abs())
                .fold(0.0, f64::max),
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
