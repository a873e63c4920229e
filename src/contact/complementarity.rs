//! Complementarity contact (MODEL §6): per step the LCP
//! λ ≥ 0, g_free + Wλ ≥ 0, λ·(g_free + Wλ) = 0, which is the convex QP
//! `min ½ λᵀWλ + g_freeᵀλ  s.t.  λ ≥ 0`. Two solvers answer it
//! (`[contact.complementarity] solver`):
//!
//! * `direct` (default): an exact principal-pivoting solve of the LCP
//!   (Murty's least-index method, `Direct`) on scratch preallocated for the
//!   run's contacts; it allocates nothing per step;
//! * `clarabel`: the QP by clarabel's interior-point method, the
//!   general-QP-solver reference that MODEL §6 names, one solver per problem
//!   size updated in place (`Clarabel`); the cross-check of `direct` (tests
//!   below and `tests/formulations.rs`), reachable from every scene and from
//!   `taut replay`. Its `solve()` still allocates a little each call, which
//!   is why `direct` is the default.
//!
//! Both solve in μ = λ·w0/g0 (w0 = max W_cc, g0 = max |g_free|), so the
//! tolerances mean the same thing at every step and in every unit system;
//! both take W's symmetric part (W is not exactly symmetric with several
//! contacts and the `end` placement; its coupling terms are tiny for carriers
//! metres apart); both set λ_c = 0 when λ_c < g_c/W_cc (an interior-point λ
//! is never exactly 0). A failed solve stops the run with a typed
//! [`ContactFailure`]; the problem is saved as a
//! [`ContactProblem`](super::ContactProblem) that `taut replay` solves again.

use super::dense::solve_in_place;
use super::{ContactFailure, ContactLaw};
use crate::scene::{ComplementaritySolver, ComplementaritySpec};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// Up to this many contacts the clarabel path builds a solver for every
/// problem size 1..=nc up front; above it (only `taut replay` of a large
/// saved problem), a size's solver is built when first asked for.
const PREBUILT_SIZES: usize = 8;

/// In the direct solve, an open contact enters the closed set when its
/// scaled gap w_i = (g_free + Wλ)_i/g0 is below −this: the round-off floor
/// of the scaled problem, as the Lagrange law's `GAP_ROUNDOFF` and the QP's
/// default tolerances (1e-12).
pub(crate) const PIVOT_GAP_TOLERANCE: f64 = 1e-12;

/// Pivot limit of the direct solve for n contacts: Murty's method visits
/// each of the 2ⁿ sets at most once on a P-matrix.
fn max_pivots(n: usize) -> usize {
    (1usize << n.min(20)) + 16
}

/// One clarabel solver for QPs of one size n, and its value buffers.
struct Qp {
    /// The solver, or why clarabel refused to build it (reported as
    /// [`ContactFailure::Setup`] when the law is asked to solve).
    solver: Result<DefaultSolver<f64>, String>,
    /// Values of P (upper triangle of sym(W)/w0, column by column).
    p_values: Vec<f64>,
    /// q = g_free/g0.
    q: Vec<f64>,
}

impl Qp {
    /// The solver for the pattern of size `n` (n ≥ 1), placeholder values
    /// P = I, q = 0.
    fn new(settings: &DefaultSettings<f64>, bilateral: bool, n: usize) -> Self {
        let mut colptr = Vec::with_capacity(n + 1);
        let mut rowval = Vec::with_capacity(n * (n + 1) / 2);
        let mut p_values = Vec::with_capacity(n * (n + 1) / 2);
        colptr.push(0);
        for j in 0..n {
            for i in 0..=j {
                rowval.push(i);
                p_values.push(if i == j { 1.0 } else { 0.0 });
            }
            colptr.push(rowval.len());
        }
        let p = CscMatrix::new(n, n, colptr, rowval, p_values.clone());
        let q = vec![0.0; n];
        let (a, b, cones) = if bilateral {
            (CscMatrix::zeros((0, n)), vec![], vec![])
        } else {
            // −μ + s = 0, s ≥ 0  ⇔  μ ≥ 0
            let a = CscMatrix::new(n, n, (0..=n).collect(), (0..n).collect(), vec![-1.0; n]);
            (a, vec![0.0; n], vec![SupportedConeT::NonnegativeConeT(n)])
        };
        let solver =
            DefaultSolver::new(&p, &q, &a, &b, &cones, settings.clone()).map_err(|e| e.to_string());
        Qp {
            solver,
            p_values,
            q,
        }
    }
}

