//! [`Blocks`] in AVX-512 registers, eight modes a register: the
//! operations of `BlocksAvx::next` (the oscillating part) and of
//! `Layer::add_into` (a clamped end's boundary-layer terms, left end then
//! right) lane by lane, so the same bits as
//! [`super::FastShapes::values_into`], with the layer terms added while
//! the block is in registers instead of a whole-vector store and reload
//! (`Blocks::layered_into`). A layer row's last partial vector is masked:
//! its lanes get the fused `row·e^{−αδ} + value` of the scalar loop, the
//! others keep their value untouched.

use std::arch::x86_64::*;

use super::{BLOCK, BlockRows, Blocks, COS, INV_FACT, LAYER_DEGREE, SIN};

/// Registers per block of [`BLOCK`] modes.
const V: usize = BLOCK / 8;

/// One end's boundary-layer row at the point: the row's values, its
/// modes' α and `−δ` in every lane (`Layer::add_into`).
struct LayerRow<'a> {
    row: &'a [f64],
    alpha: &'a [f64],
    minus_delta: __m512d,
}

/// [`Blocks`] in AVX-512 registers: the recurrence's state, the
/// constants of the slow-phase polynomial and the layer rows at the point.
pub(crate) struct BlocksAvx512<'a> {
    vr: [__m512d; V],
    vi: [__m512d; V],
    cr: __m512d,
    ci: __m512d,
    dl: __m512d,
    /// The left end's row, then the right's: the order of
    /// `FastShapes::values_into`.
    layers: [Option<LayerRow<'a>>; 2],
}

impl<'a> BlocksAvx512<'a> {
    /// The registers for `b`'s first block.
    ///
    /// # Safety
    /// The CPU supports AVX-512F.
    #[target_feature(enable = "avx512f")]
    #[inline]
    pub(crate) unsafe fn new(b: &Blocks<'a>) -> Self {
        let delta = match b.rows {
            BlockRows::Shifted { delta, .. } => delta,
            BlockRows::Sine(_) => 0.0,
        };
        let layers = b.layers.map(|l| {
            let (layer, d) = l?;
            let (row, alpha, delta) = layer.row_at(d)?;
            Some(LayerRow {
                row,
                alpha,
                minus_delta: _mm512_set1_pd(-delta),
            })
        });
        // SAFETY: rr and ri hold BLOCK entries.
        unsafe {
            BlocksAvx512 {
                vr: std::array::from_fn(|v| _mm512_loadu_pd(b.rr.as_ptr().add(8 * v))),
                vi: std::array::from_fn(|v| _mm512_loadu_pd(b.ri.as_ptr().add(8 * v))),
                cr: _mm512_set1_pd(b.rot.0),
                ci: _mm512_set1_pd(b.rot.1),
                dl: _mm512_set1_pd(delta),
                layers,
            }
        }
    }

