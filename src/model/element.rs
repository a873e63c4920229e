//! Element matrices: Hermite beam elements with tension (MODEL §4) and C0
//! string elements (MODEL §6). Dof order (v_e, θ_e, v_{e+1}, θ_{e+1}).

use nalgebra::{Cholesky, DMatrix, SMatrix, SVector};

/// 4×4 element matrix of a Hermite beam element.
pub(crate) type Mat4 = SMatrix<f64, 4, 4>;
/// 2×2 element matrix of a linear string element.
pub(crate) type Mat2 = SMatrix<f64, 2, 2>;

/// Consistent mass M_e = ρA h/420 [...] (MODEL §4).
pub fn hermite_mass(rho_a: f64, h: f64) -> Mat4 {
    let h2 = h * h;
    // a deliberate defect of the test build (`crate::defects`)
    let m11 = if crate::defects::on(crate::defects::Defect::HermiteMass) {
        5.0
    } else {
        4.0
    };
    #[rustfmt::skip]
    let m = Mat4::new(
        156.0,      22.0 * h,   54.0,      -13.0 * h,
        22.0 * h,   m11 * h2,   13.0 * h,  -3.0 * h2,
        54.0,       13.0 * h,   156.0,     -22.0 * h,
        -13.0 * h,  -3.0 * h2,  -22.0 * h, 4.0 * h2,
    );
    m * (rho_a * h / 420.0)
}

/// Bending stiffness K_Be = EI/h³ [...] (MODEL §4).
pub fn hermite_bending(ei: f64, h: f64) -> Mat4 {
    let h2 = h * h;
    #[rustfmt::skip]
    let k = Mat4::new(
        12.0,      6.0 * h,   -12.0,     6.0 * h,
        6.0 * h,   4.0 * h2,  -6.0 * h,  2.0 * h2,
        -12.0,     -6.0 * h,  12.0,      -6.0 * h,
        6.0 * h,   2.0 * h2,  -6.0 * h,  4.0 * h2,
    );
    k * (ei / (h2 * h))
}

/// Tension (geometric) stiffness K_Te = T/(30h) [...] (MODEL §4).
pub fn hermite_tension(tension: f64, h: f64) -> Mat4 {
    let h2 = h * h;
    #[rustfmt::skip]
    let k = Mat4::new(
        36.0,      3.0 * h,   -36.0,     3.0 * h,
        3.0 * h,   4.0 * h2,  -3.0 * h,  -h2,
        -36.0,     -3.0 * h,  36.0,      -3.0 * h,
        3.0 * h,   -h2,       -3.0 * h,  4.0 * h2,
    );
    k * (tension / (30.0 * h))
}

/// Consistent load vector of a uniform load p (N/m) on a Hermite element.
pub(crate) fn hermite_uniform_load(p: f64, h: f64) -> SVector<f64, 4> {
    SVector::<f64, 4>::new(h / 2.0, h * h / 12.0, h / 2.0, -h * h / 12.0) * p
}

/// Hermite shape functions N1..N4 at local coordinate s ∈ [0, 1] (MODEL §4).
pub fn hermite_shape(s: f64, h: f64) -> [f64; 4] {
    let s2 = s * s;
    let s3 = s2 * s;
    [
        1.0 - 3.0 * s2 + 2.0 * s3,
        h * (s - 2.0 * s2 + s3),
        3.0 * s2 - 2.0 * s3,
        h * (s3 - s2),
    ]
}

/// x-derivatives dN1/dx..dN4/dx of the Hermite shape functions at s ∈ [0, 1].
pub fn hermite_slope(s: f64, h: f64) -> [f64; 4] {
    let s2 = s * s;
    [
        (-6.0 * s + 6.0 * s2) / h,
        1.0 - 4.0 * s + 3.0 * s2,
        (6.0 * s - 6.0 * s2) / h,
        3.0 * s2 - 2.0 * s,
    ]
}

/// String mass M_e = ρA h/6 [2 1; 1 2] (MODEL §6).
pub(crate) fn string_mass(rho_a: f64, h: f64) -> Mat2 {
    Mat2::new(2.0, 1.0, 1.0, 2.0) * (rho_a * h / 6.0)
}