/// The clarabel path: one solver per problem size, built once.
///
/// The number of contacts nc is fixed for a run, so the QP's sparsity pattern
/// is too: P is the full upper triangle of an n×n matrix, A = −I (or 0×n when
/// bilateral), b = 0. [`Complementarity::new`] builds one clarabel
/// [`DefaultSolver`] per problem size (placeholder values P = I, q = 0; every
/// size 1..=nc up to [`PREBUILT_SIZES`] contacts, because the velocity-level
/// `moreau_jean` step hands the law only the contacts of its index set), and
/// each step overwrites P's values and q through clarabel 0.11's
/// data-updating API (`update_P`, `update_q`) and calls `solve()` again.
/// What this relies on, read in clarabel 0.11.1's source
/// (`solver/implementations/default/data_updating.rs`, `solver/core/solver.rs`,
/// `timers/timers.rs`):
///
/// * `update_P`/`update_q` `copy_from_slice` into the solver's own CSC values
///   and vectors and rewrite the KKT matrix's values through its precomputed
///   index maps; the symbolic LDLᵀ factorization is kept. They allocate
///   nothing (checked with a counting allocator). They are refused when the
///   presolver changed the problem or structural zeros were dropped:
///   `presolve_enable = false` and `input_sparse_dropzeros = false` keep the
///   pattern, so an off-diagonal W entry that is exactly 0 is still a slot.
/// * `solve()` starts every call from clarabel's default (cold) starting
///   point: no warm start, so a step's answer does not depend on the previous
///   step's, and `taut replay` (a fresh law, one solve) reproduces a step.
/// * An update re-applies the equilibration computed when the solver was
///   built, i.e. fitted to the placeholder problem, so equilibration is
///   switched off (`equilibrate_enable = false`) and the scaling above does
///   its job. For one contact clarabel's Ruiz equilibration of
///   (P = 1, q = ±1, A = −1) is the identity anyway, so single-contact
///   answers are those of a solver built per step.
/// * **`solve()` itself still allocates**: one 404-byte hash table per call.
///   `Info::reset` clears the "solve" timer's sub-timers, so the
///   "IP iteration" timer is re-created empty and its own sub-timer map
///   ("scale cones", "kkt update", "kkt solve") allocates again on the next
///   solve (`clarabel::timers`, always compiled in; no setting or cargo
///   feature of 0.11.1 turns it off). That is why `direct` is the default:
///   the per-step path of the default allocates nothing, and the clarabel
///   path went from a full solver build per step (CSC matrices, KKT system,
///   symbolic factorization, workspace) to that one small allocation.
struct Clarabel {
    settings: DefaultSettings<f64>,
    /// `qps[n - 1]`: the QP of n contacts, once built.
    qps: Vec<Option<Qp>>,
}

impl Clarabel {
    fn new(spec: &ComplementaritySpec, bilateral: bool, nc: usize) -> Self {
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .presolve_enable(false)
            .input_sparse_dropzeros(false)
            .equilibrate_enable(false)
            .tol_gap_abs(spec.tol_gap_abs)
            .tol_gap_rel(spec.tol_gap_rel)
            .tol_feas(spec.tol_feas)
            .max_iter(spec.max_iter)
            .build()
            .expect("validated settings");
        let qps = (1..=nc)
            .map(|n| (nc <= PREBUILT_SIZES || n == nc).then(|| Qp::new(&settings, bilateral, n)))
            .collect();
        Clarabel { settings, qps }
    }

    /// μ from the scaled problem (m = sym(W)/w0 row-major, q = g_free/g0).
    fn solve(
        &mut self,
        bilateral: bool,
        m: &[f64],
        q: &[f64],
        mu: &mut [f64],
    ) -> Result<(), ContactFailure> {
        let n = q.len();
        if self.qps.len() < n {
            self.qps.resize_with(n, || None);
        }
        let settings = &self.settings;
        let qp = self.qps[n - 1].get_or_insert_with(|| Qp::new(settings, bilateral, n));
        let solver = match &mut qp.solver {
            Ok(s) => s,
            Err(e) => return Err(ContactFailure::Setup(e.clone())),
        };
        let mut k = 0;
        for j in 0..n {
            for i in 0..=j {
                qp.p_values[k] = m[i * n + j];
                k += 1;
            }
        }
        qp.q.copy_from_slice(q);
        let updated = solver
            .update_P(&qp.p_values)
            .and_then(|()| solver.update_q(&qp.q));
        if let Err(e) = updated {
            return Err(ContactFailure::Setup(e.to_string()));
        }
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
        mu.copy_from_slice(&sol.x[..n]);
        Ok(())
    }
}

