//! Penalty contact (MODEL §6): λ = κ·max(0, −g) with g = g_free + Wλ, solved
//! exactly per step. With several contacts that is the complementarity
//! problem λ ≥ 0, g_free + (W + K⁻¹)λ ≥ 0, λ·(…) = 0, K = diag(κ): the
//! Lagrange active set on the Delassus matrix stiffened by 1/κ on its diagonal.
//! For one contact λ = κ max(0, −g_free)/(1 + κW), MODEL §6.
//! The penetration is then −g = λ/κ.

use super::{ContactFailure, ContactLaw, Lagrange};

/// How κ is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kappa {
    /// κ in N/m.
    Absolute(f64),
    /// κ = ρ / W_cc (dimensionless ρ): the step's contact stiffness times ρ.
    Relative(f64),
}

/// Penalty law: a Lagrange law on the modified Delassus matrix.
pub(crate) struct Penalty {
    kappa: Kappa,
    /// The rows that get the penalty 1/κ: the first `penalized` (the
    /// contacts); rows after them are compliant already (droppers, whose
    /// W carries 1/k_d: their own penalty spring).
    penalized: usize,
    inner: Lagrange,
    w_mod: Vec<f64>,
}

impl Penalty {
    /// A penalty law for `nc` contacts; `bilateral` makes it a two-sided spring.
    pub(crate) fn new(kappa: Kappa, bilateral: bool, nc: usize) -> Self {
        Penalty {
            kappa,
            penalized: nc,
            inner: Lagrange::new(bilateral, nc),
            w_mod: vec![0.0; nc * nc],
        }
    }
}

impl Penalty {
    /// Penalize the first `nc` rows only (the contacts; the struct's docs).
    pub(crate) fn penalize_first(mut self, nc: usize) -> Self {
        self.penalized = nc;
        self
    }
}

impl ContactLaw for Penalty {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        let nc = g_free.len();
        let wm = &mut self.w_mod[..nc * nc];
        wm.copy_from_slice(&w[..nc * nc]);
        for c in 0..nc.min(self.penalized) {
            let kappa = match self.kappa {
                Kappa::Absolute(k) => k,
                // a deliberate defect of the test build (`crate::defects`)
                Kappa::Relative(r)
                    if crate::defects::on(crate::defects::Defect::PenaltyUnscaled) =>
                {
                    r
                }
                Kappa::Relative(r) => r / w[c * nc + c],
            };
            wm[c * nc + c] += 1.0 / kappa;
        }
        self.inner
            .solve(g_free, &self.w_mod[..nc * nc], lambda, active)
    }

    /// At t = 0 the gap is zero, so the penalty force κ·max(0, −g) is zero:
    /// the contacts touch without force until the first step penetrates.
    /// (The Lagrange acceleration-level rule would add 1/κ, in m/N, to a
    /// matrix in 1/kg.)
    fn initial(
        &mut self,
        _g_free: &[f64],
        _w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        lambda.fill(0.0);
        active.fill(true);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_contact_matches_the_closed_form() {
        let (g, w, k) = (-3e-4, 2e-6, 5e5);
        let mut law = Penalty::new(Kappa::Absolute(k), false, 1);
        let (mut l, mut a) = ([0.0], [false]);
        law.solve(&[g], &[w], &mut l, &mut a).unwrap();
        let exact = k * (-g) / (1.0 + k * w);
        assert!((l[0] - exact).abs() <= 1e-12 * exact);
        // the penetration is λ/κ
        let gap = g + w * l[0];
        assert!((gap + l[0] / k).abs() <= 1e-12 * gap.abs());
    }

    #[test]
    fn relative_stiffness_scales_the_lagrange_force() {
        let (g, w, rho) = (-3e-4, 2e-6, 99.0);
        let mut law = Penalty::new(Kappa::Relative(rho), false, 1);
        let (mut l, mut a) = ([0.0], [false]);
        law.solve(&[g], &[w], &mut l, &mut a).unwrap();
        let lagrange = -g / w;
        assert!((l[0] / lagrange - rho / (1.0 + rho)).abs() < 1e-13);
    }

    /// Two coupled contacts, both penetrating: λ solves (W + diag(1/κ_c))λ
    /// = −g_free (MODEL §6), each κ_c = ρ/W_cc from its own diagonal — the
    /// single-contact tests cannot tell a row's index or its diagonal apart
    /// (cargo mutants: `c * nc + c` → `c * nc − c`, `nc * nc` → `nc / nc`
    /// survived them).
    #[test]
    fn two_coupled_contacts_solve_the_stiffened_system() {
        let (g, w, rho) = ([-3e-4, -2e-4], [2e-6, 5e-7, 5e-7, 4e-6], 9.0);
        let mut law = Penalty::new(Kappa::Relative(rho), false, 2);
        let (mut l, mut a) = ([0.0; 2], [false; 2]);
        law.solve(&g, &w, &mut l, &mut a).unwrap();
        assert_eq!(a, [true, true]);
        // W + diag(W_cc/ρ), solved by Cramer's rule
        let m = [
            w[0] * (1.0 + 1.0 / rho),
            w[1],
            w[2],
            w[3] * (1.0 + 1.0 / rho),
        ];
        let det = m[0] * m[3] - m[1] * m[2];
        let exact = [
            (-g[0] * m[3] + g[1] * m[1]) / det,
            (-g[1] * m[0] + g[0] * m[2]) / det,
        ];
        for c in 0..2 {
            assert!(l[c] > 0.0);
            assert!(
                (l[c] - exact[c]).abs() <= 1e-12 * exact[c],
                "{l:?} {exact:?}"
            );
        }
    }

    /// `penalize_first`: rows after the first `nc` (droppers, compliant
    /// already) keep their W; an absolute κ stiffens the contact's alone.
    #[test]
    fn only_the_first_rows_are_penalized() {
        let (g, w, k) = ([-3e-4, -2e-4], [2e-6, 0.0, 0.0, 4e-6], 1e6);
        let mut law = Penalty::new(Kappa::Absolute(k), true, 2).penalize_first(1);
        let (mut l, mut a) = ([0.0; 2], [false; 2]);
        law.solve(&g, &w, &mut l, &mut a).unwrap();
        assert!((l[0] - (-g[0]) / (w[0] + 1.0 / k)).abs() <= 1e-12 * l[0]);
        assert!((l[1] - (-g[1]) / w[3]).abs() <= 1e-12 * l[1]);
    }

    /// At t = 0 the penalty carries no force and every contact is closed.
    #[test]
    fn the_initial_force_is_zero() {
        let mut law = Penalty::new(Kappa::Absolute(1e6), false, 2);
        let (mut l, mut a) = ([5.0; 2], [false; 2]);
        law.initial(&[-1e-4, 1e-4], &[1e-6, 0.0, 0.0, 1e-6], &mut l, &mut a)
            .unwrap();
        assert_eq!((l, a), ([0.0; 2], [true; 2]));
    }
}
