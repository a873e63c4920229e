//! The J exact mode shapes at a moving point, without a transcendental call
//! per mode (MODEL §9.3): what `integrator.method = "modal_exact"`
//! evaluates every step, for every carrier, on a `galerkin` basis.
//!
//! [`super::ModeShapes::values_into`] costs one `sin_cos` (and, off
//! pinned–pinned, two `exp`) per mode, most of a modal step. Here the same
//! values come from one `sin_cos` per call and small tables built once per
//! basis (the phase table's rows on first use) and shared by every run on
//! it: the oscillating part
//! `C cos βs + D sin βs = Re[(C − iD) e^{iβs}]` by a rotation recurrence in
//! blocks of `BLOCK` modes (not the three-term recurrence, whose error grows
//! without bound near a support) times a table of slow phase shifts, and the
//! clamped ends' boundary layers `P e^{−αs}`, `Q e^{−α(L−s)}` from tables in
//! the distance to each end (both derived on [`FastShapes`]).
//!
//! The kernels round `a·b + c` once (AVX2 + FMA vectors, or
//! [`f64::mul_add`] lane by lane: the same bits, `crate::numeric::lanes`).
//! `FastShapes::blocks_at` hands the values out a block of `BLOCK` modes at
//! a time, with the very operations of the whole-vector kernels, for the
//! fused `modal_exact` step. Against the direct evaluation the values agree
//! to `FAST_SHAPES_AGREEMENT` of the amplitude `sqrt(2/(ρA L))` for every
//! support pair and J up to [`super::MAX_MODES`] (`tests`).

use super::mode_shapes::{Ends, ModeShapes};
use crate::numeric::lanes;
use std::cell::UnsafeCell;
use std::f64::consts::PI;
use std::sync::OnceLock;

#[cfg(target_arch = "x86_64")]
mod avx512;
#[cfg(target_arch = "x86_64")]
pub(crate) use avx512::BlocksAvx512;

/// Modes advanced together by the rotation recurrence ([`FastShapes`]): four
/// AVX2 vectors of independent chains, so the chain's latency is hidden,
/// and a chain of J/16 products.
pub(crate) const BLOCK: usize = 16;

/// Boundary-layer terms with `α_j d` at or above this are left out: they
/// are below `e^{−40} ≈ 4.2·10⁻¹⁸` of their coefficient.
pub(crate) const LAYER_CUT: f64 = 40.0;

/// Fast against direct evaluation, relative to the amplitude
/// `sqrt(2/(ρA L))`: measured worst 9.2·10⁻¹³ over the test cases up to
/// J = 1000, growing linearly in j (the recurrence's ~j/16 products and the
/// direct evaluation's own phase error `ε β_j L`, mode_shapes.rs), so
/// ~4·10⁻¹² at J = 4000 (measured on the reference span); 10⁻¹¹ leaves a
/// factor 2.5 there.
#[cfg(test)]
pub(crate) const FAST_SHAPES_AGREEMENT: f64 = 1e-11;

/// Table rows per radian of slow phase: `|ε_j δ| ≤ 1/64` ([`FastShapes`]).
const ROWS_PER_RADIAN: f64 = 32.0;

/// Half the boundary-layer row spacing times α_J: `|α_j δ| ≤ 1/2`.
const LAYER_OFFSET: f64 = 0.5;

/// Degree of the boundary layers' Taylor polynomial for `e^{−y}`, |y| ≤ 1/2.
const LAYER_DEGREE: usize = 15;

/// The J mode shapes of a [`ModeShapes`] basis, fast at any point (module
/// docs). Built once per basis; [`FastShapes::values_into`] allocates nothing.
///
/// ## The oscillating part: a rotation recurrence and a table of phase shifts
///
/// Every mode's oscillating part is `C cos βs + D sin βs = Re[(C − iD) e^{iβs}]`
/// in the stable form's coordinate `s` (`x`, or `L − x` for a mirrored
/// basis). Write `β_j L = jπ + ε_j`: `ε_j = 0` pinned–pinned, `ε_j ∈ [0, π/2)`
/// clamped–pinned, `[0, π)` clamped–clamped (mode numbering of
/// `mode_shapes.rs`). With `θ = πs/L` and `ξ = s/L`,
///
/// ```text
/// e^{iβ_j s} = e^{ijθ} · e^{iε_j ξ}.
/// ```
///
/// * `e^{ijθ}` for j = 1 … J by a **rotation recurrence** in blocks of
///   `BLOCK` modes: `e^{iθ}` from one `sin_cos`, the first block by
///   repeated squaring and products, then block b+1 = block b × `e^{iBθ}`
///   (a complex product per mode; the B chains are independent, so they
///   vectorize). Each product adds at most a few ulps, so mode j carries
///   about `2.2·(j/B + log₂B)·ε` relative error: linear growth, independent
///   of θ. The textbook three-term (Chebyshev) recurrence
///   `sin (j+1)θ = 2 cos θ sin jθ − sin (j−1)θ` is cheaper but amplifies
///   errors by up to `j/sin θ`, which is unbounded as the carrier nears a
///   support (θ → 0); `tests` measure both.
/// * `e^{iε_j ξ}`, a slow phase (at most π over the span), from a **table**
///   at `ξ_k = k/K` holding `(C_j − iD_j) e^{iε_j ξ_k}`, times
///   `e^{iε_j δ}`, `δ = ξ − ξ_k`, by its Taylor polynomial (cos to y⁶, sin
///   to y⁵). `K = ⌈32 max ε_j⌉` keeps `|ε_j δ| ≤ 1/64`, where the
///   remainders are below `(1/64)⁸/8! ≈ 2·10⁻¹⁹` and `(1/64)⁷/7! ≈
///   4.5·10⁻¹⁷`: the table's interpolation error is below round-off by
///   construction. (A coarser table with longer polynomials costs more per
///   step: the step reads one row, but evaluates the polynomial for every
///   mode.)
#[derive(Debug, Clone)]
pub struct FastShapes {
    length: f64,
    count: usize,
    /// Evaluate at `s = L − x` (pinned–clamped).
    mirrored: bool,
    oscillating: Oscillating,
    /// `P_j e^{−α_j s}` (the end at s = 0), when any P_j ≠ 0.
    left: Option<Layer>,
    /// `Q_j e^{−α_j (L − s)}` (the end at s = L), when any Q_j ≠ 0.
    right: Option<Layer>,
}

/// The oscillating part of every mode.
#[derive(Debug, Clone)]
enum Oscillating {
    /// Pinned–pinned: `d_j sin(jθ)`.
    Sine { d: Vec<f64> },
    /// `Re[(C_j − iD_j) e^{iε_j ξ} e^{ijθ}]` with the table of
    /// `(C_j − iD_j) e^{iε_j ξ_k}` at `ξ_k = k/K` ([`PhaseRows`]).
    Shifted {
        eps: Vec<f64>,
        rows: usize,
        table: PhaseRows,
    },
}

/// The table of `(C_j − iD_j) e^{iε_j ξ_k}`, `ξ_k = k/K`, k = 0 … K, real
/// and imaginary parts apart, each row made the first time it is read
/// ([`PhaseRows::row`]): a run reads only the rows near the points where
/// its shapes come from the tables (a boundary layer, a cruise's
/// restarts), so most of the K + 1 rows of J `sin_cos` each are never
/// made. A row holds the values the whole table held (the same
/// operations), whenever and on whichever thread it is made.
struct PhaseRows {
    count: usize,
    /// `C_j`, `D_j` and `ε_j` of each mode.
    c: Vec<f64>,
    d: Vec<f64>,
    eps: Vec<f64>,
    rows: usize,
    /// Row k's real parts at `k·J`, its imaginary parts at `(K + 1 + k)·J`;
    /// written once, under `made[k]`.
    cells: Box<[UnsafeCell<f64>]>,
    made: Vec<OnceLock<()>>,
}

