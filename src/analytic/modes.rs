//! Free vibration of a tensioned beam (MODEL §1, §8): the dispersion relation
//! of the infinite beam, the closed-form eigenfrequencies of a pinned–pinned
//! span, and the eigenfrequencies of the clamped–pinned reference span as
//! roots of its characteristic equation (references for mesh convergence:
//! Hermite cubics converge eigenvalues at O(h⁴)).
//!
//! Clamped–pinned characteristic equation. With `EI v'''' − T v'' = ρA ω² v`
//! and `v = A cosh αx + B sinh αx + C cos βx + D sin βx`,
//!
//! ```text
//! α² = (T + sqrt(T² + 4 EI ρA ω²)) / (2 EI),   β² = α² − T/EI,   α²β² = ρA ω²/EI.
//! ```
//!
//! `v(0) = v'(0) = 0` give `C = −A`, `D = −(α/β) B`; `v(L) = v''(L) = 0` then
//! leave a 2×2 system whose determinant is `(α² + β²)/β · [α cosh αL sin βL −
//! β sinh αL cos βL]`. Dividing by `cosh αL` (no overflow for `αL ≫ 1`) and by
//! `sqrt(α² + β²)` (dimensionless, in [−1, 1]):
//!
//! ```text
//! h(β) = [α sin βL − β tanh(αL) cos βL] / sqrt(α² + β²) = 0.
//! ```
//!
//! `T → 0`: `tan βL = tanh βL` (βL = 3.9266, 7.0686, …); `EI → 0`:
//! `sin βL → 0`, `ω → jπc/L`. Bracketing: `h = 0 ⇔ tan βL = p(β) :=
//! β tanh(αL)/α ∈ [0, 1)`, and on `βL ∈ [jπ, jπ + π/2)` the left side rises
//! from 0 to +∞ with slope ≥ L while `p' ≤ 1/α + L sech²(αL) < L` (α ≥ jπ/L):
//! exactly one root per interval, none in (0, π/2) (there `tan βL ≥ βL > p`).
//! Mode `j` is therefore bisected on `βL ∈ [jπ, jπ + π/2]` to round-off.

use crate::error::{Error, Result};

/// `value > 0` and finite, else an [`Error::Invalid`] naming `field`.
pub(super) fn require_positive(field: &str, value: f64, unit: &str) -> Result<f64> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("must be > 0 ({unit})"),
        ))
    }
}

/// `value ≥ 0` and finite, else an [`Error::Invalid`] naming `field`.
pub(super) fn require_nonnegative(field: &str, value: f64, unit: &str) -> Result<f64> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("must be ≥ 0 ({unit})"),
        ))
    }
}

/// Shared checks for (EI, T, ρA): EI, T ≥ 0, ρA > 0 and some stiffness.
fn check_section(ei: f64, tension: f64, rho_a: f64) -> Result<()> {
    require_nonnegative("ei", ei, "N·m²")?;
    require_nonnegative("tension", tension, "N")?;
    require_positive("rho_a", rho_a, "kg/m")?;
    if ei == 0.0 && tension == 0.0 {
        return Err(Error::invalid(
            "ei, tension",
            "0, 0",
            "need EI > 0 or T > 0 (no stiffness at all)",
        ));
    }
    Ok(())
}

/// Dispersion of free waves on an infinite tensioned beam (MODEL §1):
/// `ω(k) = k sqrt((EI k² + T)/ρA)` and phase speed
/// `c(ℓ) = sqrt((4π² EI + ℓ² T)/(ρA ℓ²))` for wavelength `ℓ = 2π/k`.
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dispersion {
    /// EI, N·m² (≥ 0).
    pub ei: f64,
    /// T, N (≥ 0; EI and T not both zero).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
}

#[cfg(test)]
impl Dispersion {
    /// Check the inputs: EI, T ≥ 0 and not both zero, ρA > 0.
    pub fn new(ei: f64, tension: f64, rho_a: f64) -> Result<Self> {
        check_section(ei, tension, rho_a)?;
        Ok(Dispersion { ei, tension, rho_a })
    }

    /// Angular frequency `ω(k) = k sqrt((EI k² + T)/ρA)`, rad/s, for the
    /// wavenumber `k`, rad/m (|k| is used).
    pub fn omega(&self, k: f64) -> f64 {
        let k = k.abs();
        k * ((self.ei * k * k + self.tension) / self.rho_a).sqrt()
    }

