//! The system every time integrator shares (MODEL §2, §5, §6, §9.1): the
//! discretized beam, the carriers (`carrier.rs`), the mass dofs'
//! parameters, a manufactured source's loads, and the run's contact law.
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
use crate::model::source::Source;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, ContactKind, ContactSpec, Formulation, Placement, Support};

use super::State;
use super::carrier::{Carrier, MassDof};
use super::chain::Chain;
use super::contact_problem::{ProblemBuilder, contact_coef};
use super::dropper::{DropperSample, Droppers};
use super::external_force::ExternalForces;
use super::step_map::{Lanes, Multipliers, StepMap};
use crate::model::banded::rhs_columns;

/// Contact forces beyond this multiple of the carriers' force scale
/// (k(δ0 + L) + m g + F) are taken as a blow-up: no physical run of this model
/// comes within orders of magnitude of it.
const FORCE_BOUND_FACTOR: f64 = 1e3;

/// A manufactured solution's source during a run (MODEL §11): the smooth
/// part projected on the basis ([`Source`]), the load time of the current
/// step, and the mass dofs' constant forces without the mass source.
#[derive(Debug, Clone)]
struct SourceState {
    source: Source,
    /// t at which [`System::place`] put the loads, s.
    t_load: f64,
    /// kδ0 − s m g of each mass dof (its `f0` is this plus the mass source).
    f0: Vec<f64>,
}