/// The direct path's scratch, sized for nc contacts.
///
/// For symmetric positive definite M (a P-matrix) the LCP has exactly one
/// solution, and Murty's least-index principal pivoting method reaches it in
/// finitely many pivots from any start. It keeps a set α of closed contacts
/// (start: empty), solves M_αα μ_α = −q_α (Gaussian elimination with partial
/// pivoting, `super::dense`), forms w = q + Mμ, and flips the smallest index
/// that violates the conditions: i ∈ α with μ_i < 0 leaves, i ∉ α with
/// w_i < −[`PIVOT_GAP_TOLERANCE`] enters. No violation: μ is the answer, exact
/// to round-off. Failures: a singular M_αα is [`ContactFailure::Singular`];
/// more than [`max_pivots`] pivots (only a W that is not a P-matrix, e.g. a
/// broken Delassus matrix, can cycle) is [`ContactFailure::Cycling`].
/// Bilateral contact is the single solve M μ = −q. nc is 1 or 2 in the
/// bundled scenes and at most a handful in any scene, so the O(nc³) solves
/// cost less than a clarabel iteration.
struct Direct {
    /// M_αα, overwritten by the elimination.
    a: Vec<f64>,
    /// −q_α, then μ_α.
    b: Vec<f64>,
    /// The closed set α, in index order.
    set: Vec<usize>,
    /// Membership of α.
    closed: Vec<bool>,
}

impl Direct {
    fn new(nc: usize) -> Self {
        Direct {
            a: vec![0.0; nc * nc],
            b: vec![0.0; nc],
            set: Vec::with_capacity(nc),
            closed: vec![false; nc],
        }
    }

    /// μ for the scaled LCP (m row-major, symmetric positive definite).
    fn solve(
        &mut self,
        bilateral: bool,
        m: &[f64],
        q: &[f64],
        mu: &mut [f64],
    ) -> Result<(), ContactFailure> {
        let n = q.len();
        if self.closed.len() < n {
            // a larger problem than the run's (not in the step loop)
            *self = Direct::new(n);
        }
        let closed = &mut self.closed[..n];
        closed.fill(bilateral);
        let limit = if bilateral { 1 } else { max_pivots(n) };
        for _ in 0..limit {
            self.set.clear();
            self.set.extend((0..n).filter(|&i| closed[i]));
            let na = self.set.len();
            for (r, &i) in self.set.iter().enumerate() {
                for (c, &j) in self.set.iter().enumerate() {
                    self.a[r * na + c] = m[i * n + j];
                }
                self.b[r] = -q[i];
            }
            if !solve_in_place(na, &mut self.a[..na * na], &mut self.b[..na]) {
                return Err(ContactFailure::Singular);
            }
            mu.fill(0.0);
            for (r, &i) in self.set.iter().enumerate() {
                mu[i] = self.b[r];
            }
            if bilateral {
                return Ok(());
            }
            // the least index that violates the conditions
            let violating = (0..n).find(|&i| {
                if closed[i] {
                    mu[i] < 0.0
                } else {
                    let w: f64 = q[i] + (0..n).map(|j| m[i * n + j] * mu[j]).sum::<f64>();
                    w < -PIVOT_GAP_TOLERANCE
                }
            });
            match violating {
                None => return Ok(()),
                Some(i) => closed[i] = !closed[i],
            }
        }
        Err(ContactFailure::Cycling { passes: limit })
    }
}

enum Backend {
    Direct(Direct),
    Clarabel(Clarabel),
}

/// The complementarity law.
pub(crate) struct Complementarity {
    backend: Backend,
    bilateral: bool,
    /// sym(W)/w0, row-major.
    m: Vec<f64>,
    /// g_free/g0.
    q: Vec<f64>,
    /// The scaled answer μ.
    mu: Vec<f64>,
}

