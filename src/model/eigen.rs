//! STUB (replaced by the faer version at merge): lowest eigenpairs.
use super::banded::SymBand;
use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// Largest FE model the dense eigenproblem takes.
pub const MAX_MODAL_DOFS: usize = 6400;

/// The J lowest eigenpairs, mass-normalized.
pub struct EigenPairs {
    /// ω_j².
    pub omega_sq: Vec<f64>,
    /// n × J column-major.
    pub shapes: Vec<f64>,
    /// n.
    pub n: usize,
    /// J.
    pub count: usize,
}

/// The J lowest eigenpairs of K φ = ω² M φ.
pub fn lowest_eigenpairs(mass: &SymBand, stiffness: &SymBand, count: usize) -> Result<EigenPairs> {
    let n = mass.n();
    if count == 0 || count > n {
        return Err(Error::invalid("mesh.modes", count, format!("1 ..= {n}")));
    }
    let m = DMatrix::from_fn(n, n, |i, j| mass.get(i, j));
    let k = DMatrix::from_fn(n, n, |i, j| stiffness.get(i, j));
    let l = m.cholesky().unwrap().l();
    let li = l.try_inverse().unwrap();
    let c = &li * k * li.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let e = c.symmetric_eigen();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
    let lit = li.transpose();
    let mut shapes = vec![0.0; n * count];
    let mut omega_sq = vec![0.0; count];
    for (c, &o) in order.iter().take(count).enumerate() {
        omega_sq[c] = e.eigenvalues[o];
        let phi = &lit * e.eigenvectors.column(o);
        shapes[c * n..(c + 1) * n].copy_from_slice(phi.as_slice());
    }
    Ok(EigenPairs {
        omega_sq,
        shapes,
        n,
        count,
    })
}
