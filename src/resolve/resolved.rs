//! A resolved scene: the physical parameters and plans a run is built from
//! (what [`Scene::validate`] returns), with the quantities derived from
//! them: the resolved length, the memory estimate, the history's rows.

use super::memory;
use crate::error::{Error, Result};
use crate::manufactured::Manufactured;
use crate::model::mesh::Mesh;
use crate::scene::{
    BeamProps, CarrierKind, CarrierProps, ContactSpec, Declared, Discretization, Dropper,
    ForceSeries, Grading, MeshPlan, Rayleigh, ResolvedMethod, Scene, fe_unknowns,
};

/// A validated scene: physical parameters ready to build a model from.
#[derive(Debug, Clone)]
pub struct Resolved {
    /// The scene as given (after overrides).
    pub scene: Scene,
    /// Beam properties.
    pub beam: BeamProps,
    /// Rayleigh damping of the wire, `C = α M + β K` (`[beam] damping`;
    /// zero: none). The attachments' dashpots are in `beam.attachments`.
    pub damping: Rayleigh,
    /// Carriers, in scene order.
    pub carriers: Vec<CarrierProps>,
    /// Droppers (`[[dropper]]`, MODEL §10), in scene order; the linear
    /// ones' springs are also in `beam.attachments`.
    pub droppers: Vec<Dropper>,
    /// Each carrier's external force series (`external_force`, N in +v;
    /// `None`: none), in scene order.
    pub external_forces: Vec<Option<ForceSeries>>,
    /// Number of elements N (`mesh.elements`).
    pub elements: usize,
    /// The space discretization (`mesh.kind`, MODEL §9.2).
    pub discretization: Discretization,
    /// The mesh grading (`mesh.grading`).
    pub grading: Grading,
    /// Contact settings.
    pub contact: ContactSpec,
    /// The time integrator, found by name once and its parameters typed
    /// (MODEL §9.1; `[integrator]` as given is `scene.integrator`).
    pub method: ResolvedMethod,
    /// Gravity on carrier masses, m/s².
    pub g: f64,
    /// Time step Δt, s.
    pub dt: f64,
    /// Number of steps.
    pub steps: usize,
    /// The run's end time `time.end`, s: as given, or when the first moving
    /// carrier leaves the beam (the run stops at the last whole step before it).
    pub t_end: f64,
    /// Probes: (name, x in m).
    pub probes: Vec<(String, f64)>,
    /// The history records row 0, every `record_every`-th step and the last
    /// step (`output.record_every`, ≥ 1); statistics use every step.
    pub record_every: usize,
    /// The wire's snapshots and space–time field to record
    /// (`[output] snapshots`, `field`; empty: none).
    pub wire: super::wire::WirePlan,
    /// The filtered force's band and the analysis section of the
    /// standards' statistics (`[analysis]`).
    pub analysis: super::analysis::AnalysisPlan,
    /// The manufactured solution of a scene with `[manufactured]` (MODEL §11).
    pub manufactured: Option<Manufactured>,
    /// The reference the scene declares (`[reference]`, or the manufactured
    /// solution), its assumptions checked.
    pub reference: Declared,
}

impl Resolved {
    /// The point vector of probe `i` on `beam`: r_b(x) on the contact wire,
    /// or r_m(x) on the messenger for `wire = "messenger"` (`docs/lines.md`
    /// eq. W1).
    pub fn probe_vector(
        &self,
        beam: &crate::model::beam::BeamModel,
        i: usize,
    ) -> crate::model::beam::PointVector {
        let x = self.probes[i].1;
        match self.scene.probes.get(i).and_then(|p| p.wire) {
            Some(crate::scene::Wire::Messenger) => beam.messenger_point_vector(x),
            _ => beam.point_vector(x),
        }
    }
}

impl Resolved {
    /// The length the space discretization resolves, m: h = L/N on a
    /// uniform mesh, the longest element of a graded one (the coarsest
    /// place), L/J for a `galerkin` basis of J modes (the half-wavelength
    /// of its last mode), and the larger of the mesh's and L/J for `modal`.
    /// Resolution checks and the contact-loss support zone use it.
    pub fn resolution(&self) -> f64 {
        let l = self.beam.length;
        let mesh = || match self.grading {
            Grading::Uniform => l / self.elements as f64,
            g => Mesh::new(l, self.elements, g).map_or(l / self.elements as f64, |m| m.h_max()),
        };
        match self.discretization {
            Discretization::Hermite => mesh(),
            Discretization::Galerkin { modes } => l / modes as f64,
            Discretization::Modal { modes } => mesh().max(l / modes as f64),
        }
    }

