//! Sums over the J coordinates of a modal basis in eight partial sums, with
//! fused multiply–adds, and the same bits on every x86-64 machine.
//!
//! A plain `Σ x_j y_j` is one chain of dependent additions (J × the add
//! latency: ~1 µs at J = 800), and the compiler may not reorder a float sum
//! to vectorize it. Here coordinate j goes into partial sum j mod
//! [`LANES`], and the eight are added in a fixed tree.
//!
//! **Fused multiply–adds, and the same bytes everywhere.** The modal
//! kernels (this sum, `FastShapes`, the `modal_exact` step) are written with
//! `a·b + c` rounded once: AVX2 + FMA vectors where the CPU has both
//! ([`avx2_fma`]), else the same formula lane by lane with
//! [`f64::mul_add`], which IEEE 754 defines as the same correctly rounded
//! operation (done in software on a CPU without FMA: slower, same bits).
//! So a run gives the same bytes on any machine, whichever path it takes,
//! and the kernels do about a third fewer operations than with a multiply
//! and an add. `tests` check the two paths bit for bit.

/// Partial sums of a sum over coordinates.
pub const LANES: usize = 8;

/// True when the CPU has AVX2 and FMA (the vector paths of the modal
/// kernels; checked once and cached by the standard library).
#[inline(always)]
pub fn avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// True when the CPU has AVX-512F besides AVX2 and FMA: `modal_exact`'s
/// cruise pass then takes its eight lanes in one register, the same
/// operations lane by lane (the same bits) in half the instructions.
#[inline(always)]
pub fn avx512() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        avx2_fma() && std::arch::is_x86_feature_detected!("avx512f")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The partial sums added in a fixed order.
#[inline(always)]
pub fn reduce(a: &[f64; LANES]) -> f64 {
    ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]))
}

/// `Σ_j x_j y_j` over the shorter of the two, in [`LANES`] partial sums
/// (`acc_l ← x_j·y_j + acc_l`, fused).
pub fn dot(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len().min(y.len());
    let (x, y) = (&x[..n], &y[..n]);
    #[cfg(target_arch = "x86_64")]
    if avx2_fma() {
        // SAFETY: the CPU supports AVX2 and FMA (checked just above).
        return unsafe { dot_avx2(x, y) };
    }
    dot_scalar(x, y)
}

fn dot_scalar(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len();
    let mut acc = [0.0; LANES];
    let full = n / LANES * LANES;
    for (a, b) in x[..full]
        .chunks_exact(LANES)
        .zip(y[..full].chunks_exact(LANES))
    {
        for l in 0..LANES {
            acc[l] = a[l].mul_add(b[l], acc[l]);
        }
    }
    tail_into(&mut acc, &x[full..], &y[full..]);
    reduce(&acc)
}

