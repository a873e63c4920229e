//! Roache's grid convergence index (GCI; Roache, *Verification and
//! Validation in Computational Science and Engineering*, 1998, §5.6;
//! MODEL §12): the numerical uncertainty of the finest of a ladder of
//! solutions refined by a constant ratio r.
//!
//! With three solutions φ₃ (coarse), φ₂, φ₁ (fine):
//!
//! ```text
//! R   = (φ₁ − φ₂)/(φ₂ − φ₃)                     0 < R < 1: monotone
//! p   = ln((φ₃ − φ₂)/(φ₂ − φ₁))/ln r            the observed order
//! ε₁  = (φ₂ − φ₁)/(r^p − 1)                     Richardson (sign: φ₁ − φ_exact)
//! GCI = F_s |ε₁|
//! ```
//!
//! with p = min(p_obs, p_formal) in ε₁ when the observed order exceeds the
//! formal one, F_s = 1.25 when p_obs is within ±0.5 of the formal order
//! (the asymptotic range) and 3 otherwise, and F_s = 3 with p = p_formal
//! for two solutions.
//!
//! Roache's consistency check GCI₂₃ ≈ r^p GCI₁₂ fails when the finest
//! difference falls faster than the formal order allows (p_obs above the
//! window): a chance cancellation at the finest level, not a smaller
//! error. taut then carries the coarser difference down at the formal
//! order, |φ₂ − φ₁| → max(|φ₂ − φ₁|, |φ₃ − φ₂|/r^p_formal), the rule `run
//! --tolerance` applies to its ladders (measured: without it the GCI of
//! the moving-force family from N₀ = 25 covered 0.93 of the true error,
//! docs/verification.md). Data that are not monotone (R ≤ 0 or R ≥ 1) get no
//! GCI: the least-squares estimator ([`super::least_squares`]) is the
//! field's answer for them.

use serde::Serialize;

use super::order::{observed_order, richardson_error};

/// Roache's safety factor for three or more solutions whose observed order
/// is near the formal one.
pub const FS_ASYMPTOTIC: f64 = 1.25;

/// Roache's safety factor for two solutions, or an observed order far
/// from the formal one (also Eça & Hoekstra's for a fit out of range).
pub const FS_CAUTIOUS: f64 = 3.0;

/// How far the observed order may be from the formal one and still count
/// as the asymptotic range (MODEL §12: "within about ±0.5").
pub(crate) const ORDER_WINDOW: f64 = 0.5;

/// The GCI of the finest of two or three solutions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Gci {
    /// Solutions used: 2 or 3.
    pub levels: usize,
    /// Refinement ratio r between them.
    pub ratio: f64,
    /// Roache's convergence ratio R (NaN for two solutions).
    pub convergence_ratio: f64,
    /// The observed order (NaN for two solutions).
    pub observed_order: f64,
    /// The order used in ε: min(observed, formal), or the formal order for
    /// two solutions.
    pub order: f64,
    /// ε = φ_fine − φ_exact estimated (Richardson), in the quantity's unit.
    pub error: f64,
    /// F_s.
    pub safety_factor: f64,
    /// GCI = F_s |ε|, in the quantity's unit.
    pub u: f64,
}

impl Gci {
    /// The GCI from the two successive differences of three solutions,
    /// `d_coarse` = φ₃ − φ₂ and `d_fine` = φ₂ − φ₁ (signed values, or both
    /// norms of history differences), refined by `r`; `formal` the formal
    /// order when known. `None` unless R = d_fine/d_coarse is in (0, 1).
    pub fn from_differences(
        d_coarse: f64,
        d_fine: f64,
        r: f64,
        formal: Option<f64>,
    ) -> Option<Gci> {
        let big_r = d_fine / d_coarse;
        if !(big_r > 0.0 && big_r < 1.0) {
            return None;
        }
        let p_obs = observed_order(d_coarse.abs(), d_fine.abs(), r);
        let p = formal.map_or(p_obs, |f| p_obs.min(f));
        let near = formal.is_some_and(|f| (p_obs - f).abs() <= ORDER_WINDOW);
        let fs = if near { FS_ASYMPTOTIC } else { FS_CAUTIOUS };
        // a finest difference falling faster than the formal order allows
        // is carried down from the coarser one (module docs)
        let d_fine = match formal {
            Some(f) if p_obs > f + ORDER_WINDOW => {
                d_fine.signum() * d_fine.abs().max(d_coarse.abs() / r.powf(f))
            }
            _ => d_fine,
        };
        let error = richardson_error(d_fine, r, p);
        Some(Gci {
            levels: 3,
            ratio: r,
            convergence_ratio: big_r,
            observed_order: p_obs,
            order: p,
            error,
            safety_factor: fs,
            u: fs * error.abs(),
        })
    }

