//! The system every time integrator shares (MODEL §2, §5, §6, §9.1), in
//! three parts: what a run steps (`physics.rs`: the beam, the carriers and
//! their mass dofs, the droppers, a manufactured source), the contact
//! law's state (`law_state.rs`: the law, the multipliers, how a method's
//! multipliers are read), and the contact problem of the current step
//! (`contact_problem.rs`, scratch).
//!
//! A method solves its step with the contact multipliers λ as unknowns and
//! describes the result in a [`StepMap`] (`step_map.rs`);
//! [`System::solve_contact`] has the pair `(g_free, W)` formed from it at
//! the law's level (`contact_problem.rs`: gaps at force level, gap rates
//! at velocity level) and calls the law — a force-level law, or the
//! velocity-level impact law that owns Moreau's index set, restitution and
//! the gap-rate memory (`crate::contact::Impact`). So every contact
//! formulation works with every method through this one seam, and a law
//! never reaches into a method. A law that fails stops the run with the
//! problem it was given ([`crate::Error::Contact`]).

use crate::contact::{ContactFailed, ContactFailure, ContactProblem, Level, RunLaw};
use crate::error::{Error, Result};
use crate::model::banded::{BandedLdlt, SymBand};
use crate::model::beam::BeamModel;
use crate::resolve::Resolved;
use crate::scene::{Formulation, Placement};

use super::carrier::PlaceTimes;
use super::chain::Chain;
use super::contact_problem::{ProblemBuilder, contact_coef};
use super::dropper::{ContactPair, DropperSample, Droppers};
use super::form_finding::FormFound;
use super::law_state::LawState;
use super::mass_dofs::MassDof;
use super::physics::Physics;
use super::state::State;
use super::step_map::{Lanes, Multipliers, StepMap};
use crate::model::banded::rhs_columns;

/// The shared system (module docs): what a run steps, its contact law's
/// state, and the contact problem of the current step.
pub struct System {
    /// The beam, the carriers and their mass dofs, the droppers, a
    /// manufactured source (`physics.rs`).
    pub(crate) physics: Physics,
    /// The contact law and what it keeps between steps (`law_state.rs`).
    pub(crate) law: LawState,
    /// The pair (g_free, W) of the current step, formed in place
    /// (scratch, `contact_problem.rs`).
    problem: ProblemBuilder,
    /// The line at rest after form-finding (`form_finding.rs`, eq. F1–F5);
    /// `None` without a dropper design height.
    form: Option<FormFound>,
}

/// Consistent initial accelerations (MODEL §5), for the methods that need them.
pub struct Initial {
    /// Beam accelerations a₀.
    pub a: Vec<f64>,
    /// Mass accelerations q̈₀, one per contact.
    pub aq: Vec<f64>,
    /// The factor of M, for a method that solves with M again (central difference).
    pub mass_factor: BandedLdlt,
}

impl System {
    /// Assemble the beam and the carriers of a validated scene.
    pub fn new(sc: &Resolved) -> Result<Self> {
        Self::with_beam(sc, BeamModel::build(&sc.beam, &sc.mesh_plan())?)
    }

    /// [`System::new`] with the beam already built (`BeamModel::build`
    /// of `sc`, or of a scene with the same beam and discretization: a
    /// batch builds a basis once for all its runs).
    pub fn with_beam(sc: &Resolved, beam: BeamModel) -> Result<Self> {
        let mut physics = Physics::new(sc, beam);
        let form = super::form_finding::form_find(sc, &mut physics)?;
        let (nc, nd) = (physics.masses.len(), physics.droppers.rows());
        Ok(System {
            law: LawState::new(sc, nc, nd),
            problem: ProblemBuilder::new(nc, nd),
            physics,
            form,
        })
    }

    /// The line at rest after form-finding (`docs/lines.md` eq. F1–F5), when
    /// a dropper has a design height.
    pub fn form_found(&self) -> Option<&FormFound> {
        self.form.as_ref()
    }

    /// The discretized beam: M, K, the distributed load, point vectors.
    pub fn beam(&self) -> &BeamModel {
        &self.physics.beam
    }

    /// The damping matrix C (docs/lines.md §10.4), `None` without damping.
    pub fn damping(&self) -> Option<&SymBand> {
        self.physics.damping.as_ref()
    }

