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
//! Both sub-steps solve for a displacement: A₁ d₁ = f₁ + M(c₀² d_n + 2c₀ v_n +
//! a_n) with c₀ = 2/h₁ and A₁ = K + c₀²M, and A₂ d_{n+1} = f_{n+1} −
//! M(c₁v_n + c₂v₁ + c₃c₁d_n + c₃c₂d₁) with A₂ = K + c₃²M: two constant
//! matrices, each factored once per run. The gap condition is imposed at
//! the end of each sub-step (the [`System`]'s contact problem with
//! `d = u`, `v = ṽ + c u`: c = c₀, then c = c₃); the force recorded is the
//! second sub-step's. Second order; strongly damps unresolved high
//! frequencies (spectral radius → 0 as ωΔt → ∞ for γ_B = ½).

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt};

use super::{
    Initial, MassPrediction, State, StepMap, Stepper, System, VelocityPrediction, combine,
    rhs_columns,
};

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
    /// Beam and mass accelerations a_n.
    a: Vec<f64>,
    aq: Vec<f64>,
    /// The first sub-step's end state.
    d1: Vec<f64>,
    v1: Vec<f64>,
    q1: Vec<f64>,
    qd1: Vec<f64>,
    /// ṽ of the current sub-step, and d̃ = 0 (both sub-steps solve for d).
    v_pred: Vec<f64>,
    zeros: Vec<f64>,
    /// Scratch: u of the affine column f − M u, and that column before the solve.
    w: Vec<f64>,
    b0: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
    rhs: Vec<f64>,
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
        let ldlt1 = BandedLdlt::factor(&beam.stiffness.combine(1.0, &beam.mass, c0 * c0))?;
        let ldlt2 = BandedLdlt::factor(&beam.stiffness.combine(1.0, &beam.mass, c3 * c3))?;
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
        let mut bathe = Bathe {
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
            a: init.a,
            aq: init.aq,
            d1: vec![0.0; n],
            v1: vec![0.0; n],
            q1: vec![0.0; nc],
            qd1: vec![0.0; nc],
            v_pred: vec![0.0; n],
            zeros: vec![0.0; n],
            w: vec![0.0; n],
            b0: vec![0.0; n],
            mass_pred: vec![MassPrediction::default(); nc],
            rhs: vec![0.0; n * rhs_columns(nc)],
        };
        // the first sub-step's operands (later steps form them in the
        // previous update pass)
        for i in 0..n {
            (bathe.w[i], bathe.v_pred[i]) = bathe.first_operands(st.d[i], st.v[i], bathe.a[i]);
        }
        Ok(bathe)
    }

    /// Sub-step 1's operands from (d_n, v_n, a_n) of a row: w = −(c₀²d +
    /// 2c₀v + a), so that f − M w = f + M(c₀²d + 2c₀v + a), and ṽ = −c₀d − v.
    #[inline(always)]
    fn first_operands(&self, d: f64, v: f64, a: f64) -> (f64, f64) {
        let c0 = self.c0;
        (-(c0 * c0 * d + 2.0 * c0 * v + a), -c0 * d - v)
    }

    /// Solve A X = B + (f − M w) e₀ᵀ with `ldlt`, B the moving forces and
    /// contact directions; the band product M w is computed inside the
    /// forward sweep ([`BandedLdlt::solve_affine`]).
    fn solve(rhs: &mut [f64], b0: &mut [f64], w: &[f64], sys: &System, ldlt: &BandedLdlt) {
        let beam = sys.beam();
        let k = sys.columns();
        rhs.fill(0.0);
        sys.scatter_loads(rhs, k, 1.0);
        let column = Affine {
            h: &beam.load,
            k: &beam.mass,
            u: w,
        };
        ldlt.solve_affine(rhs, k, &column, b0);
    }
}

impl Stepper for Bathe {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let (c0, c1, c2, c3) = (self.c0, self.c1, self.c2, self.c3);
        let k = sys.columns();

        // sub-step 1: trapezoidal to t_n + γ_BΔt
        let ts = st.t + self.h1;
        sys.place(ts, ts, ts);
        // w and ṽ were formed by the previous step's last pass
        Self::solve(&mut self.rhs, &mut self.b0, &self.w, sys, &self.ldlt1);
        for (j, m) in sys.masses().iter().enumerate() {
            let (q, qd, aq) = (st.q[j], st.q_dot[j], self.aq[j]);
            let b = m.f0 + m.m * (c0 * c0 * q + 2.0 * c0 * qd + aq) + m.c * (c0 * q + qd);
            self.mass_pred[j] = MassPrediction {
                q: 0.0,
                q_dot: -c0 * q - qd,
                u: b / self.a_eff1[j],
                a_eff: self.a_eff1[j],
            };
        }
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c0,
            d_pred: &self.zeros,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
        };
        sys.solve_contact(&map, st)?;
        let lambda = sys.multipliers();
        for (i, d) in combine(&self.rhs, k, lambda).enumerate() {
            let v1 = self.v_pred[i] + c0 * d;
            self.d1[i] = d;
            self.v1[i] = v1;
            // sub-step 2's operands: f − M w with
            // w = c₁v_n + c₂v₁ + c₃(c₁d_n + c₂d₁), and ṽ = c₁d_n + c₂d₁
            let v_pred = c1 * st.d[i] + c2 * d;
            self.w[i] = c1 * st.v[i] + c2 * v1 + c3 * v_pred;
            self.v_pred[i] = v_pred;
        }
        for (j, m) in self.mass_pred.iter().enumerate() {
            let q = m.unknown(lambda[j]);
            self.q1[j] = q;
            self.qd1[j] = m.q_dot + c0 * q;
        }
        sys.keep_gap_rates(&self.d1, &self.v1, &self.qd1);

        // sub-step 2: three-point backward Euler to t_{n+1}
        let t1 = st.next_time(self.dt);
        sys.place(t1, t1, t1);
        Self::solve(&mut self.rhs, &mut self.b0, &self.w, sys, &self.ldlt2);
        for (j, m) in sys.masses().iter().enumerate() {
            let (q, qd) = (st.q[j], st.q_dot[j]);
            let b = m.f0
                - m.m * (c1 * qd + c2 * self.qd1[j] + c3 * (c1 * q + c2 * self.q1[j]))
                - m.c * (c1 * q + c2 * self.q1[j]);
            self.mass_pred[j] = MassPrediction {
                q: 0.0,
                q_dot: c1 * q + c2 * self.q1[j],
                u: b / self.a_eff2[j],
                a_eff: self.a_eff2[j],
            };
        }
        let map = StepMap {
            solved: &self.rhs,
            c_d: 1.0,
            c_v: c3,
            d_pred: &self.zeros,
            v_pred: VelocityPrediction::Vector(&self.v_pred),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
        };
        sys.solve_contact(&map, st)?;
        let lambda = sys.multipliers();
        for (i, d) in combine(&self.rhs, k, lambda).enumerate() {
            let v = self.v_pred[i] + c3 * d;
            let a = c1 * st.v[i] + c2 * self.v1[i] + c3 * v;
            self.a[i] = a;
            st.d[i] = d;
            st.v[i] = v;
            // the next step's sub-step 1 operands
            (self.w[i], self.v_pred[i]) = self.first_operands(d, v, a);
        }
        for (j, m) in self.mass_pred.iter().enumerate() {
            let q = m.unknown(lambda[j]);
            let qd = m.q_dot + c3 * q;
            self.aq[j] = c1 * st.q_dot[j] + c2 * self.qd1[j] + c3 * qd;
            st.q[j] = q;
            st.q_dot[j] = qd;
        }
        Ok(())
    }
}
