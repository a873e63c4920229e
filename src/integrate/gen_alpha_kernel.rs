//! The generalized-α step (MODEL §5, "One step, spelled out") for one run
//! or several side by side: the one kernel that both a run alone
//! ([`super::GenAlpha`], one lane) and a batch of runs sharing their
//! effective matrix ([`super::Batch`], L lanes) step with, so the two
//! cannot drift apart and a run in a batch is bit-identical to the run
//! alone (`tests/batch.rs` compares the bytes).
//!
//! M and K do not couple the beam with the masses (only the contact does),
//! so the effective matrix `A = (1 − α_m)M + (1 − α_f)γΔt C + (1 − α_f)βΔt²K`
//! is the banded beam block, factored once, plus one scalar A_q per mass.
//! Without damping (MODEL §1, eq. 1) the block is `(1 − α_m)M +
//! (1 − α_f)βΔt²K` and the residual is the one band product below; with a
//! damping matrix C (docs/lines.md §10.4) the block gains
//! `c_c C`, c_c = (1 − α_f)γΔt, and the residual one more product,
//! [`Kernel::damp`]. A damped run steps alone (its batch key is `None`).
//!
//! A step is four phases, each run's own where it is per run and all lanes
//! at once where it is per row: [`Kernel::load`] (place the carriers,
//! scatter the moving forces and contact directions), [`Kernel::solve`]
//! (one fused banded sweep for `A⁻¹F` and `A⁻¹r_f` of every contact and
//! lane), [`Kernel::contact`] (the mass predictions and the contact problem
//! through the run's [`System`]), [`Kernel::update`] (the new state and the
//! next step's predictors, one pass over memory) and [`Kernel::finish`]
//! (the contact columns' part of h, the mass dofs). Nothing is allocated
//! and the work is O(n) per lane.
//!
//! How lanes are laid out and why the residual takes one band product are
//! on `Kernel`; the damping term on `Damping`.

#![allow(non_snake_case)]

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt, SymBand};
use crate::model::beam::BeamModel;
use crate::scene::{GenAlphaParams, Placement};

use super::gen_alpha_update::{MAX_COLUMNS, Pass, UpdateCoefs};
use super::mass_step::{Coefficients, Effective, Kinematics, MassSteps, Predicted, Stage};
use super::state::State;
use super::step_map::Lanes;
use super::step_map::{StepMap, VelocityPrediction};
use super::system::{Initial, System};

pub(crate) use super::gen_alpha_update::MAX_LANES;

/// Generalized-α's step of a mass dof (MODEL §2, §5; docs/lines.md P3 for
/// a chain's dofs): the unknown is its acceleration ü_{n+1},
///
/// ```text
///   A ü = f₀ − α_m m ü_n − c((1 − α_f)ṽ + α_f v_n) − k((1 − α_f)q̃ + α_f q_n) − λ e₁,
///   A = (1 − α_m)m + (1 − α_f)γΔt c + (1 − α_f)βΔt² k,
///   q̃ = q_n + Δt v_n + (½ − β)Δt² ü_n,  ṽ = v_n + (1 − γ)Δt ü_n,
/// ```
///
/// then q_{n+1} = q̃ + βΔt² ü, v_{n+1} = ṽ + γΔt ü (`mass_step.rs`
/// applies it to a single mass and to a chain alike).
#[derive(Debug, Clone, Copy)]
pub(crate) struct GenAlphaMass {
    /// The family's parameters.
    pub(crate) p: GenAlphaParams,
    /// Δt, s.
    pub(crate) dt: f64,
}

impl Stage for GenAlphaMass {
    type Dof = Kinematics;

    fn matrix(&self) -> Coefficients {
        let (p, dt) = (self.p, self.dt);
        Coefficients {
            c_m: 1.0 - p.alpha_m,
            c_c: (1.0 - p.alpha_f) * p.gamma * dt,
            c_k: (1.0 - p.alpha_f) * p.beta * dt * dt,
        }
    }

