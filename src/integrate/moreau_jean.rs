//! Moreau–Jean's time-stepping scheme (Jean 1999; Acary & Brogliato 2008;
//! MODEL §9.1): the event-capturing, velocity-level θ-scheme of nonsmooth
//! dynamics, with impulses, not forces:
//!
//! ```text
//!   M(v_{n+1} − v_n) = Δt(f_{n+θ} − K d_{n+θ}) + Σ r_c P_c,   d_{n+1} = d_n + Δt v_{n+θ}
//!   y_{n+θ} = (1 − θ) y_n + θ y_{n+1},   θ ∈ [½, 1]
//! ```
//!
//! so that, for the velocity increment Δv = v_{n+1} − v_n (θ² + θ(1 − θ) = θ),
//! `(M + θ²Δt²K) Δv = Δt(f_{n+θ} − K(d_n + θΔt v_n)) + Σ r_c P_c`: a constant
//! matrix factored once, and one band product, computed inside the forward
//! sweep. A mass dof follows the same θ-rule with its dashpot:
//! `(m + θΔt c_s + θ²Δt² k) Δq̇ = …`.
//!
//! A contact whose predicted gap closes (the free step's gap at t_{n+1},
//! g_free ≤ 0) obeys Signorini–Newton at velocity level,
//! `0 ≤ U_{n+1} + e U_n ⊥ P_{n+1} ≥ 0`, U the gap rate and e the
//! restitution `contact.impact.restitution`. In the [`System`]'s terms the
//! unknown is Δv with v_{n+1} = v_n + Δv (c_v = 1) and
//! d_{n+1} = d_n + Δt v_n + θΔt Δv (c_d = θΔt), and the multipliers are
//! impulses: the system hands the law
//! `(U_free, W_v)` and the force recorded is P/Δt.
//!
//! The impulse acts at the carrier's position at t_{n+θ}, like every other
//! force of the θ-rule (the reason, and the exception near the beam's ends,
//! on `impulse_time`). The position gap is not imposed, only its rate: it
//! drifts by O(Δt²) over a run. First order where impacts occur, second
//! order between them with θ = ½ (the trapezoidal rule).

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt};

use super::mass_step::{Coefficients, Effective, Kinematics, MassSteps, Predicted, Stage};
use super::state::State;
use super::step_map::{StepMap, VelocityPrediction, combine};
use super::stepper::Stepper;
use super::system::System;
use crate::model::banded::rhs_columns;

/// A Moreau–Jean stepper for one run.
pub(crate) struct MoreauJean {
    theta: f64,
    dt: f64,
    ldlt: BandedLdlt,
    /// The mass dofs' rule, its effective matrix over each body, and the
    /// mass dofs (`mass_step.rs`).
    rule: MoreauJeanMass,
    effective: Vec<Effective>,
    masses: MassSteps<Kinematics>,
    /// d̃ = d_n + Δt v_n.
    d_pred: Vec<f64>,
    /// Δt·f and Δt(d_n + θΔt v_n): the affine column Δt f − K(…) (scratch),
    /// and that column before the solve.
    h: Vec<f64>,
    w: Vec<f64>,
    b0: Vec<f64>,
    rhs: Vec<f64>,
}

/// Moreau–Jean's step of a mass dof (module docs): the unknown is its
/// velocity change Δq̇, `(m + θΔt c + θ²Δt² k) Δq̇ = Δt(f₀ − c q̇_n −
/// k(q_n + θΔt q̇_n)) − P`, then q̇_{n+1} = q̇_n + Δq̇,
/// q_{n+1} = q_n + Δt q̇_n + θΔt Δq̇.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MoreauJeanMass {
    /// θ.
    pub(crate) theta: f64,
    /// Δt, s.
    pub(crate) dt: f64,
}

impl Stage for MoreauJeanMass {
    type Dof = Kinematics;

    fn matrix(&self) -> Coefficients {
        let (theta, dt) = (self.theta, self.dt);
        Coefficients {
            c_m: 1.0,
            c_c: theta * dt,
            c_k: theta * theta * dt * dt,
        }
    }

    #[inline]
    fn predict(&self, d: &mut Kinematics) -> Predicted {
        let (theta, dt) = (self.theta, self.dt);
        Predicted {
            q: d.z + dt * d.zd,
            q_dot: d.zd,
            c_at: d.zd,
            k_at: d.z + theta * dt * d.zd,
        }
    }

    #[inline]
    fn load(&self, f0: f64, _: f64, _: &Kinematics, c_term: f64, k_term: f64) -> f64 {
        self.dt * (f0 - c_term - k_term)
    }

    #[inline]
    fn update(&self, d: &mut Kinematics, p: &Predicted, dqd: f64) {
        d.zd += dqd;
        d.z = p.q + self.theta * self.dt * dqd;
    }
}

