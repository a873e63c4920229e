//! The finite-element mesh along the span (MODEL §4, §9.2): node positions,
//! uniform or **graded** (elements shrinking geometrically toward chosen
//! points), and the lookup of the element holding a point.
//!
//! Grading. A segment of length S carrying m elements graded toward one of
//! its ends with size ratio R = h_max/h_min has element sizes
//! `h_i = h_min q^i` (i = 0 at the graded end), `q = R^{1/(m−1)}`, and
//! `h_min = S (q − 1)/(q^m − 1)`: neighbouring elements differ by the
//! constant factor q, so the mesh stays smooth (no element jumps in size,
//! which would cost the Hermite cubics accuracy), and refining N at fixed R
//! shrinks every element by the same factor, so the observed order in h is
//! the uniform mesh's. The gradings:
//!
//! * `supports`: two halves of the span, each graded toward its support
//!   (the carrier's arrival forces w = 0 over a bending length sqrt(EI/T)
//!   there, MODEL §9.2);
//! * `left`, `right`: the whole span graded toward one support;
//! * `point`: toward a position x_p, the two sides graded toward it with
//!   elements shared in proportion to their lengths (R holds on each side;
//!   their smallest elements differ by the rounding of that split).
//!
//! A uniform mesh keeps the arithmetic it always had (x/h lookup, one
//! element length), so its runs are bit-identical to the code before grading.

use crate::error::{Error, Result};
use crate::scene::Grading;

/// The mesh: N elements between N + 1 nodes on [0, L].
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Node positions x_0 = 0 < x_1 < … < x_N = L, m.
    pub nodes: Vec<f64>,
    /// Element length h = L/N when uniform, m.
    uniform: Option<f64>,
}

impl Mesh {
    /// N equal elements on [0, L].
    pub fn uniform(length: f64, elements: usize) -> Self {
        let h = length / elements as f64;
        let nodes = (0..=elements).map(|i| i as f64 * h).collect();
        Mesh {
            nodes,
            uniform: Some(h),
        }
    }

    /// N elements graded as `grading` says (module docs); uniform for
    /// [`Grading::Uniform`] or a ratio of 1.
    pub fn new(length: f64, elements: usize, grading: Grading) -> Result<Self> {
        let (ratio, sizes) = match grading {
            Grading::Uniform => return Ok(Mesh::uniform(length, elements)),
            Grading::Supports { ratio } => {
                check_elements(grading, elements)?;
                let left = elements.div_ceil(2);
                let mut h = graded_sizes(length / 2.0, left, ratio);
                let mut right = graded_sizes(length / 2.0, elements - left, ratio);
                right.reverse();
                h.extend(right);
                (ratio, h)
            }
            Grading::Left { ratio } => (ratio, graded_sizes(length, elements, ratio)),
            Grading::Right { ratio } => {
                let mut h = graded_sizes(length, elements, ratio);
                h.reverse();
                (ratio, h)
            }
            Grading::Point { ratio, at } => {
                check_elements(grading, elements)?;
                let left =
                    ((elements as f64 * at / length).round() as usize).clamp(1, elements - 1);
                let mut h = graded_sizes(at, left, ratio);
                h.reverse();
                h.extend(graded_sizes(length - at, elements - left, ratio));
                (ratio, h)
            }
        };
        if ratio == 1.0 {
            return Ok(Mesh::uniform(length, elements));
        }
        let mut nodes = Vec::with_capacity(elements + 1);
        let mut x = 0.0;
        nodes.push(x);
        for h in &sizes[..elements - 1] {
            x += h;
            nodes.push(x);
        }
        nodes.push(length);
        Ok(Mesh {
            nodes,
            uniform: None,
        })
    }

    /// Number of elements N.
    pub fn elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// True for equal elements.
    pub fn is_uniform(&self) -> bool {
        self.uniform.is_some()
    }

    /// Position of node i, m (node e starts element e).
    #[inline]
    pub fn node(&self, i: usize) -> f64 {
        self.nodes[i]
    }