    /// Time step Δt, s.
    pub fn dt(&self) -> f64 {
        self.physics.dt
    }

    /// Number of contacts (mass–spring carriers).
    pub fn contacts(&self) -> usize {
        self.physics.masses.len()
    }

    /// Columns of a right-hand side for [`System::scatter_loads`]:
    /// `rhs_columns` of the number of contacts.
    pub fn columns(&self) -> usize {
        rhs_columns(self.physics.masses.len())
    }

    /// Keep the multipliers of the step just taken before the next solve
    /// replaces them ([`Multipliers::Held`]).
    pub(crate) fn hold_multipliers(&mut self) {
        self.law.hold_multipliers();
    }

    /// A method that takes impacts itself asks for the restitution e of
    /// `contact.formulation = "impact"`, its law then at force level
    /// ([`LawState::impacts_taken_by_method`]); `None` for any other
    /// formulation.
    pub(crate) fn take_impacts(&mut self) -> Option<f64> {
        let nc = self.contacts();
        self.law.impacts_taken_by_method(nc)
    }

    /// The contact force of contact `j` reported after step `step`, N
    /// ([`Multipliers`]).
    #[inline]
    pub(crate) fn reported_force(&self, j: usize, step: usize) -> f64 {
        self.law.reported_force(j, step, self.physics.dt)
    }

    /// True when the scene has a manufactured source (MODEL §11).
    pub(crate) fn has_source(&self) -> bool {
        self.physics.has_source()
    }

    /// A manufactured source's whole load on the beam at `t` (MODEL §11),
    /// in the basis, into `out` ([`Physics::source_load_into`]).
    pub(crate) fn source_load_into(&mut self, t: f64, out: &mut [f64]) {
        self.physics.source_load_into(t, out);
    }

    /// Each mass dof's constant force plus its external force and a
    /// manufactured mass source at `t` (MODEL §11), for a method that
    /// holds the mass's force over the step itself (`modal_exact`, at the
    /// step's midpoint). No-op without either.
    pub(crate) fn set_mass_source(&mut self, t: f64) {
        self.physics.set_mass_source(t);
    }

    /// The multi-mass pantograph of each contact (`None` for a single
    /// mass), one per contact.
    pub(crate) fn chains(&self) -> &[Option<Chain>] {
        &self.physics.masses.chains
    }

    /// True when some carrier is a multi-mass pantograph.
    pub fn has_chains(&self) -> bool {
        self.physics.masses.has_chains()
    }

    /// True when the run has external forces on its mass dofs (a series,
    /// or a force held with [`System::hold_external_force`]).
    pub(crate) fn has_external_force(&self) -> bool {
        self.physics.masses.has_external_force()
    }

    /// Hold `newtons` (in +v, MODEL §2) on contact `j`'s mass from the next
    /// step on, until changed, on top of its series if any
    /// (`external_force.rs`). Allocates the first time only.
    pub fn hold_external_force(&mut self, j: usize, newtons: f64) {
        self.physics.masses.hold_external_force(j, newtons);
    }

    /// The force held on contact `j`'s mass ([`System::hold_external_force`]),
    /// N in +v; 0 when none.
    pub fn held_external_force(&self, j: usize) -> f64 {
        self.physics.masses.held_external_force(j)
    }

    /// The mass dofs, one per contact.
    pub fn masses(&self) -> &[MassDof] {
        &self.physics.masses.heads
    }

    /// The multipliers of the last contact solve (N, or N·s for impulses),
    /// one per contact.
    pub fn multipliers(&self) -> &[f64] {
        &self.law.lambda[..self.physics.masses.len()]
    }

    /// Number of droppers (`[[dropper]]`, tension-only and linear).
    pub fn droppers(&self) -> usize {
        self.physics.droppers.len()
    }

    /// Each dropper's force (N) and slack state, in scene order, for the
    /// beam dofs `d` and velocities `v` of the state the last step reached
    /// (`dropper.rs`): the tension-only ones' multipliers, the linear ones'
    /// k_d e + c_d ė.
    pub fn dropper_samples_into(&self, d: &[f64], v: &[f64], out: &mut [DropperSample]) {
        self.physics.droppers.samples_into(d, v, out);
    }

    /// The level the contact law works at during the run.
    pub fn level(&self) -> Level {
        self.law.level()
    }

