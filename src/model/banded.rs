//! Symmetric banded matrices and their LDLᵀ factorization.
//!
//! Written by hand on purpose: neither faer nor nalgebra has a banded solver,
//! and faer's general sparse LDLᵀ is slower for this band. The per-step solve
//! is bound by the dependency chain of the triangular sweeps (row i needs
//! rows i−1..i−p), so the kernel sweeps several right-hand sides at once (the
//! free step and A⁻¹r of each contact, MODEL §5): their chains overlap in the
//! CPU, for nearly the price of one. The half-bandwidth p and the number of
//! right-hand sides are compile-time constants (p = 3 Hermite, p = 1 string,
//! p = 7 the Hermite contact and messenger wires interleaved, `docs/lines.md`
//! eq. W5), so the inner loops unroll, the last p solved rows stay in
//! registers, and an affine column h − K u (the generalized-α residual) is
//! computed inside the forward sweep ([`BandedLdlt::solve_affine`];
//! docs/performance.md has the figures).
//!
//! **Subnormals.** A solution decays geometrically away from the loads, and
//! on fine meshes its tails would pass through the subnormal range, where
//! many CPUs are many times slower. Every sweep replaces a value below
//! `NEGLIGIBLE` (1e-200) by exactly 0 as it produces it, so no subnormal is
//! ever formed: plain IEEE arithmetic, not a processor mode (flush-to-zero
//! flags are undefined behaviour in Rust), so every machine, thread and batch
//! width gives the same bytes, and the outputs are unchanged
//! (`tests/subnormal.rs` counts subnormals in every method's states).
//! `tests/banded_faer.rs` cross-checks the factorization and the fused solves
//! against faer's sparse LDLᵀ (backward errors held to O(n ε)).

use crate::error::{Error, Result};

/// Columns of a right-hand side for `nc` contacts: the free step and one
/// per contact, rounded up to an even number (at least two). The banded
/// sweeps carry the columns side by side in two-wide SIMD lanes: with one
/// column the compiler packs the sweep's window into vectors through general
/// registers, three extra moves on the dependency chain (measured: one-column
/// sweeps took 2.7× as long as two-column ones, `examples/step_profile.rs`);
/// with three, a half-empty lane and register spills (two carriers at
/// N = 800: 1.16 × 10⁸ DOF-steps/s with three columns, 1.55 × 10⁸ with four).
/// A padding column stays zero (A⁻¹0 = 0) and enters the update with weight 0.
pub(crate) fn rhs_columns(nc: usize) -> usize {
    (1 + nc).max(2).next_multiple_of(2)
}

/// A symmetric banded matrix with half-bandwidth `p`, stored as full band
/// rows: row i holds A[i, i−p ..= i+p] (entries outside the matrix are 0).
#[derive(Debug, Clone, PartialEq)]
pub struct SymBand {
    n: usize,
    p: usize,
    data: Vec<f64>,
}

impl SymBand {
    /// An n×n zero matrix of half-bandwidth p.
    pub fn zeros(n: usize, p: usize) -> Self {
        SymBand {
            n,
            p,
            data: vec![0.0; n * (2 * p + 1)],
        }
    }

    /// Dimension n.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Half-bandwidth p.
    pub fn bandwidth(&self) -> usize {
        self.p
    }

