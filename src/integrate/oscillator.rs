//! The exact step of a linear oscillator over Δt (Duhamel; Nigam & Jennings
//! 1969; MODEL §9.3): what `modal_exact` advances each mode and each mass
//! dof with.
//!
//! **A mode** (mass-normalized, undamped: the beam of MODEL §1 has no
//! damping), `η̈ + ω²η = f(t)`, with the load linear in time over the step
//! between its samples `f_n`, `f_{n+1}` (first-order hold), has the exact
//! step map
//!
//! ```text
//! η_{n+1} = cos(u) η_n + sin(u)/ω η̇_n + a0 f_n + a1 f_{n+1}
//! η̇_{n+1} = −ω sin(u) η_n + cos(u) η̇_n + b0 f_n + b1 f_{n+1},    u = ωΔt,
//! a1 = Δt² (u − sin u)/u³,  a0 = Δt² · 2 sin²(u/2)/u² − a1,
//! b1 = Δt · 2 sin²(u/2)/u²,  b0 = Δt · sin(u)/u − b1
//! ```
//!
//! (`∫₀^Δt sin(ω(Δt − τ))/ω · τ/Δt dτ = (u − sin u)/(ω³Δt)`, and so on). A
//! load held over the step (`f_n = f_{n+1}`) enters with `a0 + a1 =
//! (1 − cos u)/ω²` and `b0 + b1 = sin(u)/ω`. Every coefficient is written
//! without cancellation: `1 − cos u = 2 sin²(u/2)`, and `(u − sin u)/u³` by
//! its series below u = 1 (its direct form loses up to `6ε/u²` there). At
//! ω = 0 they take their limits (Δt²/3, Δt²/6, Δt/2, Δt/2).
//!
//! **A mass dof**, `m q̈ + c q̇ + k q = F` with F held over the step (the
//! contact force is; MODEL §2), has the step map
//! `[q, q̇]_{n+1} = E [q, q̇]_n + g F`, from the exponential of the augmented
//! matrix of `(q, q̇, F)` (nalgebra's Padé scaling-and-squaring), which covers
//! every case at once: under-, critically and over-damped, no spring (a
//! riding mass), no dashpot.

use nalgebra::Matrix3;

/// Below this u = ωΔt, `(u − sin u)/u³` is summed as its series (ten terms:
/// remainder below u²⁰/23! ≈ 4·10⁻²³ at u = 1); above it the direct form
/// loses at most 6ε/u² ≤ 6ε.
const SERIES_BELOW: f64 = 1.0;

/// The exact step maps of J modes at one Δt (module docs), one array per
/// coefficient (what the step's vector loops read).
#[derive(Debug, Clone, PartialEq)]
pub struct ModeSteps {
    /// Δt, s.
    pub dt: f64,
    /// cos(ωΔt).
    pub cos: Vec<f64>,
    /// sin(ωΔt)/ω, s.
    pub sin_over_omega: Vec<f64>,
    /// −ω sin(ωΔt), 1/s.
    pub minus_omega_sin: Vec<f64>,
    /// η̇_{n+1} per η̇_n: cos(ωΔt) here; its own value for a damped mode
    /// (`damped_modes.rs`).
    pub cos_v: Vec<f64>,
    /// a0, a1: η_{n+1} per unit load sample at t_n, t_{n+1}, s².
    pub a0: Vec<f64>,
    /// See `a0`.
    pub a1: Vec<f64>,
    /// b0, b1: η̇_{n+1} per unit load sample at t_n, t_{n+1}, s.
    pub b0: Vec<f64>,
    /// See `b0`.
    pub b1: Vec<f64>,
}

/// `(u − sin u)/u³`, without cancellation.
fn u_minus_sin_over_u3(u: f64) -> f64 {
    if u < SERIES_BELOW {
        // Σ_k (−u²)^k/(2k + 3)!, k = 0 … 9, by Horner from k = 9 down
        const INV: [f64; 10] = {
            let mut c = [0.0; 10];
            let mut k = 0;
            while k < 10 {
                let mut fact = 1.0;
                let mut i = 2;
                while i <= 2 * k + 3 {
                    fact *= i as f64;
                    i += 1;
                }
                c[k] = 1.0 / fact;
                k += 1;
            }
            c
        };
        let x = -u * u;
        INV.iter().rev().fold(0.0, |acc, c| acc * x + c)
    } else {
        (u - u.sin()) / (u * u * u)
    }
}

/// The exact step map of one undamped mode over `dt` (module docs): what
/// [`ModeSteps`] stores for each of J modes at the run's Δt, and what a
/// located re-contact (`modal_impact.rs`) evaluates at its own sub-steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ModeStep {
    /// cos(ωΔt).
    pub cos: f64,
    /// sin(ωΔt)/ω, s.
    pub sin_over_omega: f64,
    /// −ω sin(ωΔt), 1/s.
    pub minus_omega_sin: f64,
    /// η_{n+1} per unit load sample at t_n, t_{n+1}, s².
    pub a0: f64,
    /// See `a0`.
    pub a1: f64,
    /// η̇_{n+1} per unit load sample at t_n, t_{n+1}, s.
    pub b0: f64,
    /// See `b0`.
    pub b1: f64,
}

