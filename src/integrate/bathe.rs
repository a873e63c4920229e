//! Bathe's composite scheme (Bathe & Baig 2005; MODEL §9.1): a trapezoidal
//! sub-step to t + γ_BΔt, then a three-point backward-Euler sub-step to
//! t + Δt.
//!
//! ```text
//!   sub-step 1   M a₁ + K d₁ = f₁,  d₁ = d_n + (h₁/2)(v_n + v₁),  v₁ = v_n + (h₁/2)(a_n + a₁),  h₁ = γ_BΔt
//!   sub-step 2   v_{n+1} = c₁d_n + c₂d₁ + c₃d_{n+1},  a_{n+1} = c₁v_n + c₂v₁ + c₃v_{n+1},
//!                M a_{n+1} + K d_{n+1} = f_{n+1}
//!                c₁ = (1 − γ_B)/(γ_BΔt), c₂ = −1/((1 − γ_B)γ_BΔt), c₃ = (2 − γ_B)/((1 − γ_B)Δt)
//! ```
//!
//! **Each sub-step solves for a correction to a predictor**, the way
//! generalized-α solves for an acceleration. With c₀ = 2/h₁, A₁ = K + c₀²M,
//! A₂ = K + c₃²M (two constant matrices, each factored once per run), and
//! c₁ + c₂ + c₃ = 0:
//!
//! ```text
//!   sub-step 1   p₁ = h₁v_n + (h₁²/4)a_n,   d̃ = d_n + p₁,   ṽ = v_n + (h₁/2)a_n
//!                A₁ e = f₁ − K d̃,   d₁ = d̃ + e,   v₁ = ṽ + c₀e   (a₁ = c₀²e),   Δ₁ = p₁ + e
//!   sub-step 2   s = c₁v_n + c₂v₁ − c₃c₁Δ₁,   d̃ = d₁ − s/c₃²,   ṽ = −c₁Δ₁ − s/c₃
//!                A₂ e = f_{n+1} − K d̃,   d_{n+1} = d̃ + e,   v_{n+1} = ṽ + c₃e,   a_{n+1} = c₃²e
//! ```
//!
//! Why corrections and not the displacements themselves: see [`Bathe`].
//! The gap condition is imposed at the end of each sub-step (`d = d̃ + e`,
//! `v = ṽ + c e` through the [`System`]); the force recorded is the second
//! sub-step's. Second order; strongly damps unresolved high frequencies
//! (spectral radius → 0 as ωΔt → ∞ for γ_B = ½).

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt};

use super::mass_step::{Coefficients, Dof, Effective, MassSteps, Predicted, Stage};
use super::state::State;
use super::step_map::{StepMap, VelocityPrediction, combine};
use super::stepper::Stepper;
use super::system::{Initial, System};
use crate::model::banded::rhs_columns;

/// A Bathe stepper for one run.
///
/// Why each sub-step solves for a correction (Δ₁ = d₁ − d_n is formed from
/// its parts): solving for the displacement itself, `A₁ d₁ = f₁ + M(c₀²d_n + 2c₀v_n + a_n)` and
/// `A₂ d_{n+1} = f_{n+1} − M(c₁v_n + c₂v₁ + c₃c₁d_n + c₃c₂d₁)`, is the same
/// scheme in exact arithmetic but not in floating point: those right-hand
/// sides hold terms of size c²|M d| ∝ |d|/Δt² that cancel to leave an
/// acceleration-sized one, so each displacement is rounded to about ε|d|
/// (times M's conditioning), the velocities and accelerations recovered as
/// c·(differences of displacements) carry ε|d|/Δt and ε|d|/Δt², and over
/// the T/Δt steps of a run the error grows like ε|d|T/Δt. Measured on a
/// riding mass, the error stopped falling at Δt ≈ 1e-5 s and rose ∝ 1/Δt
/// below (docs/methods.md, "Bathe at small steps"). Here every right-hand
/// side is f − K d̃, of the size of M a, the unknown e is of the size
/// a/c², and no velocity or acceleration is a difference of displacements;
/// the cost is the same (one band product per sub-step, computed inside the
/// forward sweep: [`BandedLdlt::solve_affine`]).
pub(crate) struct Bathe {
    dt: f64,
    /// c₀ = 2/(γ_BΔt), c₁, c₂, c₃ (module docs).
    c0: f64,
    c1: f64,
    c2: f64,
    c3: f64,
    /// γ_BΔt, s.
    h1: f64,
    ldlt1: BandedLdlt,
    ldlt2: BandedLdlt,
    /// The mass dofs' rule of each sub-step, and its effective matrix
    /// over each body (`mass_step.rs`).
    first: FirstSubStep,
    second: SecondSubStep,
    effective1: Vec<Effective>,
    effective2: Vec<Effective>,
    /// The mass dofs (their q̈_n, and the first sub-step's end).
    masses: MassSteps<BatheDof>,
    /// Sub-step 1's displacement predictor increment p₁ = h₁v_n + (h₁²/4)a_n, m.
    p1: Vec<f64>,
    /// The first sub-step's end state of the beam, and q̇ of the masses there.
    d1: Vec<f64>,
    v1: Vec<f64>,
    qd1: Vec<f64>,
    /// d̃ and ṽ of the current sub-step (module docs).
    d_pred: Vec<f64>,
    v_pred: Vec<f64>,
    /// Scratch: the affine column f − K d̃ before the solve.
    b0: Vec<f64>,
    rhs: Vec<f64>,
    /// `f − C ṽ` of a sub-step with a damping matrix C (`None`: no damping).
    damped_load: Option<Vec<f64>>,
}

