//! One interface over the kinds of batch ([`RunBatch`]): several runs
//! stepped in lockstep, each bit-identical to the run alone — generalized-α
//! lanes ([`super::Batch`]) and `modal_exact` runs on one basis
//! ([`super::ModalBatch`]). Which runs share a batch is `batch_run.rs`'s.

use crate::model::beam::PointVector;

use super::batch::{Batch, Lane};
use super::sample::CarrierSample;

/// Several runs stepped in lockstep, each bit-identical to the run alone.
pub trait RunBatch: Send {
    /// The runs still in the batch, in lane order.
    fn lanes(&self) -> &[Lane];
    /// True when the batch can step its current number of runs (else the
    /// caller steps them alone).
    fn supported(&self) -> bool;
    /// Advance every run one step; a run that stops keeps its error in
    /// [`Lane::failed`].
    fn step(&mut self);
    /// The values of carrier `i` of lane `l` now.
    fn sample(&self, l: usize, i: usize) -> CarrierSample;
    /// rᵀd of lane `l` (a probe's displacement).
    fn displacement_at(&self, l: usize, pv: &PointVector) -> f64;
    /// Remove the runs at `gone` (lane indices, ascending); returns them in
    /// that order.
    fn retire(&mut self, gone: &[usize]) -> Vec<Lane>;
}

impl RunBatch for Batch {
    fn lanes(&self) -> &[Lane] {
        Batch::lanes(self)
    }
    fn supported(&self) -> bool {
        Batch::supported(self)
    }
    fn step(&mut self) {
        Batch::step(self)
    }
    fn sample(&self, l: usize, i: usize) -> CarrierSample {
        Batch::sample(self, l, i)
    }
    fn displacement_at(&self, l: usize, pv: &PointVector) -> f64 {
        Batch::displacement_at(self, l, pv)
    }
    fn retire(&mut self, gone: &[usize]) -> Vec<Lane> {
        Batch::retire(self, gone)
    }
}
