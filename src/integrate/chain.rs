//! A multi-mass pantograph during a run (MODEL §10, docs/lines.md P1–P4):
//! the chain's matrices and static contact force ([`Chain`]). Every
//! method that carries it steps it with its own mass rule through
//! `mass_step.rs`, the rule it steps a single mass with, condensed onto
//! the head so that the contact problem sees the head as it sees a single
//! mass. `modal_exact` refuses a chain ([`refusal`]).
//!
//! **Coordinates.** z_i = s·ξ_i of mass i (positive into the beam, like q
//! in MODEL §2), measured from the chain's static equilibrium against the
//! undeformed wire (P2): at t = 0 the chain is at rest there and the wire
//! is straight, so the wire is loaded by the static contact force λ₀ from
//! t = 0 on — the single carrier's convention (its q = 0 start with
//! k δ0 − s m g is its static state against the undeformed wire). The head
//! z₁ is the contact's mass dof (`State::q`); z₂ … z_n live with the
//! method's mass step (`mass_step.rs`).
//!
//! **Equations** (P1): `M z̈ + C ż + K z = f₀ − λ e₁`, M = diag(m_i), K and
//! C tridiagonal from the springs and dashpots, f₀ = λ₀ e₁ (the static
//! forces relative to the equilibrium; an uplift step adds ΔF e_n).
//!
//! **A method's step** (P3; MODEL §5 applied to the chain's dofs): with
//! its unknown u of every mass, `A u = F − λ e₁`, A = c_m M + c_c C + c_k K
//! (generalized-α: the acceleration, c_m = 1 − α_m, c_c = (1 − α_f)γΔt,
//! c_k = (1 − α_f)βΔt²; Bathe's sub-steps, Moreau–Jean and central
//! difference: their own, `mass_step.rs`), so u = A⁻¹F − λ A⁻¹e₁ and the
//! head's unknown is u₁ = u★₁ − λ/A_q with A_q = 1/(A⁻¹)₁₁ (P3): the
//! chain's dynamic stiffness seen from the head. A is inverted (at most
//! 3 × 3) once per run ([`inverse`]); a step is O(n²) in the chain's n ≤ 3
//! masses and allocates nothing.

use crate::error::Error;
use crate::scene::{ChainProps, MAX_CHAIN};

/// A chain matrix, row-major (the first n rows and columns used).
pub(crate) type Mat = [[f64; MAX_CHAIN]; MAX_CHAIN];

/// A chain's matrices and static forces (module docs, P1–P2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Chain {
    /// Masses n.
    pub n: usize,
    /// m_i, kg.
    pub m: [f64; MAX_CHAIN],
    /// K, N/m (tridiagonal).
    pub k: Mat,
    /// C, N·s/m (tridiagonal).
    pub c: Mat,
    /// f₀, N: the constant forces on z relative to the static state,
    /// λ₀ e₁ (P2).
    pub f0: [f64; MAX_CHAIN],
    /// λ₀, N: the static contact force against the undeformed wire (P2).
    pub static_force: f64,
    /// z of every mass at t = 0, m: zero (the static state against the
    /// undeformed wire, P2) unless a static start holds the head at the
    /// static wire's height ([`Chain::hold_head`], `static_start.rs`).
    pub z_start: [f64; MAX_CHAIN],
}

/// A tridiagonal chain matrix from its links: link i joins mass i and
/// i + 1, the last link joins m_n to the roof.
fn chain_matrix(n: usize, links: &[f64]) -> Mat {
    let mut a = [[0.0; MAX_CHAIN]; MAX_CHAIN];
    for i in 0..n {
        a[i][i] += links[i];
        if i + 1 < n {
            a[i + 1][i + 1] += links[i];
            a[i][i + 1] -= links[i];
            a[i + 1][i] -= links[i];
        }
    }
    a
}

/// K' = K without the head's row and column (masses 2 … n): positive
/// definite since k₁ … k_{n−1} > 0.
fn lower_block(n: usize, k: &Mat) -> Mat {
    let mut kr = [[0.0; MAX_CHAIN]; MAX_CHAIN];
    for i in 1..n {
        for j in 1..n {
            kr[i - 1][j - 1] = k[i][j];
        }
    }
    kr
}

/// x = A⁻¹b of an n × n symmetric positive definite A (n ≤ 3), by Gaussian
/// elimination without pivoting (SPD: the pivots are positive).
fn solve(n: usize, a: &Mat, b: &[f64; MAX_CHAIN]) -> [f64; MAX_CHAIN] {
    let (mut a, mut x) = (*a, *b);
    for p in 0..n {
        for r in p + 1..n {
            let f = a[r][p] / a[p][p];
            for c in p..n {
                a[r][c] -= f * a[p][c];
            }
            x[r] -= f * x[p];
        }
    }
    for p in (0..n).rev() {
        let mut s = x[p];
        for c in p + 1..n {
            s -= a[p][c] * x[c];
        }
        x[p] = s / a[p][p];
    }
    x
}