impl MoreauJean {
    /// Factor M + θ²Δt²K once.
    pub fn new(theta: f64, sys: &System, _st: &State) -> Result<Self> {
        let dt = sys.dt();
        let beam = sys.beam();
        let (n, nc) = (beam.n, sys.contacts());
        let c = theta * theta * dt * dt;
        let mut a = beam.mass.combine(1.0, &beam.stiffness, c);
        if let Some(damping) = sys.damping() {
            // C v_θ = C v_n + θ C Δv (docs/lines.md §10.4): θΔt C into the matrix
            a = a.combine(1.0, damping, theta * dt);
        }
        let ldlt = BandedLdlt::factor(&a)?;
        let rule = MoreauJeanMass { theta, dt };
        Ok(MoreauJean {
            effective: MassSteps::effective(&rule, &sys.physics.masses),
            masses: MassSteps::new(&sys.physics.masses),
            rule,
            theta,
            dt,
            ldlt,
            d_pred: vec![0.0; n],
            h: vec![0.0; n],
            w: vec![0.0; n],
            b0: vec![0.0; n],
            rhs: vec![0.0; n * rhs_columns(nc)],
        })
    }
}

/// When the impulse acts (module docs): t_{n+θ}, or t_{n+1} when a
/// contact carrier ends the step within one step's travel, |V|Δt, of an
/// end of the beam.
///
/// **Where the impulse acts.** The gap rate is taken at t_{n+1} (the law's
/// condition), but the impulse P_{n+1} is applied at the carrier's position
/// at t_{n+θ}, `r(x_m(t_{n+θ}))`, like every other force of the θ-rule:
/// P stands for `∫ r(x_m(t)) λ(t) dt` over the step, and with θ = ½ that is
/// the midpoint rule, O(Δt³) per step. Applying it at `x_m(t_{n+1})`
/// instead puts the force, on average, VΔt/2 ahead of where it acts: an
/// O(Δt²) error per step (`V r'λΔt²/2`), first order over a run. Measured on
/// a riding mass (docs/methods.md): first order (0.99–1.00) with the
/// impulse at t_{n+1}, second order (1.98–2.01) at t_{n+½}. For a carrier
/// at rest the two are the same. One exception: a step that ends with a
/// carrier within one step's travel (|V|Δt) of an end of the beam applies
/// its impulse at x_m(t_{n+1}). Arriving at a pinned end, the mass follows
/// the beam's slope there (the convective rate V·v'), and an impulse
/// behind it tilts that slope the wrong way: the velocity-level Delassus
/// W_v becomes negative, and the law has no solution (measured: the
/// reference case at V0 = 120 and 125 m/s, Δt = 1e-4 s, stopped at its last
/// step). At most a step or two per arrival takes the end point, so a
/// run's order is unchanged. The recorded force P/Δt is the step's mean
/// force, the force near t_{n+θ}: read as λ(t_{n+1}) it lags by about θΔt,
/// a first-order offset in the force history, while the displacements are
/// second order.
fn impulse_time(sys: &System, t_theta: f64, t1: f64) -> f64 {
    let near_end = sys
        .physics
        .carriers
        .iter()
        .filter(|c| c.contact.is_some())
        .any(|c| {
            let x = c.props.motion.position(t1);
            x.min(sys.physics.length - x) < c.props.motion.speed(t1).abs() * sys.physics.dt
        });
    if near_end { t1 } else { t_theta }
}

impl Stepper for MoreauJean {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let (theta, dt) = (self.theta, self.dt);
        let k = sys.columns();
        let t1 = st.next_time(dt);
        let t_theta = st.t + theta * dt;
        // loads and the impulse direction at t_{n+θ} (at t_{n+1} within a
        // step's travel of an end), the gap row at t_{n+1} (module docs:
        // where the impulse acts)
        sys.place(t_theta, impulse_time(sys, t_theta, t1), t1);
        let beam = sys.beam();
        for i in 0..st.d.len() {
            self.w[i] = dt * (st.d[i] + theta * dt * st.v[i]);
            self.d_pred[i] = st.d[i] + dt * st.v[i];
            self.h[i] = dt * beam.load[i];
        }
        if let Some(damping) = sys.damping() {
            // and −Δt C v_n into the right-hand side
            damping.mul_acc(&st.v, -dt, &mut self.h);
        }
        self.rhs.fill(0.0);
        sys.scatter_loads(&mut self.rhs, k, dt);
        let column = Affine {
            h: &self.h,
            k: &beam.stiffness,
            u: &self.w,
        };
        self.ldlt
            .solve_affine(&mut self.rhs, k, &column, &mut self.b0);
        self.masses.begin(st);
        self.masses
            .predict(&self.rule, &self.effective, &sys.physics.masses);
        let map = StepMap {
            solved: &self.rhs,
            c_d: theta * dt,
            c_v: 1.0,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&st.v),
            alpha_weight: 0.0,
            masses: self.masses.predictions(),
        };
        sys.solve_contact(&map, st)?;
        let impulse = sys.multipliers();
        let c_d = theta * dt;
        for (i, dv) in combine(&self.rhs, k, impulse).enumerate() {
            st.v[i] += dv;
            st.d[i] = self.d_pred[i] + c_d * dv;
        }
        self.masses
            .finish(&self.rule, &self.effective, &sys.physics.masses, impulse);
        self.masses.end(st);
        Ok(())
    }

    /// The chain's dofs step with the same rule (`mass_step.rs`).
    fn carries_chains(&self) -> bool {
        true
    }
}
