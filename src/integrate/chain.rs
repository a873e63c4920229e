//! A multi-mass pantograph during a run (MODEL §10, docs/lines.md P1–P4):
//! the chain's matrices and static contact force ([`Chain`]), and its step
//! by each method that carries it — [`ChainGenAlpha`] (the generalized-α
//! family), [`ChainBathe`], [`ChainMoreauJean`], [`ChainCentral`] —
//! condensed onto the head so the contact problem sees the head as it sees
//! a single mass. `modal_exact` refuses a chain ([`refusal`]).
//!
//! **Coordinates.** z_i = s·ξ_i of mass i (positive into the beam, like q
//! in MODEL §2), measured from the chain's static equilibrium against the
//! undeformed wire (P2): at t = 0 the chain is at rest there and the wire
//! is straight, so the wire is loaded by the static contact force λ₀ from
//! t = 0 on — the single carrier's convention (its q = 0 start with
//! k δ0 − s m g is its static state against the undeformed wire). The head
//! z₁ is the contact's mass dof (`State::q`); z₂ … z_n live here.
//!
//! **Equations** (P1): `M z̈ + C ż + K z = f₀ − λ e₁`, M = diag(m_i), K and
//! C tridiagonal from the springs and dashpots, f₀ = λ₀ e₁ (the static
//! forces relative to the equilibrium; an uplift step adds ΔF e_n).
//!
//! **Generalized-α** (P3; MODEL §5 applied to the chain's dofs, as
//! `gen_alpha_kernel.rs` applies it to one mass): with the unknown ü_{n+1},
//!
//! ```text
//!   A ü_{n+1} = F − λ e₁,  A = (1 − α_m)M + (1 − α_f)γΔt C + (1 − α_f)βΔt² K,
//!   F = f₀ − α_m M ü_n − C((1 − α_f)ṽ + α_f ż_n) − K((1 − α_f)z̃ + α_f z_n),
//! ```
//!
//! so ü = A⁻¹F − λ A⁻¹e₁ and the head's unknown is u₁ = u★₁ − λ/A_q with
//! A_q = 1/(A⁻¹)₁₁ (P3): the chain's dynamic stiffness seen from the head.
//! A is factored (inverted: at most 3 × 3) once per run; a step is O(n²)
//! in the chain's n ≤ 3 masses and allocates nothing. The other methods
//! are the same with their own unknown and A = c_m M + c_c C + c_k K
//! (each struct's docs; lines.md P3).

use crate::error::Error;
use crate::scene::{ChainProps, GenAlphaParams, MAX_CHAIN};

use super::step_map::MassPrediction;

type Mat = [[f64; MAX_CHAIN]; MAX_CHAIN];

/// A chain's matrices and static forces (module docs, P1–P2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
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
fn inverse(chain: &Chain, c_m: f64, c_c: f64, c_k: f64) -> Mat {
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

    /// (K y)_i + … for the first n entries: `a · y`.
    #[inline]
    fn mul(&self, a: &Mat, y: &[f64; MAX_CHAIN], i: usize) -> f64 {
        let mut s = 0.0;
        for (j, yj) in y.iter().enumerate().take(self.n) {
            s += a[i][j] * yj;
        }
        s
    }
}

/// A chain stepped by generalized-α (module docs): the lower masses'
/// state and the step's free solution; the head's state is the contact's
/// (`State::q`, `q_dot` and the kernel's q̈).
#[derive(Debug, Clone, PartialEq)]
pub struct ChainGenAlpha {
    /// The chain.
    pub chain: Chain,
    p: GenAlphaParams,
    dt: f64,
    /// A⁻¹ (module docs), row-major.
    a_inv: Mat,
    /// z, ż, z̈ of every mass (index 0, the head, mirrors the contact's).
    z: [f64; MAX_CHAIN],
    zd: [f64; MAX_CHAIN],
    za: [f64; MAX_CHAIN],
    /// This step's u★ = A⁻¹F.
    u_star: [f64; MAX_CHAIN],
}