    /// Declare how the method's multipliers are to be read; impulses make
    /// the law work at velocity level (called once, before the run).
    pub(crate) fn set_multipliers(&mut self, m: Multipliers) {
        self.law.set_multipliers(m, self.physics.masses.len());
    }

    /// Make a velocity-level law (`contact.formulation = "impact"`) take
    /// the gap's increment over the step as the gap rate,
    /// ġ_{n+1/2} = (g_{n+1} − g_n)/Δt (`contact_problem.rs`,
    /// `ProblemBuilder::increment`): for a method whose displacement
    /// advances by its own half-step velocity, d_{n+1} = d_n + Δt v_{n+1/2}
    /// (central difference), that is the rate its velocity gives the gap,
    /// exactly, with the carrier's motion between t_n and t_{n+1} in it.
    /// The convective rate at t_{n+1} read with v_{n+1/2} is off by
    /// O(Δt)·V(2w_xt + V w_xx): the position gap then drifts at that rate,
    /// and where it drifts open the contact leaves Moreau's index set and
    /// comes back with an impact (docs/verification.md, "Central difference
    /// with the impact law"). A force-level law ignores it (called once,
    /// before the run).
    pub fn set_increment_rates(&mut self) {
        self.law.increment_rates = true;
    }

    /// The time the contact force recorded at `t` (after a step) acts at,
    /// as a lag in steps: `(t − t_force)/Δt` of the method's last
    /// [`System::place`] (generalized-α α_f, central difference 1, Bathe
    /// and backward Euler 0), or ½ for impulses (P/Δt is the step's mean
    /// force). A reference force is compared at `t − lag·Δt`.
    pub fn force_lag(&self, t: f64) -> f64 {
        // a deliberate defect of the test build (`crate::defects`)
        if crate::defects::on(crate::defects::Defect::SamplingLag) {
            return 0.5 + self.force_lag_of(t);
        }
        self.force_lag_of(t)
    }

    /// [`System::force_lag`] itself.
    fn force_lag_of(&self, t: f64) -> f64 {
        match self.law.multipliers {
            Multipliers::Impulses => 0.5,
            Multipliers::Held => 1.0,
            Multipliers::Forces => (t - self.physics.t_force) / self.physics.dt,
        }
    }

    /// Place the carriers for a step: moving forces at x_m(t_load), contact
    /// force directions r_f at x_m(t_force), gap rows r_g at x_m(t_gap).
    pub fn place(&mut self, t_load: f64, t_force: f64, t_gap: f64) {
        let velocity = self.law.level() == Level::Velocity;
        let at = PlaceTimes {
            load: t_load,
            force: t_force,
            gap: t_gap,
        };
        self.physics.place(at, velocity);
    }

    /// Add the moving forces scale·s·F·r_f into column 0 of `rhs` (k
    /// columns, row-major) and the contact directions s_c r_f,c into columns
    /// 1 + c. `scale` is 1 for a force balance, Δt for an impulse balance.
    pub fn scatter_loads(&self, rhs: &mut [f64], k: usize, scale: f64) {
        self.physics.scatter_loads_in(rhs, k, Lanes::ONE, scale)
    }

    /// [`System::scatter_loads`] into this run's columns of a batched
    /// right-hand side (`k` columns per run, [`Lanes`]).
    pub(crate) fn scatter_loads_in(&self, rhs: &mut [f64], k: usize, lanes: Lanes, scale: f64) {
        self.physics.scatter_loads_in(rhs, k, lanes, scale)
    }

    /// Add coef·λ_c·s_c r_f,c of every contact into `y` (one column): the
    /// contact forces' part of a right-hand side, after the solve.
    pub fn scatter_contact_directions(&self, y: &mut [f64], coef: f64) {
        self.scatter_contact_directions_in(y, Lanes::ONE, coef)
    }

    /// [`System::scatter_contact_directions`] into this run's lane of an
    /// interleaved vector.
    pub(crate) fn scatter_contact_directions_in(&self, y: &mut [f64], lanes: Lanes, coef: f64) {
        for c in &self.physics.carriers {
            if let Some(j) = c.contact {
                c.pv_f
                    .scatter(coef * self.law.lambda[j] * c.s, y, lanes.count, lanes.lane);
            }
        }
        if self.physics.droppers.rows() > 0 {
            self.physics
                .droppers
                .scatter_forces(y, lanes.count, lanes.lane, coef);
        }
    }