/// The shared system (module docs).
pub struct System {
    pub(crate) beam: BeamModel,
    pub(crate) carriers: Vec<Carrier>,
    pub(crate) masses: Vec<MassDof>,
    /// The multi-mass pantograph of each contact (`chain.rs`; `None` for
    /// a single mass): its head is the contact's mass dof in `masses`.
    pub(crate) chains: Vec<Option<Chain>>,
    /// Time step Δt, s.
    pub(crate) dt: f64,
    pub(crate) placement: Placement,
    pub(crate) bilateral: bool,
    /// Beam length L, m.
    pub(crate) length: f64,
    pub(crate) supports: (Support, Support),
    /// String wave speed c = sqrt(T/ρA), m/s.
    pub(crate) wave_speed: f64,
    /// Largest |λ| accepted before a run is taken as diverged, N.
    pub(crate) force_bound: f64,
    /// The contact law, at the level it works at.
    law: RunLaw,
    /// The contact settings, saved with a failed problem.
    contact: ContactSpec,
    multipliers: Multipliers,
    /// The pair (g_free, W) of the current step.
    problem: ProblemBuilder,
    pub(crate) lambda: Vec<f64>,
    /// The contacts' static forces of a static start (`static_start.rs`,
    /// W7–W8), N; empty otherwise.
    pub(crate) static_forces: Vec<f64>,
    /// The previous step's multipliers ([`Multipliers::Held`] only).
    held_prev: Vec<f64>,
    pub(crate) active: Vec<bool>,
    /// The damping matrix C = αM + βK + Σ c_a r_a r_aᵀ (docs/lines.md
    /// §10.4); `None` without damping, and then no method does C's work.
    damping: Option<SymBand>,
    /// A manufactured scene's source; `None` costs a branch per step.
    source: Option<SourceState>,
    /// The droppers (`dropper.rs`): the slack tension-only ones are rows
    /// of the contact problem after the contacts' (their multipliers in
    /// `lambda[nc..]` during the solve), every one's force and state kept
    /// there; none costs a branch per step.
    pub(crate) droppers: Droppers,
    /// The time the last [`System::place`] put the contact forces at, s.
    t_force: f64,
    /// External forces on the mass dofs (`external_force.rs`); `None`
    /// costs a branch per step.
    external: Option<ExternalForces>,
    /// True when the velocity-level law takes the gap's increment over the
    /// step as its rate ([`System::set_increment_rates`]: central
    /// difference); false for the convective rate at t_{n+1}.
    increment_rates: bool,
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
    pub fn with_beam(sc: &Resolved, mut beam: BeamModel) -> Result<Self> {
        let mut nc = 0;
        let mut masses = Vec::new();
        let mut chains = Vec::new();
        let mut force_scale: f64 = 0.0;
        let carriers: Vec<Carrier> = sc
            .carriers
            .iter()
            .map(|p| {
                let s = p.side.sign();
                let contact = match p.kind {
                    CarrierKind::MassSpring {
                        mass,
                        stiffness,
                        damping,
                        preload,
                    } if p.chain.is_some() => {
                        // a multi-mass pantograph: its head as the mass
                        // dof, with the static contact force as its f0
                        // (chain.rs: the chain starts at rest in its static
                        // state, so at t = 0 only the head's balance with λ
                        // differs from it)
                        let ch = Chain::new(&p.chain.expect("guarded"), s, sc.g);
                        nc += 1;
                        force_scale = force_scale.max(
                            stiffness * (preload + sc.beam.length)
                                + ch.static_force.abs()
                                + p.chain.map_or(0.0, |c| c.uplift + c.total_mass() * sc.g),
                        );
                        masses.push(MassDof {
                            m: mass,
                            k: stiffness,
                            c: damping,
                            f0: ch.static_force,
                        });
                        chains.push(Some(ch));
                        Some(nc - 1)
                    }
                    CarrierKind::MassSpring {
                        mass,
                        stiffness,
                        damping,
                        preload,
                    } => {
                        chains.push(None);
                        nc += 1;
                        force_scale =
                            force_scale.max(stiffness * (preload + sc.beam.length) + mass * sc.g);
                        // a deliberate defect of the test build (`crate::defects`)
                        let half = crate::defects::on(crate::defects::Defect::HalfDashpot);
                        masses.push(MassDof {
                            m: mass,
                            k: stiffness,
                            c: if half { 0.5 * damping } else { damping },
                            f0: stiffness * preload - s * mass * sc.g,
                        });
                        Some(nc - 1)
                    }
                    CarrierKind::Force { force } => {
                        force_scale = force_scale.max(force);
                        None
                    }
                };
                Carrier::new(p.clone(), contact, &beam)
            })
            .collect();
        let droppers = Droppers::new(&sc.droppers, &beam, nc);
        // C = αM + βK + dashpots from K *before* the tension-only droppers'
        // springs join it: a slack dropper carries no force, so its spring
        // must not put a dashpot β k_d r_d r_dᵀ in C (the linear droppers'
        // springs are in K already, and in βK as before)
        let tie_dashpots = sc
            .beam
            .messenger
            .as_ref()
            .map_or(&[][..], |m| &m.tie_dashpots[..]);
        let mut damping =
            beam.damping_matrix_with_ties(sc.damping, &sc.beam.attachments, tie_dashpots);
        // the tension-only droppers' dashpots in C (`dropper.rs`, D12), into
        // a zero C of K's band when nothing else damps
        if droppers.has_dashpots() {
            let c = damping.get_or_insert_with(|| beam.stiffness.combine(0.0, &beam.mass, 0.0));
            droppers.add_dashpots(c);
        }
        // every dropper's spring in K and preload in the load (`dropper.rs`, D7)
        droppers.add_springs(&mut beam.stiffness);
        droppers.add_preloads(&mut beam.load);
        let nd = droppers.rows();
        let law = RunLaw::with_droppers(&sc.contact, nc, nd);
        let source = sc.manufactured.as_ref().map(|m| SourceState {
            source: Source::new(&beam, m),
            t_load: 0.0,
            f0: masses.iter().map(|m| m.f0).collect(),
        });
        let external = sc
            .external_forces
            .iter()
            .any(Option::is_some)
            .then(|| external_forces(sc, &carriers, &masses));
        if let Some(ext) = &external {
            // the initial state's accelerations see the force at t = 0
            for (j, m) in masses.iter_mut().enumerate() {
                m.f0 = ext.f0(j, 0.0);
            }
        }
        Ok(System {
            damping,
            source,
            external,
            increment_rates: false,
            t_force: 0.0,
            dt: sc.dt,
            placement: sc.contact.placement,
            bilateral: sc.contact.kind == ContactKind::Bilateral,
            length: sc.beam.length,
            supports: (sc.beam.left, sc.beam.right),
            wave_speed: sc.beam.wave_speed(),
            force_bound: FORCE_BOUND_FACTOR * force_scale.max(f64::MIN_POSITIVE),
            law,
            contact: sc.contact.clone(),
            multipliers: Multipliers::Forces,
            problem: ProblemBuilder::new(nc, nd),
            lambda: vec![0.0; nc + nd],
            static_forces: Vec::new(),
            held_prev: vec![0.0; nc + nd],
            active: vec![false; nc + nd],
            droppers,
            beam,
            carriers,
            masses,
            chains,
        })
    }

