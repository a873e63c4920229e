//! The highest natural frequency ω_max of the assembled model, for the
//! stability limit of an explicit method (central difference: Δt ≤ 2/ω_max,
//! MODEL §9.1).
//!
//! Computed from the assembled model, not guessed:
//!
//! * [`lanczos_max`]: a Lanczos iteration on M⁻¹K in the M-inner product
//!   (M's banded factor, full reorthogonalization), whose largest Ritz value
//!   θ ≤ ω_max² converges fast even where the top eigenvalues cluster (a
//!   uniform mesh), with its residual r: an eigenvalue lies in [θ − r, θ + r]
//!   (Parlett, *The Symmetric Eigenvalue Problem*, Thm 4.5.1), and θ + r is
//!   the upper estimate a run is held to. Measured against dense solves
//!   (`tests/methods.rs`) after 100 steps: θ is within 3e-5 of ω_max² on the
//!   reference beam at N = 400 (13 ms), and θ + r above it by 4e-4.
//! * [`element_bound`]: the largest eigenvalue of an element pair (K_e, M_e).
//!   For consistent masses the global ω_max² is at most the largest element
//!   ω² (Irons 1970; Hughes, *The Finite Element Method*, §9.1.3): a
//!   rigorous bound, but 1.8–2× too high for Hermite elements (their
//!   rotational element modes), so alone it would refuse stable steps; for
//!   string elements it is within 1e-4 of ω_max, tighter than θ + r. The
//!   limit uses the smaller of the two upper figures.

use nalgebra::DMatrix;

use super::banded::BandedLdlt;
use super::beam::BeamModel;
use super::element;
use crate::scene::BeamProps;

/// The largest ω (rad/s) of one element's (K_e, M_e) for `props`
/// ([`element::omega_max`]); its square bounds the assembled model's
/// ω_max² (module docs).
pub fn element_bound(props: &BeamProps, h: f64) -> f64 {
    element::omega_max(props.rho_a, props.ei, props.tension, h)
}

/// Largest eigenvalue ω_max² of K x = ω² M x by `steps` Lanczos steps:
/// (θ, r) with θ the largest Ritz value and r its residual norm (module
/// docs); ω_max ≤ sqrt(θ + r) unless the start vector misses the top mode,
/// which a pseudo-random start (fixed seed: deterministic) does not.
pub fn lanczos_max(beam: &BeamModel, mass_factor: &BandedLdlt, steps: usize) -> (f64, f64) {
    let n = beam.n;
    if n == 0 {
        return (0.0, 0.0);
    }
    let m = steps.clamp(1, n);
    // q_j and M q_j, column by column
    let mut q: Vec<Vec<f64>> = Vec::with_capacity(m + 1);
    let mut mq: Vec<Vec<f64>> = Vec::with_capacity(m + 1);
    let (mut alpha, mut beta) = (Vec::with_capacity(m), Vec::with_capacity(m));
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut w: Vec<f64> = (0..n)
        .map(|_| {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let m_norm = |x: &[f64], mx: &mut Vec<f64>| -> f64 {
        mx.iter_mut().for_each(|v| *v = 0.0);
        beam.mass.mul_acc(x, 1.0, mx);
        x.iter()
            .zip(mx.iter())
            .map(|(a, b)| a * b)
            .sum::<f64>()
            .sqrt()
    };
    let mut mw = vec![0.0; n];
    let mut last_beta = 0.0;
    for j in 0..m {
        let norm = m_norm(&w, &mut mw);
        if !(norm > 0.0 && norm.is_finite()) {
            break;
        }
        if j > 0 {
            beta.push(norm);
        }
        let qj: Vec<f64> = w.iter().map(|x| x / norm).collect();
        let mqj: Vec<f64> = mw.iter().map(|x| x / norm).collect();
        // w = M⁻¹ K q_j
        let mut kq = vec![0.0; n];
        beam.stiffness.mul_acc(&qj, 1.0, &mut kq);
        let a: f64 = qj.iter().zip(&kq).map(|(x, y)| x * y).sum();
        alpha.push(a);
        mass_factor.solve(&mut kq);
        w = kq;
        q.push(qj);
        mq.push(mqj);
        // full reorthogonalization in the M-inner product, twice
        for _ in 0..2 {
            for (qi, mqi) in q.iter().zip(&mq) {
                let c: f64 = mqi.iter().zip(&w).map(|(x, y)| x * y).sum();
                w.iter_mut().zip(qi).for_each(|(wv, qv)| *wv -= c * qv);
            }
        }
        last_beta = m_norm(&w, &mut mw);
    }
    let k = alpha.len();
    let t = DMatrix::from_fn(k, k, |i, j| {
        if i == j {
            alpha[i]
        } else if i.abs_diff(j) == 1 {
            beta[i.min(j)]
        } else {
            0.0
        }
    });
    let eig = t.symmetric_eigen();
    let (imax, theta) =
        eig.eigenvalues
            .iter()
            .copied()
            .enumerate()
            .fold(
                (0, f64::NEG_INFINITY),
                |acc, (i, v)| {
                    if v > acc.1 { (i, v) } else { acc }
                },
            );
    let residual = last_beta * eig.eigenvectors[(k - 1, imax)].abs();
    (theta.max(0.0), residual)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Support;

    fn props(ei: f64) -> BeamProps {
        BeamProps {
            length: 10.0,
            rho_a: 1.3,
            ei,
            ea: None,
            tension: 2e4,
            left: Support::Pinned,
            right: Support::Pinned,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    #[test]
    fn a_string_element_has_the_closed_form() {
        // (K_e, M_e) = (T/h [1 −1; −1 1], ρAh/6 [2 1; 1 2]): ω² = 12 T/(ρA h²)
        let p = props(0.0);
        let h = 0.25;
        let w = element_bound(&p, h);
        let exact = (12.0 * p.tension / (p.rho_a * h * h)).sqrt();
        assert!((w / exact - 1.0).abs() < 1e-12, "{w} vs {exact}");
    }
}
