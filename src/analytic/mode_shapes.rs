//! Exact eigenfunctions of the continuous tensioned beam (MODEL §1, §9.2): the
//! basis of the `[mesh] kind = "galerkin"` discretization. No finite elements
//! anywhere on this path: it is an independent discretization to hold the FE
//! answers against.
//!
//! `ρA φ ω² = EI φ'''' − T φ''` on `0 ≤ x ≤ L` has the solutions
//! `φ = A cosh αx + B sinh αx + C cos βx + D sin βx` with (as in
//! [`super::modes`]) `α² = β² + T/EI`, `ω = sqrt(EI/ρA) α β`. On a tensioned
//! span `αL` is in the hundreds already for mode 1, so `cosh αL` overflows
//! (and, before that, `cosh αx − sinh αx` cancels). Every shape here is
//! therefore written in the **stable form**
//!
//! ```text
//! φ(x) = P e^{−αx} + Q e^{−α(L−x)} + C cos βx + D sin βx,
//! ```
//!
//! with `|P|, |Q|, |C|, |D| ≤ 2` before normalization: each term is O(1) on the
//! whole span, the boundary layers of width `1/α` at either end are carried by
//! the decaying exponentials, and `E = e^{−αL}` (which may underflow to 0,
//! harmlessly) is the only coupling between the ends. The supports' shapes
//! and characteristic equations (one bracketed root per interval, bisected
//! to round-off) are derived on `Ends`; normalization and loads are closed
//! form (`Stable::integral_of_square`); [`MAX_MODES`] bounds the phase error.
//! A free end, or a string with a clamped end (MODEL §1), has no basis here:
//! both are refused naming `mesh.kind`.

use super::modes::{ClampedPinnedModes, PinnedPinnedModes};
use crate::error::{Error, Result};
use crate::scene::{BeamProps, Support};
use std::f64::consts::PI;

/// Largest basis accepted.
///
/// The root β_J is found to a relative round-off `ε`,
/// so the phase `β_J x` of the oscillating part carries an absolute error up
/// to `ε β_J L ≈ ε J π` (and the argument reduction of `sin`/`cos` as much
/// again): `≈ 1.4·10⁻¹²` at J = 1000 and `≈ 5.6·10⁻¹²` at J = 4000, which
/// keeps every shape, slope/β and curvature/β² within ~10⁻¹¹ of its size.
/// 4000 modes resolve half-wavelengths `L/4000` (1.25 cm on the 50 m
/// reference span, finer than its 1600-element refined Hermite meshes),
/// enough for `modal_exact` to refine J past J = 1000 (`sweep
/// --check-refinement` doubles it, `run --tolerance` quadruples it). At O(J)
/// transcendental calls per evaluation such a basis is slow on this
/// direct path; `modal_exact` evaluates it without them
/// ([`super::FastShapes`]).
pub const MAX_MODES: usize = 4000;

/// Largest `T L²/EI` (the square of the clamped ends' boundary-layer
/// parameter μL) the basis takes with a clamped end: curvatures carry
/// α² ≈ T/EI times O(1) coefficients, and products of α² with the modal
/// coordinates must stay far from f64's 1.8e308. Below it every root is
/// found to round-off (`ClampedPinnedModes::phase`: tested down to
/// EI = 10⁻¹⁰⁰ N·m² on the reference span, T L²/EI ≈ 10¹⁰⁸).
pub(crate) const MAX_MU_L_SQUARED: f64 = 1e200;

/// Which supported end pair the basis is for.
///
/// Writing `E = e^{−αL}`, `r = β/α`, `ℓ = L/2`:
///
/// - **pinned–pinned** (`EI ≥ 0`, the string included): `φ_j = sqrt(2/(ρA L))
///   sin(jπx/L)`, `ω_j` from [`PinnedPinnedModes`] (`jπc/L` for a string).
/// - **clamped (0) – pinned (L)**: `v(L) = v''(L) = 0` give `Q = −P E` and
///   `C cos βL + D sin βL = 0`; `v(0) = v'(0) = 0` then give `C = −P(1 − E²)`,
///   `D = P (α/β)(1 + E²)`, and the characteristic equation of
///   [`ClampedPinnedModes`] (`α sin βL − β tanh(αL) cos βL = 0`, its module doc
///   proves one root per `βL ∈ [jπ, jπ + π/2)`). With `P = r`:
///   `φ = r e^{−αx} − r E e^{−α(L−x)} − r(1 − E²) cos βx + (1 + E²) sin βx`.
/// - **pinned (0) – clamped (L)**: the mirror image, `φ_PC(x) = φ_CP(L − x)`,
///   same frequencies.
/// - **clamped–clamped**: symmetric about `x = ℓ`, so every mode is even or odd
///   in `y = x − ℓ`.
///   - *odd* `φ = b sinh αy + d sin βy`: `φ(ℓ) = φ'(ℓ) = 0` ⇔
///     `α sin βℓ − β tanh(αℓ) cos βℓ = 0`, which is exactly the clamped–pinned
///     equation for a span `ℓ` (an odd mode has `φ = φ'' = 0` at mid-span: it
///     *is* a clamped–pinned mode of the half span). Its roots are
///     [`ClampedPinnedModes`] of length `ℓ`: one per `βℓ ∈ [kπ, kπ + π/2)`,
///     k ≥ 1. Stable form with `d = 1`:
///     `φ = sin β(x − ℓ) + sin βℓ (e^{−αx} − e^{−α(L−x)})/(1 − E)`.
///   - *even* `φ = a cosh αy + c cos βy`: `a cosh αℓ + c cos βℓ = 0`,
///     `a α sinh αℓ − c β sin βℓ = 0`, determinant over `cosh αℓ`:
///
///     ```text
///     g(β) = [β sin βℓ + α tanh(αℓ) cos βℓ] / sqrt(α² + β²) = 0
///          ⇔ tan(βℓ − π/2) = s(β) := β coth(αℓ)/α  (> 0).
///     ```
///
///     *Bracketing.* With `z = βℓ − π/2`, `tan z < 0 < s` on every
///     `z ∈ (kπ − π/2, kπ)` (and on `βℓ ∈ (0, π/2)`): no roots there. On
///     `z ∈ [kπ, kπ + π/2)`, k ≥ 0, `tan z` rises from 0 to +∞ with
///     `d/dβ tan z ≥ ℓ`, while `s' = (T/EI) coth(αℓ)/α³ − (β/α)² ℓ csch²(αℓ)
///     ≤ coth(αℓ)/α`, and `coth(αℓ)/α < ℓ ⇔ αℓ tanh αℓ > 1 ⇔ αℓ > 1.1997`,
///     true since `αℓ ≥ βℓ ≥ π/2`. So `tan z − s` rises strictly from `−s < 0`
///     to +∞: exactly one root per `βℓ ∈ [kπ + π/2, kπ + π)`, bisected to
///     round-off. (`T = 0`: `cos βL cosh βL = 1`, βL = 4.7300, 10.9956, ….)
///     Stable form with `c = 1`:
///     `φ = cos β(x − ℓ) − cos βℓ (e^{−αx} + e^{−α(L−x)})/(1 + E)`.
///   - Together, in `βL = 2βℓ`: mode `n ≥ 1` has `βL ∈ [nπ, (n + 1)π)`, even
///     for odd n, odd for even n; the intervals are disjoint and ordered and
///     `ω(β)` increases, so this numbering is the ascending order of ω.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Ends {
    PinnedPinned,
    ClampedPinned,
    /// Evaluated as clamped–pinned at `L − x`.
    PinnedClamped,
    ClampedClamped,
}

