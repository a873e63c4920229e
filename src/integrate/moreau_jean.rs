//! Moreau–Jean's time-stepping scheme (Jean 1999; Acary & Brogliato 2008;
//! MODEL §9.1): the event-capturing, velocity-level θ-scheme of nonsmooth
//! dynamics, with impulses, not forces:
//!
//! ```text
//!   M(v_{n+1} − v_n) = Δt(f_{n+θ} − K d_{n+θ}) + Σ r_c P_c,   d_{n+1} = d_n + Δt v_{n+θ}
//!   y_{n+θ} = (1 − θ) y_n + θ y_{n+1},   θ ∈ [½, 1]
//! ```
//!
//! so that `(M + θ²Δt²K) v_{n+1} = M v_n + Δt(f_{n+θ} − K(d_n + θ(1 − θ)Δt v_n))
//! + Σ r_c P_c`, a constant matrix factored once. A mass dof follows the same
//! θ-rule with its dashpot: `(m + θΔt c_s + θ²Δt² k) q̇_{n+1} = …`.
//!
//! A contact whose predicted gap closes (the free step's gap at t_{n+1},
//! g_free ≤ 0) obeys Signorini–Newton at velocity level,
//! `0 ≤ U_{n+1} + e U_n ⊥ P_{n+1} ≥ 0`, U the gap rate and e the
//! restitution `contact.impact.restitution`. In the [`System`]'s terms the
//! unknown is v_{n+1} (c_v = 1) with d_{n+1} = d_n + (1 − θ)Δt v_n + θΔt v_{n+1}
//! (c_d = θΔt), and the multipliers are impulses: the system hands the law
//! `(U_free, W_v)` and the force recorded is P/Δt. The position gap is not
//! imposed, so it drifts by O(Δt²) per impact (the largest penetration is
//! reported). First order where impacts occur, however small Δt; second
//! order between them with θ = ½ (the trapezoidal rule, which conserves a
//! linear system's energy).

use crate::error::Result;
use crate::model::banded::BandedLdlt;

use super::{MassPrediction, State, StepMap, Stepper, System, VelocityPrediction, rhs_columns};

/// A Moreau–Jean stepper for one run.
pub struct MoreauJean {
    theta: f64,
    dt: f64,
    ldlt: BandedLdlt,
    /// A_q = m + θΔt c + θ²Δt² k per contact.
    a_eff: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
    /// d̃ = d_n + (1 − θ)Δt v_n.
    d_pred: Vec<f64>,
    zeros: Vec<f64>,
    /// d_n + θ(1 − θ)Δt v_n (scratch), and the column it makes.
    w: Vec<f64>,
    y: Vec<f64>,
    rhs: Vec<f64>,
}

impl MoreauJean {
    /// Factor M + θ²Δt²K once.
    pub fn new(theta: f64, sys: &System, _st: &State) -> Result<Self> {
        let dt = sys.dt();
        let beam = sys.beam();
        let (n, nc) = (beam.n, sys.contacts());
        let c = theta * theta * dt * dt;
        let ldlt = BandedLdlt::factor(&beam.mass.combine(1.0, &beam.stiffness, c))?;
        let a_eff = sys
            .masses()
            .iter()
            .map(|m| m.m + theta * dt * m.c + c * m.k)
            .collect();
        Ok(MoreauJean {
            theta,
            dt,
            ldlt,
            a_eff,
            mass_pred: vec![MassPrediction::default(); nc],
            d_pred: vec![0.0; n],
            zeros: vec![0.0; n],
            w: vec![0.0; n],
            y: vec![0.0; n],
            rhs: vec![0.0; n * rhs_columns(nc)],
        })
    }
}

impl Stepper for MoreauJean {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let (theta, dt) = (self.theta, self.dt);
        let k = sys.columns();
        let t1 = st.next_time(dt);
        let t_theta = st.t + theta * dt;
        // loads at t_{n+θ}; the impulse direction and the gap row at t_{n+1}
        sys.place(t_theta, t1, t1);
        let beam = sys.beam();
        let c_w = theta * (1.0 - theta) * dt;
        for i in 0..st.d.len() {
            self.w[i] = st.d[i] + c_w * st.v[i];
            self.d_pred[i] = st.d[i] + (1.0 - theta) * dt * st.v[i];
            self.y[i] = dt * beam.load[i];
        }
        beam.stiffness.mul_acc(&self.w, -dt, &mut self.y);
        beam.mass.mul_acc(&st.v, 1.0, &mut self.y);
        self.rhs.fill(0.0);
        for (row, yi) in self.rhs.chunks_exact_mut(k).zip(&self.y) {
            row[0] = *yi;
        }
        sys.scatter_loads(&mut self.rhs, k, dt);
        self.ldlt.solve_many(&mut self.rhs, k);
        for (j, m) in sys.masses().iter().enumerate() {
            let (q, qd) = (st.q[j], st.q_dot[j]);
            let b = m.m * qd + dt * (m.f0 - m.c * (1.0 - theta) * qd - m.k * (q + c_w * qd));
            self.mass_pred[j] = MassPrediction {
                q: q + (1.0 - theta) * dt * qd,
                q_dot: 0.0,
                u: b / self.a_eff[j],
                a_eff: self.a_eff[j],
            };
        }
        let map = StepMap {
            solved: &self.rhs,
            c_d: theta * dt,
            c_v: 1.0,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&self.zeros),
            alpha_weight: 0.0,
            masses: &self.mass_pred,
        };
        sys.solve_contact(&map, st)?;
        let impulse = sys.multipliers();
        let c_d = theta * dt;
        for (i, row) in self.rhs.chunks_exact(k).enumerate() {
            let mut v = row[0];
            for (p, z) in impulse.iter().zip(&row[1..]) {
                v += p * z;
            }
            st.v[i] = v;
            st.d[i] = self.d_pred[i] + c_d * v;
        }
        for (j, m) in self.mass_pred.iter().enumerate() {
            let qd = m.u - impulse[j] / m.a_eff;
            st.q_dot[j] = qd;
            st.q[j] = m.q + c_d * qd;
        }
        Ok(())
    }
}
