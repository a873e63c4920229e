//! The system every time integrator shares (MODEL §2, §5, §6, §9.1): the
//! discretized beam, the carriers and their contact kinematics, the mass
//! dofs' parameters, and the contact problem of a step.
//!
//! A method solves its step with the contact multipliers λ as unknowns: its
//! unknown vector `u` (an acceleration, a displacement or a velocity,
//! depending on the method) is `u = u★ + Σ_c λ_c z_c`, with `u★` the free
//! solution and `z_c = A⁻¹ s_c r_f,c` the response to a unit multiplier of
//! contact c, and the step's end state is affine in it:
//! `d_{n+1} = d̃ + c_d u`, `v_{n+1} = ṽ + c_v u` (the same for each mass dof,
//! whose own unknown is `u_q = u★_q − λ/A_q`). The method describes that in a
//! [`StepMap`]; [`System::solve_contact`] forms from it the pair `(g_free, W)`
//! the contact law needs — gaps at force level, gap rates at velocity level
//! (the `impact` law, Moreau–Jean's impulses) — and calls the law. So every
//! contact formulation works with every method through this one seam, and a
//! law never reaches into a method.

use crate::contact::{ContactFailed, ContactFailure, ContactLaw, ContactProblem, Level, law_for};
use crate::error::{Error, Result};
use crate::model::banded::BandedLdlt;
use crate::model::beam::{BeamModel, PointVector};
use crate::model::source::Source;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, CarrierProps, ContactKind, ContactSpec, Placement, Support};

use super::State;
use crate::model::banded::rhs_columns;

/// Contact forces beyond this multiple of the carriers' force scale
/// (k(δ0 + L) + m g + F) are taken as a blow-up: no physical run of this model
/// comes within orders of magnitude of it.
const FORCE_BOUND_FACTOR: f64 = 1e3;

/// A mass–spring carrier's mass dof: `m q̈ + c q̇ + k q = f0 − λ` (MODEL §2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassDof {
    /// Mass m, kg.
    pub m: f64,
    /// Spring stiffness k, N/m.
    pub k: f64,
    /// Dashpot c_s, N·s/m.
    pub c: f64,
    /// Constant force on q: k δ0 − s m g, N (MODEL §2).
    pub f0: f64,
}

/// What a method predicts for one mass dof this step (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassPrediction {
    /// q̃: the part of q_{n+1} independent of the unknown, m.
    pub q: f64,
    /// q̇̃: the part of q̇_{n+1} independent of the unknown, m/s.
    pub q_dot: f64,
    /// u★_q: the free unknown (λ = 0).
    pub u: f64,
    /// A_q: the method's effective scalar, u_q = u★_q − λ/A_q.
    pub a_eff: f64,
}

impl MassPrediction {
    /// The mass dof's unknown once its multiplier λ is known:
    /// u_q = u★_q − λ/A_q (the contact pushes the mass with −λ).
    #[inline]
    pub fn unknown(&self, lambda: f64) -> f64 {
        self.u - lambda / self.a_eff
    }
}

/// The beam unknown of each row once the multipliers are known,
/// u = u★ + Σ_c λ_c z_c, from the solved right-hand sides (`k` columns,
/// row-major: column 0 u★, column 1 + c z_c).
pub fn combine<'a>(
    solved: &'a [f64],
    k: usize,
    lambda: &'a [f64],
) -> impl Iterator<Item = f64> + 'a {
    solved.chunks_exact(k).map(move |row| {
        let mut u = row[0];
        for (l, z) in lambda.iter().zip(&row[1..]) {
            u += l * z;
        }
        u
    })
}

/// ṽ of the beam, as the method keeps it.
#[derive(Debug, Clone, Copy)]
pub enum VelocityPrediction<'a> {
    /// ṽ stored as a vector.
    Vector(&'a [f64]),
    /// ṽ = v_n + coef·shift (generalized-α: v_n + (1 − γ)Δt a_n), so the
    /// method need not form it.
    Shifted {
        /// The vector added to v_n.
        shift: &'a [f64],
        /// Its coefficient.
        coef: f64,
    },
}