/// One mode in the stable form `P e^{−αs} + Q e^{−α(L−s)} + C cos βs + D sin βs`
/// (`s = x`, or `L − x` for a mirrored basis), coefficients mass-normalized.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Stable {
    pub(super) alpha: f64,
    pub(super) beta: f64,
    pub(super) p: f64,
    pub(super) q: f64,
    pub(super) c: f64,
    pub(super) d: f64,
}

impl Stable {
    /// `∫₀ᴸ φ² dx` and `∫₀ᴸ φ dx` of the stable form are sums of elementary
    /// integrals (`∫ e^{−2αx}`, `∫ e^{−αx} cos βx`, `∫ cos² βx`, …; see
    /// `Stable::integral_of_square`), each evaluated without overflow and
    /// without cancellation beyond a few ulps (the result ≈ L/2 is dominated by
    /// the positive `cos²`/`sin²` terms; the exponential cross terms are
    /// O(1/α)). This is exact, costs O(1) per mode, and needs no argument about
    /// resolving the boundary layer. The tests check it against an independent
    /// composite Gauss–Legendre quadrature that does resolve it.
    ///
    /// `∫₀ᴸ φ² ds`, m (closed form).
    fn integral_of_square(&self, l: f64) -> f64 {
        let Stable {
            alpha: a,
            beta: b,
            p,
            q,
            c,
            d,
        } = *self;
        let (sl, cl) = (b * l).sin_cos();
        // sin²/cos² of βs over the span
        let s2 = (2.0 * b * l).sin() / (4.0 * b);
        let cc = 0.5 * l + s2;
        let ss = 0.5 * l - s2;
        let cs = sl * sl / (2.0 * b);
        let trig = c * c * cc + d * d * ss + 2.0 * c * d * cs;
        if p == 0.0 && q == 0.0 {
            return trig;
        }
        let e = (-a * l).exp();
        // ∫ e^{−2αs} = ∫ e^{−2α(L−s)} = (1 − E²)/(2α); ∫ e^{−αs} e^{−α(L−s)} = L E
        let uu = -(-2.0 * a * l).exp_m1() / (2.0 * a);
        let uw = l * e;
        // ∫ e^{−αs} cos βs, ∫ e^{−αs} sin βs
        let k2 = a * a + b * b;
        let ic = (a - e * (a * cl - b * sl)) / k2;
        let is = (b - e * (a * sl + b * cl)) / k2;
        // ∫ e^{−α(L−s)} cos βs, … (s → L − s)
        let wc = cl * ic + sl * is;
        let ws = sl * ic - cl * is;
        p * p * uu
            + q * q * uu
            + 2.0 * p * q * uw
            + 2.0 * p * (c * ic + d * is)
            + 2.0 * q * (c * wc + d * ws)
            + trig
    }

    /// `∫₀ᴸ φ ds`, m (closed form).
    fn integral(&self, l: f64) -> f64 {
        let (sl, cl) = (self.beta * l).sin_cos();
        let trig = self.c * sl / self.beta + self.d * (1.0 - cl) / self.beta;
        if self.p == 0.0 && self.q == 0.0 {
            return trig;
        }
        let ends = -(-self.alpha * l).exp_m1() / self.alpha;
        (self.p + self.q) * ends + trig
    }

    fn scaled(self, f: f64) -> Self {
        Stable {
            p: self.p * f,
            q: self.q * f,
            c: self.c * f,
            d: self.d * f,
            ..self
        }
    }
}

/// The first J exact eigenfunctions of the tensioned beam on its supports
/// (the stable form of the module docs), mass-normalized: `∫ ρA φ_i φ_j dx = δ_ij`, so the modal
/// mass is the identity and the modal stiffness `diag(ω_j²)`.
///
/// Units: `φ` in kg^{−1/2} (so `φ_j(x) q_j` is metres when the modal
/// coordinate `q_j` is in m·kg^{1/2}), slopes per metre, curvatures per m².
/// Evaluation points are clamped to `[0, L]`. Signs are as the stable forms
/// of each support pair give them (pinned–pinned: `+sin`); nothing else is
/// promised about them.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShapes {
    length: f64,
    ends: Ends,
    omega: Vec<f64>,
    modes: Vec<Stable>,
    /// `∫ φ_j dx`, m·kg^{−1/2}.
    load: Vec<f64>,
}

