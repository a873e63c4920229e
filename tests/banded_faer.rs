//! An independent cross-check of the hand-written banded LDLᵀ
//! (`taut::model::banded::BandedLdlt`, the solver every time step uses)
//! against faer's sparse LDLᵀ: random symmetric positive definite band
//! matrices, well and ill conditioned, and the assembled Hermite and string
//! matrices `A = M + c K` of `BeamModel`, each solved for several right-hand
//! sides by both.
//!
//! What is asserted, and why it is the right yardstick: LDLᵀ without pivoting
//! is backward stable on SPD matrices (Higham, *Accuracy and Stability of
//! Numerical Algorithms*, §10.1: the computed x solves (A + ΔA) x = b with
//! ‖ΔA‖ ≤ c·n·ε‖A‖), so
//!
//! * the normwise backward error `η = ‖Ax − b‖ / (‖A‖‖x‖ + ‖b‖)` of each
//!   solver is O(n ε) whatever the conditioning ([`BACKWARD_C`]);
//! * the relative residual `‖Ax − b‖ / ‖b‖` is then at most η (1 + κ(A)),
//!   which is what ill conditioning is allowed to cost;
//! * the two solutions differ by at most the sum of their forward errors,
//!   O(n ε κ(A)) relative to ‖x‖ ([`DIFF_C`]).
//!
//! κ(A) is bounded from above by Gershgorin for the random matrices (built
//! strictly diagonally dominant) and estimated by inverse iteration for the
//! beam matrices ([`condition_estimate`]). faer is used with the identity ordering and one symbolic
//! analysis reused across numeric factorizations (the beam cases), and with
//! its default fill-reducing ordering (AMD) for the random ones, a route
//! whose elimination order has nothing in common with the band sweep.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::cholesky::{
    SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Par, Side};
use proptest::prelude::*;
use taut::model::banded::{BandedLdlt, SymBand};
use taut::model::beam::BeamModel;
use taut::scene::{BeamProps, Support};

/// Normwise backward error allowed of either solver: η ≤ BACKWARD_C · n · ε.
/// The a-priori bound's constant for a band of half-width p is about p + 1
/// per entry (each entry of L D Lᵀ sums at most p + 1 rounded products),
/// times a small factor for the substitutions; 8 covers p ≤ 8 with a margin,
/// and the n in the bound already over-counts for a band (measured η is a
/// few ε).
const BACKWARD_C: f64 = 8.0;

/// Relative difference of the two solutions allowed: ‖x₁ − x₂‖ / ‖x₁‖ ≤
/// DIFF_C · n · ε · κ(A): each forward error is at most κ(A)·η (first order),
/// so the difference is at most twice the backward bound times κ.
const DIFF_C: f64 = 2.0 * BACKWARD_C;

/// Right-hand sides per matrix: one fused sweep of the hand-written kernel
/// serves them all (k = 1, 2, 3, 4, 6 take the unrolled kernels for p = 1, 3;
/// 5 takes the generic path).
const RHS: [usize; 3] = [1, 3, 5];

/// faer's sparse LDLᵀ of a band matrix given by its upper triangle.
struct FaerLdlt {
    n: usize,
    upper: SparseColMat<usize, f64>,
    symbolic: SymbolicCholesky<usize>,
}

impl FaerLdlt {
    /// The symbolic analysis (once per sparsity pattern).
    fn analyse(a: &SymBand, identity: bool) -> Self {
        let (n, p) = (a.n(), a.bandwidth());
        let upper = upper_triangle(a);
        let ordering = if identity {
            SymmetricOrdering::Identity
        } else {
            SymmetricOrdering::Amd
        };
        let symbolic = factorize_symbolic_cholesky(
            upper.symbolic(),
            Side::Upper,
            ordering,
            Default::default(),
        )
        .unwrap_or_else(|e| panic!("symbolic analysis n={n} p={p}: {e:?}"));
        FaerLdlt { n, upper, symbolic }
    }

