//! The mode kernels of `modal_exact` (MODEL §9.3; `modal_exact.rs` has
//! the step they make up): each mode's free step, the two sums of a
//! single contact's pair, and a force held along a carrier's path into
//! the modes — scalar, and AVX2 + FMA eight or four modes at a time with
//! the very operations of the scalar loops (the same bits) — and the fused
//! passes that take a block of shapes or a rotated phasor and the free
//! step of its modes while in registers (the latter also with AVX-512F,
//! eight modes a register, the same bits).
//!
//! The kernels round `a·b + c` once (AVX2 + FMA vectors where the CPU has
//! both, `f64::mul_add` lane by lane otherwise: the same bits,
//! `crate::numeric::lanes`), and take sums over modes in its eight lanes.

use std::ops::Range;

#[cfg(target_arch = "x86_64")]
use crate::analytic::{Blocks, BlocksAvx, SHAPE_BLOCK};
use crate::numeric::lanes::{self, LANES};

use super::carrier::Carrier;
use super::oscillator::ModeSteps;
use super::state::State;

/// The two sums of a run with one contact and no other carrier, in
/// [`LANES`] partial sums (carried from one range of modes to the next
/// when a pass is split, as the tests do):
/// `Σ φ_j(x_{n+1}) η_free,j` and
/// `Σ φ_j(x_{n+1}) (a0_j φ_j(x_n) + a1_j φ_j(x_{n+1}))`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PairSums {
    pub(crate) g: [f64; LANES],
    pub(crate) w: [f64; LANES],
}

impl PairSums {
    pub(crate) fn total(&self) -> (f64, f64) {
        (lanes::reduce(&self.g), lanes::reduce(&self.w))
    }

    /// The partial sums as two AVX2 vectors each (lanes 0–3, 4–7).
    ///
    /// # Safety
    /// The CPU supports AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(crate) unsafe fn load_avx2(
        &self,
    ) -> (
        [std::arch::x86_64::__m256d; 2],
        [std::arch::x86_64::__m256d; 2],
    ) {
        use std::arch::x86_64::_mm256_loadu_pd;
        // SAFETY: g and w hold LANES = 8 entries.
        unsafe {
            let ld = |x: &[f64; LANES], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
            (
                [ld(&self.g, 0), ld(&self.g, 4)],
                [ld(&self.w, 0), ld(&self.w, 4)],
            )
        }
    }

    /// Back from [`PairSums::load_avx2`]'s vectors.
    ///
    /// # Safety
    /// The CPU supports AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(crate) unsafe fn store_avx2(
        &mut self,
        g: [std::arch::x86_64::__m256d; 2],
        w: [std::arch::x86_64::__m256d; 2],
    ) {
        use std::arch::x86_64::_mm256_storeu_pd;
        // SAFETY: g and w hold LANES = 8 entries.
        unsafe {
            _mm256_storeu_pd(self.g.as_mut_ptr(), g[0]);
            _mm256_storeu_pd(self.g.as_mut_ptr().add(4), g[1]);
            _mm256_storeu_pd(self.w.as_mut_ptr(), w[0]);
            _mm256_storeu_pd(self.w.as_mut_ptr().add(4), w[1]);
        }
    }
}

/// Eight modes' step coefficients side by side, each row one 64-byte
/// line: what the AVX-512 cruise pass reads of a block of modes in one
/// aligned stream instead of seven ([`fused_free_pair_avx512`]). Copies
/// of [`ModeSteps`]' values (the same bits).
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(64))]
pub(crate) struct CoefBlock {
    pub(crate) cos: [f64; LANES],
    pub(crate) sin_over_omega: [f64; LANES],
    pub(crate) minus_omega_sin: [f64; LANES],
    pub(crate) a0: [f64; LANES],
    pub(crate) a1: [f64; LANES],
    pub(crate) b0: [f64; LANES],
    pub(crate) b1: [f64; LANES],
}

/// The ⌊J/8⌋ whole blocks of `m`'s coefficients ([`CoefBlock`]).
pub(crate) fn coef_blocks(m: &ModeSteps) -> Vec<CoefBlock> {
    (0..m.len() / LANES)
        .map(|b| {
            let row = |x: &[f64]| -> [f64; LANES] { std::array::from_fn(|l| x[b * LANES + l]) };
            CoefBlock {
                cos: row(&m.cos),
                sin_over_omega: row(&m.sin_over_omega),
                minus_omega_sin: row(&m.minus_omega_sin),
                a0: row(&m.a0),
                a1: row(&m.a1),
                b0: row(&m.b0),
                b1: row(&m.b1),
            }
        })
        .collect()
}

