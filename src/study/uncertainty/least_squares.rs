//! The least-squares estimator of Eça & Hoekstra, "A procedure for the
//! estimation of the numerical uncertainty of CFD calculations based on
//! grid refinement studies", J. Comput. Phys. 262 (2014) 104–130 (MODEL
//! §12), for scattered or non-monotone data: solutions φ_i at relative step
//! sizes h_i (h₁ = 1 the finest), n ≥ 3 of them.
//!
//! The four error estimators and their weighted fits are on [`FitKind`],
//! the uncertainty of each solution on [`estimate`].
//!
//! **Which fit.** The observed order is δ_RE's p. When 0.5 ≤ p < p_th + 0.1
//! (the paper's 0.5 ≤ p < 2.1 for a second-order method, p_th the formal
//! order) and its σ is below the data range Δ_φ = (φ_max − φ_min)/(n − 1),
//! δ_RE is the error estimate. Otherwise (p out of that range, or a poor
//! fit) the estimate is the fit of smallest σ among δ_1, δ_2, δ_12 (and
//! δ_RE when its p is in range).
//!
//! Two choices of taut's where the paper, written for second-order CFD
//! codes, is silent: the range's top is p_th + 0.1 for the formal order
//! p_th of the quantity (2.1 for p_th = 2, as in the paper), and with only
//! three solutions δ_12, which three points determine exactly whatever
//! they are, is not a candidate (n − n_p is then taken as 1 in σ, so a
//! three-point fit that misses a point is not called exact).

use serde::Serialize;

use super::gci::{FS_ASYMPTOTIC, FS_CAUTIOUS};

/// Lowest observed order the paper accepts for δ_RE: below it the fit's
/// extrapolation is too far from the data to trust.
pub(crate) const LOWEST_ORDER: f64 = 0.5;

/// How far above the formal order δ_RE's p may be and still be used (the
/// paper's 2.1 for a second-order method).
pub(crate) const ORDER_MARGIN: f64 = 0.1;

/// The range of p searched for δ_RE: above zero (p → 0 makes h^p the
/// constant and the fit singular) up to an order no discretization here
/// reaches; a best p at either end is out of range.
pub(crate) const ORDER_SEARCH: (f64, f64) = (0.05, 10.0);

/// Points of the first, logarithmic scan of p (then golden section).
const ORDER_SCAN: usize = 400;

/// Which expansion a fit is.
///
/// **Error estimators** (the paper's power-series expansions):
///
/// ```text
/// δ_RE = φ_i − φ₀ = α h_i^p          p free            (3 parameters)
/// δ_1  = φ_i − φ₀ = α h_i            first order       (2 parameters)
/// δ_2  = φ_i − φ₀ = α h_i²           second order      (2 parameters)
/// δ_12 = φ_i − φ₀ = α₁ h_i + α₂ h_i²                   (3 parameters)
/// ```
///
/// each fitted by least squares, unweighted (minimize Σ(φ_i − φ_fit,i)²)
/// and weighted (minimize Σ w_i(φ_i − φ_fit,i)², w_i = (1/h_i)/Σ_j(1/h_j),
/// which favours the finer solutions), with the standard deviations
///
/// ```text
/// σ   = sqrt( Σ (φ_i − φ_fit,i)² / (n − n_p) )
/// σ_w = sqrt( n Σ w_i (φ_i − φ_fit,i)² / (n − n_p) )
/// ```
///
/// (n_p the fit's parameters); of the two, the fit with the smaller σ is
/// kept. δ_RE is fitted for every p on a fine grid (the fit is linear in φ₀
/// and α at fixed p), refined by golden section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitKind {
    /// δ_RE = α h^p, p free.
    FreeOrder,
    /// δ_1 = α h.
    First,
    /// δ_2 = α h².
    Second,
    /// δ_12 = α₁ h + α₂ h².
    FirstAndSecond,
}

impl FitKind {
    /// Its name in tables.
    pub fn name(self) -> &'static str {
        match self {
            FitKind::FreeOrder => "free_order",
            FitKind::First => "first_order",
            FitKind::Second => "second_order",
            FitKind::FirstAndSecond => "first_and_second_order",
        }
    }

    /// Parameters n_p, φ₀ included.
    pub fn parameters(self) -> usize {
        match self {
            FitKind::FreeOrder | FitKind::FirstAndSecond => 3,
            FitKind::First | FitKind::Second => 2,
        }
    }
}

