//! Rayleigh damping `C = α M + β K` (MODEL §10) and the damped free
//! vibration of one mode (docs/lines.md L12–L13): the independent
//! reference for the wire's damping, built before it.
//!
//! With mass-normalized modes (φⱼᵀMφⱼ = 1, φⱼᵀKφⱼ = ωⱼ²), C is diagonal in
//! the modes and each modal coordinate obeys
//! `q̈ + 2ζⱼωⱼ q̇ + ωⱼ² q = 0` with
//!
//! ```text
//! (L12) ζⱼ = α/(2ωⱼ) + β ωⱼ/2
//! ```
//!
//! Its free vibration from (q₀, q̇₀), in one form for every ζ ≥ 0, with
//! `ω_d² = ω²(1 − ζ²)` (negative when overdamped):
//!
//! ```text
//! (L13) q(t) = e^{−ζωt} [q₀ C(t) + (q̇₀ + ζω q₀) S(t)]
//!       q̇(t) = e^{−ζωt} [q̇₀ C(t) − (ω² q₀ + ζω q̇₀) S(t)]
//!       C = cos ω_d t, S = sin(ω_d t)/ω_d      (ζ < 1)
//!       C = 1,         S = t                   (ζ = 1)
//!       C = cosh γt,   S = sinh(γt)/γ,  γ = ω sqrt(ζ² − 1)   (ζ > 1)
//!       envelope (ζ < 1): |q(t)| ≤ A e^{−ζωt},  A = sqrt(q₀² + ((q̇₀ + ζωq₀)/ω_d)²)
//! ```
//!
//! S is evaluated as `t·sinc` by its series when |ω_d t| is small, so the
//! three cases join continuously at ζ = 1; when overdamped the products
//! `e^{−ζωt} cosh γt` are formed as sums of `e^{(−ζω ± γ)t}`, with
//! `ζω − γ = ω/(ζ + sqrt(ζ² − 1))` (no cancellation, no overflow).

use super::modes::{require_nonnegative, require_positive};
use crate::error::{Error, Result};

/// Rayleigh damping coefficients: `C = α M + β K`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rayleigh {
    /// α, 1/s (≥ 0): mass-proportional part.
    pub alpha: f64,
    /// β, s (≥ 0): stiffness-proportional part.
    pub beta: f64,
}

impl Rayleigh {
    /// Check the inputs: α, β ≥ 0 and finite.
    pub fn new(alpha: f64, beta: f64) -> Result<Self> {
        require_nonnegative("alpha", alpha, "1/s")?;
        require_nonnegative("beta", beta, "s")?;
        Ok(Rayleigh { alpha, beta })
    }

    /// The α, β that give ratio `zeta1` at `omega1` and `zeta2` at `omega2`
    /// (L12 at two frequencies: a 2×2 solve); an error if they differ in
    /// sign from α, β ≥ 0 (no Rayleigh damping fits those two ratios).
    pub fn from_two_modes(omega1: f64, zeta1: f64, omega2: f64, zeta2: f64) -> Result<Self> {
        require_positive("omega1", omega1, "rad/s")?;
        require_positive("omega2", omega2, "rad/s")?;
        require_nonnegative("zeta1", zeta1, "")?;
        require_nonnegative("zeta2", zeta2, "")?;
        if omega1 == omega2 {
            return Err(Error::invalid(
                "omega2",
                omega2,
                "must differ from omega1 (two modes fix two coefficients)",
            ));
        }
        // [1/(2ω₁) ω₁/2; 1/(2ω₂) ω₂/2] (α, β) = (ζ₁, ζ₂)
        let det = 0.25 * (omega2 / omega1 - omega1 / omega2);
        let alpha = (zeta1 * omega2 / 2.0 - zeta2 * omega1 / 2.0) / det;
        let beta = (zeta2 / (2.0 * omega1) - zeta1 / (2.0 * omega2)) / det;
        if alpha < 0.0 || beta < 0.0 {
            return Err(Error::invalid(
                "zeta1, zeta2",
                format!("{zeta1}, {zeta2}"),
                format!(
                    "need α, β ≥ 0; these give α = {alpha:.3e} 1/s, β = {beta:.3e} s (ζ₂/ζ₁ must lie between ω₁/ω₂ and ω₂/ω₁)"
                ),
            ));
        }
        Ok(Rayleigh {
            alpha: alpha.max(0.0),
            beta: beta.max(0.0),
        })
    }

    /// ζ(ω) = α/(2ω) + βω/2 (L12), for ω > 0 rad/s.
    pub fn ratio(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + self.beta * omega / 2.0
    }

    /// The damped oscillator of a mode at ω (L12 → L13).
    pub fn mode(&self, omega: f64) -> Result<DampedOscillator> {
        DampedOscillator::new(omega, self.ratio(omega))
    }
}

/// `q̈ + 2ζω q̇ + ω² q = 0`: one mode's free vibration (L13).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedOscillator {
    /// ω, rad/s (> 0): undamped natural frequency.
    pub omega: f64,
    /// ζ (≥ 0): damping ratio.
    pub zeta: f64,
}

