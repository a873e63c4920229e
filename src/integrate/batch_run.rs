//! Choosing a batch, as the driver of a batch (`run::run_batch`) sees it:
//! which runs may share one ([`super::batch_key`], `batch_key.rs`), how many at most
//! ([`lanes_cap`]), and building it ([`new_batch`]) of the kind the key
//! names — generalized-α runs sharing one factorization as SIMD lanes
//! ([`super::Batch`]), `modal_exact` runs sharing one basis
//! ([`super::ModalBatch`]); both step behind [`RunBatch`].

use crate::error::Error;
use crate::resolve::Resolved;
use crate::scene::Scheme;

use super::batch::Batch;
use super::batch::{MAX_LANES, max_lanes};
use super::batch_key::scene_columns;
use super::modal_batch::ModalBatch;
use super::run_batch::RunBatch;

/// Most runs of scene `sc` one batch takes: the kernels compiled for its
/// columns (generalized-α, [`max_lanes`]), or [`MAX_LANES`] (`modal_exact`).
pub(crate) fn lanes_cap(sc: &Resolved) -> usize {
    match sc.method.scheme {
        Scheme::ModalExact => MAX_LANES,
        _ => max_lanes(scene_columns(sc)),
    }
}

/// A built batch (when any run built) and the runs that failed to build,
/// with the caller's ids.
pub(crate) type NewBatch = (Option<Box<dyn RunBatch>>, Vec<(usize, Error)>);

/// Build the batch for `scenes` (equal [`super::batch_key`]s; `ids` are the
/// caller's indices), of the kind the key names. A run that fails to build
/// is returned in the error list with its id.
pub fn new_batch(scenes: &[(usize, &Resolved)]) -> NewBatch {
    match scenes.first().map(|(_, sc)| sc.method.scheme) {
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