/// Inputs of the AVX-512 kernels' bit-for-bit tests: J modes of distinct
/// frequencies, ω_j = 9.4·j·(1 + 10⁻³ j) rad/s, stepped at Δt = 6.25e-5 s,
/// and J sample values sin(k·j).
#[cfg(test)]
pub(crate) mod samples {
    use super::ModeSteps;

    /// The steps of J such modes.
    pub(crate) fn steps(j: usize) -> ModeSteps {
        let omega: Vec<f64> = (1..=j)
            .map(|i| 9.4 * i as f64 * (1.0 + 1e-3 * i as f64))
            .collect();
        ModeSteps::new(&omega, 6.25e-5)
    }

    /// J sample values sin(k·j), j = 1 … J.
    pub(crate) fn wave(j: usize, k: f64) -> Vec<f64> {
        (0..j).map(|i| (k * (i + 1) as f64).sin()).collect()
    }
}

/// The operands of one fused pass over the modes ([`fused_free_pair_avx2`],
/// [`shapes_free_pair_avx2`]): the modes' steps, their state, the shapes
/// `pn` = φ(x_n) and `pn1` (the pass stores φ(x_{n+1}) there), the held
/// load's step and the pair's partial sums.
pub(crate) struct FusedPass<'a> {
    pub(crate) m: &'a ModeSteps,
    pub(crate) modes: ModeState<'a>,
    pub(crate) pn: &'a [f64],
    pub(crate) pn1: &'a mut [f64],
    pub(crate) held: HeldStep<'a>,
    pub(crate) sums: &'a mut PairSums,
}

/// A fused pass's phasors at constant speed (`modal_cruise.rs`): their
/// imaginary parts `fi` (each overwritten by its rotation) and the step's
/// rotation `(rr, ri)`; empty when the shapes are stored, not rotated.
pub(crate) struct Phasors<'a> {
    pub(crate) fi: &'a mut [f64],
    pub(crate) rr: &'a [f64],
    pub(crate) ri: &'a [f64],
}

/// Modes `0 .. end` of one fused pass: each mode's shape `q` — with
/// `ROTATE`, `Re[(pn + i·fi)(rr + i·ri)]` (its imaginary part back into
/// `fi`; [`rotate_free_pair`]), else `fi` itself, shapes the caller stored
/// there (a boundary layer's blocks, [`place_free_pair_tables`]) — stored
/// into `pn1`; with `DEFERRED` the last step's update added first (from
/// `pn1` before that store, φ(x_{n−1}), to `pn`, φ(x_n)); then
/// [`free_with_pair_avx2`]'s operations, eight modes at a time into the
/// same partial sums. The same operations as the separate passes, so the
/// same bits.
///
/// # Safety
/// The CPU supports AVX2 and FMA; `end` is a multiple of [`LANES`];
/// every slice has at least `end` entries (`rr` and `ri` only with
/// `ROTATE`), or the held step's are both empty.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn fused_free_pair_avx2<const ROTATE: bool, const DEFERRED: bool>(
    pass: FusedPass,
    phasors: Phasors,
    end: usize,
    f: f64,
) {
    use std::arch::x86_64::*;
    let FusedPass {
        m,
        mut modes,
        pn,
        pn1,
        held,
        sums,
    } = pass;
    let Phasors { fi, rr, ri } = phasors;
    // SAFETY (whole body): loads and stores at k .. k + 4 ≤ end.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let (mut g, mut w) = sums.load_avx2();
        let mut i = 0;
        while i < end {
            for h in 0..2 {
                let k = i + 4 * h;
                // the shape: one complex product (Cruise::rotate_range)
                let (p, b) = (ld(pn, k), ld(fi, k));
                let mut now = modes.load4(k);
                if DEFERRED {
                    // the last step's update: from φ(x_{n−1}) (pn1 before
                    // this pass stores into it) to φ(x_n) (pn)
                    let fv = _mm256_set1_pd(f);
                    let from = QuadPath {
                        at_n: ld(pn1, k),
                        at_n1: p,
                    };
                    now = path_load4(PathWeights::of(m), k, fv, from, now);
                }
                let q = if ROTATE {
                    let (cr, ci) = (ld(rr, k), ld(ri, k));
                    let q = _mm256_fmsub_pd(p, cr, _mm256_mul_pd(b, ci));
                    _mm256_storeu_pd(
                        fi.as_mut_ptr().add(k),
                        _mm256_fmadd_pd(p, ci, _mm256_mul_pd(b, cr)),
                    );
                    q
                } else {
                    // the shapes stored by the caller
                    b
                };
                _mm256_storeu_pd(pn1.as_mut_ptr().add(k), q);
                let path = QuadPath { at_n: p, at_n1: q };
                let into = QuadSums {
                    g: &mut g[h],
                    w: &mut w[h],
                };
                free_pair4(m, k, now, path, held, &mut modes, into);
            }
            i += LANES;
        }
        sums.store_avx2(g, w);
    }
}

