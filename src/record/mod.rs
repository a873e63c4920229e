//! Histories and statistics of a run (MODEL §7).
//!
//! Row 0 of every history is the initial state at t = 0; rows 1..=steps are
//! the ends of the steps. Time statistics (means, σ, RMS, P_l) are taken
//! over the window [0, T], T the scene's end time, whatever Δt
//! ([`window`]); extremes over the steps (rows 1..).

use crate::integrate::CarrierSample;

pub mod dropper;
pub mod envelope;
pub mod filter;
pub mod span;
pub mod standard;
pub mod stats;
pub mod support;
pub mod window;
pub mod wire;
pub mod zone;

pub(crate) use dropper::DropperAccumulator;
pub use dropper::{DropperSample, DropperStats};
pub use envelope::Envelope;
pub use span::SpanStats;
pub(crate) use span::{SpanAccumulator, span_of};
pub use standard::StandardStats;
pub(crate) use standard::{Section, SectionCount, standard_stats};
pub(crate) use stats::ContactAccumulator;
pub use stats::{ContactStats, Filtered, FilteredForce, ForceStats, LossClass, Recontact};
pub use support::SupportUplift;
pub use wire::WireSeries;
pub use zone::LossGeometry;

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
    /// λ low-pass filtered to 0–`History::filter_band_hz` Hz (zero phase,
    /// [`filter::lowpass_zero_phase`]), N, one value per row; filled when
    /// the run ends, and empty when the history keeps only every K-th step
    /// (the filter needs every step).
    pub force_filtered: Vec<f64>,
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
            force_filtered: Vec::new(),
        }
    }

    /// Append one sample (no allocation while within capacity).
    #[inline]
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
    /// Dropper names and their force N_d (tension positive), N; empty
    /// without `[[dropper]]`.
    pub droppers: Vec<(String, Vec<f64>)>,
    /// Rows are row 0 (t = 0), every `record_every`-th step and the last
    /// step (`output.record_every`; 0 in a default history means 1).
    pub record_every: usize,
    /// Snapshots of v(x) (`output.snapshots`; empty when none asked for).
    pub snapshots: WireSeries,
    /// The space–time field v(x, t) (`output.field`; empty when none).
    pub field: WireSeries,
    /// v's range at each support (`output.supports`; empty when none).
    pub supports: Vec<SupportUplift>,
    /// v's range at every node (`output.envelope`; empty when not asked).
    pub envelope: Envelope,
    /// The band of the carriers' `force_filtered`, Hz (`[analysis] band`;
    /// 0 in a default history means [`filter::FORCE_BAND_HZ`]).
    pub filter_band_hz: f64,
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
            droppers: Vec::new(),
            snapshots: WireSeries::default(),
            field: WireSeries::default(),
            supports: Vec::new(),
            envelope: Envelope::default(),
            filter_band_hz: filter::FORCE_BAND_HZ,
        }
    }

    /// The band of the filtered force, Hz.
    pub fn band_hz(&self) -> f64 {
        if self.filter_band_hz > 0.0 {
            self.filter_band_hz
        } else {
            filter::FORCE_BAND_HZ
        }
    }

    /// Filter every carrier's force to 0–[`History::band_hz`] Hz into its
    /// `force_filtered` (time step `dt`, s), when the history holds every
    /// step; else leave them empty.
    pub fn filter_forces(&mut self, dt: f64) {
        let band = self.band_hz();
        let every = self.record_every <= 1;
        for tr in &mut self.carriers {
            tr.force_filtered = if every && !tr.force.is_empty() {
                filter::lowpass_zero_phase(&tr.force, dt, band)
            } else {
                Vec::new()
            };
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