/// A sub-step's predictors of the beam: d̃ and ṽ (module docs).
#[derive(Debug, Clone, Copy)]
struct BeamPredictors<'a> {
    d: &'a [f64],
    v: &'a [f64],
}

/// A mass dof as Bathe's step keeps it: its state at t_n and the first
/// sub-step's end.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct BatheDof {
    /// z, ż, z̈ at t_n (m, m/s, m/s²).
    pub(crate) z: f64,
    pub(crate) zd: f64,
    pub(crate) za: f64,
    /// z₁, ż₁ at t_n + γ_BΔt, and Δ₁ = z₁ − z_n formed from its parts.
    pub(crate) z1: f64,
    pub(crate) zd1: f64,
    pub(crate) dz1: f64,
}

impl Dof for BatheDof {
    fn rest(z: f64) -> Self {
        BatheDof {
            z,
            ..BatheDof::default()
        }
    }

    fn head(&self) -> (f64, f64) {
        (self.z, self.zd)
    }

    fn set_head(&mut self, q: f64, q_dot: f64) {
        (self.z, self.zd) = (q, q_dot);
    }
}

/// Sub-step 1 of a mass dof (module docs, with m, c, k): A₁ = c₀²m + c₀c + k,
/// the unknown the increment e, `A₁ e = f₀ − c ṽ − k q̃`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FirstSubStep {
    /// h₁ = γ_BΔt, s.
    pub(crate) h1: f64,
    /// c₀ = 2/h₁, 1/s.
    pub(crate) c0: f64,
}

impl Stage for FirstSubStep {
    type Dof = BatheDof;

    fn matrix(&self) -> Coefficients {
        Coefficients {
            c_m: self.c0 * self.c0,
            c_c: self.c0,
            c_k: 1.0,
        }
    }

    #[inline]
    fn predict(&self, d: &mut BatheDof) -> Predicted {
        let h = self.h1;
        let p = h * d.zd + 0.25 * h * h * d.za;
        d.dz1 = p;
        let (q, q_dot) = (d.z + p, d.zd + 0.5 * h * d.za);
        Predicted {
            q,
            q_dot,
            c_at: q_dot,
            k_at: q,
        }
    }

    #[inline]
    fn load(&self, f0: f64, _: f64, _: &BatheDof, c_term: f64, k_term: f64) -> f64 {
        f0 - c_term - k_term
    }

    /// A chain's head at this sub-step's end feeds only the chain's second
    /// sub-step (the contact's gap rate takes ż₁ from u★₁ − λ/A_q, formed
    /// in [`Bathe::step`]): updated with the inverse's row, as the lower
    /// masses are (`mass_step.rs`, bit-identical outputs).
    const CHAIN_HEAD_BY_INVERSE: bool = true;

    #[inline]
    fn update(&self, d: &mut BatheDof, p: &Predicted, e: f64) {
        d.z1 = p.q + e;
        d.zd1 = p.q_dot + self.c0 * e;
        d.dz1 += e;
    }
}

/// Sub-step 2 of a mass dof (module docs): A₂ = c₃²m + c₃c + k,
/// s = c₁ż_n + c₂ż₁ − c₃c₁Δ₁, q̃ = z₁ − s/c₃², q̇̃ = −c₁Δ₁ − s/c₃.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SecondSubStep {
    /// c₁, c₂, c₃ (module docs), 1/s.
    pub(crate) c1: f64,
    pub(crate) c2: f64,
    pub(crate) c3: f64,
}

impl Stage for SecondSubStep {
    type Dof = BatheDof;

    fn matrix(&self) -> Coefficients {
        Coefficients {
            c_m: self.c3 * self.c3,
            c_c: self.c3,
            c_k: 1.0,
        }
    }