impl ModeShapes {
    /// The J = `count` lowest exact modes for the beam's supports;
    /// mass-normalized: `∫ρA φ_i φ_j dx = δ_ij`.
    ///
    /// Allowed: EI > 0 with each end clamped or pinned; EI = 0 (a string) with
    /// both ends pinned; `1 ≤ count ≤` [`MAX_MODES`].
    pub fn new(props: &BeamProps, count: usize) -> Result<Self> {
        if count == 0 || count > MAX_MODES {
            return Err(Error::invalid(
                "mesh.modes",
                count,
                format!(
                    "the galerkin basis needs 1 … {MAX_MODES} modes (beyond that the \
                     eigenfunctions' phase loses accuracy)"
                ),
            ));
        }
        let (l, ei, t, ra) = (props.length, props.ei, props.tension, props.rho_a);
        let string = ei == 0.0;
        let ends = match (props.left, props.right) {
            (Support::Pinned, Support::Pinned) => Ends::PinnedPinned,
            (Support::Clamped, Support::Pinned) if !string => Ends::ClampedPinned,
            (Support::Pinned, Support::Clamped) if !string => Ends::PinnedClamped,
            (Support::Clamped, Support::Clamped) if !string => Ends::ClampedClamped,
            (left, right) => {
                let name = |s: Support| format!("{s:?}").to_lowercase();
                return Err(Error::invalid(
                    "mesh.kind",
                    format!(
                        "galerkin (beam.left = {}, beam.right = {}{})",
                        name(left),
                        name(right),
                        if string { ", EI = 0" } else { "" }
                    ),
                    "the galerkin basis needs each end clamped or pinned when EI > 0, and \
                     both ends pinned for a string (EI = 0); a free end is not supported: \
                     use kind = \"hermite\"",
                ));
            }
        };
        // the boundary layers of clamped ends are 1/α ≈ sqrt(EI/T) wide:
        // curvatures carry α² = T/EI, which must stay finite
        let mu_l_sq = t / ei * l * l;
        if ends != Ends::PinnedPinned && (mu_l_sq.is_nan() || mu_l_sq > MAX_MU_L_SQUARED) {
            return Err(Error::invalid(
                "beam.youngs_modulus",
                format!(
                    "EI = {} N·m² with T = {} N",
                    crate::error::compact_number(ei),
                    crate::error::compact_number(t)
                ),
                format!(
                    "the galerkin basis with a clamped end needs T L²/EI ≤ {MAX_MU_L_SQUARED:e} (here {}): its boundary layer, sqrt(EI/T) wide, enters the curvatures as T/EI, which overflows; use kind = \"hermite\", or pinned ends",
                    crate::error::compact_number(mu_l_sq)
                ),
            ));
        }
        let mut modes = Vec::with_capacity(count);
        let mut omega = Vec::with_capacity(count);
        match ends {
            Ends::PinnedPinned => {
                let pp = PinnedPinnedModes::new(ei, t, ra, l)?;
                let amp = (2.0 / (ra * l)).sqrt();
                for j in 1..=count {
                    omega.push(pp.omega(j));
                    modes.push(Stable {
                        alpha: 0.0,
                        beta: j as f64 * PI / l,
                        p: 0.0,
                        q: 0.0,
                        c: 0.0,
                        d: amp,
                    });
                }
            }
            Ends::ClampedPinned | Ends::PinnedClamped => {
                let cp = ClampedPinnedModes::new(ei, t, ra, l)?;
                for j in 1..=count {
                    let beta = cp.beta(j);
                    let alpha = alpha_of(beta, t / ei);
                    let e = (-alpha * l).exp();
                    let r = beta / alpha;
                    omega.push(cp.omega_of_beta(beta));
                    modes.push(Stable {
                        alpha,
                        beta,
                        p: r,
                        q: -r * e,
                        c: -r * (1.0 - e * e),
                        d: 1.0 + e * e,
                    });
                }
            }
            Ends::ClampedClamped => {
                let half = 0.5 * l;
                // odd modes: clamped–pinned on the half span (`Ends`' docs)
                let odd = ClampedPinnedModes::new(ei, t, ra, half)?;
                for n in 1..=count {
                    let k = n / 2;
                    // βℓ = kπ + δ (odd) or kπ + π/2 + δ (even), δ ∈ [0, π/2):
                    // sin βℓ and cos βℓ from δ, not from the rounded βℓ (its
                    // rounding, ε kπ, is as large as sin βℓ ≈ β/α itself
                    // when αℓ ≳ 1/ε: modes.rs, ClampedPinnedModes::phase)
                    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                    let (beta, sh, ch) = if n % 2 == 0 {
                        let d = odd.phase(k);
                        let (s, c) = d.sin_cos();
                        ((k as f64 * PI + d) / half, sign * s, sign * c)
                    } else {
                        let d = clamped_clamped_even_phase(k, t / ei, half);
                        let (s, c) = d.sin_cos();
                        // sin(π/2 + δ) = cos δ, cos(π/2 + δ) = −sin δ
                        ((k as f64 * PI + 0.5 * PI + d) / half, sign * c, -sign * s)
                    };
                    let alpha = alpha_of(beta, t / ei);
                    let e = (-alpha * l).exp();
                    omega.push(odd.omega_of_beta(beta));
                    modes.push(if n % 2 == 0 {
                        // sin β(x − ℓ) + sin βℓ (e^{−αx} − e^{−α(L−x)})/(1 − E)
                        let b = sh / (1.0 - e);
                        Stable {
                            alpha,
                            beta,
                            p: b,
                            q: -b,
                            c: -sh,
                            d: ch,
                        }
                    } else {
                        // cos β(x − ℓ) − cos βℓ (e^{−αx} + e^{−α(L−x)})/(1 + E)
                        let a = -ch / (1.0 + e);
                        Stable {
                            alpha,
                            beta,
                            p: a,
                            q: a,
                            c: ch,
                            d: sh,
                        }
                    });
                }
            }
        }
        if ends != Ends::PinnedPinned {
            for m in &mut modes {
                *m = m.scaled(1.0 / (ra * m.integral_of_square(l)).sqrt());
            }
        }
        let load = modes
            .iter()
            .enumerate()
            .map(|(i, m)| match ends {
                // exact zeros for the even sines: ∫ sin(jπx/L) = (1 − (−1)^j) L/(jπ)
                Ends::PinnedPinned if i % 2 == 1 => 0.0,
                Ends::PinnedPinned => 2.0 * m.d / m.beta,
                _ => m.integral(l),
            })
            .collect();
        Ok(ModeShapes {
            length: l,
            ends,
            omega,
            modes,
            load,
        })
    }

    /// J, the number of modes.
    pub fn count(&self) -> usize {
        self.modes.len()
    }

