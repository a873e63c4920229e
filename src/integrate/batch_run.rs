//! Runs stepped together, as the driver of a batch (`run::run_batch`) sees
//! them: which runs may share a batch ([`batch_key`]), how many at most
//! ([`lanes_cap`]), and one interface ([`RunBatch`]) over the two kinds —
//! generalized-α runs sharing one factorization as SIMD lanes
//! ([`super::Batch`]), `modal_exact` runs sharing one basis
//! ([`super::ModalBatch`]).

use crate::error::Error;
use crate::model::beam::PointVector;
use crate::scene::{Resolved, Scheme};

use super::batch::{MAX_LANES, gen_alpha_key, max_lanes, scene_columns};
use super::modal_batch::modal_key;
use super::{Batch, CarrierSample, Lane, ModalBatch};

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

/// The key of the runs that may step together: `None` when `sc` cannot
/// batch. Generalized-α runs with equal keys share their effective matrix
/// and right-hand-side columns (`integrate::batch`); `modal_exact` runs
/// their basis and Δt (`integrate::modal_batch`).
pub fn batch_key(sc: &Resolved) -> Option<String> {
    gen_alpha_key(sc).or_else(|| modal_key(sc))
}

/// Most runs of scene `sc` one batch takes: the kernels compiled for its
/// columns (generalized-α, [`max_lanes`]), or [`MAX_LANES`] (`modal_exact`).
pub fn lanes_cap(sc: &Resolved) -> usize {
    match sc.scheme {
        Scheme::ModalExact => MAX_LANES,
        _ => max_lanes(scene_columns(sc)),
    }
}

/// A built batch (when any run built) and the runs that failed to build,
/// with the caller's ids.
pub type NewBatch = (Option<Box<dyn RunBatch>>, Vec<(usize, Error)>);

/// Build the batch for `scenes` (equal [`batch_key`]s; `ids` are the
/// caller's indices), of the kind the key names. A run that fails to build
/// is returned in the error list with its id.
pub fn new_batch(scenes: &[(usize, &Resolved)]) -> NewBatch {
    match scenes.first().map(|(_, sc)| sc.scheme) {
        Some(Scheme::ModalExact) => {
            let (b, e) = ModalBatch::new(scenes);
            (b.map(|b| Box::new(b) as Box<dyn RunBatch>), e)
        }
        _ => {
            let (b, e) = Batch::new(scenes);
            (b.map(|b| Box::new(b) as Box<dyn RunBatch>), e)
        }
    }
}
