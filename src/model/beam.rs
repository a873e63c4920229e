//! The discretized beam: uniform mesh, dof numbering with supports removed,
//! global banded M and K (MODEL §4, §6), and point vectors r_b(x).
//!
//! Only what the scene requires: Hermite elements (v, θ per node,
//! half-bandwidth 3) when EI > 0, linear string elements (v per node,
//! half-bandwidth 1) when EI = 0.

use super::banded::SymBand;
use super::element;
use crate::scene::{BeamProps, Support};

/// Which element family the beam uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Hermite cubic beam elements with tension (EI > 0).
    Hermite,
    /// Linear C0 string elements (EI = 0).
    String,
}

/// A sparse vector over at most four beam dofs: the shape functions of the
/// element holding a point (MODEL §4, r_b(x)). Supported dofs carry weight 0.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointVector {
    /// Global dof indices (unused slots point at 0 with weight 0).
    pub idx: [usize; 4],
    /// Weights (shape function values).
    pub val: [f64; 4],
}

impl PointVector {
    /// rᵀx.
    #[inline]
    pub fn dot(&self, x: &[f64]) -> f64 {
        self.val[0] * x[self.idx[0]]
            + self.val[1] * x[self.idx[1]]
            + self.val[2] * x[self.idx[2]]
            + self.val[3] * x[self.idx[3]]
    }

    /// y += a·r. `y` has `stride` interleaved columns; this writes column `col`.
    #[inline]
    pub fn scatter(&self, a: f64, y: &mut [f64], stride: usize, col: usize) {
        for k in 0..4 {
            y[self.idx[k] * stride + col] += a * self.val[k];
        }
    }

    /// rᵀx where x has `stride` interleaved columns; reads column `col`.
    #[inline]
    pub fn dot_strided(&self, x: &[f64], stride: usize, col: usize) -> f64 {
        (0..4)
            .map(|k| self.val[k] * x[self.idx[k] * stride + col])
            .sum()
    }
}

/// The assembled beam.
#[derive(Debug, Clone)]
pub struct BeamModel {
    /// Element family.
    pub family: Family,
    /// Number of elements N.
    pub elements: usize,
    /// Span L, m.
    pub length: f64,
    /// Element length h = L/N, m.
    pub h: f64,
    /// For each node-local dof (node·dofs_per_node + local), its global index
    /// or `None` when a support removes it.
    pub dof_of: Vec<Option<usize>>,
    /// Number of free dofs n.
    pub n: usize,
    /// Global consistent mass matrix M, kg (and kg·m² on rotations).
    pub mass: SymBand,
    /// Global stiffness K = K_B + K_T, N/m.
    pub stiffness: SymBand,
    /// Consistent load vector of the distributed load p, N.
    pub load: Vec<f64>,
}

impl BeamModel {
    /// Assemble the beam for `props` on `elements` equal elements.
    pub fn new(props: &BeamProps, elements: usize) -> Self {
        let family = if props.is_string() {
            Family::String
        } else {
            Family::Hermite
        };
        let per_node = match family {
            Family::Hermite => 2,
            Family::String => 1,
        };
        let nodes = elements + 1;
        let mut removed = vec![false; nodes * per_node];
        for (node, support) in [(0, props.left), (elements, props.right)] {
            match support {
                Support::Clamped => {
                    removed[node * per_node] = true;
                    if per_node == 2 {
                        removed[node * per_node + 1] = true;
                    }
                }
                Support::Pinned => removed[node * per_node] = true,
                Support::Free => {}
            }
        }
        let mut n = 0;
        let dof_of: Vec<Option<usize>> = removed
            .iter()
            .map(|&r| {
                if r {
                    None
                } else {
                    n += 1;
                    Some(n - 1)
                }
            })
            .collect();
        let h = props.length / elements as f64;
        let p = match family {
            Family::Hermite => 3,
            Family::String => 1,
        };
        let mut mass = SymBand::zeros(n, p);
        let mut stiffness = SymBand::zeros(n, p);
        let mut load = vec![0.0; n];
        let w = props.distributed_load;
        match family {
            Family::Hermite => {
                let me = element::hermite_mass(props.rho_a, h);
                let ke = element::hermite_bending(props.ei, h)
                    + element::hermite_tension(props.tension, h);
                let fe = element::hermite_uniform_load(w, h);
                for e in 0..elements {
                    let dofs: [Option<usize>; 4] = std::array::from_fn(|k| dof_of[2 * e + k]);
                    scatter(
                        &mut mass,
                        &mut stiffness,
                        &mut load,
                        &dofs,
                        &me,
                        &ke,
                        fe.as_slice(),
                    );
                }
            }
            Family::String => {
                let me = element::string_mass(props.rho_a, h);
                let ke = element::string_stiffness(props.tension, h);
                let fe = element::string_uniform_load(w, h);
                for e in 0..elements {
                    let dofs: [Option<usize>; 2] = [dof_of[e], dof_of[e + 1]];
                    scatter(
                        &mut mass,
                        &mut stiffness,
                        &mut load,
                        &dofs,
                        &me,
                        &ke,
                        fe.as_slice(),
                    );
                }
            }
        }
        BeamModel {
            family,
            elements,
            length: props.length,
            h,
            dof_of,
            n,
            mass,
            stiffness,
            load,
        }
    }