/// Below this |ω_d t| (or γt), S(t) = t·sin(x)/x by its two-term series: the
/// next term is x⁴/120 ≈ 1e-18, below round-off.
const SINC_SERIES: f64 = 1e-4;

impl DampedOscillator {
    /// Check the inputs: ω > 0, ζ ≥ 0.
    pub fn new(omega: f64, zeta: f64) -> Result<Self> {
        require_positive("omega", omega, "rad/s")?;
        require_nonnegative("zeta", zeta, "")?;
        Ok(DampedOscillator { omega, zeta })
    }

    /// ζω, 1/s: the decay rate of the envelope (ζ ≤ 1).
    pub fn decay_rate(&self) -> f64 {
        self.zeta * self.omega
    }

    /// ω_d = ω sqrt(1 − ζ²), rad/s (0 when ζ ≥ 1).
    pub fn damped_omega(&self) -> f64 {
        self.omega * (1.0 - self.zeta * self.zeta).max(0.0).sqrt()
    }

    /// (e^{−ζωt} C(t), e^{−ζωt} S(t)) of L13.
    fn weights(&self, t: f64) -> (f64, f64) {
        let (w, z) = (self.omega, self.zeta);
        if z <= 1.0 {
            let wd = self.damped_omega();
            let x = wd * t;
            let s = if x.abs() < SINC_SERIES {
                t * (1.0 - x * x / 6.0)
            } else {
                x.sin() / wd
            };
            let e = (-z * w * t).exp();
            (e * x.cos(), e * s)
        } else {
            let root = (z * z - 1.0).sqrt();
            let gamma = w * root;
            let x = gamma * t;
            if x.abs() < SINC_SERIES {
                let e = (-z * w * t).exp();
                return (e * (1.0 + x * x / 2.0), e * t * (1.0 + x * x / 6.0));
            }
            // slow and fast exponents −ζω ± γ; the slow one without cancellation
            let slow = (-w / (z + root) * t).exp();
            let fast = (-(z * w + gamma) * t).exp();
            (0.5 * (slow + fast), 0.5 * (slow - fast) / gamma)
        }
    }

    /// (q(t), q̇(t)) from (q₀, q̇₀) at t = 0 (L13).
    pub fn free(&self, q0: f64, v0: f64, t: f64) -> (f64, f64) {
        let (w, z) = (self.omega, self.zeta);
        let (c, s) = self.weights(t);
        (
            q0 * c + (v0 + z * w * q0) * s,
            v0 * c - (w * w * q0 + z * w * v0) * s,
        )
    }

