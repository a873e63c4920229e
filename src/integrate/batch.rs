//! Batched stepping: runs that share their effective matrix step together,
//! so that a study runs at the speed of the hardware.
//!
//! In a sweep over speed, mass, spring, preload or carrier count every run
//! has the same effective matrix A = (1 − α_m)M + (1 − α_f)βΔt²K (same beam,
//! mesh, Δt and generalized-α parameters, MODEL §5). A [`Batch`] factors A
//! once and advances L such runs in lockstep: one pass over the band per
//! step carries every run's right-hand-side columns side by side (column c
//! of run l at c·L + l), and the runs' beam vectors are stored interleaved
//! (`x[i·L + l]`), so the residual h − Kũ, the elimination and the update
//! pass work on the L runs as SIMD lanes. A single run's sweep is bound by
//! the dependency chain of its rows (docs/performance.md); L runs share
//! that chain and fill the arithmetic units it leaves idle.
//!
//! **Bit-identical to the runs alone.** A batch and a run alone
//! ([`super::GenAlpha`]) step with one kernel (`gen_alpha_kernel.rs`), this
//! file only keeping the lanes: every run's columns get exactly the
//! operations, in the same order, whatever the number of lanes, the contact
//! problem is the run's own [`System`] reading its lane
//! ([`super::Lanes`]). `tests/batch.rs` compares the bytes.
//!
//! **What batches**: generalized-α (and its named sets newmark, hht, wbz),
//! contact laws at force level (lagrange, penalty, complementarity) with the
//! `end` placement, Hermite or string elements (half-bandwidth 3 or 1), and
//! 2 to 8 runs of one or two contacts ([`super::batch_key`]), without a
//! manufactured source (its load depends on time); `modal_exact` runs batch
//! their own way (`modal_batch.rs`). Anything else steps alone, as before.
//!
//! **Retiring.** A run that is done or stops leaves the batch
//! ([`Batch::retire`]); the others move down one lane and carry on.

use crate::error::Error;
use crate::model::beam::PointVector;
use crate::resolve::Resolved;
use crate::scene::Scheme;

use super::gen_alpha_kernel::Kernel;
pub(crate) use super::gen_alpha_kernel::MAX_LANES;
use super::sample::CarrierSample;
use super::state::{Dofs, State};
use super::step_map::Lanes;
use super::system::{Initial, System};

/// Most runs of `k` right-hand-side columns each a batch takes: the
/// kernels compiled in `BandedLdlt::solve_affine_lanes` (2 ..= 8 lanes of
/// two columns, 2 ..= 4 of four).
pub fn max_lanes(k: usize) -> usize {
    if k <= 2 { MAX_LANES } else { 4 }
}

/// One run in a batch: its own system (carriers, contact law, multipliers)
/// and mass dofs. In a generalized-α [`Batch`] its beam vectors live in
/// the batch's interleaved arrays; in a `modal_exact` batch
/// (`super::ModalBatch`) in its own state.
pub struct Lane {
    /// The run's system.
    pub sys: System,
    /// Its state: step, time and mass dofs (the beam's d and v too, unless
    /// the batch interleaves them).
    pub st: State,
    /// The caller's index of this run.
    pub id: usize,
    /// An error this run stopped with during the last step.
    pub failed: Option<Error>,
}

/// L generalized-α runs sharing one factorization (module docs).
pub struct Batch {
    lanes: Vec<Lane>,
    /// The generalized-α step of every lane.
    kernel: Kernel,
    /// Beam displacements and velocities of every lane, interleaved n × L.
    d: Vec<f64>,
    v: Vec<f64>,
}

