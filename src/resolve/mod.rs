//! The resolve layer: a parsed [`Scene`] (plain data, its own range checks
//! in `crate::scene`) turned into what a run needs, a [`Resolved`] set of
//! physical parameters, with the checks of combinations that need more than
//! the scene: the mesh against the model's bounds (`mesh`), the point
//! attachments against the basis and references (`attachment`), the
//! manufactured solution's and the declared reference's assumptions
//! (`reference`, `crate::manufactured`), the method's own check of the
//! contact settings and basis (its `MethodInfo`), and the memory plan
//! ([`memory`]).
//!
//! It stands above the model, the references and the contact laws, and
//! below the integrators, which run a `Resolved`. [`Scene::validate`] is
//! defined here, so that the scene's own module imports nothing above it.

pub mod analysis;
pub(crate) mod attachment;
pub(crate) mod budget_check;
mod builder;
pub(crate) mod damping;
pub(crate) mod dropper;
pub mod memory;
pub(crate) mod mesh;
pub mod messenger;
pub mod plausible;
pub mod reference;
mod resolved;
pub mod wire;

use std::path::Path;

pub(crate) use attachment::check_attachments;
pub(crate) use budget_check::{DropperSource, check_budget};
pub use builder::SceneBuilder;
pub(crate) use damping::check_damping;
pub(crate) use dropper::check_droppers;
pub(crate) use memory::MAX_STORED_EVENTS;
pub use memory::{
    HISTORY_ROWS_AT_A_TIME, MEMORY_BUDGET_BYTES, MemoryEstimate, RunSizes,
    estimate as estimate_memory,
};
pub(crate) use mesh::resolve_mesh;
pub(crate) use reference::declared_reference;
pub use resolved::Resolved;

use crate::error::Result;
use crate::manufactured::{Manufactured, Setting};
use crate::scene::{
    Scene, in_file, read_scene, resolve_droppers, resolve_rayleigh, scene_with_overrides,
    validate_contact,
};

impl Scene {
    /// Check every value and resolve the physical parameters: the scene's
    /// own checks (`crate::scene`) and the combinations that need the
    /// model, the references or the memory plan, in one fixed order (the
    /// first fault found is the one reported).
    pub fn validate(&self) -> Result<Resolved> {
        // an error names the key a user wrote, not its path in the
        // expanded `[line]` (`scene::Generated`)
        self.validate_expanded()
            .map_err(|e| self.generated.user_error(e))
    }

