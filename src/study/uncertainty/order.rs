//! Orders of convergence observed on a ladder, and how a ladder behaves
//! (MODEL §12): the one observed order from two successive differences,
//! the one least-squares order over a whole ladder, Roache's convergence
//! ratio R and the ladder's behaviour (monotone, oscillatory, diverging).
//! Every study reads them from here: `converge`, `verify`, `run
//! --tolerance`, `uncertainty` and the accuracy-targeted sweep.

use serde::Serialize;

/// Observed order p = ln(e_c/e_f)/ln r from two successive differences
/// (coarse, fine) of a ladder refined by r; NaN unless both are > 0 (a
/// zero, negative or NaN difference has no order).
pub fn observed_order(e_coarse: f64, e_fine: f64, r: f64) -> f64 {
    if e_coarse > 0.0 && e_fine > 0.0 {
        (e_coarse / e_fine).ln() / r.ln()
    } else {
        f64::NAN
    }
}

/// The observed order over a whole ladder refined by `r` at each level:
/// the least-squares slope of ln(error) against the level, over ln r (the
/// two-level [`observed_order`] for two errors). For a ladder whose single
/// halvings scatter (impacts that fall at different places within the
/// steps); NaN unless every error is > 0 and there are at least two.
pub fn fitted_order(errors: &[f64], r: f64) -> f64 {
    if errors.len() < 2 || !errors.iter().all(|e| *e > 0.0) {
        return f64::NAN;
    }
    let n = errors.len() as f64;
    let xm = (n - 1.0) / 2.0;
    let ym = errors.iter().map(|e| e.ln()).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, e) in errors.iter().enumerate() {
        let x = i as f64 - xm;
        sxy += x * (e.ln() - ym);
        sxx += x * x;
    }
    -sxy / sxx / r.ln()
}

/// Richardson's estimate of the error of the finer of two solutions,
/// ε = φ_fine − φ_exact ≈ d/(r^p − 1), from their difference
/// d = φ_coarse − φ_fine on a ladder refined by `r` at order `p` (with
/// φ = φ_exact + α h^p: d = α h_f^p (r^p − 1)); φ_exact ≈ φ_fine − ε
/// (Roache 1998; MODEL §12's ε₁). The one Richardson formula of the
/// studies.
pub(crate) fn richardson_error(d: f64, r: f64, p: f64) -> f64 {
    d / (r.powf(p) - 1.0)
}

/// Roache's convergence ratio of three solutions, fine to coarse:
/// R = (φ₁ − φ₂)/(φ₂ − φ₃) (MODEL §12). 0 < R < 1: monotone convergence,
/// R < 0: oscillatory, R ≥ 1: divergence; NaN when φ₂ = φ₃. (The GCI
/// forms it inline; this is its test's statement.)
#[cfg(test)]
fn convergence_ratio(fine: f64, mid: f64, coarse: f64) -> f64 {
    let den = mid - coarse;
    if den == 0.0 {
        f64::NAN
    } else {
        (fine - mid) / den
    }
}

/// How a ladder's values behave as it is refined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Behaviour {
    /// Every difference is round-off: the refined variables do not matter.
    Exact,
    /// Every triplet has 0 < R < 1: the differences keep their sign and
    /// fall.
    Monotone,
    /// The differences fall (every |R| < 1) but change sign.
    Oscillatory,
    /// The differences grow at every level (every |R| > 1).
    Diverging,
    /// Neither: differences that fall and rise (events appearing and
    /// vanishing with the resolution), or too few levels to tell.
    Scattered,
}

impl Behaviour {
    /// Its name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Behaviour::Exact => "exact",
            Behaviour::Monotone => "monotone",
            Behaviour::Oscillatory => "oscillatory",
            Behaviour::Diverging => "diverging",
            Behaviour::Scattered => "scattered",
        }
    }
}

/// The behaviour of a ladder's values, coarsest first; differences at most
/// `round_off` count as zero (a quantity that does not move).
pub fn behaviour(values: &[f64], round_off: f64) -> Behaviour {
    let d: Vec<f64> = values
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            if d.abs() <= round_off { 0.0 } else { d }
        })
        .collect();
    if d.iter().all(|x| *x == 0.0) {
        return Behaviour::Exact;
    }
    if d.len() < 2 {
        return Behaviour::Scattered;
    }
    // R of each triplet: the finer difference over the coarser one
    let ratios: Vec<f64> = d
        .windows(2)
        .map(|w| {
            if w[0] == 0.0 {
                f64::INFINITY
            } else {
                w[1] / w[0]
            }
        })
        .collect();
    if ratios.iter().all(|r| *r > 0.0 && *r < 1.0) {
        Behaviour::Monotone
    } else if ratios.iter().all(|r| r.abs() < 1.0) {
        Behaviour::Oscillatory
    } else if ratios.iter().all(|r| r.abs() > 1.0) {
        Behaviour::Diverging
    } else {
        Behaviour::Scattered
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_of_a_second_order_sequence() {
        // u_ℓ = 1 + C h_ℓ², h halves: differences fall by 4
        assert!((observed_order(0.3, 0.075, 2.0) - 2.0).abs() < 1e-12);
        assert!(observed_order(0.0, 1.0, 2.0).is_nan());
        assert!(observed_order(1.0, 0.0, 2.0).is_nan());
        assert!(observed_order(f64::NAN, 1.0, 2.0).is_nan());
        // a fit through an exact sequence is its order; two errors give
        // the two-level order
        let e: Vec<f64> = (0..5).map(|l| 3.0 * 0.5f64.powi(3 * l)).collect();
        assert!((fitted_order(&e, 2.0) - 3.0).abs() < 1e-12);
        assert!((fitted_order(&[0.3, 0.075], 2.0) - 2.0).abs() < 1e-12);
        assert!(fitted_order(&[0.3], 2.0).is_nan());
        assert!(fitted_order(&[0.3, 0.0], 2.0).is_nan());
    }

    #[test]
    fn richardson_recovers_the_limit_of_an_exact_sequence() {
        // φ = 2 + 3h² at h = 0.2, 0.1: ε of the finer is 3·0.01
        let (c, f) = (2.0 + 3.0 * 0.04, 2.0 + 3.0 * 0.01);
        let e = richardson_error(c - f, 2.0, 2.0);
        assert!((e - 0.03).abs() < 1e-14);
        assert!((f - e - 2.0).abs() < 1e-14);
        assert!((convergence_ratio(f, c, 2.0 + 3.0 * 0.16) - 0.25).abs() < 1e-12);
    }

    #[test]
    fn behaviours_are_told_apart() {
        assert_eq!(
            behaviour(&[1.0, 1.5, 1.75, 1.875], 0.0),
            Behaviour::Monotone
        );
        assert_eq!(
            behaviour(&[1.0, 2.0, 1.5, 1.75], 0.0),
            Behaviour::Oscillatory
        );
        assert_eq!(behaviour(&[1.0, 1.1, 1.4, 2.0], 0.0), Behaviour::Diverging);
        assert_eq!(behaviour(&[1.0, 1.1, 1.12, 1.3], 0.0), Behaviour::Scattered);
        assert_eq!(behaviour(&[1.0, 1.0 + 1e-15, 1.0], 1e-12), Behaviour::Exact);
        assert_eq!(behaviour(&[1.0, 2.0], 0.0), Behaviour::Scattered);
    }
}