    /// The discretized beam: M, K, the distributed load, point vectors.
    pub fn beam(&self) -> &BeamModel {
        &self.beam
    }

    /// The damping matrix C (docs/lines.md §10.4), `None` without damping.
    pub fn damping(&self) -> Option<&SymBand> {
        self.damping.as_ref()
    }

    /// Time step Δt, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Number of contacts (mass–spring carriers).
    pub fn contacts(&self) -> usize {
        self.masses.len()
    }

    /// Columns of a right-hand side for [`System::scatter_loads`]:
    /// [`rhs_columns`] of the number of contacts.
    pub fn columns(&self) -> usize {
        rhs_columns(self.masses.len())
    }

    /// Keep the multipliers of the step just taken before the next solve
    /// replaces them ([`Multipliers::Held`]: the reported force is the
    /// mean of the two held forces around a time step).
    pub(crate) fn hold_multipliers(&mut self) {
        self.held_prev.copy_from_slice(&self.lambda);
    }

    /// The contact force of contact `j` reported after step `step`, N
    /// ([`Multipliers`]).
    pub(crate) fn reported_force(&self, j: usize, step: usize) -> f64 {
        match self.multipliers {
            Multipliers::Forces => self.lambda[j],
            // the impulse of the step over its length; at t = 0 the
            // recorded value is the initial force itself
            Multipliers::Impulses if step > 0 => self.lambda[j] / self.dt,
            Multipliers::Impulses => self.lambda[j],
            // at t_{n−1}: the mean of the forces held over the steps on
            // either side; after the first step, the initial force
            Multipliers::Held if step > 1 => 0.5 * (self.lambda[j] + self.held_prev[j]),
            Multipliers::Held if step == 1 => self.held_prev[j],
            Multipliers::Held => self.lambda[j],
        }
    }

    /// True when the scene has a manufactured source (MODEL §11).
    pub(crate) fn has_source(&self) -> bool {
        self.source.is_some()
    }

    /// A manufactured source's whole load on the beam at `t` (MODEL §11),
    /// in the basis, into `out` (overwritten): the smooth part plus each
    /// carrier's point load at x_m(t). For a method that samples the load
    /// itself (`modal_exact`'s first-order hold); zero without a source.
    pub(crate) fn source_load_into(&mut self, t: f64, out: &mut [f64]) {
        out.fill(0.0);
        let Some(src) = &self.source else { return };
        src.source.add_into(t, 1.0, out, 1, 0);
        let m = src.source.solution();
        for (i, c) in self.carriers.iter_mut().enumerate() {
            let p = m.point_load(i, t);
            self.beam
                .point_vector_into(c.props.motion.position(t), false, &mut c.pv_l);
            c.pv_l.scatter(p, out, 1, 0);
        }
    }

    /// Each mass dof's constant force plus a manufactured mass source at
    /// `t` (MODEL §11), for a method that holds the mass's force over the
    /// step itself (`modal_exact`, at the step's midpoint). No-op without
    /// a source.
    pub(crate) fn set_mass_source(&mut self, t: f64) {
        if let Some(ext) = &self.external {
            // external forces (and a source, if any): base + s·F_ext(t) + source
            for (i, c) in self.carriers.iter().enumerate() {
                if let Some(j) = c.contact {
                    let source = self
                        .source
                        .as_ref()
                        .map_or(0.0, |s| s.source.solution().mass_source(i, t));
                    self.masses[j].f0 = ext.f0(j, t) + source;
                }
            }
            return;
        }
        let Some(src) = &self.source else { return };
        let m = src.source.solution();
        for (i, c) in self.carriers.iter().enumerate() {
            if let Some(j) = c.contact {
                self.masses[j].f0 = src.f0[j] + m.mass_source(i, t);
            }
        }
    }