    #[inline]
    fn predict(&self, d: &mut Kinematics) -> Predicted {
        let (p, dt) = (self.p, self.dt);
        let af = p.alpha_f;
        let c_pred = (0.5 - p.beta) * dt * dt;
        let q = d.z + dt * d.zd + c_pred * d.za;
        let q_dot = d.zd + (1.0 - p.gamma) * dt * d.za;
        Predicted {
            q,
            q_dot,
            c_at: (1.0 - af) * q_dot + af * d.zd,
            // a deliberate defect of the test build (`crate::defects`)
            k_at: if crate::defects::on(crate::defects::Defect::PredictorSpring) {
                (1.0 - af) * q
            } else {
                (1.0 - af) * q + af * d.z
            },
        }
    }

    #[inline]
    fn load(&self, f0: f64, m: f64, d: &Kinematics, c_term: f64, k_term: f64) -> f64 {
        f0 - self.p.alpha_m * m * d.za - c_term - k_term
    }

    #[inline]
    fn update(&self, d: &mut Kinematics, _: &Predicted, acc: f64) {
        let (dt, beta, gamma) = (self.dt, self.p.beta, self.p.gamma);
        let (bdt2, c_pred) = (beta * dt * dt, (0.5 - beta) * dt * dt);
        let a = d.za;
        d.z += dt * d.zd + c_pred * a + bdt2 * acc;
        d.zd += dt * ((1.0 - gamma) * a + gamma * acc);
        d.za = acc;
    }
}

/// What generalized-α keeps per run for its mass dofs: their state and
/// predictions, and the effective matrix over each body.
struct MassLane {
    masses: MassSteps<Kinematics>,
    effective: Vec<Effective>,
}

/// What a damped run's step adds.
///
/// **Damping.** C enters at the α-weighted velocity
/// `(1 − α_f)v_{n+1} + α_f v_n = (1 − α_f)γΔt a_{n+1} + w`,
/// `w = v_n + (1 − α_f)(1 − γ)Δt a_n`: the first term goes into A, and
/// `−C w` into F. With `A a_n` now holding `c_c C a_n` too, the same
/// rearrangement gives
///
/// ```text
///   F = h − K ũ − C w̃,   w̃ = w − α′ c_c a_n = v_n + κ a_n,
///   κ = (1 − α_f)(1 − γ)Δt − α′ c_c,
/// ```
///
/// and [`Kernel::damp`] subtracts `C w̃` from h before the solve (so the
/// solve's b₀, hence the next A a_n, includes it). O(n·p) per step, no
/// allocation; a run without C skips it.
struct Damping {
    /// C, the run's damping matrix.
    c: SymBand,
    /// κ = (1 − α_f)(1 − γ)Δt − α′ c_c, s.
    kappa: f64,
    /// w̃ of one lane, m/s (scratch).
    w: Vec<f64>,
    /// C w̃ of one lane, N (scratch).
    cw: Vec<f64>,
}

