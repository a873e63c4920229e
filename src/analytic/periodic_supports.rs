//! Free waves on an infinite string or tensioned beam resting on identical
//! supports every `d` (Floquet–Bloch), their pass and stop bands, and the
//! natural frequencies of a finite line of N such spans with pinned ends
//! (docs/lines.md L4–L8): the independent reference for
//! multi-span lines, built before them.
//!
//! A support is rigid (v = 0) or elastic: a spring k to ground and a point
//! mass M, a dynamic stiffness `s(ω) = k − M ω²`, N/m. A Bloch wave has
//! `u_{n+1} = e^{iqd} u_n` from one support to the next; its propagation
//! constant follows from one cell:
//!
//! ```text
//! (L4) string, κ = ω sqrt(ρA/T):  cos qd = cos κd + s(ω) sin κd / (2 T κ)
//!      (the half trace of the cell's transfer matrix [[1, 0], [s, 1]]·
//!      [[cos κd, sin κd/(Tκ)], [−Tκ sin κd, cos κd]], determinant 1)
//! ```
//!
//! The beam's rigid-support band function (L5, Mead 1970) is derived on
//! [`PeriodicLine::cos_qd`], the elastic supports' palindromic Bloch
//! polynomial (L6) on [`PeriodicLine::bloch_polynomial`], and the finite
//! line's frequencies (L8) on [`PeriodicLine::span_line_frequencies`]; band
//! edges are bisected to round-off (L7, [`PeriodicLine::pass_bands`]).

use nalgebra::SMatrix;

use super::modes::{require_nonnegative, require_positive};
use crate::error::{Error, Result};

/// The support repeated every `d`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PeriodicSupport {
    /// v = 0 at each support (rotation free).
    Rigid,
    /// A spring to ground and a point mass at each support.
    Elastic {
        /// k, N/m (≥ 0).
        k: f64,
        /// M, kg (≥ 0).
        mass: f64,
    },
}

/// An infinite string (EI = 0) or tensioned beam on periodic supports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PeriodicLine {
    /// EI, N·m² (≥ 0; 0 is a string).
    pub ei: f64,
    /// T, N (> 0 for a string, ≥ 0 for a beam).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
    /// Support spacing d, m (> 0).
    pub spacing: f64,
    /// The support at every x = n d.
    pub support: PeriodicSupport,
}

/// `(coth u, csch u)` for u > 0 without overflow.
fn coth_csch(u: f64) -> (f64, f64) {
    let e = (-u).exp();
    let den = -(-2.0 * u).exp_m1(); // 1 − e^{−2u}
    ((1.0 + e * e) / den, 2.0 * e / den)
}

/// Roots of `a z² + b z + c = 0` that are real, by the stable formula.
fn real_quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return vec![0.0, 0.0];
    }
    vec![q / a, c / q]
}

impl PeriodicLine {
    /// Check the inputs: EI ≥ 0, T ≥ 0 (T > 0 for a string), ρA > 0, d > 0,
    /// an elastic support's k, M ≥ 0.
    pub fn new(
        ei: f64,
        tension: f64,
        rho_a: f64,
        spacing: f64,
        support: PeriodicSupport,
    ) -> Result<Self> {
        require_nonnegative("ei", ei, "N·m²")?;
        require_nonnegative("tension", tension, "N")?;
        require_positive("rho_a", rho_a, "kg/m")?;
        require_positive("spacing", spacing, "m")?;
        if ei == 0.0 && tension == 0.0 {
            return Err(Error::invalid(
                "tension",
                0.0,
                "a string (EI = 0) needs T > 0 (N)",
            ));
        }
        if let PeriodicSupport::Elastic { k, mass } = support {
            require_nonnegative("support.k", k, "N/m")?;
            require_nonnegative("support.mass", mass, "kg")?;
        }
        Ok(PeriodicLine {
            ei,
            tension,
            rho_a,
            spacing,
            support,
        })
    }

    /// The support's dynamic stiffness s(ω) = k − M ω², N/m (∞ if rigid).
    pub fn support_stiffness(&self, omega: f64) -> f64 {
        match self.support {
            PeriodicSupport::Rigid => f64::INFINITY,
            PeriodicSupport::Elastic { k, mass } => k - mass * omega * omega,
        }
    }

    /// (α, β), rad/m, of the beam at ω ([`PeriodicLine::cos_qd`]), without cancellation.
    pub fn alpha_beta(&self, omega: f64) -> (f64, f64) {
        let (ei, t) = (self.ei, self.tension);
        let root = (t * t + 4.0 * ei * self.rho_a * omega * omega).sqrt();
        let beta = (2.0 * self.rho_a * omega * omega / (root + t)).sqrt();
        let alpha = ((root + t) / (2.0 * ei)).sqrt();
        (alpha, beta)
    }

