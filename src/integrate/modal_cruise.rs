//! The mode shapes at a carrier moving at constant speed, advanced by a
//! fixed rotation a step (`modal_exact`'s cruise; MODEL §9.3).
//!
//! Outside the clamped ends' boundary layers every mode shape of a
//! `galerkin` basis is the real part of a phasor,
//! `φ_j(x) = Re F_j(x)`, `F_j = (C_j − iD_j) e^{iβ_j s}`
//! ([`crate::analytic::FastShapes`]). A carrier at constant speed V moves
//! by the same `Δx = V Δt` every step, so
//!
//! ```text
//! F_j(x_{n+1}) = F_j(x_n) · e^{iβ_j Δs},
//! ```
//!
//! one complex product per mode (4 multiplies or FMAs per four modes
//! against the table path's 18: its slow-phase polynomial, the table
//! product and the recurrence) with rotations `e^{iβ_j Δs}` computed once
//! for the speed. Where the step is not uniform (a ramp, a table's sloped
//! segment), within a boundary layer, or every [`RESYNC_STEPS`] steps, the
//! shapes come from the tables as before and the phasors restart from
//! them ([`crate::analytic::FastShapes::phasor_im_into`]).
//!
//! **Accuracy.** Each product rounds the phasor by about two ulps, and
//! the rotation's own rounding (about one ulp in phase and modulus) adds
//! the same at every step, so after m steps the shapes carry about
//! `4 m` ulps of the amplitude: at most [`RESYNC_STEPS`] · 4 · 1.1·10⁻¹⁶
//! ≈ 4.5·10⁻¹³ before a restart (measured: 5.4·10⁻¹³ against the tables
//! over a whole cruise, `tests`), 20 times inside the fast shapes'
//! agreement with the direct evaluation,
//! [`crate::analytic::FAST_SHAPES_AGREEMENT`].

use std::ops::Range;

use crate::analytic::FastShapes;
use crate::analytic::fast_shapes::rotate;
use crate::numeric::lanes::AlignedLanes;

/// Steps a carrier's phasors are advanced by rotation before they restart
/// from the tables: bounds the rotation's accumulated round-off to about
/// `4 · 1024` ulps ≈ 4.5·10⁻¹³ of the amplitude (module docs), while a
/// restart (the J phasors from the tables, scalar: 1.1 µs at J = 800,
/// `cargo run --release --example modal_profile`) costs about 0.05 % of
/// the 1024 steps it serves.
pub const RESYNC_STEPS: usize = 1024;

/// One carrier's phasors and rotations (J each), for the run's single
/// contact.
#[derive(Debug, Clone)]
pub struct Cruise {
    /// `Im F_j` at the position of [`Cruise::at_step`] (the real parts are
    /// the carrier's `φ(x_n)` itself).
    im: AlignedLanes,
    /// `e^{iβ_j V Δt}`, real and imaginary parts (cache-line aligned, as
    /// `im`, for the AVX-512 pass's loads).
    rot_re: AlignedLanes,
    rot_im: AlignedLanes,
    /// The speed the rotations are for, m/s (NaN before any).
    speed: f64,
    /// The step whose carrier position the phasors hold (`None`: not
    /// valid).
    at_step: Option<usize>,
    /// Rotations since the phasors last restarted from the tables.
    since: usize,
}

impl Cruise {
    /// Room for J modes, nothing valid yet.
    pub fn new(j: usize) -> Self {
        Cruise {
            im: AlignedLanes::zeros(j),
            rot_re: AlignedLanes::zeros(j),
            rot_im: AlignedLanes::zeros(j),
            speed: f64::NAN,
            at_step: None,
            since: 0,
        }
    }

    /// True when step `step` (t_n → t_{n+1}) may rotate: the phasors hold
    /// x_n, have not run [`RESYNC_STEPS`] steps, and are for `speed`.
    pub fn can_rotate(&self, step: usize, speed: f64) -> bool {
        self.at_step == Some(step) && self.since < RESYNC_STEPS && self.speed == speed
    }

    /// Restart at `x` (m), the carrier's position after step `step`, whose
    /// shapes `φ(x)` the step took from the tables: the imaginary parts
    /// from the same tables, and the rotations for `speed` (m/s) over `dt`
    /// (s) when the speed changed.
    pub fn restart(&mut self, shapes: &FastShapes, x: f64, step: usize, speed: f64, dt: f64) {
        if self.speed != speed {
            shapes.rotations_into(speed * dt, &mut self.rot_re, &mut self.rot_im);
            self.speed = speed;
        }
        shapes.phasor_im_into(x, &mut self.im);
        self.at_step = Some(step + 1);
        self.since = 0;
    }