impl ChainGenAlpha {
    /// `chain` at rest in its static state (z = ż = 0), with the head's
    /// initial acceleration `a_head` (the lower masses' is 0: nothing but
    /// the contact force differs from the static balance at t = 0).
    pub fn new(chain: Chain, p: GenAlphaParams, dt: f64, a_head: f64) -> Self {
        let a_inv = inverse(
            &chain,
            1.0 - p.alpha_m,
            (1.0 - p.alpha_f) * p.gamma * dt,
            (1.0 - p.alpha_f) * p.beta * dt * dt,
        );
        let mut za = [0.0; MAX_CHAIN];
        za[0] = a_head;
        ChainGenAlpha {
            chain,
            p,
            dt,
            a_inv,
            z: chain.z_start,
            zd: [0.0; MAX_CHAIN],
            za,
            u_star: [0.0; MAX_CHAIN],
        }
    }

    /// A_q = 1/(A⁻¹)₁₁, the head's effective scalar (P3).
    pub fn a_eff(&self) -> f64 {
        1.0 / self.a_inv[0][0]
    }

    /// The step's prediction for the head (module docs), from the head's
    /// state `(q, q̇, q̈)` at t_n (the contact's; copied into the chain).
    pub fn predict(&mut self, (q, v, a): (f64, f64, f64)) -> MassPrediction {
        let (n, dt) = (self.chain.n, self.dt);
        let GenAlphaParams {
            alpha_m: am,
            alpha_f: af,
            beta,
            gamma,
        } = self.p;
        (self.z[0], self.zd[0], self.za[0]) = (q, v, a);
        let c_pred = (0.5 - beta) * dt * dt;
        let mut zk = [0.0; MAX_CHAIN];
        let mut vc = [0.0; MAX_CHAIN];
        for i in 0..n {
            let zp = self.z[i] + dt * self.zd[i] + c_pred * self.za[i];
            let vp = self.zd[i] + (1.0 - gamma) * dt * self.za[i];
            zk[i] = (1.0 - af) * zp + af * self.z[i];
            vc[i] = (1.0 - af) * vp + af * self.zd[i];
        }
        let mut f = [0.0; MAX_CHAIN];
        for (i, fi) in f.iter_mut().enumerate().take(n) {
            *fi = self.chain.f0[i]
                - am * self.chain.m[i] * self.za[i]
                - self.chain.mul(&self.chain.c, &vc, i)
                - self.chain.mul(&self.chain.k, &zk, i);
        }
        for i in 0..n {
            self.u_star[i] = self.chain.mul(&self.a_inv, &f, i);
        }
        MassPrediction {
            q: q + dt * v + c_pred * a,
            q_dot: v + (1.0 - gamma) * dt * a,
            u: self.u_star[0],
            a_eff: self.a_eff(),
        }
    }

    /// After the contact force λ is known: the lower masses' new state,
    /// ü = u★ − λ A⁻¹e₁ (the head's is the contact's, updated by the caller).
    pub fn finish(&mut self, lambda: f64) {
        let dt = self.dt;
        let (beta, gamma) = (self.p.beta, self.p.gamma);
        let (bdt2, c_pred) = (beta * dt * dt, (0.5 - beta) * dt * dt);
        for i in 1..self.chain.n {
            let (a, acc) = (self.za[i], self.u_star[i] - lambda * self.a_inv[i][0]);
            self.z[i] += dt * self.zd[i] + c_pred * a + bdt2 * acc;
            self.zd[i] += dt * ((1.0 - gamma) * a + gamma * acc);
            self.za[i] = acc;
        }
    }

    /// z_i of mass i (0 = head, as last copied in), m.
    pub fn displacement(&self, i: usize) -> f64 {
        self.z[i]
    }

    /// ż_i of mass i, m/s.
    pub fn velocity(&self, i: usize) -> f64 {
        self.zd[i]
    }
}

/// Each mass's unknown once the head's multiplier λ is known:
/// u = u★ − λ A⁻¹e₁ (the contact pushes the head with −λ).
#[inline]
fn unknowns(n: usize, u_star: &[f64; MAX_CHAIN], inv: &Mat, lambda: f64) -> [f64; MAX_CHAIN] {
    let mut u = [0.0; MAX_CHAIN];
    for i in 0..n {
        u[i] = u_star[i] - lambda * inv[i][0];
    }
    u
}