/// [`fused_free_pair_avx2`] with eight modes in one AVX-512 register,
/// their coefficients from `blocks` (`pass.m`'s, [`coef_blocks`]): the
/// same operations lane by lane, mode i in lane i mod 8 of the same
/// partial sums, so the same bits, in half the instructions and one
/// aligned stream of coefficients.
///
/// # Safety
/// The CPU supports AVX-512F; `end` is a multiple of [`LANES`]; `blocks`
/// holds `end / LANES` blocks; every slice has at least `end` entries
/// (`rr` and `ri` only with `ROTATE`), or the held step's are both empty.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
pub(crate) unsafe fn fused_free_pair_avx512<const ROTATE: bool, const DEFERRED: bool>(
    pass: FusedPass,
    blocks: &[CoefBlock],
    phasors: Phasors,
    end: usize,
    f: f64,
) {
    use std::arch::x86_64::*;
    let FusedPass {
        m: _,
        modes: ModeState { d, v },
        pn,
        pn1,
        held: HeldStep { d: hp, v: hv },
        sums,
    } = pass;
    let Phasors { fi, rr, ri } = phasors;
    let held = HeldStep { d: hp, v: hv };
    // SAFETY (whole body): loads and stores at k .. k + 8 ≤ end, block
    // k / 8 < end / 8 of `blocks`, whose rows are 64-byte aligned.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm512_loadu_pd(x.as_ptr().add(i));
        let mut acc = [ld(&sums.g, 0), ld(&sums.w, 0)];
        let fv = _mm512_set1_pd(f);
        let mut k = 0;
        while k < end {
            let c = blocks.get_unchecked(k / LANES);
            let (p, b) = (ld(pn, k), ld(fi, k));
            let q = if ROTATE {
                let (cr, ci) = (ld(rr, k), ld(ri, k));
                let q = _mm512_fmsub_pd(p, cr, _mm512_mul_pd(b, ci));
                let im = _mm512_fmadd_pd(p, ci, _mm512_mul_pd(b, cr));
                _mm512_storeu_pd(fi.as_mut_ptr().add(k), im);
                q
            } else {
                b
            };
            let modes = ModeState {
                d: &mut *d,
                v: &mut *v,
            };
            step_block_avx512::<DEFERRED>(c, k, [p, q], modes, &mut *pn1, &held, fv, &mut acc);
            k += LANES;
        }
        _mm512_storeu_pd(sums.g.as_mut_ptr(), acc[0]);
        _mm512_storeu_pd(sums.w.as_mut_ptr(), acc[1]);
    }
}