/// String stiffness K_e = T/h [1 −1; −1 1] (MODEL §6).
pub(crate) fn string_stiffness(tension: f64, h: f64) -> Mat2 {
    Mat2::new(1.0, -1.0, -1.0, 1.0) * (tension / h)
}

/// Consistent load vector of a uniform load p (N/m) on a string element.
pub(crate) fn string_uniform_load(p: f64, h: f64) -> SVector<f64, 2> {
    SVector::<f64, 2>::new(h / 2.0, h / 2.0) * p
}

/// Linear shape functions at s ∈ [0, 1].
pub(crate) fn string_shape(s: f64) -> [f64; 2] {
    [1.0 - s, s]
}

/// The largest ω (rad/s) of one element's (K_e, M_e): Hermite with tension
/// (ρA kg/m, EI N·m², T N, length h m), or a string element when EI = 0.
/// For consistent masses its square bounds the assembled model's ω_max²
/// (Irons 1970; `model::spectrum`).
pub fn omega_max(rho_a: f64, ei: f64, tension: f64, h: f64) -> f64 {
    omega_max_attached(rho_a, ei, tension, h, &[])
}

/// [`omega_max`] of one element of length `h` carrying point attachments
/// (MODEL §10): each `(s, k_a, m_a)` adds `k_a n nᵀ` to K_e and `m_a n nᵀ`
/// to M_e, n the element's shape functions at local coordinate s ∈ [0, 1].
/// Splitting the assembled K and M into such element sums
/// keeps Irons' bound: the assembled ω_max² is at most the largest of
/// these element ω² (a spring raises it, a mass lowers it).
pub(crate) fn omega_max_attached(
    rho_a: f64,
    ei: f64,
    tension: f64,
    h: f64,
    attached: &[(f64, f64, f64)],
) -> f64 {
    let (mut k, mut m, d) = if ei == 0.0 {
        let k = string_stiffness(tension, h);
        let m = string_mass(rho_a, h);
        (
            DMatrix::from_column_slice(2, 2, k.as_slice()),
            DMatrix::from_column_slice(2, 2, m.as_slice()),
            2,
        )
    } else {
        let k = hermite_bending(ei, h) + hermite_tension(tension, h);
        let m = hermite_mass(rho_a, h);
        (
            DMatrix::from_column_slice(4, 4, k.as_slice()),
            DMatrix::from_column_slice(4, 4, m.as_slice()),
            4,
        )
    };
    for &(s, ka, ma) in attached {
        let n: Vec<f64> = if d == 2 {
            string_shape(s).to_vec()
        } else {
            hermite_shape(s, h).to_vec()
        };
        for a in 0..d {
            for b in 0..d {
                k[(a, b)] += ka * n[a] * n[b];
                m[(a, b)] += ma * n[a] * n[b];
            }
        }
    }
    largest_generalized(&k, &m).sqrt()
}