    /// The span L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// ω_j, rad/s, ascending (the modal stiffness is `diag(ω_j²)`).
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }

    /// The end pair and every mode's stable-form coefficients, for the
    /// fast evaluation at a moving point ([`super::FastShapes`]).
    pub(super) fn parts(&self) -> (Ends, &[Stable]) {
        (self.ends, &self.modes)
    }

    /// The coordinate `s` the stable form is written in, and `ds/dx`.
    fn local(&self, x: f64) -> (f64, f64) {
        debug_assert!(x.is_finite(), "mode shapes at x = {x}");
        let x = x.clamp(0.0, self.length);
        if self.ends == Ends::PinnedClamped {
            (self.length - x, -1.0)
        } else {
            (x, 1.0)
        }
    }

    /// `φ_j(x)`, kg^{−1/2}, for all j into `out` (length J). `x` is clamped to
    /// `[0, L]`. No allocation: O(J) `sin_cos` (and, off pinned–pinned, two
    /// `exp`) calls. Pinned–pinned uses plain `sin_cos` per mode, not the
    /// three-term recurrence: its error grows with j and the saving is not
    /// worth an accuracy argument.
    pub fn values_into(&self, x: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.modes.len(), "one slot per mode");
        let (s, _) = self.local(x);
        let r = self.length - s;
        for (o, m) in out.iter_mut().zip(&self.modes) {
            let (sn, cs) = (m.beta * s).sin_cos();
            let mut v = m.c * cs + m.d * sn;
            if m.alpha > 0.0 {
                v += m.p * (-m.alpha * s).exp() + m.q * (-m.alpha * r).exp();
            }
            *o = v;
        }
    }

    /// `φ_j'(x) = dφ_j/dx`, kg^{−1/2}/m, for all j into `out` (length J).
    pub fn slopes_into(&self, x: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.modes.len(), "one slot per mode");
        let (s, sign) = self.local(x);
        let r = self.length - s;
        for (o, m) in out.iter_mut().zip(&self.modes) {
            let (sn, cs) = (m.beta * s).sin_cos();
            let mut v = m.beta * (m.d * cs - m.c * sn);
            if m.alpha > 0.0 {
                v += m.alpha * (m.q * (-m.alpha * r).exp() - m.p * (-m.alpha * s).exp());
            }
            *o = sign * v;
        }
    }

    /// `φ_j''(x)`, kg^{−1/2}/m², for all j into `out` (length J): the
    /// curvature a riding mass's convective term `V² w_xx` needs (MODEL §9.2).
    pub fn curvatures_into(&self, x: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.modes.len(), "one slot per mode");
        let (s, _) = self.local(x);
        let r = self.length - s;
        for (o, m) in out.iter_mut().zip(&self.modes) {
            let (sn, cs) = (m.beta * s).sin_cos();
            let mut v = -m.beta * m.beta * (m.c * cs + m.d * sn);
            if m.alpha > 0.0 {
                v += m.alpha * m.alpha * (m.p * (-m.alpha * s).exp() + m.q * (-m.alpha * r).exp());
            }
            *o = v;
        }
    }

    /// Values, slopes and curvatures at one point in one pass (one
    /// `sin_cos` and two `exp` per mode instead of three of each): what a
    /// riding mass's contact row and convective terms need every step. Each
    /// slice has length J; equal to [`Self::values_into`],
    /// [`Self::slopes_into`] and [`Self::curvatures_into`].
    pub fn all_into(&self, x: f64, values: &mut [f64], slopes: &mut [f64], curvatures: &mut [f64]) {
        let n = self.modes.len();
        assert!(
            values.len() == n && slopes.len() == n && curvatures.len() == n,
            "one slot per mode"
        );
        let (s, sign) = self.local(x);
        let r = self.length - s;
        for (i, m) in self.modes.iter().enumerate() {
            let (sn, cs) = (m.beta * s).sin_cos();
            let (osc, dosc) = (m.c * cs + m.d * sn, m.d * cs - m.c * sn);
            let (mut v, mut d, mut c) = (osc, m.beta * dosc, -m.beta * m.beta * osc);
            if m.alpha > 0.0 {
                let (left, right) = (m.p * (-m.alpha * s).exp(), m.q * (-m.alpha * r).exp());
                v += left + right;
                d += m.alpha * (right - left);
                c += m.alpha * m.alpha * (left + right);
            }
            values[i] = v;
            slopes[i] = sign * d;
            curvatures[i] = c;
        }
    }

    /// Generalized loads `∫₀ᴸ p φ_j dx`, N·kg^{−1/2}, of a uniform distributed
    /// load `p`, N/m (closed form).
    pub fn uniform_load(&self, p: f64) -> Vec<f64> {
        self.load.iter().map(|f| p * f).collect()
    }

    /// Composite 10-point Gauss–Legendre nodes and weights on [0, L] that
    /// resolve every mode of the basis: panels of width `0.5/α_J` in the
    /// end layers (thickness `40/α_1`, where `e^{−αx}` < 10⁻¹⁷) and
    /// `0.5/β_J` between them, so every panel spans ≤ 0.5 rad of the fastest
    /// oscillation and ≤ 0.5 decay lengths of the thinnest layer (10-point
    /// rule: error ~ 0.5²⁰/20! per panel); no panel wider than `max_panel`
    /// (m), for an integrand that varies faster than the modes.
    pub fn quadrature(&self, max_panel: f64) -> Vec<(f64, f64)> {
        let l = self.length;
        let last = self.modes.last().expect("a basis has a mode");
        let first = self.modes[0];
        let (h_layer, layer) = if first.alpha > 0.0 {
            (
                (0.5 / last.alpha).min(max_panel),
                (40.0 / first.alpha).min(0.5 * l),
            )
        } else {
            (l, 0.0)
        };
        let h_in = (0.5 / last.beta).min(max_panel);
        let mut cuts = vec![0.0];
        for (a, b, h) in [
            (0.0, layer, h_layer),
            (layer, l - layer, h_in),
            (l - layer, l, h_layer),
        ] {
            if b > a {
                let n = ((b - a) / h).ceil() as usize;
                cuts.extend((1..=n).map(|i| a + (b - a) * i as f64 / n as f64));
            }
        }
        crate::numeric::quadrature::composite(
            &crate::numeric::quadrature::gauss_legendre(10),
            &cuts,
        )
    }
}

/// `α = sqrt(β² + μ²)`, 1/m.
fn alpha_of(beta: f64, mu2: f64) -> f64 {
    (beta * beta + mu2).sqrt()
}

/// The phase δ ∈ [0, π/2) of the even clamped–clamped mode of index k past
/// `kπ + π/2` (`βℓ = kπ + π/2 + δ`), half span `half`, `mu2 = T/EI`: the
/// root of `β cos δ − α tanh(αℓ) sin δ` (`g(β)` of `Ends`' docs times
/// `(−1)^k hypot(α, β)`), positive at 0 and negative at π/2, bisected in δ
/// so that no rounded `cos βℓ` enters (see `ClampedPinnedModes::phase`).
fn clamped_clamped_even_phase(k: usize, mu2: f64, half: f64) -> f64 {
    let base = k as f64 * PI + 0.5 * PI;
    let g = |d: f64| {
        let beta = (base + d) / half;
        let alpha = alpha_of(beta, mu2);
        let (s, c) = d.sin_cos();
        beta * c - alpha * (alpha * half).tanh() * s
    };
    super::modes::bisect_phase(g, true)
}