/// Eight modes of a fused pass, their shapes in registers: `p` = φ(x_n)
/// and `q` = φ(x_{n+1}) of modes `k .. k + 8`. With `DEFERRED` the last
/// step's update first (from `pn1` before `q` is stored into it,
/// φ(x_{n−1}), to `p`; `path_load4`'s operations), then `q` stored, the
/// free step plus the held load and the two sums `acc` = [g, w]
/// (`free_pair4`'s), lane by lane: what the cruise's and the tables'
/// AVX-512 passes share.
///
/// # Safety
/// The CPU supports AVX-512F; `c` is modes `k .. k + 8`'s block; every
/// slice holds `k + 8` entries, or the held step's are both empty.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
#[allow(clippy::too_many_arguments)] // the pass's registers, kept out of memory
pub(crate) unsafe fn step_block_avx512<const DEFERRED: bool>(
    c: &CoefBlock,
    k: usize,
    [p, q]: [std::arch::x86_64::__m512d; 2],
    modes: ModeState,
    pn1: &mut [f64],
    held: &HeldStep,
    fv: std::arch::x86_64::__m512d,
    acc: &mut [std::arch::x86_64::__m512d; 2],
) {
    use std::arch::x86_64::*;
    let ModeState { d, v } = modes;
    // SAFETY: loads and stores at k .. k + 8, within every slice; `c`'s
    // rows are 64-byte aligned.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm512_loadu_pd(x.as_ptr().add(i));
        let row = |x: &[f64; LANES]| _mm512_load_pd(x.as_ptr());
        let (a0, a1) = (row(&c.a0), row(&c.a1));
        let (mut e, mut ev) = (ld(d, k), ld(v, k));
        if DEFERRED {
            let p0 = ld(pn1, k);
            let z = _mm512_fmadd_pd(a0, p0, _mm512_mul_pd(a1, p));
            let zv = _mm512_fmadd_pd(row(&c.b0), p0, _mm512_mul_pd(row(&c.b1), p));
            e = _mm512_fmadd_pd(fv, z, e);
            ev = _mm512_fmadd_pd(fv, zv, ev);
        }
        _mm512_storeu_pd(pn1.as_mut_ptr().add(k), q);
        let (cs, so, mos) = (row(&c.cos), row(&c.sin_over_omega), row(&c.minus_omega_sin));
        let mut e1 = _mm512_fmadd_pd(cs, e, _mm512_mul_pd(so, ev));
        let mut v1 = _mm512_fmadd_pd(mos, e, _mm512_mul_pd(cs, ev));
        if !held.d.is_empty() {
            e1 = _mm512_add_pd(e1, ld(held.d, k));
            v1 = _mm512_add_pd(v1, ld(held.v, k));
        }
        _mm512_storeu_pd(d.as_mut_ptr().add(k), e1);
        _mm512_storeu_pd(v.as_mut_ptr().add(k), v1);
        let [g, w] = acc;
        *g = _mm512_fmadd_pd(q, e1, *g);
        let z = _mm512_fmadd_pd(a0, p, _mm512_mul_pd(a1, q));
        *w = _mm512_fmadd_pd(q, z, *w);
    }
}

/// Modes `from .. blocks.full()` of [`place_free_pair`]: each block of shapes
/// evaluated ([`BlocksAvx::next`]), stored into `pn1`, and taken by
/// [`free_with_pair_avx2`]'s operations, four modes at a time, into the
/// same partial sums (mode k into the lanes of vector ⌊k/4⌋ mod 2).
///
/// # Safety
/// The CPU supports AVX2 and FMA; every slice holds at least
/// `blocks.full()` entries, or the held step's are both empty.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn shapes_free_pair_avx2<const DEFERRED: bool>(
    blocks: &mut Blocks,
    from: usize,
    pass: FusedPass,
    f: f64,
) {
    use std::arch::x86_64::*;
    let FusedPass {
        m,
        mut modes,
        pn,
        pn1,
        held,
        sums,
    } = pass;
    let end = blocks.full();
    // SAFETY (whole body): loads and stores at k .. k + 4 ≤ end.
    unsafe {
        let mut shapes = BlocksAvx::new(blocks);
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let (mut g, mut w) = sums.load_avx2();
        let mut at = from;
        while at < end {
            let q4 = shapes.next(blocks, at);
            for (u, q) in q4.into_iter().enumerate() {
                let (k, h) = (at + 4 * u, u % 2);
                let p = ld(pn, k);
                let mut now = modes.load4(k);
                if DEFERRED {
                    // the last step's update: from φ(x_{n−1}) (pn1 before
                    // this pass stores into it) to φ(x_n) (pn)
                    let fv = _mm256_set1_pd(f);
                    let from = QuadPath {
                        at_n: ld(pn1, k),
                        at_n1: p,
                    };
                    now = path_load4(PathWeights::of(m), k, fv, from, now);
                }
                _mm256_storeu_pd(pn1.as_mut_ptr().add(k), q);
                let path = QuadPath { at_n: p, at_n1: q };
                let into = QuadSums {
                    g: &mut g[h],
                    w: &mut w[h],
                };
                free_pair4(m, k, now, path, held, &mut modes, into);
            }
            at += SHAPE_BLOCK;
        }
        shapes.finish(blocks);
        sums.store_avx2(g, w);
    }
}