    /// The real values of cos qd at ω > 0 (L4, L5, L6): one for a string or
    /// a beam on rigid supports, none or two for a beam on elastic supports
    /// (none: a complex pair, no wave propagates). A rigid string gives ±∞
    /// except at the span modes.
    ///
    /// For the beam, `EI v'''' − T v'' = ρA ω² v` on a span has the solutions
    /// cosh/sinh αx, cos/sin βx with
    /// `α² = (T + sqrt(T² + 4 EI ρA ω²))/(2EI)`, `β² = α² − T/EI`.
    ///
    /// ```text
    /// (L5) rigid supports (three-moment form, Mead 1970): with end moments and
    ///      rotations of a pinned–pinned span,
    ///      cos qd = [α coth(αd) sin βd − β cos βd] / [α csch(αd) sin βd − β]
    /// ```
    ///
    /// The denominator is < 0 for every β > 0 (|α csch(αd) sin βd| < β because
    /// αd/sinh αd < 1 and |sin βd| ≤ βd), so L5 is smooth; coth and csch are
    /// evaluated as `(1 + e^{−2αd})/(1 − e^{−2αd})` and `2e^{−αd}/(1 − e^{−2αd})`,
    /// so no αd overflows. At βd = rπ (the span's pinned–pinned modes) it equals
    /// cos βd = ±1: those are band edges; the other edges are the span's
    /// clamped–clamped modes.
    pub fn cos_qd(&self, omega: f64) -> Vec<f64> {
        let d = self.spacing;
        if self.ei == 0.0 {
            let kappa = omega * (self.rho_a / self.tension).sqrt();
            let (sn, cs) = (kappa * d).sin_cos();
            let s = self.support_stiffness(omega);
            let f = if s.is_infinite() {
                if sn == 0.0 {
                    cs
                } else {
                    sn.signum() * f64::INFINITY
                }
            } else {
                cs + s * sn / (2.0 * self.tension * kappa)
            };
            return vec![f];
        }
        let (alpha, beta) = self.alpha_beta(omega);
        match self.support {
            PeriodicSupport::Rigid => {
                let (coth, csch) = coth_csch(alpha * d);
                let (sn, cs) = (beta * d).sin_cos();
                vec![(alpha * coth * sn - beta * cs) / (alpha * csch * sn - beta)]
            }
            PeriodicSupport::Elastic { .. } => {
                let q = self.bloch_polynomial(omega);
                let (a4, a3) = (0.5 * (q[4] + q[0]), 0.5 * (q[3] + q[1]));
                real_quadratic_roots(a4, a3, q[2] - 2.0 * a4)
                    .into_iter()
                    .map(|z| 0.5 * z)
                    .collect()
            }
        }
    }

    /// The span's dynamic stiffness R (L6): rows EI v''(0), EI v'''(0),
    /// EI v''(d), EI v'''(d); columns v(0), v'(0), v(d), v'(d).
    pub fn span_stiffness(&self, omega: f64) -> SMatrix<f64, 4, 4> {
        let d = self.spacing;
        let (alpha, beta) = self.alpha_beta(omega);
        // [v, v', v'', v'''] of each basis function at x
        let jets = |x: f64| -> [[f64; 4]; 4] {
            let (sn, cs) = (beta * x).sin_cos();
            let (b1, b2, b3) = (beta, beta * beta, beta * beta * beta);
            let (a1, a2, a3) = (alpha, alpha * alpha, alpha * alpha * alpha);
            let hyper = if alpha * d >= 1.0 {
                let (e1, e2) = ((-alpha * x).exp(), (-alpha * (d - x)).exp());
                [
                    [e1, -a1 * e1, a2 * e1, -a3 * e1],
                    [e2, a1 * e2, a2 * e2, a3 * e2],
                ]
            } else {
                let (ch, sh) = ((alpha * x).cosh(), (alpha * x).sinh());
                [
                    [ch, a1 * sh, a2 * ch, a3 * sh],
                    [sh, a1 * ch, a2 * sh, a3 * ch],
                ]
            };
            [
                hyper[0],
                hyper[1],
                [cs, -b1 * sn, -b2 * cs, b3 * sn],
                [sn, b1 * cs, -b2 * sn, -b3 * cs],
            ]
        };
        let (j0, jd) = (jets(0.0), jets(d));
        let mut e = SMatrix::<f64, 4, 4>::zeros();
        let mut f = SMatrix::<f64, 4, 4>::zeros();
        for c in 0..4 {
            e[(0, c)] = j0[c][0];
            e[(1, c)] = j0[c][1];
            e[(2, c)] = jd[c][0];
            e[(3, c)] = jd[c][1];
            f[(0, c)] = self.ei * j0[c][2];
            f[(1, c)] = self.ei * j0[c][3];
            f[(2, c)] = self.ei * jd[c][2];
            f[(3, c)] = self.ei * jd[c][3];
        }
        // R = F E⁻¹: solve Eᵀ Rᵀ = Fᵀ
        let rt = e
            .transpose()
            .lu()
            .solve(&f.transpose())
            .unwrap_or_else(|| SMatrix::from_element(f64::NAN));
        rt.transpose()
    }

