//! The resolve layer: a parsed [`Scene`] (plain data, its own range checks
//! in `crate::scene`) turned into what a run needs, a [`Resolved`] set of
//! physical parameters, with the checks of combinations that need more than
//! the scene: the mesh against the model's bounds ([`mesh`]), the
//! manufactured solution's and the declared reference's assumptions
//! ([`reference`], `crate::manufactured`), the method's own check of the
//! contact settings and basis (its `MethodInfo`), and the memory plan
//! ([`memory`]).
//!
//! It stands above the model, the references and the contact laws, and
//! below the integrators, which run a `Resolved`. [`Scene::validate`] is
//! defined here, so that the scene's own module imports nothing above it.

pub mod memory;
pub mod mesh;
pub mod reference;

use std::path::Path;

pub use memory::{
    EVENT_BYTES, HISTORY_ROWS_AT_A_TIME, MAX_STORED_EVENTS, MEMORY_BUDGET_BYTES, MemoryEstimate,
    PLOT_BUCKETS, check_budget, estimate as estimate_memory, event_capacity, history_rows,
};
pub use mesh::{MAX_GALERKIN_MODES, resolve_mesh};
pub use reference::declared_reference;

use crate::error::{Error, Result};
use crate::manufactured::{Manufactured, Setting};
use crate::model::mesh::Mesh;
use crate::scene::{
    BeamProps, CarrierKind, CarrierProps, ContactSpec, Declared, Discretization, Grading,
    IntegratorSpec, MeshPlan, Scene, Scheme, fe_unknowns, in_file, read_scene,
    scene_with_overrides, validate_contact,
};

/// A validated scene: physical parameters ready to build a model from.
#[derive(Debug, Clone)]
pub struct Resolved {
    /// The scene as given (after overrides).
    pub scene: Scene,
    /// Beam properties.
    pub beam: BeamProps,
    /// Carriers, in scene order.
    pub carriers: Vec<CarrierProps>,
    /// Number of elements N (`mesh.elements`).
    pub elements: usize,
    /// The space discretization (`mesh.kind`, MODEL §9.2).
    pub discretization: Discretization,
    /// The mesh grading (`mesh.grading`).
    pub grading: Grading,
    /// Contact settings.
    pub contact: ContactSpec,
    /// `[integrator]` as given.
    pub integrator: IntegratorSpec,
    /// The time integrator with its parameters resolved (MODEL §9.1).
    pub scheme: Scheme,
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
    /// The manufactured solution of a scene with `[manufactured]` (MODEL §11).
    pub manufactured: Option<Manufactured>,
    /// The reference the scene declares (`[reference]`, or the manufactured
    /// solution), its assumptions checked.
    pub reference: Declared,
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
        let mut need = memory::estimate(
            self.steps,
            self.record_every,
            self.elements,
            per_node,
            half_band,
            self.carriers.len(),
            masses,
            self.probes.len(),
        );
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

impl Scene {
    /// Check every value and resolve the physical parameters: the scene's
    /// own checks (`crate::scene`) and the combinations that need the
    /// model, the references or the memory plan, in one fixed order (the
    /// first fault found is the one reported).
    pub fn validate(&self) -> Result<Resolved> {
        let beam = self.resolve_beam()?;
        let l = beam.length;
        let elements = self.elements()?;
        let (discretization, grading) = resolve_mesh(&self.mesh, &beam)?;
        let carriers = self.resolve_carriers(l)?;

        let scheme = self.integrator.scheme()?;
        let g = self.gravity_g()?;
        validate_contact(&self.contact)?;
        // the method's own check of the contact settings and basis
        self.integrator
            .method_info()?
            .accepts(&self.contact, discretization)?;

        let time = self.resolve_time(&carriers, l)?;
        let (dt, t_end, steps) = (time.dt, time.t_end, time.steps);
        let probes = self.resolve_probes(l)?;
        let record_every = self.record_every()?;
        let manufactured = match &self.manufactured {
            None => None,
            Some(spec) => Some(Manufactured::new(
                spec,
                Setting {
                    beam: &beam,
                    carriers: &carriers,
                    contact: self.contact.kind,
                    g,
                    t_end,
                    steps,
                },
            )?),
        };
        let reference = declared_reference(self, &beam, &carriers)?;

        let resolved = Resolved {
            manufactured,
            reference,
            scene: self.clone(),
            beam,
            carriers,
            elements,
            discretization,
            grading,
            contact: self.contact.clone(),
            integrator: self.integrator.clone(),
            scheme,
            g,
            dt,
            steps,
            t_end,
            probes,
            record_every,
        };
        check_budget(
            &resolved.memory_estimate(),
            steps,
            record_every,
            elements,
            resolved.carriers.len(),
            resolved.probes.len(),
        )?;
        Ok(resolved)
    }
}

/// Parse scene text, apply overrides in order, deserialize and validate.
pub fn resolve_scene(text: &str, overrides: &[String]) -> Result<Resolved> {
    scene_with_overrides(text, overrides)?.validate()
}

/// Read a scene file, apply overrides, deserialize and validate.
pub fn load_scene(path: &Path, overrides: &[String]) -> Result<Resolved> {
    let text = read_scene(path)?;
    resolve_scene(&text, overrides).map_err(|e| in_file(e, path))
}