/// The last `n mod 8` terms into lanes 0, 1, … (as both paths do).
#[inline(always)]
fn tail_into(acc: &mut [f64; LANES], x: &[f64], y: &[f64]) {
    for (l, (a, b)) in x.iter().zip(y).enumerate() {
        acc[l] = a.mul_add(*b, acc[l]);
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn dot_avx2(x: &[f64], y: &[f64]) -> f64 {
    use std::arch::x86_64::*;
    let n = x.len();
    let full = n / LANES * LANES;
    let (mut lo, mut hi) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    let mut at = 0;
    while at < full {
        // SAFETY: at + 8 ≤ full ≤ len of both slices.
        unsafe {
            let (xp, yp) = (x.as_ptr().add(at), y.as_ptr().add(at));
            lo = _mm256_fmadd_pd(_mm256_loadu_pd(xp), _mm256_loadu_pd(yp), lo);
            hi = _mm256_fmadd_pd(_mm256_loadu_pd(xp.add(4)), _mm256_loadu_pd(yp.add(4)), hi);
        }
        at += LANES;
    }
    let mut acc = [0.0; LANES];
    // SAFETY: acc holds eight f64.
    unsafe {
        _mm256_storeu_pd(acc.as_mut_ptr(), lo);
        _mm256_storeu_pd(acc.as_mut_ptr().add(4), hi);
    }
    tail_into(&mut acc, &x[full..], &y[full..]);
    reduce(&acc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Aligned lines hold what a `Vec<f64>` holds through zeros, resize
    /// (up, down, up again within the lines) and clear, each start on a
    /// 64-byte boundary.
    #[test]
    fn aligned_lanes_behave_as_a_vec() {
        let mut a = AlignedLanes::zeros(13);
        let mut v = vec![0.0; 13];
        assert_eq!(a.as_ptr() as usize % 64, 0);
        for (i, (x, y)) in a.iter_mut().zip(v.iter_mut()).enumerate() {
            (*x, *y) = (i as f64, i as f64);
        }
        for (len, value) in [(30, 2.5), (5, 1.0), (9, -3.0), (0, 4.0), (17, 7.0)] {
            a.resize(len, value);
            v.resize(len, value);
            assert_eq!(*a, *v, "resize to {len}");
            assert_eq!(a.as_ptr() as usize % 64, 0);
        }
        a.clear();
        v.clear();
        a.resize(4, 1.5);
        v.resize(4, 1.5);
        assert_eq!(*a, *v);
        assert_eq!(a, a.clone());
    }

    #[test]
    fn the_two_paths_agree_bit_for_bit_and_give_the_sum() {
        for n in [0, 1, 7, 8, 9, 64, 803] {
            let x: Vec<f64> = (0..n)
                .map(|i| ((i * 37 % 101) as f64 - 50.0) / 7.0)
                .collect();
            let y: Vec<f64> = (0..n)
                .map(|i| ((i * 13 % 97) as f64).sqrt() - 3.0)
                .collect();
            let s = dot_scalar(&x, &y);
            assert_eq!(dot(&x, &y).to_bits(), s.to_bits(), "n = {n}");
            #[cfg(target_arch = "x86_64")]
            if avx2_fma() {
                // SAFETY: checked just above.
                assert_eq!(
                    unsafe { dot_avx2(&x, &y) }.to_bits(),
                    s.to_bits(),
                    "n = {n}"
                );
            }
            let plain: f64 = x.iter().zip(&y).map(|(a, b)| a * b).sum();
            assert!((s - plain).abs() <= 1e-12 * (1.0 + plain.abs()));
        }
    }
}

/// One 64-byte line of [`LANES`] values, aligned to a cache line.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(64))]
struct Line([f64; LANES]);

/// `len` values in whole 64-byte-aligned lines, seen as a slice: each
/// block of [`LANES`] modes one cache line, so that a kernel's 512-bit
/// load at a multiple of [`LANES`] never spans two lines (a split load
/// costs about a second one). The same values as a `Vec<f64>`.
#[derive(Debug, Clone, Default)]
pub(crate) struct AlignedLanes {
    lines: Vec<Line>,
    len: usize,
}

impl AlignedLanes {
    /// `len` zeros.
    pub(crate) fn zeros(len: usize) -> Self {
        AlignedLanes {
            lines: vec![Line::default(); len.div_ceil(LANES)],
            len,
        }
    }

    /// Empty, its lines kept.
    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// `len` values: the first ones kept, any new ones `value` (as
    /// `Vec::resize`); allocates only beyond the lines held.
    pub(crate) fn resize(&mut self, len: usize, value: f64) {
        let lines = len.div_ceil(LANES);
        if lines > self.lines.len() {
            self.lines.resize(lines, Line::default());
        }
        let old = self.len;
        self.len = len;
        if len > old {
            self[old..].fill(value);
        }
    }
}

impl PartialEq for AlignedLanes {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl std::ops::Deref for AlignedLanes {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        // SAFETY: `Line` is `repr(C)` over `[f64; LANES]` with no padding
        // (64 bytes), so the lines are `LANES · lines.len() ≥ len`
        // contiguous, initialized f64s.
        unsafe { std::slice::from_raw_parts(self.lines.as_ptr().cast::<f64>(), self.len) }
    }
}

impl std::ops::DerefMut for AlignedLanes {
    fn deref_mut(&mut self) -> &mut [f64] {
        // SAFETY: as in `deref`, through the unique borrow of `lines`.
        unsafe { std::slice::from_raw_parts_mut(self.lines.as_mut_ptr().cast::<f64>(), self.len) }
    }
}