    #[inline]
    fn predict(&self, d: &mut BatheDof) -> Predicted {
        let (c1, c2, c3) = (self.c1, self.c2, self.c3);
        let (inv_c3, inv_c3_sq) = (1.0 / c3, 1.0 / (c3 * c3));
        let s = c1 * d.zd + c2 * d.zd1 - c3 * c1 * d.dz1;
        let (q, q_dot) = (d.z1 - s * inv_c3_sq, -c1 * d.dz1 - s * inv_c3);
        Predicted {
            q,
            q_dot,
            c_at: q_dot,
            k_at: q,
        }
    }

    /// The same with s divided by c₃² and c₃ rather than multiplied by
    /// their reciprocals: the chain's order of operations before the mass
    /// dofs were one abstraction (`mass_step.rs`, bit-identical outputs).
    #[inline]
    fn predict_in_chain(&self, d: &mut BatheDof) -> Predicted {
        let (c1, c2, c3) = (self.c1, self.c2, self.c3);
        let s = c1 * d.zd + c2 * d.zd1 - c3 * c1 * d.dz1;
        let (q, q_dot) = (d.z1 - s / (c3 * c3), -c1 * d.dz1 - s / c3);
        Predicted {
            q,
            q_dot,
            c_at: q_dot,
            k_at: q,
        }
    }

    #[inline]
    fn load(&self, f0: f64, _: f64, _: &BatheDof, c_term: f64, k_term: f64) -> f64 {
        f0 - c_term - k_term
    }

    #[inline]
    fn update(&self, d: &mut BatheDof, p: &Predicted, e: f64) {
        let c3 = self.c3;
        d.z = p.q + e;
        d.zd = p.q_dot + c3 * e;
        d.za = c3 * c3 * e;
    }
}

impl Bathe {
    /// Factor both matrices once.
    pub fn new(gamma: f64, sys: &System, st: &State, init: Initial) -> Result<Self> {
        let dt = sys.dt();
        let beam = sys.beam();
        let n = beam.n;
        let nc = sys.contacts();
        let h1 = gamma * dt;
        let c0 = 2.0 / h1;
        // a deliberate defect of the test build (`crate::defects`)
        let c1 = if crate::defects::on(crate::defects::Defect::BatheC1) {
            gamma / ((1.0 - gamma) * dt)
        } else {
            (1.0 - gamma) / (gamma * dt)
        };
        let c2 = -1.0 / ((1.0 - gamma) * gamma * dt);
        let c3 = (2.0 - gamma) / ((1.0 - gamma) * dt);
        // with a damping matrix C (docs/lines.md §10.4): A₁ += c₀C, A₂ += c₃C
        let effective = |c: f64| {
            let a = beam.stiffness.combine(1.0, &beam.mass, c * c);
            match sys.damping() {
                Some(damping) => a.combine(1.0, damping, c),
                None => a,
            }
        };
        let ldlt1 = BandedLdlt::factor(&effective(c0))?;
        let ldlt2 = BandedLdlt::factor(&effective(c3))?;
        let first = FirstSubStep { h1, c0 };
        let second = SecondSubStep { c1, c2, c3 };
        let mut masses = MassSteps::<BatheDof>::new(&sys.physics.masses);
        for (j, &aq) in init.aq.iter().enumerate() {
            masses.head_mut(j).za = aq;
        }
        let mut bathe = Bathe {
            effective1: MassSteps::effective(&first, &sys.physics.masses),
            effective2: MassSteps::effective(&second, &sys.physics.masses),
            first,
            second,
            masses,
            dt,
            c0,
            c1,
            c2,
            c3,
            h1,
            ldlt1,
            ldlt2,
            p1: vec![0.0; n],
            d1: vec![0.0; n],
            v1: vec![0.0; n],
            qd1: vec![0.0; nc],
            d_pred: vec![0.0; n],
            v_pred: vec![0.0; n],
            b0: vec![0.0; n],
            rhs: vec![0.0; n * rhs_columns(nc)],
            damped_load: sys.damping().map(|_| vec![0.0; n]),
        };
        // the first sub-step's predictors (later steps form them in the
        // previous update pass)
        for i in 0..n {
            (bathe.p1[i], bathe.d_pred[i], bathe.v_pred[i]) =
                bathe.first_predictors(st.d[i], st.v[i], init.a[i]);
        }
        Ok(bathe)
    }

    /// Sub-step 1's predictors from (d_n, v_n, a_n) of a row:
    /// (p₁, d̃ = d_n + p₁, ṽ = v_n + (h₁/2)a_n), module docs.
    #[inline(always)]
    fn first_predictors(&self, d: f64, v: f64, a: f64) -> (f64, f64, f64) {
        let h = self.h1;
        let p = h * v + 0.25 * h * h * a;
        (p, d + p, v + 0.5 * h * a)
    }

