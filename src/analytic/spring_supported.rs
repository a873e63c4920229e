//! Static deflection of a string or a pinned–pinned tensioned beam resting on
//! discrete vertical springs, under a point load (docs/lines.md
//! L1–L3): the independent reference for point attachments (MODEL §10) and
//! for the supports of a multi-span line, built before those features.
//!
//! Unit point load at `x = a` on the bare line of length L, pinned at both
//! ends (`EI v'''' − T v'' = δ(x − a)`, v positive up), for `x ≤ a`,
//! `b = L − a` (swap x and a for `x > a`; G is symmetric):
//!
//! ```text
//! (L1) string, EI = 0:         G(x, a) = x b / (T L)
//! (L2) tensioned beam, T > 0:  G(x, a) = [x b / L − sinh(μb) sinh(μx) / (μ sinh μL)] / T,
//!                              μ = sqrt(T/EI)
//!      bare beam, T = 0:       G(x, a) = b x (L² − b² − x²) / (6 EI L)
//! ```
//!
//! A spring `k_i` at `x_i` pushes back with `−f_i δ(x − x_i)`, `f_i = k_i v(x_i)`
//! (the spring's tension, N). Superposing point loads, `v(x) = P G(x, x_P) −
//! Σ_j f_j G(x, x_j)`; at each spring `f_i/k_i = v(x_i)`, so
//!
//! ```text
//! (L3) Σ_j [G(x_i, x_j) + δ_ij / k_i] f_j = P G(x_i, x_P),
//!      v(x) = P G(x, x_P) − Σ_j f_j G(x, x_j)
//! ```
//!
//! The matrix is symmetric positive definite (a Green's function of a
//! positive operator at distinct points, plus a non-negative diagonal) and is
//! solved by Cholesky. Writing it in compliances `1/k_i` lets `k_i = ∞` be a
//! rigid support (`v(x_i) = 0` exactly); `k → 0` leaves `f → 0`, the bare line.
//! How L2 is evaluated without overflow or cancellation: `MU_L_BARE`.

use nalgebra::{DMatrix, DVector};

use super::modes::{require_nonnegative, require_positive};
use crate::error::{Error, Result};

/// Below this μL the tensioned-beam form L2 is replaced by the bare beam
/// (T = 0): there the round-off of L2 (measured 7.9e-10 of the midspan
/// compliance at μL = 1e-3, growing like 1/(μL)²: ≈ 2e-8 here) and the
/// neglected tension ((μL)²/10 = 4e-9 relative at midspan) are both small.
///
/// **Cancellation in L2.** `sinh` overflows for μL > 710 and the ratio of
/// three of them loses nothing only if written as `e^{−μ(a − x)} s(μb) s(μx) /
/// s(μL)` with `s(u) = (1 − e^{−2u})/2 = −expm1(−2u)/2` (each factor in
/// [0, ½], no overflow at any μL). The remaining difference `x b/L − R/μ` is
/// benign for μL ≳ 1: at the load both terms are O(L) and O(1/μ). For μL → 0
/// the two terms agree to O((μL)²) and the difference carries a relative
/// round-off of about ε/(μL)² (times the spread of the two terms); below
/// `MU_L_BARE` the bare-beam form is used instead, whose relative error
/// there is (μL)²/10, so neither exceeds ≈ 2e-8 of the midspan compliance.
/// Near a support (`μx ≪ 1` and `μa ≪ 1`) the same cancellation costs
/// relative accuracy in a deflection that is itself small: the absolute error
/// stays ≲ ε·L/T.
pub(crate) const MU_L_BARE: f64 = 2e-4;

/// A vertical spring between the line at `x` and a fixed anchor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscreteSpring {
    /// Position x_i, m (strictly inside (0, L)).
    pub x: f64,
    /// Stiffness k_i, N/m (> 0; `f64::INFINITY` is a rigid support).
    pub k: f64,
}