/// u★ = A⁻¹ b over the chain's n masses.
#[inline]
fn apply(n: usize, inv: &Mat, b: &[f64; MAX_CHAIN]) -> [f64; MAX_CHAIN] {
    let mut u = [0.0; MAX_CHAIN];
    for (ui, row) in u.iter_mut().zip(inv).take(n) {
        *ui = row.iter().zip(b).take(n).map(|(a, x)| a * x).sum();
    }
    u
}

/// A chain stepped by Bathe's composite scheme (MODEL §9.1, `bathe.rs`):
/// each sub-step's effective matrix `c² M + c C + K` (c = c₀ = 2/(γ_BΔt),
/// then c₃) over the chain, its unknown the displacement increment e of
/// each mass, `A e = f₀ − C ṽ − K d̃ − λ e₁` (P3 with Bathe's
/// coefficients). The head's state is the contact's.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainBathe {
    /// The chain.
    pub chain: Chain,
    inv1: Mat,
    inv2: Mat,
    /// h₁ = γ_BΔt, c₁, c₂, c₃ (`bathe.rs`).
    h1: f64,
    c1: f64,
    c2: f64,
    c3: f64,
    c0: f64,
    z: [f64; MAX_CHAIN],
    zd: [f64; MAX_CHAIN],
    za: [f64; MAX_CHAIN],
    /// The current sub-step's predictors and free increments.
    zp: [f64; MAX_CHAIN],
    zdp: [f64; MAX_CHAIN],
    u_star: [f64; MAX_CHAIN],
    /// Sub-step 1's end state and its increment Δ₁ = z₁ − z_n.
    z1: [f64; MAX_CHAIN],
    zd1: [f64; MAX_CHAIN],
    dz1: [f64; MAX_CHAIN],
}

impl ChainBathe {
    /// `chain` at rest in its static state, the head's acceleration `a_head`.
    pub fn new(chain: Chain, gamma: f64, dt: f64, a_head: f64) -> Self {
        let h1 = gamma * dt;
        let c0 = 2.0 / h1;
        let c3 = (2.0 - gamma) / ((1.0 - gamma) * dt);
        let mut za = [0.0; MAX_CHAIN];
        za[0] = a_head;
        ChainBathe {
            inv1: inverse(&chain, c0 * c0, c0, 1.0),
            inv2: inverse(&chain, c3 * c3, c3, 1.0),
            chain,
            h1,
            c0,
            c1: (1.0 - gamma) / (gamma * dt),
            c2: -1.0 / ((1.0 - gamma) * gamma * dt),
            c3,
            z: chain.z_start,
            zd: [0.0; MAX_CHAIN],
            za,
            zp: [0.0; MAX_CHAIN],
            zdp: [0.0; MAX_CHAIN],
            u_star: [0.0; MAX_CHAIN],
            z1: [0.0; MAX_CHAIN],
            zd1: [0.0; MAX_CHAIN],
            dz1: [0.0; MAX_CHAIN],
        }
    }

    /// u★ = A⁻¹(f₀ − C ṽ − K d̃) from the current predictors.
    fn free(&mut self, inv: Mat) -> MassPrediction {
        let (ch, n) = (&self.chain, self.chain.n);
        let mut b = [0.0; MAX_CHAIN];
        for (i, bi) in b.iter_mut().enumerate().take(n) {
            *bi = ch.f0[i] - ch.mul(&ch.c, &self.zdp, i) - ch.mul(&ch.k, &self.zp, i);
        }
        self.u_star = apply(n, &inv, &b);
        MassPrediction {
            q: self.zp[0],
            q_dot: self.zdp[0],
            u: self.u_star[0],
            a_eff: 1.0 / inv[0][0],
        }
    }