impl Complementarity {
    /// The law for `nc` contacts: solvers and scratch are built here, so
    /// that the steps do not rebuild them (see `Clarabel`).
    pub(crate) fn new(spec: &ComplementaritySpec, bilateral: bool, nc: usize) -> Self {
        let backend = match spec.solver {
            ComplementaritySolver::Direct => Backend::Direct(Direct::new(nc)),
            ComplementaritySolver::Clarabel => {
                Backend::Clarabel(Clarabel::new(spec, bilateral, nc))
            }
        };
        Complementarity {
            backend,
            bilateral,
            m: vec![0.0; nc * nc],
            q: vec![0.0; nc],
            mu: vec![0.0; nc],
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
        self.solve_lcp(g_free, w, lambda, active)
    }
}

impl Complementarity {
    /// Solve one step's LCP (see the module docs).
    pub(crate) fn solve_lcp(
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
        if self.q.len() < n {
            // a larger problem than the run's (not in the step loop)
            self.m.resize(n * n, 0.0);
            self.q.resize(n, 0.0);
            self.mu.resize(n, 0.0);
        }
        let (m, q, mu) = (&mut self.m[..n * n], &mut self.q[..n], &mut self.mu[..n]);
        for i in 0..n {
            for j in 0..n {
                m[i * n + j] = 0.5 * (w[i * n + j] + w[j * n + i]) / w0;
            }
            q[i] = g_free[i] / g0;
        }
        match &mut self.backend {
            Backend::Direct(d) => d.solve(self.bilateral, m, q, mu)?,
            Backend::Clarabel(c) => c.solve(self.bilateral, m, q, mu)?,
        }
        let scale = g0 / w0;
        for c in 0..n {
            lambda[c] = mu[c] * scale;
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

    fn spec(solver: ComplementaritySolver) -> ComplementaritySpec {
        ComplementaritySpec {
            solver,
            ..ComplementaritySpec::default()
        }
    }

    fn solve(solver: ComplementaritySolver, bilateral: bool, g: &[f64], w: &[f64]) -> Vec<f64> {
        let n = g.len();
        let mut law = Complementarity::new(&spec(solver), bilateral, n);
        let (mut l, mut a) = (vec![0.0; n], vec![false; n]);
        law.solve_lcp(g, w, &mut l, &mut a).unwrap();
        l
    }

    fn both(solver: ComplementaritySolver, g: &[f64], w: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = g.len();
        let mut qp = Complementarity::new(&spec(solver), false, n);
        let mut lg = Lagrange::new(false, n);
        let (mut l1, mut a1) = (vec![0.0; n], vec![false; n]);
        let (mut l2, mut a2) = (vec![0.0; n], vec![false; n]);
        qp.solve_lcp(g, w, &mut l1, &mut a1).unwrap();
        lg.solve(g, w, &mut l2, &mut a2).unwrap();
        assert_eq!(a1, a2, "active sets differ for g = {g:?} ({solver:?})");
        (l1, l2)
    }

    const SOLVERS: [ComplementaritySolver; 2] = [
        ComplementaritySolver::Direct,
        ComplementaritySolver::Clarabel,
    ];

    #[test]
    fn agrees_with_lagrange_on_one_contact() {
        for solver in SOLVERS {
            for g in [-3e-7, -1e-9, 2e-7] {
                let (l1, l2) = both(solver, &[g], &[5e-9]);
                assert!(
                    (l1[0] - l2[0]).abs() <= QP_AGREEMENT * l2[0].abs().max(1.0),
                    "{l1:?} {l2:?}"
                );
            }
        }
    }

    #[test]
    fn agrees_with_lagrange_on_two_coupled_contacts() {
        let w = [2.0e-9, 1.5e-9, 1.5e-9, 2.0e-9];
        for solver in SOLVERS {
            for g in [[-1e-7, -0.5e-7], [-1e-7, -1e-7], [-1e-7, 3e-7]] {
                let (l1, l2) = both(solver, &g, &w);
                for c in 0..2 {
                    assert!(
                        (l1[c] - l2[c]).abs() <= QP_AGREEMENT * l2[c].abs().max(1.0),
                        "{l1:?} {l2:?}"
                    );
                }
            }
        }
    }

    /// A small deterministic generator (no dependency for a unit test).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// A random symmetric positive definite W = BBᵀ + δI of size n, in the
    /// units of a Delassus matrix (≈ 1e-9 m/N), and free gaps ≈ 1e-7 m.
    fn random_lcp(rng: &mut Lcg, n: usize) -> (Vec<f64>, Vec<f64>) {
        let b: Vec<f64> = (0..n * n).map(|_| rng.next()).collect();
        let mut w = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                w[i * n + j] = 1e-9 * (0..n).map(|k| b[i * n + k] * b[j * n + k]).sum::<f64>();
            }
            w[i * n + i] += 1e-9 * (0.05 + rng.next().abs());
        }
        let g = (0..n).map(|_| 1e-7 * rng.next()).collect();
        (g, w)
    }

