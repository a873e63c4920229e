//! Batched stepping: runs that share their effective matrix step together
//! (issue: studies at the speed of the hardware).
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
//! **Bit-identical to the runs alone.** Every run's columns get exactly the
//! operations, in the same order, that [`super::GenAlpha`] gives them alone:
//! the banded kernel is the same generic kernel with more columns
//! ([`BandedLdlt::solve_affine_lanes`]), the residual is summed per lane in
//! the single run's order, the contact problem is the run's own [`System`]
//! reading its lane ([`Lanes`]), and the update is the same element-wise
//! formula. Rust does not contract a·b + c into fused multiply–adds, so the
//! vectorized code rounds as the scalar code does. `tests/batch.rs` compares
//! the bytes.
//!
//! **What batches**: generalized-α (and its named sets newmark, hht, wbz),
//! contact laws at force level (lagrange, penalty, complementarity) with the
//! `end` placement, Hermite or string elements (half-bandwidth 3 or 1), and
//! 2 to 8 runs of one or two contacts ([`super::batch_key`]), without a
//! manufactured source (its load depends on time); `modal_exact` runs batch
//! their own way (`modal_batch.rs`). Anything else steps alone, as before.
//!
//! **Retiring.** A run whose steps are done (its carrier left the beam) or
//! that stops (divergence, failed contact solve) leaves the batch
//! ([`Batch::retire`]); the others' data are moved down one lane, in place,
//! and carry on bit-for-bit as before.

#![allow(non_snake_case)]

use crate::error::Error;
use crate::model::banded::{Affine, BandedLdlt, SymBand};
use crate::model::beam::{BeamModel, PointVector};
use crate::resolve::Resolved;
use crate::scene::{Discretization, Formulation, GenAlphaParams, Placement, Scheme};

use super::gen_alpha::{RowState, UpdateCoefs};
use super::system::Lanes;
use super::{
    CarrierSample, MassPrediction, State, StepMap, System, VelocityPrediction, rhs_columns,
};

/// Most runs a batch steps together (the widest kernel compiled).
pub const MAX_LANES: usize = 8;

/// Most runs of `k` right-hand-side columns each a batch takes: the
/// kernels compiled in `BandedLdlt::solve_affine_lanes` (2 ..= 8 lanes of
/// two columns, 2 ..= 4 of four).
pub fn max_lanes(k: usize) -> usize {
    if k <= 2 { MAX_LANES } else { 4 }
}

/// Right-hand-side columns of a scene's runs: the free step and one per
/// contact (mass–spring carrier), [`rhs_columns`].
pub fn scene_columns(sc: &Resolved) -> usize {
    rhs_columns(
        sc.carriers
            .iter()
            .filter(|c| matches!(c.kind, crate::scene::CarrierKind::MassSpring { .. }))
            .count(),
    )
}

/// The key of the generalized-α runs that may step together: `None` when
/// `sc` cannot batch this way (module docs); runs with equal keys share
/// their effective matrix and their number of right-hand-side columns.
pub(crate) fn gen_alpha_key(sc: &Resolved) -> Option<String> {
    let Scheme::GenAlpha(p) = sc.scheme else {
        return None;
    };
    if sc.contact.placement != Placement::End
        || sc.contact.formulation == Formulation::Impact
        || sc.discretization != Discretization::Hermite
        // a manufactured source is a time-dependent load: alone
        || sc.manufactured.is_some()
    {
        return None;
    }
    let k = scene_columns(sc);
    if k > 4 {
        return None;
    }
    // what A, K and the load are made of (bits of every float), and k
    let b = &sc.beam;
    Some(format!(
        "{:?}|{:x}|{:x}|{:x}|{:x}|{:?}|{:?}|{}|{:?}|{:x}|{:x}|{:x}|{:x}|{k}",
        (b.left, b.right),
        b.length.to_bits(),
        b.rho_a.to_bits(),
        b.ei.to_bits(),
        b.tension.to_bits(),
        b.distributed_load.to_bits(),
        sc.grading,
        sc.elements,
        sc.dt.to_bits(),
        p.alpha_m.to_bits(),
        p.alpha_f.to_bits(),
        p.beta.to_bits(),
        p.gamma.to_bits(),
    ))
}

/// One run in a batch: its own system (carriers, contact law, multipliers)
/// and mass dofs. In a generalized-α [`Batch`] its beam vectors live in
/// the batch's interleaved arrays; in a `modal_exact` batch
/// ([`super::ModalBatch`]) in its own state.
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

