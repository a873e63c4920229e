//! Gauss–Legendre quadrature: the rule a manufactured source is projected
//! with (`model::source`) and the exact modes are checked with.

use std::f64::consts::PI;

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_m from the
/// Chebyshev-like first guesses; converged to round-off). Exact for
/// polynomials of degree 2m − 1.
pub fn gauss_legendre(m: usize) -> Vec<(f64, f64)> {
    (1..=m)
        .map(|i| {
            let mut x = (PI * (i as f64 - 0.25) / (m as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=m {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = m as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The rule of `gl` on each of the panels between successive `cuts`:
/// (x, weight) pairs.
pub fn composite(gl: &[(f64, f64)], cuts: &[f64]) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(gl.len() * cuts.len().saturating_sub(1));
    for w in cuts.windows(2) {
        let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
        out.extend(gl.iter().map(|(x, wt)| (mid + half * x, half * wt)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_points_integrate_degree_fifteen_exactly() {
        let gl = gauss_legendre(8);
        // ∫_{-1}^{1} x^14 dx = 2/15, and odd powers vanish
        let s: f64 = gl.iter().map(|(x, w)| w * x.powi(14)).sum();
        assert!((s - 2.0 / 15.0).abs() < 1e-15);
        let odd: f64 = gl.iter().map(|(x, w)| w * x.powi(15)).sum();
        assert!(odd.abs() < 1e-15);
        let c = composite(&gl, &[0.0, 0.5, 2.0]);
        let s: f64 = c.iter().map(|(x, w)| w * x * x).sum();
        assert!((s - 8.0 / 3.0).abs() < 1e-14);
    }
}