    /// Where the gap condition is imposed (MODEL §5).
    pub fn placement(&self) -> Placement {
        self.law.placement
    }

    /// Consistent initial accelerations: M a₀ = f(0) + Σ λ r, with the gap
    /// acceleration of each closed contact zero (the beam is straight and at
    /// rest, so g̈ = rᵀa − q̈). The contact law solves this
    /// acceleration-level problem; its λ is the force recorded at t = 0.
    pub fn initial(&mut self) -> Result<Initial> {
        self.initial_at(None)
    }

    /// [`System::initial`] from a displaced start at rest (`[time] initial
    /// = "static"`, `static_start.rs`): the wire at d₀ and the masses at
    /// q₀, so M a₀ = f(0) − K d₀ + Σ λ r and each mass's spring acts at
    /// its q₀. `None` is the straight wire with the masses at 0.
    pub(crate) fn initial_at(&mut self, start: Option<(&[f64], &[f64])>) -> Result<Initial> {
        let n = self.physics.beam.n;
        let nc = self.physics.masses.len();
        let k = rhs_columns(nc);
        let mass_factor = BandedLdlt::factor(&self.physics.beam.mass)?;
        self.place(0.0, 0.0, 0.0);
        let mut rhs = vec![0.0; n * k];
        for i in 0..n {
            rhs[i * k] = self.physics.beam.load[i];
        }
        let saved_masses = self.physics.masses.heads.clone();
        if let Some((d0, q0)) = start {
            let mut kd = vec![0.0; n];
            self.physics.beam.stiffness.mul_acc(d0, 1.0, &mut kd);
            for i in 0..n {
                rhs[i * k] -= kd[i];
            }
            // a mass's spring at q₀: its free force f₀ − k q₀ (a chain's
            // head: f₀ − (K z₀)₁ with its lower masses at z₀, chain.rs)
            let masses = &mut self.physics.masses;
            for ((m, q), ch) in masses.heads.iter_mut().zip(q0).zip(&masses.chains) {
                m.f0 -= match ch {
                    Some(ch) => ch.head_spring_force(),
                    None => m.k * q,
                };
            }
        }
        self.scatter_loads(&mut rhs, k, 1.0);
        // the slack droppers' initial corrections are known loads (`dropper.rs`)
        self.physics
            .droppers
            .initial(start.map(|s| s.0), &mut rhs, k);
        let contacts = &mut self.law.lambda[..nc];
        mass_factor.solve_many(&mut rhs, k);
        let problem = &mut self.problem;
        problem.acceleration(
            &self.physics.carriers,
            &self.physics.masses.heads,
            self.law.placement,
            &rhs,
            k,
        );
        let (g_free, w) = (&problem.g_free[..nc], &problem.w[..nc * nc]);
        if let Err(failure) = self
            .law
            .law
            .initial(g_free, w, contacts, &mut self.law.active[..nc])
        {
            self.physics.masses.heads = saved_masses;
            return Err(self.failure(0, 0.0, Level::Acceleration, failure));
        }
        // a penalty started static (static_start.rs, W7): with an absolute
        // κ the head starts at its static penetration, so its force at
        // t = 0 is κ times it; with a κ relative to the step the head
        // starts at the rigid equilibrium and the force is its static one
        // (the penetration λW/ρ builds over the first steps); not the
        // rest start's 0 either way
        if let (Some((d0, q0)), Formulation::Penalty) = (start, self.law.contact.formulation) {
            for c in &self.physics.carriers {
                if let Some(j) = c.contact {
                    self.law.lambda[j] = match self.law.contact.penalty.stiffness {
                        Some(kappa) => {
                            let penetration = q0[j] - c.s * c.pv_g.dot(d0);
                            if self.law.bilateral {
                                kappa * penetration
                            } else {
                                kappa * penetration.max(0.0)
                            }
                        }
                        None => self.law.static_forces.get(j).copied().unwrap_or(0.0),
                    };
                }
            }
        }
        let mut a = vec![0.0; n];
        for i in 0..n {
            let mut acc = rhs[i * k];
            for (j, l) in self.law.lambda[..nc].iter().enumerate() {
                acc += l * rhs[i * k + 1 + j];
            }
            a[i] = acc;
        }
        let aq = (0..nc)
            .map(|j| {
                (self.physics.masses.heads[j].f0 - self.law.lambda[j])
                    / self.physics.masses.heads[j].m
            })
            .collect();
        self.physics.masses.heads = saved_masses;
        Ok(Initial { a, aq, mass_factor })
    }