    /// A[i, j] (0 outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i.abs_diff(j) > self.p {
            return 0.0;
        }
        self.data[i * (2 * self.p + 1) + (j + self.p - i)]
    }

    /// A[i, j] += v, that entry alone (the band stores both triangles: a
    /// symmetric assembly calls it for (i, j) and for (j, i), as the element
    /// loops do over full element matrices).
    pub fn add_entry(&mut self, i: usize, j: usize, v: f64) {
        assert!(
            i.abs_diff(j) <= self.p,
            "entry ({i}, {j}) outside band {}",
            self.p
        );
        let w = 2 * self.p + 1;
        self.data[i * w + (j + self.p - i)] += v;
    }

    /// A += coef · r rᵀ for a sparse r given as (index, value) pairs, zero
    /// values skipped: a point spring, dashpot or mass (rank one). Its
    /// entries must fall within the band (one element's dofs, or a tie's
    /// two elements side by side).
    pub fn add_outer(&mut self, r: &[(usize, f64)], coef: f64) {
        for &(i, vi) in r {
            for &(j, vj) in r {
                if vi != 0.0 && vj != 0.0 {
                    self.add_entry(i, j, coef * vi * vj);
                }
            }
        }
    }

    /// Linear combination a·self + b·other (same shape).
    pub fn combine(&self, a: f64, other: &SymBand, b: f64) -> SymBand {
        assert_eq!((self.n, self.p), (other.n, other.p));
        SymBand {
            n: self.n,
            p: self.p,
            data: self
                .data
                .iter()
                .zip(&other.data)
                .map(|(x, y)| a * x + b * y)
                .collect(),
        }
    }

    /// y += alpha · A x.
    pub fn mul_acc(&self, x: &[f64], alpha: f64, y: &mut [f64]) {
        match self.p {
            1 => self.mul_acc_p::<1>(x, alpha, y),
            3 => self.mul_acc_p::<3>(x, alpha, y),
            7 => self.mul_acc_p::<7>(x, alpha, y),
            _ => self.mul_acc_any(x, alpha, y),
        }
    }

    fn mul_acc_any(&self, x: &[f64], alpha: f64, y: &mut [f64]) {
        let (n, p) = (self.n, self.p);
        let w = 2 * p + 1;
        for i in 0..n {
            let lo = i.saturating_sub(p);
            let hi = (i + p).min(n - 1);
            let row = &self.data[i * w..(i + 1) * w];
            let mut acc = 0.0;
            for j in lo..=hi {
                acc += row[j + p - i] * x[j];
            }
            y[i] += alpha * acc;
        }
    }

    fn mul_acc_p<const P: usize>(&self, x: &[f64], alpha: f64, y: &mut [f64]) {
        let n = self.n;
        if n <= 2 * P {
            return self.mul_acc_any(x, alpha, y);
        }
        let w = 2 * P + 1;
        // edges with bounds, interior without
        for i in (0..P).chain(n - P..n) {
            let lo = i.saturating_sub(P);
            let hi = (i + P).min(n - 1);
            let mut acc = 0.0;
            for j in lo..=hi {
                acc += self.data[i * w + j + P - i] * x[j];
            }
            y[i] += alpha * acc;
        }
        for (i, row) in self.data.chunks_exact(w).enumerate().take(n - P).skip(P) {
            let xs = &x[i - P..i + P + 1];
            let mut acc = 0.0;
            for k in 0..w {
                acc += row[k] * xs[k];
            }
            y[i] += alpha * acc;
        }
    }
}

/// An affine column `h − K u` with K banded: what a time step's right-hand
/// side is made of (for generalized-α, h = f − α′ A a_n and u = ũ; the
/// algebra is in `integrate::gen_alpha`). [`BandedLdlt::solve_affine`]
/// computes it row by row inside its forward sweep; [`affine_into`] is the
/// same as a pass of its own.
#[derive(Debug, Clone, Copy)]
pub struct Affine<'a> {
    /// h.
    pub h: &'a [f64],
    /// The banded matrix K.
    pub k: &'a SymBand,
    /// u.
    pub u: &'a [f64],
}