    /// The multi-mass pantograph of each contact (`None` for a single
    /// mass), one per contact.
    pub fn chains(&self) -> &[Option<Chain>] {
        &self.chains
    }

    /// True when some carrier is a multi-mass pantograph.
    pub fn has_chains(&self) -> bool {
        self.chains.iter().any(Option::is_some)
    }

    /// True when the run has external forces on its mass dofs (a series,
    /// or a force held with [`System::hold_external_force`]).
    pub(crate) fn has_external_force(&self) -> bool {
        self.external.is_some()
    }

    /// Hold `newtons` (in +v, MODEL §2) on contact `j`'s mass from the next
    /// step on, until changed, on top of its series if any
    /// (`external_force.rs`). Allocates the first time only.
    pub fn hold_external_force(&mut self, j: usize, newtons: f64) {
        if self.external.is_none() {
            let base = match &self.source {
                Some(src) => src.f0.clone(),
                None => self.masses.iter().map(|m| m.f0).collect(),
            };
            let side = self
                .carriers
                .iter()
                .filter(|c| c.contact.is_some())
                .map(|c| c.s)
                .collect();
            let nc = self.masses.len();
            self.external = Some(ExternalForces {
                base,
                side,
                series: vec![None; nc],
                held: vec![0.0; nc],
            });
        }
        if let Some(ext) = &mut self.external {
            ext.held[j] = newtons;
        }
    }

    /// The force held on contact `j`'s mass ([`System::hold_external_force`]),
    /// N in +v; 0 when none.
    pub fn held_external_force(&self, j: usize) -> f64 {
        self.external.as_ref().map_or(0.0, |e| e.held[j])
    }

    /// The mass dofs, one per contact.
    pub fn masses(&self) -> &[MassDof] {
        &self.masses
    }

    /// The multipliers of the last contact solve (N, or N·s for impulses),
    /// one per contact.
    pub fn multipliers(&self) -> &[f64] {
        &self.lambda[..self.masses.len()]
    }

    /// Number of droppers (`[[dropper]]`, tension-only and linear).
    pub fn droppers(&self) -> usize {
        self.droppers.len()
    }

    /// Each dropper's force (N) and slack state, in scene order, for the
    /// beam dofs `d` and velocities `v` of the state the last step reached
    /// (`dropper.rs`): the tension-only ones' multipliers, the linear ones'
    /// k_d e + c_d ė.
    pub fn dropper_samples_into(&self, d: &[f64], v: &[f64], out: &mut [DropperSample]) {
        self.droppers.samples_into(d, v, out);
    }

    /// The level the contact law works at during the run.
    pub fn level(&self) -> Level {
        self.law.level()
    }

    /// Declare how the method's multipliers are to be read; impulses make
    /// the law work at velocity level (called once, before the run).
    pub fn set_multipliers(&mut self, m: Multipliers) {
        self.multipliers = m;
        if m == Multipliers::Impulses {
            self.law.make_velocity(&self.contact, self.masses.len());
        }
    }