    /// Half-bandwidth of M and K.
    pub fn bandwidth(&self) -> usize {
        self.mass.bandwidth()
    }

    /// The element holding x and the local coordinate s ∈ [0, 1].
    pub fn locate(&self, x: f64) -> (usize, f64) {
        let xi = (x / self.h).clamp(0.0, self.elements as f64);
        let e = (xi.floor() as usize).min(self.elements - 1);
        (e, (xi - e as f64).clamp(0.0, 1.0))
    }

    /// r_b(x): beam displacement v(x) = r_b(x)ᵀ d (MODEL §4).
    pub fn point_vector(&self, x: f64) -> PointVector {
        self.shape_vector(x, false)
    }

    /// r_b'(x): beam slope v'(x) = r_b'(x)ᵀ d (for the convective part of a
    /// moving contact's gap rate, V·v'(x_m)).
    pub fn slope_vector(&self, x: f64) -> PointVector {
        self.shape_vector(x, true)
    }

    fn shape_vector(&self, x: f64, slope: bool) -> PointVector {
        let (e, s) = self.locate(x);
        let mut pv = PointVector::default();
        match self.family {
            Family::Hermite => {
                let n = if slope {
                    element::hermite_slope(s, self.h)
                } else {
                    element::hermite_shape(s, self.h)
                };
                for k in 0..4 {
                    if let Some(i) = self.dof_of[2 * e + k] {
                        pv.idx[k] = i;
                        pv.val[k] = n[k];
                    }
                }
            }
            Family::String => {
                let n = if slope {
                    [-1.0 / self.h, 1.0 / self.h]
                } else {
                    element::string_shape(s)
                };
                for k in 0..2 {
                    if let Some(i) = self.dof_of[e + k] {
                        pv.idx[k] = i;
                        pv.val[k] = n[k];
                    }
                }
            }
        }
        pv
    }
}

/// Add one element's matrices and load into the global band.
fn scatter<const D: usize>(
    mass: &mut SymBand,
    stiffness: &mut SymBand,
    load: &mut [f64],
    dofs: &[Option<usize>; D],
    me: &nalgebra::SMatrix<f64, D, D>,
    ke: &nalgebra::SMatrix<f64, D, D>,
    fe: &[f64],
) {
    for a in 0..D {
        let Some(i) = dofs[a] else { continue };
        load[i] += fe[a];
        for b in 0..D {
            let Some(j) = dofs[b] else { continue };
            mass.add_entry(i, j, me[(a, b)]);
            stiffness.add_entry(i, j, ke[(a, b)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::banded::BandedLdlt;

    fn props(ei: f64, left: Support, right: Support) -> BeamProps {
        BeamProps {
            length: 2.0,
            rho_a: 1.5,
            ei,
            ea: None,
            tension: 10.0,
            left,
            right,
            distributed_load: 0.0,
        }
    }

    #[test]
    fn supports_remove_the_right_dofs() {
        let b = BeamModel::new(&props(1.0, Support::Clamped, Support::Pinned), 4);
        assert_eq!(b.n, 10 - 3);
        let b = BeamModel::new(&props(1.0, Support::Free, Support::Free), 4);
        assert_eq!(b.n, 10);
        let s = BeamModel::new(&props(0.0, Support::Pinned, Support::Pinned), 4);
        assert_eq!(s.n, 3);
        assert_eq!(s.bandwidth(), 1);
    }

    #[test]
    fn global_mass_carries_the_beam_mass() {
        // a free–free beam: 1ᵀ M 1 over the translation dofs = ρA L
        let b = BeamModel::new(&props(1.0, Support::Free, Support::Free), 7);
        let ones: Vec<f64> = (0..b.n)
            .map(|i| if i % 2 == 0 { 1.0 } else { 0.0 })
            .collect();
        let mut y = vec![0.0; b.n];
        b.mass.mul_acc(&ones, 1.0, &mut y);
        let total: f64 = ones.iter().zip(&y).map(|(a, b)| a * b).sum();
        assert!((total - 3.0).abs() < 1e-12);
    }

    #[test]
    fn supported_stiffness_is_positive_definite() {
        for (l, r) in [
            (Support::Clamped, Support::Pinned),
            (Support::Clamped, Support::Free),
            (Support::Pinned, Support::Pinned),
        ] {
            let b = BeamModel::new(&props(1.0, l, r), 6);
            assert!(BandedLdlt::factor(&b.stiffness).is_ok(), "{l:?}-{r:?}");
        }
    }

    #[test]
    fn point_vector_interpolates_nodal_values() {
        let b = BeamModel::new(&props(1.0, Support::Pinned, Support::Pinned), 5);
        // v(x) = x(L − x) has nodal values and slopes; Hermite cubics hold it exactly
        let l = b.length;
        let mut d = vec![0.0; b.n];
        for node in 0..=5 {
            let x = node as f64 * b.h;
            if let Some(i) = b.dof_of[2 * node] {
                d[i] = x * (l - x);
            }
            if let Some(i) = b.dof_of[2 * node + 1] {
                d[i] = l - 2.0 * x;
            }
        }
        for k in 0..=40 {
            let x = k as f64 * l / 40.0;
            assert!((b.point_vector(x).dot(&d) - x * (l - x)).abs() < 1e-13);
        }
    }
}