// SAFETY: `cells` is written only inside `made[k].get_or_init` for row k
// (one writer, once), and read only through `PhaseRows::row`, after that
// row's `get_or_init` has returned (which orders the write before every
// read); rows are disjoint. So sharing across threads has no data race.
unsafe impl Sync for PhaseRows {}

impl PhaseRows {
    fn new(c: Vec<f64>, d: Vec<f64>, eps: Vec<f64>, rows: usize) -> Self {
        let count = c.len();
        PhaseRows {
            cells: (0..2 * (rows + 1) * count)
                .map(|_| UnsafeCell::new(0.0))
                .collect(),
            made: (0..=rows).map(|_| OnceLock::new()).collect(),
            count,
            c,
            d,
            eps,
            rows,
        }
    }

    /// Row k's real and imaginary parts (J each), made now if not yet.
    #[inline]
    fn row(&self, k: usize) -> (&[f64], &[f64]) {
        assert!(k <= self.rows, "a phase row within the table");
        let j = self.count;
        let base = UnsafeCell::raw_get(self.cells.as_ptr());
        let (at_re, at_im) = (k * j, (self.rows + 1 + k) * j);
        self.made[k].get_or_init(|| {
            // SAFETY: row k's cells lie within `cells`, and nothing else
            // reads or writes them until this returns (type docs).
            let (re, im) = unsafe {
                (
                    std::slice::from_raw_parts_mut(base.add(at_re), j),
                    std::slice::from_raw_parts_mut(base.add(at_im), j),
                )
            };
            self.make(k, re, im);
        });
        // SAFETY: row k is made (just above) and never written again.
        unsafe {
            (
                std::slice::from_raw_parts(base.add(at_re).cast_const(), j),
                std::slice::from_raw_parts(base.add(at_im).cast_const(), j),
            )
        }
    }

    /// Row k's values into `re` and `im`: `(C − iD)(cos + i sin)(ε_j ξ_k)`.
    /// Kept out of line, so that it rounds as it always did wherever it is
    /// first called from.
    #[inline(never)]
    fn make(&self, k: usize, re: &mut [f64], im: &mut [f64]) {
        let xi = k as f64 / self.rows as f64;
        for j in 0..self.count {
            let (s, c) = (self.eps[j] * xi).sin_cos();
            // (C − iD)(c + is)
            re[j] = self.c[j] * c + self.d[j] * s;
            im[j] = self.c[j] * s - self.d[j] * c;
        }
    }
}

impl Clone for PhaseRows {
    /// A table with the rows made so far.
    fn clone(&self) -> Self {
        let t = PhaseRows::new(self.c.clone(), self.d.clone(), self.eps.clone(), self.rows);
        for k in 0..=self.rows {
            if self.made[k].get().is_some() {
                let (re, im) = self.row(k);
                t.made[k].get_or_init(|| {
                    let (j, base) = (t.count, UnsafeCell::raw_get(t.cells.as_ptr()));
                    // SAFETY: row k of the new table, not yet shared.
                    unsafe {
                        std::slice::from_raw_parts_mut(base.add(k * j), j).copy_from_slice(re);
                        std::slice::from_raw_parts_mut(base.add((t.rows + 1 + k) * j), j)
                            .copy_from_slice(im);
                    }
                });
            }
        }
        t
    }
}

impl std::fmt::Debug for PhaseRows {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let made = self.made.iter().filter(|m| m.get().is_some()).count();
        f.debug_struct("PhaseRows")
            .field("count", &self.count)
            .field("rows", &(self.rows + 1))
            .field("made", &made)
            .finish()
    }
}

/// One end's boundary-layer terms `coef_j e^{−α_j d}` in the distance d to
/// that end, tabulated (`Layer`).
///
/// ## The boundary layers: tables in the distance to each end
///
/// The terms `P_j e^{−α_j s}` and `Q_j e^{−α_j (L − s)}` (clamped ends,
/// mode_shapes.rs) are tabulated in the distance `d` to their end at
/// spacing `Δ = 1/α_J`, times `e^{−α_j δ}` (`|α_j δ| ≤ 1/2`) by its Taylor
/// polynomial to degree 15 (remainder ≤ `e^{1/2}·0.5¹⁶/16! ≈ 1.2·10⁻¹⁸`).
/// A term with `α_j d ≥ LAYER_CUT` is below `e^{−40} ≈ 4·10⁻¹⁸` of its
/// coefficient (itself at most ~2 amplitudes) and is left out: since α_j
/// rises with j, row k keeps only the modes that count within half a row of
/// it, and rows stop at `d = 40/α_1`. On the reference span (αL ≥ 760)
/// the layer is 2.6 m wide at the clamped end and absent at the pinned one
/// (there `Q_j = −P_j e^{−α_j L}` underflows to 0).
#[derive(Debug, Clone)]
struct Layer {
    alpha: Vec<f64>,
    /// Row spacing Δ, m.
    spacing: f64,
    /// Row k's values `coef_j e^{−α_j kΔ}` for its first `starts[k+1] − starts[k]` modes.
    values: Vec<f64>,
    starts: Vec<usize>,
    /// `K + 1/2`, K the last row with a mode: a row applies at d exactly
    /// when `d/Δ < K + 1/2` ([`Layer::reaches`]).
    edge: f64,
}

impl Layer {
    /// The table for `coef_j e^{−α_j d}`, α ascending; `None` when every
    /// coefficient is 0.
    fn new(alpha: &[f64], coef: &[f64], length: f64) -> Option<Layer> {
        if coef.iter().all(|c| *c == 0.0) {
            return None;
        }
        let a_max = alpha.iter().copied().fold(0.0, f64::max);
        let a_min = alpha.iter().copied().fold(f64::INFINITY, f64::min);
        let spacing = 2.0 * LAYER_OFFSET / a_max;
        let reach = (LAYER_CUT / a_min).min(length);
        let rows = (reach / spacing).ceil() as usize + 1;
        let (mut values, mut starts) = (Vec::new(), vec![0]);
        for k in 0..rows {
            let d = k as f64 * spacing;
            // every mode that counts anywhere within half a row of d
            let near = (d - 0.5 * spacing).max(0.0);
            let m = alpha.iter().take_while(|a| **a * near < LAYER_CUT).count();
            values.extend((0..m).map(|j| coef[j] * (-alpha[j] * d).exp()));
            starts.push(values.len());
        }
        // rows shorten as d grows (α ascending): the last one with a mode
        let last = (0..rows)
            .rev()
            .find(|&k| starts[k + 1] > starts[k])
            .unwrap_or(0);
        Some(Layer {
            alpha: alpha.to_vec(),
            spacing,
            values,
            starts,
            edge: last as f64 + 0.5,
        })
    }

    /// True when a row with a mode applies at `d ≥ 0`: `modes_at(d) > 0`
    /// without its `round` (a library call, not an instruction, on
    /// x86-64), for the test every cruise step makes
    /// ([`FastShapes::in_layer`]). Rows shorten as d grows, so a row with
    /// a mode applies exactly when `round(d/Δ) ≤ K`, K the last such row,
    /// that is (`round` takes halves away from zero) when `d/Δ < K + 1/2`:
    /// the same quotient, so the same answer.
    #[inline(always)]
    fn reaches(&self, d: f64) -> bool {
        d / self.spacing < self.edge
    }