    /// The contact problem of a step (module docs): free gaps and Delassus
    /// matrix at the law's level, the law's multipliers into
    /// [`System::multipliers`]. `st` is the state at t_n; a failure names
    /// step n + 1 and saves the problem.
    pub fn solve_contact(&mut self, map: &StepMap, st: &State) -> Result<()> {
        self.solve_contact_in(map, Lanes::ONE, st)
    }

    /// [`System::solve_contact`] for a run stepping in a batch: `map`'s
    /// solved columns and beam vectors hold the batch's runs side by side
    /// ([`Lanes`]). Only the force level with the `end` placement steps in
    /// batches (`integrate::batch`), so `st` is read for its mass dofs and
    /// step count only.
    pub(crate) fn solve_contact_in(
        &mut self,
        map: &StepMap,
        lanes: Lanes,
        st: &State,
    ) -> Result<()> {
        let (nc, nd) = (self.physics.masses.len(), self.physics.droppers.rows());
        if nc == 0 && nd == 0 {
            return Ok(());
        }
        let problem = &mut self.problem;
        problem.gaps(&self.physics.carriers, self.law.placement, map, lanes, st);
        let solved = match &mut self.law.law {
            RunLaw::Velocity(law) => {
                debug_assert_eq!(lanes, Lanes::ONE, "the velocity level steps alone");
                if self.law.increment_rates {
                    problem.position(&self.physics.carriers, self.law.placement, map, lanes);
                    problem.increment(&self.physics.carriers, st, self.physics.dt);
                } else {
                    problem.velocity(&self.physics.carriers, map, st);
                }
                let (g, rate, w_v) = (&problem.g_free, &problem.rate_free, &problem.w_v);
                let solved = law.solve(g, rate, w_v, &mut self.law.lambda, &mut self.law.active);
                if self.law.increment_rates {
                    // ġ_{n+1/2} = ġ_free + W_v λ, the next step's restitution memory
                    problem.rates_after(&self.law.lambda, law.gap_rates_mut());
                }
                solved
            }
            RunLaw::Force(law) => {
                problem.position(&self.physics.carriers, self.law.placement, map, lanes);
                if nd == 0 {
                    law.solve(
                        &problem.g_free,
                        &problem.w,
                        &mut self.law.lambda,
                        &mut self.law.active,
                    )
                } else {
                    // the contacts and the slack droppers' rows (`dropper.rs`,
                    // D9–D10; a run with droppers steps alone)
                    debug_assert_eq!(lanes, Lanes::ONE, "droppers step alone");
                    let k = rhs_columns(nc);
                    let rows = self.physics.carriers.iter().filter_map(|c| {
                        let pv = match self.law.placement {
                            Placement::End => &c.pv_g,
                            Placement::Alpha => &c.pv_f,
                        };
                        c.contact.map(|i| (i, c.s, pv))
                    });
                    let coef_c = contact_coef(self.law.placement, map);
                    let pair = ContactPair {
                        g: &problem.g_free,
                        w: &problem.w,
                        stride: nc + nd,
                    };
                    let d = &mut self.physics.droppers;
                    d.begin(map, k, st, rows, coef_c, pair);
                    solve_with_droppers(
                        law.as_mut(),
                        d,
                        problem,
                        &mut self.law.lambda,
                        &mut self.law.active,
                    )
                }
            }
        };
        solved.map_err(|failure| {
            let step = st.step + 1;
            self.failure(
                step,
                st.next_time(self.physics.dt),
                self.law.level(),
                failure,
            )
        })
    }