impl Affine<'_> {
    /// Row i with bounds (edge rows and small meshes).
    fn row_any(&self, i: usize) -> f64 {
        self.row_any_lane(i, 1, 0)
    }

    /// Row i of lane `lane` when h and u hold `lanes` runs interleaved
    /// (`h[i·lanes + lane]`): the same operations, in the same order, as
    /// [`Affine::row_any`] on that run alone.
    #[inline(always)]
    fn row_any_lane(&self, i: usize, lanes: usize, lane: usize) -> f64 {
        let (n, p) = (self.k.n, self.k.p);
        let mut acc = self.h[i * lanes + lane];
        for j in i.saturating_sub(p)..=(i + p).min(n - 1) {
            acc -= self.k.get(i, j) * self.u[j * lanes + lane];
        }
        acc
    }

    /// [`Affine::band_sum`] of L interleaved runs (`uu[j·L + l]`): each
    /// lane summed in exactly the single run's order, so a batched run's
    /// residual has the same bits as the run alone; across lanes the sums
    /// are independent, which is what vectorizes.
    #[inline(always)]
    fn band_sum_lanes<const P: usize, const L: usize>(kr: &[f64], uu: &[f64]) -> [f64; L] {
        let kr = &kr[..2 * P + 1];
        // fixed-size rows of the window, so each lane operation is one
        // vector operation (slices of run-time length kept it scalar)
        let (rows, _) = uu[..(2 * P + 1) * L].as_chunks::<L>();
        let mut even = [0.0; L];
        let mut odd = [0.0; L];
        for q in 0..P {
            let (ke, ko) = (kr[2 * q], kr[2 * q + 1]);
            let (ue, uo) = (&rows[2 * q], &rows[2 * q + 1]);
            for r in 0..L {
                even[r] += ke * ue[r];
            }
            for r in 0..L {
                odd[r] += ko * uo[r];
            }
        }
        let (kl, last) = (kr[2 * P], &rows[2 * P]);
        core::array::from_fn(|r| (even[r] + kl * last[r]) + odd[r])
    }

    /// Row i for P ≤ i < n − P: the full band, no bounds in the inner loop.
    #[inline(always)]
    fn row_interior<const P: usize>(&self, i: usize) -> f64 {
        let w = 2 * P + 1;
        self.h[i] - Self::band_sum::<P>(&self.k.data[i * w..(i + 1) * w], &self.u[i - P..i + P + 1])
    }

    /// Σ_j K_ij ũ_j over one full band row (2P + 1 entries), summed in two
    /// lanes (even and odd j) that compile to one SIMD multiply–add per pair:
    /// half the instructions of a left-to-right sum, and half its depth,
    /// which is what the CPU must overlap with the sweep's chain.
    #[inline(always)]
    fn band_sum<const P: usize>(kr: &[f64], uu: &[f64]) -> f64 {
        let (kr, uu) = (&kr[..2 * P + 1], &uu[..2 * P + 1]);
        let mut lane = [0.0; 2];
        for q in 0..P {
            for l in 0..2 {
                lane[l] += kr[2 * q + l] * uu[2 * q + l];
            }
        }
        (lane[0] + kr[2 * P] * uu[2 * P]) + lane[1]
    }

    /// Row i, by the interior kernel where the fused sweep uses it (so the
    /// separate and the fused paths agree bit for bit).
    fn row(&self, i: usize) -> f64 {
        let n = self.k.n;
        let interior = |p: usize| n > 2 * p && i >= p && i < n - p;
        match self.k.p {
            1 if interior(1) => self.row_interior::<1>(i),
            3 if interior(3) => self.row_interior::<3>(i),
            7 if interior(7) => self.row_interior::<7>(i),
            _ => self.row_any(i),
        }
    }
}

/// The affine column as a pass of its own: `out[i·stride] = (h − K u)_i` and
/// the other `stride − 1` columns of row i zeroed (the reference for the
/// fused sweep, and the "before" of `examples/step_profile.rs`).
pub fn affine_into(r: &Affine, out: &mut [f64], stride: usize) {
    assert_eq!(out.len(), r.k.n * stride, "output has the wrong length");
    for (i, row) in out.chunks_exact_mut(stride).enumerate() {
        row.fill(0.0);
        row[0] = r.row(i);
    }
}

/// LDLᵀ factorization of a symmetric positive definite banded matrix.
///
/// L is unit lower triangular with the same band; stored twice (by rows for
/// the forward sweep, by columns for the backward sweep) so both sweeps read
/// memory in order.
#[derive(Debug, Clone)]
pub struct BandedLdlt {
    n: usize,
    p: usize,
    /// Row i: L[i, i−p .. i] (p entries; zeros before row 0).
    rows: Vec<f64>,
    /// Row i: L[i+1 ..= i+p, i] (p entries; zeros past row n−1).
    cols: Vec<f64>,
    /// 1 / D[i].
    dinv: Vec<f64>,
}

impl BandedLdlt {
    /// Factor A = L D Lᵀ. Fails if A is not positive definite (a pivot ≤ 0).
    pub fn factor(a: &SymBand) -> Result<Self> {
        let (n, p) = (a.n, a.p);
        let mut rows = vec![0.0; n * p];
        let mut d = vec![0.0; n];
        for i in 0..n {
            // L[i, j] for j in i−p .. i
            for j in i.saturating_sub(p)..i {
                let mut s = a.get(i, j);
                for k in i.saturating_sub(p)..j {
                    // L[i,k] D[k] L[j,k], with k within j's band too
                    if j - k <= p {
                        s -= rows[i * p + (k + p - i)] * d[k] * rows[j * p + (k + p - j)];
                    }
                }
                rows[i * p + (j + p - i)] = s / d[j];
            }
            let mut s = a.get(i, i);
            for k in i.saturating_sub(p)..i {
                let l = rows[i * p + (k + p - i)];
                s -= l * l * d[k];
            }
            if s.is_nan() || s <= 0.0 {
                return Err(Error::invalid(
                    "model",
                    format!("pivot {i} = {s:e}"),
                    "the effective matrix A = (1−α_m)M + (1−α_f)βΔt²K must be positive definite: check the mass and stiffness values",
                ));
            }
            d[i] = s;
        }
        let mut cols = vec![0.0; n * p];
        for i in 0..n {
            for k in 1..=p {
                if i + k < n {
                    cols[i * p + (k - 1)] = rows[(i + k) * p + (i + p - (i + k))];
                }
            }
        }
        Ok(BandedLdlt {
            n,
            p,
            rows,
            cols,
            dinv: d.iter().map(|x| 1.0 / x).collect(),
        })
    }