    /// Numeric factorization of `a` (same pattern as analysed) and the solve
    /// of A X = B, B given row-major with k columns as `BandedLdlt` takes it.
    fn solve(&mut self, a: &SymBand, b: &[f64], k: usize) -> Vec<f64> {
        let n = self.n;
        self.upper = upper_triangle(a);
        let mut l_values = vec![0.0; self.symbolic.len_val()];
        let mut mem = MemBuffer::new(StackReq::any_of(&[
            self.symbolic
                .factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
            self.symbolic.solve_in_place_scratch::<f64>(k, Par::Seq),
        ]));
        let ldlt = self
            .symbolic
            .factorize_numeric_ldlt(
                &mut l_values,
                self.upper.as_ref(),
                Side::Upper,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .unwrap_or_else(|e| panic!("faer LDLᵀ n={n}: {e:?}"));
        let mut x = faer::Mat::from_fn(n, k, |i, c| b[i * k + c]);
        ldlt.solve_in_place_with_conj(Conj::No, x.as_mut(), Par::Seq, MemStack::new(&mut mem));
        (0..n * k).map(|r| x[(r / k, r % k)]).collect()
    }
}

/// The band's upper triangle as a CSC matrix (every band position stored,
/// zeros included, so one pattern serves every matrix of the same shape).
fn upper_triangle(a: &SymBand) -> SparseColMat<usize, f64> {
    let (n, p) = (a.n(), a.bandwidth());
    let triplets: Vec<Triplet<usize, usize, f64>> = (0..n)
        .flat_map(|j| (j.saturating_sub(p)..=j).map(move |i| Triplet::new(i, j, a.get(i, j))))
        .collect();
    SparseColMat::try_new_from_triplets(n, n, &triplets).expect("valid triplets")
}

/// ‖A‖_∞ (max row sum).
fn norm_inf(a: &SymBand) -> f64 {
    let (n, p) = (a.n(), a.bandwidth());
    (0..n)
        .map(|i| {
            (i.saturating_sub(p)..=(i + p).min(n - 1))
                .map(|j| a.get(i, j).abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

fn max_abs(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |m, x| m.max(x.abs()))
}

/// Solve with both, assert the backward errors and the agreement, return
/// (worst η, worst relative difference / (n ε κ)) for the report.
fn cross_check(a: &SymBand, kappa: f64, faer: &mut FaerLdlt, seed: u64, label: &str) -> (f64, f64) {
    let n = a.n();
    let ours = BandedLdlt::factor(a).unwrap_or_else(|e| panic!("{label}: {e}"));
    let anorm = norm_inf(a);
    let eps = f64::EPSILON;
    let (mut worst_eta, mut worst_diff) = (0.0_f64, 0.0_f64);
    let mut rng = Rng(seed | 1);
    for k in RHS {
        let b: Vec<f64> = (0..n * k).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let mut x = b.clone();
        ours.solve_many(&mut x, k);
        let y = faer.solve(a, &b, k);
        for c in 0..k {
            let col = |v: &[f64]| -> Vec<f64> { (0..n).map(|i| v[i * k + c]).collect() };
            let (bc, xc, yc) = (col(&b), col(&x), col(&y));
            let bnorm = max_abs(bc.iter().copied());
            for (who, sol) in [("banded", &xc), ("faer", &yc)] {
                let mut r = bc.clone();
                a.mul_acc(sol, -1.0, &mut r);
                let rnorm = max_abs(r.iter().copied());
                let eta = rnorm / (anorm * max_abs(sol.iter().copied()) + bnorm);
                worst_eta = worst_eta.max(eta / (n as f64 * eps));
                assert!(
                    eta <= BACKWARD_C * n as f64 * eps,
                    "{label} k={k} col={c} {who}: backward error {eta:e} (n={n})"
                );
                // the relative residual, what η implies at this conditioning
                let rel = rnorm / bnorm;
                assert!(
                    rel <= BACKWARD_C * n as f64 * eps * (1.0 + kappa),
                    "{label} k={k} col={c} {who}: ‖Ax−b‖/‖b‖ = {rel:e}, κ ≤ {kappa:e}"
                );
            }
            let diff = max_abs(xc.iter().zip(&yc).map(|(p, q)| p - q));
            let scale = max_abs(xc.iter().copied());
            let allowed = DIFF_C * n as f64 * eps * kappa;
            worst_diff = worst_diff.max(diff / scale / (n as f64 * eps * kappa));
            assert!(
                diff <= allowed * scale,
                "{label} k={k} col={c}: ‖x − y‖/‖x‖ = {:e} > {allowed:e} (κ ≤ {kappa:e})",
                diff / scale
            );
        }
    }
    (worst_eta, worst_diff)
}

/// xorshift64*: reproducible matrices from a proptest-chosen seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// A random SPD band matrix: off-diagonal entries uniform in [−1, 1], each
/// diagonal entry the absolute sum of its row's off-diagonals plus a margin
/// `δ·(1 + u)`, u uniform in [0, 1]. Gershgorin puts every eigenvalue in
/// [δ, 2·max row sum + 2δ], which bounds κ (returned alongside).
fn random_spd(n: usize, p: usize, delta: f64, seed: u64) -> (SymBand, f64) {
    let mut rng = Rng(seed | 1);
    let mut a = SymBand::zeros(n, p);
    let mut offsum = vec![0.0; n];
    for i in 0..n {
        for j in i + 1..(i + p + 1).min(n) {
            let v = rng.uniform(-1.0, 1.0);
            a.add_entry(i, j, v);
            a.add_entry(j, i, v);
            offsum[i] += v.abs();
            offsum[j] += v.abs();
        }
    }
    let mut lo = f64::INFINITY;
    let mut hi = 0.0_f64;
    for (i, off) in offsum.iter().enumerate() {
        let margin = delta * (1.0 + rng.uniform(0.0, 1.0));
        a.add_entry(i, i, off + margin);
        lo = lo.min(margin);
        hi = hi.max(2.0 * off + margin);
    }
    (a, hi / lo)
}

/// Headroom on the κ estimate of [`condition_estimate`]: inverse iteration
/// approaches λ_min from above, so the estimate can fall short of κ; after
/// [`INVERSE_ITERATIONS`] steps from a dense random start, the Rayleigh
/// quotient is within a factor of a few of λ_min even when the lowest
/// eigenvalues cluster (the beam's lowest modes are well separated), and 10
/// covers it.
const KAPPA_SAFETY: f64 = 10.0;

/// Inverse-iteration steps for λ_min (each one banded solve).
const INVERSE_ITERATIONS: usize = 30;

/// κ∞(A) estimate for the beam matrices, cheap at any n: ‖A‖_∞ (an upper
/// bound of λ_max) over λ_min from inverse iteration with faer's factor (not
/// the one under test), times [`KAPPA_SAFETY`]; the ∞-norm tolerances are
/// widened by n on top (κ∞ ≤ n κ₂).
fn condition_estimate(a: &SymBand, faer: &mut FaerLdlt) -> f64 {
    let n = a.n();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut v: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 1.5)).collect();
    let mut lambda = f64::INFINITY;
    for _ in 0..INVERSE_ITERATIONS {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter_mut().for_each(|x| *x /= norm);
        let w = faer.solve(a, &v, 1);
        // Rayleigh quotient of A⁻¹ at v: vᵀ A⁻¹ v ≤ 1/λ_min
        let q: f64 = v.iter().zip(&w).map(|(x, y)| x * y).sum();
        lambda = lambda.min(1.0 / q);
        v = w;
    }
    assert!(lambda > 0.0, "not positive definite: λ_min ≈ {lambda:e}");
    norm_inf(a) / lambda * KAPPA_SAFETY * n as f64
}

fn bandwidth() -> impl Strategy<Value = usize> {
    prop_oneof![4 => 1usize..=3, 1 => Just(5usize), 1 => Just(8usize)]
}

fn size() -> impl Strategy<Value = usize> {
    prop_oneof![2 => 1usize..=12, 2 => 13usize..=80, 1 => 81usize..=300]
}

/// Diagonal-dominance margins from comfortable to κ ≈ 10¹³.
fn margin() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1.0), Just(1e-3), Just(1e-7), Just(1e-12)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_band_matrices_agree_with_faer(
        n in size(),
        p in bandwidth(),
        delta in margin(),
        seed in any::<u64>(),
        identity in any::<bool>(),
    ) {
        let (a, kappa) = random_spd(n, p, delta, seed);
        let mut faer = FaerLdlt::analyse(&a, identity);
        cross_check(&a, kappa, &mut faer, seed.rotate_left(17), &format!("random n={n} p={p} δ={delta:e}"));
    }
}