    /// The envelope A e^{−ζωt} that bounds |q(t)| (L13), ζ < 1.
    pub fn envelope(&self, q0: f64, v0: f64, t: f64) -> Result<f64> {
        if self.zeta >= 1.0 {
            return Err(Error::invalid(
                "zeta",
                self.zeta,
                "an envelope needs an underdamped mode (ζ < 1)",
            ));
        }
        let wd = self.damped_omega();
        let b = (v0 + self.zeta * self.omega * q0) / wd;
        Ok(q0.hypot(b) * (-self.decay_rate() * t).exp())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// RK4 at ω Δt = 2π/2000 over 10 periods: global error ≈ (ωΔt)⁴·ωt/120
    /// ≈ 1e-11 of the amplitude (measured ≤ 5e-11, and 1.0e-10 at ζ = 2.5,
    /// whose fast exponent 4.8ω is the stiffest).
    const RK4: f64 = 5e-10;
    /// ζ from the logarithmic decrement of RK4 peaks located by a parabola
    /// through three samples (ωΔt = 2π/2000): the parabola's vertex error and
    /// RK4's, measured ≤ 3.2e-12 of ζ at ζ ≥ 0.01.
    const LOG_DECREMENT: f64 = 1e-9;

    /// RK4 of q̈ = −2ζωq̇ − ω²q, n steps of dt: every (q, q̇).
    fn rk4(osc: &DampedOscillator, q0: f64, v0: f64, dt: f64, n: usize) -> Vec<(f64, f64)> {
        let (w, z) = (osc.omega, osc.zeta);
        let f = |q: f64, v: f64| (v, -2.0 * z * w * v - w * w * q);
        let mut out = vec![(q0, v0)];
        let (mut q, mut v) = (q0, v0);
        for _ in 0..n {
            let k1 = f(q, v);
            let k2 = f(q + 0.5 * dt * k1.0, v + 0.5 * dt * k1.1);
            let k3 = f(q + 0.5 * dt * k2.0, v + 0.5 * dt * k2.1);
            let k4 = f(q + dt * k3.0, v + dt * k3.1);
            q += dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            v += dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            out.push((q, v));
        }
        out
    }

    #[test]
    fn validation_names_the_field() {
        let e = Rayleigh::new(-1.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("`alpha`"), "{e}");
        let e = DampedOscillator::new(0.0, 0.1).unwrap_err();
        assert!(e.to_string().contains("`omega`"), "{e}");
        let e = Rayleigh::from_two_modes(10.0, 0.01, 10.0, 0.02).unwrap_err();
        assert!(e.to_string().contains("omega2"), "{e}");
        // ζ₂/ζ₁ above ω₂/ω₁ would need α < 0
        let e = Rayleigh::from_two_modes(1.0, 0.01, 10.0, 0.5).unwrap_err();
        assert!(e.to_string().contains("zeta1, zeta2"), "{e}");
        let over = DampedOscillator::new(3.0, 1.5).unwrap();
        assert!(over.envelope(1.0, 0.0, 1.0).is_err());
    }

    #[test]
    fn ratio_is_l12_and_two_modes_invert_it() {
        let r = Rayleigh::new(0.4, 2e-4).unwrap();
        assert_relative_eq!(
            r.ratio(20.0),
            0.4 / 40.0 + 2e-4 * 10.0,
            max_relative = 1e-15
        );
        // minimum at ω = sqrt(α/β), ζ_min = sqrt(αβ)
        let wmin = (0.4_f64 / 2e-4).sqrt();
        assert_relative_eq!(r.ratio(wmin), (0.4_f64 * 2e-4).sqrt(), max_relative = 1e-15);
        assert!(r.ratio(0.9 * wmin) > r.ratio(wmin) && r.ratio(1.1 * wmin) > r.ratio(wmin));
        let fit = Rayleigh::from_two_modes(6.0, r.ratio(6.0), 90.0, r.ratio(90.0)).unwrap();
        assert_relative_eq!(fit.alpha, r.alpha, max_relative = 1e-12);
        assert_relative_eq!(fit.beta, r.beta, max_relative = 1e-12);
    }

    #[test]
    fn free_decay_matches_rk4_in_every_regime() {
        let (q0, v0) = (0.02, -0.3);
        println!("  ζ      max |closed form − RK4| / amplitude");
        for zeta in [0.0, 0.02, 0.3, 0.999_999, 1.0, 1.000_001, 2.5] {
            let osc = DampedOscillator::new(12.0, zeta).unwrap();
            let period = 2.0 * std::f64::consts::PI / osc.omega;
            let (dt, n) = (period / 2000.0, 20_000);
            let path = rk4(&osc, q0, v0, dt, n);
            let amp = q0.hypot(v0 / osc.omega);
            let mut worst: f64 = 0.0;
            for (i, (q, v)) in path.iter().enumerate().step_by(97) {
                let (qc, vc) = osc.free(q0, v0, i as f64 * dt);
                worst = worst.max((qc - q).abs() / amp);
                worst = worst.max((vc - v).abs() / (amp * osc.omega));
            }
            println!("  {zeta:<9} {worst:.2e}");
            assert!(worst < RK4, "ζ = {zeta}: {worst}");
            // the initial state is reproduced exactly
            assert_eq!(osc.free(q0, v0, 0.0), (q0, v0));
        }
    }

    #[test]
    fn rayleigh_mode_decays_at_its_ratio() {
        // RK4 of each mode of a Rayleigh-damped line; ζ read from the
        // logarithmic decrement of successive positive peaks
        let r = Rayleigh::new(0.3, 4e-4).unwrap();
        println!("  ω       ζ (L12)      ζ (RK4 log decrement)");
        for omega in [5.0, 27.0, 150.0] {
            let osc = r.mode(omega).unwrap();
            let period = 2.0 * std::f64::consts::PI / osc.damped_omega();
            let dt = period / 2000.0;
            let path = rk4(&osc, 1.0, 0.0, dt, 2000 * 6);
            let mut peaks = Vec::new();
            for i in 1..path.len() - 1 {
                let (a, b, c) = (path[i - 1].0, path[i].0, path[i + 1].0);
                if b > a && b >= c && b > 0.0 {
                    // parabola through three samples: its vertex value
                    let curv = a - 2.0 * b + c;
                    peaks.push(b - (c - a) * (c - a) / (8.0 * curv));
                }
            }
            assert!(peaks.len() >= 4, "{}", peaks.len());
            let delta = (peaks[0] / peaks[3]).ln() / 3.0;
            let zeta = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
            println!(
                "  {omega:<7} {:.9}  {zeta:.9}   rel. diff. {:.1e}",
                osc.zeta,
                (zeta / osc.zeta - 1.0).abs()
            );
            assert_relative_eq!(zeta, osc.zeta, max_relative = LOG_DECREMENT);
            // and the envelope bounds the closed form, touching it at peaks
            let env = osc.envelope(1.0, 0.0, 0.0).unwrap();
            for i in 0..400 {
                let t = i as f64 * period / 37.0;
                let (q, _) = osc.free(1.0, 0.0, t);
                assert!(q.abs() <= osc.envelope(1.0, 0.0, t).unwrap() * (1.0 + 1e-14));
            }
            assert!(env >= 1.0);
        }
    }
}
