//! Natural frequencies of the discretized beam: the generalized eigenproblem
//! K φ = ω² M φ of MODEL §4 (or §6 for strings), for mesh-convergence checks
//! against the exact frequencies of `analytic::modes` (Hermite cubics
//! converge eigenvalues at O(h⁴)).
//!
//! Dense on purpose: the checks need a few hundred unknowns at most, where a
//! Cholesky reduction L⁻¹KL⁻ᵀ and nalgebra's symmetric eigensolver take
//! milliseconds. A sparse shift-invert solver would pay off only for large
//! meshes, which no check needs. The eigenpairs the `modal` discretization
//! runs on come from [`super::eigen`] (faer, banded reduction, mode shapes);
//! this nalgebra path stays as its independent reference.

use nalgebra::DMatrix;

use super::beam::BeamModel;
use crate::error::{Error, Result};
use crate::scene::BeamProps;

/// Largest system solved densely (n³ work: 2000³ ≈ 10¹⁰ flops, seconds).
pub(crate) const MAX_DENSE_DOFS: usize = 2000;

/// The `count` lowest natural frequencies ω_j (rad/s) of the beam on
/// `elements` equal elements, ascending.
pub fn fe_frequencies(props: &BeamProps, elements: usize, count: usize) -> Result<Vec<f64>> {
    let beam = BeamModel::new(props, elements);
    let n = beam.n;
    if n > MAX_DENSE_DOFS {
        return Err(Error::invalid(
            "elements",
            elements,
            format!("gives {n} dofs; the dense modal solve takes at most {MAX_DENSE_DOFS}"),
        ));
    }
    let m = DMatrix::from_fn(n, n, |i, j| beam.mass.get(i, j));
    let k = DMatrix::from_fn(n, n, |i, j| beam.stiffness.get(i, j));
    let chol = m
        .cholesky()
        .ok_or_else(|| Error::invalid("beam", "mass matrix", "must be positive definite"))?;
    let l = chol.l();
    let linv = l.clone().try_inverse().ok_or_else(|| {
        Error::invalid("beam", "mass matrix", "Cholesky factor must be invertible")
    })?;
    let c = &linv * k * linv.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let mut lambda: Vec<f64> = c.symmetric_eigenvalues().iter().copied().collect();
    lambda.sort_by(f64::total_cmp);
    Ok(lambda
        .into_iter()
        .take(count)
        .map(|l| l.max(0.0).sqrt())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::{ClampedPinnedModes, PinnedPinnedModes};
    use crate::scene::Support;

    fn props(ei: f64, left: Support, right: Support) -> BeamProps {
        BeamProps {
            length: 1.0,
            rho_a: 1.335,
            ei,
            ea: None,
            tension: 25.0 * ei,
            left,
            right,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    /// Observed order of the first three eigenfrequencies of a clamped–pinned
    /// tensioned beam (T L²/EI = 25) under mesh halving: theory 4 (Hermite
    /// cubics); ±0.3, the band every smooth case is held to.
    const EIGEN_ORDER_TOL: f64 = 0.3;

    #[test]
    fn hermite_frequencies_converge_at_fourth_order() {
        let p = props(129.2, Support::Clamped, Support::Pinned);
        let exact = ClampedPinnedModes::new(p.ei, p.tension, p.rho_a, p.length)
            .unwrap()
            .frequencies(3);
        let errs: Vec<Vec<f64>> = [4, 8, 16]
            .iter()
            .map(|&n| {
                let fe = fe_frequencies(&p, n, 3).unwrap();
                fe.iter().zip(&exact).map(|(a, b)| (a - b) / b).collect()
            })
            .collect();
        for j in 0..3 {
            // Hermite elements with a consistent mass over-estimate frequencies
            assert!(errs.iter().all(|e| e[j] > 0.0), "mode {j}: {errs:?}");
            let order = crate::study::uncertainty::observed_order(errs[1][j], errs[2][j], 2.0);
            println!(
                "mode {j}: relative errors {:.2e} {:.2e} {:.2e}, order {order:.2}",
                errs[0][j], errs[1][j], errs[2][j]
            );
            assert!(
                (order - 4.0).abs() <= EIGEN_ORDER_TOL,
                "mode {j}: order {order}"
            );
        }
    }

    #[test]
    fn string_frequencies_converge_at_second_order() {
        let mut p = props(0.0, Support::Pinned, Support::Pinned);
        p.tension = 3e4;
        let exact = PinnedPinnedModes::new(0.0, p.tension, p.rho_a, p.length)
            .unwrap()
            .frequencies(2);
        let e: Vec<f64> = [16, 32]
            .iter()
            .map(|&n| (fe_frequencies(&p, n, 1).unwrap()[0] - exact[0]) / exact[0])
            .collect();
        let order = crate::study::uncertainty::observed_order(e[0], e[1], 2.0);
        assert!((order - 2.0).abs() <= EIGEN_ORDER_TOL, "order {order}");
    }
}