/// A method's step as the contact problem sees it (module docs).
#[derive(Debug, Clone, Copy)]
pub struct StepMap<'a> {
    /// The solved right-hand sides, n × k row-major
    /// ([`System::columns`] = k): column 0 is u★, column 1 + c is z_c.
    pub solved: &'a [f64],
    /// c_d in d_{n+1} = d̃ + c_d u.
    pub c_d: f64,
    /// c_v in v_{n+1} = ṽ + c_v u.
    pub c_v: f64,
    /// d̃ of the beam.
    pub d_pred: &'a [f64],
    /// ṽ of the beam.
    pub v_pred: VelocityPrediction<'a>,
    /// For `contact.placement = "alpha"`: the gap is imposed on
    /// (1 − w) y_{n+1} + w y_n with w = α_f, along r_f (MODEL §5); 0 otherwise.
    pub alpha_weight: f64,
    /// One prediction per contact.
    pub masses: &'a [MassPrediction],
}

/// Where one run's columns and vectors sit when several runs step together
/// (batched stepping, `integrate::batch`): `count` runs side by side, this
/// one at `lane`. A right-hand side then has `k·count` columns (column c of
/// this run at `c·count + lane`) and a beam vector holds the runs
/// interleaved (`x[i·count + lane]`). [`Lanes::ONE`] is a run alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Lanes {
    /// Runs side by side.
    pub count: usize,
    /// This run's lane.
    pub lane: usize,
}

impl Lanes {
    /// A run alone.
    pub const ONE: Lanes = Lanes { count: 1, lane: 0 };

    /// The column of this run's column c.
    #[inline]
    pub fn col(&self, c: usize) -> usize {
        c * self.count + self.lane
    }

    /// rᵀx for this run's part of an interleaved vector (the run's own
    /// vector when alone): bit-identical either way.
    #[inline]
    pub fn dot(&self, pv: &PointVector, x: &[f64]) -> f64 {
        if self.count == 1 {
            pv.dot(x)
        } else {
            pv.dot_lane(x, self.count, self.lane)
        }
    }
}

/// How a method's multipliers are to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Multipliers {
    /// Forces, N: the contact law works at its own level.
    Forces,
    /// Impulses over the step, N·s (Moreau–Jean): the law works at
    /// velocity level and the reported force is P/Δt.
    Impulses,
    /// Forces held over each step with the gap imposed at its end
    /// (`modal_exact`, MODEL §9.3). Such a sequence carries a neutral
    /// (−1)ⁿ mode: a held force is the step's mean only up to a zigzag of
    /// amplitude O(Δt) that the start (and every closing of the contact)
    /// excites and nothing damps (for a rigid follower of a path X(t),
    /// `(λ_{n−1/2} + λ_{n+1/2})/2 = m δ²X/Δt²` exactly, while each λ alone
    /// is off by `±m Δt X‴/6`). The reported force at t_n is the mean of
    /// the two held forces on either side, second order, recorded one step
    /// late (lag 1).
    Held,
}