    /// [`Scene::validate`], its errors naming paths of the expanded scene.
    fn validate_expanded(&self) -> Result<Resolved> {
        let mut beam = self.resolve_beam()?;
        let l = beam.length;
        let elements = self.elements()?;
        let droppers =
            resolve_droppers(&self.droppers, l, beam.messenger.as_ref().map(|m| m.height))?;
        // the scene index of each contact-wire attachment (the others are
        // the messenger's, `wire = "messenger"`)
        let own = crate::scene::contact_indices(&self.attachments);
        let (discretization, grading) = resolve_mesh(&self.mesh, &beam)?;
        check_droppers(self, &droppers, discretization)?;
        dropper::check_design_heights(&droppers, l)?;
        check_attachments(self, &beam, discretization)?;
        // a linear dropper's spring is an attachment (`dropper` module docs),
        // a linear messenger dropper's a tie between the lines
        beam.attachments
            .extend(dropper::linear_attachments(&droppers));
        if let Some(m) = &mut beam.messenger {
            m.ties = messenger::ties(&droppers);
            m.tie_dashpots = messenger::tie_dashpots(&droppers);
        }
        let carriers = self.resolve_carriers(l)?;
        crate::scene::check_chain_scene(self, &carriers)?;

        // the method, found by name and its parameters typed: once
        let method = self.integrator.resolve()?;
        let damping = resolve_rayleigh(self.beam.damping.as_ref())?;
        check_damping(
            self,
            &own,
            &beam,
            &droppers,
            damping,
            discretization,
            &method,
        )?;
        messenger::check_messenger(self, &beam, elements, grading, discretization, &method)?;
        let g = self.gravity_g()?;
        validate_contact(&self.contact)?;
        // the method's own check of the contact settings and basis
        method.accepts(&self.contact, discretization)?;
        if method.built_in_method() == Some(crate::scene::Method::ModalExact)
            && self.contact.formulation == crate::scene::Formulation::Impact
        {
            let contacts = carriers
                .iter()
                .filter(|c| !matches!(c.kind, crate::scene::CarrierKind::Force { .. }))
                .count();
            let source = self.manufactured.is_some()
                && self.contact.kind == crate::scene::ContactKind::Unilateral;
            if let Some(why) =
                crate::scene::impact_refusal(carriers.len(), contacts, source, !damping.is_zero())
            {
                return Err(crate::error::Error::invalid(
                    "contact.formulation",
                    "\"impact\"",
                    why,
                ));
            }
        }

        let time = self.resolve_time(&carriers, l)?;
        let (dt, t_end, steps) = (time.dt, time.t_end, time.steps);
        // each lumped element within what a model on this wire and step
        // can compute (the scene's own attachments: the linear droppers'
        // springs after them are the droppers')
        plausible::check_plausible(
            &plausible::Scales::of(&beam, elements, dt),
            &carriers,
            &own,
            &beam.attachments[..own.len()],
            &droppers,
            self.contact.penalty.stiffness,
            damping,
        )?;
        if let Some(m) = &beam.messenger {
            let one_table = self
                .messenger
                .as_ref()
                .and_then(|s| s.support.as_ref())
                .is_some_and(toml::Value::is_table);
            let on_messenger: Vec<usize> = (0..self.attachments.len())
                .filter(|i| !own.contains(i))
                .collect();
            plausible::check_messenger(m, one_table, &on_messenger, l, elements, dt)?;
        }
        plausible::check_uplift(
            &plausible::Scales::of(&beam, elements, dt),
            &carriers,
            t_end,
        )?;
        crate::scene::check_speed_tables_cover(&carriers, t_end)?;
        let probes = self.resolve_probes(l)?;
        if let Some(i) = self
            .probes
            .iter()
            .position(|p| p.wire == Some(crate::scene::Wire::Messenger))
            && beam.messenger.is_none()
        {
            return Err(crate::error::Error::invalid(
                format!("probe.{i}.wire"),
                "\"messenger\"",
                "needs a [messenger] section: use wire = \"contact\" (the default)",
            ));
        }
        let record_every = self.record_every()?;
        let mut wire = wire::resolve_wire(
            &self.output,
            &wire::Grid {
                length: l,
                elements,
                grading,
                discretization,
                dt,
                steps,
                t_end,
            },
        )?;
        // a line's supports are its messenger's when `[output] supports`
        // does not name them (docs/lines.md#outputs)
        if wire.supports.is_empty()
            && let Some(m) = &beam.messenger
        {
            wire.supports = m.supports.clone();
        }
        if self.manufactured.is_some() && !self.time.initial.is_rest() {
            // the carriers' and droppers' preloads and the self-weight would
            // sag the static start, while the manufactured lines start
            // straight (crate::manufactured; the static start leaves the
            // source out of d₀)
            return Err(crate::error::Error::invalid(
                "time.initial",
                "\"static\"",
                "a manufactured solution starts straight and at rest (v* = 0 at t = 0; its source cancels the preloads and the self-weight): use \"rest\"",
            ));
        }
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
                    droppers: &droppers,
                    // the scene's own, first; the linear droppers' springs
                    // after them are in `droppers`
                    attachments: &beam.attachments[..own.len()],
                },
            )?),
        };
        let analysis = analysis::resolve_analysis(&self.analysis, l, dt, &wire.supports)?;
        let reference = declared_reference(self, &beam, &carriers)?;
        let external_forces = self.resolve_external_forces(&carriers, t_end)?;

        let resolved = Resolved {
            external_forces,
            manufactured,
            reference,
            scene: self.clone(),
            beam,
            damping,
            carriers,
            droppers,
            elements,
            discretization,
            grading,
            contact: self.contact.clone(),
            method,
            g,
            dt,
            steps,
            t_end,
            probes,
            record_every,
            wire,
            analysis,
        };
        let sizes = resolved.run_sizes();
        check_budget(
            &memory::estimate(&sizes),
            &sizes,
            if self.generated.droppers > 0 {
                DropperSource::Line
            } else {
                DropperSource::Tables
            },
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
