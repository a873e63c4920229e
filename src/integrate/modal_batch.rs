//! `modal_exact` runs stepped together: runs that share a basis
//! and Δt — a sweep over speed, mass, spring, preload, carriers — build the
//! basis, its exact step maps and its fast-shape tables once
//! ([`ModalCoefs`], shared by reference) and step in lockstep.
//!
//! A modal step has no recurrence across modes for lanes to hide (its loops
//! are vectorized across modes already, `modal_exact.rs`), so what runs on
//! one basis share is its data: the batch builds the basis (root finding
//! and normalization of J modes), the step maps and the shape tables once,
//! and steps each run with the very function a run alone calls, on its own
//! state, with its contact update deferred to the next step's pass
//! (`modal_exact.rs`, "Deferred update": one pass over the modes a step
//! instead of two, as a whole run alone does): bit-identical
//! to the run alone (`tests/batch.rs` compares the bytes). Interleaving the runs by blocks of modes, so that
//! a block's coefficients are read once for all of them, was measured and
//! gave nothing (0.9–1.07× on 8 runs at J = 800, within the timing noise on
//! an AMD EPYC, 2 vCPUs: the passes stream from L2 as fast alone), so it was
//! left out.
//!
//! What batches: `integrator.method = "modal_exact"` on `galerkin` or
//! `modal`, runs with the same beam, basis (kind, J, and the FE mesh of a
//! `modal` basis) and Δt ([`super::modal_key`]); up to [`super::MAX_LANES`] runs.

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::model::beam::{BeamModel, PointVector};
use crate::resolve::Resolved;

use super::batch::Lane;
use super::modal_exact::{ModalCoefs, ModalExact};
use super::run_batch::RunBatch;
use super::sample::CarrierSample;
use super::state::State;
use super::system::System;

/// `modal_exact` runs on one basis at one Δt (module docs).
pub(crate) struct ModalBatch {
    lanes: Vec<Lane>,
    steppers: Vec<ModalExact>,
}

impl ModalBatch {
    /// Build the runs `scenes` (equal [`super::modal_key`]s): the basis and its
    /// coefficients once, then each run's system, initial state and
    /// stepper as [`super::Integrator::new`] makes them. A run that fails
    /// to build is returned in the error list with its id.
    pub fn new(scenes: &[(usize, &Resolved)]) -> (Option<ModalBatch>, Vec<(usize, Error)>) {
        let mut errors = Vec::new();
        let Some(&(_, first)) = scenes.first() else {
            return (None, errors);
        };
        let shared = BeamModel::build(&first.beam, &first.mesh_plan())
            .and_then(|beam| Ok((Arc::new(ModalCoefs::new(&beam, first.dt)?), beam)));
        let (coefs, beam) = match shared {
            Ok(s) => s,
            Err(e) => {
                // each run alone would stop with the same error
                for &(id, _) in scenes {
                    errors.push((id, Error::invalid("batch", "basis", e.to_string())));
                }
                return (None, errors);
            }
        };
        let mut b = ModalBatch {
            lanes: Vec::with_capacity(scenes.len()),
            steppers: Vec::with_capacity(scenes.len()),
        };
        for &(id, sc) in scenes {
            let made = (|| -> Result<(System, State, ModalExact)> {
                let mut sys = System::with_beam(sc, beam.clone())?;
                let st = State::at_rest(sys.beam().n, sys.contacts());
                sys.initial()?;
                let stepper = ModalExact::with_coefs(Arc::clone(&coefs), &mut sys)?;
                Ok((sys, st, stepper))
            })();
            match made {
                Ok((sys, st, stepper)) => {
                    b.lanes.push(Lane {
                        sys,
                        st,
                        id,
                        failed: None,
                    });
                    b.steppers.push(stepper);
                }
                Err(e) => errors.push((id, e)),
            }
        }
        if b.lanes.is_empty() {
            return (None, errors);
        }
        (Some(b), errors)
    }
}

impl RunBatch for ModalBatch {
    fn lanes(&self) -> &[Lane] {
        &self.lanes
    }

    /// Any number of runs steps together.
    fn supported(&self) -> bool {
        true
    }

    /// Each run's step as [`super::Integrator::step`] takes it, its
    /// contact update left to the next step's pass
    /// ([`ModalExact::step_deferred`]): the lanes' `st.d` and `st.v` are
    /// settled only when a run retires; [`RunBatch::sample`] and
    /// [`RunBatch::displacement_at`] account for a pending update.
    fn step(&mut self) {
        for (lane, stepper) in self.lanes.iter_mut().zip(&mut self.steppers) {
            if lane.failed.is_some() {
                continue;
            }
            match stepper.step_deferred(&mut lane.sys, &mut lane.st) {
                Ok(()) => {
                    lane.st.step += 1;
                    lane.st.t = lane.st.step as f64 * lane.sys.physics.dt;
                    lane.sys.end_step(&lane.st);
                }
                Err(e) => lane.failed = Some(e),
            }
        }
    }

    fn sample(&self, l: usize, i: usize) -> CarrierSample {
        let lane = &self.lanes[l];
        let stepper = &self.steppers[l];
        super::sample::sample_of(&lane.sys, &lane.st, i, |pv| {
            stepper.displacement_at(&lane.sys, &lane.st, pv)
        })
    }

    fn displacement_at(&self, l: usize, pv: &PointVector) -> f64 {
        let lane = &self.lanes[l];
        self.steppers[l].displacement_at(&lane.sys, &lane.st, pv)
    }

    fn retire(&mut self, gone: &[usize]) -> Vec<Lane> {
        let mut out = Vec::with_capacity(gone.len());
        for &l in gone.iter().rev() {
            let mut lane = self.lanes.remove(l);
            let mut stepper = self.steppers.remove(l);
            stepper.settle(&lane.sys, &mut lane.st);
            out.push(lane);
        }
        out.reverse();
        out
    }
}
