//! The convergence model an accuracy-targeted sweep (and so `run
//! --tolerance`) plans its first check and predicts its cost with, and the
//! cheapest resolution it allows.
//!
//! The discretization error of a quantity is modelled as a mesh part plus a
//! step part,
//!
//! ```text
//! e(h, Δt) ≈ F_s · (C_h h^p + C_t Δt^q)
//! ```
//!
//! (MODEL §4 Hermite elements in h, §5 generalized-α in Δt; mixed terms are
//! neglected). Each part is measured on a ladder of three pilot runs that
//! refines only its own parameter by r = 2: from the successive differences
//! d₁ = ‖u₀ − u₁‖, d₂ = ‖u₁ − u₂‖ the observed order is log_r(d₁/d₂), the
//! Richardson estimate of the finest rung's error is d₂/(r^p − 1) and
//! C = that / (finest h or Δt)^p. An observed order above the method's
//! ([`crate::quantity::formal_orders::MAX_MESH_ORDER`], …) is capped, and d₂ raised to d₁/r^p: differences
//! that fall faster than the method allows are a chance cancellation at the
//! finest rung, not a smaller error. F_s is Roache's three-grid safety factor
//! ([`FS_ASYMPTOTIC`]): the reported estimate is a GCI-style band, not a
//! bare extrapolation.

use serde::Serialize;

use crate::study::uncertainty::{FS_ASYMPTOTIC, observed_order, richardson_error};

/// Refinement ratio of each pilot ladder: 2, so every coarser time is a
/// finer time and histories compare sample by sample.
pub(crate) const LADDER_RATIO: f64 = 2.0;

use crate::quantity::formal_orders::ROUND_OFF;

/// Smallest observed order accepted as convergence. Below it a halving
/// shrinks the difference by less than 2^0.5 ≈ 1.41: too little to tell a
/// converging sequence from a noisy non-converging one, and extrapolating
/// such an order to a tolerance asks for refinements far beyond the pilots.
pub(crate) const MIN_ORDER: f64 = 0.5;

/// What a pilot ladder says about one parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LadderStatus {
    /// Differences fall at an order ≥ `MIN_ORDER`.
    Converging,
    /// Both differences are zero (round-off): the parameter does not matter.
    Exact,
    /// Differences do not fall, or fall at an order below `MIN_ORDER`.
    NotConverging,
}

/// One ladder's fit: e(x) ≈ C x^order for the refined parameter x (h or Δt).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LadderFit {
    /// ‖u₀ − u₁‖ and ‖u₁ − u₂‖ (relative, absolute or in the result's unit).
    pub differences: [f64; 2],
    /// log_r(d₁/d₂); +∞ when d₂ = 0 < d₁; NaN when undefined (JSON null).
    pub observed_order: f64,
    /// The order used: the observed one capped at the method's maximum
    /// (the maximum when d₂ = 0); when capped, d₂ is replaced by d₁/r^order.
    pub order: f64,
    /// The constant C of C·x^order (0 when exact; NaN when not converging).
    pub constant: f64,
    /// Richardson estimate of the finest rung's error, without F_s.
    pub finest_error: f64,
    /// Verdict.
    pub status: LadderStatus,
}

impl LadderFit {
    /// Fit a ladder from its two successive differences; `finest` is the
    /// refined parameter at the finest rung, `scale` the quantity's size
    /// (for the round-off test), `max_order` the method's order.
    pub fn new(differences: [f64; 2], finest: f64, scale: f64, max_order: f64) -> Self {
        let floor = ROUND_OFF * scale.abs().max(f64::MIN_POSITIVE);
        let [d1, d2] = differences.map(|d| if d.abs() <= floor { 0.0 } else { d.abs() });
        let r = LADDER_RATIO;
        let not = |observed| LadderFit {
            differences,
            observed_order: observed,
            order: f64::NAN,
            constant: f64::NAN,
            finest_error: f64::NAN,
            status: LadderStatus::NotConverging,
        };
        if !(d1.is_finite() && d2.is_finite()) {
            return not(f64::NAN);
        }
        if d1 == 0.0 && d2 == 0.0 {
            return LadderFit {
                differences,
                observed_order: f64::NAN,
                order: max_order,
                constant: 0.0,
                finest_error: 0.0,
                status: LadderStatus::Exact,
            };
        }
        if d1 == 0.0 {
            return not(f64::NEG_INFINITY);
        }
        let observed = if d2 == 0.0 {
            f64::INFINITY
        } else {
            observed_order(d1, d2, r)
        };
        if observed < MIN_ORDER {
            return not(observed);
        }
        let order = observed.min(max_order);
        // differences cannot fall faster than the method's order: a faster
        // fall (d₂ = 0 included: P_l counts whole steps) is a chance
        // cancellation at the finest rung, so d₂ is taken as d₁/r^order
        let d2 = d2.max(d1 / r.powf(order));
        let finest_error = richardson_error(d2, r, order);
        LadderFit {
            differences,
            observed_order: observed,
            order,
            constant: finest_error / finest.powf(order),
            finest_error,
            status: LadderStatus::Converging,
        }
    }