    /// The contact problem of a method that forms the pair itself
    /// (`modal_exact`, MODEL §9.3: sums over modes): `g_free` (one per
    /// contact, m) and `w` (row-major nc × nc, m/N), at force level. The
    /// law's multipliers go into [`System::multipliers`]; a failure names
    /// step n + 1 and saves the problem, as [`System::solve_contact`].
    pub fn solve_formed(&mut self, g_free: &[f64], w: &[f64], st: &State) -> Result<()> {
        let nc = self.physics.masses.len();
        if nc == 0 {
            return Ok(());
        }
        let RunLaw::Force(law) = &mut self.law.law else {
            unreachable!("modal_exact works at force level")
        };
        let problem = &mut self.problem;
        problem.set(g_free, w);
        law.solve(
            &problem.g_free,
            &problem.w,
            &mut self.law.lambda,
            &mut self.law.active,
        )
        .map_err(|failure| {
            let step = st.step + 1;
            self.failure(
                step,
                st.next_time(self.physics.dt),
                Level::Position,
                failure,
            )
        })
    }

    /// The error for a failed law, with the problem it was given: the
    /// builder's pair, or the impact law's problem on its index set. A
    /// velocity-level Delassus failure gets its kinematics here (V·Δt of
    /// the contact's carrier and the element length h).
    fn failure(&self, step: usize, time: f64, level: Level, mut failure: ContactFailure) -> Error {
        let (g_free, w) = match (&self.law.law, level) {
            (RunLaw::Velocity(law), Level::Velocity) => law.problem(),
            (_, Level::Acceleration) => {
                // the contacts' block alone (the droppers' forces are loads at t = 0)
                let nc = self.physics.masses.len();
                (&self.problem.g_free[..nc], &self.problem.w[..nc * nc])
            }
            _ => {
                let ns = self.problem.size;
                (&self.problem.g_free[..ns], &self.problem.w[..ns * ns])
            }
        };
        if let ContactFailure::VelocityDelassus {
            contact, travel, h, ..
        } = &mut failure
        {
            let speed = self
                .physics
                .carriers
                .iter()
                .find(|c| c.contact == Some(*contact))
                .map_or(0.0, |c| c.speed);
            *travel = speed * self.physics.dt;
            *h = self.physics.beam.h;
        }
        Error::Contact {
            step,
            time,
            run: String::new(),
            failure: Box::new(ContactFailed {
                failure,
                problem: ContactProblem {
                    level,
                    g_free: g_free.to_vec(),
                    w: w.to_vec(),
                    contact: self.law.contact.clone(),
                },
            }),
        }
    }

    /// After a step (state at t_{n+1}): keep the gap rates ġ_{n+1} that the
    /// next velocity-level step's restitution term needs.
    pub fn end_step(&mut self, st: &State) {
        self.keep_gap_rates(&st.d, &st.v, &st.q_dot);
    }

    /// Keep the gap rates ġ = s(r_gᵀv + V r_g'ᵀd) − q̇ of a state given by
    /// its parts (a method with sub-steps calls this between them), for the
    /// restitution term of the next velocity-level problem.
    pub fn keep_gap_rates(&mut self, d: &[f64], v: &[f64], q_dot: &[f64]) {
        let RunLaw::Velocity(law) = &mut self.law.law else {
            return;
        };
        if self.law.increment_rates {
            // the solve kept the increments' rates
            return;
        }
        let rates = law.gap_rates_mut();
        for c in &self.physics.carriers {
            let Some(j) = c.contact else { continue };
            rates[j] = c.gap_rate(d, v, q_dot[j]);
        }
    }
}

/// The contact problem of a step with tension-only droppers
/// (`dropper.rs`, D9–D10): the pair over the contacts and the set of slack
/// droppers, solved by the law, again while a dropper outside the set
/// pushes (the set only grows: at most m + 1 passes). The packed pair
/// stays in `problem` (its size too) for a failure's record.
fn solve_with_droppers(
    law: &mut dyn crate::contact::ContactLaw,
    d: &mut Droppers,
    problem: &mut ProblemBuilder,
    lambda: &mut [f64],
    active: &mut [bool],
) -> std::result::Result<(), ContactFailure> {
    let passes = d.rows() + 1;
    for _ in 0..passes {
        let ns = d.assemble(&mut problem.g_free, &mut problem.w)?;
        problem.size = ns;
        let (g, w) = (&problem.g_free[..ns], &problem.w[..ns * ns]);
        let (lam, act) = (&mut lambda[..ns], &mut active[..ns]);
        if ns > 0 {
            law.solve(g, w, lam, act)?;
        }
        if d.settle(g, w, lam, act) {
            return Ok(());
        }
    }
    Err(ContactFailure::Cycling { passes })
}