    /// Dimension n.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Solve A X = B in place for `k` right-hand sides stored row-major:
    /// `x[i * k + j]` is row i of column j. One fused sweep serves all columns.
    pub fn solve_many(&self, x: &mut [f64], k: usize) {
        self.dispatch(x, k, None)
    }

    /// Solve A X = B + F e₀ᵀ in place: as [`BandedLdlt::solve_many`], with
    /// the affine column F = h − K u of `r` added to column 0 of B; `b0`
    /// receives that column (B e₀ + F, before the solve), from which
    /// generalized-α forms the next step's A a_{n+1}. F is computed inside
    /// the forward sweep: that sweep is bound by its dependency chain (row i
    /// waits for row i − 1), which leaves the CPU's arithmetic units mostly
    /// idle, and F's independent row sums fill them, so most of the pass over
    /// K and u that F costs on its own is hidden.
    pub fn solve_affine(&self, x: &mut [f64], k: usize, r: &Affine, b0: &mut [f64]) {
        assert_eq!((r.k.n, r.k.p), (self.n, self.p));
        assert_eq!(b0.len(), self.n, "b0 has the wrong length");
        self.dispatch(x, k, Some((r, b0)))
    }

    /// Solve A x = b in place for one right-hand side.
    pub fn solve(&self, x: &mut [f64]) {
        self.solve_many(x, 1)
    }

    /// Solve L runs' systems at once, their columns side by side in one
    /// sweep (batched stepping): `x` holds n rows of `k·lanes` columns,
    /// column c of run l at `c·lanes + l`; the affine column of run l
    /// (`r.h`, `r.u` interleaved, `h[i·lanes + l]`) is added to its column 0,
    /// and `b0[i·lanes + l]` receives it. Every column gets exactly the
    /// operations the run alone would get from [`BandedLdlt::solve_affine`]
    /// with `k` columns (the same kernel, more columns), so a batched run is
    /// bit-identical to the run alone. Returns false, touching nothing,
    /// when no kernel is compiled for this (band, k, lanes) — the caller
    /// then steps its runs alone.
    pub fn solve_affine_lanes(
        &self,
        x: &mut [f64],
        k: usize,
        lanes: usize,
        r: &Affine,
        b0: &mut [f64],
    ) -> bool {
        assert_eq!((r.k.n, r.k.p), (self.n, self.p));
        assert_eq!(
            x.len(),
            self.n * k * lanes,
            "right-hand side has the wrong length"
        );
        assert_eq!(b0.len(), self.n * lanes, "b0 has the wrong length");
        assert_eq!(r.h.len(), self.n * lanes, "h has the wrong length");
        let r = Some((r, b0));
        macro_rules! lanes {
            ($($p:literal, $k:literal, $kl:literal, $l:literal);*) => {
                match (self.p, k, lanes) {
                    $(($p, $k, $l) => self.lanes_kernel::<$p, $kl, $l>(x, r),)*
                    _ => return false,
                }
            };
        }
        lanes!(3, 2, 4, 2; 3, 2, 6, 3; 3, 2, 8, 4; 3, 2, 10, 5; 3, 2, 12, 6; 3, 2, 14, 7;
               3, 2, 16, 8; 3, 4, 8, 2; 3, 4, 12, 3; 3, 4, 16, 4;
               1, 2, 4, 2; 1, 2, 6, 3; 1, 2, 8, 4; 1, 2, 10, 5; 1, 2, 12, 6; 1, 2, 14, 7;
               1, 2, 16, 8; 1, 4, 8, 2; 1, 4, 12, 3; 1, 4, 16, 4);
        true
    }