    /// The direct solve is the LCP's exact answer, and clarabel's QP agrees
    /// with it to the solver tolerance, on 400 random problems of 1–8
    /// contacts, unilateral and bilateral.
    #[test]
    fn direct_and_clarabel_agree_on_random_spd_lcps() {
        let mut rng = Lcg(14);
        for case in 0..400 {
            let n = 1 + case % 8;
            let (g, w) = random_lcp(&mut rng, n);
            let g0 = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let w0 = (0..n).fold(0.0f64, |m, c| m.max(w[c * n + c]));
            let l0 = g0 / w0;
            for bilateral in [false, true] {
                let d = solve(ComplementaritySolver::Direct, bilateral, &g, &w);
                let c = solve(ComplementaritySolver::Clarabel, bilateral, &g, &w);
                for i in 0..n {
                    assert!(
                        (d[i] - c[i]).abs() <= QP_AGREEMENT * l0,
                        "case {case} (n = {n}, bilateral {bilateral}): {d:?} vs {c:?}"
                    );
                }
                // the direct answer satisfies Signorini to round-off
                for i in 0..n {
                    let gap = g[i] + (0..n).map(|j| w[i * n + j] * d[j]).sum::<f64>();
                    if bilateral {
                        assert!(gap.abs() <= 1e-12 * g0, "case {case}: gap {gap}");
                    } else {
                        assert!(d[i] >= 0.0 && gap >= -1e-12 * g0, "case {case}");
                        assert!((d[i] * gap).abs() <= 1e-12 * g0 * l0, "case {case}");
                    }
                }
            }
        }
    }

    /// A law built for nc contacts solves the smaller problems the
    /// velocity-level step hands it, with either solver.
    #[test]
    fn a_law_solves_problems_smaller_than_its_run() {
        let mut rng = Lcg(3);
        for solver in SOLVERS {
            let mut law = Complementarity::new(&spec(solver), false, 4);
            for n in [4, 1, 3, 2, 4] {
                let (g, w) = random_lcp(&mut rng, n);
                let (mut l, mut a) = (vec![0.0; n], vec![false; n]);
                law.solve_lcp(&g, &w, &mut l, &mut a).unwrap();
                let fresh = solve(ComplementaritySolver::Direct, false, &g, &w);
                let l0 = g.iter().fold(0.0f64, |m, x| m.max(x.abs())) / w[0].max(w[n * n - 1]);
                for i in 0..n {
                    assert!(
                        (l[i] - fresh[i]).abs() <= QP_AGREEMENT * l0,
                        "{l:?} {fresh:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn an_iteration_limit_of_one_fails_with_the_solver_status() {
        let spec = ComplementaritySpec {
            solver: ComplementaritySolver::Clarabel,
            max_iter: 1,
            ..ComplementaritySpec::default()
        };
        let mut qp = Complementarity::new(&spec, false, 1);
        let (mut l, mut a) = ([0.0], [false]);
        let err = qp.solve_lcp(&[-3e-7], &[5e-9], &mut l, &mut a).unwrap_err();
        assert!(
            matches!(&err, ContactFailure::Solver { status, .. } if status == "MaxIterations"),
            "{err}"
        );
    }

    /// A Delassus matrix that is not positive definite is refused by the
    /// direct solve with a typed failure, not a wrong force.
    #[test]
    fn a_singular_closed_set_is_a_typed_failure() {
        let w = [1.0, 1.0, 1.0, 1.0];
        let mut law = Complementarity::new(&spec(ComplementaritySolver::Direct), true, 2);
        let (mut l, mut a) = ([0.0; 2], [false; 2]);
        let err = law
            .solve_lcp(&[-1.0, -2.0], &w, &mut l, &mut a)
            .unwrap_err();
        assert_eq!(err, ContactFailure::Singular);
    }
}
