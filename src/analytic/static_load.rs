//! Static deflection of a tensioned beam under a point load: the continuum
//! solution of `EI v'''' − T v'' = P δ(x − a)` (MODEL eq. 1 at rest), used as
//! an independent reference for static contact forces (TARGETS T2).
//!
//! On each side of the load the solution is a combination of
//! {1, x, e^{−μ(x − x_l)}, e^{−μ(x_r − x)}} with μ = sqrt(T/EI) (decaying
//! exponentials rather than cosh/sinh, so μL ≫ 1 does not overflow), or
//! {1, x, x², x³} when T = 0. Supports give two conditions per end; at the
//! load v, v', v'' are continuous and EI[v'''] = P. The 8×8 system is solved
//! by LU with partial pivoting (nalgebra). A string (EI = 0) has the closed
//! form v(a) = P a (L − a)/(T L).

use nalgebra::{SMatrix, SVector};

use crate::error::{Error, Result};
use crate::scene::Support;

/// A tensioned beam at rest with a unit point load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticPointLoad {
    /// EI, N·m² (≥ 0).
    pub ei: f64,
    /// T, N (≥ 0).
    pub tension: f64,
    /// L, m (> 0).
    pub length: f64,
    /// Support at x = 0.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
}

/// Values of a basis function and its first three derivatives.
type Jet = [f64; 4];

impl StaticPointLoad {
    /// Check the inputs: positive length, non-negative EI and T, and supports
    /// that hold the beam (no rigid-body motion).
    pub fn new(ei: f64, tension: f64, length: f64, left: Support, right: Support) -> Result<Self> {
        if !(length > 0.0 && length.is_finite()) {
            return Err(Error::invalid("length", length, "must be > 0 (m)"));
        }
        if !(ei >= 0.0 && ei.is_finite() && tension >= 0.0 && tension.is_finite()) {
            return Err(Error::invalid(
                "ei, tension",
                format!("{ei}, {tension}"),
                "must be ≥ 0",
            ));
        }
        let held = !matches!(
            (left, right),
            (Support::Free, Support::Free)
                | (Support::Free, Support::Pinned)
                | (Support::Pinned, Support::Free)
        );
        if !held || (ei == 0.0 && (left != Support::Pinned || right != Support::Pinned)) {
            return Err(Error::invalid(
                "supports",
                format!("{left:?}-{right:?}"),
                "must hold the beam statically (a string needs pinned-pinned)",
            ));
        }
        if ei == 0.0 && tension == 0.0 {
            return Err(Error::invalid("tension", 0.0, "a string needs T > 0"));
        }
        Ok(StaticPointLoad {
            ei,
            tension,
            length,
            left,
            right,
        })
    }

    /// Compliance at the load point: v(a)/P for a load at x = a, m/N.
    pub fn compliance(&self, a: f64) -> f64 {
        self.deflection(a, a)
    }