/// What generalized-α keeps per run beyond its [`Lane`]: the mass dofs'
/// accelerations, effective masses and this step's predictions.
struct MassLane {
    aq: Vec<f64>,
    a_eff: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
}

/// L generalized-α runs sharing one factorization (module docs).
pub struct Batch {
    lanes: Vec<Lane>,
    /// Per lane, in lane order.
    masses: Vec<MassLane>,
    p: GenAlphaParams,
    dt: f64,
    n: usize,
    /// Right-hand-side columns per run.
    k: usize,
    ldlt: BandedLdlt,
    stiffness: SymBand,
    load: Vec<f64>,
    // interleaved n × L
    d: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    d_pred: Vec<f64>,
    u_shift: Vec<f64>,
    h: Vec<f64>,
    b0: Vec<f64>,
    /// n × k × L right-hand sides.
    rhs: Vec<f64>,
    alpha_p: f64,
    c_k: f64,
    step: usize,
}

impl Batch {
    /// Build the runs `scenes` (equal [`batch_key`]s, 2 ..= [`MAX_LANES`]
    /// of them; `ids` are the caller's indices), factor A once, and set
    /// each run's initial state as [`super::Integrator::new`] would. A run
    /// that fails to build is returned in the error list with its id.
    pub fn new(scenes: &[(usize, &Resolved)]) -> (Option<Batch>, Vec<(usize, Error)>) {
        let mut errors = Vec::new();
        let mut built: Vec<(usize, System, State, super::Initial)> = Vec::new();
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
        let Scheme::GenAlpha(p) = scenes[0].1.scheme else {
            unreachable!("batch_key admits generalized-α only")
        };
        let beam: &BeamModel = built[0].1.beam();
        let (n, dt) = (beam.n, built[0].1.dt());
        let c_k = (1.0 - p.alpha_f) * p.beta * dt * dt;
        let A = beam.mass.combine(1.0 - p.alpha_m, &beam.stiffness, c_k);
        let ldlt = match BandedLdlt::factor(&A) {
            Ok(l) => l,
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
        let k = built[0].1.columns();
        let lanes_n = built.len();
        let mut b = Batch {
            lanes: Vec::with_capacity(lanes_n),
            masses: Vec::with_capacity(lanes_n),
            p,
            dt,
            n,
            k,
            ldlt,
            stiffness: beam.stiffness.clone(),
            load: beam.load.clone(),
            d: vec![0.0; n * lanes_n],
            v: vec![0.0; n * lanes_n],
            a: vec![0.0; n * lanes_n],
            d_pred: vec![0.0; n * lanes_n],
            u_shift: vec![0.0; n * lanes_n],
            h: vec![0.0; n * lanes_n],
            b0: vec![0.0; n * lanes_n],
            rhs: vec![0.0; n * k * lanes_n],
            alpha_p: p.alpha_m / (1.0 - p.alpha_m),
            c_k,
            step: 0,
        };
        let mut a_a = vec![0.0; n];
        for (l, (id, sys, st, init)) in built.into_iter().enumerate() {
            // GenAlpha::new and GenAlpha::predict, this run's lane
            let a_eff = sys
                .masses()
                .iter()
                .map(|m| {
                    (1.0 - p.alpha_m) * m.m + (1.0 - p.alpha_f) * p.gamma * dt * m.c + c_k * m.k
                })
                .collect();
            let c_pred = (0.5 - p.beta) * dt * dt;
            a_a.fill(0.0);
            sys.beam().mass.mul_acc(&init.a, 1.0 - p.alpha_m, &mut a_a);
            sys.beam().stiffness.mul_acc(&init.a, c_k, &mut a_a);
            for i in 0..n {
                let dp = st.d[i] + dt * st.v[i] + c_pred * init.a[i];
                let u = (1.0 - p.alpha_f) * dp + p.alpha_f * st.d[i];
                let at = i * lanes_n + l;
                b.a[at] = init.a[i];
                b.d_pred[at] = dp;
                b.u_shift[at] = u - b.alpha_p * c_k * init.a[i];
                b.h[at] = sys.beam().load[i] - b.alpha_p * a_a[i];
            }
            let nc = sys.contacts();
            b.lanes.push(Lane {
                st: State {
                    d: Vec::new(),
                    v: Vec::new(),
                    ..st
                },
                sys,
                id,
                failed: None,
            });
            b.masses.push(MassLane {
                aq: init.aq,
                a_eff,
                mass_pred: vec![MassPrediction::default(); nc],
            });
        }
        (Some(b), errors)
    }

    /// The runs still in the batch, in lane order.
    pub fn lanes(&self) -> &[Lane] {
        &self.lanes
    }

    /// True when the kernel for this many lanes exists (else the caller
    /// steps the runs alone).
    pub fn supported(&self) -> bool {
        self.lanes.len() == 1 || self.ldlt.has_lanes(self.k, self.lanes.len())
    }

    /// Advance every run one step (GenAlpha::step, lane by lane where it is
    /// per run, all lanes at once where it is per row). A run that stops
    /// keeps its error in [`Lane::failed`]; the others are not touched.
    pub fn step(&mut self) {
        let L = self.lanes.len();
        let (n, k) = (self.n, self.k);
        let GenAlphaParams {
            alpha_m: _,
            alpha_f: af,
            beta,
            gamma,
        } = self.p;
        let dt = self.dt;
        let t1 = (self.step + 1) as f64 * dt;
        let tf = t1 - af * dt;
        let bdt2 = beta * dt * dt;
        let c_pred = (0.5 - beta) * dt * dt;
        let kl = k * L;
        let rhs = &mut self.rhs[..n * kl];
        rhs.fill(0.0);
        for (l, lane) in self.lanes.iter_mut().enumerate() {
            lane.sys.place(tf, tf, t1);
            lane.sys
                .scatter_loads_in(rhs, k, Lanes { count: L, lane: l }, 1.0);
        }
        let residual = Affine {
            h: &self.h[..n * L],
            k: &self.stiffness,
            u: &self.u_shift[..n * L],
        };
        if L == 1 {
            self.ldlt.solve_affine(rhs, k, &residual, &mut self.b0[..n]);
        } else {
            let solved = self
                .ldlt
                .solve_affine_lanes(rhs, k, L, &residual, &mut self.b0[..n * L]);
            assert!(solved, "a batch is only built for compiled kernels");
        }
        for (l, (lane, ml)) in self.lanes.iter_mut().zip(&mut self.masses).enumerate() {
            let rhs = &self.rhs[..n * kl];
            for (j, m) in lane.sys.masses().iter().enumerate() {
                let now = (lane.st.q[j], lane.st.q_dot[j], ml.aq[j]);
                ml.mass_pred[j] =
                    super::gen_alpha::mass_prediction(self.p, dt, m, now, ml.a_eff[j]);
            }
            let map = StepMap {
                solved: rhs,
                c_d: bdt2,
                c_v: gamma * dt,
                d_pred: &self.d_pred[..n * L],
                v_pred: VelocityPrediction::Shifted {
                    shift: &self.a[..n * L],
                    coef: (1.0 - gamma) * dt,
                },
                alpha_weight: 0.0,
                masses: &ml.mass_pred,
            };
            if let Err(e) = lane
                .sys
                .solve_contact_in(&map, Lanes { count: L, lane: l }, &lane.st)
            {
                lane.failed = Some(e);
            }
        }
        // the update pass, all lanes (Rows::update of gen_alpha, per lane)
        let alpha_p = self.alpha_p;
        let c_shift = alpha_p * self.c_k;
        // λ of column c of lane l at lk[c][l]: contiguous across lanes
        let mut lk = [[0.0; MAX_LANES]; 4];
        for (l, lane) in self.lanes.iter().enumerate() {
            for (c, lkc) in lk.iter_mut().enumerate().take(k).skip(1) {
                lkc[l] = lane.sys.multipliers().get(c - 1).copied().unwrap_or(0.0);
            }
        }
        let c = UpdateCoefs {
            dt,
            gamma,
            bdt2,
            c_pred,
            alpha_f: af,
            c_shift,
            alpha_p,
        };
        macro_rules! update {
            ($(($k:literal, $l:literal, $kl:literal)),*) => {
                match (k, L) {
                    $(($k, $l) => self.update_dispatch::<$k, $l, $kl>(&lk, c),)*
                    _ => unreachable!("a batch has a kernel for its (k, lanes)"),
                }
            };
        }
        update!(
            (2, 1, 2),
            (2, 2, 4),
            (2, 3, 6),
            (2, 4, 8),
            (2, 5, 10),
            (2, 6, 12),
            (2, 7, 14),
            (2, 8, 16),
            (4, 1, 4),
            (4, 2, 8),
            (4, 3, 12),
            (4, 4, 16)
        );
        for (l, (lane, ml)) in self.lanes.iter_mut().zip(&mut self.masses).enumerate() {
            lane.sys.scatter_contact_directions_in(
                &mut self.h[..n * L],
                Lanes { count: L, lane: l },
                -alpha_p,
            );
            for (j, m) in ml.mass_pred.iter().enumerate() {
                let lambda = lane.sys.multipliers()[j];
                let (a, acc) = (ml.aq[j], m.u - lambda / m.a_eff);
                lane.st.q[j] += dt * lane.st.q_dot[j] + c_pred * a + bdt2 * acc;
                lane.st.q_dot[j] += dt * ((1.0 - gamma) * a + gamma * acc);
                ml.aq[j] = acc;
            }
            lane.st.step += 1;
            lane.st.t = lane.st.step as f64 * dt;
        }
        self.step += 1;
    }

    /// [`Batch::update`] with AVX2 where the CPU has it (as the banded
    /// kernel: same operations, same rounding).
    fn update_dispatch<const K: usize, const L: usize, const KL: usize>(
        &mut self,
        lk: &[[f64; MAX_LANES]; 4],
        c: UpdateCoefs,
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            if L >= 4 {
                // SAFETY: the CPU supports AVX2 (checked just above).
                unsafe { self.update_avx2_x4::<K, L, KL>(lk, c) };
            } else {
                // SAFETY: as above.
                unsafe { self.update_avx2::<K, L, KL>(lk, c) };
            }
            return;
        }
        self.update::<K, L, KL>(lk, c)
    }