    /// Coefficients q₀ … q₄ of det(Bλ² + Aλ + C) (L6), for an elastic beam.
    ///
    /// ```text
    /// (L6) elastic supports: the span's dynamic stiffness R (4×4: end values
    ///      (v, v') ↦ (EI v'', EI v''') at both ends), blocks R_00, R_0d, R_d0, R_dd,
    ///      gives at each support (continuity of v, v', EI v''; the jump of
    ///      EI v''' balanced by s v)
    ///      [A + B λ + C/λ] u = 0,  A = R_00 − R_dd + [[0, 0], [s, 0]],
    ///      B = R_0d, C = −R_d0,  λ = e^{iqd},
    ///      det(Bλ² + Aλ + C) = q₄λ⁴ + q₃λ³ + q₂λ² + q₁λ + q₀ is palindromic
    ///      (q₀ = q₄, q₁ = q₃: reciprocity), so with z = λ + 1/λ = 2 cos qd
    ///      q₄ z² + q₃ z + (q₂ − 2q₄) = 0.
    /// ```
    ///
    /// Two wave types: each real root with |z/2| ≤ 1 is a propagating wave, a
    /// real root outside is evanescent, a complex pair attenuates. R is computed
    /// as F·E⁻¹ from a basis whose values stay bounded (e^{−αx}, e^{−α(d−x)},
    /// cos βx, sin βx once αd ≥ 1; cosh αx, sinh αx below).
    ///
    /// A frequency passes when some wave propagates. Band edges are found by
    /// scanning ω and bisecting the pass/stop switch to round-off (L7).
    pub fn bloch_polynomial(&self, omega: f64) -> [f64; 5] {
        let r = self.span_stiffness(omega);
        let s = self.support_stiffness(omega);
        let blk = |i0: usize, j0: usize| {
            [
                [r[(i0, j0)], r[(i0, j0 + 1)]],
                [r[(i0 + 1, j0)], r[(i0 + 1, j0 + 1)]],
            ]
        };
        let (r00, r0d, rd0, rdd) = (blk(0, 0), blk(0, 2), blk(2, 0), blk(2, 2));
        // entry (i, j) of Bλ² + Aλ + C as coefficients [λ⁰, λ¹, λ²]
        let p = |i: usize, j: usize| {
            let sij = if (i, j) == (1, 0) { s } else { 0.0 };
            [-rd0[i][j], r00[i][j] - rdd[i][j] + sij, r0d[i][j]]
        };
        let mul = |a: [f64; 3], b: [f64; 3]| {
            let mut c = [0.0; 5];
            for i in 0..3 {
                for j in 0..3 {
                    c[i + j] += a[i] * b[j];
                }
            }
            c
        };
        let (d1, d2) = (mul(p(0, 0), p(1, 1)), mul(p(0, 1), p(1, 0)));
        std::array::from_fn(|i| d1[i] - d2[i])
    }

    /// Whether some wave propagates at ω (|cos qd| ≤ 1 for a real root).
    pub fn passes(&self, omega: f64) -> bool {
        self.cos_qd(omega).iter().any(|c| c.abs() <= 1.0)
    }

    /// The pass bands `[ω_lo, ω_hi]`, rad/s, below `omega_max` (L7): `samples`
    /// equal steps are scanned for the pass/stop switch, each switch bisected
    /// to round-off. A band narrower than a step can be missed; a band cut
    /// by `omega_max` ends there. The rigid string's bands are the points
    /// rπc/d.
    pub fn pass_bands(&self, omega_max: f64, samples: usize) -> Result<Vec<(f64, f64)>> {
        require_positive("omega_max", omega_max, "rad/s")?;
        if samples < 2 {
            return Err(Error::invalid("samples", samples, "must be ≥ 2"));
        }
        if self.ei == 0.0 && self.support == PeriodicSupport::Rigid {
            let w1 = std::f64::consts::PI * (self.tension / self.rho_a).sqrt() / self.spacing;
            let n = (omega_max / w1).floor() as usize;
            return Ok((1..=n).map(|r| (r as f64 * w1, r as f64 * w1)).collect());
        }
        let step = omega_max / samples as f64;
        let edge = |mut lo: f64, mut hi: f64| {
            // the switch lies in (lo, hi]; passes(lo) != passes(hi)
            let at_lo = self.passes(lo);
            loop {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    return 0.5 * (lo + hi);
                }
                if self.passes(mid) == at_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
        };
        let mut bands = Vec::new();
        let first = step * 1e-9;
        let mut open = if self.passes(first) { Some(0.0) } else { None };
        let mut prev = first;
        for i in 1..=samples {
            let w = step * i as f64;
            let now = self.passes(w);
            match (open, now) {
                (None, true) => open = Some(edge(prev, w)),
                (Some(lo), false) => {
                    bands.push((lo, edge(prev, w)));
                    open = None;
                }
                _ => {}
            }
            prev = w;
        }
        if let Some(lo) = open {
            bands.push((lo, omega_max));
        }
        Ok(bands)
    }

    /// First entry of `S (P S)^{N−1} (0, 1)ᵀ` (L8, string): zero at the
    /// natural frequencies of N spans with pinned ends.
    pub fn string_frequency_function(&self, n_spans: usize, omega: f64) -> f64 {
        let (t, d) = (self.tension, self.spacing);
        let kappa = omega * (self.rho_a / t).sqrt();
        let (sn, cs) = (kappa * d).sin_cos();
        let s = self.support_stiffness(omega);
        // state (v, T v') from x = 0 with v = 0, T v' = 1
        let (mut v, mut tv) = (0.0, 1.0);
        for span in 0..n_spans {
            if span > 0 {
                tv += s * v;
            }
            (v, tv) = (
                cs * v + sn / (t * kappa) * tv,
                -t * kappa * sn * v + cs * tv,
            );
        }
        v
    }