/// The generalized-α step of L runs sharing A (module docs).
///
/// **Lanes.** With L runs the beam vectors hold the runs interleaved
/// (`x[i·L + l]`) and a right-hand side has k·L columns (column c of run l
/// at c·L + l, [`Lanes`]); with L = 1 that is a run's own layout. Every
/// run's columns get the same operations in the same order whatever L: the
/// banded kernel is one generic kernel with more columns
/// ([`BandedLdlt::solve_affine_lanes`]), and the update pass is
/// [`UpdateCoefs::row`] per element (or its AVX2 transcription, operation
/// for operation). Rust does not contract a·b + c into fused multiply–adds,
/// so vectorized code rounds as scalar code does.
///
///
/// **The residual in one band product.** F = f − α_m M a_n − K u with
/// u = (1 − α_f) d̃ + α_f d_n takes two band products; with
/// M a_n = (A a_n − c_k K a_n)/(1 − α_m), c_k = (1 − α_f)βΔt²,
///
/// ```text
///   F = (f − α′ A a_n) − K (u − α′ c_k a_n) = h − K ũ,   α′ = α_m/(1 − α_m),
/// ```
///
/// one product, because A a_n needs none: it is the right-hand side the last
/// step solved, b₀ + Σ λ_c s_c r_f,c. The two differ by that solve's backward
/// error, ε|A||a_n|: an error every solve makes anyway, and which a's own
/// round-off already carries into the step. h and ũ are formed in the update
/// pass; the banded kernel computes h − Kũ row by row inside its forward
/// sweep ([`BandedLdlt::solve_affine`]).
pub(crate) struct Kernel {
    p: GenAlphaParams,
    /// Δt, s.
    dt: f64,
    /// Beam dofs n.
    n: usize,
    /// Right-hand-side columns per run.
    k: usize,
    /// Runs side by side.
    lanes: usize,
    ldlt: BandedLdlt,
    /// α′ = α_m/(1 − α_m).
    alpha_p: f64,
    /// c_k = (1 − α_f)βΔt², s².
    c_k: f64,
    /// The damping matrix's share of the step (`None`: no damping).
    damping: Option<Damping>,
    /// Per lane, in lane order.
    masses: Vec<MassLane>,
    // interleaved n × L
    /// Beam accelerations a_n, m/s².
    a: Vec<f64>,
    /// d̃ of the next step, m.
    d_pred: Vec<f64>,
    /// ũ = u − α′ c_k a_n with u = (1 − α_f) d̃ + α_f d_n (`Kernel`'s docs), m.
    u_shift: Vec<f64>,
    /// h = f − α′ A a_n, N (`Kernel`'s docs).
    h: Vec<f64>,
    /// Column 0 of the last step's right-hand side before the solve, N.
    b0: Vec<f64>,
    /// n × k × L right-hand sides: column 0 the free step, column 1 + c
    /// the direction s_c r_b of contact c.
    rhs: Vec<f64>,
}

impl Kernel {
    /// Factor A of `beam` (with its damping matrix `damping`, if any) once
    /// for `lanes` runs of `k` columns each.
    pub(crate) fn new(
        p: GenAlphaParams,
        beam: &BeamModel,
        damping: Option<&SymBand>,
        dt: f64,
        k: usize,
        lanes: usize,
    ) -> Result<Self> {
        let n = beam.n;
        let c_k = (1.0 - p.alpha_f) * p.beta * dt * dt;
        let mut A = beam.mass.combine(1.0 - p.alpha_m, &beam.stiffness, c_k);
        let alpha_p = p.alpha_m / (1.0 - p.alpha_m);
        let damping = damping.map(|c| {
            let c_c = (1.0 - p.alpha_f) * p.gamma * dt;
            A = A.combine(1.0, c, c_c);
            Damping {
                c: c.clone(),
                kappa: (1.0 - p.alpha_f) * (1.0 - p.gamma) * dt - alpha_p * c_c,
                w: vec![0.0; n],
                cw: vec![0.0; n],
            }
        });
        let ldlt = BandedLdlt::factor(&A)?;
        Ok(Kernel {
            damping,
            p,
            dt,
            n,
            k,
            lanes,
            ldlt,
            alpha_p,
            c_k,
            masses: Vec::with_capacity(lanes),
            a: vec![0.0; n * lanes],
            d_pred: vec![0.0; n * lanes],
            u_shift: vec![0.0; n * lanes],
            h: vec![0.0; n * lanes],
            b0: vec![0.0; n * lanes],
            rhs: vec![0.0; n * k * lanes],
        })
    }

    /// True when the banded kernel for this many lanes exists.
    pub(crate) fn supported(&self) -> bool {
        self.lanes == 1 || self.ldlt.has_lanes(self.k, self.lanes)
    }