    /// Phase speed `c(ℓ) = sqrt((4π² EI + ℓ² T)/(ρA ℓ²))`, m/s, for the
    /// wavelength `ℓ > 0`, m. Tends to the string speed `sqrt(T/ρA)` as ℓ → ∞.
    pub fn phase_speed(&self, wavelength: f64) -> f64 {
        let l2 = wavelength * wavelength;
        ((4.0 * std::f64::consts::PI.powi(2) * self.ei + l2 * self.tension) / (self.rho_a * l2))
            .sqrt()
    }
}

/// Eigenfrequencies of a pinned–pinned tensioned beam of length L (MODEL §8):
/// `ω_j = (jπ/L)² sqrt(EI/ρA) sqrt(1 + T L²/(EI j²π²))`, rad/s, i.e.
/// `ω_j = ω(k = jπ/L)` of `Dispersion` (written in that form, it also
/// covers the string EI = 0: `ω_j = jπ c/L`). Mode shapes `sin(jπx/L)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinnedPinnedModes {
    /// EI, N·m² (≥ 0).
    pub ei: f64,
    /// T, N (≥ 0; EI and T not both zero).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
    /// L, m (> 0).
    pub length: f64,
}

impl PinnedPinnedModes {
    /// Check the inputs: EI, T ≥ 0 and not both zero, ρA > 0, L > 0.
    pub fn new(ei: f64, tension: f64, rho_a: f64, length: f64) -> Result<Self> {
        check_section(ei, tension, rho_a)?;
        require_positive("length", length, "m")?;
        Ok(PinnedPinnedModes {
            ei,
            tension,
            rho_a,
            length,
        })
    }

    /// ω_j, rad/s, for mode `j ≥ 1` (j = 0 gives 0).
    pub fn omega(&self, j: usize) -> f64 {
        let k = j as f64 * std::f64::consts::PI / self.length;
        k * ((self.ei * k * k + self.tension) / self.rho_a).sqrt()
    }

    /// The first `n` eigenfrequencies ω_1 … ω_n, rad/s, ascending.
    pub fn frequencies(&self, n: usize) -> Vec<f64> {
        (1..=n).map(|j| self.omega(j)).collect()
    }
}

/// Eigenfrequencies of a clamped (x = 0) – pinned (x = L) tensioned beam, the
/// reference span of MODEL §1, from the roots of the scaled characteristic
/// equation `h(β) = 0` (module docs), `ω = sqrt(EI/ρA) α β`, rad/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClampedPinnedModes {
    /// EI, N·m² (> 0: a string cannot be clamped).
    pub ei: f64,
    /// T, N (≥ 0).
    pub tension: f64,
    /// ρA, kg/m (> 0).
    pub rho_a: f64,
    /// L, m (> 0).
    pub length: f64,
}

impl ClampedPinnedModes {
    /// Check the inputs: EI > 0, T ≥ 0, ρA > 0, L > 0.
    pub fn new(ei: f64, tension: f64, rho_a: f64, length: f64) -> Result<Self> {
        require_positive("ei", ei, "N·m²; a string (EI = 0) cannot be clamped")?;
        require_nonnegative("tension", tension, "N")?;
        require_positive("rho_a", rho_a, "kg/m")?;
        require_positive("length", length, "m")?;
        Ok(ClampedPinnedModes {
            ei,
            tension,
            rho_a,
            length,
        })
    }

    /// `μ² = T/EI`, 1/m².
    fn mu2(&self) -> f64 {
        self.tension / self.ei
    }

    /// The scaled characteristic function `h(β)`, dimensionless in [−1, 1],
    /// whose positive roots are the modes (β in rad/m).
    pub fn characteristic(&self, beta: f64) -> f64 {
        let l = self.length;
        let alpha = (beta * beta + self.mu2()).sqrt();
        let num = alpha * (beta * l).sin() - beta * (alpha * l).tanh() * (beta * l).cos();
        num / alpha.hypot(beta)
    }

    /// The angular frequency belonging to the wavenumber β, rad/s:
    /// `ω = sqrt(EI/ρA) α β` with `α = sqrt(β² + T/EI)`.
    pub fn omega_of_beta(&self, beta: f64) -> f64 {
        let alpha = (beta * beta + self.mu2()).sqrt();
        (self.ei / self.rho_a).sqrt() * alpha * beta
    }