/// One least-squares fit φ(h) = φ₀ + α h^p (+ α₂ h² for δ_12).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fit {
    /// The expansion.
    pub kind: FitKind,
    /// Weighted by w_i ∝ 1/h_i.
    pub weighted: bool,
    /// φ₀, the extrapolated value.
    pub phi0: f64,
    /// α (α₁ for δ_12).
    pub alpha: f64,
    /// α₂ of δ_12 (0 otherwise).
    pub alpha2: f64,
    /// p: fitted for δ_RE, 1 or 2 for δ_1, δ_2, NaN for δ_12.
    pub order: f64,
    /// Its standard deviation σ (σ_w when weighted).
    pub sigma: f64,
}

impl Fit {
    /// φ_fit(h) − φ₀.
    pub fn error_at(&self, h: f64) -> f64 {
        match self.kind {
            FitKind::FirstAndSecond => self.alpha * h + self.alpha2 * h * h,
            _ => self.alpha * h.powf(self.order),
        }
    }

    /// φ_fit(h).
    pub fn at(&self, h: f64) -> f64 {
        self.phi0 + self.error_at(h)
    }
}

/// Where δ_RE's observed order lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum OrderRange {
    /// `LOWEST_ORDER` ≤ p < p_th + `ORDER_MARGIN`.
    InRange,
    /// Below `LOWEST_ORDER`.
    Below,
    /// At or above p_th + `ORDER_MARGIN`.
    Above,
}

/// The estimate of a set of solutions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeastSquares {
    /// δ_RE, the fit with p free (weighted or not, by σ).
    pub free: Fit,
    /// Where its p lies.
    pub range: OrderRange,
    /// The fit the error estimate comes from.
    pub fit: Fit,
    /// Δ_φ = (φ_max − φ_min)/(n − 1).
    pub data_range: f64,
    /// F_s.
    pub safety_factor: f64,
    /// σ ≥ Δ_φ: U widened by 3σ/Δ_φ.
    pub widened: bool,
    /// ε_i = φ_fit(h_i) − φ₀ of each solution, in the given order.
    pub error: Vec<f64>,
    /// U_i of each solution, in the given order.
    pub u: Vec<f64>,
}

impl LeastSquares {
    /// True when the estimate is δ_RE in range with a good fit and the
    /// small F_s: the data are in the asymptotic range.
    pub fn asymptotic(&self) -> bool {
        self.safety_factor == FS_ASYMPTOTIC
    }
}

/// The estimate of solutions `phi` at relative step sizes `h` (same
/// length, n ≥ 3, h > 0 and distinct), for a quantity of formal order
/// `formal`; `smooth` false keeps F_s = 3 (MODEL §12). `None` for fewer
/// than three solutions or a fit that cannot be made (non-finite data).
///
/// **Uncertainty of each solution** (ε_i the chosen fit's φ_fit,i − φ₀):
///
/// ```text
/// σ < Δ_φ:   U_i = F_s |ε_i| + σ + |φ_i − φ_fit,i|
/// σ ≥ Δ_φ:   U_i = 3 σ/Δ_φ · (|ε_i| + σ + |φ_i − φ_fit,i|)
/// ```
///
/// F_s = 1.25 for δ_RE with p in range and σ < Δ_φ, 3 otherwise (always 3
/// for a quantity that is not smooth, MODEL §12).
pub fn estimate(h: &[f64], phi: &[f64], formal: f64, smooth: bool) -> Option<LeastSquares> {
    let n = h.len();
    if n < 3 || phi.len() != n || !phi.iter().chain(h).all(|v| v.is_finite()) {
        return None;
    }
    let free = best(FitKind::FreeOrder, h, phi)?;
    let range = if free.order < LOWEST_ORDER || free.order <= ORDER_SEARCH.0 {
        OrderRange::Below
    } else if free.order >= formal + ORDER_MARGIN || free.order >= ORDER_SEARCH.1 {
        OrderRange::Above
    } else {
        OrderRange::InRange
    };
    let (lo, hi) = phi
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let data_range = (hi - lo) / (n - 1) as f64;
    let in_range = range == OrderRange::InRange;
    let fit = if in_range && free.sigma < data_range {
        free
    } else {
        let mut candidates: Vec<Fit> = [FitKind::First, FitKind::Second, FitKind::FirstAndSecond]
            .into_iter()
            .filter(|k| k.parameters() < n)
            .filter_map(|k| best(k, h, phi))
            .collect();
        if in_range {
            candidates.push(free);
        }
        candidates
            .into_iter()
            .min_by(|a, b| a.sigma.total_cmp(&b.sigma))?
    };
    let widened = fit.sigma >= data_range;
    let safety_factor = if smooth && fit.kind == FitKind::FreeOrder && in_range && !widened {
        FS_ASYMPTOTIC
    } else {
        FS_CAUTIOUS
    };
    let error: Vec<f64> = h.iter().map(|&x| fit.error_at(x)).collect();
    let u = h
        .iter()
        .zip(phi)
        .zip(&error)
        .map(|((&x, &y), e)| {
            let residual = (y - fit.at(x)).abs();
            let sum = e.abs() + fit.sigma + residual;
            if widened {
                // data_range may be 0 only with σ = 0 = data_range: exact data
                if data_range > 0.0 {
                    FS_CAUTIOUS * fit.sigma / data_range * sum
                } else {
                    sum
                }
            } else {
                safety_factor * e.abs() + fit.sigma + residual
            }
        })
        .collect();
    Some(LeastSquares {
        free,
        range,
        fit,
        data_range,
        safety_factor,
        widened,
        error,
        u,
    })
}