    /// Set lane `l` (the next one, in order) from its consistent initial
    /// state: the mass dofs' A_q and q̈₀, and the first predictors
    /// d̃ = d + Δt v + (½ − β)Δt² a, u = (1 − α_f) d̃ + α_f d and the
    /// residual's operands ũ and h (`Kernel`'s docs), with A a₀ formed
    /// explicitly (the only time it is: afterwards A a_n is the last
    /// solve's right-hand side). `d`, `v` are the run's beam state at t = 0.
    pub(crate) fn start(&mut self, sys: &System, d: &[f64], v: &[f64], init: Initial) {
        let l = self.masses.len();
        let GenAlphaParams {
            alpha_m: am,
            alpha_f: af,
            beta,
            gamma,
        } = self.p;
        let (dt, c_k, L) = (self.dt, self.c_k, self.lanes);
        let stage = GenAlphaMass { p: self.p, dt };
        let mut masses = MassSteps::<Kinematics>::new(&sys.physics.masses);
        for (j, &aq) in init.aq.iter().enumerate() {
            masses.head_mut(j).za = aq;
        }
        let effective = MassSteps::effective(&stage, &sys.physics.masses);
        let beam = sys.beam();
        let c_pred = (0.5 - beta) * dt * dt;
        let mut a_a = vec![0.0; self.n];
        beam.mass.mul_acc(&init.a, 1.0 - am, &mut a_a);
        beam.stiffness.mul_acc(&init.a, c_k, &mut a_a);
        if let Some(dm) = &self.damping {
            dm.c.mul_acc(&init.a, (1.0 - af) * gamma * dt, &mut a_a);
        }
        for i in 0..self.n {
            let dp = d[i] + dt * v[i] + c_pred * init.a[i];
            let u = (1.0 - af) * dp + af * d[i];
            let at = i * L + l;
            self.a[at] = init.a[i];
            self.d_pred[at] = dp;
            self.u_shift[at] = u - self.alpha_p * c_k * init.a[i];
            self.h[at] = beam.load[i] - self.alpha_p * a_a[i];
        }
        self.masses.push(MassLane { masses, effective });
    }

    /// t_{n+1} and the force time t_{n+1−α_f} of the step from `st`.
    fn times(&self, st: &State) -> (f64, f64) {
        let t1 = st.next_time(self.dt);
        (t1, t1 - self.p.alpha_f * self.dt)
    }

    /// Clear the right-hand sides (first, each step).
    pub(crate) fn clear(&mut self) {
        self.rhs[..self.n * self.k * self.lanes].fill(0.0);
    }

    /// Lane `l`'s loads: its carriers placed (moving forces and contact
    /// directions at t_{n+1−α_f}, gap rows at t_{n+1}), the moving forces
    /// into its column 0 and the contact directions s_c r_f,c into its
    /// columns 1 + c.
    pub(crate) fn load(&mut self, l: usize, sys: &mut System, st: &State) {
        let (t1, tf) = self.times(st);
        sys.place(tf, tf, t1);
        let lanes = Lanes {
            count: self.lanes,
            lane: l,
        };
        let n = self.n * self.k * self.lanes;
        sys.scatter_loads_in(&mut self.rhs[..n], self.k, lanes, 1.0);
    }

    /// The damping's share of every lane's residual (`Damping`'s docs,
    /// "Damping"): h −= C w̃, w̃ = v_n + κ a_n, before [`Kernel::solve`].
    /// `v` is the lanes' beam velocities (interleaved). Nothing without C.
    pub(crate) fn damp(&mut self, v: &[f64]) {
        let Some(dm) = &mut self.damping else { return };
        let (n, L) = (self.n, self.lanes);
        for l in 0..L {
            for i in 0..n {
                dm.w[i] = v[i * L + l] + dm.kappa * self.a[i * L + l];
            }
            dm.cw.fill(0.0);
            dm.c.mul_acc(&dm.w, 1.0, &mut dm.cw);
            for i in 0..n {
                self.h[i * L + l] -= dm.cw[i];
            }
        }
    }