    /// How many modes [`Layer::add_into`] adds to at `d` (the length of
    /// the row that applies there; 0 beyond the last row).
    #[inline(always)]
    fn modes_at(&self, d: f64) -> usize {
        let k = (d / self.spacing).round() as usize;
        if k + 1 < self.starts.len() {
            self.starts[k + 1] - self.starts[k]
        } else {
            0
        }
    }

    /// The row that applies at `d`, its modes' α (the same length) and
    /// `δ = d − kΔ`; `None` beyond the last row.
    #[inline(always)]
    fn row_at(&self, d: f64) -> Option<(&[f64], &[f64], f64)> {
        let k = (d / self.spacing).round() as usize;
        if k + 1 >= self.starts.len() {
            return None;
        }
        let delta = d - k as f64 * self.spacing;
        let row = &self.values[self.starts[k]..self.starts[k + 1]];
        Some((row, &self.alpha[..row.len()], delta))
    }

    /// Add `coef_j e^{−α_j d}` into `out` for the modes that count at `d`
    /// (AVX2 + FMA where the CPU has them: the same fused operations, the
    /// same bits; `crate::numeric::lanes`).
    #[inline(always)]
    fn add_into(&self, d: f64, out: &mut [f64], vector: bool) {
        let Some((row, alpha, delta)) = self.row_at(d) else {
            return;
        };
        let out = &mut out[..row.len()];
        let mut done = 0;
        #[cfg(target_arch = "x86_64")]
        if vector {
            // SAFETY: the caller checked AVX2 and FMA (lanes::avx2_fma).
            done = unsafe { layer_avx2(row, alpha, delta, out) };
        }
        for i in done..row.len() {
            out[i] = row[i].mul_add(exp_minus(alpha[i] * delta), out[i]);
        }
    }
}

/// `1/k!`, k = 0 … [`LAYER_DEGREE`].
const INV_FACT: [f64; LAYER_DEGREE + 1] = {
    let mut f = [1.0; LAYER_DEGREE + 1];
    let mut k = 1;
    while k <= LAYER_DEGREE {
        f[k] = f[k - 1] / k as f64;
        k += 1;
    }
    f
};

/// `e^{−y}` for `|y| ≤ 1/2` by its Taylor polynomial of degree
/// [`LAYER_DEGREE`] (Horner, fused).
#[inline(always)]
fn exp_minus(y: f64) -> f64 {
    let z = -y;
    let mut acc = INV_FACT[LAYER_DEGREE];
    for k in (0..LAYER_DEGREE).rev() {
        acc = acc.mul_add(z, INV_FACT[k]);
    }
    acc
}

/// [`Layer::add_into`] four modes at a time, as many as fill whole
/// vectors; returns how many it did.
///
/// # Safety
/// The CPU supports AVX2 and FMA; the three slices have equal lengths.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn layer_avx2(row: &[f64], alpha: &[f64], delta: f64, out: &mut [f64]) -> usize {
    use std::arch::x86_64::*;
    let full = row.len() / 4 * 4;
    let minus_delta = _mm256_set1_pd(-delta);
    let mut i = 0;
    while i < full {
        // SAFETY: i + 4 ≤ full ≤ the slices' length.
        unsafe {
            // z = −(α δ): the scalar path's −y with y = α·δ rounds the same
            let z = _mm256_mul_pd(_mm256_loadu_pd(alpha.as_ptr().add(i)), minus_delta);
            let mut acc = _mm256_set1_pd(INV_FACT[LAYER_DEGREE]);
            for k in (0..LAYER_DEGREE).rev() {
                acc = _mm256_fmadd_pd(acc, z, _mm256_set1_pd(INV_FACT[k]));
            }
            let o = out.as_mut_ptr().add(i);
            _mm256_storeu_pd(
                o,
                _mm256_fmadd_pd(
                    _mm256_loadu_pd(row.as_ptr().add(i)),
                    acc,
                    _mm256_loadu_pd(o),
                ),
            );
        }
        i += 4;
    }
    full
}

/// Taylor coefficients of cos y (y², y⁴, y⁶) and sin y / y (y², y⁴).
const COS: [f64; 3] = [-0.5, 1.0 / 24.0, -1.0 / 720.0];
const SIN: [f64; 2] = [-1.0 / 6.0, 1.0 / 120.0];

/// `(sin y, cos y)` for `|y| ≤ 1/64` (cos to y⁶, sin to y⁵; [`FastShapes`]),
/// fused.
#[inline(always)]
fn small_sin_cos(y: f64) -> (f64, f64) {
    let y2 = y * y;
    let c = y2.mul_add(y2.mul_add(y2.mul_add(COS[2], COS[1]), COS[0]), 1.0);
    let s = y * y2.mul_add(y2.mul_add(SIN[1], SIN[0]), 1.0);
    (s, c)
}

/// One mode's shifted oscillating part: `Re[T e^{iy} R]` with
/// `T = tr + i·ti`, `R = rr + i·ri`, `y = ε δ` ([`FastShapes`]), fused.
#[inline(always)]
fn shifted(e: f64, delta: f64, t: (f64, f64), (rr, ri): (f64, f64)) -> f64 {
    let (zr, zi) = shifted_row(e, delta, t);
    zr.mul_add(rr, -(zi * ri))
}

/// `z = T e^{iy}`, `y = ε δ`: a table entry carried to the point (the
/// first half of [`shifted`]), fused.
#[inline(always)]
fn shifted_row(e: f64, delta: f64, (tr, ti): (f64, f64)) -> (f64, f64) {
    let (sy, cy) = small_sin_cos(e * delta);
    (tr.mul_add(cy, -(ti * sy)), tr.mul_add(sy, ti * cy))
}

/// `e^{ijθ}` for j = 1 … B (the first block) and `e^{iBθ}`, from `e^{iθ}`
/// by squaring and products (log₂B levels).
#[inline(always)]
fn first_block(theta: f64) -> ([f64; BLOCK], [f64; BLOCK], (f64, f64)) {
    let (s1, c1) = theta.sin_cos();
    let (mut re, mut im) = ([0.0; BLOCK], [0.0; BLOCK]);
    re[0] = c1;
    im[0] = s1;
    let mut have = 1;
    while have < BLOCK {
        // modes have+1 … 2·have from modes 1 … have times e^{i·have·θ}
        let (cr, ci) = (re[have - 1], im[have - 1]);
        for j in 0..have {
            (re[have + j], im[have + j]) = rotate((re[j], im[j]), (cr, ci));
        }
        have *= 2;
    }
    let rot = (re[BLOCK - 1], im[BLOCK - 1]);
    (re, im, rot)
}

impl FastShapes {
    /// The fast evaluator of a basis (tables built here, once).
    pub fn new(shapes: &ModeShapes) -> Self {
        let (ends, modes) = shapes.parts();
        let length = shapes.length();
        let count = modes.len();
        let mirrored = ends == Ends::PinnedClamped;
        let oscillating = if ends == Ends::PinnedPinned {
            Oscillating::Sine {
                d: modes.iter().map(|m| m.d).collect(),
            }
        } else {
            let eps: Vec<f64> = modes
                .iter()
                .enumerate()
                .map(|(i, m)| m.beta * length - (i + 1) as f64 * PI)
                .collect();
            let eps_max = eps.iter().fold(0.0f64, |a, e| a.max(e.abs()));
            let rows = (ROWS_PER_RADIAN * eps_max).ceil().max(1.0) as usize;
            let (c, d) = modes.iter().map(|m| (m.c, m.d)).unzip();
            let table = PhaseRows::new(c, d, eps.clone(), rows);
            Oscillating::Shifted { eps, rows, table }
        };
        let alpha: Vec<f64> = modes.iter().map(|m| m.alpha).collect();
        let (p, q): (Vec<f64>, Vec<f64>) = modes.iter().map(|m| (m.p, m.q)).unzip();
        let layers = ends != Ends::PinnedPinned;
        FastShapes {
            length,
            count,
            mirrored,
            oscillating,
            left: layers.then(|| Layer::new(&alpha, &p, length)).flatten(),
            right: layers.then(|| Layer::new(&alpha, &q, length)).flatten(),
        }
    }