    /// The natural frequencies, rad/s, ascending, below `omega_max`, of N
    /// spans with pinned ends and this line's supports at the N − 1 interior
    /// points (L8). A string on elastic supports scans its frequency function
    /// in `samples` steps (two roots within one step are missed); a beam on
    /// elastic supports is not covered (an error).
    ///
    /// ```text
    /// (L8) N spans, pinned ends, supports at the N − 1 interior points:
    ///      string:  rigid: ω = rπc/d, each N-fold; elastic: the roots of the
    ///               first entry of S (P S)^{N−1} (0, 1)ᵀ, S the span, P the support
    ///               transfer matrix of L4 (a product, not the trace).
    ///      beam, rigid supports: in band r, ω_pp,r (every span in its r-th
    ///               pinned–pinned mode, all support moments zero) and the N − 1
    ///               roots of L5 = cos(jπ/N), j = 1 … N − 1 (the support moments
    ///               M_n = sin(njπ/N) solve the three-moment recurrence with
    ///               M_0 = M_N = 0): N frequencies per band.
    /// ```
    ///
    /// The rigid-beam roots are bisected between the band's edges, which
    /// assumes L5 monotone within a band (true of the bands checked against
    /// Hermite elements in the tests; a non-monotone band would return one root
    /// per target, not all).
    pub fn span_line_frequencies(
        &self,
        n_spans: usize,
        omega_max: f64,
        samples: usize,
    ) -> Result<Vec<f64>> {
        require_positive("omega_max", omega_max, "rad/s")?;
        if n_spans == 0 {
            return Err(Error::invalid("n_spans", 0, "must be ≥ 1"));
        }
        if samples < 2 {
            return Err(Error::invalid("samples", samples, "must be ≥ 2"));
        }
        let pi = std::f64::consts::PI;
        let d = self.spacing;
        let mut out = Vec::new();
        match (self.ei == 0.0, self.support) {
            (true, PeriodicSupport::Rigid) => {
                let w1 = pi * (self.tension / self.rho_a).sqrt() / d;
                let mut r = 1;
                while r as f64 * w1 <= omega_max {
                    out.extend(std::iter::repeat_n(r as f64 * w1, n_spans));
                    r += 1;
                }
            }
            (true, PeriodicSupport::Elastic { .. }) => {
                let g = |w: f64| self.string_frequency_function(n_spans, w);
                let step = omega_max / samples as f64;
                let mut prev = g(step * 1e-6);
                for i in 1..=samples {
                    let w = step * i as f64;
                    let now = g(w);
                    if now == 0.0 {
                        out.push(w);
                    } else if prev != 0.0 && (now > 0.0) != (prev > 0.0) {
                        out.push(bisect(&g, w - step, w));
                    }
                    prev = now;
                }
            }
            (false, PeriodicSupport::Rigid) => {
                // band r: [ω_pp,r, ω_cc,r], f runs from (−1)^r to −(−1)^r
                let pp = super::PinnedPinnedModes::new(self.ei, self.tension, self.rho_a, d)?;
                let f = |w: f64| self.cos_qd(w)[0];
                let mut r = 1;
                while pp.omega(r) <= omega_max {
                    let (lo, next) = (pp.omega(r), pp.omega(r + 1));
                    let start = if r % 2 == 0 { 1.0 } else { -1.0 };
                    // upper edge: f = −start, bisected between lo and the
                    // first of 64 points of (lo, next) in the stop band
                    // (f returns to −start at next, so next is no bracket)
                    let stop = (1..64)
                        .map(|i| lo + (next - lo) * i as f64 / 64.0)
                        .find(|&w| f(w).abs() > 1.0)
                        .ok_or_else(|| {
                            Error::invalid(
                                "omega",
                                lo,
                                "found no stop band above this pinned–pinned span mode",
                            )
                        })?;
                    let hi = bisect(&|w: f64| f(w) + start, lo, stop);
                    out.push(lo);
                    for j in 1..n_spans {
                        let target = (j as f64 * pi / n_spans as f64).cos();
                        let w = bisect(&|w: f64| f(w) - target, lo, hi);
                        if w <= omega_max {
                            out.push(w);
                        }
                    }
                    r += 1;
                }
                out.sort_by(f64::total_cmp);
            }
            (false, PeriodicSupport::Elastic { .. }) => {
                return Err(Error::invalid(
                    "support",
                    "elastic",
                    "the finite-line frequencies of a beam are given for rigid supports only",
                ));
            }
        }
        out.retain(|w| *w <= omega_max);
        Ok(out)
    }
}