    /// Modes `lo .. hi` of step `step`'s shapes by rotation:
    /// `φ(x_{n+1}) = Re[F(x_n) e^{iβΔs}]` into `pn1` from `pn = φ(x_n)`,
    /// the imaginary parts advanced in place (scalar, fused: the
    /// operations of the vector kernel in `modal_exact.rs`, the same bits).
    /// Inlined into the step, which is compiled for FMA where the CPU has
    /// it, so that `f64::mul_add` is the instruction.
    #[inline(always)]
    pub fn rotate_range(&mut self, pn: &[f64], pn1: &mut [f64], modes: Range<usize>) {
        for i in modes {
            (pn1[i], self.im[i]) = rotate((pn[i], self.im[i]), (self.rot_re[i], self.rot_im[i]));
        }
    }

    /// The phasors' imaginary parts and the rotations, for a kernel that
    /// rotates them itself (`modal_exact.rs`).
    pub fn parts(&mut self) -> (&mut [f64], &[f64], &[f64]) {
        (&mut self.im, &self.rot_re, &self.rot_im)
    }

    /// Record that step `step` rotated the phasors: they now hold x_{n+1}.
    pub fn rotated(&mut self, step: usize) {
        self.at_step = Some(step + 1);
        self.since += 1;
    }

    /// Steps rotated since the phasors last restarted (0 right after a
    /// restart).
    #[cfg(test)]
    pub fn rotations(&self) -> usize {
        self.since
    }

    /// Forget the phasors (the step took another path).
    pub fn invalidate(&mut self) {
        self.at_step = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::fast_shapes::tests::{REFERENCE, shapes};
    use crate::scene::Support;

    /// The shapes a cruise rotates agree with the tables' at every step up
    /// to a restart: measured worst 5.4·10⁻¹³ of the amplitude over the
    /// cases below (J = 800, 1024 steps: about 4.8 ulps a step, as the
    /// module docs estimate); 10⁻¹² leaves a factor of about 2, and is
    /// still 10 times inside the fast shapes' own agreement with the
    /// direct evaluation.
    const CRUISE_AGREEMENT: f64 = 1e-12;

    /// Rotate the phasors [`RESYNC_STEPS`] steps from x0 at speed V and
    /// compare each step's shapes with [`FastShapes::values_into`] there.
    #[test]
    fn rotated_shapes_follow_the_tables_up_to_a_restart() {
        let dt = 6.25e-5;
        let ends = [
            (Support::Pinned, Support::Pinned),
            (Support::Clamped, Support::Pinned),
            (Support::Pinned, Support::Clamped),
            (Support::Clamped, Support::Clamped),
        ];
        let mut worst = 0.0f64;
        for e in ends {
            for (length, x0, speed) in [(50.0, 10.0, 230.0), (50.0, 30.0, 50.0), (20.0, 5.0, 100.0)]
            {
                let (ei, tension, rho_a, _) = REFERENCE;
                let modes = shapes((ei, tension, rho_a, length), e, 800);
                let shapes = FastShapes::new(&modes);
                let j = shapes.count();
                let amp = (2.0 / (8900.0 * 1.5e-4 * length)).sqrt();
                let mut cruise = Cruise::new(j);
                let (mut pn, mut pn1, mut exact) = (vec![0.0; j], vec![0.0; j], vec![0.0; j]);
                shapes.values_into(x0, &mut pn);
                cruise.restart(&shapes, x0, 0, speed, dt);
                for n in 1..=RESYNC_STEPS {
                    assert!(cruise.can_rotate(n, speed));
                    cruise.rotate_range(&pn, &mut pn1, 0..j);
                    cruise.rotated(n);
                    let x = x0 + speed * dt * n as f64;
                    assert!(!shapes.in_layer(x), "{e:?}: x = {x} within a layer");
                    shapes.values_into(x, &mut exact);
                    for (a, b) in pn1.iter().zip(&exact) {
                        worst = worst.max((a - b).abs() / amp);
                    }
                    std::mem::swap(&mut pn, &mut pn1);
                }
                assert!(!cruise.can_rotate(RESYNC_STEPS + 1, speed), "restarts");
            }
        }
        println!("worst |rotated − tables| / amplitude: {worst:.2e}");
        assert!(worst <= CRUISE_AGREEMENT, "{worst:e}");
    }
}