/// The scaled characteristic function of the even clamped–clamped modes
/// (`Ends`' docs), half span `half`, `mu2 = T/EI`; for tests.
#[cfg(test)]
fn clamped_clamped_even(beta: f64, mu2: f64, half: f64) -> f64 {
    let alpha = alpha_of(beta, mu2);
    let (s, c) = (beta * half).sin_cos();
    (beta * s + alpha * (alpha * half).tanh() * c) / alpha.hypot(beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed forms evaluated two ways (PP shapes, frequencies shared with
    /// modes.rs): a few ulps of arithmetic.
    const ROUND_OFF: f64 = 1e-13;
    /// Boundary conditions, relative to the size of the quantity (value
    /// `sqrt(2/(ρA L))`, slope ×β, curvature ×αβ). The roots are bisected to
    /// round-off of the scaled characteristic functions, whose terms are
    /// O(hypot(α, β)); the clamp-slope residual is therefore ~`ε α/β` (a
    /// few 10⁻¹² for the EXTREME case, μL ≈ 1.6·10⁵) and the phase error
    /// `ε β_J L` adds ~10⁻¹³ at J = MAX_MODES. Worst observed 1.1·10⁻¹¹.
    const BOUNDARY: f64 = 1e-10;
    /// Closed-form normalization and loads against composite Gauss–Legendre
    /// quadrature (≤ ~10⁵ nodes, errors ~0.5²⁰/20! per panel): summation
    /// round-off only. Worst observed 1.3·10⁻¹⁴ (M, K, loads, single modes
    /// up to J = MAX_MODES).
    const ORTHO: f64 = 1e-12;
    /// Central differences with step `FD_STEP/max(α_J, β_J)`: truncation
    /// `FD_STEP²/6 ≈ 1.7·10⁻⁹` of the fastest scale, round-off
    /// `ε/FD_STEP ≈ 2·10⁻¹²`. Worst observed 2.4·10⁻⁹.
    const FD_STEP: f64 = 1e-4;
    const FD: f64 = 1e-8;
    /// Roots compared with 16-digit Euler–Bernoulli references
    /// (`cos x cosh x = 1`, Blevins table 8-1): their printed precision.
    const ROOT: f64 = 1e-12;

    /// Clamped–clamped Euler–Bernoulli βL.
    const EB_CLAMPED_CLAMPED: [f64; 5] = [
        4.730_040_744_862_704,
        7.853_204_624_095_838,
        10.995_607_838_001_671,
        14.137_165_491_257_464,
        17.278_759_657_399_48,
    ];

    /// (EI, T, ρA, L): the reference span of scenes/reference.toml
    /// (αL ≈ 760 at mode 1), the brief's 20 m span, a balanced case
    /// (T L²/EI = 25), a bare beam, and an extreme one (μL ≈ 1.6·10⁵:
    /// `cosh αL` would be 10^68000).
    const REFERENCE: (f64, f64, f64, f64) = (1.34e11 * 9.64e-10, 3.0e4, 8900.0 * 1.5e-4, 50.0);
    const SHORT: (f64, f64, f64, f64) = (195.0, 2.0e4, 1.35, 20.0);
    const BALANCED: (f64, f64, f64, f64) = (4.0, 100.0, 1.35, 1.0);
    const BARE: (f64, f64, f64, f64) = (3.0, 0.0, 2.0, 1.7);
    const EXTREME: (f64, f64, f64, f64) = (1e-2, 1e5, 1.35, 50.0);
    const CASES: [(f64, f64, f64, f64); 5] = [REFERENCE, SHORT, BALANCED, BARE, EXTREME];

    const BEAM_ENDS: [(Support, Support); 4] = [
        (Support::Pinned, Support::Pinned),
        (Support::Clamped, Support::Pinned),
        (Support::Pinned, Support::Clamped),
        (Support::Clamped, Support::Clamped),
    ];

    fn props(case: (f64, f64, f64, f64), left: Support, right: Support) -> BeamProps {
        let (ei, tension, rho_a, length) = case;
        BeamProps {
            length,
            rho_a,
            ei,
            ea: None,
            tension,
            left,
            right,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    fn shapes(case: (f64, f64, f64, f64), ends: (Support, Support), j: usize) -> ModeShapes {
        ModeShapes::new(&props(case, ends.0, ends.1), j).unwrap()
    }

    fn quadrature(s: &ModeShapes) -> Vec<(f64, f64)> {
        s.quadrature(f64::INFINITY)
    }

    type Eval = fn(&ModeShapes, f64, &mut [f64]);

    /// Rows of `f(x)` at the quadrature nodes.
    fn table(s: &ModeShapes, nodes: &[(f64, f64)], f: Eval) -> Vec<Vec<f64>> {
        nodes
            .iter()
            .map(|(x, _)| {
                let mut row = vec![0.0; s.count()];
                f(s, *x, &mut row);
                row
            })
            .collect()
    }

    /// `∫ a_i b_j dx` for all i, j.
    fn gram(nodes: &[(f64, f64)], a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let j = a[0].len();
        let mut g = vec![vec![0.0; j]; j];
        for ((_, w), (ra, rb)) in nodes.iter().zip(a.iter().zip(b)) {
            for (gi, ai) in g.iter_mut().zip(ra) {
                for (gij, bj) in gi.iter_mut().zip(rb) {
                    *gij += w * ai * bj;
                }
            }
        }
        g
    }

    fn at(s: &ModeShapes, f: Eval, x: f64) -> Vec<f64> {
        let mut out = vec![0.0; s.count()];
        f(s, x, &mut out);
        out
    }

    #[test]
    fn validation_names_the_field() {
        let pp = props(BALANCED, Support::Pinned, Support::Pinned);
        for j in [0, MAX_MODES + 1] {
            let e = ModeShapes::new(&pp, j).unwrap_err();
            assert!(e.to_string().contains("`mesh.modes`"), "{e}");
        }
        assert!(ModeShapes::new(&pp, MAX_MODES).is_ok());
        for (l, r) in [
            (Support::Free, Support::Pinned),
            (Support::Clamped, Support::Free),
            (Support::Free, Support::Free),
        ] {
            let e = ModeShapes::new(&props(BALANCED, l, r), 3).unwrap_err();
            let msg = e.to_string();
            assert!(msg.contains("`mesh.kind`") && msg.contains("free"), "{msg}");
        }
        let string = (0.0, 100.0, 1.35, 1.0);
        for (l, r) in [
            (Support::Clamped, Support::Pinned),
            (Support::Clamped, Support::Clamped),
        ] {
            let e = ModeShapes::new(&props(string, l, r), 3).unwrap_err();
            let msg = e.to_string();
            assert!(
                msg.contains("`mesh.kind`") && msg.contains("EI = 0"),
                "{msg}"
            );
        }
        // the section itself is checked by modes.rs
        let e = ModeShapes::new(
            &props((1.0, 1.0, -1.0, 1.0), Support::Clamped, Support::Pinned),
            3,
        )
        .unwrap_err();
        assert!(e.to_string().contains("`rho_a`"), "{e}");
    }

    #[test]
    fn pinned_pinned_is_the_scaled_sine_series() {
        for case in [REFERENCE, BALANCED, (0.0, 100.0, 1.35, 3.0)] {
            let (ei, t, ra, l) = case;
            let s = shapes(case, BEAM_ENDS[0], 40);
            let pp = PinnedPinnedModes::new(ei, t, ra, l).unwrap();
            let amp = (2.0 / (ra * l)).sqrt();
            for x in [0.0, 0.1 * l, 0.37 * l, 0.5 * l, 0.999 * l, l] {
                let (v, d) = (
                    at(&s, ModeShapes::values_into, x),
                    at(&s, ModeShapes::slopes_into, x),
                );
                for j in 1..=40 {
                    let k = j as f64 * PI / l;
                    assert!((v[j - 1] - amp * (k * x).sin()).abs() <= ROUND_OFF * amp);
                    assert!((d[j - 1] - amp * k * (k * x).cos()).abs() <= ROUND_OFF * amp * k);
                    assert!((s.omega()[j - 1] / pp.omega(j) - 1.0).abs() <= ROUND_OFF);
                }
            }
        }
    }

    #[test]
    fn the_string_is_the_pinned_pinned_sine_basis() {
        // EI = 0: ω_j = jπc/L, shapes sqrt(2/(ρA L)) sin(jπx/L)
        let (t, ra, l) = (2.0e4, 1.35, 20.0);
        let s = shapes((0.0, t, ra, l), BEAM_ENDS[0], 25);
        let c = (t / ra).sqrt();
        for (j, w) in s.omega().iter().enumerate() {
            let j = (j + 1) as f64;
            assert!((w / (j * PI * c / l) - 1.0).abs() <= ROUND_OFF);
        }
        let v = at(&s, ModeShapes::values_into, 0.3 * l);
        assert!((v[2] - (2.0 / (ra * l)).sqrt() * (0.9 * PI).sin()).abs() < ROUND_OFF);
    }

    #[test]
    fn clamped_pinned_tends_to_the_string_shapes() {
        // bending length ℓb = sqrt(EI/T) → 0: the boundary layer (amplitude
        // β/α ≈ jπℓb/L) and the shortened span (phase jπℓb/L) both vanish
        // linearly in ℓb/L.
        let (t, ra, l): (f64, f64, f64) = (2e4, 1.35, 20.0);
        let amp = (2.0 / (ra * l)).sqrt();
        println!("  lb/L    max_j,x |φ_CP − φ_string|/amp / (jπ lb/L)");
        for lb_over_l in [1e-2, 1e-3, 1e-4] {
            let lb = lb_over_l * l;
            let s = shapes((t * lb * lb, t, ra, l), BEAM_ENDS[1], 5);
            let mut worst: f64 = 0.0;
            for i in 0..=400 {
                let x = l * i as f64 / 400.0;
                let v = at(&s, ModeShapes::values_into, x);
                for (j, vj) in v.iter().enumerate() {
                    let k = (j + 1) as f64 * PI / l;
                    let dev = (vj - amp * (k * x).sin()).abs() / amp;
                    worst = worst.max(dev / ((j + 1) as f64 * PI * lb_over_l));
                }
            }
            println!("  {lb_over_l:.0e}   {worst:.3}");
            assert!(worst < 2.5, "lb/L = {lb_over_l}: {worst}");
        }
    }

    #[test]
    fn frequencies_match_the_characteristic_equations() {
        for case in CASES {
            let (ei, t, ra, l) = case;
            let cp = ClampedPinnedModes::new(ei, t, ra, l).unwrap();
            for ends in [BEAM_ENDS[1], BEAM_ENDS[2]] {
                let s = shapes(case, ends, 30);
                for (j, w) in s.omega().iter().enumerate() {
                    assert_eq!(*w, cp.omega(j + 1));
                }
            }
            let pp = PinnedPinnedModes::new(ei, t, ra, l).unwrap();
            let s = shapes(case, BEAM_ENDS[0], 30);
            for (j, w) in s.omega().iter().enumerate() {
                assert_eq!(*w, pp.omega(j + 1));
            }
        }
    }

    #[test]
    fn clamped_clamped_without_tension_is_euler_bernoulli() {
        let (ei, ra, l) = (3.0, 2.0, 1.7);
        let s = shapes((ei, 0.0, ra, l), BEAM_ENDS[3], 200);
        for (j, bl) in EB_CLAMPED_CLAMPED.iter().enumerate() {
            assert!((s.modes[j].beta * l / bl - 1.0).abs() <= ROOT);
            let w = bl * bl * (ei / (ra * l.powi(4))).sqrt();
            assert!((s.omega()[j] / w - 1.0).abs() <= ROOT);
        }
        // large modes: βL → (2n + 1)π/2
        let n = 200;
        assert!((s.modes[n - 1].beta * l / ((2 * n + 1) as f64 * PI / 2.0) - 1.0).abs() <= ROOT);
    }

    #[test]
    fn clamped_clamped_interlaces_clamped_pinned_and_misses_no_root() {
        for (ei, t) in [(1.0, 0.0), (195.0, 2e4), (1e-3, 2e4), (50.0, 10.0)] {
            let (ra, l) = (1.35, 10.0);
            let n = 12;
            let cc = shapes((ei, t, ra, l), BEAM_ENDS[3], n + 1);
            let cp = ClampedPinnedModes::new(ei, t, ra, l).unwrap();
            let w = cc.omega();
            // one more constraint (v'(L) = 0): ω_j^CP < ω_j^CC < ω_{j+1}^CP
            for j in 1..=n {
                assert!(
                    cp.omega(j) < w[j - 1] && w[j - 1] < cp.omega(j + 1),
                    "{ei} {t} {j}"
                );
            }
            // sign changes of the even and odd characteristic functions on a
            // fine ω grid below (ω_n + ω_{n+1})/2: exactly n roots in all
            let half = 0.5 * l;
            let odd = ClampedPinnedModes::new(ei, t, ra, half).unwrap();
            let wmax = 0.5 * (w[n - 1] + w[n]);
            let beta_of = |om: f64| {
                let disc = (t * t + 4.0 * ei * ra * om * om).sqrt();
                (2.0 * ra * om * om / (disc + t)).sqrt()
            };
            let steps = 100_000;
            let (mut count, mut prev) = (0, (0.0, 0.0));
            for i in 1..=steps {
                let b = beta_of(wmax * i as f64 / steps as f64);
                let h = (clamped_clamped_even(b, t / ei, half), odd.characteristic(b));
                if i > 1 {
                    count += usize::from((h.0 > 0.0) != (prev.0 > 0.0));
                    count += usize::from((h.1 > 0.0) != (prev.1 > 0.0));
                }
                prev = h;
            }
            assert_eq!(count, n, "EI = {ei}, T = {t}");
        }
    }

    #[test]
    fn boundary_conditions_hold() {
        for case in CASES {
            let (_, _, ra, l) = case;
            let amp = (2.0 / (ra * l)).sqrt();
            for ends in BEAM_ENDS {
                let j = 50;
                let s = shapes(case, ends, j);
                for (x, support) in [(0.0, ends.0), (l, ends.1)] {
                    let v = at(&s, ModeShapes::values_into, x);
                    let d = at(&s, ModeShapes::slopes_into, x);
                    let c = at(&s, ModeShapes::curvatures_into, x);
                    for (i, m) in s.modes.iter().enumerate() {
                        let slope = amp * m.beta;
                        let curv = amp * m.beta * m.alpha.max(m.beta);
                        assert!(v[i].abs() <= BOUNDARY * amp, "{ends:?} {x} {i}: {}", v[i]);
                        match support {
                            Support::Clamped => {
                                assert!(
                                    d[i].abs() <= BOUNDARY * slope,
                                    "{ends:?} {x} {i}: {}",
                                    d[i]
                                )
                            }
                            _ => {
                                assert!(c[i].abs() <= BOUNDARY * curv, "{ends:?} {x} {i}: {}", c[i])
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn finite_differences_confirm_slopes_and_curvatures() {
        for case in [BALANCED, BARE, SHORT] {
            let (_, _, ra, l) = case;
            let amp = (2.0 / (ra * l)).sqrt();
            for ends in BEAM_ENDS {
                let s = shapes(case, ends, 8);
                let last = s.modes[7];
                let h = FD_STEP / last.alpha.max(last.beta);
                for x in [2.0 * h, 0.013 * l, 0.3 * l, 0.71 * l, l - 2.0 * h] {
                    let fd = |f: Eval| {
                        let (a, b) = (at(&s, f, x - h), at(&s, f, x + h));
                        a.iter()
                            .zip(&b)
                            .map(|(a, b)| (b - a) / (2.0 * h))
                            .collect::<Vec<_>>()
                    };
                    let (d, c) = (
                        at(&s, ModeShapes::slopes_into, x),
                        at(&s, ModeShapes::curvatures_into, x),
                    );
                    let (fd_d, fd_c) = (fd(ModeShapes::values_into), fd(ModeShapes::slopes_into));
                    for (i, m) in s.modes.iter().enumerate() {
                        let k = m.alpha.max(m.beta);
                        assert!((d[i] - fd_d[i]).abs() <= FD * amp * k, "{ends:?} {x} {i}");
                        assert!(
                            (c[i] - fd_c[i]).abs() <= FD * amp * k * k,
                            "{ends:?} {x} {i}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn pinned_clamped_mirrors_clamped_pinned() {
        for case in [REFERENCE, BALANCED, BARE] {
            let l = case.3;
            let cp = shapes(case, BEAM_ENDS[1], 20);
            let pc = shapes(case, BEAM_ENDS[2], 20);
            assert_eq!(cp.omega(), pc.omega());
            assert_eq!(cp.uniform_load(1.0), pc.uniform_load(1.0));
            for x in [0.0, 0.01 * l, 0.4 * l, 0.93 * l, l] {
                let f = |s: &ModeShapes, g: Eval, x| at(s, g, x);
                assert_eq!(
                    f(&pc, ModeShapes::values_into, x),
                    f(&cp, ModeShapes::values_into, l - x)
                );
                assert_eq!(
                    f(&pc, ModeShapes::curvatures_into, x),
                    f(&cp, ModeShapes::curvatures_into, l - x)
                );
                let (a, b) = (
                    f(&pc, ModeShapes::slopes_into, x),
                    f(&cp, ModeShapes::slopes_into, l - x),
                );
                assert!(a.iter().zip(&b).all(|(a, b)| *a == -b));
            }
        }
    }

    /// `|G_ij − δ_ij·diag_i| ≤ tol·scale_i·scale_j` for a Gram matrix.
    fn assert_diagonal(g: &[Vec<f64>], diag: &[f64], tol: f64, what: &str) {
        for (i, gi) in g.iter().enumerate() {
            for (j, gij) in gi.iter().enumerate() {
                let want = if i == j { diag[i] } else { 0.0 };
                let scale = (diag[i] * diag[j]).sqrt();
                assert!(
                    (gij - want).abs() <= tol * scale,
                    "{what}: ({i}, {j}) = {gij} vs {want}"
                );
            }
        }
    }

    #[test]
    fn modes_are_mass_orthonormal_and_stiffness_orthogonal() {
        // M: ∫ρA φ_i φ_j = δ_ij; K: ∫(EI φ_i''φ_j'' + T φ_i'φ_j') = ω_i² δ_ij
        // (φ = 0 at both ends and φ''φ' = 0 at clamps and pins: no boundary terms)
        for case in CASES {
            let (ei, t, ra, _) = case;
            for ends in BEAM_ENDS {
                let s = shapes(case, ends, 12);
                let nodes = quadrature(&s);
                let v = table(&s, &nodes, ModeShapes::values_into);
                let d = table(&s, &nodes, ModeShapes::slopes_into);
                let c = table(&s, &nodes, ModeShapes::curvatures_into);
                let m: Vec<Vec<f64>> = gram(&nodes, &v, &v)
                    .into_iter()
                    .map(|r| r.into_iter().map(|x| ra * x).collect())
                    .collect();
                assert_diagonal(
                    &m,
                    &vec![1.0; s.count()],
                    ORTHO,
                    &format!("M {case:?} {ends:?}"),
                );
                let (kb, kt) = (gram(&nodes, &c, &c), gram(&nodes, &d, &d));
                let k: Vec<Vec<f64>> = kb
                    .iter()
                    .zip(&kt)
                    .map(|(b, t_)| b.iter().zip(t_).map(|(b, t_)| ei * b + t * t_).collect())
                    .collect();
                let w2: Vec<f64> = s.omega().iter().map(|w| w * w).collect();
                assert_diagonal(&k, &w2, ORTHO, &format!("K {case:?} {ends:?}"));
            }
        }
    }

    #[test]
    fn the_string_basis_is_orthonormal_too() {
        let (t, ra) = (2.0e4, 1.35);
        let s = shapes((0.0, t, ra, 20.0), BEAM_ENDS[0], 30);
        let nodes = quadrature(&s);
        let v = table(&s, &nodes, ModeShapes::values_into);
        let d = table(&s, &nodes, ModeShapes::slopes_into);
        let m: Vec<Vec<f64>> = gram(&nodes, &v, &v)
            .into_iter()
            .map(|r| r.into_iter().map(|x| ra * x).collect())
            .collect();
        assert_diagonal(&m, &vec![1.0; 30], ORTHO, "M string");
        let k: Vec<Vec<f64>> = gram(&nodes, &d, &d)
            .into_iter()
            .map(|r| r.into_iter().map(|x| t * x).collect())
            .collect();
        let w2: Vec<f64> = s.omega().iter().map(|w| w * w).collect();
        assert_diagonal(&k, &w2, ORTHO, "K string");
    }

    #[test]
    fn large_alpha_l_gives_finite_normalized_shapes_up_to_the_limit() {
        // the reference span at J = MAX_MODES (αL from 760 to 3300) and the
        // extreme one (αL ≈ 1.6·10⁵): every value finite and O(amplitude)
        for case in [REFERENCE, EXTREME] {
            let (_, _, ra, l) = case;
            let amp = (2.0 / (ra * l)).sqrt();
            for ends in BEAM_ENDS {
                let s = shapes(case, ends, MAX_MODES);
                assert!(s.omega().windows(2).all(|w| w[0] < w[1]));
                for i in 0..=1000 {
                    let x = l * i as f64 / 1000.0;
                    for (f, what) in [
                        (ModeShapes::values_into as Eval, "value"),
                        (ModeShapes::slopes_into, "slope"),
                        (ModeShapes::curvatures_into, "curvature"),
                    ] {
                        let v = at(&s, f, x);
                        assert!(v.iter().all(|v| v.is_finite()), "{what} at {x}");
                        if what == "value" {
                            assert!(v.iter().all(|v| v.abs() <= 2.0 * amp), "{x}");
                        }
                    }
                }
                // the boundary conditions at the top of the basis
                for x in [0.0, l] {
                    let v = at(&s, ModeShapes::values_into, x);
                    assert!(v.iter().all(|v| v.abs() <= BOUNDARY * amp), "{ends:?} {x}");
                }
                // normalization of single modes across the range, by quadrature
                for j in [1, 10, 100, MAX_MODES] {
                    let one = ModeShapes {
                        omega: vec![s.omega[j - 1]],
                        modes: vec![s.modes[j - 1]],
                        load: vec![s.load[j - 1]],
                        ..s.clone()
                    };
                    let nodes = quadrature(&one);
                    let v = table(&one, &nodes, ModeShapes::values_into);
                    let n = ra * gram(&nodes, &v, &v)[0][0];
                    assert!((n - 1.0).abs() <= ORTHO, "{case:?} {ends:?} mode {j}: {n}");
                }
            }
        }
    }

    #[test]
    fn uniform_load_matches_quadrature() {
        for case in CASES {
            let (_, _, ra, l) = case;
            for ends in BEAM_ENDS {
                let s = shapes(case, ends, 15);
                let p = -9.81 * ra;
                let nodes = quadrature(&s);
                let v = table(&s, &nodes, ModeShapes::values_into);
                let mut q = vec![0.0; s.count()];
                for ((_, w), row) in nodes.iter().zip(&v) {
                    for (qj, vj) in q.iter_mut().zip(row) {
                        *qj += w * p * vj;
                    }
                }
                // scale: |∫ p φ| ≤ |p| sqrt(L/ρA) (Cauchy–Schwarz)
                let scale = p.abs() * (l / ra).sqrt();
                for (a, b) in s.uniform_load(p).iter().zip(&q) {
                    assert!(
                        (a - b).abs() <= ORTHO * scale,
                        "{case:?} {ends:?}: {a} vs {b}"
                    );
                }
            }
        }
        // pinned–pinned: 2L/(jπ) sqrt(2/(ρA L)) for odd j, exactly 0 for even
        let (_, _, ra, l) = BALANCED;
        let f = shapes(BALANCED, BEAM_ENDS[0], 6).uniform_load(1.0);
        for (j, fj) in f.iter().enumerate() {
            let j = (j + 1) as f64;
            let want = if j % 2.0 == 1.0 {
                2.0 * l / (j * PI) * (2.0 / (ra * l)).sqrt()
            } else {
                0.0
            };
            assert!((fj - want).abs() <= ROUND_OFF * want.abs().max(1e-300));
        }
    }
    #[test]
    fn all_into_equals_the_separate_evaluations() {
        for case in [REFERENCE, BARE] {
            let l = case.3;
            for ends in BEAM_ENDS {
                let s = shapes(case, ends, 30);
                for x in [0.0, 1e-3 * l, 0.42 * l, l] {
                    let (mut v, mut d, mut c) = (vec![0.0; 30], vec![0.0; 30], vec![0.0; 30]);
                    s.all_into(x, &mut v, &mut d, &mut c);
                    assert_eq!(v, at(&s, ModeShapes::values_into, x));
                    assert_eq!(d, at(&s, ModeShapes::slopes_into, x));
                    assert_eq!(c, at(&s, ModeShapes::curvatures_into, x));
                }
            }
        }
    }

    /// A regression: with clamped ends and a boundary layer thinner than ε L
    /// (μL ≳ 4.5·10¹⁵, EI ≲ 10⁻²⁴ N·m² on the reference span) the roots
    /// were bisected on the rounded sin βL and landed a quarter period off.
    /// Now every root and clamp holds to round-off down to the refusal at
    /// T L²/EI = MAX_MU_L_SQUARED, on both sides of the old break.
    #[test]
    fn clamped_ends_hold_for_boundary_layers_thinner_than_round_off() {
        let (t, ra, l) = (3.0e4, 1.335, 50.0);
        for ei in [1e-20, 1e-24, 1e-25, 1e-26, 1e-40, 1e-100, 1e-190] {
            for ends in [
                (Support::Clamped, Support::Clamped),
                (Support::Clamped, Support::Pinned),
            ] {
                let m = shapes((ei, t, ra, l), ends, 40);
                let n = m.count();
                let (mut v0, mut d0, mut vl) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                let mut dl = vec![0.0; n];
                m.values_into(0.0, &mut v0);
                m.slopes_into(0.0, &mut d0);
                m.values_into(l, &mut vl);
                m.slopes_into(l, &mut dl);
                let amp = (2.0 / (ra * l)).sqrt();
                for j in 0..n {
                    let beta = m.modes[j].beta;
                    // the string limit: β_j L → (j + 1)π from above by O(1/(μL))
                    let phase = beta * l - (j + 1) as f64 * PI;
                    assert!(
                        (0.0..1e-3).contains(&phase),
                        "EI {ei:e} {ends:?} mode {j}: βL − (j+1)π = {phase:e}"
                    );
                    assert!(v0[j].abs() <= BOUNDARY * amp, "EI {ei:e} φ(0) = {}", v0[j]);
                    assert!(
                        d0[j].abs() <= BOUNDARY * amp * beta,
                        "EI {ei:e} {ends:?} mode {j}: φ'(0) = {:e}, β = {beta:e}",
                        d0[j]
                    );
                    assert!(vl[j].abs() <= BOUNDARY * amp, "EI {ei:e} φ(L) = {}", vl[j]);
                    if ends.1 == Support::Clamped {
                        assert!(
                            dl[j].abs() <= BOUNDARY * amp * beta,
                            "EI {ei:e} mode {j}: φ'(L) = {:e}",
                            dl[j]
                        );
                    }
                }
            }
        }
        // past the bound: refused with the reason, naming EI
        let e = ModeShapes::new(
            &props((1e-194, t, ra, l), Support::Clamped, Support::Clamped),
            10,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("beam.youngs_modulus") && e.contains("T L²/EI ≤ 1e200"),
            "{e}"
        );
        // pinned ends have no boundary layer: any EI
        assert!(
            ModeShapes::new(
                &props((1e-300, 1e10, ra, l), Support::Pinned, Support::Pinned),
                10
            )
            .is_ok()
        );
    }
}
