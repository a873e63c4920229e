//! Test support: a dense Hermite beam model (MODEL §4, consistent mass,
//! bending and tension stiffness) and its natural frequencies, for the
//! references' independent finite-element checks. Dense and slow on
//! purpose: it shares nothing with `model`, which the references verify.

use nalgebra::{DMatrix, SymmetricEigen};

/// Assembled (K, M) of `n` uniform Hermite elements of length `h` (m), ρA
/// `ra` (kg/m), EI `ei` (N·m²), tension `t` (N); DOFs (v, θ) per node.
pub(crate) fn hermite_km(
    ei: f64,
    t: f64,
    ra: f64,
    h: f64,
    n: usize,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let dofs = 2 * (n + 1);
    let mut k = DMatrix::<f64>::zeros(dofs, dofs);
    let mut m = DMatrix::<f64>::zeros(dofs, dofs);
    let me = [
        [156.0, 22.0 * h, 54.0, -13.0 * h],
        [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
        [54.0, 13.0 * h, 156.0, -22.0 * h],
        [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
    ];
    let kb = [
        [12.0, 6.0 * h, -12.0, 6.0 * h],
        [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
        [-12.0, -6.0 * h, 12.0, -6.0 * h],
        [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
    ];
    let kt = [
        [36.0, 3.0 * h, -36.0, 3.0 * h],
        [3.0 * h, 4.0 * h * h, -3.0 * h, -h * h],
        [-36.0, -3.0 * h, 36.0, -3.0 * h],
        [3.0 * h, -h * h, -3.0 * h, 4.0 * h * h],
    ];
    for e in 0..n {
        for a in 0..4 {
            for b in 0..4 {
                let (i, j) = (2 * e + a, 2 * e + b);
                m[(i, j)] += ra * h / 420.0 * me[a][b];
                k[(i, j)] += ei / h.powi(3) * kb[a][b] + t / (30.0 * h) * kt[a][b];
            }
        }
    }
    (k, m)
}

/// Natural frequencies (rad/s, ascending) of (K, M) restricted to the DOFs
/// `keep`: the symmetric form L⁻¹ K L⁻ᵀ with M = L Lᵀ.
pub(crate) fn frequencies(k: &DMatrix<f64>, m: &DMatrix<f64>, keep: &[usize]) -> Vec<f64> {
    let k = k.select_rows(keep).select_columns(keep);
    let m = m.select_rows(keep).select_columns(keep);
    let linv = m
        .cholesky()
        .expect("M is SPD")
        .l()
        .try_inverse()
        .expect("L is regular");
    let a = &linv * k * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let mut w: Vec<f64> = SymmetricEigen::new(a)
        .eigenvalues
        .iter()
        .map(|l| l.max(0.0).sqrt())
        .collect();
    w.sort_by(f64::total_cmp);
    w
}
