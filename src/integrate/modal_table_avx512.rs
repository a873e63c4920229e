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

use super::modal_kernels::{CoefBlock, FusedPass, HeldStep, ModeState, step_block_avx512};

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
    let held = HeldStep { d: hp, v: hv };
    let end = blocks.full();
    debug_assert!(
        coefs.len() >= end / LANES
            && [pn.len(), pn1.len(), d.len(), v.len()]
                .iter()
                .all(|&n| n >= end),
        "the pass's preconditions"
    );
    // SAFETY (whole body): loads and stores at k .. k + 8 ≤ end, block
    // k / 8 < end / 8 of `coefs`, whose rows are 64-byte aligned.
    unsafe {
        let mut shapes = BlocksAvx512::new(blocks);
        let ld = |x: &[f64], i: usize| _mm512_loadu_pd(x.as_ptr().add(i));
        let mut acc = [ld(&sums.g, 0), ld(&sums.w, 0)];
        let fv = _mm512_set1_pd(f);
        let mut at = 0;
        while at < end {
            for (u, q) in shapes.next(blocks, at).into_iter().enumerate() {
                let k = at + LANES * u;
                let c = coefs.get_unchecked(k / LANES);
                let modes = ModeState {
                    d: &mut *d,
                    v: &mut *v,
                };
                let pq = [ld(pn, k), q];
                step_block_avx512::<DEFERRED>(c, k, pq, modes, &mut *pn1, &held, fv, &mut acc);
            }
            at += SHAPE_BLOCK;
        }
        shapes.finish(blocks);
        _mm512_storeu_pd(sums.g.as_mut_ptr(), acc[0]);
        _mm512_storeu_pd(sums.w.as_mut_ptr(), acc[1]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::FastShapes;
    use crate::analytic::fast_shapes::tests::{REFERENCE, shapes};
    use crate::integrate::modal_kernels::{
        PairSums, Phasors, coef_blocks, fused_free_pair_avx2, samples, shapes_free_pair_avx2,
    };
    use crate::numeric::lanes;
    use crate::scene::Support::{Clamped, Pinned};

    /// The table pass in AVX-512 registers gives the bits of the AVX2
    /// passes (the layer's blocks whole, `Blocks::layered_into`, then
    /// `fused_free_pair_avx2` over them and `shapes_free_pair_avx2` over
    /// the rest, as `place_free_pair_tables` takes them): the shapes
    /// stored, the state, the pair's partial sums and the recurrence
    /// handed to the tail, with and without a deferred update and a held
    /// load, within a clamped end's boundary layer (one end or both) and
    /// beyond it.
    #[test]
    fn the_avx512_table_pass_gives_the_bits_of_the_avx2_one() {
        if !lanes::avx512() {
            return;
        }
        let j = 808;
        let m = samples::steps(j);
        let coefs = coef_blocks(&m);
        let wave = |k: f64| samples::wave(j, k);
        let held = (wave(0.2), wave(0.9));
        type Run = (Vec<f64>, Vec<f64>, Vec<f64>, PairSums, Vec<f64>);
        let pass = |f: &FastShapes, x: f64, wide: bool, deferred: Option<f64>, h: bool| {
            let mut blocks = f.blocks_at(x)?;
            let full = blocks.full();
            let (mut d, mut v, mut pn1) = (wave(1.3), wave(0.7), wave(0.33));
            let pn = wave(0.37);
            let mut sums = PairSums {
                g: [0.5; LANES],
                w: [-0.25; LANES],
            };
            let mut layered = vec![0.0; j];
            let hs = HeldStep::of(h.then_some(&held), j);
            macro_rules! fp {
                () => {
                    FusedPass {
                        m: &m,
                        modes: ModeState {
                            d: &mut d,
                            v: &mut v,
                        },
                        pn: &pn,
                        pn1: &mut pn1,
                        held: hs,
                        sums: &mut sums,
                    }
                };
            }
            let f = deferred.unwrap_or(0.0);
            // SAFETY: AVX-512F (so AVX2 and FMA) checked above; every
            // slice holds J ≥ full, `coefs` J / 8 blocks.
            unsafe {
                if wide {
                    let p = fp!();
                    match deferred {
                        Some(_) => shapes_free_pair_avx512::<true>(&mut blocks, p, &coefs, f),
                        None => shapes_free_pair_avx512::<false>(&mut blocks, p, &coefs, f),
                    }
                } else {
                    let lo = blocks.layered_into(&mut layered);
                    let p = fp!();
                    let stored = Phasors {
                        fi: &mut layered,
                        rr: &[],
                        ri: &[],
                    };
                    match deferred {
                        Some(_) => fused_free_pair_avx2::<false, true>(p, stored, lo, f),
                        None => fused_free_pair_avx2::<false, false>(p, stored, lo, f),
                    }
                    let p = fp!();
                    match deferred {
                        Some(_) => shapes_free_pair_avx2::<true>(&mut blocks, lo, p, f),
                        None => shapes_free_pair_avx2::<false>(&mut blocks, lo, p, f),
                    }
                }
            }
            let mut tail = vec![0.0; j - full];
            blocks.tail_into(&mut tail);
            Some::<Run>((d, v, pn1, sums, tail))
        };
        let bits = |x: &[f64]| -> Vec<u64> { x.iter().map(|y| y.to_bits()).collect() };
        let mut layered = 0;
        for ends in [(Clamped, Pinned), (Pinned, Clamped), (Clamped, Clamped)] {
            let f = FastShapes::new(&shapes(REFERENCE, ends, j));
            for i in 0..=120 {
                let u = (i as f64 / 120.0).powi(3);
                for x in [REFERENCE.3 * u, REFERENCE.3 * (1.0 - u)] {
                    layered += usize::from(f.in_layer(x));
                    for deferred in [None, Some(-37.5)] {
                        for h in [false, true] {
                            let (Some(a), Some(b)) = (
                                pass(&f, x, true, deferred, h),
                                pass(&f, x, false, deferred, h),
                            ) else {
                                continue;
                            };
                            let case = format!("{ends:?} x = {x}, deferred {deferred:?}, held {h}");
                            assert_eq!(bits(&a.0), bits(&b.0), "d, {case}");
                            assert_eq!(bits(&a.1), bits(&b.1), "v, {case}");
                            assert_eq!(bits(&a.2), bits(&b.2), "shapes, {case}");
                            assert_eq!(bits(&a.3.g), bits(&b.3.g), "g, {case}");
                            assert_eq!(bits(&a.3.w), bits(&b.3.w), "w, {case}");
                            assert_eq!(bits(&a.4), bits(&b.4), "tail, {case}");
                        }
                    }
                }
            }
        }
        assert!(layered > 100, "the layers were met: {layered}");
    }
}