    /// Make a velocity-level law (`contact.formulation = "impact"`) take
    /// the gap's increment over the step as the gap rate,
    /// ġ_{n+1/2} = (g_{n+1} − g_n)/Δt (`contact_problem.rs`,
    /// [`ProblemBuilder::increment`]): for a method whose displacement
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
        self.increment_rates = true;
    }

    /// How the multipliers are read.
    pub fn multiplier_kind(&self) -> Multipliers {
        self.multipliers
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
        match self.multipliers {
            Multipliers::Impulses => 0.5,
            Multipliers::Held => 1.0,
            Multipliers::Forces => (t - self.t_force) / self.dt,
        }
    }

    /// Place the carriers for a step: moving forces at x_m(t_load), contact
    /// force directions r_f at x_m(t_force), gap rows r_g at x_m(t_gap).
    pub fn place(&mut self, t_load: f64, t_force: f64, t_gap: f64) {
        let velocity = self.law.level() == Level::Velocity;
        self.t_force = t_force;
        // deliberate defects of the test build (`crate::defects`)
        use crate::defects::{Defect, on};
        let t_force = if on(Defect::ForceBehind) {
            t_force - self.dt
        } else {
            t_force
        };
        let t_load = if on(Defect::SourceLate) && self.source.is_some() {
            t_load + 0.5 * self.dt
        } else {
            t_load
        };
        if let Some(src) = &mut self.source {
            // a manufactured source: its loads at t_load (MODEL §11)
            src.t_load = t_load;
            let m = src.source.solution();
            for (i, c) in self.carriers.iter_mut().enumerate() {
                c.point = m.point_load(i, t_load);
                if c.contact.is_some() {
                    self.beam.point_vector_into(
                        c.props.motion.position(t_load),
                        false,
                        &mut c.pv_l,
                    );
                }
            }
        }
        self.set_mass_source(t_load);
        for c in self.carriers.iter_mut() {
            c.place(&self.beam, (t_load, t_force, t_gap), velocity);
        }
    }

    /// Add the moving forces scale·s·F·r_f into column 0 of `rhs` (k
    /// columns, row-major) and the contact directions s_c r_f,c into columns
    /// 1 + c. `scale` is 1 for a force balance, Δt for an impulse balance.
    pub fn scatter_loads(&self, rhs: &mut [f64], k: usize, scale: f64) {
        self.scatter_loads_in(rhs, k, Lanes::ONE, scale)
    }

    /// [`System::scatter_loads`] into this run's columns of a batched
    /// right-hand side (`k` columns per run, [`Lanes`]).
    pub fn scatter_loads_in(&self, rhs: &mut [f64], k: usize, lanes: Lanes, scale: f64) {
        let stride = k * lanes.count;
        if let Some(src) = &self.source {
            // a manufactured source: the smooth part and each carrier's
            // point load, at the load time of `place` (MODEL §11)
            src.source
                .add_into(src.t_load, scale, rhs, stride, lanes.col(0));
            for c in &self.carriers {
                let pv = if c.contact.is_some() {
                    &c.pv_l
                } else {
                    &c.pv_f
                };
                pv.scatter(c.point * scale, rhs, stride, lanes.col(0));
            }
        }
        for c in &self.carriers {
            match (c.props.kind, c.contact) {
                (CarrierKind::Force { force }, _) => {
                    c.pv_f
                        .scatter(c.s * force * scale, rhs, stride, lanes.col(0))
                }
                (_, Some(j)) => c.pv_f.scatter(c.s, rhs, stride, lanes.col(1 + j)),
                _ => {}
            }
        }
    }

    /// Add coef·λ_c·s_c r_f,c of every contact into `y` (one column): the
    /// contact forces' part of a right-hand side, after the solve.
    pub fn scatter_contact_directions(&self, y: &mut [f64], coef: f64) {
        self.scatter_contact_directions_in(y, Lanes::ONE, coef)
    }

    /// [`System::scatter_contact_directions`] into this run's lane of an
    /// interleaved vector.
    pub fn scatter_contact_directions_in(&self, y: &mut [f64], lanes: Lanes, coef: f64) {
        for c in &self.carriers {
            if let Some(j) = c.contact {
                c.pv_f
                    .scatter(coef * self.lambda[j] * c.s, y, lanes.count, lanes.lane);
            }
        }
        if self.droppers.rows() > 0 {
            self.droppers
                .scatter_forces(y, lanes.count, lanes.lane, coef);
        }
    }

    /// Where the gap condition is imposed (MODEL §5).
    pub fn placement(&self) -> Placement {
        self.placement
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
        let n = self.beam.n;
        let nc = self.masses.len();
        let k = rhs_columns(nc);
        let mass_factor = BandedLdlt::factor(&self.beam.mass)?;
        self.place(0.0, 0.0, 0.0);
        let mut rhs = vec![0.0; n * k];
        for i in 0..n {
            rhs[i * k] = self.beam.load[i];
        }
        let saved_masses = self.masses.clone();
        if let Some((d0, q0)) = start {
            let mut kd = vec![0.0; n];
            self.beam.stiffness.mul_acc(d0, 1.0, &mut kd);
            for i in 0..n {
                rhs[i * k] -= kd[i];
            }
            // a mass's spring at q₀: its free force f₀ − k q₀ (a chain's
            // head: f₀ − (K z₀)₁ with its lower masses at z₀, chain.rs)
            for ((m, q), ch) in self.masses.iter_mut().zip(q0).zip(&self.chains) {
                m.f0 -= match ch {
                    Some(ch) => ch.head_spring_force(),
                    None => m.k * q,
                };
            }
        }
        self.scatter_loads(&mut rhs, k, 1.0);
        // the slack droppers' initial corrections are known loads (`dropper.rs`)
        self.droppers.initial(start.map(|s| s.0), &mut rhs, k);
        let contacts = &mut self.lambda[..nc];
        mass_factor.solve_many(&mut rhs, k);
        let problem = &mut self.problem;
        problem.acceleration(&self.carriers, &self.masses, self.placement, &rhs, k);
        let (g_free, w) = (&problem.g_free[..nc], &problem.w[..nc * nc]);
        if let Err(failure) = self
            .law
            .initial(g_free, w, contacts, &mut self.active[..nc])
        {
            self.masses = saved_masses;
            return Err(self.failure(0, 0.0, Level::Acceleration, failure));
        }
        // a penalty started static (static_start.rs, W7): with an absolute
        // κ the head starts at its static penetration, so its force at
        // t = 0 is κ times it; with a κ relative to the step the head
        // starts at the rigid equilibrium and the force is its static one
        // (the penetration λW/ρ builds over the first steps); not the
        // rest start's 0 either way
        if let (Some((d0, q0)), Formulation::Penalty) = (start, self.contact.formulation) {
            for c in &self.carriers {
                if let Some(j) = c.contact {
                    self.lambda[j] = match self.contact.penalty.stiffness {
                        Some(kappa) => {
                            let penetration = q0[j] - c.s * c.pv_g.dot(d0);
                            if self.bilateral {
                                kappa * penetration
                            } else {
                                kappa * penetration.max(0.0)
                            }
                        }
                        None => self.static_forces.get(j).copied().unwrap_or(0.0),
                    };
                }
            }
        }
        let mut a = vec![0.0; n];
        for i in 0..n {
            let mut acc = rhs[i * k];
            for (j, l) in self.lambda[..nc].iter().enumerate() {
                acc += l * rhs[i * k + 1 + j];
            }
            a[i] = acc;
        }
        let aq = (0..nc)
            .map(|j| (self.masses[j].f0 - self.lambda[j]) / self.masses[j].m)
            .collect();
        self.masses = saved_masses;
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
    pub fn solve_contact_in(&mut self, map: &StepMap, lanes: Lanes, st: &State) -> Result<()> {
        let (nc, nd) = (self.masses.len(), self.droppers.rows());
        if nc == 0 && nd == 0 {
            return Ok(());
        }
        let problem = &mut self.problem;
        problem.gaps(&self.carriers, self.placement, map, lanes, st);
        let solved = match &mut self.law {
            RunLaw::Velocity(law) => {
                debug_assert_eq!(lanes, Lanes::ONE, "the velocity level steps alone");
                if self.increment_rates {
                    problem.position(&self.carriers, self.placement, map, lanes);
                    problem.increment(&self.carriers, st, self.dt);
                } else {
                    problem.velocity(&self.carriers, map, st);
                }
                let (g, rate, w_v) = (&problem.g_free, &problem.rate_free, &problem.w_v);
                let solved = law.solve(g, rate, w_v, &mut self.lambda, &mut self.active);
                if self.increment_rates {
                    // ġ_{n+1/2} = ġ_free + W_v λ, the next step's restitution memory
                    problem.rates_after(&self.lambda, law.gap_rates_mut());
                }
                solved
            }
            RunLaw::Force(law) => {
                problem.position(&self.carriers, self.placement, map, lanes);
                if nd == 0 {
                    law.solve(
                        &problem.g_free,
                        &problem.w,
                        &mut self.lambda,
                        &mut self.active,
                    )
                } else {
                    // the contacts and the slack droppers' rows (`dropper.rs`,
                    // D9–D10; a run with droppers steps alone)
                    debug_assert_eq!(lanes, Lanes::ONE, "droppers step alone");
                    let k = rhs_columns(nc);
                    let rows = self.carriers.iter().filter_map(|c| {
                        let pv = match self.placement {
                            Placement::End => &c.pv_g,
                            Placement::Alpha => &c.pv_f,
                        };
                        c.contact.map(|i| (i, c.s, pv))
                    });
                    let coef_c = contact_coef(self.placement, map);
                    let pair = (&problem.g_free[..], &problem.w[..], nc + nd);
                    let d = &mut self.droppers;
                    d.begin(
                        (map.solved, k),
                        map.c_d,
                        map.d_pred,
                        &st.d,
                        (map.v_pred, &st.v, map.c_v),
                        rows,
                        coef_c,
                        pair,
                    );
                    solve_with_droppers(
                        law.as_mut(),
                        d,
                        problem,
                        &mut self.lambda,
                        &mut self.active,
                    )
                }
            }
        };
        solved.map_err(|failure| {
            let step = st.step + 1;
            self.failure(step, st.next_time(self.dt), self.law.level(), failure)
        })
    }

    /// The contact problem of a method that forms the pair itself
    /// (`modal_exact`, MODEL §9.3: sums over modes): `g_free` (one per
    /// contact, m) and `w` (row-major nc × nc, m/N), at force level. The
    /// law's multipliers go into [`System::multipliers`]; a failure names
    /// step n + 1 and saves the problem, as [`System::solve_contact`].
    pub fn solve_formed(&mut self, g_free: &[f64], w: &[f64], st: &State) -> Result<()> {
        let nc = self.masses.len();
        if nc == 0 {
            return Ok(());
        }
        let RunLaw::Force(law) = &mut self.law else {
            unreachable!("modal_exact works at force level")
        };
        let problem = &mut self.problem;
        problem.set(g_free, w);
        law.solve(
            &problem.g_free,
            &problem.w,
            &mut self.lambda,
            &mut self.active,
        )
        .map_err(|failure| {
            let step = st.step + 1;
            self.failure(step, st.next_time(self.dt), Level::Position, failure)
        })
    }

    /// The error for a failed law, with the problem it was given: the
    /// builder's pair, or the impact law's problem on its index set. A
    /// velocity-level Delassus failure gets its kinematics here (V·Δt of
    /// the contact's carrier and the element length h).
    fn failure(&self, step: usize, time: f64, level: Level, mut failure: ContactFailure) -> Error {
        let (g_free, w) = match (&self.law, level) {
            (RunLaw::Velocity(law), Level::Velocity) => law.problem(),
            (_, Level::Acceleration) => {
                // the contacts' block alone (the droppers' forces are loads at t = 0)
                let nc = self.masses.len();
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
                .carriers
                .iter()
                .find(|c| c.contact == Some(*contact))
                .map_or(0.0, |c| c.speed);
            *travel = speed * self.dt;
            *h = self.beam.h;
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
                    contact: self.contact.clone(),
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
        let RunLaw::Velocity(law) = &mut self.law else {
            return;
        };
        if self.increment_rates {
            // the solve kept the increments' rates
            return;
        }
        let rates = law.gap_rates_mut();
        for c in &self.carriers {
            let Some(j) = c.contact else { continue };
            rates[j] = c.gap_rate(d, v, q_dot[j]);
        }
    }
}

/// The external forces of a run whose scene gives at least one series:
/// each mass dof's base force (its `f0` before), side sign and series.
fn external_forces(sc: &Resolved, carriers: &[Carrier], masses: &[MassDof]) -> ExternalForces {
    let mut series = vec![None; masses.len()];
    let mut side = vec![1.0; masses.len()];
    for (c, s) in carriers.iter().zip(&sc.external_forces) {
        if let Some(j) = c.contact {
            series[j] = s.clone();
            side[j] = c.s;
        }
    }
    ExternalForces {
        base: masses.iter().map(|m| m.f0).collect(),
        side,
        series,
        held: vec![0.0; masses.len()],
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
