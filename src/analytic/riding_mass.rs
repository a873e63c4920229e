//! A mass riding (bilateral, no spring) on a pinned–pinned tensioned beam at
//! constant speed, solved in the exact eigenfunctions (MODEL §9.2 `galerkin`):
//! a reference for the moving *mass* with no finite-element code on its path.
//!
//! Basis `φ_j = sin(κ_j x)`, `κ_j = jπ/L`, `j = 1 … J`, modal mass
//! `M_j = ρA L/2`, `ω_j` of MODEL §8 ([`PinnedPinnedModes`]). With
//! `v = Σ a_j φ_j` (m, positive up) and `x_m = x₀ + V t`, the attached mass
//! moves with `v(x_m(t), t)`, so its acceleration is the convective total
//! derivative (MODEL §9.2)
//!
//! ```text
//! v̈_m = Σ_j [a_j'' φ_j + 2V a_j' φ_j' + V² a_j φ_j'']   at x = x_m.
//! ```
//!
//! The beam carries the force `F_b = s·λ` (up) at `x_m`, and the mass's
//! balance (MODEL §2, k = 0, `q = s·v_m`) gives `λ = −s·m (g + v̈_m)`, so
//! `F_b = −m (g + v̈_m)` on either side: gravity pulls the mass down, its
//! inertia resists the beam's motion. Projected on the basis,
//!
//! ```text
//! (M + m φφᵀ) a'' + 2mV φφ'ᵀ a' + (K + m V² φφ''ᵀ) a = −m g φ.
//! ```
//!
//! `M + m φφᵀ` is diagonal plus rank one, so each `a''` is solved exactly in
//! O(J) by Sherman–Morrison (a unit test holds it against a dense LU). The
//! first-order system `(a, a')` is integrated with classical RK4 — no
//! relation to taut's implicit integrators — at a step at most
//! `STEP_FACTOR/ω_J`, from MODEL §5's start (straight, at rest, gravity on at
//! t = 0). Outputs: `w = s·v(x_m)`, its rate, and the contact force `λ`.

use std::f64::consts::PI;

use super::PinnedPinnedModes;
use super::modes::{require_nonnegative, require_positive};
use crate::error::{Error, Result};
use crate::scene::Side;

/// Largest `ω_J Δt` of the Runge–Kutta step: RK4 is stable up to
/// `ω Δt ≈ 2.8` on the imaginary axis and its per-step phase error falls like
/// `(ω Δt)⁵/120`, so the highest mode dominates the time error. Measured on
/// `scenes/riding_mass_pinned.toml` (J = 800, 0.4 s): halving the step from
/// 0.5/ω_J changes w by 1.5e-6 m, from 0.25/ω_J by 9.4e-8 m (fourth order),
/// i.e. 5e-7 of max |w| here, well under the J-truncation error.
pub(crate) const STEP_FACTOR: f64 = 0.25;

/// A riding mass on a pinned–pinned tensioned beam (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RidingMassBeam {
    /// The beam's pinned–pinned modes (EI > 0, T ≥ 0, ρA, L).
    pub beam: PinnedPinnedModes,
    /// m, kg (> 0).
    pub mass: f64,
    /// Gravity on the mass, m/s² (≥ 0).
    pub gravity: f64,
    /// The side of the beam the mass is on (sets the sign of w and λ).
    pub side: Side,
    /// x₀, m, in [0, L).
    pub start: f64,
    /// V, m/s (≥ 0).
    pub speed: f64,
}

/// Sampled solution of [`RidingMassBeam::solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct RidingMassHistory {
    /// Sampling interval, s.
    pub dt: f64,
    /// Sample times `k·dt`, s.
    pub t: Vec<f64>,
    /// `w = s·v(x_m(t), t)`, m.
    pub w: Vec<f64>,
    /// `dw/dt` along the mass path, m/s.
    pub w_rate: Vec<f64>,
    /// Contact force λ, N (positive pressing, MODEL §2).
    pub force: Vec<f64>,
}

