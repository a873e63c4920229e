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
//! (Δ₁ = d₁ − d_n, formed from its parts.) Solving for the displacement
//! itself, `A₁ d₁ = f₁ + M(c₀²d_n + 2c₀v_n + a_n)` and
//! `A₂ d_{n+1} = f_{n+1} − M(c₁v_n + c₂v₁ + c₃c₁d_n + c₃c₂d₁)`, is the same
//! scheme in exact arithmetic but not in floating point: those right-hand
//! sides hold terms of size c²|M d| ∝ |d|/Δt² that cancel to leave an
//! acceleration-sized one, so each displacement is rounded to about ε|d|
//! (times M's conditioning), the velocities and accelerations recovered as
//! c·(differences of displacements) carry ε|d|/Δt and ε|d|/Δt², and over
//! the T/Δt steps of a run the error grows like ε|d|T/Δt. Measured on a
//! riding mass, the error stopped falling at Δt ≈ 1e-5 s and rose ∝ 1/Δt
//! below (docs/methods.md, "Bathe at small steps"). Here every right-hand
//! side is f − K d̃, of the size of M a, the unknown e is of the size
//! a/c², and no velocity or acceleration is a difference of displacements;
//! the cost is the same (one band product per sub-step, computed inside the
//! forward sweep: [`BandedLdlt::solve_affine`]).
//!
//! The gap condition is imposed at the end of each sub-step (the
//! [`System`]'s contact problem with `d = d̃ + e`, `v = ṽ + c e`, c = c₀,
//! then c = c₃); the force recorded is the second sub-step's. Second order;
//! strongly damps unresolved high frequencies (spectral radius → 0 as
//! ωΔt → ∞ for γ_B = ½).

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt};

use super::chain::ChainBathe;
use super::state::State;
use super::step_map::{MassPrediction, StepMap, VelocityPrediction, combine};
use super::stepper::Stepper;
use super::system::{Initial, System};
use crate::model::banded::rhs_columns;

/// A Bathe stepper for one run.
pub struct Bathe {
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
    /// A_q of each mass dof for sub-steps 1 and 2.
    a_eff1: Vec<f64>,
    a_eff2: Vec<f64>,
    /// Mass accelerations q̈_n.
    aq: Vec<f64>,
    /// Sub-step 1's displacement predictor increment p₁ = h₁v_n + (h₁²/4)a_n, m.
    p1: Vec<f64>,
    /// The first sub-step's end state, and Δ₁ = d₁ − d_n of the masses.
    d1: Vec<f64>,
    v1: Vec<f64>,
    q1: Vec<f64>,
    qd1: Vec<f64>,
    dq1: Vec<f64>,
    /// d̃ and ṽ of the current sub-step (module docs).
    d_pred: Vec<f64>,
    v_pred: Vec<f64>,
    /// Scratch: the affine column f − K d̃ before the solve.
    b0: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
    rhs: Vec<f64>,
    /// `f − C ṽ` of a sub-step with a damping matrix C (`None`: no damping).
    damped_load: Option<Vec<f64>>,
    /// The multi-mass pantograph of each contact, if any (`chain.rs`).
    chains: Vec<Option<ChainBathe>>,
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
        let c1 = (1.0 - gamma) / (gamma * dt);
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
        let a_eff1 = sys
            .masses()
            .iter()
            .map(|m| c0 * c0 * m.m + c0 * m.c + m.k)
            .collect();
        let a_eff2 = sys
            .masses()
            .iter()
            .map(|m| c3 * c3 * m.m + c3 * m.c + m.k)
            .collect();
        let chains = sys
            .chains()
            .iter()
            .zip(&init.aq)
            .map(|(ch, &aq)| ch.map(|ch| ChainBathe::new(ch, gamma, dt, aq)))
            .collect();
        let mut bathe = Bathe {
            chains,
            dt,
            c0,
            c1,
            c2,
            c3,
            h1,
            ldlt1,
            ldlt2,
            a_eff1,
            a_eff2,
            aq: init.aq,
            p1: vec![0.0; n],
            d1: vec![0.0; n],
            v1: vec![0.0; n],
            q1: vec![0.0; nc],
            qd1: vec![0.0; nc],
            dq1: vec![0.0; nc],
            d_pred: vec![0.0; n],
            v_pred: vec![0.0; n],
            b0: vec![0.0; n],
            mass_pred: vec![MassPrediction::default(); nc],
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
        (d_pred, v_pred): (&[f64], &[f64]),
        damped_load: &mut Option<Vec<f64>>,
        sys: &System,
        ldlt: &BandedLdlt,
    ) {
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
            (&self.d_pred, &self.v_pred),
            &mut self.damped_load,
            sys,
            &self.ldlt1,
        );
        for (j, m) in sys.masses().iter().enumerate() {
            let (q, qd, aq) = (st.q[j], st.q_dot[j], self.aq[j]);
            let p = h1 * qd + 0.25 * h1 * h1 * aq;
            let (q_pred, qd_pred) = (q + p, qd + 0.5 * h1 * aq);
            self.dq1[j] = p;
            self.mass_pred[j] = match &mut self.chains[j] {
                Some(ch) => ch.first((q, qd, aq)),
                None => MassPrediction {
                    q: q_pred,
                    q_dot: qd_pred,
                    u: (m.f0 - m.c * qd_pred - m.k * q_pred) / self.a_eff1[j],
                    a_eff: self.a_eff1[j],
                },
            };
        }
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c0,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
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
        for (j, m) in self.mass_pred.iter().enumerate() {
            let e = m.unknown(lambda[j]);
            self.q1[j] = m.q + e;
            self.qd1[j] = m.q_dot + c0 * e;
            self.dq1[j] += e;
            if let Some(ch) = &mut self.chains[j] {
                ch.end_first(lambda[j]);
            }
        }
        sys.keep_gap_rates(&self.d1, &self.v1, &self.qd1);

        // sub-step 2: three-point backward Euler to t_{n+1}
        let t1 = st.next_time(self.dt);
        sys.place(t1, t1, t1);
        Self::solve(
            &mut self.rhs,
            &mut self.b0,
            (&self.d_pred, &self.v_pred),
            &mut self.damped_load,
            sys,
            &self.ldlt2,
        );
        for (j, m) in sys.masses().iter().enumerate() {
            let (qd, dq1) = (st.q_dot[j], self.dq1[j]);
            let s = c1 * qd + c2 * self.qd1[j] - c3 * c1 * dq1;
            let (q_pred, qd_pred) = (self.q1[j] - s * inv_c3_sq, -c1 * dq1 - s * inv_c3);
            self.mass_pred[j] = match &mut self.chains[j] {
                Some(ch) => ch.second(),
                None => MassPrediction {
                    q: q_pred,
                    q_dot: qd_pred,
                    u: (m.f0 - m.c * qd_pred - m.k * q_pred) / self.a_eff2[j],
                    a_eff: self.a_eff2[j],
                },
            };
        }
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c3,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
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
        for (j, m) in self.mass_pred.iter().enumerate() {
            let e = m.unknown(lambda[j]);
            st.q[j] = m.q + e;
            st.q_dot[j] = m.q_dot + c3 * e;
            self.aq[j] = c3_sq * e;
            if let Some(ch) = &mut self.chains[j] {
                ch.end_second(lambda[j]);
            }
        }
        Ok(())
    }

    /// Each sub-step's effective matrix over the chain (`chain.rs`).
    fn carries_chains(&self) -> bool {
        true
    }
}