impl Batch {
    /// Build the runs `scenes` (equal [`super::batch_key`]s, 2 ..= `MAX_LANES`
    /// of them; `ids` are the caller's indices), factor A once, and set
    /// each run's initial state as [`super::Integrator::new`] would. A run
    /// that fails to build is returned in the error list with its id.
    pub fn new(scenes: &[(usize, &Resolved)]) -> (Option<Batch>, Vec<(usize, Error)>) {
        let mut errors = Vec::new();
        let mut built: Vec<(usize, System, State, Initial)> = Vec::new();
        for &(id, sc) in scenes {
            let made = System::new(sc).and_then(|mut sys| {
                let st = State::at_rest(sys.beam().n, sys.contacts());
                let init = sys.initial()?;
                Ok((sys, st, init))
            });
            match made {
                Ok((sys, st, init)) => built.push((id, sys, st, init)),
                Err(e) => errors.push((id, e)),
            }
        }
        if built.is_empty() {
            return (None, errors);
        }
        let Scheme::GenAlpha(p) = scenes[0].1.method.scheme else {
            unreachable!("batch_key admits generalized-α only")
        };
        let sys0 = &built[0].1;
        let (n, k, lanes_n) = (sys0.beam().n, sys0.columns(), built.len());
        // batch_key admits undamped runs only: no damping matrix
        let mut kernel = match Kernel::new(p, sys0.beam(), None, sys0.dt(), k, lanes_n) {
            Ok(kernel) => kernel,
            Err(_) => {
                // each run alone reports its own error (the same factorization)
                for (id, ..) in built {
                    errors.push((
                        id,
                        Error::invalid(
                            "batch",
                            "A",
                            "the effective matrix did not factor: run alone for the diagnosis",
                        ),
                    ));
                }
                return (None, errors);
            }
        };
        let (mut d, mut v) = (vec![0.0; n * lanes_n], vec![0.0; n * lanes_n]);
        let mut lanes = Vec::with_capacity(lanes_n);
        for (l, (id, sys, st, init)) in built.into_iter().enumerate() {
            for i in 0..n {
                d[i * lanes_n + l] = st.d[i];
                v[i * lanes_n + l] = st.v[i];
            }
            kernel.start(&sys, &st.d, &st.v, init);
            lanes.push(Lane {
                st: State {
                    d: Dofs::default(),
                    v: Dofs::default(),
                    ..st
                },
                sys,
                id,
                failed: None,
            });
        }
        let b = Batch {
            lanes,
            kernel,
            d,
            v,
        };
        (Some(b), errors)
    }

    /// The runs still in the batch, in lane order.
    pub fn lanes(&self) -> &[Lane] {
        &self.lanes
    }

    /// True when the kernel for this many lanes exists (else the caller
    /// steps the runs alone).
    pub fn supported(&self) -> bool {
        self.kernel.supported()
    }

    /// Advance every run one step: the kernel's phases (`gen_alpha_kernel`),
    /// lane by lane where they are per run, all lanes at once where they are
    /// per row. A run that stops keeps its error in [`Lane::failed`]; the
    /// others are not touched.
    pub fn step(&mut self) {
        let count = self.lanes.len();
        let kernel = &mut self.kernel;
        kernel.clear();
        for (l, lane) in self.lanes.iter_mut().enumerate() {
            kernel.load(l, &mut lane.sys, &lane.st);
        }
        kernel.solve(self.lanes[0].sys.beam());
        for (l, lane) in self.lanes.iter_mut().enumerate() {
            if let Err(e) = kernel.contact(l, &mut lane.sys, &lane.st) {
                lane.failed = Some(e);
            }
        }
        let mut lambda: [&[f64]; MAX_LANES] = [&[]; MAX_LANES];
        for (l, lane) in self.lanes.iter().enumerate() {
            lambda[l] = lane.sys.multipliers();
        }
        let load = &self.lanes[0].sys.beam().load;
        kernel.update(load, &mut self.d, &mut self.v, &lambda[..count]);
        for (l, lane) in self.lanes.iter_mut().enumerate() {
            kernel.finish(l, &lane.sys, &mut lane.st);
            lane.st.step += 1;
            lane.st.t = lane.st.step as f64 * lane.sys.dt();
        }
    }

    /// The beam displacements and velocities of every lane, interleaved
    /// (`d[i·L + l]` is dof i of lane l), for checks (`tests/subnormal.rs`).
    pub fn beam_vectors(&self) -> (&[f64], &[f64]) {
        (&self.d, &self.v)
    }

    /// rᵀd of lane `l` (a carrier's or a probe's displacement).
    pub fn displacement_at(&self, l: usize, pv: &PointVector) -> f64 {
        pv.dot_lane(&self.d, self.lanes.len(), l)
    }

    /// The values of carrier `i` of lane `l` now (as
    /// [`super::Integrator::sample`]).
    pub fn sample(&self, l: usize, i: usize) -> CarrierSample {
        let lane = &self.lanes[l];
        let lanes = Lanes {
            count: self.lanes.len(),
            lane: l,
        };
        super::sample::sample_of(&lane.sys, &lane.st, i, |pv| lanes.dot(pv, &self.d))
    }

    /// Remove the runs at `gone` (lane indices, ascending) from the batch,
    /// moving the others down in place; returns them in that order.
    pub(crate) fn retire(&mut self, gone: &[usize]) -> Vec<Lane> {
        if gone.is_empty() {
            return Vec::new();
        }
        let keep: Vec<usize> = (0..self.lanes.len())
            .filter(|l| !gone.contains(l))
            .collect();
        self.kernel.retire(&keep, &mut self.d, &mut self.v);
        let mut out = Vec::with_capacity(gone.len());
        for &l in gone.iter().rev() {
            out.push(self.lanes.remove(l));
        }
        out.reverse();
        out
    }
}