impl RidingMassHistory {
    /// `w` at time `t` (s), m: cubic Hermite interpolation of the samples
    /// (values and rates; error O(dt⁴)), exact at the sample times. NaN
    /// outside the sampled interval.
    pub fn w_at(&self, t: f64) -> f64 {
        let n = self.t.len();
        if n == 0 || !(0.0..=self.t[n - 1] + 1e-9 * self.dt).contains(&t) {
            return f64::NAN;
        }
        let u = t / self.dt;
        let k = (u.floor() as usize).min(n.saturating_sub(2));
        if n == 1 {
            return self.w[0];
        }
        let s = (u - k as f64).clamp(0.0, 1.0);
        let (h00, h10) = (
            1.0 - 3.0 * s * s + 2.0 * s * s * s,
            s - 2.0 * s * s + s * s * s,
        );
        let (h01, h11) = (3.0 * s * s - 2.0 * s * s * s, s * s * s - s * s);
        h00 * self.w[k]
            + h10 * self.dt * self.w_rate[k]
            + h01 * self.w[k + 1]
            + h11 * self.dt * self.w_rate[k + 1]
    }
}

/// `(φ_j, φ_j', φ_j'')` at x for j = 1 … J, by the angle-addition recurrence
/// (error grows like j·ε, harmless for the J used here).
fn basis(x: f64, l: f64, modes: usize, phi: &mut [f64], dphi: &mut [f64], ddphi: &mut [f64]) {
    let th = PI * x / l;
    let (s1, c1) = th.sin_cos();
    let (mut s, mut c) = (s1, c1);
    for j in 0..modes {
        let kappa = (j + 1) as f64 * PI / l;
        phi[j] = s;
        dphi[j] = kappa * c;
        ddphi[j] = -kappa * kappa * s;
        (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
    }
}

/// The riding mass of a [`RidingMassBeam`] (MODEL §2, §3; SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rider {
    /// Mass m, kg (> 0).
    pub mass: f64,
    /// Gravity g, m/s² (≥ 0).
    pub gravity: f64,
    /// The side of the beam it rides on.
    pub side: Side,
    /// x_m(0), m, in [0, L).
    pub start: f64,
    /// Constant speed V, m/s (≥ 0).
    pub speed: f64,
}

/// Work arrays for one right-hand-side evaluation.
struct Work {
    omega2: Vec<f64>,
    phi: Vec<f64>,
    dphi: Vec<f64>,
    ddphi: Vec<f64>,
}

impl RidingMassBeam {
    /// Check the inputs (module docs). EI must be > 0: on a string the
    /// curvature under a point load is a delta, `φ''ᵀa` diverges with J and
    /// the convective series has no limit.
    pub fn new(ei: f64, tension: f64, rho_a: f64, length: f64, rider: Rider) -> Result<Self> {
        let Rider {
            mass,
            gravity,
            side,
            start,
            speed,
        } = rider;
        require_positive(
            "ei",
            ei,
            "N·m²; a riding mass on a string (EI = 0) has no convergent Galerkin solution",
        )?;
        require_nonnegative("tension", tension, "N")?;
        let beam = PinnedPinnedModes::new(ei, tension, rho_a, length)?;
        require_positive("mass", mass, "kg")?;
        require_nonnegative("gravity", gravity, "m/s²")?;
        require_nonnegative("speed", speed, "m/s")?;
        if !(start.is_finite() && (0.0..length).contains(&start)) {
            return Err(Error::invalid(
                "start",
                start,
                format!("must be in [0, {length}) m (on the span)"),
            ));
        }
        Ok(RidingMassBeam {
            beam,
            mass,
            gravity,
            side,
            start,
            speed,
        })
    }

    /// Largest Runge–Kutta step for J modes, `STEP_FACTOR/ω_J`, s.
    pub fn max_step(&self, modes: usize) -> f64 {
        STEP_FACTOR / self.beam.omega(modes.max(1))
    }

    /// Time the mass reaches x = L, s (infinite at V = 0).
    pub fn exit_time(&self) -> f64 {
        (self.beam.length - self.start) / self.speed
    }

    /// `(a'', F_b)` at position `x` for state `(a, b = a')`; fills `acc`.
    fn rhs(&self, x: f64, a: &[f64], b: &[f64], acc: &mut [f64], w: &mut Work) -> f64 {
        let n = a.len();
        let mj = 0.5 * self.beam.rho_a * self.beam.length;
        basis(
            x,
            self.beam.length,
            n,
            &mut w.phi,
            &mut w.dphi,
            &mut w.ddphi,
        );
        let (mut u, mut c1, mut c2, mut s) = (0.0, 0.0, 0.0, 0.0);
        for j in 0..n {
            u -= w.phi[j] * w.omega2[j] * a[j];
            c1 += w.dphi[j] * b[j];
            c2 += w.ddphi[j] * a[j];
            s += w.phi[j] * w.phi[j];
        }
        let v = self.speed;
        let conv = 2.0 * v * c1 + v * v * c2;
        let m = self.mass;
        let fb = -m * (self.gravity + u + conv) / (1.0 + m * s / mj);
        for j in 0..n {
            acc[j] = -w.omega2[j] * a[j] + w.phi[j] * fb / mj;
        }
        fb
    }