/// The shapes of a carrier's path over a step: φ(x_n) and φ(x_{n+1}) (J
/// each, or a range of them).
#[derive(Clone, Copy)]
pub(crate) struct PathShapes<'a> {
    pub(crate) at_n: &'a [f64],
    pub(crate) at_n1: &'a [f64],
}

impl<'a> PathShapes<'a> {
    /// Carrier `c`'s: `pv_f` holds φ(x_n), `pv_g` φ(x_{n+1}) after `place`.
    #[inline(always)]
    pub(crate) fn of(c: &'a Carrier) -> Self {
        PathShapes {
            at_n: c.pv_f.dense(),
            at_n1: c.pv_g.dense(),
        }
    }
}

/// Each mode's weights of a load held over the step along a carrier's
/// path (`oscillator.rs`): a0, a1 into η, b0, b1 into η̇.
#[derive(Clone, Copy)]
pub(crate) struct PathWeights<'a> {
    pub(crate) a0: &'a [f64],
    pub(crate) a1: &'a [f64],
    pub(crate) b0: &'a [f64],
    pub(crate) b1: &'a [f64],
}

impl<'a> PathWeights<'a> {
    /// The weights of every mode of `m`.
    #[inline(always)]
    pub(crate) fn of(m: &'a ModeSteps) -> Self {
        PathWeights {
            a0: &m.a0,
            a1: &m.a1,
            b0: &m.b0,
            b1: &m.b1,
        }
    }

    /// The weights of modes `r`.
    #[inline(always)]
    pub(crate) fn range(self, r: Range<usize>) -> Self {
        PathWeights {
            a0: &self.a0[r.clone()],
            a1: &self.a1[r.clone()],
            b0: &self.b0[r.clone()],
            b1: &self.b1[r],
        }
    }
}

/// The held distributed load's step of each mode: (a0 + a1) p_j into η,
/// (b0 + b1) p_j into η̇ (both empty without a load).
#[derive(Clone, Copy)]
pub(crate) struct HeldStep<'a> {
    pub(crate) d: &'a [f64],
    pub(crate) v: &'a [f64],
}

impl<'a> HeldStep<'a> {
    /// The first `j` modes' of `held` ([`ModalCoefs`]), empty without one.
    #[inline(always)]
    pub(crate) fn of(held: Option<&'a (Vec<f64>, Vec<f64>)>, j: usize) -> Self {
        match held {
            Some((hp, hv)) => HeldStep {
                d: &hp[..j],
                v: &hv[..j],
            },
            None => HeldStep { d: &[], v: &[] },
        }
    }
}

/// The modes' displacements η and velocities η̇, stepped in place.
pub(crate) struct ModeState<'a> {
    pub(crate) d: &'a mut [f64],
    pub(crate) v: &'a mut [f64],
}

#[cfg(target_arch = "x86_64")]
impl ModeState<'_> {
    /// Modes `k .. k + 4` into registers.
    ///
    /// # Safety
    /// The CPU supports AVX; both slices hold `k + 4` entries.
    #[target_feature(enable = "avx")]
    #[inline]
    pub(crate) unsafe fn load4(&self, k: usize) -> Quad {
        use std::arch::x86_64::_mm256_loadu_pd;
        // SAFETY: loads at k .. k + 4 (the caller's contract).
        unsafe {
            Quad {
                d: _mm256_loadu_pd(self.d.as_ptr().add(k)),
                v: _mm256_loadu_pd(self.v.as_ptr().add(k)),
            }
        }
    }

    /// Modes `k .. k + 4` from registers.
    ///
    /// # Safety
    /// The CPU supports AVX; both slices hold `k + 4` entries.
    #[target_feature(enable = "avx")]
    #[inline]
    pub(crate) unsafe fn store4(&mut self, k: usize, q: Quad) {
        use std::arch::x86_64::_mm256_storeu_pd;
        // SAFETY: stores at k .. k + 4 (the caller's contract).
        unsafe {
            _mm256_storeu_pd(self.d.as_mut_ptr().add(k), q.d);
            _mm256_storeu_pd(self.v.as_mut_ptr().add(k), q.v);
        }
    }
}

/// Four modes' η and η̇ in registers.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub(crate) struct Quad {
    pub(crate) d: std::arch::x86_64::__m256d,
    pub(crate) v: std::arch::x86_64::__m256d,
}