    /// a★ = A⁻¹(F + moving forces) and z_c = A⁻¹(s_c r_f,c) of every lane
    /// in one sweep, F = h − K ũ formed inside its forward pass (module
    /// docs). `beam` is any lane's (they share K).
    pub(crate) fn solve(&mut self, beam: &BeamModel) {
        let (n, k, L) = (self.n, self.k, self.lanes);
        let residual = Affine {
            h: &self.h[..n * L],
            k: &beam.stiffness,
            u: &self.u_shift[..n * L],
        };
        let rhs = &mut self.rhs[..n * k * L];
        if L == 1 {
            self.ldlt.solve_affine(rhs, k, &residual, &mut self.b0[..n]);
        } else {
            let solved = self
                .ldlt
                .solve_affine_lanes(rhs, k, L, &residual, &mut self.b0[..n * L]);
            assert!(solved, "a batch is only built for compiled kernels");
        }
    }

    /// x ← A⁻¹x for one vector (a run's one-off solves: the droppers'
    /// responses, `dropper.rs`).
    pub(crate) fn solve_one(&self, x: &mut [f64]) {
        self.ldlt.solve(x);
    }

    /// After [`Kernel::contact`] of a run alone: the tension-only droppers'
    /// slack corrections μ_d into the free solution, a★ += Σ μ_d A'⁻¹r_d
    /// (`dropper.rs`),
    /// so the update pass takes them with the contacts'. No-op without them.
    pub(crate) fn add_dropper_responses(&mut self, sys: &System) {
        if sys.physics.droppers.rows() == 0 {
            return;
        }
        debug_assert_eq!(self.lanes, 1, "droppers step alone");
        let (n, k) = (self.n, self.k);
        sys.physics
            .droppers
            .add_responses(&mut self.rhs[..n * k], k);
    }

    /// Lane `l`'s contact problem: its mass dofs' predictions, and the
    /// [`StepMap`] of the step handed to its system (MODEL §5: c_d = βΔt²,
    /// c_v = γΔt, ṽ = v_n + (1 − γ)Δt a_n), which sets its multipliers.
    pub(crate) fn contact(&mut self, l: usize, sys: &mut System, st: &State) -> Result<()> {
        let (n, L, dt) = (self.n, self.lanes, self.dt);
        let GenAlphaParams {
            alpha_f: af,
            beta,
            gamma,
            ..
        } = self.p;
        let ml = &mut self.masses[l];
        let stage = GenAlphaMass { p: self.p, dt };
        ml.masses.begin(st);
        ml.masses
            .predict(&stage, &ml.effective, &sys.physics.masses);
        let alpha_weight = match sys.law.placement {
            Placement::End => 0.0,
            Placement::Alpha => af,
        };
        let map = StepMap {
            solved: &self.rhs[..n * self.k * L],
            c_d: beta * dt * dt,
            c_v: gamma * dt,
            d_pred: &self.d_pred[..n * L],
            v_pred: VelocityPrediction::Shifted {
                shift: &self.a[..n * L],
                coef: (1.0 - gamma) * dt,
            },
            alpha_weight,
            masses: ml.masses.predictions(),
        };
        sys.solve_contact_in(&map, Lanes { count: L, lane: l }, st)
    }