/// The fit of `kind`, weighted or not, whichever has the smaller σ.
pub fn best(kind: FitKind, h: &[f64], phi: &[f64]) -> Option<Fit> {
    let plain = fit(kind, h, phi, false);
    let weighted = fit(kind, h, phi, true);
    match (plain, weighted) {
        (Some(a), Some(b)) => Some(if b.sigma < a.sigma { b } else { a }),
        (a, b) => a.or(b),
    }
}

/// The least-squares fit of `kind` to `phi` at `h`, weighted (w ∝ 1/h) or
/// not.
pub fn fit(kind: FitKind, h: &[f64], phi: &[f64], weighted: bool) -> Option<Fit> {
    let n = h.len();
    let w: Vec<f64> = if weighted {
        let s: f64 = h.iter().map(|x| 1.0 / x).sum();
        h.iter().map(|x| (1.0 / x) / s).collect()
    } else {
        vec![1.0; n]
    };
    let sigma = |sum_wr2: f64| {
        let dof = n.saturating_sub(kind.parameters()).max(1) as f64;
        let scale = if weighted { n as f64 } else { 1.0 };
        (scale * sum_wr2 / dof).sqrt()
    };
    let (coef, order) = match kind {
        FitKind::First => (linear(h, phi, &w, &[1.0])?, 1.0),
        FitKind::Second => (linear(h, phi, &w, &[2.0])?, 2.0),
        FitKind::FirstAndSecond => (linear(h, phi, &w, &[1.0, 2.0])?, f64::NAN),
        FitKind::FreeOrder => {
            let s = |p: f64| linear(h, phi, &w, &[p]).map_or(f64::INFINITY, |c| c.1);
            let p = minimize_log(s, ORDER_SEARCH)?;
            (linear(h, phi, &w, &[p])?, p)
        }
    };
    let ([phi0, alpha, alpha2], sum_wr2) = coef;
    Some(Fit {
        kind,
        weighted,
        phi0,
        alpha,
        alpha2,
        order,
        sigma: sigma(sum_wr2),
    })
}

/// Weighted linear least squares φ ≈ φ₀ + Σ_k c_k h^{e_k} (one or two
/// exponents): `([φ₀, c₁, c₂], Σ w r²)`, or None when singular.
fn linear(h: &[f64], phi: &[f64], w: &[f64], exps: &[f64]) -> Option<([f64; 3], f64)> {
    let m = 1 + exps.len();
    let basis = |x: f64, k: usize| if k == 0 { 1.0 } else { x.powf(exps[k - 1]) };
    let mut a = [[0.0f64; 4]; 3];
    for ((&x, &y), &wi) in h.iter().zip(phi).zip(w) {
        for i in 0..m {
            for j in 0..m {
                a[i][j] += wi * basis(x, i) * basis(x, j);
            }
            a[i][m] += wi * basis(x, i) * y;
        }
    }
    let c = solve(&mut a, m)?;
    let mut coef = [0.0; 3];
    coef[..m].copy_from_slice(&c[..m]);
    let sum: f64 = h
        .iter()
        .zip(phi)
        .zip(w)
        .map(|((&x, &y), &wi)| {
            let f = (0..m).map(|k| coef[k] * basis(x, k)).sum::<f64>();
            wi * (y - f) * (y - f)
        })
        .sum();
    sum.is_finite().then_some((coef, sum))
}

