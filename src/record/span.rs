//! A carrier's contact force statistics per span (`[output] supports`;
//! docs/output.md#spans): the contact force's mean, σ, max and min, P_l and
//! the number of samples over the steps whose contact point x_m lies in
//! each span, the pieces EN 50318/50367 read span by span.
//!
//! The supports x_0 < x_1 < … < x_S (m) cut the line into spans
//! [x_k, x_{k+1}); the last span is closed, [x_{S−1}, x_S]. A step counts
//! in span k when its contact point x_m lies there (steps outside
//! [x_0, x_S] count in no span). As for the whole-run statistics (MODEL §5,
//! §7), the steps are rows 1…; row 0 (t = 0) is the initial state.
//!
//! ```text
//! mean_k = Σ λ_i / n_k,   σ_k² = Σ (λ_i − mean_k)² / n_k,   P_l,k = (open steps)_k / n_k
//! ```
//!
//! over the n_k steps i in span k; σ_k is Welford's running update, as
//! `super::ContactAccumulator`'s, the mean the plain running sum over n_k.

use serde::Serialize;

/// The span of position `x` (m) among the `supports` (m, strictly
/// increasing): k with x_k ≤ x < x_{k+1}, or the last span for x = x_S;
/// `None` outside [x_0, x_S] or with fewer than two supports. O(log S), no
/// allocation.
pub(crate) fn span_of(supports: &[f64], x: f64) -> Option<usize> {
    let (&first, &last) = (supports.first()?, supports.last()?);
    if supports.len() < 2 || !(first..=last).contains(&x) {
        return None;
    }
    // supports ≤ x: at least one (x ≥ x_0); the span starts at the last of them
    let k = supports.partition_point(|&s| s <= x) - 1;
    Some(k.min(supports.len() - 2))
}

/// One carrier's contact force statistics over one span.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct SpanStats {
    /// The carrier's index, in scene order.
    pub carrier: usize,
    /// The span's index k (0 from the first support).
    pub span: usize,
    /// The span's start x_k, m.
    pub x_start: f64,
    /// The span's end x_{k+1}, m.
    pub x_end: f64,
    /// Steps whose contact point lies in the span.
    pub samples: usize,
    /// Mean contact force, N (null when no step lies in the span).
    pub force_mean: Option<f64>,
    /// Standard deviation (population), N.
    pub force_std: Option<f64>,
    /// Maximum, N.
    pub force_max: Option<f64>,
    /// Minimum, N.
    pub force_min: Option<f64>,
    /// Mean of the 0–20 Hz filtered force over the same steps, N
    /// (docs/output.md#filtered-force; null when the history does not hold
    /// every step, or no step lies in the span; absent where the summary's
    /// filter is not run).
    pub filtered_mean: Option<f64>,
    /// Standard deviation (population) of the 0–20 Hz filtered force, N.
    pub filtered_std: Option<f64>,
    /// P_l in the span: steps with the contact open over the span's steps
    /// (null when no step lies in the span).
    pub loss_fraction: Option<f64>,
}

/// Accumulates one carrier's [`SpanStats`] over one span, a step at a time
/// (no allocation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpanAccumulator {
    carrier: usize,
    span: usize,
    x_start: f64,
    x_end: f64,
    samples: usize,
    lost: usize,
    sum: f64,
    mean: f64,
    m2: f64,
    min: f64,
    max: f64,
}

impl SpanAccumulator {
    /// Empty statistics of carrier `carrier` over span `span`, [x_start, x_end] (m).
    pub fn new(carrier: usize, span: usize, x_start: f64, x_end: f64) -> Self {
        SpanAccumulator {
            carrier,
            span,
            x_start,
            x_end,
            samples: 0,
            lost: 0,
            sum: -0.0,
            mean: 0.0,
            m2: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
        }
    }

    /// The spans between consecutive `supports` of carrier `carrier`, each
    /// empty.
    pub fn for_supports(carrier: usize, supports: &[f64]) -> Vec<Self> {
        supports
            .windows(2)
            .enumerate()
            .map(|(k, w)| Self::new(carrier, k, w[0], w[1]))
            .collect()
    }

    /// Add one step's contact force `force` (N) and contact state.
    pub fn push(&mut self, force: f64, in_contact: bool) {
        self.samples += 1;
        self.lost += usize::from(!in_contact);
        self.sum += force;
        let d = force - self.mean;
        self.mean += d / self.samples as f64;
        self.m2 += d * (force - self.mean);
        self.min = self.min.min(force);
        self.max = self.max.max(force);
    }

    /// The statistics of the steps pushed (the filtered ones left out:
    /// [`SpanStats::filtered_mean`] is filled by the summary, which runs the
    /// filter over the history).
    pub fn finish(&self) -> SpanStats {
        let n = self.samples as f64;
        let some = |v: f64| (self.samples > 0).then_some(v);
        SpanStats {
            carrier: self.carrier,
            span: self.span,
            x_start: self.x_start,
            x_end: self.x_end,
            samples: self.samples,
            force_mean: some(self.sum / n),
            force_std: some((self.m2 / n).sqrt()),
            force_max: some(self.max),
            force_min: some(self.min),
            filtered_mean: None,
            filtered_std: None,
            loss_fraction: some(self.lost as f64 / n),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_lies_in_the_span_that_starts_at_or_before_it() {
        let s = [0.0, 10.0, 25.0];
        assert_eq!(span_of(&s, 0.0), Some(0));
        assert_eq!(span_of(&s, 9.999), Some(0));
        assert_eq!(span_of(&s, 10.0), Some(1));
        assert_eq!(span_of(&s, 25.0), Some(1), "the last span is closed");
        assert_eq!(span_of(&s, -1e-9), None);
        assert_eq!(span_of(&s, 25.000_001), None);
        assert_eq!(span_of(&s, f64::NAN), None);
        assert_eq!(span_of(&[5.0], 5.0), None, "one support: no span");
        assert_eq!(span_of(&[], 5.0), None);
    }

    #[test]
    fn statistics_of_a_span() {
        let mut a = SpanAccumulator::new(1, 2, 10.0, 20.0);
        assert_eq!(a.finish().force_mean, None);
        for (f, c) in [(1.0, true), (0.0, false), (5.0, true), (2.0, true)] {
            a.push(f, c);
        }
        let s = a.finish();
        assert_eq!((s.carrier, s.span, s.samples), (1, 2, 4));
        assert_eq!(s.force_mean, Some(2.0));
        assert_eq!(s.force_std, Some(3.5f64.sqrt()));
        assert_eq!((s.force_min, s.force_max), (Some(0.0), Some(5.0)));
        assert_eq!(s.loss_fraction, Some(0.25));
    }
}