    /// The batched sweep, with AVX2 where the CPU has it (found at run
    /// time; four lanes per vector instead of SSE2's two) and the portable
    /// path otherwise. Both round alike: the same IEEE operations in the same
    /// order, and no fused multiply–add (Rust never contracts `a·b + c`, and
    /// the `fma` feature is not enabled).
    #[inline(always)]
    fn lanes_kernel<const P: usize, const K: usize, const L: usize>(
        &self,
        x: &mut [f64],
        r: Option<(&Affine, &mut [f64])>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above).
            unsafe { self.solve_kernel_avx2::<P, K, L>(x, r) };
            return;
        }
        self.solve_kernel::<P, K, L>(x, r)
    }

    /// [`BandedLdlt::solve_kernel`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_kernel_avx2<const P: usize, const K: usize, const L: usize>(
        &self,
        x: &mut [f64],
        r: Option<(&Affine, &mut [f64])>,
    ) {
        self.solve_kernel::<P, K, L>(x, r)
    }

    /// True when [`BandedLdlt::solve_affine_lanes`] has a kernel for `k`
    /// columns per run and `lanes` runs on this band.
    pub fn has_lanes(&self, k: usize, lanes: usize) -> bool {
        matches!((self.p, k, lanes), (3 | 1, 2, 2..=8) | (3 | 1, 4, 2..=4)) && self.n > 0
    }

    fn dispatch(&self, x: &mut [f64], k: usize, r: Option<(&Affine, &mut [f64])>) {
        assert_eq!(x.len(), self.n * k, "right-hand side has the wrong length");
        macro_rules! dispatch {
            ($($p:literal, $k:literal);*) => {
                match (self.p, k) {
                    $(($p, $k) => self.solve_kernel::<$p, $k, 1>(x, r),)*
                    _ => {
                        if let Some((r, b0)) = r {
                            for (i, row) in x.chunks_exact_mut(k).enumerate() {
                                row[0] += r.row(i);
                                b0[i] = row[0];
                            }
                        }
                        self.solve_generic(x, k)
                    }
                }
            };
        }
        dispatch!(3, 1; 3, 2; 3, 3; 3, 4; 3, 6; 1, 1; 1, 2; 1, 3; 1, 4; 1, 6;
                  7, 1; 7, 2; 7, 4; 7, 6)
    }

    /// One elimination row: `acc − Σ_k row[k] win[k]`, oldest row first so the
    /// newest (the end of the dependency chain) enters last, one multiply and
    /// one subtract after it is known.
    #[inline(always)]
    fn eliminate<const P: usize, const K: usize>(
        row: &[f64],
        win: &[[f64; K]; P],
        mut acc: [f64; K],
    ) -> [f64; K] {
        for kk in 0..P {
            for c in 0..K {
                acc[c] -= row[kk] * win[kk][c];
            }
        }
        acc
    }

    /// The sweep for K columns; with L > 1 the columns are L runs' (column
    /// c of run l at c·L + l) and the affine column of run l goes to column
    /// l ([`BandedLdlt::solve_affine_lanes`]).
    #[inline(always)]
    fn solve_kernel<const P: usize, const K: usize, const L: usize>(
        &self,
        x: &mut [f64],
        r: Option<(&Affine, &mut [f64])>,
    ) {
        let n = self.n;
        let (x, _) = x.as_chunks_mut::<K>();
        // rows whose residual is computed inside the sweep: P .. n − P; the
        // others (the edges, or all rows of a tiny mesh) get theirs here
        let inside = if n > 2 * P { P..n - P } else { 0..0 };
        let fused = match r {
            Some((r, b0)) => {
                let edges = (0..inside.start.min(n)).chain(inside.end.max(inside.start)..n);
                for i in edges.filter(|&i| !inside.contains(&i)) {
                    for l in 0..L {
                        x[i][l] += r.row_any_lane(i, L, l);
                        b0[i * L + l] = x[i][l];
                    }
                }
                (!inside.is_empty()).then_some((r, b0))
            }
            None => None,
        };
        // forward: y_i = b_i − Σ_k L[i, i−k] y_{i−k}
        for i in 1..n.min(P) {
            let row = &self.rows[i * P..(i + 1) * P];
            for kk in (P - i)..P {
                let j = i + kk - P;
                let l = row[kk];
                let xj = x[j];
                for c in 0..K {
                    x[i][c] -= l * xj[c];
                }
            }
            x[i] = drop_negligible(x[i]);
        }
        // The sliding window of the last P solved rows lives in registers: were
        // it re-read from `x`, every row would wait on a store-to-load
        // forwarding of the previous row (measured: the sweeps ran 2.2× slower).
        // The loops run on zipped iterators so that no row pays bounds checks
        // (the fused row is ≈ 40 instructions; checks and reloads had made it 72).
        if n >= P {
            let mut win: [[f64; K]; P] = core::array::from_fn(|j| x[j]);
            let split = if fused.is_some() { inside.end } else { P };
            let (lanes, single) = if L > 1 { (fused, None) } else { (None, fused) };
            if let Some((r, b0)) = lanes {
                // L runs side by side: their residuals vectorize across lanes
                let w = 2 * P + 1;
                let rows = self.rows[P * P..split * P].chunks_exact(P);
                let kband = r.k.data[P * w..split * w].chunks_exact(w);
                for (i, (row, kr)) in (P..split).zip(rows.zip(kband)) {
                    let f = Affine::band_sum_lanes::<P, L>(kr, &r.u[(i - P) * L..(i + P + 1) * L]);
                    let mut acc = x[i];
                    let (h, b) = (&r.h[i * L..(i + 1) * L], &mut b0[i * L..(i + 1) * L]);
                    for l in 0..L {
                        acc[l] += h[l] - f[l];
                    }
                    b.copy_from_slice(&acc[..L]);
                    let acc = drop_negligible(Self::eliminate(row, &win, acc));
                    x[i] = acc;
                    win = core::array::from_fn(|j| if j + 1 < P { win[j + 1] } else { acc });
                }
            } else if let Some((r, b0)) = single {
                let w = 2 * P + 1;
                let rows = self.rows[P * P..split * P].chunks_exact(P);
                let kband = r.k.data[P * w..split * w].chunks_exact(w);
                let operands = kband.zip(r.u.windows(w)).zip(&r.h[P..split]);
                let out = x[P..split].iter_mut().zip(&mut b0[P..split]);
                for ((xi, b), (row, ((kr, uu), h))) in out.zip(rows.zip(operands)) {
                    let mut acc = *xi;
                    acc[0] += h - Affine::band_sum::<P>(kr, uu);
                    *b = acc[0];
                    let acc = drop_negligible(Self::eliminate(row, &win, acc));
                    *xi = acc;
                    win = core::array::from_fn(|j| if j + 1 < P { win[j + 1] } else { acc });
                }
            }
            let rows = self.rows[split * P..].chunks_exact(P);
            for (xi, row) in x[split..].iter_mut().zip(rows) {
                let acc = drop_negligible(Self::eliminate(row, &win, *xi));
                *xi = acc;
                win = core::array::from_fn(|j| if j + 1 < P { win[j + 1] } else { acc });
            }
        }
        // backward with the diagonal folded in: x_i = y_i / D_i − Σ_k L[i+k, i] x_{i+k}
        let tail = n.saturating_sub(P);
        for i in (tail..n).rev() {
            let col = &self.cols[i * P..(i + 1) * P];
            let mut acc = x[i];
            for c in 0..K {
                acc[c] *= self.dinv[i];
            }
            for kk in (0..(n - 1 - i)).rev() {
                let xj = x[i + 1 + kk];
                for c in 0..K {
                    acc[c] -= col[kk] * xj[c];
                }
            }
            x[i] = drop_negligible(acc);
        }
        if n >= P {
            // win[k] = x_{i+1+k}; farthest row first, x_{i+1} last (as forward)
            let mut win: [[f64; K]; P] = core::array::from_fn(|j| x[tail + j]);
            let cols = self.cols[..tail * P].chunks_exact(P).rev();
            let rows = x[..tail]
                .iter_mut()
                .rev()
                .zip(self.dinv[..tail].iter().rev());
            for ((xi, &d), col) in rows.zip(cols) {
                let mut acc = *xi;
                for c in 0..K {
                    acc[c] *= d;
                }
                for kk in (0..P).rev() {
                    for c in 0..K {
                        acc[c] -= col[kk] * win[kk][c];
                    }
                }
                let acc = drop_negligible(acc);
                *xi = acc;
                win = core::array::from_fn(|j| if j == 0 { acc } else { win[j - 1] });
            }
        }
    }

    fn solve_generic(&self, x: &mut [f64], k: usize) {
        let (n, p) = (self.n, self.p);
        for i in 0..n {
            for j in i.saturating_sub(p)..i {
                let l = self.rows[i * p + (j + p - i)];
                for c in 0..k {
                    x[i * k + c] -= l * x[j * k + c];
                }
            }
        }
        for i in 0..n {
            for c in 0..k {
                x[i * k + c] *= self.dinv[i];
            }
        }
        for i in (0..n).rev() {
            for kk in 1..=p {
                if i + kk < n {
                    let l = self.cols[i * p + (kk - 1)];
                    for c in 0..k {
                        x[i * k + c] -= l * x[(i + kk) * k + c];
                    }
                }
            }
            for v in &mut x[i * k..(i + 1) * k] {
                if v.abs() < NEGLIGIBLE {
                    *v = 0.0;
                }
            }
        }
    }
}