impl ModeStep {
    /// The step map of a mode of angular frequency `w` (rad/s, ≥ 0) over
    /// `dt` (s), every coefficient without cancellation (module docs).
    #[inline]
    pub fn of(w: f64, dt: f64) -> Self {
        let u = w * dt;
        let (su, cu) = u.sin_cos();
        // 2 sin²(u/2)/u² = (1 − cos u)/u², and sin(u)/u
        let (c2, sinc) = if u > 0.0 {
            let h = (0.5 * u).sin();
            (2.0 * h * h / (u * u), su / u)
        } else {
            (0.5, 1.0)
        };
        let s3 = u_minus_sin_over_u3(u);
        let a1 = dt * dt * s3;
        let b1 = dt * c2;
        ModeStep {
            cos: cu,
            sin_over_omega: dt * sinc,
            minus_omega_sin: -w * su,
            a0: dt * dt * c2 - a1,
            a1,
            b0: dt * sinc - b1,
            b1,
        }
    }
}

impl ModeSteps {
    /// The step maps of modes with angular frequencies `omega` (rad/s, ≥ 0) at `dt`.
    pub fn new(omega: &[f64], dt: f64) -> Self {
        let n = omega.len();
        let mut m = ModeSteps {
            dt,
            cos: Vec::with_capacity(n),
            sin_over_omega: Vec::with_capacity(n),
            minus_omega_sin: Vec::with_capacity(n),
            cos_v: Vec::with_capacity(n),
            a0: Vec::with_capacity(n),
            a1: Vec::with_capacity(n),
            b0: Vec::with_capacity(n),
            b1: Vec::with_capacity(n),
        };
        for &w in omega {
            let c = ModeStep::of(w, dt);
            m.cos.push(c.cos);
            m.sin_over_omega.push(c.sin_over_omega);
            m.minus_omega_sin.push(c.minus_omega_sin);
            m.cos_v.push(c.cos);
            // a deliberate defect of the test build (`crate::defects`)
            let (a0, a1) = if crate::defects::on(crate::defects::Defect::HoldSwapped) {
                (c.a1, c.a0)
            } else {
                (c.a0, c.a1)
            };
            m.a0.push(a0);
            m.a1.push(a1);
            m.b0.push(c.b0);
            m.b1.push(c.b1);
        }
        m
    }

    /// J.
    pub fn len(&self) -> usize {
        self.cos.len()
    }

    /// True for no modes.
    pub fn is_empty(&self) -> bool {
        self.cos.is_empty()
    }
}

/// The exact step map of a mass dof under a force held over the step
/// (module docs): `[q, q̇]_{n+1} = E [q, q̇]_n + g F`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MassStep {
    /// E, row-major.
    pub e: [[f64; 2]; 2],
    /// g: q and q̇ per newton held over the step, m/N and m/(N·s).
    pub g: [f64; 2],
}

impl MassStep {
    /// `m q̈ + c q̇ + k q = F` (m > 0; k, c ≥ 0) over `dt`.
    pub fn new(m: f64, k: f64, c: f64, dt: f64) -> Self {
        #[rustfmt::skip]
        let a = Matrix3::new(
            0.0, 1.0, 0.0,
            -k / m, -c / m, 1.0 / m,
            0.0, 0.0, 0.0,
        ) * dt;
        let x = a.exp();
        MassStep {
            e: [[x[(0, 0)], x[(0, 1)]], [x[(1, 0)], x[(1, 1)]]],
            g: [x[(0, 2)], x[(1, 2)]],
        }
    }