    /// The wavenumber β_j of mode `j ≥ 1`, rad/m: `(jπ + δ_j)/L` with the
    /// phase δ_j of [`Self::phase`].
    pub fn beta(&self, j: usize) -> f64 {
        (j as f64 * std::f64::consts::PI + self.phase(j)) / self.length
    }

    /// The phase δ_j ∈ [0, π/2) of mode `j ≥ 1` past jπ: `β_j L = jπ + δ_j`.
    ///
    /// The root is bisected in δ, on `g(δ) = α sin δ − β tanh(αL) cos δ`
    /// (`h` times `(−1)^j hypot(α, β)`, with `β = (jπ + δ)/L`): `g(0) < 0 <
    /// g(π/2) = α`. Bisecting `h` in β instead evaluates `sin βL` near jπ,
    /// whose rounding (ε jπ) times α outweighs the `β cos βL` term once
    /// `αL ≳ 1/ε`: the sign at the bracket's end was then noise and the
    /// root could land a quarter period off (EI = 10⁻²⁶ N·m² on the
    /// reference span: clamped–clamped Galerkin forces 9 % low).
    /// In δ the terms are O(α δ) and O(β) with no cancellation, so δ ≈ β/α
    /// is found to its own relative round-off for any αL.
    pub fn phase(&self, j: usize) -> f64 {
        assert!(j >= 1, "modes are numbered from 1");
        let (l, mu2) = (self.length, self.mu2());
        let jpi = j as f64 * std::f64::consts::PI;
        let g = |d: f64| {
            let beta = (jpi + d) / l;
            let alpha = (beta * beta + mu2).sqrt();
            let (s, c) = d.sin_cos();
            alpha * s - beta * (alpha * l).tanh() * c
        };
        // the root estimated by the fixed point of tan δ = β tanh(αL)/α
        // (a contraction: β/α varies by O(1/(αL)²) of itself over δ)
        let mut guess = 0.25 * std::f64::consts::PI;
        for _ in 0..PHASE_GUESS_ITERATIONS {
            let beta = (jpi + guess) / l;
            let alpha = (beta * beta + mu2).sqrt();
            let next = (beta * (alpha * l).tanh() / alpha).atan();
            let done = (next - guess).abs() <= PHASE_GUESS_CONVERGED;
            guess = next;
            if done {
                break;
            }
        }
        bisect_phase_near(g, guess)
    }

    /// ω_j, rad/s, for mode `j ≥ 1`.
    pub fn omega(&self, j: usize) -> f64 {
        self.omega_of_beta(self.beta(j))
    }

    /// The first `n` eigenfrequencies ω_1 … ω_n, rad/s, ascending.
    pub fn frequencies(&self, n: usize) -> Vec<f64> {
        (1..=n).map(|j| self.omega(j)).collect()
    }
}

/// The root in `[0, π/2]` of a phase function `g` that changes sign there
/// (`g(0) < 0` unless `falling`, then `g(0) > 0`), bisected until the
/// bracket cannot shrink; the endpoint with the smaller residual.
pub(crate) fn bisect_phase(g: impl Fn(f64) -> f64, falling: bool) -> f64 {
    bisect_phase_from(g, falling, 0.0, 0.5 * std::f64::consts::PI)
}

/// Fixed-point iterations at most for a clamped–pinned phase's estimate
/// ([`ClampedPinnedModes::phase`]): the contraction's factor is below
/// 1/4 for every mode of a beam with EI > 0, so 40 reach round-off.
const PHASE_GUESS_ITERATIONS: usize = 40;

/// Change of the estimate, rad, at which its iteration stops: a
/// thousandth of [`PHASE_GUESS_MARGIN`].
const PHASE_GUESS_CONVERGED: f64 = 1e-13;

/// Half-width, rad, around the estimate of a phase within which
/// [`bisect_phase_near`] evaluates `g`: far above the estimate's error
/// (round-off, [`PHASE_GUESS_CONVERGED`]) and far below the distance at
/// which `g`'s rounded sign could be wrong, so the halvings outside it
/// are the ones [`bisect_phase`] takes.
const PHASE_GUESS_MARGIN: f64 = 1e-10;

