//! Complementarity contact (MODEL §6): per step the LCP
//! λ ≥ 0, g_free + Wλ ≥ 0, λ·(g_free + Wλ) = 0 as the convex QP
//! `min ½ λᵀWλ + g_freeᵀλ  s.t.  λ ≥ 0`, solved by clarabel (interior point).
//!
//! * Scaling: the QP is solved in μ = λ·w0/g0 (w0 = max W_cc, g0 = max |g_free|),
//!   so P = W/w0 and q = g_free/g0 are O(1) and clarabel's tolerances mean the
//!   same thing at every step and in every unit system.
//! * W is symmetric for one contact and for the `alpha` placement (r_g = r_f).
//!   With several contacts and the `end` placement, r_g (at t_{n+1}) and r_f
//!   (at t_{n+1−α_f}) differ by the carriers' travel in α_fΔt and W is not
//!   exactly symmetric; a QP needs a symmetric P, so its symmetric part is
//!   used. The coupling terms themselves are tiny for carriers metres apart
//!   (A⁻¹ decays over a few c·Δt; measured W₁₂/W₁₁ ≈ 1e-125 at 10 m), so this
//!   changes nothing observable there; the late two-carrier differences are
//!   the dynamics amplifying round-off (`docs/formulations.md`).
//! * An interior-point λ is never exactly 0. A contact counts as open when its
//!   force is smaller than the force that would close its gap, λ_c < g_c/W_cc;
//!   its λ is then set to 0 (a change within the solver tolerance).
//! * A failed solve stops the run with a typed [`ContactFailure`]; the
//!   integrator's system saves the problem as a
//!   [`ContactProblem`](super::ContactProblem) that `taut replay` solves again.

use super::{ContactFailure, ContactLaw};
use crate::scene::ComplementaritySpec;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// The clarabel-backed law.
pub(crate) struct Complementarity {
    settings: DefaultSettings<f64>,
    bilateral: bool,
}

impl Complementarity {
    pub(crate) fn new(spec: &ComplementaritySpec, bilateral: bool) -> Self {
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .tol_gap_abs(spec.tol_gap_abs)
            .tol_gap_rel(spec.tol_gap_rel)
            .tol_feas(spec.tol_feas)
            .max_iter(spec.max_iter)
            .build()
            .expect("validated settings");
        Complementarity {
            settings,
            bilateral,
        }
    }
}

impl ContactLaw for Complementarity {
    fn solve(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        self.solve_qp(g_free, w, lambda, active)
    }
}