    /// [`Batch::update`] written in AVX2 vectors of four lanes (L ≥ 4; the
    /// lanes past the last multiple of 4 by the scalar formulas): the
    /// compiler, left to itself, vectorizes across rows and transposes
    /// (measured 3× slower per element than a run alone).
    /// Each vector operation is the scalar code's operation on four lanes,
    /// in the scalar code's order and association, so the bits agree.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn update_avx2_x4<const K: usize, const L: usize, const KL: usize>(
        &mut self,
        lk: &[[f64; MAX_LANES]; 4],
        c: UpdateCoefs,
    ) {
        use std::arch::x86_64::*;
        let n = self.n;
        let s = _mm256_set1_pd;
        let (dt, gamma, one_m_gamma) = (s(c.dt), s(c.gamma), s(1.0 - c.gamma));
        let (bdt2, c_pred, alpha_p) = (s(c.bdt2), s(c.c_pred), s(c.alpha_p));
        let (af, one_m_af, c_shift) = (s(c.alpha_f), s(1.0 - c.alpha_f), s(c.c_shift));
        let rhs = &self.rhs[..n * KL];
        let (d, v, a) = (
            &mut self.d[..n * L],
            &mut self.v[..n * L],
            &mut self.a[..n * L],
        );
        let (dp, u) = (&mut self.d_pred[..n * L], &mut self.u_shift[..n * L]);
        let (h, b0) = (&mut self.h[..n * L], &self.b0[..n * L]);
        for i in 0..n {
            let row = &rhs[i * KL..(i + 1) * KL];
            let f = s(self.load[i]);
            for l in L - L % 4..L {
                let at = i * L + l;
                let mut acc = row[l];
                for cc in 1..K {
                    acc += lk[cc][l] * row[cc * L + l];
                }
                let r = RowState {
                    d: &mut d[at],
                    v: &mut v[at],
                    a: &mut a[at],
                    dp: &mut dp[at],
                    u: &mut u[at],
                    h: &mut h[at],
                };
                c.row(acc, r, b0[at], self.load[i]);
            }
            for g in (0..L - L % 4).step_by(4) {
                let at = i * L + g;
                // SAFETY: every slice below has at least four elements from
                // its start (at + 3 < n·L, g + 3 < L, cc·L + g + 3 < KL).
                unsafe {
                    let ld = |x: &[f64]| _mm256_loadu_pd(x.as_ptr());
                    let mut acc = ld(&row[g..]);
                    for cc in 1..K {
                        acc = _mm256_add_pd(
                            acc,
                            _mm256_mul_pd(ld(&lk[cc][g..]), ld(&row[cc * L + g..])),
                        );
                    }
                    let a_old = ld(&a[at..]);
                    // v += dt((1 − γ)a + γ acc)
                    let vv = _mm256_add_pd(
                        ld(&v[at..]),
                        _mm256_mul_pd(
                            dt,
                            _mm256_add_pd(
                                _mm256_mul_pd(one_m_gamma, a_old),
                                _mm256_mul_pd(gamma, acc),
                            ),
                        ),
                    );
                    // d = d̃ + βΔt² acc
                    let dd = _mm256_add_pd(ld(&dp[at..]), _mm256_mul_pd(bdt2, acc));
                    // next = d + Δt v + c_pred acc
                    let next = _mm256_add_pd(
                        _mm256_add_pd(dd, _mm256_mul_pd(dt, vv)),
                        _mm256_mul_pd(c_pred, acc),
                    );
                    // ũ = (1 − α_f) next + α_f d − c_shift acc
                    let uu = _mm256_sub_pd(
                        _mm256_add_pd(_mm256_mul_pd(one_m_af, next), _mm256_mul_pd(af, dd)),
                        _mm256_mul_pd(c_shift, acc),
                    );
                    // h = f − α′ b₀
                    let hh = _mm256_sub_pd(f, _mm256_mul_pd(alpha_p, ld(&b0[at..])));
                    _mm256_storeu_pd(v[at..].as_mut_ptr(), vv);
                    _mm256_storeu_pd(d[at..].as_mut_ptr(), dd);
                    _mm256_storeu_pd(a[at..].as_mut_ptr(), acc);
                    _mm256_storeu_pd(dp[at..].as_mut_ptr(), next);
                    _mm256_storeu_pd(u[at..].as_mut_ptr(), uu);
                    _mm256_storeu_pd(h[at..].as_mut_ptr(), hh);
                }
            }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn update_avx2<const K: usize, const L: usize, const KL: usize>(
        &mut self,
        lk: &[[f64; MAX_LANES]; 4],
        c: UpdateCoefs,
    ) {
        self.update::<K, L, KL>(lk, c)
    }

    /// The update pass of every lane (gen_alpha's `Rows::update`, element
    /// by element in the same order): L and the columns are compile-time
    /// constants, so each row's L lanes are one vector operation.
    #[inline(always)]
    fn update<const K: usize, const L: usize, const KL: usize>(
        &mut self,
        lk: &[[f64; MAX_LANES]; 4],
        c: UpdateCoefs,
    ) {
        let n = self.n;
        let (rhs, _) = self.rhs[..n * KL].as_chunks::<KL>();
        let (d, _) = self.d[..n * L].as_chunks_mut::<L>();
        let (v, _) = self.v[..n * L].as_chunks_mut::<L>();
        let (a, _) = self.a[..n * L].as_chunks_mut::<L>();
        let (dp, _) = self.d_pred[..n * L].as_chunks_mut::<L>();
        let (u, _) = self.u_shift[..n * L].as_chunks_mut::<L>();
        let (h, _) = self.h[..n * L].as_chunks_mut::<L>();
        let (b0, _) = self.b0[..n * L].as_chunks::<L>();
        let state = d.iter_mut().zip(v.iter_mut()).zip(a.iter_mut());
        let pred = dp.iter_mut().zip(u.iter_mut());
        let load = h.iter_mut().zip(b0).zip(&self.load);
        for ((row, ((d, v), a)), ((dp, u), ((h, b0), f))) in
            rhs.iter().zip(state).zip(pred.zip(load))
        {
            for l in 0..L {
                let mut acc = row[l];
                for cc in 1..K {
                    acc += lk[cc][l] * row[cc * L + l];
                }
                let r = RowState {
                    d: &mut d[l],
                    v: &mut v[l],
                    a: &mut a[l],
                    dp: &mut dp[l],
                    u: &mut u[l],
                    h: &mut h[l],
                };
                c.row(acc, r, b0[l], *f);
            }
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
        super::sample_of(&lane.sys, &lane.st, i, |pv| lanes.dot(pv, &self.d))
    }

    /// Remove the runs at `gone` (lane indices, ascending) from the batch,
    /// moving the others down in place; returns them in that order.
    pub fn retire(&mut self, gone: &[usize]) -> Vec<Lane> {
        if gone.is_empty() {
            return Vec::new();
        }
        let old = self.lanes.len();
        let keep: Vec<usize> = (0..old).filter(|l| !gone.contains(l)).collect();
        let new = keep.len();
        let n = self.n;
        for v in [
            &mut self.d,
            &mut self.v,
            &mut self.a,
            &mut self.d_pred,
            &mut self.u_shift,
            &mut self.h,
            &mut self.b0,
        ] {
            // destination i·new + j ≤ source i·old + keep[j]: in place, forward
            for i in 0..n {
                for (j, &l) in keep.iter().enumerate() {
                    v[i * new + j] = v[i * old + l];
                }
            }
        }
        let mut out = Vec::with_capacity(gone.len());
        for &l in gone.iter().rev() {
            out.push(self.lanes.remove(l));
            self.masses.remove(l);
        }
        out.reverse();
        out
    }
}