    /// The GCI of three solutions `coarse`, `mid`, `fine` ([`Gci::from_differences`]).
    pub fn three(coarse: f64, mid: f64, fine: f64, r: f64, formal: Option<f64>) -> Option<Gci> {
        Gci::from_differences(coarse - mid, mid - fine, r, formal)
    }

    /// The GCI of two solutions: the formal order assumed, F_s = 3.
    pub fn two(coarse: f64, fine: f64, r: f64, formal: f64) -> Gci {
        let error = richardson_error(coarse - fine, r, formal);
        Gci {
            levels: 2,
            ratio: r,
            convergence_ratio: f64::NAN,
            observed_order: f64::NAN,
            order: formal,
            error,
            safety_factor: FS_CAUTIOUS,
            u: FS_CAUTIOUS * error.abs(),
        }
    }

    /// True when F_s is the asymptotic 1.25.
    pub fn asymptotic(&self) -> bool {
        self.safety_factor == FS_ASYMPTOTIC
    }

    /// The GCI relative to the finest value (NaN when that is 0).
    pub fn relative(&self, value: f64) -> f64 {
        if value == 0.0 {
            f64::NAN
        } else {
            self.u / value.abs()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// φ = 1 + 0.02 h^p at h = 4, 2, 1.
    fn ladder(p: f64) -> (f64, f64, f64) {
        let f = |h: f64| 1.0 + 2e-2 * h.powf(p);
        (f(4.0), f(2.0), f(1.0))
    }

    #[test]
    fn an_asymptotic_ladder_gets_the_small_factor() {
        let (c, m, f) = ladder(2.0);
        let g = Gci::three(c, m, f, 2.0, Some(2.0)).unwrap();
        assert!((g.observed_order - 2.0).abs() < 1e-12);
        assert!((g.error - 2e-2).abs() < 1e-14, "{g:?}");
        assert_eq!(g.safety_factor, FS_ASYMPTOTIC);
        assert!((g.u - 1.25 * 2e-2).abs() < 1e-14);
        assert!(g.asymptotic());
    }

    #[test]
    fn an_order_far_from_formal_gets_the_cautious_factor_and_the_formal_cap() {
        // observed 3 against formal 2: p = 2 in ε, F_s = 3
        let (c, m, f) = ladder(3.0);
        let g = Gci::three(c, m, f, 2.0, Some(2.0)).unwrap();
        assert!((g.observed_order - 3.0).abs() < 1e-12);
        assert_eq!(g.order, 2.0);
        assert_eq!(g.safety_factor, FS_CAUTIOUS);
        // ε with p = 2, from the coarser difference carried down at order
        // 2, is larger than the true error 2e-2
        assert!(g.error > 2e-2);
        let carried = (c - m) / 4.0 / 3.0;
        assert!((g.error - carried).abs() < 1e-14, "{g:?}");
        // unknown formal order: cautious too
        assert_eq!(
            Gci::three(c, m, f, 2.0, None).unwrap().safety_factor,
            FS_CAUTIOUS
        );
    }

    #[test]
    fn non_monotone_data_get_no_gci_and_two_levels_the_cautious_factor() {
        assert!(Gci::three(1.0, 2.0, 1.5, 2.0, Some(2.0)).is_none());
        assert!(Gci::three(1.0, 1.1, 1.3, 2.0, Some(2.0)).is_none());
        assert!(Gci::three(1.0, 1.0, 1.0, 2.0, Some(2.0)).is_none());
        let g = Gci::two(1.04, 1.01, 2.0, 2.0);
        assert!((g.error - 0.01).abs() < 1e-12);
        assert_eq!(g.safety_factor, FS_CAUTIOUS);
        assert!((g.relative(g.u / 2.0) - 2.0).abs() < 1e-12);
    }
}
