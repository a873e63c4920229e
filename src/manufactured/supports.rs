//! Making a chosen x-shape meet the supports (MODEL §11): pinned
//! `w = w'' = 0`, clamped `w = w' = 0`, free `w'' = EI w''' − T w' = 0`
//! (a string, EI = 0, has only `w = 0` at its pinned ends).
//!
//! A user picks a smooth shape S(ξ), ξ = x/L, from the family of
//! [`super::factor`]; the manufactured shape is `X = S − c` with c the
//! polynomial in ξ of fewest terms that has S's boundary values in the
//! supports' conditions, so X meets them exactly. A shape that already
//! meets them (sin(nπξ) on a pinned–pinned span) gets c = 0 up to
//! round-off. The powers of c are the first set in [`CANDIDATES`] whose
//! conditions are independent: {1, ξ, ξ², ξ³} for every support pair but
//! free–free (whose conditions leave a constant free: {ξ, …, ξ⁴} there).

use nalgebra::{DMatrix, DVector};

use super::factor::Product;
use super::jet::Jet;
use crate::error::{Error, Result};
use crate::scene::Support;

/// Power sets tried for the correction polynomial of a beam, in order.
pub const CANDIDATES: [[usize; 4]; 4] = [[0, 1, 2, 3], [1, 2, 3, 4], [0, 1, 2, 4], [2, 3, 4, 5]];

/// A condition set is dependent when |det| falls below this fraction of
/// the product of its rows' norms (Hadamard's bound): a well-posed set of
/// four conditions on O(1) polynomials sits near 1e-2.
const INDEPENDENT: f64 = 1e-9;

/// An x-shape meeting the supports: `X(ξ) = S(ξ) − Σ cₖ ξ^{pₖ}`, or on a
/// line with interior supports `X(ξ) = (S(ξ) − Σ cₖ ξ^{pₖ}) P(ξ)`, P a
/// polynomial vanishing at each of them ([`Shape::weighted`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    raw: Product,
    /// (power, coefficient) of the correction.
    correction: Vec<(usize, f64)>,
    length: f64,
    /// P(ξ) (`None`: 1).
    weight: Option<Product>,
}

/// The span's supports and section, as the conditions need them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ends {
    /// Support at x = 0 and at x = L.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
    /// L, m.
    pub length: f64,
    /// EI, N·m² (0: a string).
    pub ei: f64,
    /// T, N.
    pub tension: f64,
}

impl Ends {
    /// The boundary conditions at one end on a jet in ξ (dimensionless:
    /// the free-end shear `EI w''' − T w'` divided by EI/L³).
    fn conditions(&self, support: Support, j: &Jet) -> Vec<f64> {
        if self.ei == 0.0 {
            // a string: v = 0 held, T v' = 0 free
            return match support {
                Support::Free => vec![j.d(1)],
                _ => vec![j.d(0)],
            };
        }
        let tau = self.tension * self.length * self.length / self.ei;
        match support {
            Support::Pinned => vec![j.d(0), j.d(2)],
            Support::Clamped => vec![j.d(0), j.d(1)],
            Support::Free => vec![j.d(2), j.d(3) - tau * j.d(1)],
        }
    }

    /// Every condition of both ends on a function given by its jets in ξ
    /// at ξ = 0 and ξ = 1.
    fn all(&self, at0: &Jet, at1: &Jet) -> Vec<f64> {
        let mut c = self.conditions(self.left, at0);
        c.extend(self.conditions(self.right, at1));
        c
    }
}

/// The jet of ξᵖ at ξ: derivative k is p!/(p − k)! ξ^{p−k} (no
/// allocation: a step evaluates it).
fn monomial(p: usize, xi: f64) -> Jet {
    let mut out = [0.0; super::jet::ORDER + 1];
    for (k, o) in out.iter_mut().enumerate() {
        if k <= p {
            let falling: f64 = ((p - k + 1)..=p).map(|i| i as f64).product();
            *o = falling * xi.powi((p - k) as i32);
        }
    }
    Jet(out)
}

impl Shape {
    /// Correct `raw` so that it meets `ends` (module docs).
    pub fn new(raw: Product, ends: &Ends, field: &str) -> Result<Self> {
        Self::build(raw, ends, None, field)
    }

    /// Correct `raw` so that `(raw − c)·weight` meets `ends` (c a
    /// polynomial of the same powers as [`Shape::new`]'s): a line held at
    /// interior points ξ_s (the messenger's supports) takes the weight
    /// P(ξ) = Π (ξ − ξ_s), so X vanishes there whatever c is, and c makes
    /// the ends' conditions hold.
    pub fn weighted(raw: Product, ends: &Ends, weight: Product, field: &str) -> Result<Self> {
        Self::build(raw, ends, Some(weight), field)
    }

