//! Central difference, explicit in K (MODEL §9.1):
//!
//! ```text
//!   M a_n = f_n − K d_n + Σ λ_c r_c,   v_{n+1/2} = v_{n−1/2} + Δt a_n,
//!   d_{n+1} = d_n + Δt v_{n+1/2}
//! ```
//!
//! with the consistent mass (its banded factor from the initial state is
//! reused: one banded solve per step, no K solve). Contact by the
//! forward-increment Lagrange multiplier (Carpenter, Taylor & Katona 1991):
//! λ_n acts along r at x_m(t_n) and is chosen so that the gap at t_{n+1}
//! closes, `W = Δt² r_{n+1}ᵀ M⁻¹ r_n` — in the [`System`]'s terms, the
//! unknown is a_n with `d_{n+1} = (d_n + Δt v_{n−1/2}) + Δt² a_n`. A mass dof
//! takes its dashpot at the average of the half-step velocities,
//! `(m + c_sΔt/2) q̈_n = f0 − k q_n − c_s q̇_{n−1/2} − λ`, second order.
//!
//! Conditionally stable: Δt ≤ 2/ω_max. ω_max is computed from the assembled
//! model by a Lanczos iteration with its residual bound
//! ([`stability_limit`], `model::spectrum`); a scene above the limit is
//! refused before the run, naming ω_max and the largest stable Δt.
//!
//! With the impact law (`contact.formulation = "impact"`, MODEL §6) the gap
//! rate is the gap's increment over the step, ġ_{n+1/2} = (g_{n+1} − g_n)/Δt
//! ([`System::set_increment_rates`]): the rate the half-step velocity gives
//! the gap, the carrier's motion over the step included, so a contact held
//! at ġ = 0 keeps its gap to round-off (a convective rate at t_{n+1}
//! mixes two times, and the gap drifts open at O(Δt)). The state's `v` is the half-step velocity v_{n+1/2} (the method's own),
//! and the force recorded at t_{n+1} is λ_n, the force that closed the gap
//! at t_{n+1} (it acts at t_n).

use crate::error::{Error, Result};
use crate::model::banded::{Affine, BandedLdlt};
use crate::model::spectrum;
use crate::resolve::Resolved;

use super::mass_step::{Coefficients, Effective, Kinematics, MassSteps, Predicted, Stage};
use super::state::State;
use super::step_map::{StepMap, VelocityPrediction, combine};
use super::stepper::Stepper;
use super::system::{Initial, System};
use crate::model::banded::rhs_columns;

/// Lanczos steps for ω_max: after 100 steps the largest Ritz value is within
/// 3e-5 of a dense solve's ω_max² on the reference beam at N = 400 and its
/// residual bound closes the rest (`tests/methods.rs`; 13 ms there).
pub const LANCZOS_STEPS: usize = 100;

/// The explicit method's stability limit for a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityLimit {
    /// ω_max the run is held to, rad/s: the smaller of the beam's two upper
    /// figures, sqrt(θ + r) (Lanczos) and the element bound, or a
    /// mass–spring's sqrt(k/m) if higher.
    pub omega_max: f64,
    /// sqrt(θ): the Lanczos estimate itself (≤ the beam's ω_max), rad/s.
    pub omega_ritz: f64,
    /// The element-eigenvalue bound (Irons), rad/s: ≥ the beam's ω_max.
    pub omega_element_bound: f64,
    /// The largest stable step 2/ω_max, s.
    pub dt_max: f64,
}

/// The stability limit of central difference for a validated scene, from
/// scratch (assembles the system and factors M): for studies choosing Δt.
pub fn central_difference_limit(sc: &Resolved) -> Result<StabilityLimit> {
    let sys = System::new(sc)?;
    let mass_factor = BandedLdlt::factor(&sys.beam().mass)?;
    Ok(stability_limit(sc, &sys, &mass_factor))
}

/// ω_max and the largest stable Δt of central difference for a scene.
pub(crate) fn stability_limit(
    sc: &Resolved,
    sys: &System,
    mass_factor: &BandedLdlt,
) -> StabilityLimit {
    let beam = sys.beam();
    let (theta, residual) = spectrum::lanczos_max(beam, mass_factor, LANCZOS_STEPS);
    let bound = beam.omega_bound(&sc.beam);
    let mut omega = (theta + residual).sqrt().min(bound);
    for m in sys.masses() {
        omega = omega.max((m.k / m.m).sqrt());
    }
    for ch in sys.chains().iter().flatten() {
        omega = omega.max(ch.omega_bound());
    }
    StabilityLimit {
        omega_max: omega,
        omega_ritz: theta.sqrt(),
        omega_element_bound: bound,
        dt_max: 2.0 / omega,
    }
}

/// A central-difference stepper for one run.
pub struct CentralDifference {
    dt: f64,
    mass_factor: BandedLdlt,
    /// The mass dofs' rule, its effective matrix over each body, and the
    /// mass dofs, their velocity at the half step (`mass_step.rs`).
    rule: CentralMass,
    effective: Vec<Effective>,
    masses: MassSteps<Kinematics>,
    /// d̃ = d_n + Δt v_{n−1/2}.
    d_pred: Vec<f64>,
    /// n × k right-hand sides: f_n − K d_n + moving forces, and s_c r_c.
    rhs: Vec<f64>,
    /// Column 0 before the solve (scratch).
    b0: Vec<f64>,
    /// The stability limit checked at the start.
    pub limit: StabilityLimit,
}

