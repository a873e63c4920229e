//! The exact step of a damped mode (docs/lines.md §10.4; MODEL §9.3):
//! what `modal_exact` advances each mode with when the wire has Rayleigh
//! damping, `η̈ + c η̇ + ω² η = f(t)`, c = α + βω² = 2ζω (C is diagonal in
//! a mass-normalized basis, L12).
//!
//! With the load linear in time over the step (first-order hold, as the
//! undamped step in `oscillator.rs`), the step map is the exponential of
//! the augmented system of `(η, η̇, f, ḟ)`:
//!
//! ```text
//!   d/dt [η, η̇, f, ḟ] = [[0, 1, 0, 0], [−ω², −c, 1, 0], [0, 0, 0, 1], [0, 0, 0, 0]] [η, η̇, f, ḟ]
//!   η_{n+1} = E₀₀ η_n + E₀₁ η̇_n + a0 f_n + a1 f_{n+1},  a1 = E₀₃/Δt,  a0 = E₀₂ − a1
//!   η̇_{n+1} = E₁₀ η_n + E₁₁ η̇_n + b0 f_n + b1 f_{n+1},  b1 = E₁₃/Δt,  b0 = E₁₂ − b1
//! ```
//!
//! (ḟ = (f_{n+1} − f_n)/Δt), one formula for under-, critically and
//! over-damped modes alike: no case split at ζ = 1. The exponential is
//! nalgebra's Padé scaling and squaring, on the balanced variables
//! `(η, η̇/s, f/s², ḟ/s³)`, s = ω (1/Δt for a rigid mode), whose matrix
//! entries are all O(ωΔt) or cΔt rather than up to (ωΔt)²: its error is a
//! few ulps of the entries' scale (checked against the closed form L13 of
//! `analytic::rayleigh` in `tests/damping.rs`).
//!
//! A damped mode's velocity row has its own diagonal E₁₁ ≠ E₀₀ ([`ModeSteps::cos_v`]).

use nalgebra::Matrix4;

use super::oscillator::ModeSteps;

impl ModeSteps {
    /// The step maps of modes with angular frequencies `omega` (rad/s,
    /// ≥ 0) and modal damping coefficients `c` = 2ζ_jω_j (1/s, ≥ 0) at `dt`
    /// (module docs).
    pub fn damped(omega: &[f64], c: &[f64], dt: f64) -> Self {
        let n = omega.len();
        let mut m = ModeSteps::new(&[], dt);
        for v in [
            &mut m.cos,
            &mut m.sin_over_omega,
            &mut m.minus_omega_sin,
            &mut m.cos_v,
            &mut m.a0,
            &mut m.a1,
            &mut m.b0,
            &mut m.b1,
        ] {
            v.reserve(n);
        }
        for (&w, &c) in omega.iter().zip(c) {
            let s = if w > 0.0 { w } else { 1.0 / dt };
            #[rustfmt::skip]
            let a = Matrix4::new(
                0.0, s, 0.0, 0.0,
                -w * w / s, -c, s, 0.0,
                0.0, 0.0, 0.0, s,
                0.0, 0.0, 0.0, 0.0,
            ) * dt;
            let e = a.exp();
            let (s2, s3) = (s * s, s * s * s);
            let a1 = e[(0, 3)] / (s3 * dt);
            let b1 = s * e[(1, 3)] / (s3 * dt);
            m.cos.push(e[(0, 0)]);
            m.sin_over_omega.push(e[(0, 1)] / s);
            m.minus_omega_sin.push(s * e[(1, 0)]);
            m.cos_v.push(e[(1, 1)]);
            let a0 = e[(0, 2)] / s2 - a1;
            // a deliberate defect of the test build (`crate::defects`)
            let (a0, a1) = if crate::defects::on(crate::defects::Defect::HoldSwapped) {
                (a1, a0)
            } else {
                (a0, a1)
            };
            m.a0.push(a0);
            m.a1.push(a1);
            m.b0.push(s * e[(1, 2)] / s2 - b1);
            m.b1.push(b1);
        }
        m
    }
}