    /// Solve A X = B + (f − K d̃) e₀ᵀ with `ldlt`, B the moving forces and
    /// contact directions; the band product K d̃ is computed inside the
    /// forward sweep ([`BandedLdlt::solve_affine`]).
    ///
    /// With a damping matrix C the fixed load becomes `f − C ṽ` (formed in
    /// `damped_load`): `C v = C ṽ + c C e` with c = c₀ or c₃, whose second
    /// term is in A₁ or A₂.
    fn solve(
        rhs: &mut [f64],
        b0: &mut [f64],
        predicted: BeamPredictors,
        damped_load: &mut Option<Vec<f64>>,
        sys: &System,
        ldlt: &BandedLdlt,
    ) {
        let BeamPredictors {
            d: d_pred,
            v: v_pred,
        } = predicted;
        let beam = sys.beam();
        let k = sys.columns();
        let load: &[f64] = match (damped_load.as_mut(), sys.damping()) {
            (Some(h), Some(c)) => {
                h.copy_from_slice(&beam.load);
                c.mul_acc(v_pred, -1.0, h);
                h
            }
            _ => &beam.load,
        };
        rhs.fill(0.0);
        sys.scatter_loads(rhs, k, 1.0);
        let column = Affine {
            h: load,
            k: &beam.stiffness,
            u: d_pred,
        };
        ldlt.solve_affine(rhs, k, &column, b0);
    }
}

impl Stepper for Bathe {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let (c0, c1, c2, c3, h1) = (self.c0, self.c1, self.c2, self.c3, self.h1);
        let k = sys.columns();

        // sub-step 1: trapezoidal to t_n + γ_BΔt
        let ts = st.t + h1;
        sys.place(ts, ts, ts);
        // d̃ and ṽ were formed by the previous step's last pass
        Self::solve(
            &mut self.rhs,
            &mut self.b0,
            BeamPredictors {
                d: &self.d_pred,
                v: &self.v_pred,
            },
            &mut self.damped_load,
            sys,
            &self.ldlt1,
        );
        self.masses.begin(st);
        self.masses
            .predict(&self.first, &self.effective1, &sys.physics.masses);
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c0,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: self.masses.predictions(),
        };
        sys.solve_contact(&map, st)?;
        let lambda = sys.multipliers();
        let (inv_c3, inv_c3_sq) = (1.0 / c3, 1.0 / (c3 * c3));
        for (i, e) in combine(&self.rhs, k, lambda).enumerate() {
            let v1 = self.v_pred[i] + c0 * e;
            let inc = self.p1[i] + e;
            self.d1[i] = self.d_pred[i] + e;
            self.v1[i] = v1;
            // sub-step 2's predictors: s = c₁v_n + c₂v₁ − c₃c₁Δ₁,
            // d̃ = d₁ − s/c₃², ṽ = −c₁Δ₁ − s/c₃
            let s = c1 * st.v[i] + c2 * v1 - c3 * c1 * inc;
            self.d_pred[i] = self.d1[i] - s * inv_c3_sq;
            self.v_pred[i] = -c1 * inc - s * inv_c3;
        }
        // each head's ż₁ for the gap rates, from u★₁ − λ/A_q (a chain's
        // head state takes the inverse's row: `FirstSubStep`)
        let preds = self.masses.predictions();
        for ((qd1, m), &l) in self.qd1.iter_mut().zip(preds).zip(lambda) {
            *qd1 = m.q_dot + c0 * m.unknown(l);
        }
        self.masses
            .finish(&self.first, &self.effective1, &sys.physics.masses, lambda);
        sys.keep_gap_rates(&self.d1, &self.v1, &self.qd1);

        // sub-step 2: three-point backward Euler to t_{n+1}
        let t1 = st.next_time(self.dt);
        sys.place(t1, t1, t1);
        Self::solve(
            &mut self.rhs,
            &mut self.b0,
            BeamPredictors {
                d: &self.d_pred,
                v: &self.v_pred,
            },
            &mut self.damped_load,
            sys,
            &self.ldlt2,
        );
        self.masses
            .predict(&self.second, &self.effective2, &sys.physics.masses);
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c3,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: self.masses.predictions(),
        };
        sys.solve_contact(&map, st)?;
        let lambda = sys.multipliers();
        let c3_sq = c3 * c3;
        for (i, e) in combine(&self.rhs, k, lambda).enumerate() {
            let d = self.d_pred[i] + e;
            let v = self.v_pred[i] + c3 * e;
            st.d[i] = d;
            st.v[i] = v;
            // a_{n+1} = c₃²e; the next step's sub-step 1 predictors
            (self.p1[i], self.d_pred[i], self.v_pred[i]) = self.first_predictors(d, v, c3_sq * e);
        }
        self.masses
            .finish(&self.second, &self.effective2, &sys.physics.masses, lambda);
        self.masses.end(st);
        Ok(())
    }

    /// Each sub-step's mass rule over the chain (`mass_step.rs`).
    fn carries_chains(&self) -> bool {
        true
    }
}