/// The root of `g` on `[lo, hi]` (signs differ at the ends, else the end
/// with the smaller |g|), bisected until the bracket cannot shrink.
fn bisect(g: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let g_lo = g(lo);
    if (g_lo > 0.0) == (g(hi) > 0.0) {
        return if g_lo.abs() <= g(hi).abs() { lo } else { hi };
    }
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return mid;
        }
        let v = g(mid);
        if v == 0.0 {
            return mid;
        }
        if (v > 0.0) == (g_lo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::{DMatrix, SymmetricEigen};
    use std::f64::consts::PI;

    /// Closed forms evaluated two ways (L6 through a 4×4 LU against cos βd):
    /// measured ≤ 1.6e-14 up to μd = 300; round-off of the solve, amplified
    /// by the spread of the basis' magnitudes.
    const ALGEBRA: f64 = 1e-8;
    /// Hermite elements (16 per span, μd = 3) against the exact frequencies
    /// of L8 in the first two bands: the O(h⁴) error, 2.3e-5 in band 2
    /// (measured against 64 per span). At μd ≫ 16 the elements would not
    /// resolve the bending length at the supports: these tests use μd = 3.
    const FE_16: f64 = 5e-5;
    /// Linear string elements after one Richardson step from 64 and 128 per
    /// span: the O(h⁴) remainder, measured ≤ 1.7e-7 in the first three bands.
    const FE_LINEAR: f64 = 1e-6;
    /// L6 for a beam of bending length ℓb = 1e-6·d against the string's L4
    /// on the same elastic supports: the bending layers at the supports,
    /// O(ℓb (1/d + s/T)) ≈ 2e-5 (measured ≤ 4.4e-5); a 0.1 % error in s
    /// would show at ≈ 7e-3.
    const BEAM_TO_STRING: f64 = 2e-4;
    /// |L6 − cos(jπ/N)| at Hermite frequencies (32 per span, μd = 3): their
    /// O(h⁴) frequency error times the slope of cos qd in ω, measured ≤ 4.8e-5.
    const STANDING_FE: f64 = 2e-4;
    /// L4 at the transfer-product roots (L8) against cos(jπ/N): the roots are
    /// bisected to round-off; L4's condition there.
    const STANDING_WAVE: f64 = 1e-9;
    /// Clamped–clamped Euler–Bernoulli βL (tables: Blevins, 12 digits).
    const EB_CLAMPED_CLAMPED: [f64; 3] = [4.730_040_744_86, 7.853_204_624_10, 10.995_607_838_0];

    fn string_elastic(k: f64, mass: f64) -> PeriodicLine {
        PeriodicLine::new(0.0, 2e4, 1.35, 9.0, PeriodicSupport::Elastic { k, mass }).unwrap()
    }

    #[test]
    fn validation_names_the_field() {
        let e = PeriodicLine::new(1.0, 1.0, 1.0, 0.0, PeriodicSupport::Rigid).unwrap_err();
        assert!(e.to_string().contains("`spacing`"), "{e}");
        let e = PeriodicLine::new(1.0, 1.0, 0.0, 1.0, PeriodicSupport::Rigid).unwrap_err();
        assert!(e.to_string().contains("`rho_a`"), "{e}");
        let e = PeriodicLine::new(
            1.0,
            1.0,
            1.0,
            1.0,
            PeriodicSupport::Elastic { k: -1.0, mass: 0.0 },
        )
        .unwrap_err();
        assert!(e.to_string().contains("support.k"), "{e}");
        let e = PeriodicLine::new(0.0, 0.0, 1.0, 1.0, PeriodicSupport::Rigid).unwrap_err();
        assert!(e.to_string().contains("tension"), "{e}");
        let line = string_elastic(1e3, 0.0);
        assert!(line.pass_bands(-1.0, 10).is_err());
        assert!(line.span_line_frequencies(0, 10.0, 10).is_err());
        let beam = PeriodicLine::new(
            1.0,
            1.0,
            1.0,
            1.0,
            PeriodicSupport::Elastic { k: 1.0, mass: 0.0 },
        )
        .unwrap();
        let e = beam.span_line_frequencies(3, 10.0, 100).unwrap_err();
        assert!(e.to_string().contains("support"), "{e}");
    }

    #[test]
    fn free_beam_propagates_cos_beta_d() {
        // k = M = 0: no supports at all, so L6 must return the bare beam's
        // waves, cos qd = cos βd, and the evanescent cosh αd
        println!("  μd      max |cos qd − cos βd|");
        for mu_d in [0.0, 0.1, 1.0, 10.0, 100.0, 300.0] {
            let (ei, ra, d) = (195.0, 1.35, 9.0);
            let t = ei * (mu_d / d) * (mu_d / d);
            let line =
                PeriodicLine::new(ei, t, ra, d, PeriodicSupport::Elastic { k: 0.0, mass: 0.0 })
                    .unwrap();
            let mut worst: f64 = 0.0;
            for w in [0.5, 3.0, 20.0, 100.0, 700.0] {
                let (alpha, beta) = line.alpha_beta(w);
                let roots = line.cos_qd(w);
                let near = roots
                    .iter()
                    .map(|c| (c - (beta * d).cos()).abs())
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(near);
                if alpha * d < 8.0 {
                    // the evanescent root carries ε e^{αd} relative (q₄ ≈ e^{−αd}
                    // is a difference of O(1) products): checked where small
                    let far = roots
                        .iter()
                        .map(|c| (c / (alpha * d).cosh() - 1.0).abs())
                        .fold(f64::INFINITY, f64::min);
                    assert!(far < ALGEBRA, "μd = {mu_d}, ω = {w}: {roots:?}");
                }
                let q = line.bloch_polynomial(w);
                let scale = q.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                assert!((q[0] - q[4]).abs() <= 1e-9 * scale, "{q:?}");
                assert!((q[1] - q[3]).abs() <= 1e-9 * scale, "{q:?}");
            }
            println!("  {mu_d:<7} {worst:.2e}");
            assert!(worst < ALGEBRA, "μd = {mu_d}: {worst}");
        }
    }

    #[test]
    fn stiff_elastic_supports_tend_to_rigid_ones() {
        for mu_d in [0.5, 5.0, 50.0] {
            let (ei, ra, d) = (195.0, 1.35, 9.0);
            let t = ei * (mu_d / d) * (mu_d / d);
            let rigid = PeriodicLine::new(ei, t, ra, d, PeriodicSupport::Rigid).unwrap();
            let stiff = PeriodicLine::new(
                ei,
                t,
                ra,
                d,
                PeriodicSupport::Elastic { k: 1e13, mass: 3.0 },
            )
            .unwrap();
            for w in [10.0, 40.0, 150.0, 400.0] {
                let f = rigid.cos_qd(w)[0];
                let near = stiff
                    .cos_qd(w)
                    .iter()
                    .map(|c| (c - f).abs())
                    .fold(f64::INFINITY, f64::min);
                // the support moves by O(force/k): an O(EIβ³d/k) correction
                assert!(
                    near < 1e-5 * (1.0 + f.abs()),
                    "μd = {mu_d}, ω = {w}: {near}"
                );
            }
        }
    }

    #[test]
    fn rigid_beam_band_edges_are_the_span_modes() {
        // Euler–Bernoulli: bands [pinned–pinned, clamped–clamped] of one span
        let (ei, ra, d) = (2.0, 1.5, 3.0);
        let line = PeriodicLine::new(ei, 0.0, ra, d, PeriodicSupport::Rigid).unwrap();
        let omega_of = |bd: f64| (bd / d).powi(2) * (ei / ra).sqrt();
        let bands = line.pass_bands(omega_of(12.0), 400).unwrap();
        assert_eq!(bands.len(), 3, "{bands:?}");
        for (r, (lo, hi)) in bands.iter().enumerate() {
            assert_relative_eq!(*lo, omega_of((r + 1) as f64 * PI), max_relative = 1e-12);
            assert_relative_eq!(*hi, omega_of(EB_CLAMPED_CLAMPED[r]), max_relative = 1e-11);
        }
        // with tension the lower edges are still the pinned–pinned modes
        let line = PeriodicLine::new(195.0, 2e4, 1.35, 9.0, PeriodicSupport::Rigid).unwrap();
        let pp = crate::analytic::PinnedPinnedModes::new(195.0, 2e4, 1.35, 9.0).unwrap();
        let bands = line.pass_bands(pp.omega(5) * 0.999, 2000).unwrap();
        assert_eq!(bands.len(), 4, "{bands:?}");
        for (r, (lo, hi)) in bands.iter().enumerate() {
            assert_relative_eq!(*lo, pp.omega(r + 1), max_relative = 1e-12);
            assert!(*hi < pp.omega(r + 2));
        }
    }

    /// Hermite elements (MODEL §4) of N spans, `m` elements each, pinned
    /// ends, the line's supports at the interior span ends: the frequencies
    /// below `omega_max`, by a dense symmetric eigensolve.
    fn hermite_spans(line: &PeriodicLine, n_spans: usize, m: usize, omega_max: f64) -> Vec<f64> {
        let (ei, t, ra) = (line.ei, line.tension, line.rho_a);
        let n = n_spans * m;
        let h = line.spacing / m as f64;
        let dofs = 2 * (n + 1);
        let (mut k, mut mm) = crate::analytic::dense_fe::hermite_km(ei, t, ra, h, n);
        let mut removed = vec![0, 2 * n];
        for s in 1..n_spans {
            let v = 2 * s * m;
            match line.support {
                PeriodicSupport::Rigid => removed.push(v),
                PeriodicSupport::Elastic { k: ks, mass } => {
                    k[(v, v)] += ks;
                    mm[(v, v)] += mass;
                }
            }
        }
        let keep: Vec<usize> = (0..dofs).filter(|i| !removed.contains(i)).collect();
        let mut w = crate::analytic::dense_fe::frequencies(&k, &mm, &keep);
        w.retain(|w| *w <= omega_max);
        w
    }

    #[test]
    fn rigid_beam_spans_hold_n_frequencies_per_band() {
        let ei = 2e4 * 81.0 / 9.0; // μd = 3
        let line = PeriodicLine::new(ei, 2e4, 1.35, 9.0, PeriodicSupport::Rigid).unwrap();
        let pp = crate::analytic::PinnedPinnedModes::new(ei, 2e4, 1.35, 9.0).unwrap();
        let top = 0.5 * (pp.omega(2) + pp.omega(3)); // above the second band
        let bands = line.pass_bands(top, 3000).unwrap();
        assert_eq!(bands.len(), 2);
        let mut widest_gap = Vec::new();
        println!("  N   max rel. diff. FE vs L8   largest gap / band width");
        for n_spans in [2, 4, 8] {
            // samples unused for a beam on rigid supports (exact roots of L5)
            let exact = line.span_line_frequencies(n_spans, top, 2).unwrap();
            let fe = hermite_spans(&line, n_spans, 16, top);
            assert_eq!(exact.len(), 2 * n_spans);
            assert_eq!(fe.len(), exact.len(), "N = {n_spans}");
            let worst = fe
                .iter()
                .zip(&exact)
                .map(|(a, b)| (a / b - 1.0).abs())
                .fold(0.0, f64::max);
            // every frequency in a band, N of them in each
            let mut gap: f64 = 0.0;
            for (lo, hi) in &bands {
                let inside: Vec<f64> = exact
                    .iter()
                    .copied()
                    .filter(|w| *w >= lo * (1.0 - 1e-12) && *w <= hi * (1.0 + 1e-12))
                    .collect();
                assert_eq!(inside.len(), n_spans, "band [{lo}, {hi}]");
                for p in inside.windows(2) {
                    gap = gap.max((p[1] - p[0]) / (hi - lo));
                }
                gap = gap.max((hi - inside[n_spans - 1]) / (hi - lo));
            }
            println!("  {n_spans}   {worst:.2e}                  {gap:.3}");
            assert!(worst < FE_16, "N = {n_spans}: {worst}");
            widest_gap.push(gap);
        }
        // the frequencies fill the bands as N grows
        assert!(widest_gap[1] < 0.7 * widest_gap[0] && widest_gap[2] < 0.7 * widest_gap[1]);
    }

    /// Linear string elements (kinks allowed at the supports), N spans of `m`
    /// elements, pinned ends: the frequencies below `omega_max`.
    fn linear_string_spans(
        line: &PeriodicLine,
        n_spans: usize,
        m: usize,
        omega_max: f64,
    ) -> Vec<f64> {
        let n = n_spans * m;
        let h = line.spacing / m as f64;
        let mut k = DMatrix::<f64>::zeros(n + 1, n + 1);
        let mut mm = DMatrix::<f64>::zeros(n + 1, n + 1);
        for e in 0..n {
            for (a, b, kk, ms) in [
                (0, 0, 1.0, 2.0),
                (0, 1, -1.0, 1.0),
                (1, 0, -1.0, 1.0),
                (1, 1, 1.0, 2.0),
            ] {
                k[(e + a, e + b)] += line.tension / h * kk;
                mm[(e + a, e + b)] += line.rho_a * h / 6.0 * ms;
            }
        }
        if let PeriodicSupport::Elastic { k: ks, mass } = line.support {
            for s in 1..n_spans {
                k[(s * m, s * m)] += ks;
                mm[(s * m, s * m)] += mass;
            }
        }
        let keep: Vec<usize> = (1..n).collect();
        let k = k.select_rows(&keep).select_columns(&keep);
        let mm = mm.select_rows(&keep).select_columns(&keep);
        let linv = mm.cholesky().expect("M is SPD").l().try_inverse().unwrap();
        let a = &linv * k * linv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let mut w: Vec<f64> = SymmetricEigen::new(a)
            .eigenvalues
            .iter()
            .map(|l| l.max(0.0).sqrt())
            .filter(|w| *w <= omega_max)
            .collect();
        w.sort_by(f64::total_cmp);
        w
    }

    #[test]
    fn elastic_beam_spans_fall_in_the_pass_bands() {
        // springs with point masses (steady-arm-like supports), μd = 3
        let line = PeriodicLine::new(
            2e4 * 81.0 / 9.0,
            2e4,
            1.35,
            9.0,
            PeriodicSupport::Elastic { k: 5e5, mass: 2.0 },
        )
        .unwrap();
        let top = 250.0;
        let bands = line.pass_bands(top, 5000).unwrap();
        println!("  bands {bands:?}");
        assert!(bands.len() >= 2);
        for n_spans in [3, 6, 12] {
            let fe = hermite_spans(&line, n_spans, 16, top);
            for w in &fe {
                let inside = bands
                    .iter()
                    .any(|(lo, hi)| *w >= lo * (1.0 - FE_16) && *w <= hi * (1.0 + FE_16));
                assert!(inside, "N = {n_spans}: ω = {w} outside {bands:?}");
            }
            let counts: Vec<usize> = bands
                .iter()
                .map(|(lo, hi)| {
                    fe.iter()
                        .filter(|w| **w >= lo * (1.0 - FE_16) && **w <= hi * (1.0 + FE_16))
                        .count()
                })
                .collect();
            println!("  N = {n_spans}: frequencies per band {counts:?}");
        }
        // a wide stop band is not empty for nothing: a frequency placed in
        // it by hand fails the test above
        let (lo, hi) = (bands[0].1, bands[1].0);
        assert!(!line.passes(0.5 * (lo + hi)));
        // standing waves: at each frequency of N spans with pinned ends, one
        // root of L6 equals cos(jπ/N) for some j = 0 … N (support values
        // sin(njπ/N), mirror-symmetric cells); finer elements so that their
        // error, not L6's, sets the tolerance
        println!("  N   max over FE frequencies of min |cos qd − cos(jπ/N)|");
        for n_spans in [3, 6] {
            let fe = hermite_spans(&line, n_spans, 32, top);
            let mut worst: f64 = 0.0;
            for w in &fe {
                let best = line
                    .cos_qd(*w)
                    .iter()
                    .flat_map(|c| {
                        (0..=n_spans)
                            .map(move |j| (c - (j as f64 * PI / n_spans as f64).cos()).abs())
                    })
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(best);
            }
            println!("  {n_spans}   {worst:.2e}");
            assert!(worst < STANDING_FE, "N = {n_spans}: {worst}");
        }
    }

    #[test]
    fn string_on_elastic_supports_n_spans() {
        let line = string_elastic(5e4, 2.0);
        // just above the third band's upper edge, the span mode 3πc/d (the
        // fourth band starts ≈ 4·0.8·πc/d)
        let top = 3.0 * PI * (2e4_f64 / 1.35).sqrt() / 9.0 * 1.001;
        let bands = line.pass_bands(top, 3000).unwrap();
        assert_eq!(bands.len(), 3, "{bands:?}");
        println!("  N   max rel. diff. L8 vs linear FE (Richardson)   per band");
        for n_spans in [2, 3, 6] {
            let tp = line.span_line_frequencies(n_spans, top, 20_000).unwrap();
            // standing waves: L4 = cos(jπ/N) at each root, j = 1 … N (j = N
            // is the span mode, all supports at rest, cos qd = ±1)
            let mut per_band = vec![0; bands.len()];
            for w in &tp {
                let f = line.cos_qd(*w)[0];
                let j = (f.clamp(-1.0, 1.0).acos() * n_spans as f64 / PI).round();
                assert!(
                    (f - (j * PI / n_spans as f64).cos()).abs() < STANDING_WAVE,
                    "N = {n_spans}: ω = {w}, cos qd = {f}"
                );
                let b = bands
                    .iter()
                    .position(|(lo, hi)| *w >= lo * (1.0 - 1e-12) && *w <= hi * (1.0 + 1e-12))
                    .unwrap_or_else(|| panic!("ω = {w} outside the bands"));
                per_band[b] += 1;
            }
            // independent: linear elements, 64 and 128 per span, Richardson
            let (c, f) = (
                linear_string_spans(&line, n_spans, 64, top * 1.1),
                linear_string_spans(&line, n_spans, 128, top * 1.1),
            );
            let worst = tp
                .iter()
                .enumerate()
                .map(|(i, w)| {
                    let rich = (4.0 * f[i] * f[i] - c[i] * c[i]) / 3.0; // in ω², h² → h⁴
                    (rich.sqrt() / w - 1.0).abs()
                })
                .fold(0.0, f64::max);
            println!("  {n_spans}   {worst:.2e}                                   {per_band:?}");
            assert!(worst < FE_LINEAR, "N = {n_spans}: {worst}");
            assert_eq!(per_band, vec![n_spans; bands.len()], "N = {n_spans}");
        }
    }

    #[test]
    fn string_on_springs_matches_its_trace_and_the_beam_limit() {
        // L4 against the transfer matrix built and traced numerically
        let line = string_elastic(3e4, 1.5);
        let (t, d): (f64, f64) = (2e4, 9.0);
        for w in [5.0, 30.0, 77.0, 140.0] {
            let kappa = w * (1.35 / t).sqrt();
            let (sn, cs) = (kappa * d).sin_cos();
            let span = nalgebra::Matrix2::new(cs, sn / (t * kappa), -t * kappa * sn, cs);
            let point = nalgebra::Matrix2::new(1.0, 0.0, 3e4 - 1.5 * w * w, 1.0);
            let cell = point * span;
            assert_relative_eq!(cell.determinant(), 1.0, max_relative = 1e-12);
            assert_relative_eq!(line.cos_qd(w)[0], 0.5 * cell.trace(), max_relative = 1e-12);
            // a beam of bending length 1e-6·d on the same supports
            let lb = 1e-6 * d;
            let beam = PeriodicLine::new(
                t * lb * lb,
                t,
                1.35,
                d,
                PeriodicSupport::Elastic { k: 3e4, mass: 1.5 },
            )
            .unwrap();
            let f = line.cos_qd(w)[0];
            let near = beam
                .cos_qd(w)
                .iter()
                .map(|c| (c - f).abs())
                .fold(f64::INFINITY, f64::min);
            println!("  ω = {w}: |L6 (ℓb = 1e-6 d) − L4| = {near:.2e}");
            assert!(near < BEAM_TO_STRING, "ω = {w}: {near}");
        }
        // rigid string: the bands are the span modes, N-fold
        let rigid = PeriodicLine::new(0.0, t, 1.35, d, PeriodicSupport::Rigid).unwrap();
        let w1 = PI * (t / 1.35).sqrt() / d;
        assert_eq!(rigid.pass_bands(2.5 * w1, 10).unwrap().len(), 2);
        let f = rigid.span_line_frequencies(4, 2.5 * w1, 10).unwrap();
        assert_eq!(f.len(), 8);
        assert_relative_eq!(f[7], 2.0 * w1, max_relative = 1e-15);
    }
}