    /// The values of modes `at .. at + BLOCK` (`at` a multiple of
    /// [`BLOCK`], `at + BLOCK ≤ b.full()`, the blocks taken in order) with
    /// their boundary-layer terms, two vectors of eight, and the
    /// recurrence advanced to the next block.
    ///
    /// Inlined whole into its caller, which is compiled for AVX-512F
    /// (a call would pass the block through memory).
    ///
    /// # Safety
    /// The CPU supports AVX-512F and the caller is compiled for it;
    /// `at + BLOCK ≤ b.full()`.
    #[inline(always)]
    pub(crate) unsafe fn next(&mut self, b: &Blocks, at: usize) -> [__m512d; V] {
        // SAFETY (whole body): every load is within at .. at + BLOCK ≤ J,
        // or masked to the lanes within a layer row.
        unsafe {
            let ld = |x: &[f64], i: usize| _mm512_loadu_pd(x.as_ptr().add(i));
            let s = _mm512_set1_pd;
            let mut out = [_mm512_setzero_pd(); V];
            for (v, o) in out.iter_mut().enumerate() {
                let i = at + 8 * v;
                let (a, bb) = (self.vr[v], self.vi[v]);
                *o = match b.rows {
                    // as sine_avx2
                    BlockRows::Sine(d) => _mm512_mul_pd(ld(d, i), bb),
                    // as shifted_avx2
                    BlockRows::Shifted { eps, tre, tim, .. } => {
                        let y = _mm512_mul_pd(ld(eps, i), self.dl);
                        let y2 = _mm512_mul_pd(y, y);
                        let cy = _mm512_fmadd_pd(
                            y2,
                            _mm512_fmadd_pd(
                                y2,
                                _mm512_fmadd_pd(y2, s(COS[2]), s(COS[1])),
                                s(COS[0]),
                            ),
                            s(1.0),
                        );
                        let sy = _mm512_mul_pd(
                            y,
                            _mm512_fmadd_pd(y2, _mm512_fmadd_pd(y2, s(SIN[1]), s(SIN[0])), s(1.0)),
                        );
                        let (tr, ti) = (ld(tre, i), ld(tim, i));
                        let zr = _mm512_fmsub_pd(tr, cy, _mm512_mul_pd(ti, sy));
                        let zi = _mm512_fmadd_pd(tr, sy, _mm512_mul_pd(ti, cy));
                        _mm512_fmsub_pd(zr, a, _mm512_mul_pd(zi, bb))
                    }
                };
                self.vr[v] = _mm512_fmsub_pd(a, self.cr, _mm512_mul_pd(bb, self.ci));
                self.vi[v] = _mm512_fmadd_pd(a, self.ci, _mm512_mul_pd(bb, self.cr));
            }
            if at < b.layered {
                for r in self.layers.iter().flatten() {
                    out = r.add(at, out);
                }
            }
            out
        }
    }

    /// Hand the recurrence's state back to `b` for [`Blocks::tail_into`].
    ///
    /// # Safety
    /// The CPU supports AVX-512F.
    #[target_feature(enable = "avx512f")]
    #[inline]
    pub(crate) unsafe fn finish(&self, b: &mut Blocks) {
        for v in 0..V {
            // SAFETY: rr and ri hold BLOCK entries.
            unsafe {
                _mm512_storeu_pd(b.rr.as_mut_ptr().add(8 * v), self.vr[v]);
                _mm512_storeu_pd(b.ri.as_mut_ptr().add(8 * v), self.vi[v]);
            }
        }
    }
}