    /// True when the run has a damping matrix C: Rayleigh damping of the
    /// wire or a dashpot on an attachment or a linear messenger dropper
    /// (docs/lines.md §10.4, eq. D11).
    pub fn is_damped(&self) -> bool {
        !self.damping.is_zero()
            || self.beam.attachments.iter().any(|a| a.damping != 0.0)
            || self.beam.messenger.as_ref().is_some_and(|m| {
                !m.tie_dashpots.is_empty() || m.attachments.iter().any(|a| a.damping != 0.0)
            })
    }

    /// The mesh plan the model is built from
    /// (`model::beam::BeamModel::build`).
    pub fn mesh_plan(&self) -> MeshPlan {
        MeshPlan {
            elements: self.elements,
            discretization: self.discretization,
            grading: self.grading,
        }
    }

    /// The unknowns of the space discretization's FE mesh (before a modal
    /// truncation): the most modes a `modal` basis can take.
    pub fn beam_unknowns(&self) -> usize {
        fe_unknowns(&self.beam, self.elements)
    }

    /// The sizes the run's memory grows with ([`memory::RunSizes`]): read
    /// off every key that sizes an allocation of the run, its records or
    /// its outputs.
    pub(crate) fn run_sizes(&self) -> memory::RunSizes {
        let messenger = self.beam.messenger.is_some();
        let half_band = match (self.beam.is_string(), messenger) {
            (true, false) => 1,
            (false, false) => 3,
            // both lines' unknowns interleaved node by node
            (true, true) => 3,
            (false, true) => 7,
        };
        let masses = self
            .carriers
            .iter()
            .map(|c| match (&c.chain, &c.kind) {
                (Some(chain), _) => chain.n,
                (None, CarrierKind::MassSpring { .. }) => 1,
                (None, CarrierKind::Force { .. }) => 0,
            })
            .sum();
        let source_vectors = self.scene.manufactured.as_ref().map_or(0, |m| {
            let terms = m.terms.len() + m.messenger.as_ref().map_or(0, |mm| mm.terms.len());
            // two load vectors a term (three with a dashpot), each over
            // both lines' unknowns
            3 * terms
        });
        let table_values = self
            .carriers
            .iter()
            .map(|c| match &c.motion.profile {
                crate::scene::SpeedProfile::Table { time, .. } => 3 * time.len(),
                _ => 0,
            })
            .sum::<usize>()
            + self
                .external_forces
                .iter()
                .flatten()
                .map(|f| 2 * f.len())
                .sum::<usize>();
        let w = &self.wire;
        memory::RunSizes {
            steps: self.steps,
            every: self.record_every,
            elements: self.elements,
            fe_unknowns: fe_unknowns(&self.beam, self.elements),
            half_band,
            masses,
            carriers: self.carriers.len(),
            probes: self.probes.len(),
            droppers: self.droppers.len(),
            tension_droppers: self.droppers.iter().filter(|d| !d.linear).count(),
            attachments: self.beam.attachments.len(),
            clarabel: self.contact.formulation == crate::scene::Formulation::Complementarity
                && self.contact.complementarity.solver
                    == crate::scene::ComplementaritySolver::Clarabel,
            modal_modes: match self.discretization {
                Discretization::Modal { modes } => Some(modes),
                _ => None,
            },
            dense_weights: self.discretization.modes().unwrap_or(0),
            snapshots: w.snapshots.len(),
            snapshot_points: w.snapshot_x.len(),
            field_rows: w.field_rows(self.steps),
            field_points: w.field_x.len(),
            envelope_points: w.envelope_x.len(),
            supports: w.supports.len(),
            source_vectors,
            table_values,
        }
    }

    /// The memory the run is estimated to need and the size of the files
    /// it writes ([`memory::estimate`] of `Resolved::run_sizes`): what
    /// validation checks against the budgets and what a run reserves from
    /// the process's budget while it runs (`crate::budget`).
    pub fn memory_estimate(&self) -> memory::MemoryEstimate {
        memory::estimate(&self.run_sizes())
    }

    /// Rows the run's history will hold.
    pub fn history_rows(&self) -> usize {
        memory::history_rows(self.steps, self.record_every)
    }

    /// Refuse a scene that records only every K-th step (K > 1), for a study
    /// (`what`) that reads the history step by step.
    pub fn require_every_step(&self, what: &str) -> Result<()> {
        if self.record_every == 1 {
            Ok(())
        } else {
            Err(Error::invalid(
                "output.record_every",
                self.record_every,
                format!(
                    "{what} reads the history at every step: must be 1 (leave out [output] record_every)"
                ),
            ))
        }
    }
}