    /// J, the number of modes.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Bytes of the tables (what a basis shared across runs saves each run).
    pub fn table_bytes(&self) -> usize {
        let osc = match &self.oscillating {
            Oscillating::Sine { d } => d.len(),
            Oscillating::Shifted { eps, table, .. } => eps.len() + table.cells.len(),
        };
        let layer = |l: &Option<Layer>| l.as_ref().map_or(0, |l| l.values.len() + l.alpha.len());
        8 * (osc + layer(&self.left) + layer(&self.right))
    }

    /// True when a boundary-layer term counts at `x` (some layer row
    /// applies there), or `x` is off the span: there `φ_j(x)` is not the
    /// real part of the phasor alone ([`FastShapes::phasor_im_into`]).
    pub fn in_layer(&self, x: f64) -> bool {
        if !(0.0..=self.length).contains(&x) {
            return true;
        }
        let s = if self.mirrored { self.length - x } else { x };
        let left = self.left.as_ref().is_some_and(|l| l.reaches(s));
        let right = self
            .right
            .as_ref()
            .is_some_and(|r| r.reaches(self.length - s));
        left || right
    }

    /// The imaginary parts of the phasors `F_j(x) = (C_j − iD_j) e^{iβ_j s}`
    /// (kg^{−1/2}), whose real parts are the oscillating parts of
    /// `φ_j(x)` ([`FastShapes`]), into `im` (length J): the same table row,
    /// slow-phase polynomial and rotation recurrence as
    /// [`FastShapes::values_into`] (scalar), taking `Im[z R]` where it takes
    /// `Re[z R]`. Outside the boundary layers `φ_j = Re F_j`, and a carrier
    /// moving at constant speed advances `F_j` by the fixed rotation
    /// [`FastShapes::rotations_into`] each step (`modal_exact`'s cruise).
    pub fn phasor_im_into(&self, x: f64, im: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if lanes::avx2_fma() {
            // SAFETY: the CPU has AVX2 and FMA (checked just above).
            unsafe { self.phasor_im_fma(x, im) };
            return;
        }
        self.phasor_im_kernel(x, im)
    }

    /// [`FastShapes::phasor_im_into`] compiled for FMA, so that
    /// `f64::mul_add` is the instruction, not its software emulation (the
    /// same bits).
    ///
    /// # Safety
    /// The CPU supports AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn phasor_im_fma(&self, x: f64, im: &mut [f64]) {
        self.phasor_im_kernel(x, im)
    }

    #[inline(always)]
    fn phasor_im_kernel(&self, x: f64, im: &mut [f64]) {
        assert_eq!(im.len(), self.count, "one slot per mode");
        let x = x.clamp(0.0, self.length);
        let s = if self.mirrored { self.length - x } else { x };
        let xi = s / self.length;
        let (mut rr, mut ri, rot) = first_block(PI * xi);
        let j = self.count;
        // Im[z_j R_j] with z_j = T_j e^{iε_j δ} (= −i d_j pinned–pinned)
        match &self.oscillating {
            Oscillating::Sine { d } => {
                for at in (0..j).step_by(BLOCK) {
                    for l in 0..BLOCK.min(j - at) {
                        im[at + l] = -d[at + l] * rr[l];
                    }
                    advance(&mut rr, &mut ri, rot);
                }
            }
            Oscillating::Shifted { eps, rows, table } => {
                let k = (xi * *rows as f64).round() as usize;
                let delta = xi - k as f64 / *rows as f64;
                let (tre, tim) = table.row(k);
                for at in (0..j).step_by(BLOCK) {
                    for l in 0..BLOCK.min(j - at) {
                        let i = at + l;
                        let (zr, zi) = shifted_row(eps[i], delta, (tre[i], tim[i]));
                        im[i] = zr.mul_add(ri[l], zi * rr[l]);
                    }
                    advance(&mut rr, &mut ri, rot);
                }
            }
        }
    }

    /// `e^{iβ_j Δs}` for every mode (real parts into `re`, imaginary into
    /// `im`, length J), where `Δs` is the step in the basis's coordinate
    /// of a carrier moving by `dx` (m) along x (`−dx` on a mirrored basis):
    /// the rotation that takes the phasors at x to those at x + dx
    /// ([`FastShapes::phasor_im_into`]). One `sin_cos` per mode, of
    /// `β_j Δs = (jπ + ε_j) Δs / L`.
    pub fn rotations_into(&self, dx: f64, re: &mut [f64], im: &mut [f64]) {
        let ds = if self.mirrored { -dx } else { dx };
        let dxi = ds / self.length;
        for i in 0..self.count {
            let eps = match &self.oscillating {
                Oscillating::Sine { .. } => 0.0,
                Oscillating::Shifted { eps, .. } => eps[i],
            };
            let (s, c) = (((i + 1) as f64).mul_add(PI, eps) * dxi).sin_cos();
            (re[i], im[i]) = (c, s);
        }
    }

    /// The values at `x` handed out `BLOCK` modes at a time, for a caller
    /// that consumes each block as it is made (the fused `modal_exact` step,
    /// `integrate/modal_exact.rs`): the same operations as
    /// [`FastShapes::values_into`], so the same bits. Within a clamped
    /// end's boundary layer the first blocks, those a layer row reaches,
    /// are evaluated whole first ([`Blocks::layered_into`]), or, in
    /// AVX-512 registers, get their layer terms block by block
    /// ([`BlocksAvx512`]); `None` where a
    /// row reaches past the whole blocks (take [`FastShapes::values_into`]
    /// there). Inlined into its caller, so that in the fused step (compiled
    /// for AVX2 + FMA) the first block's products use the FMA instruction,
    /// not the library's `fma` call (the same bits, ~75 ns a step less).
    #[inline(always)]
    pub(crate) fn blocks_at(&self, x: f64) -> Option<Blocks<'_>> {
        // as values_kernel
        let x = x.clamp(0.0, self.length);
        let s = if self.mirrored { self.length - x } else { x };
        let j = self.count;
        let full = j / BLOCK * BLOCK;
        // the left end's terms first, then the right's: as values_kernel
        let layers = [
            self.left.as_ref().map(|l| (l, s)),
            self.right.as_ref().map(|r| (r, self.length - s)),
        ];
        let reach = layers
            .iter()
            .flatten()
            .map(|(l, d)| l.modes_at(*d))
            .max()
            .unwrap_or(0);
        if reach > full {
            return None;
        }
        let xi = s / self.length;
        let (rr, ri, rot) = first_block(PI * xi);
        let rows = match &self.oscillating {
            Oscillating::Sine { d } => BlockRows::Sine(&d[..j]),
            Oscillating::Shifted { eps, rows, table } => {
                let k = (xi * *rows as f64).round() as usize;
                let delta = xi - k as f64 / *rows as f64;
                let (tre, tim) = table.row(k);
                BlockRows::Shifted {
                    eps: &eps[..j],
                    tre,
                    tim,
                    delta,
                }
            }
        };
        Some(Blocks {
            rows,
            layers,
            layered: reach.next_multiple_of(BLOCK),
            rr,
            ri,
            rot,
            full,
        })
    }

    /// `φ_j(x)`, kg^{−1/2}, for all j into `out` (length J), equal to
    /// [`ModeShapes::values_into`] within `FAST_SHAPES_AGREEMENT` of the
    /// amplitude. `x` is clamped to `[0, L]`. No allocation; one `sin_cos`.
    pub fn values_into(&self, x: f64, out: &mut [f64]) {
        self.values_by(x, out, lanes::avx2_fma())
    }

    /// [`FastShapes::values_into`] by the AVX2 + FMA path (`vector`, only
    /// where the CPU has both) or the scalar one: the same bits. The vector
    /// path compiles the whole evaluation for AVX2 + FMA, so its scalar
    /// parts (the first block of the recurrence, the last partial block)
    /// use the FMA instruction, not its software emulation.
    fn values_by(&self, x: f64, out: &mut [f64], vector: bool) {
        #[cfg(target_arch = "x86_64")]
        if vector {
            // SAFETY: the caller checked AVX2 and FMA (lanes::avx2_fma).
            unsafe { self.values_fma(x, out) };
            return;
        }
        self.values_kernel(x, out, false)
    }

    /// # Safety
    /// The CPU supports AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn values_fma(&self, x: f64, out: &mut [f64]) {
        self.values_kernel(x, out, true)
    }

    #[inline(always)]
    fn values_kernel(&self, x: f64, out: &mut [f64], vector: bool) {
        assert_eq!(out.len(), self.count, "one slot per mode");
        let x = x.clamp(0.0, self.length);
        let s = if self.mirrored { self.length - x } else { x };
        let xi = s / self.length;
        self.oscillating_into(xi, out, vector);
        if let Some(l) = &self.left {
            l.add_into(s, out, vector);
        }
        if let Some(r) = &self.right {
            r.add_into(self.length - s, out, vector);
        }
    }

    /// The oscillating parts at `ξ = s/L` ([`FastShapes`]), overwriting `out`:
    /// blocks of [`BLOCK`] modes, each an independent lane of the
    /// recurrence, with AVX2 + FMA where the CPU has them (the same fused
    /// operations, the same bits), then the last partial block.
    #[inline(always)]
    fn oscillating_into(&self, xi: f64, out: &mut [f64], vector: bool) {
        let (mut rr, mut ri, rot) = first_block(PI * xi);
        let j = self.count;
        let full = j / BLOCK * BLOCK;
        let out = &mut out[..j];
        match &self.oscillating {
            Oscillating::Sine { d } => {
                let mut done = 0;
                #[cfg(target_arch = "x86_64")]
                if vector {
                    // SAFETY: AVX2 and FMA (the caller checked); d and out hold ≥ full.
                    unsafe { sine_avx2(&d[..full], &mut out[..full], (&mut rr, &mut ri), rot) };
                    done = full;
                }
                for at in (done..full).step_by(BLOCK) {
                    for l in 0..BLOCK {
                        out[at + l] = d[at + l] * ri[l];
                    }
                    advance(&mut rr, &mut ri, rot);
                }
                for i in full..j {
                    out[i] = d[i] * ri[i - full];
                }
            }
            Oscillating::Shifted { eps, rows, table } => {
                let k = (xi * *rows as f64).round() as usize;
                let delta = xi - k as f64 / *rows as f64;
                let (tre, tim) = table.row(k);
                let mut done = 0;
                #[cfg(target_arch = "x86_64")]
                if vector {
                    // SAFETY: AVX2 and FMA (the caller checked); every slice holds ≥ full.
                    unsafe {
                        shifted_avx2(
                            (&eps[..full], &tre[..full], &tim[..full]),
                            delta,
                            &mut out[..full],
                            (&mut rr, &mut ri),
                            rot,
                        )
                    };
                    done = full;
                }
                for at in (done..full).step_by(BLOCK) {
                    for l in 0..BLOCK {
                        let i = at + l;
                        out[i] = shifted(eps[i], delta, (tre[i], tim[i]), (rr[l], ri[l]));
                    }
                    advance(&mut rr, &mut ri, rot);
                }
                for i in full..j {
                    let l = i - full;
                    out[i] = shifted(eps[i], delta, (tre[i], tim[i]), (rr[l], ri[l]));
                }
            }
        }
    }
}

