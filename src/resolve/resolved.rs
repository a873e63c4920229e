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
            || self
                .beam
                .messenger
                .as_ref()
                .is_some_and(|m| !m.tie_dashpots.is_empty())
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

    /// The memory the run is estimated to need (history, model, a modal
    /// basis's eigenproblem) and the size of its `history.csv`: what
    /// validation checks against the budgets and what a run reserves from
    /// the process's budget while it runs ([`crate::budget`]).
    pub fn memory_estimate(&self) -> memory::MemoryEstimate {
        let (per_node, half_band) = if self.beam.is_string() {
            (1, 1)
        } else {
            (2, 3)
        };
        let masses = self
            .carriers
            .iter()
            .filter(|c| matches!(c.kind, CarrierKind::MassSpring { .. }))
            .count();
        let mut need = memory::estimate(&memory::RunSize {
            steps: self.steps,
            every: self.record_every,
            elements: self.elements,
            per_node,
            half_band,
            carriers: self.carriers.len(),
            masses,
            probes: self.probes.len(),
        });
        // snapshots and field: their values and one point vector a point
        // (counted with the output buffers: they are recorded outputs)
        need.outputs = need.outputs.saturating_add(memory::wire_bytes(
            self.wire.values(self.steps),
            self.wire.points(),
            self.discretization.modes().unwrap_or(0) as u64,
        ));
        if let Discretization::Modal { modes } = self.discretization {
            need.model = need.model.saturating_add(memory::modal_bytes(
                fe_unknowns(&self.beam, self.elements),
                modes,
            ));
        }
        need
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