    /// Sub-step 1's prediction for the head, from its state `(q, q̇, q̈)` at t_n.
    pub fn first(&mut self, (q, v, a): (f64, f64, f64)) -> MassPrediction {
        (self.z[0], self.zd[0], self.za[0]) = (q, v, a);
        let h = self.h1;
        for i in 0..self.chain.n {
            let p = h * self.zd[i] + 0.25 * h * h * self.za[i];
            self.dz1[i] = p;
            self.zp[i] = self.z[i] + p;
            self.zdp[i] = self.zd[i] + 0.5 * h * self.za[i];
        }
        self.free(self.inv1)
    }

    /// After sub-step 1's λ: the chain at t_n + γ_BΔt.
    pub fn end_first(&mut self, lambda: f64) {
        let e = unknowns(self.chain.n, &self.u_star, &self.inv1, lambda);
        for (i, ei) in e.iter().enumerate().take(self.chain.n) {
            self.z1[i] = self.zp[i] + ei;
            self.zd1[i] = self.zdp[i] + self.c0 * ei;
            self.dz1[i] += ei;
        }
    }

    /// Sub-step 2's prediction for the head.
    pub fn second(&mut self) -> MassPrediction {
        let (c1, c2, c3) = (self.c1, self.c2, self.c3);
        for i in 0..self.chain.n {
            let s = c1 * self.zd[i] + c2 * self.zd1[i] - c3 * c1 * self.dz1[i];
            self.zp[i] = self.z1[i] - s / (c3 * c3);
            self.zdp[i] = -c1 * self.dz1[i] - s / c3;
        }
        self.free(self.inv2)
    }

    /// After sub-step 2's λ: the chain at t_{n+1}.
    pub fn end_second(&mut self, lambda: f64) {
        let c3 = self.c3;
        let e = unknowns(self.chain.n, &self.u_star, &self.inv2, lambda);
        for (i, ei) in e.iter().enumerate().take(self.chain.n) {
            self.z[i] = self.zp[i] + ei;
            self.zd[i] = self.zdp[i] + c3 * ei;
            self.za[i] = c3 * c3 * ei;
        }
    }
}

/// A chain stepped by Moreau–Jean (MODEL §9.1, `moreau_jean.rs`): the
/// unknown is each mass's velocity change over the step,
/// `(M + θΔt C + θ²Δt² K) Δż = Δt(f₀ − C ż_n − K(z_n + θΔt ż_n)) − P e₁`,
/// P the head's impulse. The head's state is the contact's.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainMoreauJean {
    /// The chain.
    pub chain: Chain,
    inv: Mat,
    theta: f64,
    dt: f64,
    z: [f64; MAX_CHAIN],
    zd: [f64; MAX_CHAIN],
    u_star: [f64; MAX_CHAIN],
}

impl ChainMoreauJean {
    /// `chain` at rest in its static state.
    pub fn new(chain: Chain, theta: f64, dt: f64) -> Self {
        ChainMoreauJean {
            inv: inverse(&chain, 1.0, theta * dt, theta * theta * dt * dt),
            chain,
            theta,
            dt,
            z: chain.z_start,
            zd: [0.0; MAX_CHAIN],
            u_star: [0.0; MAX_CHAIN],
        }
    }

    /// The step's prediction for the head, from its state `(q, q̇)` at t_n.
    pub fn predict(&mut self, (q, v): (f64, f64)) -> MassPrediction {
        (self.z[0], self.zd[0]) = (q, v);
        let (ch, n, dt) = (&self.chain, self.chain.n, self.dt);
        let mut zt = [0.0; MAX_CHAIN];
        for i in 0..n {
            zt[i] = self.z[i] + self.theta * dt * self.zd[i];
        }
        let mut b = [0.0; MAX_CHAIN];
        for (i, bi) in b.iter_mut().enumerate().take(n) {
            *bi = dt * (ch.f0[i] - ch.mul(&ch.c, &self.zd, i) - ch.mul(&ch.k, &zt, i));
        }
        self.u_star = apply(n, &self.inv, &b);
        MassPrediction {
            q: q + dt * v,
            q_dot: v,
            u: self.u_star[0],
            a_eff: 1.0 / self.inv[0][0],
        }
    }