/// The mode shapes at one point, block by block ([`FastShapes::blocks_at`]):
/// the table rows at that point and the rotation recurrence's state.
#[derive(Debug, Clone)]
pub(crate) struct Blocks<'a> {
    rows: BlockRows<'a>,
    /// Each end's boundary-layer table (left, right) and the distance to
    /// that end.
    layers: [Option<(&'a Layer, f64)>; 2],
    /// The whole blocks a layer row reaches at the point (0 outside the
    /// layers): [`Blocks::layered_into`]'s.
    layered: usize,
    rr: [f64; BLOCK],
    ri: [f64; BLOCK],
    rot: (f64, f64),
    full: usize,
}

/// The oscillating part's rows at one point (J entries each).
#[derive(Debug, Clone)]
enum BlockRows<'a> {
    Sine(&'a [f64]),
    Shifted {
        eps: &'a [f64],
        tre: &'a [f64],
        tim: &'a [f64],
        delta: f64,
    },
}

impl Blocks<'_> {
    /// The values of the first modes, those in the blocks a boundary-layer
    /// row reaches at the point, into `out[..end]`, and `end` (a multiple
    /// of `BLOCK`, ≤ [`Blocks::full`]; 0 outside the layers): the
    /// oscillating parts block by block (`BlocksAvx::next`), then each
    /// layer row's terms over those modes (`Layer::add_into`), the
    /// operations of [`FastShapes::values_into`]. The blocks from `end` on
    /// are then handed out as usual.
    ///
    /// # Safety
    /// The CPU supports AVX2 and FMA; `out` holds at least `end` entries.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn layered_into(&mut self, out: &mut [f64]) -> usize {
        use std::arch::x86_64::_mm256_storeu_pd;
        let end = self.layered;
        if end == 0 {
            return 0;
        }
        // SAFETY: AVX2 and FMA (the caller's contract); out holds ≥ end.
        unsafe {
            let mut v = BlocksAvx::new(self);
            for at in (0..end).step_by(BLOCK) {
                for (u, q) in v.next(self, at).into_iter().enumerate() {
                    _mm256_storeu_pd(out.as_mut_ptr().add(at + 4 * u), q);
                }
            }
            v.finish(self);
        }
        for (layer, d) in self.layers.iter().flatten() {
            layer.add_into(*d, &mut out[..end], true);
        }
        end
    }

    /// The modes in whole blocks, ⌊J/B⌋·B: the vector blocks
    /// (`BlocksAvx`) cover `0 .. full()`, [`Blocks::tail_into`] the rest.
    pub fn full(&self) -> usize {
        self.full
    }

    /// The values of modes `full() .. J` into `out` (length J − full()),
    /// after the whole blocks have advanced the recurrence
    /// (`BlocksAvx::finish`): as the last partial block of
    /// [`FastShapes::values_into`].
    #[inline(always)]
    pub fn tail_into(&self, out: &mut [f64]) {
        let at = self.full;
        match self.rows {
            BlockRows::Sine(d) => {
                for (l, o) in out.iter_mut().enumerate() {
                    *o = d[at + l] * self.ri[l];
                }
            }
            BlockRows::Shifted {
                eps,
                tre,
                tim,
                delta,
            } => {
                for (l, o) in out.iter_mut().enumerate() {
                    let i = at + l;
                    *o = shifted(eps[i], delta, (tre[i], tim[i]), (self.rr[l], self.ri[l]));
                }
            }
        }
    }
}

/// `a·b` for complex a, b, fused: `(a_r b_r − a_i b_i, a_r b_i + a_i b_r)`
/// (also a cruise's phasor step, `integrate/modal_cruise.rs`).
#[inline(always)]
pub(crate) fn rotate((a, b): (f64, f64), (cr, ci): (f64, f64)) -> (f64, f64) {
    (a.mul_add(cr, -(b * ci)), a.mul_add(ci, b * cr))
}