/// A pinned–pinned string (EI = 0) or tensioned beam on discrete springs.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringSupportedLine {
    /// EI, N·m² (≥ 0; 0 is a string).
    pub ei: f64,
    /// T, N (≥ 0; > 0 for a string).
    pub tension: f64,
    /// L, m (> 0).
    pub length: f64,
    /// The springs, any number, at distinct positions.
    pub springs: Vec<DiscreteSpring>,
}

/// `s(u) = sinh(u) e^{−u} = (1 − e^{−2u})/2`, no overflow, no cancellation.
fn s(u: f64) -> f64 {
    -0.5 * (-2.0 * u).exp_m1()
}

impl SpringSupportedLine {
    /// Check the inputs: L > 0, EI ≥ 0, T ≥ 0 (T > 0 if EI = 0), every
    /// spring strictly inside the span with k > 0 (∞ allowed), no two springs
    /// at the same x.
    pub fn new(ei: f64, tension: f64, length: f64, springs: &[DiscreteSpring]) -> Result<Self> {
        require_positive("length", length, "m")?;
        require_nonnegative("ei", ei, "N·m²")?;
        require_nonnegative("tension", tension, "N")?;
        if ei == 0.0 && tension == 0.0 {
            return Err(Error::invalid(
                "tension",
                0.0,
                "a string (EI = 0) needs T > 0 (N)",
            ));
        }
        for (i, sp) in springs.iter().enumerate() {
            if !(sp.x > 0.0 && sp.x < length) {
                return Err(Error::invalid(
                    format!("springs[{i}].x"),
                    sp.x,
                    format!("must lie strictly inside (0, {length}) (m)"),
                ));
            }
            if sp.k.is_nan() || sp.k <= 0.0 {
                return Err(Error::invalid(
                    format!("springs[{i}].k"),
                    sp.k,
                    "must be > 0 (N/m; inf for a rigid support)",
                ));
            }
            if let Some(j) = springs[..i].iter().position(|o| o.x == sp.x) {
                return Err(Error::invalid(
                    format!("springs[{i}].x"),
                    sp.x,
                    format!("must differ from springs[{j}].x (one spring per point)"),
                ));
            }
        }
        Ok(SpringSupportedLine {
            ei,
            tension,
            length,
            springs: springs.to_vec(),
        })
    }

    /// μ = sqrt(T/EI), 1/m (∞ for a string).
    pub fn mu(&self) -> f64 {
        if self.ei == 0.0 {
            f64::INFINITY
        } else {
            (self.tension / self.ei).sqrt()
        }
    }

    /// The bare line's Green's function G(x, a), m/N: deflection at `x`
    /// under a unit upward load at `a` (L1, L2; both in [0, L]).
    pub fn green(&self, x: f64, a: f64) -> f64 {
        let l = self.length;
        let (x, a) = if x <= a { (x, a) } else { (a, x) };
        let b = l - a;
        if self.ei == 0.0 {
            return x * b / (self.tension * l);
        }
        let mu = self.mu();
        if mu * l < MU_L_BARE {
            return b * x * (l * l - b * b - x * x) / (6.0 * self.ei * l);
        }
        let ratio = (-mu * (a - x)).exp() * s(mu * b) * s(mu * x) / s(mu * l);
        (x * b / l - ratio / mu) / self.tension
    }

    /// The spring tensions f_i = k_i v(x_i), N, under a point load `p`
    /// (N, positive up) at `xp` (L3), in the order of `springs`.
    pub fn spring_forces(&self, p: f64, xp: f64) -> Result<Vec<f64>> {
        if !p.is_finite() {
            return Err(Error::invalid("p", p, "must be finite (N)"));
        }
        if !(0.0..=self.length).contains(&xp) {
            return Err(Error::invalid(
                "xp",
                xp,
                format!("must lie in [0, {}] (m)", self.length),
            ));
        }
        let n = self.springs.len();
        if n == 0 {
            return Ok(Vec::new());
        }
        let g = DMatrix::from_fn(n, n, |i, j| {
            let c = if i == j { 1.0 / self.springs[i].k } else { 0.0 };
            self.green(self.springs[i].x, self.springs[j].x) + c
        });
        let rhs = DVector::from_fn(n, |i, _| p * self.green(self.springs[i].x, xp));
        let chol = g.cholesky().ok_or_else(|| {
            Error::invalid(
                "springs",
                n,
                "gave a singular system (springs too close for double precision)",
            )
        })?;
        Ok(chol.solve(&rhs).iter().copied().collect())
    }

