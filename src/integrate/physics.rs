//! What a run steps (MODEL §1–§3, §10, §11): the discretized beam with its
//! damping matrix, the carriers and their mass dofs, the droppers, a
//! manufactured source, and the run's fixed geometry. The carriers are
//! placed anew each step at the times the method asks for ([`Physics::place`])
//! and scatter their loads and contact directions into a method's
//! right-hand sides. Nothing here knows the contact law (`law_state.rs`).

use crate::model::banded::SymBand;
use crate::model::beam::BeamModel;
use crate::model::source::Source;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, Support};

use super::carrier::{Carrier, PlaceTimes};
use super::dropper::Droppers;
use super::mass_dofs::MassDofs;
use super::step_map::Lanes;

/// A manufactured solution's source during a run (MODEL §11): the smooth
/// part projected on the basis ([`Source`]) and the load time of the
/// current step.
#[derive(Debug, Clone)]
struct SourceState {
    source: Source,
    /// t at which [`Physics::place`] put the loads, s.
    t_load: f64,
}

/// What a run steps (module docs).
pub(crate) struct Physics {
    /// The discretized beam: M, K (with every dropper's spring), the
    /// distributed load (with their preloads), point vectors.
    pub(crate) beam: BeamModel,
    /// The damping matrix C = αM + βK + Σ c_a r_a r_aᵀ (docs/lines.md
    /// §10.4); `None` without damping, and then no method does C's work.
    pub(crate) damping: Option<SymBand>,
    /// The carriers, in scene order, placed for the current step.
    pub(crate) carriers: Vec<Carrier>,
    /// The carriers' mass dofs, one body per contact (`mass_dofs.rs`).
    pub(crate) masses: MassDofs,
    /// The droppers (`dropper.rs`): the slack tension-only ones are rows
    /// of the contact problem after the contacts', every one's force and
    /// state kept there; none costs a branch per step.
    pub(crate) droppers: Droppers,
    /// A manufactured scene's source; `None` costs a branch per step.
    source: Option<SourceState>,
    /// Time step Δt, s.
    pub(crate) dt: f64,
    /// Beam length L, m.
    pub(crate) length: f64,
    /// The supports at x = 0 and x = L.
    pub(crate) supports: (Support, Support),
    /// String wave speed c = sqrt(T/ρA), m/s.
    pub(crate) wave_speed: f64,
    /// The constant load before the droppers' preloads (f₀ of
    /// `form_finding.rs`, eq. F1), kept only when a dropper has a design
    /// height.
    pub(crate) free_load: Option<Vec<f64>>,
    /// The time the last [`Physics::place`] put the contact forces at, s.
    pub(crate) t_force: f64,
}

impl Physics {
    /// The physics of a validated scene on `beam` (`BeamModel::build` of
    /// it, or of a scene with the same beam and discretization): the
    /// carriers numbered, their mass dofs, the droppers' springs, preloads
    /// and dashpots put into K, the load and C.
    pub(crate) fn new(sc: &Resolved, mut beam: BeamModel) -> Self {
        let mut nc = 0;
        let carriers: Vec<Carrier> = sc
            .carriers
            .iter()
            .map(|p| {
                let contact = match p.kind {
                    CarrierKind::MassSpring { .. } => {
                        nc += 1;
                        Some(nc - 1)
                    }
                    CarrierKind::Force { .. } => None,
                };
                Carrier::new(p.clone(), contact, &beam)
            })
            .collect();
        let masses = MassDofs::new(sc, &carriers);
        let droppers = Droppers::new(&sc.droppers, &beam, nc);
        // C = αM + βK + dashpots from K *before* the tension-only droppers'
        // springs join it: a slack dropper carries no force, so its spring
        // must not put a dashpot β k_d r_d r_dᵀ in C (the linear droppers'
        // springs are in K already, and in βK as before)
        let (tie_dashpots, messenger_attachments) =
            sc.beam.messenger.as_ref().map_or((&[][..], &[][..]), |m| {
                (&m.tie_dashpots[..], &m.attachments[..])
            });
        let mut damping = beam.damping_matrix_with_ties(
            sc.damping,
            &sc.beam.attachments,
            tie_dashpots,
            messenger_attachments,
        );
        // the tension-only droppers' dashpots in C (`dropper.rs`, D12), into
        // a zero C of K's band when nothing else damps
        if droppers.has_dashpots() {
            let c = damping.get_or_insert_with(|| beam.stiffness.combine(0.0, &beam.mass, 0.0));
            droppers.add_dashpots(c);
        }
        // every dropper's spring in K and preload in the load (`dropper.rs`, D7)
        droppers.add_springs(&mut beam.stiffness);
        let free_load = sc
            .droppers
            .iter()
            .any(|d| d.design_height.is_some())
            .then(|| beam.load.clone());
        droppers.add_preloads(&mut beam.load);
        let source = sc.manufactured.as_ref().map(|m| SourceState {
            source: Source::new(&beam, m),
            t_load: 0.0,
        });
        Physics {
            damping,
            source,
            t_force: 0.0,
            dt: sc.dt,
            length: sc.beam.length,
            supports: (sc.beam.left, sc.beam.right),
            wave_speed: sc.beam.wave_speed(),
            free_load,
            droppers,
            beam,
            carriers,
            masses,
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

    /// Each mass dof's constant force plus its external force and a
    /// manufactured mass source at `t` (MODEL §11, `mass_dofs.rs`).
    pub(crate) fn set_mass_source(&mut self, t: f64) {
        let source = self.source.as_ref().map(|s| s.source.solution());
        self.masses.set_load_time(t, source);
    }

    /// Place the carriers for a step ([`PlaceTimes`]): moving forces at
    /// x_m(load), contact force directions r_f at x_m(force), gap rows r_g
    /// at x_m(gap), and, for a law at velocity level (`velocity`), the
    /// slope rows and speeds there.
    pub(crate) fn place(&mut self, at: PlaceTimes, velocity: bool) {
        let (t_load, t_force) = (at.load, at.force);
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
        let at = PlaceTimes {
            load: t_load,
            force: t_force,
            gap: at.gap,
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
            c.place(&self.beam, at, velocity);
        }
    }

    /// Add the moving forces scale·s·F·r_f into column 0 of this run's
    /// columns of `rhs` (`k` columns per run, [`Lanes`]) and the contact
    /// directions s_c r_f,c into its columns 1 + c.
    pub(crate) fn scatter_loads_in(&self, rhs: &mut [f64], k: usize, lanes: Lanes, scale: f64) {
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
}