/// The whole blocks of [`FastShapes::oscillating_into`] for pinned–pinned
/// modes: `d_j sin(jθ)`, the recurrence advanced after each block (left
/// at the first mode past them).
///
/// # Safety
/// The CPU supports AVX2 and FMA; `d` and `out` have equal lengths, a
/// multiple of [`BLOCK`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn sine_avx2(
    d: &[f64],
    out: &mut [f64],
    (rr, ri): (&mut [f64; BLOCK], &mut [f64; BLOCK]),
    rot: (f64, f64),
) {
    use std::arch::x86_64::*;
    const V: usize = BLOCK / 4;
    // SAFETY (whole body): every access is within a block of BLOCK entries
    // at `at` < len, or within rr/ri.
    unsafe {
        let (cr, ci) = (_mm256_set1_pd(rot.0), _mm256_set1_pd(rot.1));
        let mut vr: [__m256d; V] = std::array::from_fn(|v| _mm256_loadu_pd(rr.as_ptr().add(4 * v)));
        let mut vi: [__m256d; V] = std::array::from_fn(|v| _mm256_loadu_pd(ri.as_ptr().add(4 * v)));
        let mut at = 0;
        while at < d.len() {
            for v in 0..V {
                let i = at + 4 * v;
                _mm256_storeu_pd(
                    out.as_mut_ptr().add(i),
                    _mm256_mul_pd(_mm256_loadu_pd(d.as_ptr().add(i)), vi[v]),
                );
                let (a, b) = (vr[v], vi[v]);
                vr[v] = _mm256_fmsub_pd(a, cr, _mm256_mul_pd(b, ci));
                vi[v] = _mm256_fmadd_pd(a, ci, _mm256_mul_pd(b, cr));
            }
            at += BLOCK;
        }
        for v in 0..V {
            _mm256_storeu_pd(rr.as_mut_ptr().add(4 * v), vr[v]);
            _mm256_storeu_pd(ri.as_mut_ptr().add(4 * v), vi[v]);
        }
    }
}

/// The whole blocks of [`FastShapes::oscillating_into`] for shifted modes
/// ([`shifted`], four at a time), the recurrence advanced after each block.
///
/// # Safety
/// The CPU supports AVX2 and FMA; the slices have equal lengths, a
/// multiple of [`BLOCK`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn shifted_avx2(
    (eps, tre, tim): (&[f64], &[f64], &[f64]),
    delta: f64,
    out: &mut [f64],
    (rr, ri): (&mut [f64; BLOCK], &mut [f64; BLOCK]),
    rot: (f64, f64),
) {
    use std::arch::x86_64::*;
    const V: usize = BLOCK / 4;
    // SAFETY (whole body): as in `sine_avx2`.
    unsafe {
        let s = _mm256_set1_pd;
        let (cr, ci, dl, one) = (s(rot.0), s(rot.1), s(delta), s(1.0));
        let (c0, c1, c2) = (s(COS[0]), s(COS[1]), s(COS[2]));
        let (s0, s1) = (s(SIN[0]), s(SIN[1]));
        let mut vr: [__m256d; V] = std::array::from_fn(|v| _mm256_loadu_pd(rr.as_ptr().add(4 * v)));
        let mut vi: [__m256d; V] = std::array::from_fn(|v| _mm256_loadu_pd(ri.as_ptr().add(4 * v)));
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let mut at = 0;
        while at < eps.len() {
            for v in 0..V {
                let i = at + 4 * v;
                let y = _mm256_mul_pd(ld(eps, i), dl);
                let y2 = _mm256_mul_pd(y, y);
                let cy = _mm256_fmadd_pd(
                    y2,
                    _mm256_fmadd_pd(y2, _mm256_fmadd_pd(y2, c2, c1), c0),
                    one,
                );
                let sy = _mm256_mul_pd(y, _mm256_fmadd_pd(y2, _mm256_fmadd_pd(y2, s1, s0), one));
                let (tr, ti) = (ld(tre, i), ld(tim, i));
                let zr = _mm256_fmsub_pd(tr, cy, _mm256_mul_pd(ti, sy));
                let zi = _mm256_fmadd_pd(tr, sy, _mm256_mul_pd(ti, cy));
                let (a, b) = (vr[v], vi[v]);
                _mm256_storeu_pd(
                    out.as_mut_ptr().add(i),
                    _mm256_fmsub_pd(zr, a, _mm256_mul_pd(zi, b)),
                );
                vr[v] = _mm256_fmsub_pd(a, cr, _mm256_mul_pd(b, ci));
                vi[v] = _mm256_fmadd_pd(a, ci, _mm256_mul_pd(b, cr));
            }
            at += BLOCK;
        }
        for v in 0..V {
            _mm256_storeu_pd(rr.as_mut_ptr().add(4 * v), vr[v]);
            _mm256_storeu_pd(ri.as_mut_ptr().add(4 * v), vi[v]);
        }
    }
}

/// [`Blocks`] in AVX2 registers: the recurrence's state and the
/// constants of [`shifted_avx2`] / [`sine_avx2`], whose operations
/// [`BlocksAvx::next`] repeats one block at a time (the same bits).
#[cfg(target_arch = "x86_64")]
pub(crate) struct BlocksAvx {
    vr: [std::arch::x86_64::__m256d; BLOCK / 4],
    vi: [std::arch::x86_64::__m256d; BLOCK / 4],
    cr: std::arch::x86_64::__m256d,
    ci: std::arch::x86_64::__m256d,
    dl: std::arch::x86_64::__m256d,
}

#[cfg(target_arch = "x86_64")]
impl BlocksAvx {
    /// The registers for `b`'s first block.
    ///
    /// # Safety
    /// The CPU supports AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub unsafe fn new(b: &Blocks) -> Self {
        use std::arch::x86_64::*;
        let delta = match b.rows {
            BlockRows::Shifted { delta, .. } => delta,
            BlockRows::Sine(_) => 0.0,
        };
        // SAFETY: rr and ri hold BLOCK entries.
        unsafe {
            BlocksAvx {
                vr: std::array::from_fn(|v| _mm256_loadu_pd(b.rr.as_ptr().add(4 * v))),
                vi: std::array::from_fn(|v| _mm256_loadu_pd(b.ri.as_ptr().add(4 * v))),
                cr: _mm256_set1_pd(b.rot.0),
                ci: _mm256_set1_pd(b.rot.1),
                dl: _mm256_set1_pd(delta),
            }
        }
    }

    /// The values of modes `at .. at + BLOCK` (`at` a multiple of
    /// [`BLOCK`], `at + BLOCK ≤ b.full()`, the blocks taken in order), four
    /// vectors of four, and the recurrence advanced to the next block.
    ///
    /// # Safety
    /// The CPU supports AVX2 and FMA; `at + BLOCK ≤ b.full()`.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub unsafe fn next(
        &mut self,
        b: &Blocks,
        at: usize,
    ) -> [std::arch::x86_64::__m256d; BLOCK / 4] {
        use std::arch::x86_64::*;
        const V: usize = BLOCK / 4;
        // SAFETY (whole body): every load is within at .. at + BLOCK ≤ J.
        unsafe {
            let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
            let mut out = [_mm256_setzero_pd(); V];
            for (v, o) in out.iter_mut().enumerate() {
                let i = at + 4 * v;
                let (a, bb) = (self.vr[v], self.vi[v]);
                *o = match b.rows {
                    // as sine_avx2
                    BlockRows::Sine(d) => _mm256_mul_pd(ld(d, i), bb),
                    // as shifted_avx2
                    BlockRows::Shifted { eps, tre, tim, .. } => {
                        let s = _mm256_set1_pd;
                        let y = _mm256_mul_pd(ld(eps, i), self.dl);
                        let y2 = _mm256_mul_pd(y, y);
                        let cy = _mm256_fmadd_pd(
                            y2,
                            _mm256_fmadd_pd(
                                y2,
                                _mm256_fmadd_pd(y2, s(COS[2]), s(COS[1])),
                                s(COS[0]),
                            ),
                            s(1.0),
                        );
                        let sy = _mm256_mul_pd(
                            y,
                            _mm256_fmadd_pd(y2, _mm256_fmadd_pd(y2, s(SIN[1]), s(SIN[0])), s(1.0)),
                        );
                        let (tr, ti) = (ld(tre, i), ld(tim, i));
                        let zr = _mm256_fmsub_pd(tr, cy, _mm256_mul_pd(ti, sy));
                        let zi = _mm256_fmadd_pd(tr, sy, _mm256_mul_pd(ti, cy));
                        _mm256_fmsub_pd(zr, a, _mm256_mul_pd(zi, bb))
                    }
                };
                self.vr[v] = _mm256_fmsub_pd(a, self.cr, _mm256_mul_pd(bb, self.ci));
                self.vi[v] = _mm256_fmadd_pd(a, self.ci, _mm256_mul_pd(bb, self.cr));
            }
            out
        }
    }

    /// Hand the recurrence's state back to `b` for [`Blocks::tail_into`].
    ///
    /// # Safety
    /// The CPU supports AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub unsafe fn finish(&self, b: &mut Blocks) {
        use std::arch::x86_64::*;
        for v in 0..BLOCK / 4 {
            // SAFETY: rr and ri hold BLOCK entries.
            unsafe {
                _mm256_storeu_pd(b.rr.as_mut_ptr().add(4 * v), self.vr[v]);
                _mm256_storeu_pd(b.ri.as_mut_ptr().add(4 * v), self.vi[v]);
            }
        }
    }
}