    /// Deflection v(x), m, under a point load `p` (N, up) at `xp` (L3).
    pub fn deflection(&self, p: f64, xp: f64, x: f64) -> Result<f64> {
        let f = self.spring_forces(p, xp)?;
        Ok(self.deflection_with(p, xp, &f, x))
    }

    /// v(x) from already solved spring tensions `f` (L3, second line).
    pub fn deflection_with(&self, p: f64, xp: f64, f: &[f64], x: f64) -> f64 {
        p * self.green(x, xp)
            - self
                .springs
                .iter()
                .zip(f)
                .map(|(sp, fj)| fj * self.green(x, sp.x))
                .sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::StaticPointLoad;
    use crate::scene::Support;
    use approx::assert_relative_eq;

    /// Closed forms against the 8×8 LU of [`StaticPointLoad`] (a different
    /// basis and solve): round-off of both, amplified by the cancellation of
    /// L2 near the supports (module docs).
    const CLOSED_FORM: f64 = 1e-9;
    /// Finite differences (h² accurate: observed order 2.00) after one
    /// Richardson step on the two finer levels: the remainder (h⁴ and the FD
    /// solve's round-off, which grows like n⁴ when bending dominates),
    /// measured ≤ 1.4e-8 of v(x_P); a wrong term in L3 shows up at O(1).
    const FD_RICHARDSON: f64 = 1e-7;
    /// The observed FD order over one halving, 2 ± this (measured within 0.05).
    const FD_ORDER: f64 = 0.2;
    /// L2's round-off at μL = 1e-3, relative to the midspan compliance:
    /// ε/(μL)² ≈ 2e-10 times the spread of its two terms (measured 8e-10).
    const SMALL_MU_ROUND_OFF: f64 = 3e-9;
    /// The beam on springs differs from the string by O(ℓb/L): the bending
    /// layers (width ℓb) at the load and at each spring; this many ℓb/L
    /// (measured 4.12 ℓb/L at the load, from ℓb/L = 1e-2 to 1e-5).
    const BEAM_TO_STRING: f64 = 5.0;
    /// A spring of k = 1e-12 T/L changes the deflection by O(1e-12): round-off
    /// above that.
    const SOFT_LIMIT: f64 = 1e-10;

    fn sp(x: f64, k: f64) -> DiscreteSpring {
        DiscreteSpring { x, k }
    }

    #[test]
    fn validation_names_the_field() {
        let e =
            SpringSupportedLine::new(1.0, 1.0, 10.0, &[sp(3.0, 1.0), sp(10.0, 1.0)]).unwrap_err();
        assert!(e.to_string().contains("springs[1].x"), "{e}");
        let e = SpringSupportedLine::new(1.0, 1.0, 10.0, &[sp(3.0, 0.0)]).unwrap_err();
        assert!(e.to_string().contains("springs[0].k"), "{e}");
        let e =
            SpringSupportedLine::new(1.0, 1.0, 10.0, &[sp(3.0, 1.0), sp(3.0, 2.0)]).unwrap_err();
        assert!(e.to_string().contains("springs[1].x"), "{e}");
        let e = SpringSupportedLine::new(0.0, 0.0, 10.0, &[]).unwrap_err();
        assert!(e.to_string().contains("tension"), "{e}");
        let e = SpringSupportedLine::new(-1.0, 1.0, 10.0, &[]).unwrap_err();
        assert!(e.to_string().contains("`ei`"), "{e}");
        let line = SpringSupportedLine::new(1.0, 1.0, 10.0, &[sp(3.0, 1.0)]).unwrap();
        let e = line.spring_forces(1.0, 11.0).unwrap_err();
        assert!(e.to_string().contains("xp"), "{e}");
        assert!(line.spring_forces(f64::NAN, 1.0).is_err());
    }

    #[test]
    fn green_matches_the_static_point_load_from_mu_l_1_to_1e3() {
        let (t, l) = (2e4, 50.0);
        // relative to the local deflection under the load (`local`), or to
        // the midspan compliance (the scale of L3's matrix)
        let worst_of = |line: &SpringSupportedLine, reference: &StaticPointLoad, local: bool| {
            let mut worst: f64 = 0.0;
            for a in [0.3, 5.0, 17.0, 25.0, 49.0] {
                let scale = if local {
                    reference.deflection(a, a).abs()
                } else {
                    reference.deflection(l / 2.0, l / 2.0).abs()
                };
                for x in [0.1, 4.0, 17.0, 30.0, 49.9] {
                    let d = (line.green(x, a) - reference.deflection(a, x)).abs() / scale;
                    worst = worst.max(d);
                }
            }
            worst
        };
        println!("  μL       max rel. diff. of G against StaticPointLoad");
        for mu_l in [1.0, 10.0, 100.0, 1e3] {
            let mu: f64 = mu_l / l;
            let ei = t / (mu * mu);
            let line = SpringSupportedLine::new(ei, t, l, &[]).unwrap();
            let reference =
                StaticPointLoad::new(ei, t, l, Support::Pinned, Support::Pinned).unwrap();
            let worst = worst_of(&line, &reference, true);
            println!("  {mu_l:<8.0e} {worst:.2e}");
            assert!(worst < CLOSED_FORM, "μL = {mu_l}: {worst}");
        }
        // small μL: StaticPointLoad's exponential basis degenerates there, so
        // L2 is held against the bare beam (T = 0, polynomial basis), from
        // which it differs by the tension's O((μL)²) share. Relative to the
        // midspan compliance: near a support both terms of L2 are O(x) and
        // their difference carries ε·x/T (module docs)
        println!("  μL       rel. diff. against the bare beam   / (μL)²");
        let mut shares = Vec::new();
        for mu_l in [1e-1, 1e-2, 1e-3] {
            let ei = 7.0;
            let t = ei * (mu_l / l) * (mu_l / l);
            let line = SpringSupportedLine::new(ei, t, l, &[]).unwrap();
            let bare = StaticPointLoad::new(ei, 0.0, l, Support::Pinned, Support::Pinned).unwrap();
            let worst = worst_of(&line, &bare, false);
            println!(
                "  {mu_l:<8.0e} {worst:.3e}                        {:.6}",
                worst / (mu_l * mu_l)
            );
            shares.push(worst / (mu_l * mu_l));
        }
        // the difference is the tension's share, (μL)²/10 at midspan (series
        // of L2), O((μL)⁴) next: its coefficient settles as μL falls ...
        assert!(
            shares.iter().all(|s| *s > 0.05 && *s < 0.1 + 1e-3),
            "{shares:?}"
        );
        assert!((shares[1] / shares[0] - 1.0).abs() < 0.01, "{shares:?}");
        // ... until round-off, ε/(μL)² times L2's spread, shows at μL = 1e-3
        let residual = (shares[2] - shares[1]).abs() * 1e-6;
        println!("  implied round-off of L2 at μL = 1e-3: {residual:.1e} of the compliance");
        assert!(residual < SMALL_MU_ROUND_OFF, "{residual}");
    }

    #[test]
    fn bare_beam_switch_is_continuous() {
        // L2 just above MU_L_BARE against the bare-beam form just below it
        let (ei, l) = (5.0, 3.0);
        let t_at = |mu_l: f64| ei * (mu_l / l).powi(2);
        let above = SpringSupportedLine::new(ei, t_at(MU_L_BARE * 1.001), l, &[]).unwrap();
        let below = SpringSupportedLine::new(ei, t_at(MU_L_BARE * 0.999), l, &[]).unwrap();
        let bare = SpringSupportedLine::new(ei, 0.0, l, &[]).unwrap();
        for (x, a) in [(1.0, 2.0), (1.5, 1.5), (0.2, 2.9)] {
            assert_relative_eq!(above.green(x, a), below.green(x, a), max_relative = 1e-7);
            assert_relative_eq!(below.green(x, a), bare.green(x, a), max_relative = 0.0);
        }
        // the bare beam itself: simply supported midspan PL³/48EI
        assert_relative_eq!(
            bare.green(1.5, 1.5),
            27.0 / (48.0 * ei),
            max_relative = 1e-14
        );
    }

    /// Finite differences of `EI v'''' − T v'' + Σ k_i δ v = P δ` on `n`
    /// intervals (pinned: v = 0 and a mirrored ghost node), springs and load
    /// at nodes (δ → 1/h); a rigid support is a removed unknown. Solved by
    /// banded Gaussian elimination (the matrix is symmetric positive definite).
    fn finite_differences(line: &SpringSupportedLine, n: usize, p: f64, xp: f64) -> Vec<f64> {
        let (l, ei, t) = (line.length, line.ei, line.tension);
        let h = l / n as f64;
        let node = |x: f64| {
            let i = (x / h).round() as usize;
            assert!((i as f64 * h - x).abs() < 1e-9 * l, "x = {x} is not a node");
            i
        };
        // unknowns v_1 … v_{n−1}; rows as a dense band of half-width 2
        let m = n - 1;
        let mut band = vec![[0.0_f64; 5]; m]; // band[i][2 + j − i]
        let mut rhs = vec![0.0; m];
        let (c4, c2) = (ei / h.powi(4), t / (h * h));
        for i in 0..m {
            band[i][2] = 6.0 * c4 + 2.0 * c2;
            if i >= 1 {
                band[i][1] = -4.0 * c4 - c2;
            }
            if i + 1 < m {
                band[i][3] = -4.0 * c4 - c2;
            }
            if i >= 2 {
                band[i][0] = c4;
            }
            if i + 2 < m {
                band[i][4] = c4;
            }
        }
        // pinned ends: ghost v_{−1} = −v_1, v_{n+1} = −v_{n−1}
        band[0][2] -= c4;
        band[m - 1][2] -= c4;
        rhs[node(xp) - 1] += p / h;
        for s in &line.springs {
            let i = node(s.x) - 1;
            if s.k.is_infinite() {
                band[i] = [0.0, 0.0, 1.0, 0.0, 0.0];
                rhs[i] = 0.0;
                for (d, r) in [(1usize, 1usize), (2, 0)] {
                    if i >= d {
                        band[i - d][2 + d] = 0.0;
                    }
                    if i + d < m {
                        band[i + d][r] = 0.0;
                    }
                }
            } else {
                band[i][2] += s.k / h;
            }
        }
        // forward elimination
        for i in 0..m {
            let piv = band[i][2];
            for d in 1..=2 {
                if i + d >= m {
                    break;
                }
                let f = band[i + d][2 - d] / piv;
                if f == 0.0 {
                    continue;
                }
                for j in 0..=2 {
                    // row i + d, column i + j: band index 2 + (i + j) − (i + d)
                    band[i + d][2 + j - d] -= f * band[i][2 + j];
                }
                rhs[i + d] -= f * rhs[i];
            }
        }
        let mut v = vec![0.0; m];
        for i in (0..m).rev() {
            let mut r = rhs[i];
            for j in 1..=2 {
                if i + j < m {
                    r -= band[i][2 + j] * v[i + j];
                }
            }
            v[i] = r / band[i][2];
        }
        let mut full = vec![0.0];
        full.extend(v);
        full.push(0.0);
        full
    }

    #[test]
    fn springs_and_supports_match_finite_differences() {
        // L = 12 m: nodes of n = 240 · 2^i hit every position below. Three
        // levels per μL: fine enough that h resolves the bending length
        // (μh ≤ 0.1 on the finest), coarse enough that the FD round-off
        // (growing like n⁴ when bending dominates) stays below the h⁴ term
        let (t, l, p, xp) = (2e4, 12.0, 150.0, 5.0);
        let springs = [
            sp(2.0, 5e3),
            sp(4.0, 2e5),
            sp(7.0, f64::INFINITY),
            sp(9.5, 1e4),
        ];
        let probes = [1.0, 2.0, 4.0, 5.0, 7.0, 8.0, 9.5, 11.0];
        println!("  μL     n₀    max rel. error of FD at n₀, 2n₀, 4n₀   order   Richardson ×1, ×2");
        let mut failures = Vec::new();
        for (mu_l, n0) in [(1.0, 120), (10.0, 240), (100.0, 960)] {
            let mu: f64 = mu_l / l;
            let line = SpringSupportedLine::new(t / (mu * mu), t, l, &springs).unwrap();
            let f = line.spring_forces(p, xp).unwrap();
            let scale = line.deflection_with(p, xp, &f, xp).abs();
            let exact: Vec<f64> = probes
                .iter()
                .map(|x| line.deflection_with(p, xp, &f, *x))
                .collect();
            let at = |fd: &[f64], n: usize| -> Vec<f64> {
                probes
                    .iter()
                    .map(|x| fd[(x * n as f64 / l).round() as usize])
                    .collect()
            };
            let levels: Vec<Vec<f64>> = [n0, 2 * n0, 4 * n0]
                .iter()
                .map(|&n| at(&finite_differences(&line, n, p, xp), n))
                .collect();
            let err = |v: &[f64]| {
                v.iter()
                    .zip(&exact)
                    .map(|(a, b)| (a - b).abs() / scale)
                    .fold(0.0, f64::max)
            };
            let errs: Vec<f64> = levels.iter().map(|v| err(v)).collect();
            let order = crate::study::uncertainty::observed_order(errs[1], errs[2], 2.0);
            // Richardson on the two finer levels (h⁴ left), then on all
            // three (h⁶ left, if the expansion holds)
            let r1 = |c: &[f64], fi: &[f64]| -> Vec<f64> {
                c.iter().zip(fi).map(|(c, f)| (4.0 * f - c) / 3.0).collect()
            };
            let (ra, rb) = (r1(&levels[0], &levels[1]), r1(&levels[1], &levels[2]));
            let rich2: Vec<f64> = ra
                .iter()
                .zip(&rb)
                .map(|(c, f)| (16.0 * f - c) / 15.0)
                .collect();
            let (rich, rich2) = (err(&rb), err(&rich2));
            let rich_order = crate::study::uncertainty::observed_order(err(&ra), rich, 2.0);
            println!(
                "  {mu_l:<6} {n0:<5} {:.2e}  {:.2e}  {:.2e}          {order:.2}    {rich:.2e}  {rich2:.2e}  (order {rich_order:.2})",
                errs[0], errs[1], errs[2]
            );
            // FD is second order: the error falls 4× per halving ...
            if (order - 2.0).abs() >= FD_ORDER {
                failures.push(format!("μL = {mu_l}: order {order}"));
            }
            // ... and Richardson leaves the h⁴ remainder
            if rich >= FD_RICHARDSON {
                failures.push(format!("μL = {mu_l}: Richardson {rich}"));
            }
            // the rigid support holds exactly
            assert!(line.deflection_with(p, xp, &f, 7.0).abs() < 1e-15 * scale);
        }
        assert!(failures.is_empty(), "{failures:?}");
    }

    #[test]
    fn string_with_springs_matches_finite_differences_exactly() {
        // the string's FD solution is exact at the nodes (piecewise linear)
        let (t, l, p, xp) = (1e3, 10.0, 20.0, 3.0);
        let springs = [sp(1.0, 300.0), sp(6.0, 50.0), sp(8.0, f64::INFINITY)];
        let line = SpringSupportedLine::new(0.0, t, l, &springs).unwrap();
        let f = line.spring_forces(p, xp).unwrap();
        let fd = finite_differences(&line, 100, p, xp);
        for (i, v) in fd.iter().enumerate() {
            let x = i as f64 * 0.1;
            assert!(
                (line.deflection_with(p, xp, &f, x) - v).abs() < 1e-12 * fd[30],
                "x = {x}"
            );
        }
        // spring tensions balance the load with the end reactions:
        // ΣF = P − Σf − T v'(0) + T v'(L) = 0
        let slope = |x0: f64, x1: f64| {
            (line.deflection_with(p, xp, &f, x1) - line.deflection_with(p, xp, &f, x0)) / (x1 - x0)
        };
        let ends = t * slope(0.0, 0.5) - t * slope(9.5, 10.0);
        let sum_f: f64 = f.iter().sum();
        assert_relative_eq!(p, sum_f + ends, max_relative = 1e-12);
    }

    #[test]
    fn soft_springs_leave_the_bare_line_and_stiff_ones_make_a_support() {
        let (ei, t, l, p, xp) = (195.0, 2e4, 50.0, 100.0, 20.0);
        let bare = SpringSupportedLine::new(ei, t, l, &[]).unwrap();
        let soft = [sp(10.0, 1e-12 * t / l), sp(30.0, 1e-12 * t / l)];
        let line = SpringSupportedLine::new(ei, t, l, &soft).unwrap();
        for x in [5.0, 20.0, 40.0] {
            assert_relative_eq!(
                line.deflection(p, xp, x).unwrap(),
                p * bare.green(x, xp),
                max_relative = SOFT_LIMIT
            );
        }
        // k → ∞ tends to the rigid support at rate 1/k; the string's rigid
        // support splits it into two strings: v(a) = P a (x_s − a)/(T x_s)
        let string_at = |k: f64| {
            SpringSupportedLine::new(0.0, t, l, &[sp(30.0, k)])
                .unwrap()
                .deflection(p, xp, xp)
                .unwrap()
        };
        let split = p * xp * (30.0 - xp) / (t * 30.0);
        assert_relative_eq!(string_at(f64::INFINITY), split, max_relative = 1e-13);
        let (e1, e2) = (string_at(1e8) - split, string_at(1e9) - split);
        assert!(e1 > 0.0 && e2 > 0.0);
        assert_relative_eq!(e1 / e2, 10.0, max_relative = 1e-3);
    }

    #[test]
    fn beam_on_springs_tends_to_the_string_as_ei_vanishes() {
        // bending length ℓb = sqrt(EI/T): the beam differs from the string by
        // O(ℓb/L) (the ℓb-wide boundary layers at load and springs)
        let (t, l, p, xp) = (2e4, 50.0, 100.0, 22.0);
        let springs = [sp(10.0, 3e3), sp(35.0, 1e4), sp(41.0, f64::INFINITY)];
        let string = SpringSupportedLine::new(0.0, t, l, &springs).unwrap();
        let vs = string.deflection(p, xp, xp).unwrap();
        let mut prev = f64::INFINITY;
        for lb_over_l in [1e-2, 1e-3, 1e-4, 1e-5] {
            let lb = lb_over_l * l;
            let beam = SpringSupportedLine::new(t * lb * lb, t, l, &springs).unwrap();
            let rel = (beam.deflection(p, xp, xp).unwrap() - vs).abs() / vs;
            println!("  ℓb/L = {lb_over_l:.0e}: |v_beam − v_string|/v_string at x_P = {rel:.2e}");
            assert!(
                rel < BEAM_TO_STRING * lb_over_l,
                "ℓb/L = {lb_over_l}: {rel}"
            );
            assert!(rel < prev / 5.0, "not converging: {rel} after {prev}");
            prev = rel;
        }
    }

    #[test]
    fn maxwell_betti_with_springs() {
        // reciprocity survives the springs: v(x | load at a) = v(a | load at x)
        let springs = [sp(4.0, 2e3), sp(13.0, f64::INFINITY), sp(17.0, 5e4)];
        let line = SpringSupportedLine::new(30.0, 5e3, 20.0, &springs).unwrap();
        let (x, a) = (3.0, 15.5);
        assert_relative_eq!(
            line.deflection(1.0, a, x).unwrap(),
            line.deflection(1.0, x, a).unwrap(),
            max_relative = 1e-11
        );
    }
}