    /// The update pass of every lane (`Kernel`'s docs): a = a★ + Σ λ_c z_c,
    /// d = d̃ + βΔt² a, v = v_n + Δt((1−γ)a_n + γa), and in the same pass
    /// the next step's d̃, ũ and h. `load` is the beam's distributed load f
    /// (any lane's: they share it), `d`, `v` the lanes' beam state
    /// (interleaved), `lambda[l]` lane l's multipliers.
    pub(crate) fn update(&mut self, load: &[f64], d: &mut [f64], v: &mut [f64], lambda: &[&[f64]]) {
        let (n, k, L) = (self.n, self.k, self.lanes);
        let GenAlphaParams {
            alpha_f: af,
            beta,
            gamma,
            ..
        } = self.p;
        let dt = self.dt;
        let c = UpdateCoefs {
            dt,
            gamma,
            bdt2: beta * dt * dt,
            c_pred: (0.5 - beta) * dt * dt,
            alpha_f: af,
            c_shift: self.alpha_p * self.c_k,
            alpha_p: self.alpha_p,
        };
        let pass = Pass {
            n,
            rhs: &self.rhs[..n * k * L],
            d: &mut d[..n * L],
            v: &mut v[..n * L],
            a: &mut self.a[..n * L],
            dp: &mut self.d_pred[..n * L],
            u: &mut self.u_shift[..n * L],
            h: &mut self.h[..n * L],
            b0: &self.b0[..n * L],
            load,
        };
        if k > MAX_COLUMNS {
            // a run alone with more than five contacts: the scalar pass
            debug_assert_eq!(L, 1, "a batch has at most four columns");
            pass.scalar(k, lambda[0], c);
            return;
        }
        // λ of column c of lane l at lk[c][l] (padding columns 0):
        // contiguous across lanes
        let mut lk = [[0.0; MAX_LANES]; MAX_COLUMNS];
        for (l, lam) in lambda.iter().enumerate() {
            for (cc, lkc) in lk.iter_mut().enumerate().take(k).skip(1) {
                lkc[l] = lam.get(cc - 1).copied().unwrap_or(0.0);
            }
        }
        macro_rules! update {
            ($(($k:literal, $l:literal, $kl:literal)),*) => {
                match (k, L) {
                    $(($k, $l) => pass.dispatch::<$k, $l, $kl>(&lk, c),)*
                    _ => unreachable!("a kernel exists for every (k, lanes) built"),
                }
            };
        }
        update!(
            (2, 1, 2),
            (2, 2, 4),
            (2, 3, 6),
            (2, 4, 8),
            (2, 5, 10),
            (2, 6, 12),
            (2, 7, 14),
            (2, 8, 16),
            (4, 1, 4),
            (4, 2, 8),
            (4, 3, 12),
            (4, 4, 16),
            (6, 1, 6)
        );
    }

    /// Lane `l` after the update pass: the contact columns' part of the
    /// next h (A a_{n+1} = b₀ + Σ λ_c s_c r_f,c, `Kernel`'s docs), and its mass
    /// dofs q, q̇, q̈ from their unknowns u_q = u★_q − λ/A_q.
    pub(crate) fn finish(&mut self, l: usize, sys: &System, st: &mut State) {
        let (n, L, dt) = (self.n, self.lanes, self.dt);
        let lanes = Lanes { count: L, lane: l };
        sys.scatter_contact_directions_in(&mut self.h[..n * L], lanes, -self.alpha_p);
        let ml = &mut self.masses[l];
        let stage = GenAlphaMass { p: self.p, dt };
        ml.masses.finish(
            &stage,
            &ml.effective,
            &sys.physics.masses,
            sys.multipliers(),
        );
        ml.masses.end(st);
    }

    /// Keep the lanes `keep` (ascending) and drop the others, moving the
    /// kept lanes' data down in place; `d`, `v` are the lanes' beam state,
    /// moved likewise.
    pub(crate) fn retire(&mut self, keep: &[usize], d: &mut [f64], v: &mut [f64]) {
        let (old, new) = (self.lanes, keep.len());
        let n = self.n;
        for x in [
            d,
            v,
            &mut self.a[..],
            &mut self.d_pred[..],
            &mut self.u_shift[..],
            &mut self.h[..],
            &mut self.b0[..],
        ] {
            // destination i·new + j ≤ source i·old + keep[j]: in place, forward
            for i in 0..n {
                for (j, &l) in keep.iter().enumerate() {
                    x[i * new + j] = x[i * old + l];
                }
            }
        }
        for l in (0..old).rev() {
            if !keep.contains(&l) {
                self.masses.remove(l);
            }
        }
        self.lanes = new;
    }
}
