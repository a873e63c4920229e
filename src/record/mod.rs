//! Histories and statistics of a run (MODEL §7).
//!
//! Row 0 of every history is the initial state at t = 0; rows 1..=steps are
//! the ends of the steps. Statistics and P_l are taken over the steps
//! (rows 1..), as MODEL §5 defines P_l: steps with λ = 0 over all steps.

use crate::integrate::CarrierSample;

pub mod dropper;
pub mod envelope;
pub mod span;
pub mod stats;
pub mod support;
pub mod wire;
pub mod zone;

pub use dropper::{DropperAccumulator, DropperSample, DropperStats};
pub use envelope::Envelope;
pub use span::{SpanAccumulator, SpanStats, span_of};
pub use stats::{
    ContactAccumulator, ContactStats, Filtered, FilteredForce, ForceStats, LossClass, Recontact,
};
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