/// One carrier during a run.
#[derive(Debug, Clone)]
pub(crate) struct Carrier {
    pub(crate) props: CarrierProps,
    /// Side sign s.
    pub(crate) s: f64,
    /// Index among the contacts (mass carriers), if any.
    pub(crate) contact: Option<usize>,
    /// r_b where the force acts (x_m at the method's force time), and the
    /// gap row (x_m at t_{n+1}).
    pub(crate) pv_f: PointVector,
    pub(crate) pv_g: PointVector,
    /// r_b' at the gap point, and V there (velocity level only).
    pub(crate) pv_s: PointVector,
    pub(crate) speed: f64,
    /// A manufactured source's point load at this carrier (MODEL §11): its
    /// magnitude at the step's load time, N in +v, and, for a contact, r_b
    /// there (a force's load point is `pv_f`). Unused without a source.
    pub(crate) pv_l: PointVector,
    pub(crate) point: f64,
}

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
    pub(crate) dt: f64,
    pub(crate) placement: Placement,
    pub(crate) bilateral: bool,
    pub(crate) length: f64,
    pub(crate) supports: (Support, Support),
    /// String wave speed c = sqrt(T/ρA), m/s.
    pub(crate) wave_speed: f64,
    pub(crate) force_bound: f64,
    law: Box<dyn ContactLaw>,
    contact: ContactSpec,
    /// The level the law works at during the run.
    level: Level,
    multipliers: Multipliers,
    restitution: f64,
    g_free: Vec<f64>,
    w: Vec<f64>,
    /// 1/A_q of each mass dof (scratch).
    inv_a: Vec<f64>,
    pub(crate) lambda: Vec<f64>,
    /// The previous step's multipliers ([`Multipliers::Held`] only).
    held_prev: Vec<f64>,
    pub(crate) active: Vec<bool>,
    /// Gap rates ġ_n (velocity level).
    gap_rate: Vec<f64>,
    // the velocity-level problem over Moreau's index set
    red_idx: Vec<usize>,
    red_g: Vec<f64>,
    red_w: Vec<f64>,
    red_l: Vec<f64>,
    red_a: Vec<bool>,
    /// A manufactured scene's source; `None` costs a branch per step.
    source: Option<SourceState>,
    /// The time the last [`System::place`] put the contact forces at, s.
    t_force: f64,
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
        let mut nc = 0;
        let mut masses = Vec::new();
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
                    } => {
                        nc += 1;
                        force_scale =
                            force_scale.max(stiffness * (preload + sc.beam.length) + mass * sc.g);
                        masses.push(MassDof {
                            m: mass,
                            k: stiffness,
                            c: damping,
                            f0: stiffness * preload - s * mass * sc.g,
                        });
                        Some(nc - 1)
                    }
                    CarrierKind::Force { force } => {
                        force_scale = force_scale.max(force);
                        None
                    }
                };
                // point vectors sized for the basis now (a modal basis's
                // are dense J-vectors), so that no step allocates
                let x0 = p.motion.position(0.0);
                Carrier {
                    props: *p,
                    s,
                    contact,
                    pv_f: beam.point_vector(x0),
                    pv_g: beam.point_vector(x0),
                    pv_s: beam.slope_vector(x0),
                    speed: 0.0,
                    pv_l: beam.point_vector(x0),
                    point: 0.0,
                }
            })
            .collect();
        let law = law_for(&sc.contact, nc);
        let level = law.level();
        let source = sc.manufactured.as_ref().map(|m| SourceState {
            source: Source::new(&beam, m),
            t_load: 0.0,
            f0: masses.iter().map(|m| m.f0).collect(),
        });
        Ok(System {
            source,
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
            level,
            multipliers: Multipliers::Forces,
            restitution: sc.contact.impact.restitution,
            g_free: vec![0.0; nc],
            w: vec![0.0; nc * nc],
            inv_a: vec![0.0; nc],
            lambda: vec![0.0; nc],
            held_prev: vec![0.0; nc],
            active: vec![false; nc],
            gap_rate: vec![0.0; nc],
            red_idx: Vec::with_capacity(nc),
            red_g: vec![0.0; nc],
            red_w: vec![0.0; nc * nc],
            red_l: vec![0.0; nc],
            red_a: vec![false; nc],
            beam,
            carriers,
            masses,
        })
    }

    /// The discretized beam: M, K, the distributed load, point vectors.
    pub fn beam(&self) -> &BeamModel {
        &self.beam
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
        let Some(src) = &self.source else { return };
        let m = src.source.solution();
        for (i, c) in self.carriers.iter().enumerate() {
            if let Some(j) = c.contact {
                self.masses[j].f0 = src.f0[j] + m.mass_source(i, t);
            }
        }
    }

    /// The mass dofs, one per contact.
    pub fn masses(&self) -> &[MassDof] {
        &self.masses
    }

    /// The multipliers of the last contact solve (N, or N·s for impulses),
    /// one per contact.
    pub fn multipliers(&self) -> &[f64] {
        &self.lambda
    }

    /// The level the contact law works at during the run.
    pub fn level(&self) -> Level {
        self.level
    }

    /// Declare how the method's multipliers are to be read; impulses make
    /// the law work at velocity level (called once, before the run).
    pub fn set_multipliers(&mut self, m: Multipliers) {
        self.multipliers = m;
        if m == Multipliers::Impulses {
            self.level = Level::Velocity;
        }
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
        match self.multipliers {
            Multipliers::Impulses => 0.5,
            Multipliers::Held => 1.0,
            Multipliers::Forces => (t - self.t_force) / self.dt,
        }
    }

    /// Place the carriers for a step: moving forces at x_m(t_load), contact
    /// force directions r_f at x_m(t_force), gap rows r_g at x_m(t_gap).
    pub fn place(&mut self, t_load: f64, t_force: f64, t_gap: f64) {
        let velocity = self.level == Level::Velocity;
        self.t_force = t_force;
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
            let tf = if c.contact.is_some() { t_force } else { t_load };
            self.beam
                .point_vector_into(c.props.motion.position(tf), false, &mut c.pv_f);
            let xg = c.props.motion.position(t_gap);
            self.beam.point_vector_into(xg, false, &mut c.pv_g);
            if velocity {
                self.beam.point_vector_into(xg, true, &mut c.pv_s);
                c.speed = c.props.motion.speed(t_gap);
            }
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
        let n = self.beam.n;
        let nc = self.masses.len();
        let k = rhs_columns(nc);
        let mass_factor = BandedLdlt::factor(&self.beam.mass)?;
        self.place(0.0, 0.0, 0.0);
        let mut rhs = vec![0.0; n * k];
        for i in 0..n {
            rhs[i * k] = self.beam.load[i];
        }
        self.scatter_loads(&mut rhs, k, 1.0);
        mass_factor.solve_many(&mut rhs, k);
        let mut aq_free = vec![0.0; nc];
        for c in &self.carriers {
            let Some(j) = c.contact else { continue };
            let m = self.masses[j];
            aq_free[j] = m.f0 / m.m;
            self.g_free[j] = c.s * c.pv_g.dot_strided(&rhs, k, 0) - aq_free[j];
        }
        for (j, m) in self.masses.iter().enumerate() {
            self.inv_a[j] = 1.0 / m.m;
        }
        fill_delassus(
            &self.carriers,
            self.placement,
            (&rhs, k, Lanes::ONE),
            1.0,
            &self.inv_a,
            &mut self.w,
        );
        if let Err(failure) =
            self.law
                .initial(&self.g_free, &self.w, &mut self.lambda, &mut self.active)
        {
            return Err(self.failure(0, 0.0, Level::Acceleration, failure, None));
        }
        let mut a = vec![0.0; n];
        for i in 0..n {
            let mut acc = rhs[i * k];
            for (j, l) in self.lambda.iter().enumerate() {
                acc += l * rhs[i * k + 1 + j];
            }
            a[i] = acc;
        }
        let aq = (0..nc)
            .map(|j| (self.masses[j].f0 - self.lambda[j]) / self.masses[j].m)
            .collect();
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
        let nc = self.masses.len();
        if nc == 0 {
            return Ok(());
        }
        let k = rhs_columns(nc) * lanes.count;
        let col0 = lanes.col(0);
        let (c_d, w_a) = (map.c_d, map.alpha_weight);
        for c in &self.carriers {
            let Some(j) = c.contact else { continue };
            let m = &map.masses[j];
            self.g_free[j] = match self.placement {
                Placement::End => {
                    c.s * (lanes.dot(&c.pv_g, map.d_pred)
                        + c_d * c.pv_g.dot_strided(map.solved, k, col0))
                        - (m.q + c_d * m.u)
                }
                Placement::Alpha => {
                    let wb = (1.0 - w_a)
                        * (lanes.dot(&c.pv_f, map.d_pred)
                            + c_d * c.pv_f.dot_strided(map.solved, k, col0))
                        + w_a * lanes.dot(&c.pv_f, &st.d);
                    let wq = (1.0 - w_a) * (m.q + c_d * m.u) + w_a * st.q[j];
                    c.s * wb - wq
                }
            };
        }
        let solved = match self.level {
            Level::Velocity => {
                debug_assert_eq!(lanes, Lanes::ONE, "the velocity level steps alone");
                self.solve_velocity_level(map, st)
            }
            _ => {
                let coef = match self.placement {
                    Placement::End => c_d,
                    Placement::Alpha => (1.0 - w_a) * c_d,
                };
                for (j, m) in map.masses.iter().enumerate() {
                    self.inv_a[j] = 1.0 / m.a_eff;
                }
                fill_delassus(
                    &self.carriers,
                    self.placement,
                    (map.solved, k, lanes),
                    coef,
                    &self.inv_a,
                    &mut self.w,
                );
                self.law
                    .solve(&self.g_free, &self.w, &mut self.lambda, &mut self.active)
                    .map_err(|f| (f, None))
            }
        };
        solved.map_err(|(failure, reduced)| {
            let step = st.step + 1;
            let level = self.level;
            self.failure(step, st.next_time(self.dt), level, failure, reduced)
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
        debug_assert_eq!(
            self.level,
            Level::Position,
            "modal_exact works at force level"
        );
        self.g_free.copy_from_slice(&g_free[..nc]);
        self.w.copy_from_slice(&w[..nc * nc]);
        self.law
            .solve(&self.g_free, &self.w, &mut self.lambda, &mut self.active)
            .map_err(|failure| {
                let step = st.step + 1;
                self.failure(step, st.next_time(self.dt), Level::Position, failure, None)
            })
    }

    /// The velocity-level problem (MODEL §6, §9.1).
    ///
    /// Index set: the contacts whose free step would close the gap
    /// (g_free ≤ 0; all of them when bilateral). On it, Signorini at velocity
    /// level with Newton's impact law: ġ_{n+1} + e·ġ_n ≥ 0, λ ≥ 0,
    /// complementary. The gap rate of a moving contact has a convective part,
    /// ġ = s(r_bᵀv + V r_b'ᵀd) − q̇, and with v_{n+1} = ṽ + c_v u,
    /// d_{n+1} = d̃ + c_d u it is linear in λ:
    /// ġ = ġ_free + W_v λ, W_v = c_v r_gᵀz + V c_d r_g'ᵀz (+ c_v/A_q on the mass).
    /// The position gap is not imposed: it drifts by O(Δt²) per step, and
    /// the largest penetration is reported.
    #[allow(clippy::type_complexity)]
    fn solve_velocity_level(
        &mut self,
        map: &StepMap,
        st: &State,
    ) -> std::result::Result<(), (ContactFailure, Option<usize>)> {
        let nc = self.masses.len();
        let k = rhs_columns(nc);
        let (c_d, c_v) = (map.c_d, map.c_v);
        let e = self.restitution;
        self.red_idx.clear();
        for j in 0..nc {
            if self.bilateral || self.g_free[j] <= 0.0 {
                self.red_idx.push(j);
            }
        }
        let na = self.red_idx.len();
        for c in &self.carriers {
            let Some(j) = c.contact else { continue };
            let Some(r) = self.red_idx.iter().position(|&i| i == j) else {
                continue;
            };
            let m = &map.masses[j];
            let u_star = c.pv_g.dot_strided(map.solved, k, 0);
            let s_star = c.pv_s.dot_strided(map.solved, k, 0);
            let v_pred = match map.v_pred {
                VelocityPrediction::Vector(v) => c.pv_g.dot(v),
                VelocityPrediction::Shifted { shift, coef } => {
                    c.pv_g.dot(&st.v) + coef * c.pv_g.dot(shift)
                }
            };
            let rate_free = c.s
                * (v_pred + c_v * u_star + c.speed * (c.pv_s.dot(map.d_pred) + c_d * s_star))
                - (m.q_dot + c_v * m.u);
            self.red_g[r] = rate_free + e * self.gap_rate[j];
            for (rr, &jj) in self.red_idx.iter().enumerate() {
                let mut wv = c.s
                    * (c_v * c.pv_g.dot_strided(map.solved, k, 1 + jj)
                        + c.speed * c_d * c.pv_s.dot_strided(map.solved, k, 1 + jj));
                if jj == j {
                    wv += c_v / m.a_eff;
                }
                self.red_w[r * na + rr] = wv;
            }
        }
        for r in 0..na {
            let wv = self.red_w[r * na + r];
            if wv.is_nan() || wv <= 0.0 {
                let j = self.red_idx[r];
                let speed = self
                    .carriers
                    .iter()
                    .find(|c| c.contact == Some(j))
                    .map_or(0.0, |c| c.speed);
                return Err((
                    ContactFailure::VelocityDelassus {
                        contact: j,
                        w: wv,
                        travel: speed * self.dt,
                        h: self.beam.h,
                    },
                    Some(na),
                ));
            }
        }
        self.law
            .solve(
                &self.red_g[..na],
                &self.red_w[..na * na],
                &mut self.red_l[..na],
                &mut self.red_a[..na],
            )
            .map_err(|f| (f, Some(na)))?;
        self.lambda.fill(0.0);
        self.active.fill(false);
        for (r, &j) in self.red_idx.iter().enumerate() {
            self.lambda[j] = self.red_l[r];
            self.active[j] = self.red_a[r];
        }
        Ok(())
    }

    /// The error for a failed law, with the problem it was given (the
    /// reduced velocity-level one when `reduced` holds its size).
    fn failure(
        &self,
        step: usize,
        time: f64,
        level: Level,
        failure: ContactFailure,
        reduced: Option<usize>,
    ) -> Error {
        let (g_free, w) = match reduced {
            Some(na) => (self.red_g[..na].to_vec(), self.red_w[..na * na].to_vec()),
            None => (self.g_free.clone(), self.w.clone()),
        };
        Error::Contact {
            step,
            time,
            run: String::new(),
            failure: Box::new(ContactFailed {
                failure,
                problem: ContactProblem {
                    level,
                    g_free,
                    w,
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
        if self.level != Level::Velocity {
            return;
        }
        for c in &self.carriers {
            let Some(j) = c.contact else { continue };
            self.gap_rate[j] = c.s * (c.pv_g.dot(v) + c.speed * c.pv_s.dot(d)) - q_dot[j];
        }
    }
}

/// W[i][j] = coef · (s_i r_iᵀ z_j + δ_ij · inv_a[i]), reading the solved
/// directions z_j from column 1 + j of `solved` (k columns) and the gap rows
/// r_i at the placement's point (r_g, or r_f for `alpha`).
fn fill_delassus(
    carriers: &[Carrier],
    placement: Placement,
    (solved, k, lanes): (&[f64], usize, Lanes),
    coef: f64,
    inv_a: &[f64],
    w: &mut [f64],
) {
    let nc = inv_a.len();
    for ci in carriers {
        let Some(i) = ci.contact else { continue };
        let pv = match placement {
            Placement::End => &ci.pv_g,
            Placement::Alpha => &ci.pv_f,
        };
        for j in 0..nc {
            let mut wij = ci.s * pv.dot_strided(solved, k, lanes.col(1 + j));
            if i == j {
                wij += inv_a[i];
            }
            w[i * nc + j] = coef * wij;
        }
    }
}