/// `(c_m M + c_c C + c_k K)⁻¹` of `chain`, row-major: the effective
/// matrix every implicit method forms for the chain's unknowns, inverted
/// once per run (n ≤ 3).
pub(crate) fn inverse(chain: &Chain, c_m: f64, c_c: f64, c_k: f64) -> Mat {
    let n = chain.n;
    let mut a = [[0.0; MAX_CHAIN]; MAX_CHAIN];
    for (i, row) in a.iter_mut().enumerate().take(n) {
        for (j, x) in row.iter_mut().enumerate().take(n) {
            *x = c_c * chain.c[i][j] + c_k * chain.k[i][j];
        }
        row[i] += c_m * chain.m[i];
    }
    let mut inv = [[0.0; MAX_CHAIN]; MAX_CHAIN];
    for j in 0..n {
        let mut e = [0.0; MAX_CHAIN];
        e[j] = 1.0;
        let col = solve(n, &a, &e);
        for (row, x) in inv.iter_mut().zip(col).take(n) {
            row[j] = x;
        }
    }
    inv
}

impl Chain {
    /// The chain of `p` on side `s` under gravity `g` (m/s²): its matrices
    /// and the static contact force (P2)
    /// `λ₀ = k₁ ζ₂ − s m₁ g`, with ζ₂ … ζ_n the static positions (from the
    /// unloaded springs) of the lower masses while the head is held at the
    /// undeformed wire: `K' ζ' = F₀ e_n − s g m'` over masses 2 … n
    /// (K' is K without the head's row and column: positive definite since
    /// k₁ … k_{n−1} > 0).
    pub fn new(p: &ChainProps, s: f64, g: f64) -> Self {
        let n = p.n;
        let k = chain_matrix(n, p.stiffnesses());
        let c = chain_matrix(n, p.dampings());
        let mut m = [0.0; MAX_CHAIN];
        m[..n].copy_from_slice(p.masses());
        // the held head's statics over the lower masses
        let kr = lower_block(n, &k);
        let mut fr = [0.0; MAX_CHAIN];
        for i in 1..n {
            fr[i - 1] = -s * g * m[i];
        }
        fr[n - 2] += p.uplift;
        let zeta = solve(n - 1, &kr, &fr);
        let static_force = p.stiffnesses[0] * zeta[0] - s * g * m[0];
        let mut f0 = [0.0; MAX_CHAIN];
        f0[0] = static_force;
        Chain {
            n,
            m,
            k,
            c,
            f0,
            static_force,
            z_start: [0.0; MAX_CHAIN],
        }
    }

    /// The chain's static stiffness seen from the head, N/m: with the
    /// lower masses in equilibrium, a head displaced by z₁ changes the
    /// contact force by −S z₁, S = K₁₁ − K₁ₗ K'⁻¹ Kₗ₁ (the Schur complement
    /// of the lower block K' of K; `docs/lines.md` eq. W7).
    pub fn head_stiffness(&self) -> f64 {
        let (_, s) = self.held_lower(1.0);
        s
    }

    /// The lower masses' static positions with the head held at z₁ (K'
    /// z' = −Kₗ₁ z₁) and S z₁ (module docs of [`Chain::head_stiffness`]).
    fn held_lower(&self, z1: f64) -> ([f64; MAX_CHAIN], f64) {
        let n = self.n;
        let kr = lower_block(n, &self.k);
        let mut fr = [0.0; MAX_CHAIN];
        for i in 1..n {
            fr[i - 1] = -self.k[i][0] * z1;
        }
        let zl = solve(n - 1, &kr, &fr);
        let mut z = [0.0; MAX_CHAIN];
        z[0] = z1;
        z[1..n].copy_from_slice(&zl[..n - 1]);
        let force = (0..n).map(|j| self.k[0][j] * z[j]).sum::<f64>();
        (z, force)
    }

    /// (K z)₁ at [`Chain::z_start`], N: the head's spring force at t = 0.
    pub fn head_spring_force(&self) -> f64 {
        (0..self.n).map(|j| self.k[0][j] * self.z_start[j]).sum()
    }

    /// Start the chain at rest in its static state with the head at z₁
    /// (the static wire's height, `static_start.rs`): the lower masses at
    /// their equilibrium against the held head (its contact force there is
    /// λ₀ − S z₁, which `static_start.rs` has solved for already).
    pub fn hold_head(&mut self, z1: f64) {
        self.z_start = self.held_lower(z1).0;
    }