    /// The modelled error C·x^order at parameter x, without F_s (NaN when
    /// not converging).
    pub fn error_at(&self, x: f64) -> f64 {
        match self.status {
            LadderStatus::Exact => 0.0,
            LadderStatus::Converging => self.constant * x.powf(self.order),
            LadderStatus::NotConverging => f64::NAN,
        }
    }

    /// True unless the differences failed to fall.
    pub fn usable(&self) -> bool {
        self.status != LadderStatus::NotConverging
    }
}

/// The two-parameter model e(h, Δt) ≈ F_s (C_h h^p + C_t Δt^q).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorModel {
    /// The mesh ladder (h refined at Δt₀).
    pub mesh: LadderFit,
    /// The step ladder (Δt refined at N₀).
    pub step: LadderFit,
    /// F_s applied to both parts.
    pub safety_factor: f64,
}

/// An estimate split into its parts (F_s included in each).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// Mesh part + step part.
    pub total: f64,
    /// F_s C_h h^p.
    pub mesh: f64,
    /// F_s C_t Δt^q.
    pub step: f64,
}

impl ErrorModel {
    /// Model from two fitted ladders, with Roache's F_s.
    pub fn new(mesh: LadderFit, step: LadderFit) -> Self {
        ErrorModel {
            mesh,
            step,
            safety_factor: FS_ASYMPTOTIC,
        }
    }

    /// Estimated error at element length `h` and step `dt`.
    pub fn estimate(&self, h: f64, dt: f64) -> Estimate {
        let mesh = self.safety_factor * self.mesh.error_at(h);
        let step = self.safety_factor * self.step.error_at(dt);
        Estimate {
            total: mesh + step,
            mesh,
            step,
        }
    }