    /// Integrate with J = `modes` and a Runge–Kutta step at most `step` (s),
    /// sampling every `dt_out` (s) up to `t_end` (s) (the last sample is the
    /// last whole `dt_out` ≤ `t_end`). `t_end` must leave the mass on the span.
    pub fn solve(
        &self,
        modes: usize,
        step: f64,
        dt_out: f64,
        t_end: f64,
    ) -> Result<RidingMassHistory> {
        if modes == 0 {
            return Err(Error::invalid("modes", modes, "must be ≥ 1 (J)"));
        }
        require_positive("step", step, "s")?;
        require_positive("dt_out", dt_out, "s")?;
        require_nonnegative("t_end", t_end, "s")?;
        if t_end > self.exit_time() * (1.0 + 1e-12) {
            return Err(Error::invalid(
                "t_end",
                t_end,
                format!(
                    "must be ≤ {} s (the mass leaves the span then)",
                    self.exit_time()
                ),
            ));
        }
        let samples = (t_end / dt_out * (1.0 + 1e-12)).floor() as usize;
        let sub = (dt_out / step).ceil().max(1.0) as usize;
        let h = dt_out / sub as f64;
        let n = modes;
        let mut work = Work {
            omega2: (1..=n).map(|j| self.beam.omega(j).powi(2)).collect(),
            phi: vec![0.0; n],
            dphi: vec![0.0; n],
            ddphi: vec![0.0; n],
        };
        let s = self.side.sign();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        let mut hist = RidingMassHistory {
            dt: dt_out,
            t: Vec::with_capacity(samples + 1),
            w: Vec::with_capacity(samples + 1),
            w_rate: Vec::with_capacity(samples + 1),
            force: Vec::with_capacity(samples + 1),
        };
        let mut acc = vec![0.0; n];
        let (mut ka, mut kb) = (vec![[0.0; 4]; n], vec![[0.0; 4]; n]);
        let (mut ta, mut tb) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..=samples {
            let t = k as f64 * dt_out;
            let x = self.start + self.speed * t;
            // sample: w, its rate along the path, and λ = s·F_b
            let fb = self.rhs(x, &a, &b, &mut acc, &mut work);
            let (mut vm, mut rate) = (0.0, 0.0);
            for j in 0..n {
                vm += work.phi[j] * a[j];
                rate += work.phi[j] * b[j] + self.speed * work.dphi[j] * a[j];
            }
            hist.t.push(t);
            hist.w.push(s * vm);
            hist.w_rate.push(s * rate);
            hist.force.push(s * fb);
            if k == samples {
                break;
            }
            for i in 0..sub {
                let t0 = t + i as f64 * h;
                for stage in 0..4 {
                    let (c, from) = match stage {
                        0 => (0.0, None),
                        1 | 2 => (0.5, Some(stage - 1)),
                        _ => (1.0, Some(2)),
                    };
                    for j in 0..n {
                        (ta[j], tb[j]) = match from {
                            None => (a[j], b[j]),
                            Some(p) => (a[j] + c * h * ka[j][p], b[j] + c * h * kb[j][p]),
                        };
                    }
                    let x = self.start + self.speed * (t0 + c * h);
                    self.rhs(x, &ta, &tb, &mut acc, &mut work);
                    for j in 0..n {
                        ka[j][stage] = tb[j];
                        kb[j][stage] = acc[j];
                    }
                }
                for j in 0..n {
                    let (p, q) = (ka[j], kb[j]);
                    a[j] += h / 6.0 * (p[0] + 2.0 * p[1] + 2.0 * p[2] + p[3]);
                    b[j] += h / 6.0 * (q[0] + 2.0 * q[1] + 2.0 * q[2] + q[3]);
                }
            }
        }
        Ok(hist)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::MovingForceBeam;
    use nalgebra::{DMatrix, DVector};

    // The study's wire (scenes/riding_mass_pinned.toml): c = 149.9 m/s.
    const EI: f64 = 1.34e11 * 9.64e-10;
    const T: f64 = 3.0e4;
    const RA: f64 = 8900.0 * 1.5e-4;
    const L: f64 = 50.0;
    const G: f64 = 9.81;

    fn wire(mass: f64, speed: f64) -> RidingMassBeam {
        RidingMassBeam::new(
            EI,
            T,
            RA,
            L,
            Rider {
                mass,
                gravity: G,
                side: Side::Above,
                start: 0.0,
                speed,
            },
        )
        .unwrap()
    }

    #[test]
    fn validation_names_the_field() {
        let bad = |ei, t, m, g, x0, v| {
            RidingMassBeam::new(
                ei,
                t,
                RA,
                L,
                Rider {
                    mass: m,
                    gravity: g,
                    side: Side::Above,
                    start: x0,
                    speed: v,
                },
            )
            .unwrap_err()
            .to_string()
        };
        assert!(bad(0.0, T, 1.0, G, 0.0, 1.0).contains("ei"));
        assert!(bad(EI, -1.0, 1.0, G, 0.0, 1.0).contains("tension"));
        assert!(bad(EI, T, 0.0, G, 0.0, 1.0).contains("mass"));
        assert!(bad(EI, T, 1.0, f64::NAN, 0.0, 1.0).contains("gravity"));
        assert!(bad(EI, T, 1.0, G, L, 1.0).contains("start"));
        assert!(bad(EI, T, 1.0, G, -1.0, 1.0).contains("start"));
        assert!(bad(EI, T, 1.0, G, 0.0, -1.0).contains("speed"));
        let r = wire(1.0, 75.0);
        assert!(
            r.solve(0, 1e-4, 1e-3, 0.1)
                .unwrap_err()
                .to_string()
                .contains("modes")
        );
        assert!(
            r.solve(4, 0.0, 1e-3, 0.1)
                .unwrap_err()
                .to_string()
                .contains("step")
        );
        assert!(
            r.solve(4, 1e-4, 1e-3, 1.0)
                .unwrap_err()
                .to_string()
                .contains("t_end")
        );
    }

    /// Sherman–Morrison evaluation vs a dense LU of the projected system.
    #[test]
    fn rank_one_solve_matches_the_dense_projected_system() {
        let r = RidingMassBeam::new(
            EI,
            T,
            RA,
            L,
            Rider {
                mass: 30.0,
                gravity: G,
                side: Side::Above,
                start: 3.0,
                speed: 75.0,
            },
        )
        .unwrap();
        let n = 12;
        let x = 17.3;
        let a: Vec<f64> = (0..n).map(|j| 1e-3 / (1.0 + j as f64).powi(2)).collect();
        let b: Vec<f64> = (0..n).map(|j| 0.1 * (j as f64).sin()).collect();
        let mut work = Work {
            omega2: (1..=n).map(|j| r.beam.omega(j).powi(2)).collect(),
            phi: vec![0.0; n],
            dphi: vec![0.0; n],
            ddphi: vec![0.0; n],
        };
        let mut acc = vec![0.0; n];
        r.rhs(x, &a, &b, &mut acc, &mut work);
        let mj = 0.5 * RA * L;
        let (m, v) = (r.mass, r.speed);
        let phi = DVector::from_fn(n, |j, _| ((j + 1) as f64 * PI * x / L).sin());
        let dphi = DVector::from_fn(n, |j, _| {
            let k = (j + 1) as f64 * PI / L;
            k * (k * x).cos()
        });
        let ddphi = DVector::from_fn(n, |j, _| {
            let k = (j + 1) as f64 * PI / L;
            -k * k * (k * x).sin()
        });
        let mm = DMatrix::from_diagonal_element(n, n, mj) + m * &phi * phi.transpose();
        let cc = 2.0 * m * v * &phi * dphi.transpose();
        let kk = DMatrix::from_fn(n, n, |i, j| if i == j { mj * work.omega2[i] } else { 0.0 })
            + m * v * v * &phi * ddphi.transpose();
        let rhs = -m * G * &phi - cc * DVector::from_vec(b) - kk * DVector::from_vec(a);
        let dense = mm.lu().solve(&rhs).unwrap();
        for j in 0..n {
            // two exact solves of a well-conditioned 12×12 system: round-off
            assert!(
                (dense[j] - acc[j]).abs() <= 1e-10 * dense.amax(),
                "mode {j}: {} vs {}",
                dense[j],
                acc[j]
            );
        }
    }

    /// A vanishing mass is the moving force −m g (MODEL §8): with the same J
    /// the series is exact in time, so the difference is the RK4 error plus
    /// the O(m/ρA L) inertia of the mass.
    #[test]
    fn a_light_mass_is_the_moving_force_of_its_weight() {
        let m = 1e-6;
        let v = 75.0;
        let modes = 60;
        let r = wire(m, v);
        let f = MovingForceBeam::new(EI, T, RA, L, -m * G, v).unwrap();
        let err_of = |h: &RidingMassHistory| {
            h.t.iter()
                .zip(&h.w)
                // w = s·v with s = −1 (above)
                .map(|(&t, &w)| (w + f.deflection_series(v * t, t, modes)).abs())
                .fold(0.0, f64::max)
        };
        let h = r.solve(modes, r.max_step(modes), 1e-3, 0.6).unwrap();
        let fine = r.solve(modes, r.max_step(modes) / 4.0, 1e-3, 0.6).unwrap();
        let scale = h.w.iter().fold(0.0f64, |s, w| s.max(w.abs()));
        let (err, err_fine) = (err_of(&h), err_of(&fine));
        // RK4 at STEP_FACTOR: measured 1.5e-6 relative (J = 60, 0.6 s)
        assert!(err <= 3e-6 * scale, "err {err:e}, scale {scale:e}");
        // a quarter step: RK4 would gain 256×; the floor is the O(m/(ρA L))
        // = 1.5e-8 inertia of the mass, so ask for 30×
        assert!(err_fine <= err / 30.0, "err {err:e} → {err_fine:e}");
        // and the force is the weight, within the same inertia
        for lam in &h.force {
            assert!((lam - m * G).abs() <= 1e-6 * m * G, "λ {lam}");
        }
    }

    /// The side only sets the sign convention of w and λ (MODEL §2): the
    /// physics (weight down, v) is the same, so both flip exactly.
    #[test]
    fn the_side_flips_w_and_the_force_only() {
        let mk = |side| {
            RidingMassBeam::new(
                EI,
                T,
                RA,
                L,
                Rider {
                    mass: 30.0,
                    gravity: G,
                    side,
                    start: 5.0,
                    speed: 75.0,
                },
            )
            .unwrap()
            .solve(40, 1e-4, 1e-3, 0.2)
            .unwrap()
        };
        let (above, below) = (mk(Side::Above), mk(Side::Below));
        for k in 0..above.t.len() {
            assert_eq!(above.w[k], -below.w[k]);
            assert_eq!(above.force[k], -below.force[k]);
        }
        // above: the weight presses (λ > 0 on average) and w = −v > 0 (down)
        let mean = above.force.iter().sum::<f64>() / above.force.len() as f64;
        assert!(mean > 0.0 && above.w[above.w.len() - 1] > 0.0);
    }

    /// `w_at` returns the samples at the sample times, interpolates between
    /// them to O(dt⁴), and is NaN outside the run.
    #[test]
    fn interpolation_hits_the_samples_and_refuses_outside() {
        let r = wire(30.0, 75.0);
        // 1.26e-4 s gives the same RK4 step (1.25e-4 s) at both samplings,
        // so the runs differ only by where they are sampled
        let h = r.solve(40, 1.26e-4, 1e-3, 0.2).unwrap();
        for k in (0..h.t.len()).step_by(7) {
            assert!((h.w_at(h.t[k]) - h.w[k]).abs() <= 4.0 * f64::EPSILON * h.w[k].abs());
        }
        assert!(h.w_at(-1e-3).is_nan() && h.w_at(0.201).is_nan());
        // against the same run sampled 4× finer: the Hermite error, O(dt⁴),
        // measured 1.6e-7 of max |w| (dt = 1 ms); 1e-6 leaves 6×
        let fine = r.solve(40, 1.26e-4, 2.5e-4, 0.2).unwrap();
        let scale = h.w.iter().fold(0.0f64, |s, w| s.max(w.abs()));
        let err = (0..fine.t.len())
            .map(|k| (h.w_at(fine.t[k]) - fine.w[k]).abs())
            .fold(0.0, f64::max);
        println!("Hermite interpolation error {err:e} of {scale:e}");
        assert!(err <= 1e-6 * scale, "{err:e}");
    }
}