impl Complementarity {
    /// Solve one step's QP (see the module docs).
    pub(crate) fn solve_qp(
        &mut self,
        g_free: &[f64],
        w: &[f64],
        lambda: &mut [f64],
        active: &mut [bool],
    ) -> Result<(), ContactFailure> {
        let n = g_free.len();
        if n == 0 {
            return Ok(());
        }
        let g0 = g_free.iter().fold(0.0f64, |m, g| m.max(g.abs()));
        if g0 == 0.0 {
            lambda.fill(0.0);
            active.fill(false);
            return Ok(());
        }
        let w0 = (0..n).fold(0.0f64, |m, c| m.max(w[c * n + c]));
        if !(w0 > 0.0 && w0.is_finite()) {
            let contact = (0..n)
                .find(|&c| !(w[c * n + c] > 0.0 && w[c * n + c].is_finite()))
                .unwrap_or(0);
            return Err(ContactFailure::NotPositive {
                contact,
                w: w[contact * n + contact],
            });
        }
        // P: upper triangle of the symmetric part of W/w0, column by column
        let mut colptr = Vec::with_capacity(n + 1);
        let mut rowval = Vec::with_capacity(n * (n + 1) / 2);
        let mut nzval = Vec::with_capacity(n * (n + 1) / 2);
        colptr.push(0);
        for j in 0..n {
            for i in 0..=j {
                rowval.push(i);
                nzval.push(0.5 * (w[i * n + j] + w[j * n + i]) / w0);
            }
            colptr.push(rowval.len());
        }
        let p = CscMatrix::new(n, n, colptr, rowval, nzval);
        let q: Vec<f64> = g_free.iter().map(|g| g / g0).collect();
        let (a, b, cones) = if self.bilateral {
            (CscMatrix::zeros((0, n)), vec![], vec![])
        } else {
            // −μ + s = 0, s ≥ 0  ⇔  μ ≥ 0
            let a = CscMatrix::new(n, n, (0..=n).collect(), (0..n).collect(), vec![-1.0; n]);
            (a, vec![0.0; n], vec![SupportedConeT::NonnegativeConeT(n)])
        };
        let mut solver = match DefaultSolver::new(&p, &q, &a, &b, &cones, self.settings.clone()) {
            Ok(s) => s,
            Err(e) => return Err(ContactFailure::Setup(e.to_string())),
        };
        solver.solve();
        let sol = &solver.solution;
        if sol.status != SolverStatus::Solved {
            return Err(ContactFailure::Solver {
                status: format!("{:?}", sol.status),
                iterations: sol.iterations,
                r_prim: sol.r_prim,
                r_dual: sol.r_dual,
            });
        }
        let scale = g0 / w0;
        for c in 0..n {
            lambda[c] = sol.x[c] * scale;
            if !lambda[c].is_finite() {
                return Err(ContactFailure::NotFinite {
                    contact: c,
                    lambda: lambda[c],
                    w: w[c * n + c],
                });
            }
        }
        if self.bilateral {
            active.fill(true);
            return Ok(());
        }
        for c in 0..n {
            let gap: f64 = g_free[c] + (0..n).map(|j| w[c * n + j] * lambda[j]).sum::<f64>();
            let closing_force = gap.max(0.0) / w[c * n + c];
            active[c] = lambda[c] > closing_force;
        }
        for c in 0..n {
            if !active[c] {
                lambda[c] = 0.0;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Lagrange;

    /// Agreement with the exact active set: the QP tolerance (1e-12, relative
    /// in the scaled variables) with a margin for the interior-point endgame.
    const QP_AGREEMENT: f64 = 1e-8;

    fn both(g: &[f64], w: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = g.len();
        let mut qp = Complementarity::new(&ComplementaritySpec::default(), false);
        let mut lg = Lagrange::new(false, n);
        let (mut l1, mut a1) = (vec![0.0; n], vec![false; n]);
        let (mut l2, mut a2) = (vec![0.0; n], vec![false; n]);
        qp.solve_qp(g, w, &mut l1, &mut a1).unwrap();
        lg.solve(g, w, &mut l2, &mut a2).unwrap();
        assert_eq!(a1, a2, "active sets differ for g = {g:?}");
        (l1, l2)
    }

    #[test]
    fn agrees_with_lagrange_on_one_contact() {
        for g in [-3e-7, -1e-9, 2e-7] {
            let (l1, l2) = both(&[g], &[5e-9]);
            assert!(
                (l1[0] - l2[0]).abs() <= QP_AGREEMENT * l2[0].abs().max(1.0),
                "{l1:?} {l2:?}"
            );
        }
    }

    #[test]
    fn agrees_with_lagrange_on_two_coupled_contacts() {
        let w = [2.0e-9, 1.5e-9, 1.5e-9, 2.0e-9];
        for g in [[-1e-7, -0.5e-7], [-1e-7, -1e-7], [-1e-7, 3e-7]] {
            let (l1, l2) = both(&g, &w);
            for c in 0..2 {
                assert!(
                    (l1[c] - l2[c]).abs() <= QP_AGREEMENT * l2[c].abs().max(1.0),
                    "{l1:?} {l2:?}"
                );
            }
        }
    }

    #[test]
    fn an_iteration_limit_of_one_fails_with_the_solver_status() {
        let spec = ComplementaritySpec {
            max_iter: 1,
            ..ComplementaritySpec::default()
        };
        let mut qp = Complementarity::new(&spec, false);
        let (mut l, mut a) = ([0.0], [false]);
        let err = qp.solve_qp(&[-3e-7], &[5e-9], &mut l, &mut a).unwrap_err();
        assert!(
            matches!(&err, ContactFailure::Solver { status, .. } if status == "MaxIterations"),
            "{err}"
        );
    }
}