    /// Length of element e, m.
    #[inline]
    pub fn element_length(&self, e: usize) -> f64 {
        match self.uniform {
            Some(h) => h,
            None => self.nodes[e + 1] - self.nodes[e],
        }
    }

    /// The shortest element, m.
    pub fn h_min(&self) -> f64 {
        match self.uniform {
            Some(h) => h,
            None => (0..self.elements())
                .map(|e| self.element_length(e))
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// The longest element, m.
    pub fn h_max(&self) -> f64 {
        match self.uniform {
            Some(h) => h,
            None => (0..self.elements())
                .map(|e| self.element_length(e))
                .fold(0.0, f64::max),
        }
    }

    /// The element holding x and the local coordinate s ∈ [0, 1]; x is
    /// clamped to the span. O(1) on a uniform mesh, O(log N) graded.
    #[inline]
    pub fn locate(&self, x: f64) -> (usize, f64) {
        let n = self.elements();
        match self.uniform {
            Some(h) => {
                let xi = (x / h).clamp(0.0, n as f64);
                let e = (xi.floor() as usize).min(n - 1);
                (e, (xi - e as f64).clamp(0.0, 1.0))
            }
            None => {
                let x = x.clamp(0.0, self.nodes[n]);
                // first node beyond x, less one: the element whose left node ≤ x
                let e = self.nodes.partition_point(|&xn| xn <= x).clamp(1, n) - 1;
                // a deliberate defect of the test build (`crate::defects`)
                let len = if e > 0 && crate::defects::on(crate::defects::Defect::LocatePrevious) {
                    self.nodes[e] - self.nodes[e - 1]
                } else {
                    self.nodes[e + 1] - self.nodes[e]
                };
                let s = (x - self.nodes[e]) / len;
                (e, s.clamp(0.0, 1.0))
            }
        }
    }
}

/// At least one element per graded segment ([`Grading::min_elements`]),
/// else an error naming `mesh.elements` (scene validation and [`Mesh::new`]).
pub(crate) fn check_elements(grading: Grading, elements: usize) -> Result<()> {
    let min = grading.min_elements();
    if elements < min {
        return Err(Error::invalid(
            "mesh.elements",
            elements,
            format!(
                "must be ≥ {min} with mesh.grading = \"{}\" (one element per graded segment)",
                grading.name()
            ),
        ));
    }
    Ok(())
}

/// Shortest element a graded mesh may have, as a fraction of L: the finest
/// mesh taut allows (10⁶ elements graded 1000 : 1) has h_min ≈ 7·10⁻⁹ L, so
/// a shorter element comes only from a `point` grading at the very end of
/// the span, where the element matrices (∝ h⁻³) lose their precision and
/// then overflow (`grading_at = 1e-300` gave a NaN pivot).
pub(crate) const MIN_ELEMENT_FRACTION: f64 = 1e-10;

/// The shortest element of `Mesh::new(length, elements, grading)`, m,
/// without building the mesh (O(1)).
pub(crate) fn shortest_element(length: f64, elements: usize, grading: Grading) -> f64 {
    // the first (smallest) size of graded_sizes(s, m, ratio)
    let first = |s: f64, m: usize, ratio: f64| {
        if m <= 1 || ratio == 1.0 {
            s / m.max(1) as f64
        } else {
            let q = ratio.powf(1.0 / (m - 1) as f64);
            s * (q - 1.0) / (q.powi(m as i32) - 1.0)
        }
    };
    match grading {
        Grading::Uniform => length / elements as f64,
        Grading::Supports { ratio } => {
            let left = elements.div_ceil(2);
            first(length / 2.0, left, ratio).min(first(length / 2.0, elements - left, ratio))
        }
        Grading::Left { ratio } | Grading::Right { ratio } => first(length, elements, ratio),
        Grading::Point { ratio, at } => {
            let left = ((elements as f64 * at / length).round() as usize).clamp(1, elements - 1);
            first(at, left, ratio).min(first(length - at, elements - left, ratio))
        }
    }
}

/// m element sizes on a segment of length `s`, graded toward its start
/// with h_max/h_min = ratio (module docs). One element takes the whole
/// segment.
fn graded_sizes(s: f64, m: usize, ratio: f64) -> Vec<f64> {
    if m == 1 || ratio == 1.0 {
        return vec![s / m as f64; m];
    }
    let q = ratio.powf(1.0 / (m - 1) as f64);
    let h_min = s * (q - 1.0) / (q.powi(m as i32) - 1.0);
    (0..m).map(|i| h_min * q.powi(i as i32)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Node positions are sums of element sizes: a few ulps of L.
    const POSITION_TOL: f64 = 1e-12;

    /// Relative excess of a `point` mesh's overall h_max/h_min over R: the
    /// element split between the sides is rounded to whole elements
    /// (measured 1.6 % for 40 elements, x_p = L/4).
    const POINT_SPLIT_TOL: f64 = 0.05;

    #[test]
    fn uniform_lookup_is_the_old_arithmetic() {
        let m = Mesh::uniform(10.0, 7);
        for k in 0..=100 {
            let x = k as f64 * 0.1;
            let h = 10.0 / 7.0;
            let xi = (x / h).clamp(0.0, 7.0);
            let e = (xi.floor() as usize).min(6);
            assert_eq!(m.locate(x), (e, (xi - e as f64).clamp(0.0, 1.0)));
        }
    }

    #[test]
    fn graded_meshes_span_the_beam_with_the_asked_ratio() {
        let l = 50.0;
        for g in [
            Grading::Supports { ratio: 8.0 },
            Grading::Left { ratio: 20.0 },
            Grading::Right { ratio: 3.0 },
            Grading::Point {
                ratio: 5.0,
                at: 12.5,
            },
        ] {
            let m = Mesh::new(l, 40, g).unwrap();
            assert_eq!(m.elements(), 40);
            assert!((m.nodes[40] - l).abs() < POSITION_TOL * l);
            assert!(m.nodes.windows(2).all(|w| w[1] > w[0]), "{g:?}");
            let r = m.h_max() / m.h_min();
            let want = match g {
                Grading::Supports { ratio }
                | Grading::Left { ratio }
                | Grading::Right { ratio }
                | Grading::Point { ratio, .. } => ratio,
                Grading::Uniform => 1.0,
            };
            // R holds on each graded side; a point's two sides have their
            // own h_min (lengths and element counts differ), so the overall
            // ratio is R up to the rounding of the element split
            let tol = match g {
                Grading::Point { .. } => POINT_SPLIT_TOL,
                _ => 1e-9,
            };
            assert!((r - want).abs() < tol * want, "{g:?}: {r}");
        }
        // grading toward the supports puts the smallest elements there
        let m = Mesh::new(l, 40, Grading::Supports { ratio: 8.0 }).unwrap();
        assert!(m.element_length(0) < m.element_length(20) / 7.0);
        assert!(m.element_length(39) < m.element_length(20) / 7.0);
        // toward a point: the node next to it sits close to it
        let m = Mesh::new(
            l,
            40,
            Grading::Point {
                ratio: 5.0,
                at: 12.5,
            },
        )
        .unwrap();
        assert!(m.nodes.iter().any(|&x| (x - 12.5).abs() < POSITION_TOL * l));
    }

    #[test]
    fn graded_lookup_finds_the_element() {
        let m = Mesh::new(3.0, 9, Grading::Left { ratio: 10.0 }).unwrap();
        for k in 0..=300 {
            let x = k as f64 * 0.01;
            let (e, s) = m.locate(x);
            let xr = m.nodes[e] + s * m.element_length(e);
            assert!((xr - x).abs() < POSITION_TOL, "{x}: {e} {s}");
        }
        assert_eq!(m.locate(-1.0), (0, 0.0));
        assert_eq!(m.locate(5.0), (8, 1.0));
    }

    #[test]
    fn ratio_one_is_uniform_and_too_few_elements_are_refused() {
        let m = Mesh::new(2.0, 4, Grading::Supports { ratio: 1.0 }).unwrap();
        assert!(m.is_uniform());
        let e = Mesh::new(2.0, 1, Grading::Supports { ratio: 4.0 }).unwrap_err();
        assert!(e.to_string().contains("mesh.elements"), "{e}");
    }
}