/// Magnitudes below this that a sweep produces are replaced by exactly 0
/// (module docs, "Subnormals"). 1e-200 is 108 orders of magnitude above the
/// subnormal range (below 2.2e-308), so a decaying tail is cut long before it
/// gets there; and a value this small changes nothing it is added to: every
/// quantity a run computes (in SI units, m, m/s, m/s², N) is of interest
/// above 1e-30 or so, where one rounding is already ≥ 1e-46, 150 orders above
/// what is dropped.
pub(crate) const NEGLIGIBLE: f64 = 1e-200;

/// A sweep's new row with each value below [`NEGLIGIBLE`] in magnitude set
/// to 0 (module docs, "Subnormals"). Each value is judged alone, so a run's
/// columns are treated alike whatever other runs share the sweep (batched
/// lanes stay bit-identical to the run alone). The test is off the sweep's
/// dependency chain: it feeds a branch that is taken only on the few rows
/// where a tail first drops below the threshold (after them the rows are
/// exact zeros, which do not take it), so the chain waits for it only there.
#[inline(always)]
fn drop_negligible<const K: usize>(acc: [f64; K]) -> [f64; K] {
    let mut tiny = false;
    for a in acc {
        let m = a.abs();
        tiny |= (m < NEGLIGIBLE) & (m > 0.0);
    }
    if tiny { zero_negligible(acc) } else { acc }
}