/// [`bisect_phase`] (`g(0) < 0`) for a root known to lie within
/// [`PHASE_GUESS_MARGIN`] of `guess`: the same halvings of `[0, π/2]`, the
/// sign of `g` taken from the estimate while the midpoint lies outside
/// `guess ± margin`, then checked at the bracket's two ends (`g(lo) < 0 <
/// g(hi)`); bisected on from there as [`bisect_phase`] does, so the same
/// bits in about half the evaluations of `g`. Where a check fails (an
/// estimate off by more than the margin), the whole bisection.
fn bisect_phase_near(g: impl Fn(f64) -> f64, guess: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 0.5 * std::f64::consts::PI);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if mid < guess - PHASE_GUESS_MARGIN {
            lo = mid;
        } else if mid > guess + PHASE_GUESS_MARGIN {
            hi = mid;
        } else {
            break;
        }
    }
    let below = lo == 0.0 || g(lo) < 0.0;
    let above = hi == 0.5 * std::f64::consts::PI || g(hi) > 0.0;
    if below && above {
        bisect_phase_from(g, false, lo, hi)
    } else {
        bisect_phase(g, false)
    }
}

/// [`bisect_phase`] from the bracket `[lo, hi]`.
fn bisect_phase_from(g: impl Fn(f64) -> f64, falling: bool, lo: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let below = |v: f64| if falling { v > 0.0 } else { v < 0.0 };
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let v = g(mid);
        if v == 0.0 {
            return mid;
        }
        if below(v) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if g(lo).abs() <= g(hi).abs() { lo } else { hi }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::PI;

    /// Closed forms evaluated two ways: a few ulps of arithmetic.
    const ROUND_OFF: f64 = 1e-13;
    /// Roots bisected to round-off, compared with 30-digit references
    /// (mpmath `findroot(tan x − tanh x)`): the condition of the root.
    const ROOT: f64 = 1e-12;

    /// Clamped–pinned Euler–Bernoulli βL, mpmath to 30 digits, truncated.
    const EB_CLAMPED_PINNED: [f64; 5] = [
        3.926_602_312_047_919,
        7.068_582_745_628_732,
        10.210_176_122_813_031,
        13.351_768_777_754_093,
        16.493_361_431_346_41,
    ];

    /// The phase from its estimate is bit for bit the whole bisection's,
    /// across tensions from none to a near string and J up to 4000.
    #[test]
    fn the_estimated_bracket_gives_the_bits_of_the_whole_bisection() {
        for (ei, t) in [
            (1.2918e2, 3.0e4),
            (1.2918e2, 0.0),
            (1.0, 3.0e4),
            (1e-8, 2.0e4),
            (1e3, 1e2),
            (1e-26, 3.0e4),
        ] {
            for l in [50.0, 25.0, 1.0] {
                let cp = ClampedPinnedModes::new(ei, t, 1.335, l).unwrap();
                let (mu2, step) = (cp.mu2(), if ei < 1e-6 { 37 } else { 1 });
                for j in (1..=4000).step_by(step) {
                    let jpi = j as f64 * PI;
                    let g = |d: f64| {
                        let beta = (jpi + d) / l;
                        let alpha = (beta * beta + mu2).sqrt();
                        let (s, c) = d.sin_cos();
                        alpha * s - beta * (alpha * l).tanh() * c
                    };
                    let whole = bisect_phase(g, false);
                    assert_eq!(
                        cp.phase(j).to_bits(),
                        whole.to_bits(),
                        "EI {ei} T {t} L {l} j {j}"
                    );
                }
            }
        }
    }

    #[test]
    fn validation_names_the_field() {
        let e = ClampedPinnedModes::new(0.0, 1.0, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("`ei`"), "{e}");
        let e = PinnedPinnedModes::new(1.0, 1.0, -1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("`rho_a`"), "{e}");
        let e = PinnedPinnedModes::new(1.0, 1.0, 1.0, f64::NAN).unwrap_err();
        assert!(e.to_string().contains("`length`"), "{e}");
        assert!(Dispersion::new(0.0, 0.0, 1.0).is_err());
        assert!(Dispersion::new(0.0, 5.0, 1.0).is_ok());
    }

    #[test]
    fn dispersion_phase_speed_is_omega_over_k() {
        let d = Dispersion::new(195.0, 2e4, 1.35).unwrap();
        for wavelength in [0.1, 1.0, 10.0, 100.0] {
            let k = 2.0 * PI / wavelength;
            assert_relative_eq!(
                d.phase_speed(wavelength),
                d.omega(k) / k,
                max_relative = ROUND_OFF
            );
        }
        // long waves travel at the string speed, short ones like a bare beam
        assert_relative_eq!(
            d.phase_speed(1e9),
            (2e4_f64 / 1.35).sqrt(),
            max_relative = ROUND_OFF
        );
        let bare = Dispersion::new(195.0, 0.0, 1.35).unwrap();
        assert_relative_eq!(
            bare.omega(3.0),
            9.0 * (195.0_f64 / 1.35).sqrt(),
            max_relative = ROUND_OFF
        );
    }

    #[test]
    fn pinned_pinned_matches_the_spec_form_and_the_dispersion() {
        let (ei, t, ra, l) = (195.0, 2e4, 1.35, 50.0);
        let m = PinnedPinnedModes::new(ei, t, ra, l).unwrap();
        let d = Dispersion::new(ei, t, ra).unwrap();
        for (i, w) in m.frequencies(20).into_iter().enumerate() {
            let j = (i + 1) as f64;
            // MODEL §8 form
            let spec = (j * PI / l).powi(2)
                * (ei / ra).sqrt()
                * (1.0 + t * l * l / (ei * j * j * PI * PI)).sqrt();
            assert_relative_eq!(w, spec, max_relative = ROUND_OFF);
            assert_relative_eq!(w, d.omega(j * PI / l), max_relative = ROUND_OFF);
        }
        // the string: ω_j = jπc/L
        let s = PinnedPinnedModes::new(0.0, t, ra, l).unwrap();
        let c = (t / ra).sqrt();
        assert_relative_eq!(s.omega(3), 3.0 * PI * c / l, max_relative = ROUND_OFF);
    }

    #[test]
    fn clamped_pinned_without_tension_is_euler_bernoulli() {
        let (ei, ra, l) = (3.0, 2.0, 1.7);
        let m = ClampedPinnedModes::new(ei, 0.0, ra, l).unwrap();
        for (j, bl) in EB_CLAMPED_PINNED.iter().enumerate() {
            let beta = m.beta(j + 1);
            assert_relative_eq!(beta * l, *bl, max_relative = ROOT);
            // ω = (βL)² sqrt(EI/(ρA L⁴))
            let w = bl * bl * (ei / (ra * l.powi(4))).sqrt();
            assert_relative_eq!(m.omega(j + 1), w, max_relative = ROOT);
        }
        // T → 0 continuously: the first correction is O(T L²/EI)
        let tiny = ClampedPinnedModes::new(ei, 1e-9 * ei / (l * l), ra, l).unwrap();
        assert_relative_eq!(tiny.beta(1) * l, EB_CLAMPED_PINNED[0], max_relative = 1e-9);
        // large modes: βL → (4j + 1)π/4
        let j = 200;
        assert_relative_eq!(
            m.beta(j) * l,
            (4 * j + 1) as f64 * PI / 4.0,
            max_relative = ROOT
        );
    }

    #[test]
    fn clamped_pinned_tends_to_the_string_as_ei_vanishes() {
        // bending length ℓb = sqrt(EI/T). The clamp shortens the effective span
        // by ℓb: ω_j ≈ jπc/(L − ℓb), with O((ℓb/L)² + (jπℓb/L)²) left over.
        let (t, ra, l): (f64, f64, f64) = (2e4, 1.35, 50.0);
        let c = (t / ra).sqrt();
        println!("  lb/L      j   (ω_j/(jπc/L) − 1)   (ω_j/(jπc/(L − lb)) − 1)");
        for lb_over_l in [1e-2, 1e-3, 1e-4, 1e-5] {
            let lb = lb_over_l * l;
            let m = ClampedPinnedModes::new(t * lb * lb, t, ra, l).unwrap();
            for j in 1..=5 {
                let w = m.omega(j);
                let string = j as f64 * PI * c / l;
                let shortened = j as f64 * PI * c / (l - lb);
                let second = 2.0 * (lb_over_l.powi(2) + (j as f64 * PI * lb_over_l).powi(2));
                println!(
                    "  {lb_over_l:.0e}  {j}   {:+.3e}          {:+.3e}",
                    w / string - 1.0,
                    w / shortened - 1.0
                );
                assert!((w / string - 1.0 - lb_over_l).abs() <= second, "j = {j}");
                assert!((w / shortened - 1.0).abs() <= second, "j = {j}");
            }
        }
    }

    #[test]
    fn clamped_pinned_interlaces_pinned_pinned() {
        // one more constraint (v'(0) = 0): ω_j^PP ≤ ω_j^CP ≤ ω_{j+1}^PP
        for (ei, t) in [(1.0, 0.0), (195.0, 2e4), (1e-3, 2e4), (50.0, 10.0)] {
            let cp = ClampedPinnedModes::new(ei, t, 1.35, 10.0).unwrap();
            let pp = PinnedPinnedModes::new(ei, t, 1.35, 10.0).unwrap();
            let w = cp.frequencies(30);
            for j in 1..=30 {
                assert!(
                    pp.omega(j) < w[j - 1] && w[j - 1] < pp.omega(j + 1),
                    "{ei} {t} {j}"
                );
            }
        }
    }

    #[test]
    fn scanning_finds_no_root_between_the_brackets() {
        // count sign changes of h on a fine ω grid (independent of the
        // bracketing argument): exactly one root below each ω_j.
        for (ei, t) in [(195.0, 2e4), (1.0, 0.0), (1e-4, 2e4), (5.0, 50.0)] {
            let m = ClampedPinnedModes::new(ei, t, 1.35, 50.0).unwrap();
            let n = 12;
            let w = m.frequencies(n);
            let wmax = 0.5 * (w[n - 1] + m.omega(n + 1));
            // β as a function of ω
            let beta_of = |om: f64| {
                let disc = (t * t + 4.0 * ei * 1.35 * om * om).sqrt();
                // β² = (disc − T)/(2EI), written without cancellation
                (2.0 * 1.35 * om * om / (disc + t)).sqrt()
            };
            let steps = 200_000;
            let mut count = 0;
            let mut prev = m.characteristic(beta_of(wmax / steps as f64));
            for i in 2..=steps {
                let h = m.characteristic(beta_of(wmax * i as f64 / steps as f64));
                if (h > 0.0) != (prev > 0.0) {
                    count += 1;
                }
                prev = h;
            }
            assert_eq!(count, n, "EI = {ei}, T = {t}");
            // and each root is a root: |h| at round-off
            for j in 1..=n {
                assert!(m.characteristic(m.beta(j)).abs() < 1e-12);
            }
        }
    }

    /// Hermite beam FE of MODEL §4, clamped–pinned, `n` elements: the lowest
    /// `modes` eigenfrequencies (an independent check of the characteristic
    /// equation for intermediate T L²/EI).
    fn hermite_clamped_pinned(
        ei: f64,
        t: f64,
        ra: f64,
        l: f64,
        n: usize,
        modes: usize,
    ) -> Vec<f64> {
        let h = l / n as f64;
        let dofs = 2 * (n + 1);
        let (k, m) = crate::analytic::dense_fe::hermite_km(ei, t, ra, h, n);
        // clamped: v0, θ0; pinned: v_N
        let keep: Vec<usize> = (0..dofs).filter(|&i| i > 1 && i != 2 * n).collect();
        let ev = crate::analytic::dense_fe::frequencies(&k, &m, &keep);
        ev.into_iter().take(modes).collect()
    }

    #[test]
    fn hermite_elements_converge_to_the_roots_at_fourth_order() {
        // T L²/EI = 25: bending and tension both matter.
        let (ei, t, ra, l) = (4.0, 100.0, 1.35, 1.0);
        let exact = ClampedPinnedModes::new(ei, t, ra, l)
            .unwrap()
            .frequencies(3);
        println!("  elements   rel. error of ω1, ω2, ω3");
        let mut prev: Option<Vec<f64>> = None;
        for n in [4, 8, 16] {
            let fe = hermite_clamped_pinned(ei, t, ra, l, n, 3);
            let err: Vec<f64> = fe.iter().zip(&exact).map(|(a, b)| a / b - 1.0).collect();
            println!("  {n:>8}   {:.3e}  {:.3e}  {:.3e}", err[0], err[1], err[2]);
            // consistent mass and conforming stiffness: FE frequencies are upper bounds
            assert!(err.iter().all(|e| *e > 0.0));
            if let Some(p) = prev {
                for (ep, e) in p.iter().zip(&err) {
                    let order = crate::study::uncertainty::observed_order(*ep, *e, 2.0);
                    println!("             observed order {order:.2}");
                    // h⁴ in the eigenvalue; pre-asymptotic modes may do better
                    assert!(order > 3.7 && order < 6.3, "order {order}");
                }
            }
            prev = Some(err);
        }
    }
}