/// λ_max of K x = λ M x for a small SPD M: L⁻¹ K L⁻ᵀ with M = LLᵀ.
fn largest_generalized(k: &DMatrix<f64>, m: &DMatrix<f64>) -> f64 {
    let l = Cholesky::new(m.clone())
        .expect("an element mass matrix is positive definite")
        .l();
    let li = l
        .clone()
        .try_inverse()
        .expect("a Cholesky factor is invertible");
    let c = &li * k * li.transpose();
    let c = 0.5 * (&c + c.transpose());
    c.symmetric_eigenvalues()
        .iter()
        .copied()
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Round-off bound for entries of O(1)-scaled element matrices.
    const ROUNDOFF: f64 = 1e-12;
    const H: f64 = 0.37;

    fn rigid_translation() -> SVector<f64, 4> {
        SVector::<f64, 4>::new(1.0, 0.0, 1.0, 0.0)
    }
    /// v = x on the element: dofs (0, 1, h, 1).
    fn rigid_rotation() -> SVector<f64, 4> {
        SVector::<f64, 4>::new(0.0, 1.0, H, 1.0)
    }

    #[test]
    fn matrices_are_symmetric() {
        for m in [
            hermite_mass(1.3, H),
            hermite_bending(2.1, H),
            hermite_tension(5.0, H),
        ] {
            assert_relative_eq!(m, m.transpose(), epsilon = ROUNDOFF);
        }
        let s = string_mass(1.3, H);
        assert_relative_eq!(s, s.transpose(), epsilon = ROUNDOFF);
    }

    #[test]
    fn bending_has_the_two_rigid_body_modes() {
        let k = hermite_bending(2.1, H);
        assert!((k * rigid_translation()).norm() < ROUNDOFF * k.norm());
        assert!((k * rigid_rotation()).norm() < ROUNDOFF * k.norm());
    }

    #[test]
    fn tension_stiffness_resists_rotation_not_translation() {
        let k = hermite_tension(5.0, H);
        assert!((k * rigid_translation()).norm() < ROUNDOFF * k.norm());
        // energy of v = x: ½ T ∫ v'² = ½ T h
        let r = rigid_rotation();
        assert_relative_eq!(
            0.5 * (r.transpose() * k * r)[0],
            0.5 * 5.0 * H,
            max_relative = 1e-13
        );
    }

    #[test]
    fn mass_is_positive_definite_and_carries_the_element_mass() {
        let m = hermite_mass(1.3, H);
        assert!(m.cholesky().is_some());
        let t = rigid_translation();
        assert_relative_eq!((t.transpose() * m * t)[0], 1.3 * H, max_relative = 1e-13);
        assert!(string_mass(1.3, H).cholesky().is_some());
    }

    #[test]
    fn shape_functions_partition_unity() {
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let n = hermite_shape(s, H);
            assert_relative_eq!(n[0] + n[2], 1.0, epsilon = ROUNDOFF);
            let l = string_shape(s);
            assert_relative_eq!(l[0] + l[1], 1.0, epsilon = ROUNDOFF);
        }
    }

    #[test]
    fn shape_functions_reproduce_a_cubic_exactly() {
        let p = |x: f64| 0.3 - 1.2 * x + 0.7 * x * x + 2.5 * x * x * x;
        let dp = |x: f64| -1.2 + 1.4 * x + 7.5 * x * x;
        let (xa, xb) = (0.0, H);
        let dofs = [p(xa), dp(xa), p(xb), dp(xb)];
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            let n = hermite_shape(s, H);
            let v: f64 = n.iter().zip(dofs).map(|(a, b)| a * b).sum();
            assert_relative_eq!(v, p(xa + s * H), epsilon = ROUNDOFF);
        }
    }

    #[test]
    fn slopes_are_the_derivative_of_a_reproduced_cubic() {
        let p = |x: f64| 0.3 - 1.2 * x + 0.7 * x * x + 2.5 * x * x * x;
        let dp = |x: f64| -1.2 + 1.4 * x + 7.5 * x * x;
        let dofs = [p(0.0), dp(0.0), p(H), dp(H)];
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            let n = hermite_slope(s, H);
            let v: f64 = n.iter().zip(dofs).map(|(a, b)| a * b).sum();
            assert_relative_eq!(v, dp(s * H), epsilon = 1e-11);
        }
    }

    #[test]
    fn load_vector_integrates_the_shape_functions() {
        // ∫ N_i ds·h by 5-point Gauss–Legendre (exact for cubics)
        let g = [
            (0.0, 128.0 / 225.0),
            (
                -(5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0,
                (322.0 + 13.0 * 70f64.sqrt()) / 900.0,
            ),
            (
                (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0,
                (322.0 + 13.0 * 70f64.sqrt()) / 900.0,
            ),
            (
                -(5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0,
                (322.0 - 13.0 * 70f64.sqrt()) / 900.0,
            ),
            (
                (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0,
                (322.0 - 13.0 * 70f64.sqrt()) / 900.0,
            ),
        ];
        let f = hermite_uniform_load(2.0, H);
        for i in 0..4 {
            let q: f64 = g
                .iter()
                .map(|&(x, w)| w * 0.5 * hermite_shape(0.5 * (x + 1.0), H)[i])
                .sum();
            assert_relative_eq!(f[i], 2.0 * H * q, max_relative = 1e-12);
        }
    }
}