impl LayerRow<'_> {
    /// `q` plus the row's terms of modes `at .. at + BLOCK` (those below
    /// the row's length): `row·e^{−αδ} + q` with `e^{−y}` by the Horner
    /// polynomial of `layer_avx2` / `exp_minus`, one rounding each. The
    /// block's registers go through the polynomial in lockstep, so that
    /// their chains of fused operations overlap.
    ///
    /// # Safety
    /// The CPU supports AVX-512F and the caller is compiled for it.
    #[inline(always)]
    unsafe fn add(&self, at: usize, q: [__m512d; V]) -> [__m512d; V] {
        let m = self.row.len();
        if at >= m {
            return q;
        }
        // the lanes of register v within the row
        let mask = |v: usize| -> __mmask8 {
            let i = at + 8 * v;
            if i >= m {
                0
            } else if m - i >= 8 {
                0xff
            } else {
                (1u8 << (m - i)) - 1
            }
        };
        let k: [__mmask8; V] = std::array::from_fn(mask);
        // register v's first lane, at most m: a register wholly beyond the
        // row (mask empty) points one past its end, never further
        let first = |v: usize| (at + 8 * v).min(m);
        // SAFETY: `first(v)` ≤ m, the length of both slices (one past the
        // end at most); the masked loads touch lanes i .. min(i + 8, m)
        // only, none when the mask is empty.
        unsafe {
            // z = −(α δ): as the scalar −y with y = α·δ
            let z: [__m512d; V] = std::array::from_fn(|v| {
                let alpha = _mm512_maskz_loadu_pd(k[v], self.alpha.as_ptr().add(first(v)));
                _mm512_mul_pd(alpha, self.minus_delta)
            });
            let mut acc = [_mm512_set1_pd(INV_FACT[LAYER_DEGREE]); V];
            for j in (0..LAYER_DEGREE).rev() {
                let c = _mm512_set1_pd(INV_FACT[j]);
                for v in 0..V {
                    acc[v] = _mm512_fmadd_pd(acc[v], z[v], c);
                }
            }
            // the lanes outside the row keep q's bits
            std::array::from_fn(|v| {
                let row = _mm512_maskz_loadu_pd(k[v], self.row.as_ptr().add(first(v)));
                _mm512_mask3_fmadd_pd(row, acc[v], q[v], k[v])
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::FastShapes;
    use super::super::tests::{REFERENCE, shapes};
    use super::*;
    use crate::numeric::lanes;
    use crate::scene::Support::{Clamped, Pinned};

    /// The values of `f` at `x` by [`BlocksAvx512`] (the whole blocks, the
    /// layer terms added in registers) and [`Blocks::tail_into`], or
    /// `None` where [`FastShapes::blocks_at`] declines.
    ///
    /// # Safety
    /// The CPU supports AVX-512F.
    #[target_feature(enable = "avx512f")]
    unsafe fn by_blocks(f: &FastShapes, x: f64, out: &mut [f64]) -> Option<bool> {
        let mut b = f.blocks_at(x)?;
        let full = b.full();
        // SAFETY: AVX-512F (the contract); out holds J ≥ full.
        unsafe {
            let mut v = BlocksAvx512::new(&b);
            for at in (0..full).step_by(BLOCK) {
                for (u, q) in v.next(&b, at).into_iter().enumerate() {
                    _mm512_storeu_pd(out.as_mut_ptr().add(at + 8 * u), q);
                }
            }
            v.finish(&mut b);
        }
        b.tail_into(&mut out[full..]);
        Some(b.layered > 0)
    }

    /// The blocks in AVX-512 registers, the boundary layers' terms added
    /// there (masked in a row's last partial register), give the bits of
    /// [`FastShapes::values_into`] (whose AVX2 and scalar paths agree bit
    /// for bit, `the_vector_and_scalar_paths_give_the_same_bits`): each
    /// support pair with a layer, one end or both, mirrored or not, J with
    /// and without a partial block, points crowded towards both ends.
    #[test]
    fn the_avx512_blocks_give_the_values_bit_for_bit() {
        if !lanes::avx512() {
            return;
        }
        const BARE: (f64, f64, f64, f64) = (3.0, 0.0, 2.0, 1.7);
        let mut layered = 0;
        for (case, ends) in [
            (REFERENCE, (Clamped, Pinned)),
            (REFERENCE, (Pinned, Clamped)),
            (REFERENCE, (Clamped, Clamped)),
            (REFERENCE, (Pinned, Pinned)),
            (BARE, (Clamped, Clamped)),
        ] {
            for j in [5, 16, 61, 803] {
                let s = shapes(case, ends, j);
                let f = FastShapes::new(&s);
                let (mut a, mut b) = (vec![0.0; j], vec![0.0; j]);
                for i in 0..=600 {
                    let u = (i as f64 / 600.0).powi(3);
                    for x in [case.3 * u, case.3 * (1.0 - u)] {
                        f.values_into(x, &mut a);
                        b.fill(f64::NAN);
                        // SAFETY: AVX-512F checked above.
                        let Some(l) = (unsafe { by_blocks(&f, x, &mut b) }) else {
                            continue;
                        };
                        layered += usize::from(l);
                        for (u, v) in a.iter().zip(&b) {
                            assert_eq!(
                                u.to_bits(),
                                v.to_bits(),
                                "{case:?} {ends:?} J = {j} x = {x}"
                            );
                        }
                    }
                }
            }
        }
        assert!(layered > 1000, "the layers were met: {layered}");
    }
}
