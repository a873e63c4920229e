//! `modal_exact`'s table pass in AVX-512 registers (MODEL §9.3): the
//! shapes φ(x_{n+1}) from the tables while the carrier accelerates or
//! within a clamped end's boundary layer, eight modes a register
//! ([`BlocksAvx512`], the layer terms added in registers), each block
//! taken at once by its modes' free step and the pair's two sums. The
//! operations of the AVX2 passes (`Blocks::layered_into` then
//! `fused_free_pair_avx2`, and `shapes_free_pair_avx2`) lane by lane, mode
//! i in lane i mod 8 of the same partial sums: the same bits.

use std::arch::x86_64::*;

use crate::analytic::{Blocks, BlocksAvx512, SHAPE_BLOCK};
use crate::numeric::lanes::LANES;

use super::modal_kernels::{CoefBlock, FusedPass, HeldStep, ModeState};

/// Modes `0 .. blocks.full()` of a single contact's step from the
/// tables: each block of shapes evaluated with its boundary-layer terms
/// ([`BlocksAvx512::next`]), stored into `pn1`, and, while in registers,
/// the last step's deferred update (with `DEFERRED`, from `pn1` before
/// that store, φ(x_{n−1}), to `pn`, φ(x_n)), the free step plus the held
/// load and the two sums, their coefficients from `coefs` (`pass.m`'s,
/// `coef_blocks`).
///
/// # Safety
/// The CPU supports AVX-512F; `coefs` holds at least `blocks.full() /
/// LANES` blocks; every slice holds at least `blocks.full()` entries, or
/// the held step's are both empty.
#[target_feature(enable = "avx512f")]
pub(crate) unsafe fn shapes_free_pair_avx512<const DEFERRED: bool>(
    blocks: &mut Blocks,
    pass: FusedPass,
    coefs: &[CoefBlock],
    f: f64,
) {
    let FusedPass {
        m: _,
        modes: ModeState { d, v },
        pn,
        pn1,
        held: HeldStep { d: hp, v: hv },
        sums,
    } = pass;
    let held = !hp.is_empty();
    let end = blocks.full();
    // SAFETY (whole body): loads and stores at k .. k + 8 ≤ end, block
    // k / 8 < end / 8 of `coefs`, whose rows are 64-byte aligned.
    unsafe {
        let mut shapes = BlocksAvx512::new(blocks);
        let ld = |x: &[f64], i: usize| _mm512_loadu_pd(x.as_ptr().add(i));
        let row = |x: &[f64; LANES]| _mm512_load_pd(x.as_ptr());
        let (mut g, mut w) = (ld(&sums.g, 0), ld(&sums.w, 0));
        let fv = _mm512_set1_pd(f);
        let mut at = 0;
        while at < end {
            for (u, q) in shapes.next(blocks, at).into_iter().enumerate() {
                let k = at + LANES * u;
                let c = coefs.get_unchecked(k / LANES);
                let (a0, a1) = (row(&c.a0), row(&c.a1));
                let p = ld(pn, k);
                let (mut e, mut ev) = (ld(d, k), ld(v, k));
                if DEFERRED {
                    // as `path_load4`
                    let p0 = ld(pn1, k);
                    let z = _mm512_fmadd_pd(a0, p0, _mm512_mul_pd(a1, p));
                    let zv = _mm512_fmadd_pd(row(&c.b0), p0, _mm512_mul_pd(row(&c.b1), p));
                    e = _mm512_fmadd_pd(fv, z, e);
                    ev = _mm512_fmadd_pd(fv, zv, ev);
                }
                _mm512_storeu_pd(pn1.as_mut_ptr().add(k), q);
                // the free step and the two sums, as `free_pair4`
                let (cs, so, mos) = (row(&c.cos), row(&c.sin_over_omega), row(&c.minus_omega_sin));
                let mut e1 = _mm512_fmadd_pd(cs, e, _mm512_mul_pd(so, ev));
                let mut v1 = _mm512_fmadd_pd(mos, e, _mm512_mul_pd(cs, ev));
                if held {
                    e1 = _mm512_add_pd(e1, ld(hp, k));
                    v1 = _mm512_add_pd(v1, ld(hv, k));
                }
                _mm512_storeu_pd(d.as_mut_ptr().add(k), e1);
                _mm512_storeu_pd(v.as_mut_ptr().add(k), v1);
                g = _mm512_fmadd_pd(q, e1, g);
                let z = _mm512_fmadd_pd(a0, p, _mm512_mul_pd(a1, q));
                w = _mm512_fmadd_pd(q, z, w);
            }
            at += SHAPE_BLOCK;
        }
        shapes.finish(blocks);
        _mm512_storeu_pd(sums.g.as_mut_ptr(), g);
        _mm512_storeu_pd(sums.w.as_mut_ptr(), w);
    }
}