/// Four modes' shapes φ(x_n), φ(x_{n+1}) in registers.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub(crate) struct QuadPath {
    pub(crate) at_n: std::arch::x86_64::__m256d,
    pub(crate) at_n1: std::arch::x86_64::__m256d,
}

/// The two partial sums' registers four modes add into ([`PairSums`]).
#[cfg(target_arch = "x86_64")]
pub(crate) struct QuadSums<'a> {
    pub(crate) g: &'a mut std::arch::x86_64::__m256d,
    pub(crate) w: &'a mut std::arch::x86_64::__m256d,
}

/// The free step of mode i: `(cos·η + sin/ω·η̇, −ω sin·η + cos_v·η̇)`,
/// fused (cos_v = cos for an undamped mode; the vector kernels below read
/// `cos` for both and run undamped modes only).
#[inline(always)]
pub(crate) fn rotate_mode(m: &ModeSteps, i: usize, e: f64, ev: f64) -> (f64, f64) {
    (
        m.cos[i].mul_add(e, m.sin_over_omega[i] * ev),
        m.minus_omega_sin[i].mul_add(e, m.cos_v[i] * ev),
    )
}

/// `a0 p + a1 q` (or b0, b1) of mode i, fused.
#[inline(always)]
pub(crate) fn path(a0: f64, p: f64, a1: f64, q: f64) -> f64 {
    a0.mul_add(p, a1 * q)
}

/// The free step of every mode: `[η, η̇] ← E [η, η̇]`, plus the held load.
#[inline(always)]
pub(crate) fn free(
    m: &ModeSteps,
    held: Option<&(Vec<f64>, Vec<f64>)>,
    st: &mut State,
    vector: bool,
) {
    let j = m.len();
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if vector {
        // SAFETY: the caller checked AVX2 and FMA; every slice holds J.
        done = unsafe { free_avx2(m, d, v) };
    }
    for i in done..j {
        (d[i], v[i]) = rotate_mode(m, i, d[i], v[i]);
    }
    if let Some((hp, hv)) = held {
        for i in 0..j {
            d[i] += hp[i];
            v[i] += hv[i];
        }
    }
}

/// The whole vectors of [`free`] (without the held load); returns how many
/// modes it did.
///
/// # Safety
/// The CPU supports AVX2 and FMA; d, v and the coefficients hold J entries.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn free_avx2(m: &ModeSteps, d: &mut [f64], v: &mut [f64]) -> usize {
    use std::arch::x86_64::*;
    let full = d.len() / 4 * 4;
    // SAFETY (whole body): loads and stores at i .. i + 4 ≤ full.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let mut i = 0;
        while i < full {
            let (e, ev, c) = (ld(d, i), ld(v, i), ld(&m.cos, i));
            let e1 = _mm256_fmadd_pd(c, e, _mm256_mul_pd(ld(&m.sin_over_omega, i), ev));
            let v1 = _mm256_fmadd_pd(ld(&m.minus_omega_sin, i), e, _mm256_mul_pd(c, ev));
            _mm256_storeu_pd(d.as_mut_ptr().add(i), e1);
            _mm256_storeu_pd(v.as_mut_ptr().add(i), v1);
            i += 4;
        }
    }
    full
}

/// [`free`] over modes `range` fused with the two sums of a single
/// contact ([`PairSums`]); mode i ≥ ⌊J/8⌋·8 goes into lane i − ⌊J/8⌋·8, as
/// [`lanes::dot`] puts its tail, so any split into ranges at multiples of
/// [`LANES`] gives the sums of one pass.
#[inline(always)]
pub(crate) fn free_with_pair(
    m: &ModeSteps,
    held: Option<&(Vec<f64>, Vec<f64>)>,
    st: &mut State,
    shapes: PathShapes,
    range: Range<usize>,
    sums: &mut PairSums,
    vector: bool,
) {
    let Range { start: lo, end: hi } = range;
    debug_assert!(lo % LANES == 0 && hi <= m.len());
    let j = m.len();
    let full = j / LANES * LANES;
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    let (pn, pn1) = (&shapes.at_n[..j], &shapes.at_n1[..j]);
    let step = HeldStep::of(held, j);
    let (hp, hv) = (step.d, step.v);
    let mut done = lo;
    #[cfg(target_arch = "x86_64")]
    if vector {
        let end = hi.min(full).max(lo);
        let modes = ModeState {
            d: &mut *d,
            v: &mut *v,
        };
        let shapes = PathShapes {
            at_n: pn,
            at_n1: pn1,
        };
        // SAFETY: the caller checked AVX2 and FMA; every slice holds J ≥ end,
        // `lo` and `end` are multiples of LANES, hp/hv hold J when present.
        unsafe { free_with_pair_avx2(m, modes, shapes, step, lo..end, sums) };
        done = end;
    }
    for i in done..hi {
        let l = if i < full { i % LANES } else { i - full };
        let (mut e1, mut v1) = rotate_mode(m, i, d[i], v[i]);
        if held.is_some() {
            e1 += hp[i];
            v1 += hv[i];
        }
        d[i] = e1;
        v[i] = v1;
        sums.g[l] = pn1[i].mul_add(e1, sums.g[l]);
        sums.w[l] = pn1[i].mul_add(path(m.a0[i], pn[i], m.a1[i], pn1[i]), sums.w[l]);
    }
}