/// Gaussian elimination with partial pivoting of an m × m system whose
/// right-hand side is column m of `a`.
fn solve(a: &mut [[f64; 4]; 3], m: usize) -> Option<[f64; 3]> {
    let scale = (0..m).map(|i| a[i][i].abs()).fold(0.0, f64::max);
    for col in 0..m {
        let piv = (col..m).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        // a pivot that is zero, NaN or round-off of the largest: singular
        let pivot = a[piv][col].abs();
        if pivot.is_nan() || pivot <= 1e-14 * scale {
            return None;
        }
        a.swap(col, piv);
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            for k in col..=m {
                a[row][k] -= f * a[col][k];
            }
        }
    }
    let mut x = [0.0; 3];
    for i in (0..m).rev() {
        let s: f64 = (i + 1..m).map(|k| a[i][k] * x[k]).sum();
        x[i] = (a[i][m] - s) / a[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The p in `range` minimizing `s(p)`: a logarithmic scan, then golden
/// section between the best point's neighbours.
fn minimize_log(s: impl Fn(f64) -> f64, range: (f64, f64)) -> Option<f64> {
    let (lo, hi) = (range.0.ln(), range.1.ln());
    let at = |k: usize| (lo + (hi - lo) * k as f64 / (ORDER_SCAN - 1) as f64).exp();
    let k = (0..ORDER_SCAN).min_by(|&a, &b| s(at(a)).total_cmp(&s(at(b))))?;
    if !s(at(k)).is_finite() {
        return None;
    }
    let (mut a, mut b) = (at(k.saturating_sub(1)), at((k + 1).min(ORDER_SCAN - 1)));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..60 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if s(c) <= s(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let p = 0.5 * (a + b);
    Some(if s(p) <= s(at(k)) { p } else { at(k) })
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: [f64; 5] = [1.0, 2.0, 4.0, 8.0, 16.0];

    fn data(f: impl Fn(f64) -> f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let h = H[..n].to_vec();
        let phi = h.iter().map(|&x| f(x)).collect();
        (h, phi)
    }

    #[test]
    fn an_exact_power_law_is_recovered_with_the_small_factor() {
        let (h, phi) = data(|x| 3.0 + 0.01 * x.powf(1.7), 5);
        let e = estimate(&h, &phi, 2.0, true).unwrap();
        assert_eq!(e.fit.kind, FitKind::FreeOrder);
        assert!((e.fit.order - 1.7).abs() < 1e-6, "{:?}", e.fit);
        assert!((e.fit.phi0 - 3.0).abs() < 1e-9);
        assert_eq!(e.range, OrderRange::InRange);
        assert_eq!(e.safety_factor, FS_ASYMPTOTIC);
        assert!(e.fit.sigma < 1e-9);
        // U of the finest: 1.25 |ε| (σ and the residual vanish)
        assert!((e.u[0] - 1.25 * 0.01).abs() < 1e-8, "{:?}", e.u);
        assert!(e.asymptotic());
        // not smooth: the same data, F_s = 3
        let rough = estimate(&h, &phi, 2.0, false).unwrap();
        assert_eq!(rough.safety_factor, FS_CAUTIOUS);
        assert!(rough.u[0] > e.u[0]);
    }

    #[test]
    fn three_solutions_reduce_to_the_gci() {
        let (h, phi) = data(|x| 1.0 + 0.02 * x * x, 3);
        let e = estimate(&h, &phi, 2.0, true).unwrap();
        let g = super::super::gci::Gci::three(phi[2], phi[1], phi[0], 2.0, Some(2.0)).unwrap();
        assert!((e.u[0] - g.u).abs() < 1e-8, "{} {}", e.u[0], g.u);
    }

    #[test]
    fn an_order_above_range_falls_back_to_fixed_orders() {
        // p = 4 against a formal 2: δ_RE is out of range
        let (h, phi) = data(|x| 1.0 + 1e-3 * x.powi(4), 5);
        let e = estimate(&h, &phi, 2.0, true).unwrap();
        assert_eq!(e.range, OrderRange::Above);
        assert_ne!(e.fit.kind, FitKind::FreeOrder);
        assert_eq!(e.safety_factor, FS_CAUTIOUS);
        // the same data against a formal 4 are in range
        let e4 = estimate(&h, &phi, 4.0, true).unwrap();
        assert_eq!(e4.range, OrderRange::InRange);
        assert_eq!(e4.fit.kind, FitKind::FreeOrder);
    }

    #[test]
    fn scattered_data_are_widened_by_their_scatter() {
        // a first-order trend with scatter larger than the data range
        let phi = vec![1.0, 1.012, 0.994, 1.03, 1.02];
        let e = estimate(&H, &phi, 1.0, false).unwrap();
        assert_eq!(e.safety_factor, FS_CAUTIOUS);
        // the finest's U covers every difference to it
        let spread = phi.iter().map(|v| (v - phi[0]).abs()).fold(0.0, f64::max);
        assert!(e.u[0] > 0.5 * spread, "{:?} {spread}", e.u);
        if e.widened {
            assert!(e.fit.sigma >= e.data_range);
        }
    }

    #[test]
    fn weighted_fits_favour_the_fine_solutions() {
        let (h, mut phi) = data(|x| 2.0 + 0.1 * x, 5);
        // spoil the coarsest
        phi[4] += 0.5;
        let w = fit(FitKind::First, &h, &phi, true).unwrap();
        let u = fit(FitKind::First, &h, &phi, false).unwrap();
        assert!((w.phi0 - 2.0).abs() < (u.phi0 - 2.0).abs());
    }
}