    /// After the impulse P: the chain at t_{n+1}.
    pub fn finish(&mut self, impulse: f64) {
        let (n, dt) = (self.chain.n, self.dt);
        let du = unknowns(n, &self.u_star, &self.inv, impulse);
        for (i, d) in du.iter().enumerate().take(n) {
            self.z[i] += dt * self.zd[i] + self.theta * dt * d;
            self.zd[i] += d;
        }
    }
}

/// A chain stepped by central difference (MODEL §9.1,
/// `central_difference.rs`): `(M + ½Δt C) z̈_n = f₀ − K z_n − C ż_{n−1/2}
/// − λ e₁` (the dashpots at the mean half-step velocity, as for one mass),
/// then `ż_{n+1/2} = ż_{n−1/2} + Δt z̈_n`, `z_{n+1} = z_n + Δt ż_{n+1/2}`.
/// Stable for Δt ≤ 2/ω_max with the chain's ω_max bounded by
/// [`Chain::omega_bound`].
#[derive(Debug, Clone, PartialEq)]
pub struct ChainCentral {
    /// The chain.
    pub chain: Chain,
    inv: Mat,
    dt: f64,
    z: [f64; MAX_CHAIN],
    /// ż_{n−1/2}.
    zd: [f64; MAX_CHAIN],
    u_star: [f64; MAX_CHAIN],
}

impl ChainCentral {
    /// `chain` at rest in its static state (its lower masses' ü₀ = 0, so
    /// their ż_{−1/2} = 0).
    pub fn new(chain: Chain, dt: f64) -> Self {
        ChainCentral {
            inv: inverse(&chain, 1.0, 0.5 * dt, 0.0),
            chain,
            dt,
            z: chain.z_start,
            zd: [0.0; MAX_CHAIN],
            u_star: [0.0; MAX_CHAIN],
        }
    }

    /// The step's prediction for the head, from `(q_n, q̇_{n−1/2})`.
    pub fn predict(&mut self, (q, v): (f64, f64)) -> MassPrediction {
        (self.z[0], self.zd[0]) = (q, v);
        let (ch, n) = (&self.chain, self.chain.n);
        let mut b = [0.0; MAX_CHAIN];
        for (i, bi) in b.iter_mut().enumerate().take(n) {
            *bi = ch.f0[i] - ch.mul(&ch.k, &self.z, i) - ch.mul(&ch.c, &self.zd, i);
        }
        self.u_star = apply(n, &self.inv, &b);
        MassPrediction {
            q: q + self.dt * v,
            q_dot: v,
            u: self.u_star[0],
            a_eff: 1.0 / self.inv[0][0],
        }
    }