/// The next block of `e^{ijθ}`: every entry times `e^{iBθ}`.
#[inline(always)]
fn advance(re: &mut [f64; BLOCK], im: &mut [f64; BLOCK], rot: (f64, f64)) {
    for l in 0..BLOCK {
        (re[l], im[l]) = rotate((re[l], im[l]), rot);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::analytic::MAX_MODES;
    use crate::scene::{BeamProps, Support};

    /// (EI, T, ρA, L): as mode_shapes.rs's cases.
    pub(crate) const REFERENCE: (f64, f64, f64, f64) =
        (1.34e11 * 9.64e-10, 3.0e4, 8900.0 * 1.5e-4, 50.0);
    const SHORT: (f64, f64, f64, f64) = (195.0, 2.0e4, 1.35, 20.0);
    const BALANCED: (f64, f64, f64, f64) = (4.0, 100.0, 1.35, 1.0);
    const BARE: (f64, f64, f64, f64) = (3.0, 0.0, 2.0, 1.7);
    const EXTREME: (f64, f64, f64, f64) = (1e-2, 1e5, 1.35, 50.0);

    const ENDS: [(Support, Support); 4] = [
        (Support::Pinned, Support::Pinned),
        (Support::Clamped, Support::Pinned),
        (Support::Pinned, Support::Clamped),
        (Support::Clamped, Support::Clamped),
    ];

    /// The basis of `case` = (EI, T, ρA, L) between `ends`, J modes.
    pub(crate) fn shapes(
        case: (f64, f64, f64, f64),
        ends: (Support, Support),
        j: usize,
    ) -> ModeShapes {
        let (ei, tension, rho_a, length) = case;
        let props = BeamProps {
            length,
            rho_a,
            ei,
            ea: None,
            tension,
            left: ends.0,
            right: ends.1,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        };
        ModeShapes::new(&props, j).unwrap()
    }

    /// The worst |fast − direct| over a grid of points (with the points
    /// near each end refined, where the layers are), relative to the
    /// amplitude, and the mode where it occurs.
    fn worst(s: &ModeShapes, f: &FastShapes, amp: f64) -> (f64, usize) {
        let l = s.length();
        let j = s.count();
        let (mut a, mut b) = (vec![0.0; j], vec![0.0; j]);
        let mut points: Vec<f64> = (0..=997).map(|i| l * i as f64 / 997.0).collect();
        for i in 0..200 {
            let d = l * 1e-4 * (1.05f64).powi(i);
            points.extend([d.min(l), (l - d).max(0.0)]);
        }
        let (mut w, mut at) = (0.0f64, 0);
        for x in points {
            s.values_into(x, &mut a);
            f.values_into(x, &mut b);
            for (i, (a, b)) in a.iter().zip(&b).enumerate() {
                let e = (a - b).abs() / amp;
                if e > w {
                    w = e;
                    at = i + 1;
                }
            }
        }
        (w, at)
    }

    #[test]
    fn fast_values_equal_the_direct_ones_for_every_support_pair() {
        println!("case  ends  J  worst |fast − direct|/amp  (mode)");
        for case in [REFERENCE, SHORT, BALANCED, BARE, EXTREME] {
            let amp = (2.0 / (case.2 * case.3)).sqrt();
            for ends in ENDS {
                let top: &[usize] = if case == REFERENCE {
                    &[1000, MAX_MODES]
                } else {
                    &[1000]
                };
                for &j in [7, 64].iter().chain(top) {
                    let s = shapes(case, ends, j);
                    let f = FastShapes::new(&s);
                    let (w, at) = worst(&s, &f, amp);
                    println!("{case:?} {ends:?} {j}: {w:.2e} ({at})");
                    assert!(
                        w <= FAST_SHAPES_AGREEMENT,
                        "{case:?} {ends:?} J = {j}: {w:e}"
                    );
                }
            }
        }
    }

    /// The recurrence's error grows linearly in j whatever θ; the
    /// three-term recurrence's is amplified by up to j/sin θ and blows up
    /// near θ = 0 and π (a carrier near a support). θ is dyadic, so jθ is
    /// exact and the reference sin(jθ) carries only libm's half ulp.
    /// Printed for docs/methods.md; asserted: the rotation within
    /// 4·2.2·(j/B + log₂B) ulps, the three-term recurrence beyond 10³ ulps
    /// near a support.
    #[test]
    fn rotation_error_grows_linearly_and_chebyshev_does_not_near_a_support() {
        let j_max = 4000;
        println!("θ          j     rotation/ε   three-term/ε");
        let mut cheb_worst = 0.0f64;
        for theta in [1.0 / 4096.0, 0.25, 1.5, 201.0 / 64.0] {
            let (mut rr, mut ri, rot) = first_block(theta);
            let (mut s_prev, mut s_now) = (0.0, theta.sin());
            let two_c = 2.0 * theta.cos();
            let mut start = 0;
            let mut rot_err = vec![0.0f64; j_max];
            let mut cheb_err = vec![0.0f64; j_max];
            while start < j_max {
                for l in 0..BLOCK {
                    let j = start + l + 1;
                    let exact = (j as f64 * theta).sin();
                    rot_err[j - 1] = (ri[l] - exact).abs() / f64::EPSILON;
                }
                advance(&mut rr, &mut ri, rot);
                start += BLOCK;
            }
            for j in 1..=j_max {
                let exact = (j as f64 * theta).sin();
                cheb_err[j - 1] = (s_now - exact).abs() / f64::EPSILON;
                let next = two_c * s_now - s_prev;
                (s_prev, s_now) = (s_now, next);
            }
            for j in [16, 100, 1000, 4000] {
                let r = rot_err[..j].iter().fold(0.0f64, |a, b| a.max(*b));
                let c = cheb_err[..j].iter().fold(0.0f64, |a, b| a.max(*b));
                println!("{theta:<10.6} {j:5} {r:10.1} {c:14.1}");
                let bound = 4.0 * 2.2 * (j as f64 / BLOCK as f64 + 4.0);
                assert!(r <= bound, "θ = {theta}, j = {j}: {r} > {bound}");
                cheb_worst = cheb_worst.max(c);
            }
        }
        assert!(
            cheb_worst > 1e3,
            "the three-term recurrence loses accuracy near θ = 0, π"
        );
    }

    /// The phase table's rows give the same bits whenever, in whatever
    /// order and on whichever thread they are made, and a clone carries
    /// the rows made so far.
    #[test]
    fn phase_rows_made_on_first_use_give_the_same_bits_in_any_order() {
        let s = shapes(REFERENCE, ENDS[1], 800);
        let xs: Vec<f64> = (0..=60).map(|i| REFERENCE.3 * i as f64 / 60.0).collect();
        let values = |f: &FastShapes, x: f64| -> Vec<u64> {
            let mut out = vec![0.0; 800];
            f.values_into(x, &mut out);
            out.iter().map(|v| v.to_bits()).collect()
        };
        let forward = FastShapes::new(&s);
        let expected: Vec<Vec<u64>> = xs.iter().map(|&x| values(&forward, x)).collect();
        let backward = FastShapes::new(&s);
        for (x, e) in xs.iter().zip(&expected).rev() {
            assert_eq!(&values(&backward, *x), e, "x = {x}");
        }
        // half the rows made, then cloned: the clone's made and new rows
        let half = FastShapes::new(&s);
        for &x in xs.iter().step_by(2) {
            values(&half, x);
        }
        let copy = half.clone();
        for (x, e) in xs.iter().zip(&expected) {
            assert_eq!(&values(&copy, *x), e, "clone, x = {x}");
        }
        // two threads making the rows of one shared table
        let shared = FastShapes::new(&s);
        std::thread::scope(|sc| {
            for t in 0..2 {
                let (shared, xs, expected) = (&shared, &xs, &expected);
                sc.spawn(move || {
                    for i in 0..xs.len() {
                        let i = if t == 0 { i } else { xs.len() - 1 - i };
                        assert_eq!(values(shared, xs[i]), expected[i], "thread {t}");
                    }
                });
            }
        });
    }

    #[test]
    fn the_vector_and_scalar_paths_give_the_same_bits() {
        if !lanes::avx2_fma() {
            return;
        }
        for (case, ends) in [
            (REFERENCE, ENDS[1]),
            (BARE, ENDS[3]),
            (SHORT, ENDS[0]),
            (BARE, ENDS[2]),
        ] {
            for j in [5, 16, 61, 800] {
                let s = shapes(case, ends, j);
                let f = FastShapes::new(&s);
                let (mut a, mut b) = (vec![0.0; j], vec![0.0; j]);
                for i in 0..=400 {
                    let x = case.3 * (i as f64 / 400.0).powi(3);
                    f.values_by(x, &mut a, true);
                    f.values_by(x, &mut b, false);
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

    /// The values handed out block by block ([`FastShapes::blocks_at`],
    /// the fused modal step) are those of [`FastShapes::values_into`], bit
    /// for bit, within the clamped ends' boundary layers too (the first
    /// blocks by [`Blocks::layered_into`]); it declines only where a layer
    /// row reaches past the whole blocks.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn the_blocks_give_the_values_bit_for_bit() {
        if !lanes::avx2_fma() {
            return;
        }
        let (mut declined, mut layered) = (0, 0);
        for (case, ends) in [
            (REFERENCE, ENDS[1]),
            (REFERENCE, ENDS[2]),
            (SHORT, ENDS[0]),
            (BARE, ENDS[3]),
        ] {
            for j in [5, 16, 61, 800] {
                let s = shapes(case, ends, j);
                let f = FastShapes::new(&s);
                let (mut a, mut b) = (vec![0.0; j], vec![0.0; j]);
                for i in 0..=400 {
                    let x = case.3 * (i as f64 / 400.0).powi(3);
                    f.values_into(x, &mut a);
                    let Some(mut blocks) = f.blocks_at(x) else {
                        declined += 1;
                        let s = if f.mirrored { f.length - x } else { x };
                        let reach = [
                            f.left.as_ref().map_or(0, |l| l.modes_at(s)),
                            f.right.as_ref().map_or(0, |r| r.modes_at(f.length - s)),
                        ];
                        assert!(reach.iter().any(|m| *m > j / BLOCK * BLOCK));
                        continue;
                    };
                    let full = blocks.full();
                    b.fill(f64::NAN);
                    // SAFETY: AVX2 and FMA checked above; b holds J ≥ full.
                    unsafe {
                        use std::arch::x86_64::_mm256_storeu_pd;
                        let lo = blocks.layered_into(&mut b);
                        layered += usize::from(lo > 0);
                        let mut v = BlocksAvx::new(&blocks);
                        for at in (lo..full).step_by(BLOCK) {
                            for (u, q) in v.next(&blocks, at).into_iter().enumerate() {
                                _mm256_storeu_pd(b.as_mut_ptr().add(at + 4 * u), q);
                            }
                        }
                        v.finish(&mut blocks);
                    }
                    blocks.tail_into(&mut b[full..]);
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
        println!("points within a layer: {layered} by blocks, {declined} declined");
        assert!(layered > 100, "the clamped ends' layers were met");
        assert!(declined > 0, "a layer row past the whole blocks was met");
    }

    #[test]
    fn the_polynomials_match_the_library_functions() {
        for i in -100..=100 {
            let y = i as f64 / 6400.0;
            let (s, c) = small_sin_cos(y);
            assert!((s - y.sin()).abs() <= 2.0 * f64::EPSILON, "{y}");
            assert!((c - y.cos()).abs() <= 2.0 * f64::EPSILON, "{y}");
            let e = exp_minus(8.0 * y);
            assert!(
                (e / (-8.0 * y).exp() - 1.0).abs() <= 4.0 * f64::EPSILON,
                "{y}"
            );
        }
    }

    /// [`Layer::reaches`] answers as `modes_at(d) > 0` everywhere, the
    /// points where `d/Δ` is a half (where `round` turns) and their
    /// neighbours one ulp either side included.
    #[test]
    fn a_layer_reaches_where_its_rows_hold_a_mode() {
        let mut checked = 0;
        for ends in ENDS {
            for (length, j) in [(50.0, 800), (20.0, 200), (50.0, 40)] {
                let (ei, tension, rho_a, _) = REFERENCE;
                let f = FastShapes::new(&shapes((ei, tension, rho_a, length), ends, j));
                for l in [&f.left, &f.right].into_iter().flatten() {
                    let rows = l.starts.len() - 1;
                    let mut ds: Vec<f64> = (0..=4000).map(|i| i as f64 * 1e-3 * length).collect();
                    for k in 0..rows + 2 {
                        let d = (k as f64 + 0.5) * l.spacing;
                        ds.extend([d, d.next_up(), d.next_down(), k as f64 * l.spacing]);
                    }
                    for d in ds.into_iter().filter(|d| *d >= 0.0) {
                        assert_eq!(l.reaches(d), l.modes_at(d) > 0, "{ends:?}, d = {d}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    #[test]
    fn the_reference_basis_has_one_small_layer_table_and_no_right_one() {
        let s = shapes(REFERENCE, ENDS[1], 800);
        let f = FastShapes::new(&s);
        assert!(f.left.is_some() && f.right.is_none());
        println!("table bytes at J = 800: {}", f.table_bytes());
        assert!(f.table_bytes() < 4 << 20);
    }
}