    /// An upper bound on the chain's highest natural frequency with the
    /// head free, rad/s: Gershgorin on M⁻¹K, ω_max² ≤ max_i Σ_j |K_ij|/m_i
    /// (for central difference's stability limit).
    pub fn omega_bound(&self) -> f64 {
        (0..self.n)
            .map(|i| (0..self.n).map(|j| self.k[i][j].abs()).sum::<f64>() / self.m[i])
            .fold(0.0, f64::max)
            .sqrt()
    }

    /// Row i of `a · y` over the chain's n masses.
    #[inline]
    pub(crate) fn mul(&self, a: &Mat, y: &[f64; MAX_CHAIN], i: usize) -> f64 {
        let mut s = 0.0;
        for (j, yj) in y.iter().enumerate().take(self.n) {
            s += a[i][j] * yj;
        }
        s
    }
}

/// The error for a method that does not step multi-mass pantographs:
/// `modal_exact` (its exact step of a mass is the exponential of one
/// oscillator, `oscillator.rs::MassStep`, and its contact pair sums over
/// modes with that scalar; the chain's 2n-state exponential is not written)
/// and methods registered from outside the crate (they see one mass dof
/// per contact, [`super::System::masses`]).
pub(crate) fn refusal(method: &str) -> Error {
    Error::invalid(
        "integrator.method",
        format!("\"{method}\""),
        "a scene with a multi-mass carrier (carrier.masses) steps with generalized_alpha, \
         newmark, hht, wbz, bathe, central_difference or moreau_jean: this method's mass \
         step is written for one mass and does not carry the chain",
    )
}

#[cfg(test)]
pub(crate) mod tests {
    //! The chain's statics against the closed-form held pantograph
    //! (docs/lines.md L9–L11); its step by each method is checked in
    //! `chain_steps.rs`.

    use super::*;
    use crate::analytic::{Pantograph, SurfaceContact};

    /// Two independent ways of forming a static force or frequency: a few
    /// hundred ulps of round-off in 3 × 3 solves and eigen decompositions.
    pub(crate) const ROUND_OFF: f64 = 1e-12;

    pub(crate) fn props(m: &[f64], k: &[f64], c: &[f64], uplift: f64) -> ChainProps {
        let mut p = ChainProps {
            n: m.len(),
            masses: [0.0; MAX_CHAIN],
            stiffnesses: [0.0; MAX_CHAIN],
            dampings: [0.0; MAX_CHAIN],
            uplift,
        };
        p.masses[..m.len()].copy_from_slice(m);
        p.stiffnesses[..m.len()].copy_from_slice(k);
        p.dampings[..m.len()].copy_from_slice(c);
        p
    }

    /// The chains checked: two masses (damped), three masses undamped and
    /// with non-proportional dashpots (an EN 50318-like set, illustrative).
    pub(crate) fn chains() -> Vec<(&'static str, ChainProps)> {
        vec![
            (
                "two masses, damped",
                props(&[6.0, 11.0], &[7000.0, 60.0], &[15.0, 40.0], 100.0),
            ),
            (
                "three masses, undamped",
                props(
                    &[7.2, 15.5, 15.0],
                    &[4200.0, 10400.0, 80.0],
                    &[0.0; 3],
                    150.0,
                ),
            ),
            (
                "three masses, non-proportional dashpots",
                props(
                    &[7.2, 15.5, 15.0],
                    &[4200.0, 10400.0, 80.0],
                    &[10.0, 0.0, 90.0],
                    150.0,
                ),
            ),
        ]
    }

    pub(crate) fn held(p: &ChainProps) -> Pantograph {
        Pantograph::new(
            p.masses(),
            p.stiffnesses(),
            p.dampings(),
            p.uplift,
            SurfaceContact::Held,
        )
        .unwrap()
    }

    #[test]
    fn the_static_force_is_the_held_pantographs() {
        for (name, p) in chains() {
            let lambda0 = Chain::new(&p, 1.0, 0.0).static_force;
            let want = held(&p).static_contact_force();
            assert!(
                (lambda0 - want).abs() <= ROUND_OFF * want,
                "{name}: {lambda0} {want}"
            );
            // with gravity: the weights of the masses below the head reach
            // the wire through the same statics, λ₀ = F₀ − s g Σm − k_n ζ_n;
            // without a roof spring the whole of F₀ − s g Σm
            let mut free_frame = p;
            free_frame.stiffnesses[p.n - 1] = 0.0;
            for s in [1.0, -1.0] {
                let l = Chain::new(&free_frame, s, 9.81).static_force;
                let want = p.uplift - s * 9.81 * p.total_mass();
                assert!(
                    (l - want).abs() <= ROUND_OFF * want.abs(),
                    "{name} {s}: {l} {want}"
                );
            }
        }
    }
}