    /// `[q, q̇]` after the step from `q`, `v` = q̇ under `f` held.
    #[inline]
    pub fn apply(&self, q: f64, v: f64, f: f64) -> (f64, f64) {
        (
            self.e[0][0] * q + self.e[0][1] * v + self.g[0] * f,
            self.e[1][0] * q + self.e[1][1] * v + self.g[1] * f,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed forms evaluated two ways: a few ulps, scaled by the size of
    /// the quantity.
    const ROUND_OFF: f64 = 1e-14;

    #[test]
    fn the_series_joins_the_direct_form() {
        for u in [1e-8, 1e-3, 0.3, 0.999_999, 1.0, 1.5, 10.0] {
            let s = u_minus_sin_over_u3(u);
            if u >= 0.05 {
                let direct = (u - u.sin()) / (u * u * u);
                assert!((s - direct).abs() <= 1e3 * f64::EPSILON * direct, "{u}");
            }
            // the series' own first terms
            let approx = 1.0 / 6.0 - u * u / 120.0 + u.powi(4) / 5040.0;
            if u < 0.1 {
                assert!((s - approx).abs() <= 1e-12, "{u}");
            }
        }
        assert_eq!(u_minus_sin_over_u3(0.0), 1.0 / 6.0);
    }

    /// The coefficients against Duhamel's integrals by composite Simpson
    /// quadrature (20 000 panels: at most 0.015 rad of the fastest
    /// oscillation per panel, error ~1e-12 of the scale).
    #[test]
    fn coefficients_are_duhamel_integrals() {
        let dt = 1e-3;
        for w in [0.0, 3.0, 700.0, 1e4, 3e5] {
            let m = ModeSteps::new(&[w], dt);
            let n = 20_000;
            let h = dt / n as f64;
            let g = |s: f64| if w > 0.0 { (w * s).sin() / w } else { s };
            let gd = |s: f64| (w * s).cos();
            let simpson = |f: &dyn Fn(f64) -> f64| {
                let mut acc = f(0.0) + f(dt);
                for i in 1..n {
                    acc += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
                }
                acc * h / 3.0
            };
            let a1 = simpson(&|t| g(dt - t) * t / dt);
            let a0 = simpson(&|t| g(dt - t) * (1.0 - t / dt));
            let b1 = simpson(&|t| gd(dt - t) * t / dt);
            let b0 = simpson(&|t| gd(dt - t) * (1.0 - t / dt));
            let scale = dt * dt;
            assert!(
                (m.a1[0] - a1).abs() <= 1e-10 * scale,
                "{w}: {} {a1}",
                m.a1[0]
            );
            assert!((m.a0[0] - a0).abs() <= 1e-10 * scale, "{w}");
            assert!((m.b1[0] - b1).abs() <= 1e-10 * dt, "{w}");
            assert!((m.b0[0] - b0).abs() <= 1e-10 * dt, "{w}");
            // a held load: a0 + a1 = (1 − cos u)/ω²
            if w > 0.0 {
                let held = (1.0 - (w * dt).cos()) / (w * w);
                assert!((m.a0[0] + m.a1[0] - held).abs() <= 1e-6 * held.abs() + ROUND_OFF * scale);
            }
        }
    }

    #[test]
    fn the_free_map_is_a_rotation_of_the_energy() {
        let (w, dt) = (37.0, 0.013);
        let m = ModeSteps::new(&[w], dt);
        let (mut q, mut v) = (0.3, -2.0);
        let e0 = v * v + w * w * q * q;
        for _ in 0..1000 {
            (q, v) = (
                m.cos[0] * q + m.sin_over_omega[0] * v,
                m.minus_omega_sin[0] * q + m.cos[0] * v,
            );
        }
        let t = 1000.0 * dt;
        let exact = 0.3 * (w * t).cos() - 2.0 / w * (w * t).sin();
        assert!((q - exact).abs() <= 1e-12, "{q} {exact}");
        assert!(((v * v + w * w * q * q) / e0 - 1.0).abs() <= 1e-12);
    }

    #[test]
    fn the_mass_step_is_the_closed_form() {
        // undamped spring: E = rotation, g = ((1 − cos)/(mω²), sin/(mω))
        let (m, k, dt): (f64, f64, f64) = (2.0, 987.0, 1e-3);
        let w = (k / m).sqrt();
        let s = MassStep::new(m, k, 0.0, dt);
        let (sn, cs) = (w * dt).sin_cos();
        let want = [[cs, sn / w], [-w * sn, cs]];
        for r in 0..2 {
            for c in 0..2 {
                assert!((s.e[r][c] - want[r][c]).abs() <= ROUND_OFF * want[r][c].abs().max(1.0));
            }
        }
        assert!((s.g[0] - (1.0 - cs) / (m * w * w)).abs() <= ROUND_OFF * dt * dt);
        assert!((s.g[1] - sn / (m * w)).abs() <= ROUND_OFF * dt);
        // a riding mass (k = c = 0): free flight
        let f = MassStep::new(3.0, 0.0, 0.0, dt);
        assert_eq!(f.e, [[1.0, dt], [0.0, 1.0]]);
        assert!((f.g[0] - dt * dt / 6.0).abs() <= ROUND_OFF * dt * dt);
        assert!((f.g[1] - dt / 3.0).abs() <= ROUND_OFF * dt);
        // damped: the step map composes (E(2Δt) = E(Δt)²) and decays
        let (c, k2) = (40.0, 300.0);
        let one = MassStep::new(m, k2, c, dt);
        let two = MassStep::new(m, k2, c, 2.0 * dt);
        let (q, v) = one.apply(0.01, 0.5, 3.0);
        let (q1, v1) = one.apply(q, v, 3.0);
        let (q2, v2) = two.apply(0.01, 0.5, 3.0);
        assert!((q1 - q2).abs() <= 1e-14 && (v1 - v2).abs() <= 1e-12);
    }
}