fn props(ei: f64, left: Support, right: Support) -> BeamProps {
    BeamProps {
        length: 1.0,
        rho_a: 1.335,
        ei,
        ea: None,
        tension: 3.2e3,
        left,
        right,
        distributed_load: 0.0,
        attachments: Vec::new(),
        messenger: None,
    }
}

#[test]
fn assembled_beam_matrices_agree_with_faer() {
    // A = M + c K as generalized-α forms it: c = (1−α_f) β Δt² over a range
    // of Δt relative to the mesh (c → 0: A ≈ M; c large: A ≈ c K), and
    // K alone (the static problem; SPD with the supports)
    let cases = [
        (129.2, Support::Clamped, Support::Pinned),
        (129.2, Support::Pinned, Support::Pinned),
        (129.2, Support::Clamped, Support::Clamped),
        (0.0, Support::Pinned, Support::Pinned),
    ];
    let mut report = Vec::new();
    for (ei, l, r) in cases {
        for elements in [2, 7, 40, 150] {
            let beam = BeamModel::new(&props(ei, l, r), elements);
            if beam.n == 0 {
                continue;
            }
            // one symbolic analysis serves every A of this mesh
            let mut faer = FaerLdlt::analyse(&beam.mass, true);
            let weights = [Some(1e-10), Some(1e-7), Some(1e-4), Some(1e-1), None];
            for (s, c) in weights.into_iter().enumerate() {
                let a = match c {
                    Some(c) => beam.mass.combine(1.0, &beam.stiffness, c),
                    None => beam.stiffness.clone(),
                };
                let kappa = condition_estimate(&a, &mut faer);
                let label = format!("beam EI={ei} {l:?}–{r:?} N={elements} c={c:?}");
                let (eta, diff) = cross_check(&a, kappa, &mut faer, 7 + s as u64, &label);
                report.push((label, kappa, eta, diff));
            }
        }
    }
    for (label, kappa, eta, diff) in &report {
        println!("{label}: κ ≤ {kappa:.1e}, η/(nε) = {eta:.2e}, diff/(nεκ) = {diff:.1e}");
    }
}