    /// After λ: the chain at t_{n+1} (and ż_{n+1/2}).
    pub fn finish(&mut self, lambda: f64) {
        let (n, dt) = (self.chain.n, self.dt);
        let a = unknowns(n, &self.u_star, &self.inv, lambda);
        for (i, ai) in a.iter().enumerate().take(n) {
            self.zd[i] += dt * ai;
            self.z[i] += dt * self.zd[i];
        }
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
mod tests {
    //! The chain's step against the closed-form held pantograph
    //! (docs/lines.md L9–L11): the head held on a rigid surface (the wire
    //! replaced by a rigid support), the contact force found each step as
    //! the contact problem finds it with a rigid beam (`end` placement:
    //! g_free = −(q̃ + c_d u★), W = c_d/A_q, bilateral λ = −g_free/W).

    use super::*;
    use crate::analytic::{Pantograph, PantographStep, SurfaceContact};

    /// Two independent ways of forming a static force or frequency: a few
    /// hundred ulps of round-off in 3 × 3 solves and eigen decompositions.
    const ROUND_OFF: f64 = 1e-12;

    /// Newmark's (trapezoidal) error is second order: the measured order of
    /// the max error on Δt halvings is within this of 2 (measured 1.99–2.00
    /// in the asymptotic range used).
    const ORDER_BAND: f64 = 0.05;

    fn newmark() -> GenAlphaParams {
        GenAlphaParams {
            alpha_m: 0.0,
            alpha_f: 0.0,
            beta: 0.25,
            gamma: 0.5,
        }
    }

    /// Chung–Hulbert generalized-α at ρ∞ = 0.8.
    fn gen_alpha_08() -> GenAlphaParams {
        let r = 0.8;
        let (am, af) = ((2.0 * r - 1.0) / (r + 1.0), r / (r + 1.0));
        let gamma = 0.5 - am + af;
        GenAlphaParams {
            alpha_m: am,
            alpha_f: af,
            beta: 0.25 * (1.0 - am + af) * (1.0 - am + af),
            gamma,
        }
    }

    fn props(m: &[f64], k: &[f64], c: &[f64], uplift: f64) -> ChainProps {
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
    fn chains() -> Vec<(&'static str, ChainProps)> {
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

    fn held(p: &ChainProps) -> Pantograph {
        Pantograph::new(
            p.masses(),
            p.stiffnesses(),
            p.dampings(),
            p.uplift,
            SurfaceContact::Held,
        )
        .unwrap()
    }

    /// Step the chain of `p` (no gravity) with the head held at the rigid
    /// surface after an uplift step ΔF at t = 0, to `t_end` at `dt`: the
    /// samples (t_{n+1}, lower masses' z, contact force λ_{n+1}).
    fn held_run(
        p: &ChainProps,
        params: GenAlphaParams,
        df: f64,
        dt: f64,
        t_end: f64,
    ) -> Vec<(f64, [f64; MAX_CHAIN], f64)> {
        let chain = Chain::new(p, 1.0, 0.0);
        let mut ch = ChainGenAlpha::new(chain, params, dt, 0.0);
        let n = p.n;
        ch.chain.f0[n - 1] += df;
        ch.za[n - 1] = df / p.masses[n - 1];
        let c_d = params.beta * dt * dt;
        let (mut q, mut v, mut a) = (0.0, 0.0, 0.0);
        let steps = (t_end / dt).round() as usize;
        let mut out = Vec::with_capacity(steps);
        for s in 0..steps {
            let pred = ch.predict((q, v, a));
            // rigid surface: g = 0 − q_{n+1}, g_free = −(q̃ + c_d u★), W = c_d/A_q
            let (g_free, w) = (-(pred.q + c_d * pred.u), c_d / pred.a_eff);
            let lambda = -g_free / w;
            let acc = pred.unknown(lambda);
            q = pred.q + c_d * acc;
            v = pred.q_dot + params.gamma * dt * acc;
            a = acc;
            ch.finish(lambda);
            out.push(((s + 1) as f64 * dt, ch.z, lambda));
        }
        out
    }

    /// A held run of each method that carries the chain: (t_{n+1}, z,
    /// λ_{n+1}) samples of [`held_run`]'s kind, each method's head held by
    /// its own gap row (q_{n+1} = q̃ + c_d u = 0 with u = u★ − λ/A_q, so
    /// λ = A_q (u★ + q̃/c_d); c_d = 1 for Bathe's increments, θΔt for
    /// Moreau–Jean's velocity change, Δt² for central difference), and the
    /// lag of its λ behind t_{n+1} in steps (`System::force_lag`).
    type Run = Vec<(f64, [f64; MAX_CHAIN], f64)>;

    fn held_bathe(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
        let n = p.n;
        let mut ch = ChainBathe::new(Chain::new(p, 1.0, 0.0), 0.5, dt, 0.0);
        ch.chain.f0[n - 1] += df;
        ch.za[n - 1] = df / p.masses[n - 1];
        let steps = (t_end / dt).round() as usize;
        (0..steps)
            .map(|s| {
                let pred = ch.first((ch.z[0], ch.zd[0], ch.za[0]));
                ch.end_first(pred.a_eff * (pred.u + pred.q));
                let pred = ch.second();
                let lambda = pred.a_eff * (pred.u + pred.q);
                ch.end_second(lambda);
                ((s + 1) as f64 * dt, ch.z, lambda)
            })
            .collect()
    }

    fn held_moreau_jean(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
        let (n, theta) = (p.n, 0.5);
        let mut ch = ChainMoreauJean::new(Chain::new(p, 1.0, 0.0), theta, dt);
        ch.chain.f0[n - 1] += df;
        let steps = (t_end / dt).round() as usize;
        (0..steps)
            .map(|s| {
                let pred = ch.predict((ch.z[0], ch.zd[0]));
                let impulse = pred.a_eff * (pred.u + pred.q / (theta * dt));
                ch.finish(impulse);
                ((s + 1) as f64 * dt, ch.z, impulse / dt)
            })
            .collect()
    }

    fn held_central(p: &ChainProps, df: f64, dt: f64, t_end: f64) -> Run {
        let n = p.n;
        let mut ch = ChainCentral::new(Chain::new(p, 1.0, 0.0), dt);
        ch.chain.f0[n - 1] += df;
        // ż_{−1/2} = ż₀ − (Δt/2) z̈₀
        ch.zd[n - 1] = -0.5 * dt * df / p.masses[n - 1];
        let steps = (t_end / dt).round() as usize;
        (0..steps)
            .map(|s| {
                let pred = ch.predict((ch.z[0], ch.zd[0]));
                let lambda = pred.a_eff * (pred.u + pred.q / (dt * dt));
                ch.finish(lambda);
                ((s + 1) as f64 * dt, ch.z, lambda)
            })
            .collect()
    }

    /// Max errors of a held run against L11 (state-space exponential): in
    /// the lower masses' z relative to the static change, and in λ (at
    /// t − lag·Δt, where the method's balance puts it) relative to ΔF.
    fn errors_of(p: &ChainProps, df: f64, dt: f64, lag: f64, run: Run) -> (f64, f64) {
        let panto = held(p);
        let resp = panto.step(PantographStep::Uplift(df)).unwrap();
        let (z0, _) = resp.initial();
        let scale = (&resp.z_static - &z0).amax();
        let (mut ez, mut ef) = (0.0_f64, 0.0_f64);
        for (t, z, lambda) in run {
            let (zr, _) = resp.state_space(t);
            for i in 1..p.n {
                ez = ez.max((z[i] - (zr[i - 1] - z0[i - 1])).abs() / scale);
            }
            let (zf, vf) = resp.state_space(t - lag * dt);
            ef = ef.max((lambda - resp.contact_force(&zf, &vf)).abs() / df.abs());
        }
        (ez, ef)
    }

    fn errors(p: &ChainProps, params: GenAlphaParams, df: f64, dt: f64, t_end: f64) -> (f64, f64) {
        errors_of(
            p,
            df,
            dt,
            params.alpha_f,
            held_run(p, params, df, dt, t_end),
        )
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

    #[test]
    fn the_head_sees_the_chains_dynamic_stiffness() {
        // A_q = 1/(A⁻¹)₁₁ against the Schur complement of the lower block
        // for two masses: A₁₁ − A₁₂²/A₂₂
        let p = props(&[6.0, 11.0], &[7000.0, 60.0], &[15.0, 40.0], 100.0);
        let (params, dt) = (gen_alpha_08(), 1e-3);
        let ch = ChainGenAlpha::new(Chain::new(&p, 1.0, 0.0), params, dt, 0.0);
        let entry = |i: usize, j: usize, c: &Chain| {
            (1.0 - params.alpha_f)
                * (params.gamma * dt * c.c[i][j] + params.beta * dt * dt * c.k[i][j])
                + if i == j {
                    (1.0 - params.alpha_m) * c.m[i]
                } else {
                    0.0
                }
        };
        let c = &ch.chain;
        let schur = entry(0, 0, c) - entry(0, 1, c) * entry(1, 0, c) / entry(1, 1, c);
        assert!((ch.a_eff() - schur).abs() <= ROUND_OFF * schur);
    }

    #[test]
    fn held_uplift_steps_match_the_closed_form_at_second_order() {
        let df = 20.0;
        for (name, p) in chains() {
            let modes = held(&p).modes().unwrap();
            let t_min = 2.0 * std::f64::consts::PI / modes.omega.last().unwrap();
            let t_end = 3.0 * 2.0 * std::f64::consts::PI / modes.omega[0];
            type Errors = Box<dyn Fn(f64) -> (f64, f64)>;
            let schemes: [(&str, Errors); 5] = [
                (
                    "newmark",
                    Box::new(move |dt| errors(&p, newmark(), df, dt, t_end)),
                ),
                (
                    "gen-α ρ∞ = 0.8",
                    Box::new(move |dt| errors(&p, gen_alpha_08(), df, dt, t_end)),
                ),
                (
                    "bathe",
                    Box::new(move |dt| errors_of(&p, df, dt, 0.0, held_bathe(&p, df, dt, t_end))),
                ),
                (
                    "moreau_jean θ = ½",
                    Box::new(move |dt| {
                        errors_of(&p, df, dt, 0.5, held_moreau_jean(&p, df, dt, t_end))
                    }),
                ),
                (
                    "central_difference",
                    Box::new(move |dt| errors_of(&p, df, dt, 1.0, held_central(&p, df, dt, t_end))),
                ),
            ];
            for (scheme, errors) in schemes {
                let e: Vec<(f64, f64)> = [40.0, 80.0, 160.0]
                    .iter()
                    .map(|per| errors(t_min / per))
                    .collect();
                let order_z = (e[1].0 / e[2].0).log2();
                let order_f = (e[1].1 / e[2].1).log2();
                println!(
                    "{name}, {scheme}: z errors {:.3e} {:.3e} {:.3e} (order {order_z:.3}), \
                     λ errors {:.3e} {:.3e} {:.3e} (order {order_f:.3})",
                    e[0].0, e[1].0, e[2].0, e[0].1, e[1].1, e[2].1
                );
                assert!(
                    (order_z - 2.0).abs() <= ORDER_BAND,
                    "{name} {scheme}: z order {order_z}"
                );
                assert!(
                    (order_f - 2.0).abs() <= ORDER_BAND,
                    "{name} {scheme}: λ order {order_f}"
                );
            }
        }
    }

    #[test]
    fn the_held_two_mass_chain_rings_at_its_natural_frequency() {
        // one degree of freedom once held: ω² = (k₁ + k₂)/m₂ (L10); the
        // trapezoidal rule rings at ω_h = (2/Δt) atan(ωΔt/2) exactly
        let p = props(&[6.0, 11.0], &[7000.0, 60.0], &[0.0, 0.0], 100.0);
        let omega = held(&p).modes().unwrap().omega[0];
        assert!((omega - ((7000.0_f64 + 60.0) / 11.0).sqrt()).abs() <= ROUND_OFF * omega);
        let dt = 2.0 * std::f64::consts::PI / omega / 100.0;
        let df = 20.0;
        let z_after = df / (7000.0 + 60.0);
        let run = held_run(
            &p,
            newmark(),
            df,
            dt,
            40.0 * 2.0 * std::f64::consts::PI / omega,
        );
        // upward crossings of z₂ − z_s by linear interpolation
        let mut crossings = Vec::new();
        let mut prev = (0.0, -z_after);
        for (t, z, _) in &run {
            let y = z[1] - z_after;
            if prev.1 < 0.0 && y >= 0.0 {
                crossings.push(prev.0 + (t - prev.0) * (-prev.1) / (y - prev.1));
            }
            prev = (*t, y);
        }
        let periods = (crossings.len() - 1) as f64;
        let measured =
            2.0 * std::f64::consts::PI * periods / (crossings.last().unwrap() - crossings[0]);
        let discrete = 2.0 / dt * (omega * dt / 2.0).atan();
        println!(
            "ω = {omega:.9} rad/s, measured {measured:.9}, trapezoidal {discrete:.9} \
             ({:.2e}, {:.2e})",
            measured / omega - 1.0,
            measured / discrete - 1.0
        );
        // the measured frequency is the scheme's to the crossing interpolation
        // (O((ωΔt)³) per crossing over 40 periods: below 1e-6), and it is ω
        // to the scheme's period error (ωΔt)²/12 = 3.3e-4 at 100 steps per period
        assert!((measured / discrete - 1.0).abs() <= 1e-6);
        let period_error = (omega * dt).powi(2) / 12.0;
        assert!((measured / omega - 1.0).abs() <= 1.05 * period_error);
    }
}