    /// The (h, Δt) of least cost ∝ 1/(h·Δt) with estimate ≤ `tol`, never
    /// coarser than (`h0`, `dt0`) (the model is measured only at and below
    /// them). Continuous values: the caller rounds them to a whole mesh and
    /// a whole number of steps. `None` when a ladder does not converge.
    ///
    /// Lagrange optimum of min 1/(hΔt) on a h^p + b Δt^q = tol: the
    /// multiplier condition p·a h^p = q·b Δt^q splits the tolerance as
    /// e_h = tol·q/(p + q), e_t = tol·p/(p + q). When that would ask for
    /// h > h₀ (or Δt > Δt₀), the bound is active instead: the parameter stays
    /// at the pilot value and the other takes the rest of the tolerance.
    pub fn cheapest(&self, tol: f64, h0: f64, dt0: f64) -> Option<(f64, f64)> {
        if !(self.mesh.usable() && self.step.usable()) {
            return None;
        }
        let fs = self.safety_factor;
        let (a, p) = (fs * self.mesh.constant, self.mesh.order);
        let (b, q) = (fs * self.step.constant, self.step.order);
        // the parameter that gives error e, capped at its pilot value
        let h_for = |e: f64| {
            if a == 0.0 {
                h0
            } else {
                (e / a).powf(1.0 / p).min(h0)
            }
        };
        let dt_for = |e: f64| {
            if b == 0.0 {
                dt0
            } else {
                (e / b).powf(1.0 / q).min(dt0)
            }
        };
        let (eh, et) = match (a == 0.0, b == 0.0) {
            (true, true) => return Some((h0, dt0)),
            (true, false) => (0.0, tol),
            (false, true) => (tol, 0.0),
            (false, false) => (tol * q / (p + q), tol * p / (p + q)),
        };
        let (mut h, mut dt) = (h_for(eh), dt_for(et));
        if a != 0.0 && h >= h0 {
            // mesh bound active: Δt takes what h₀ leaves
            h = h0;
            dt = dt_for(tol - a * h0.powf(p));
        } else if b != 0.0 && dt >= dt0 {
            dt = dt0;
            h = h_for(tol - b * dt0.powf(q));
        }
        (h > 0.0 && dt > 0.0 && h.is_finite() && dt.is_finite()).then_some((h, dt))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quantity::formal_orders::{MAX_MESH_ORDER, MAX_STEP_ORDER};

    const H0: f64 = 0.125;
    const DT0: f64 = 1e-4;

    /// Exact data e = C x^p sampled on a ladder x, x/2, x/4 ending at `fine`.
    fn ladder(c: f64, p: f64, fine: f64, max: f64) -> LadderFit {
        let e = |x: f64| c * x.powf(p);
        let (x0, x1, x2) = (4.0 * fine, 2.0 * fine, fine);
        // u_ℓ = u* + e(x_ℓ): differences are e(x_ℓ) − e(x_{ℓ+1})
        LadderFit::new([e(x0) - e(x1), e(x1) - e(x2)], x2, 1.0, max)
    }

    #[test]
    fn an_exact_power_law_is_recovered() {
        let f = ladder(3.0, 2.0, 0.03125, MAX_MESH_ORDER);
        assert_eq!(f.status, LadderStatus::Converging);
        assert!((f.observed_order - 2.0).abs() < 1e-12);
        assert!((f.constant - 3.0).abs() < 1e-9);
        assert!((f.error_at(0.1) - 0.03).abs() < 1e-12);
    }

    #[test]
    fn orders_above_the_method_are_capped() {
        // e = C Δt³ with errors of order 1e-2 (well above round-off)
        let c = 1e12;
        let f = ladder(c, 3.0, 2.5e-5, MAX_STEP_ORDER);
        assert!((f.observed_order - 3.0).abs() < 1e-9);
        assert_eq!(f.order, 2.0);
        // capping makes the finest rung's estimate larger (safer)
        let exact = c * (2.5e-5f64).powi(3);
        assert!(f.finest_error > exact);
    }

    #[test]
    fn growing_or_stalling_differences_do_not_converge() {
        let grow = LadderFit::new([1.0, 1.5], 0.1, 1.0, 2.0);
        assert_eq!(grow.status, LadderStatus::NotConverging);
        assert!(grow.observed_order < 0.0);
        let stall = LadderFit::new([1.0, 0.9], 0.1, 1.0, 2.0);
        assert_eq!(stall.status, LadderStatus::NotConverging);
        let from_zero = LadderFit::new([0.0, 0.1], 0.1, 1.0, 2.0);
        assert_eq!(from_zero.status, LadderStatus::NotConverging);
        let none = LadderFit::new([0.0, 1e-15], 0.1, 1.0, 2.0);
        assert_eq!(none.status, LadderStatus::Exact);
    }

    #[test]
    fn the_optimum_splits_the_tolerance_by_the_orders() {
        let m = ErrorModel::new(
            ladder(2.0, 2.0, H0 / 4.0, MAX_MESH_ORDER),
            ladder(4e6, 2.0, DT0 / 4.0, MAX_STEP_ORDER),
        );
        let tol = 1e-4;
        let (h, dt) = m.cheapest(tol, H0, DT0).unwrap();
        let e = m.estimate(h, dt);
        assert!((e.total - tol).abs() < 1e-12 * tol.max(1.0));
        // p = q: equal parts
        assert!((e.mesh - e.step).abs() < 1e-9 * tol);
        // and no other split on the constraint is cheaper
        for share in [0.3, 0.4, 0.6, 0.7] {
            let hh = (share * tol / (m.safety_factor * 2.0)).sqrt();
            let tt = ((1.0 - share) * tol / (m.safety_factor * 4e6)).sqrt();
            assert!(1.0 / (hh * tt) > 1.0 / (h * dt));
        }
    }

    #[test]
    fn a_negligible_part_stays_at_the_pilot_value() {
        // mesh error tiny at h0: h stays h0, Δt takes nearly all the tolerance
        let m = ErrorModel::new(
            ladder(1e-9, 2.0, H0 / 4.0, MAX_MESH_ORDER),
            ladder(4e6, 2.0, DT0 / 4.0, MAX_STEP_ORDER),
        );
        let tol = 1e-3;
        let (h, dt) = m.cheapest(tol, H0, DT0).unwrap();
        assert_eq!(h, H0);
        assert!((m.estimate(h, dt).total - tol).abs() < 1e-9 * tol);
    }

    #[test]
    fn tighter_tolerances_never_coarsen() {
        let m = ErrorModel::new(
            ladder(2.0, 1.5, H0 / 4.0, MAX_MESH_ORDER),
            ladder(4e6, 2.0, DT0 / 4.0, MAX_STEP_ORDER),
        );
        let mut last = (f64::INFINITY, f64::INFINITY);
        for tol in [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4] {
            let (h, dt) = m.cheapest(tol, H0, DT0).unwrap();
            assert!(
                h <= last.0 && dt <= last.1,
                "tol {tol}: {h}, {dt} after {last:?}"
            );
            last = (h, dt);
        }
    }
}