/// The rare branch of [`drop_negligible`], kept out of line so that the
/// compiler keeps it a branch (a select would sit on the chain every row).
#[cold]
#[inline(never)]
fn zero_negligible<const K: usize>(acc: [f64; K]) -> [f64; K] {
    acc.map(|a| if a.abs() < NEGLIGIBLE { 0.0 } else { a })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// Residual bound for a well-conditioned SPD solve: n·ε scaled by ‖A‖‖x‖.
    fn residual_tol(n: usize) -> f64 {
        64.0 * n as f64 * f64::EPSILON
    }

    /// A deterministic SPD banded matrix (diagonally dominant).
    fn sample(n: usize, p: usize) -> SymBand {
        let mut a = SymBand::zeros(n, p);
        for i in 0..n {
            a.add_entry(i, i, 10.0 + (i % 7) as f64);
            for k in 1..=p {
                if i + k < n {
                    let v = ((i * 31 + k * 17) % 11) as f64 / 11.0 - 0.5;
                    a.add_entry(i, i + k, v);
                    a.add_entry(i + k, i, v);
                }
            }
        }
        a
    }

    fn dense(a: &SymBand) -> DMatrix<f64> {
        DMatrix::from_fn(a.n(), a.n(), |i, j| a.get(i, j))
    }

    #[test]
    fn fused_solves_match_dense_cholesky() {
        for &(n, p) in &[
            (1, 1),
            (2, 3),
            (5, 3),
            (40, 3),
            (40, 1),
            (17, 2),
            (40, 7),
            (9, 7),
        ] {
            let a = sample(n, p);
            let f = BandedLdlt::factor(&a).unwrap();
            let ad = dense(&a);
            let chol = ad.clone().cholesky().unwrap();
            for k in 1..=7 {
                let b: Vec<f64> = (0..n * k).map(|i| ((i * 13) % 7) as f64 - 3.0).collect();
                let mut x = b.clone();
                f.solve_many(&mut x, k);
                for c in 0..k {
                    let bc = DVector::from_fn(n, |i, _| b[i * k + c]);
                    let xc = DVector::from_fn(n, |i, _| x[i * k + c]);
                    let xref = chol.solve(&bc);
                    let r = (&ad * &xc - &bc).norm();
                    assert!(
                        r <= residual_tol(n) * ad.norm() * xc.norm().max(1.0),
                        "n={n} p={p} k={k} r={r}"
                    );
                    assert!((xc - xref).norm() <= residual_tol(n) * 100.0 * (1.0 + bc.norm()));
                }
            }
        }
    }

    #[test]
    fn matvec_matches_dense() {
        for &(n, p) in &[(3, 3), (9, 3), (30, 3), (30, 1), (12, 2), (30, 7)] {
            let a = sample(n, p);
            let x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
            let mut y = vec![1.0; n];
            a.mul_acc(&x, -2.0, &mut y);
            let yref = DVector::from_element(n, 1.0) - 2.0 * dense(&a) * DVector::from_vec(x);
            for i in 0..n {
                assert!((y[i] - yref[i]).abs() < 1e-13 * (1.0 + yref[i].abs()));
            }
        }
    }

    #[test]
    fn residual_is_h_minus_k_u() {
        for &(n, p, stride) in &[(4, 3, 2), (30, 3, 3), (30, 1, 1), (12, 2, 2)] {
            let k = sample(n, p).combine(2.0, &sample(n, p), -0.5);
            let h: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
            let u: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + i as f64)).collect();
            let mut expect = h.clone();
            k.mul_acc(&u, -1.0, &mut expect);
            let mut out = vec![7.0; n * stride];
            affine_into(
                &Affine {
                    h: &h,
                    k: &k,
                    u: &u,
                },
                &mut out,
                stride,
            );
            for i in 0..n {
                assert!((out[i * stride] - expect[i]).abs() < 1e-13 * (1.0 + expect[i].abs()));
                assert!(
                    out[i * stride + 1..(i + 1) * stride]
                        .iter()
                        .all(|&v| v == 0.0)
                );
            }
        }
    }

    #[test]
    fn fused_residual_solve_equals_residual_then_solve_bit_for_bit() {
        // p = 3 and 1 take the fused kernels (interior rows inside the sweep),
        // p = 2, k = 5 and k = 7 the generic path; n ≤ 2p has no interior rows, and
        // n < p (a one-element clamped–pinned beam) not even a full window
        for &(n, p) in &[
            (40, 7),
            (15, 7),
            (5, 7),
            (1, 3),
            (2, 3),
            (1, 1),
            (3, 3),
            (6, 3),
            (7, 3),
            (40, 3),
            (2, 1),
            (3, 1),
            (40, 1),
            (17, 2),
        ] {
            let a = sample(n, p);
            let fac = BandedLdlt::factor(&a).unwrap();
            let kmat = sample(n, p).combine(2.0, &sample(n, p), -0.5);
            let h: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
            let u: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + i as f64)).collect();
            let r = Affine {
                h: &h,
                k: &kmat,
                u: &u,
            };
            for k in 1..=7 {
                // loads scattered into every column, as generalized-α's step does
                let scattered: Vec<f64> = (0..n * k)
                    .map(|i| {
                        if i % 3 == 0 {
                            (i as f64 * 0.3).sin()
                        } else {
                            0.0
                        }
                    })
                    .collect();
                let mut separate = vec![0.0; n * k];
                affine_into(&r, &mut separate, k);
                for (x, s) in separate.iter_mut().zip(&scattered) {
                    *x += s;
                }
                let b0_separate: Vec<f64> = separate.iter().step_by(k).copied().collect();
                fac.solve_many(&mut separate, k);
                let mut fused = scattered.clone();
                let mut b0 = vec![f64::NAN; n];
                fac.solve_affine(&mut fused, k, &r, &mut b0);
                assert_eq!(fused, separate, "n={n} p={p} k={k}");
                assert_eq!(b0, b0_separate, "n={n} p={p} k={k}");
            }
        }
    }

    #[test]
    fn decaying_tails_form_no_subnormals() {
        // a mass-like band (consistent linear-element mass h/6·[1 4 1]
        // with a small stiffness): its inverse decays ≈ 0.27 per row, so a
        // point load's solution falls below 1e-308 about 550 rows away
        let n = 4000;
        let mut a = SymBand::zeros(n, 3);
        for i in 0..n {
            a.add_entry(i, i, 4.0 + 1e-3);
            if i + 1 < n {
                a.add_entry(i, i + 1, 1.0);
                a.add_entry(i + 1, i, 1.0);
            }
        }
        let f = BandedLdlt::factor(&a).unwrap();
        for k in [1usize, 2, 4, 5] {
            let mut x = vec![0.0; n * k];
            for c in 0..k {
                x[(n / 2) * k + c] = 1.0 + c as f64;
            }
            let b = x.clone();
            f.solve_many(&mut x, k);
            assert_eq!(x.iter().filter(|v| v.is_subnormal()).count(), 0, "k={k}");
            // the tails were cut to exact zeros, not just above the range
            assert!(x[..k].iter().all(|&v| v == 0.0), "k={k}");
            // and what was cut is negligible: the residual is at round-off
            for c in 0..k {
                let xc: Vec<f64> = (0..n).map(|i| x[i * k + c]).collect();
                let mut r: Vec<f64> = (0..n).map(|i| -b[i * k + c]).collect();
                a.mul_acc(&xc, 1.0, &mut r);
                let rmax = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(
                    rmax <= residual_tol(n) * (1.0 + c as f64),
                    "k={k} c={c} r={rmax}"
                );
            }
        }
    }

    #[test]
    fn indefinite_matrix_is_rejected() {
        let mut a = SymBand::zeros(3, 1);
        a.add_entry(0, 0, 1.0);
        a.add_entry(1, 1, -1.0);
        a.add_entry(2, 2, 1.0);
        assert!(BandedLdlt::factor(&a).is_err());
    }
}