/// Modes `range` of [`free_with_pair`], eight at a time.
///
/// # Safety
/// The CPU supports AVX2 and FMA; the range's ends are multiples of
/// [`LANES`]; every slice has at least `range.end` entries, or the held
/// step's are both empty (no held load).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn free_with_pair_avx2(
    m: &ModeSteps,
    mut modes: ModeState,
    path: PathShapes,
    held: HeldStep,
    range: Range<usize>,
    sums: &mut PairSums,
) {
    use std::arch::x86_64::*;
    // SAFETY (whole body): loads and stores at i .. i + 4 ≤ range.end.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let (mut g, mut w) = sums.load_avx2();
        let mut i = range.start;
        while i < range.end {
            for h in 0..2 {
                let k = i + 4 * h;
                let now = modes.load4(k);
                let shapes = QuadPath {
                    at_n: ld(path.at_n, k),
                    at_n1: ld(path.at_n1, k),
                };
                let into = QuadSums {
                    g: &mut g[h],
                    w: &mut w[h],
                };
                free_pair4(m, k, now, shapes, held, &mut modes, into);
            }
            i += LANES;
        }
        sums.store_avx2(g, w);
    }
}

/// Modes `k .. k + 4` of a fused pass (`free_with_pair_avx2` and the
/// fused kernels): the free step from `now` plus the held load (when the
/// held step is not empty), stored into `modes`, and the two sums with
/// `p = φ(x_n)`, `q = φ(x_{n+1})` (`path`) into `into`: the operations of
/// [`free_with_pair`]'s scalar loop (the same bits).
///
/// # Safety
/// The CPU supports AVX2 and FMA; every slice holds `k + 4` entries, or
/// the held step's are both empty.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(crate) unsafe fn free_pair4(
    m: &ModeSteps,
    k: usize,
    now: Quad,
    path: QuadPath,
    held: HeldStep,
    modes: &mut ModeState,
    into: QuadSums,
) {
    use std::arch::x86_64::*;
    let (Quad { d: e, v: ev }, QuadPath { at_n: p, at_n1: q }) = (now, path);
    let (HeldStep { d: hp, v: hv }, QuadSums { g, w }) = (held, into);
    let ModeState { d, v } = modes;
    // SAFETY: loads and stores at k .. k + 4 (the caller's contract).
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let c = ld(&m.cos, k);
        let mut e1 = _mm256_fmadd_pd(c, e, _mm256_mul_pd(ld(&m.sin_over_omega, k), ev));
        let mut v1 = _mm256_fmadd_pd(ld(&m.minus_omega_sin, k), e, _mm256_mul_pd(c, ev));
        if !hp.is_empty() {
            e1 = _mm256_add_pd(e1, ld(hp, k));
            v1 = _mm256_add_pd(v1, ld(hv, k));
        }
        _mm256_storeu_pd(d.as_mut_ptr().add(k), e1);
        _mm256_storeu_pd(v.as_mut_ptr().add(k), v1);
        *g = _mm256_fmadd_pd(q, e1, *g);
        let z = _mm256_fmadd_pd(ld(&m.a0, k), p, _mm256_mul_pd(ld(&m.a1, k), q));
        *w = _mm256_fmadd_pd(q, z, *w);
    }
}