/// Central difference's step of a mass dof (module docs): the unknown is
/// its acceleration q̈_n, `(m + c_sΔt/2) q̈_n = f₀ − k q_n − c_s q̇_{n−1/2}
/// − λ` (the dashpot at the mean half-step velocity), then
/// q̇_{n+1/2} = q̇_{n−1/2} + Δt q̈_n, q_{n+1} = q_n + Δt q̇_{n−1/2} + Δt² q̈_n.
/// A chain's masses likewise, stable for Δt ≤ 2/ω_max with its ω_max
/// bounded by [`Chain::omega_bound`](super::chain::Chain::omega_bound).
#[derive(Debug, Clone, Copy)]
pub(crate) struct CentralMass {
    /// Δt, s.
    pub(crate) dt: f64,
}

impl Stage for CentralMass {
    type Dof = Kinematics;

    fn matrix(&self) -> Coefficients {
        Coefficients {
            c_m: 1.0,
            c_c: 0.5 * self.dt,
            c_k: 0.0,
        }
    }

    #[inline]
    fn predict(&self, d: &mut Kinematics) -> Predicted {
        Predicted {
            q: d.z + self.dt * d.zd,
            q_dot: d.zd,
            c_at: d.zd,
            k_at: d.z,
        }
    }

    #[inline]
    fn load(&self, f0: f64, _: f64, _: &Kinematics, c_term: f64, k_term: f64) -> f64 {
        f0 - k_term - c_term
    }

    #[inline]
    fn update(&self, d: &mut Kinematics, p: &Predicted, a: f64) {
        let dt = self.dt;
        d.zd += dt * a;
        d.z = p.q + dt * dt * a;
    }
}

impl CentralDifference {
    /// Check the stability limit and start from v_{−1/2} = v₀ − (Δt/2) a₀,
    /// so that the first half-step velocity is v₀ + (Δt/2) a₀.
    pub fn new(sc: &Resolved, sys: &mut System, st: &mut State, init: Initial) -> Result<Self> {
        let dt = sys.dt();
        let limit = stability_limit(sc, sys, &init.mass_factor);
        if dt > limit.dt_max {
            return Err(Error::invalid(
                "time.step",
                format!("{dt:e} s"),
                format!(
                    "integrator.method = central_difference is stable for Δt ≤ 2/ω_max = {:.4e} s, with ω_max = {:.6e} rad/s the highest natural frequency of the assembled model (Lanczos; the element bound is {:.4e} rad/s): use time.step ≤ {:.4e} s or an implicit method",
                    limit.dt_max, limit.omega_max, limit.omega_element_bound, limit.dt_max
                ),
            ));
        }
        Ok(Self::start(sys, st, init, limit))
    }

    /// As [`CentralDifference::new`] without refusing a step above the
    /// limit: for stability studies that show what happens beyond it (the
    /// highest mode grows by |z| > 1 per step; `tests/methods.rs`).
    pub fn unchecked(sc: &Resolved, sys: &mut System, st: &mut State, init: Initial) -> Self {
        let limit = stability_limit(sc, sys, &init.mass_factor);
        Self::start(sys, st, init, limit)
    }

    fn start(sys: &mut System, st: &mut State, init: Initial, limit: StabilityLimit) -> Self {
        let dt = sys.dt();
        // an impact law's gap rate: the gap's increment over the step
        sys.set_increment_rates();
        let n = sys.beam().n;
        let nc = sys.contacts();
        for i in 0..n {
            st.v[i] -= 0.5 * dt * init.a[i];
        }
        for j in 0..nc {
            st.q_dot[j] -= 0.5 * dt * init.aq[j];
        }
        let rule = CentralMass { dt };
        CentralDifference {
            effective: MassSteps::effective(&rule, &sys.physics.masses),
            masses: MassSteps::new(&sys.physics.masses),
            rule,
            dt,
            mass_factor: init.mass_factor,
            d_pred: vec![0.0; n],
            rhs: vec![0.0; n * rhs_columns(nc)],
            b0: vec![0.0; n],
            limit,
        }
    }
}

impl Stepper for CentralDifference {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let dt = self.dt;
        let k = sys.columns();
        let (t0, t1) = (st.t, st.next_time(dt));
        sys.place(t0, t0, t1);
        let beam = sys.beam();
        // a★ = M⁻¹(f_n − K d_n + moving forces), z_c = M⁻¹ s_c r_c, the
        // product K d_n inside the forward sweep
        self.rhs.fill(0.0);
        sys.scatter_loads(&mut self.rhs, k, 1.0);
        let column = Affine {
            h: &beam.load,
            k: &beam.stiffness,
            u: &st.d,
        };
        self.mass_factor
            .solve_affine(&mut self.rhs, k, &column, &mut self.b0);
        for (dp, (d, v)) in self.d_pred.iter_mut().zip(st.d.iter().zip(&st.v)) {
            *dp = d + dt * v;
        }
        self.masses.begin(st);
        self.masses
            .predict(&self.rule, &self.effective, &sys.physics.masses);
        let map = StepMap {
            solved: &self.rhs,
            c_d: dt * dt,
            c_v: dt,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Vector(&st.v),
            alpha_weight: 0.0,
            masses: self.masses.predictions(),
        };
        sys.solve_contact(&map, st)?;
        let lambda = sys.multipliers();
        let dt2 = dt * dt;
        for (i, a) in combine(&self.rhs, k, lambda).enumerate() {
            st.v[i] += dt * a;
            st.d[i] = self.d_pred[i] + dt2 * a;
        }
        self.masses
            .finish(&self.rule, &self.effective, &sys.physics.masses, lambda);
        self.masses.end(st);
        Ok(())
    }

    /// The chain's dofs step with the same rule (`mass_step.rs`).
    fn carries_chains(&self) -> bool {
        true
    }
}
