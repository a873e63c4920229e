//! One carrier of one run, as the quantities read it ([`Reading`]): its
//! contact statistics, its trace, and what several quantities share and is
//! worth computing once (the 0–20 Hz filtered force).

use std::cell::OnceCell;

use crate::record::filter::{lowpass_zero_phase, stats_of_filtered};
use crate::record::{CarrierTrace, ContactStats};
use crate::run::RunOutput;

/// Carrier `carrier` of a run, read by [`super::Quantity::read`].
pub struct Reading<'a> {
    /// The run.
    pub out: &'a RunOutput,
    /// The carrier's index.
    pub carrier: usize,
    /// Its contact statistics (MODEL §7).
    pub stats: &'a ContactStats,
    /// Its trace (the history's rows).
    pub trace: &'a CarrierTrace,
    filtered: OnceCell<[f64; 4]>,
}

impl<'a> Reading<'a> {
    /// Carrier `carrier` of `out`; `None` when the run has no such carrier.
    pub fn new(out: &'a RunOutput, carrier: usize) -> Option<Self> {
        Some(Reading {
            out,
            carrier,
            stats: out.stats.get(carrier)?,
            trace: out.history.carriers.get(carrier)?,
            filtered: OnceCell::new(),
        })
    }

    /// [mean, std, min, max] of the filtered force, N (band 0–20 Hz unless
    /// `[analysis] band`; mean and σ over the window [0, T], min and max
    /// over the steps): the history's `force_filtered`,
    /// or, when the history does not hold it (every K-th step kept), its
    /// rows filtered at the run's Δt. Filtered once per reading.
    pub fn filtered(&self) -> [f64; 4] {
        *self.filtered.get_or_init(|| {
            let band = self.out.history.band_hz();
            let (tr, t, end) = (self.trace, &self.out.history.t, self.out.window_end);
            let s = if tr.force_filtered.is_empty() {
                let f = lowpass_zero_phase(&tr.force, self.out.dt, band);
                stats_of_filtered(t, &f, end, band)
            } else {
                stats_of_filtered(t, &tr.force_filtered, end, band)
            };
            [s.mean, s.std, s.min, s.max]
        })
    }

    /// The beam's displacement w under the carrier at every row, m.
    pub fn w(&self) -> &'a [f64] {
        &self.trace.w
    }
}