/// Modes `k .. k + 4` of `now` plus a force `fv` held along the path
/// from shapes `p` to `q` (`path`): `(e + f (a0 p + a1 q), ev + f (b0 p +
/// b1 q))`, the operations of [`add_path_load`]'s scalar loop (the same
/// bits).
///
/// # Safety
/// The CPU supports AVX2 and FMA; the four weight slices hold `k + 4`
/// entries.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(crate) unsafe fn path_load4(
    weights: PathWeights,
    k: usize,
    fv: std::arch::x86_64::__m256d,
    path: QuadPath,
    now: Quad,
) -> Quad {
    use std::arch::x86_64::*;
    let PathWeights { a0, a1, b0, b1 } = weights;
    let (QuadPath { at_n: p, at_n1: q }, Quad { d: e, v: ev }) = (path, now);
    // SAFETY: loads at k .. k + 4 (the caller's contract).
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let z = _mm256_fmadd_pd(ld(a0, k), p, _mm256_mul_pd(ld(a1, k), q));
        let zv = _mm256_fmadd_pd(ld(b0, k), p, _mm256_mul_pd(ld(b1, k), q));
        Quad {
            d: _mm256_fmadd_pd(fv, z, e),
            v: _mm256_fmadd_pd(fv, zv, ev),
        }
    }
}

/// Add a force `f` (N) held over the step along the carrier's path into
/// modes `range`: `η += f (a0 φ(x_n) + a1 φ(x_{n+1}))`,
/// `η̇ += f (b0 φ(x_n) + b1 φ(x_{n+1}))` (mode by mode: any split gives the
/// same bits).
#[inline(always)]
pub(crate) fn add_path_load(
    m: &ModeSteps,
    f: f64,
    shapes: PathShapes,
    st: &mut State,
    range: Range<usize>,
    vector: bool,
) {
    let (lo, hi) = (range.start, range.end);
    let (d, v) = (&mut st.d[lo..hi], &mut st.v[lo..hi]);
    let (pn, pn1) = (&shapes.at_n[lo..hi], &shapes.at_n1[lo..hi]);
    let weights = PathWeights::of(m).range(lo..hi);
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if vector {
        let modes = ModeState {
            d: &mut *d,
            v: &mut *v,
        };
        let shapes = PathShapes {
            at_n: pn,
            at_n1: pn1,
        };
        // SAFETY: the caller checked AVX2 and FMA; every slice holds hi − lo.
        done = unsafe { add_path_load_avx2(f, weights, shapes, modes) };
    }
    let PathWeights { a0, a1, b0, b1 } = weights;
    for i in done..hi - lo {
        d[i] = f.mul_add(path(a0[i], pn[i], a1[i], pn1[i]), d[i]);
        v[i] = f.mul_add(path(b0[i], pn[i], b1[i], pn1[i]), v[i]);
    }
}

/// The whole vectors of [`add_path_load`]; returns how many modes it did.
///
/// # Safety
/// The CPU supports AVX2 and FMA; every slice has the length of
/// `modes.d`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(crate) unsafe fn add_path_load_avx2(
    f: f64,
    weights: PathWeights,
    path: PathShapes,
    mut modes: ModeState,
) -> usize {
    use std::arch::x86_64::*;
    let full = modes.d.len() / 4 * 4;
    // SAFETY (whole body): loads and stores at i .. i + 4 ≤ full.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let fv = _mm256_set1_pd(f);
        let mut i = 0;
        while i < full {
            let shapes = QuadPath {
                at_n: ld(path.at_n, i),
                at_n1: ld(path.at_n1, i),
            };
            let now = path_load4(weights, i, fv, shapes, modes.load4(i));
            modes.store4(i, now);
            i += 4;
        }
    }
    full
}

/// `Σ_j r_j (a0_j p_j + a1_j q_j)`: a contact row against a unit force
/// held along a carrier's path (φ(x_n) = p, φ(x_{n+1}) = q), in [`LANES`]
/// partial sums (scalar: the general path of several carriers).
#[inline(always)]
pub(crate) fn path_dot(m: &ModeSteps, r: &[f64], p: &[f64], q: &[f64]) -> f64 {
    let j = m.len();
    let mut acc = [0.0; LANES];
    let full = j / LANES * LANES;
    for i in 0..j {
        let l = if i < full { i % LANES } else { i - full };
        acc[l] = r[i].mul_add(path(m.a0[i], p[i], m.a1[i], q[i]), acc[l]);
    }
    lanes::reduce(&acc)
}