    /// Deflection v(x) under a unit load at x = a, m/N.
    pub fn deflection(&self, a: f64, x: f64) -> f64 {
        let l = self.length;
        if self.ei == 0.0 {
            let (lo, hi) = if x <= a { (x, a) } else { (a, x) };
            return lo * (l - hi) / (self.tension * l);
        }
        let mu = (self.tension / self.ei).sqrt();
        // basis on the segment [xl, xr], evaluated at x
        let basis = |xl: f64, xr: f64, x: f64| -> [Jet; 4] {
            if mu == 0.0 {
                let s = x - xl;
                [
                    [1.0, 0.0, 0.0, 0.0],
                    [s, 1.0, 0.0, 0.0],
                    [s * s, 2.0 * s, 2.0, 0.0],
                    [s * s * s, 3.0 * s * s, 6.0 * s, 6.0],
                ]
            } else {
                let e1 = (-mu * (x - xl)).exp();
                let e2 = (-mu * (xr - x)).exp();
                [
                    [1.0, 0.0, 0.0, 0.0],
                    [x - xl, 1.0, 0.0, 0.0],
                    [e1, -mu * e1, mu * mu * e1, -mu * mu * mu * e1],
                    [e2, mu * e2, mu * mu * e2, mu * mu * mu * e2],
                ]
            }
        };
        let mut m = SMatrix::<f64, 8, 8>::zeros();
        let mut rhs = SVector::<f64, 8>::zeros();
        // boundary rows: derivative orders used by each support
        let bc = |s: Support| -> [(usize, f64); 2] {
            match s {
                Support::Clamped => [(0, 0.0), (1, 0.0)],
                Support::Pinned => [(0, 0.0), (2, 0.0)],
                // moment and shear (EI v''' − T v') vanish; encoded as order 4
                Support::Free => [(2, 0.0), (4, 0.0)],
            }
        };
        let row_of = |jet: &Jet, order: usize| -> f64 {
            if order == 4 {
                self.ei * jet[3] - self.tension * jet[1]
            } else {
                jet[order]
            }
        };
        let left_at = |x: f64| basis(0.0, a, x);
        let right_at = |x: f64| basis(a, l, x);
        let mut r = 0;
        for (order, _) in bc(self.left) {
            let b = left_at(0.0);
            for j in 0..4 {
                m[(r, j)] = row_of(&b[j], order);
            }
            r += 1;
        }
        for (order, _) in bc(self.right) {
            let b = right_at(l);
            for j in 0..4 {
                m[(r, 4 + j)] = row_of(&b[j], order);
            }
            r += 1;
        }
        let (bl, br) = (left_at(a), right_at(a));
        for order in 0..3 {
            for j in 0..4 {
                m[(r, j)] = bl[j][order];
                m[(r, 4 + j)] = -br[j][order];
            }
            r += 1;
        }
        // EI (v'''(a+) − v'''(a−)) = P = 1
        for j in 0..4 {
            m[(r, j)] = -self.ei * bl[j][3];
            m[(r, 4 + j)] = self.ei * br[j][3];
        }
        rhs[r] = 1.0;
        let c = m
            .lu()
            .solve(&rhs)
            .expect("supports checked in new(): the system is regular");
        let (b, off) = if x <= a {
            (left_at(x), 0)
        } else {
            (right_at(x), 4)
        };
        (0..4).map(|j| c[off + j] * b[j][0]).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Agreement with textbook closed forms: round-off of an 8×8 LU.
    const CLOSED_FORM: f64 = 1e-9;

    #[test]
    fn cantilever_tip_load_without_tension() {
        let b = StaticPointLoad::new(2.0, 0.0, 3.0, Support::Clamped, Support::Free).unwrap();
        assert_relative_eq!(b.compliance(3.0), 27.0 / 6.0, max_relative = CLOSED_FORM);
    }

    #[test]
    fn simply_supported_midspan_without_tension() {
        let b = StaticPointLoad::new(5.0, 0.0, 2.0, Support::Pinned, Support::Pinned).unwrap();
        assert_relative_eq!(
            b.compliance(1.0),
            8.0 / (48.0 * 5.0),
            max_relative = CLOSED_FORM
        );
    }

    #[test]
    fn tensioned_pinned_beam_matches_its_closed_form() {
        // midspan of a pinned–pinned tensioned beam:
        // v = P/(2T) [L/2 − tanh(μL/2)/μ]
        let (ei, t, l) = (3.0, 400.0, 2.0);
        let b = StaticPointLoad::new(ei, t, l, Support::Pinned, Support::Pinned).unwrap();
        let mu = (t / ei).sqrt();
        let exact = (l / 2.0 - (mu * l / 2.0).tanh() / mu) / (2.0 * t);
        assert_relative_eq!(b.compliance(1.0), exact, max_relative = CLOSED_FORM);
    }

    #[test]
    fn stiff_tension_tends_to_the_string() {
        // bending length sqrt(EI/T) = 1e-3·L: within a few ‰ of the string
        let (l, a, t) = (50.0, 20.0, 3e4);
        let ei = t * (1e-3 * l) * (1e-3 * l);
        let beam = StaticPointLoad::new(ei, t, l, Support::Pinned, Support::Pinned).unwrap();
        let string = StaticPointLoad::new(0.0, t, l, Support::Pinned, Support::Pinned).unwrap();
        let rel = (beam.compliance(a) - string.compliance(a)).abs() / string.compliance(a);
        assert!(rel < 5e-3, "{rel}");
    }

    #[test]
    fn deflection_is_symmetric_maxwell_betti() {
        let b = StaticPointLoad::new(129.2, 3e4, 50.0, Support::Clamped, Support::Pinned).unwrap();
        assert_relative_eq!(
            b.deflection(1.0, 7.0),
            b.deflection(7.0, 1.0),
            max_relative = 1e-9
        );
    }
}