    fn build(raw: Product, ends: &Ends, weight: Option<Product>, field: &str) -> Result<Self> {
        let times = |j: Jet, xi: f64| match &weight {
            Some(w) => j * w.jet(xi),
            None => j,
        };
        let target = ends.all(&times(raw.jet(0.0), 0.0), &times(raw.jet(1.0), 1.0));
        let sets: Vec<Vec<usize>> = if ends.ei == 0.0 {
            vec![vec![0, 1], vec![0, 2], vec![1, 2]]
        } else {
            CANDIDATES.iter().map(|s| s.to_vec()).collect()
        };
        for powers in sets {
            let n = powers.len();
            let columns: Vec<Vec<f64>> = powers
                .iter()
                .map(|&p| ends.all(&times(monomial(p, 0.0), 0.0), &times(monomial(p, 1.0), 1.0)))
                .collect();
            let a = DMatrix::from_fn(n, n, |i, j| columns[j][i]);
            let hadamard: f64 = a.row_iter().map(|r| r.norm()).product();
            let det = a.determinant();
            // NaN (a singular set) is dependent too
            if det.is_nan() || det.abs() <= INDEPENDENT * hadamard {
                continue;
            }
            let Some(c) = a.lu().solve(&DVector::from_vec(target.clone())) else {
                continue;
            };
            return Ok(Shape {
                raw,
                correction: powers.into_iter().zip(c.iter().copied()).collect(),
                length: ends.length,
                weight,
            });
        }
        Err(Error::invalid(
            field,
            format!("supports {:?}–{:?}", ends.left, ends.right).to_lowercase(),
            "no polynomial correction of up to degree 5 makes this shape meet the supports: choose other supports",
        ))
    }

    /// X and its x-derivatives 1 ..= 4 at x (m), per m⁰ … m⁻⁴.
    pub fn jet(&self, x: f64) -> Jet {
        let xi = x / self.length;
        let mut j = self.raw.jet(xi);
        for &(p, c) in &self.correction {
            j = j + monomial(p, xi).scale(-c);
        }
        if let Some(w) = &self.weight {
            j = j * w.jet(xi);
        }
        j.rescaled(self.length)
    }

    /// The shape as given, before the correction.
    pub fn raw(&self) -> &Product {
        &self.raw
    }

    /// The correction's coefficients, (power of ξ, coefficient).
    #[cfg(test)]
    fn correction(&self) -> &[(usize, f64)] {
        &self.correction
    }
}

#[cfg(test)]
mod tests {
    use super::super::factor::Factor;
    use super::*;

    /// Conditions met to round-off of O(1) polynomials and a 4×4 solve.
    const MET: f64 = 1e-11;

    fn ends(left: Support, right: Support, ei: f64) -> Ends {
        Ends {
            left,
            right,
            length: 2.0,
            ei,
            tension: 30.0,
        }
    }

    #[test]
    fn every_support_pair_is_met() {
        use Support::*;
        let raw = Product(vec![
            Factor::Polynomial(vec![0.3, 1.0, -0.5, 0.2]),
            Factor::Exponential { rate: 0.7 },
            Factor::Sine {
                rate: 2.0,
                phase: 0.1,
            },
        ]);
        for (l, r) in [
            (Pinned, Pinned),
            (Clamped, Pinned),
            (Pinned, Clamped),
            (Clamped, Clamped),
            (Clamped, Free),
            (Free, Clamped),
            (Pinned, Free),
            (Free, Free),
        ] {
            let e = ends(l, r, 5.0);
            let s = Shape::new(raw.clone(), &e, "manufactured.term.0.x").unwrap();
            // the conditions in x units
            for (support, x) in [(l, 0.0), (r, e.length)] {
                let j = s.jet(x);
                let c = match support {
                    Pinned => [j.d(0), j.d(2)],
                    Clamped => [j.d(0), j.d(1)],
                    Free => [j.d(2), e.ei * j.d(3) - e.tension * j.d(1)],
                };
                assert!(
                    c.iter().all(|v| v.abs() < MET * 100.0),
                    "{l:?}-{r:?}: {c:?}"
                );
            }
        }
        // a string: v = 0 at both ends
        let s = Shape::new(raw, &ends(Pinned, Pinned, 0.0), "f").unwrap();
        assert!(s.jet(0.0).d(0).abs() < MET && s.jet(2.0).d(0).abs() < MET);
    }

    #[test]
    fn monomial_jets_are_the_polynomial_s() {
        for p in 0..6 {
            let mut c = vec![0.0; p + 1];
            c[p] = 1.0;
            let poly = Factor::Polynomial(c).jet(0.7);
            let mono = monomial(p, 0.7);
            for k in 0..5 {
                assert!((poly.d(k) - mono.d(k)).abs() < 1e-14, "p {p}, k {k}");
            }
        }
    }

    #[test]
    fn a_shape_that_meets_the_supports_is_left_alone() {
        let raw = Product(vec![Factor::Sine {
            rate: 3.0 * std::f64::consts::PI,
            phase: 0.0,
        }]);
        let s = Shape::new(raw, &ends(Support::Pinned, Support::Pinned, 5.0), "f").unwrap();
        assert!(s.correction().iter().all(|(_, c)| c.abs() < MET));
    }
}
