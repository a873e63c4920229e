//! A scene built in code: [`Scene::builder`] starts from the reference
//! case ([`Scene::default`]), each setter replaces one table or key, and
//! [`SceneBuilder::build`] checks the result with [`Scene::validate`], the
//! same checks a scene file gets (an error names the key, the value and the
//! allowed range).
//!
//! It lives in the resolve layer because `build` returns a [`Resolved`]
//! scene; the scene module stays plain data.

use super::Resolved;
use crate::error::Result;
use crate::scene::{
    BeamSpec, CarrierSpec, ContactSpec, EndTime, Formulation, GravitySpec, IntegratorSpec,
    MeshSpec, Scene, TimeSpec,
};

/// Builds a [`Scene`] in code: `Scene::builder().elements(100).end(0.02).build()?`.
///
/// Starts from [`Scene::default`] (the source study's reference case);
/// keys no setter names are set on the tables (`beam`, `mesh`, `carrier`,
/// …), whose structs have defaults of their own (`..BeamSpec::default()`).
#[derive(Debug, Clone, Default)]
#[must_use = "a builder does nothing until `build`"]
pub struct SceneBuilder {
    scene: Scene,
}

impl Scene {
    /// A builder starting from the reference case ([`Scene::default`]).
    pub fn builder() -> SceneBuilder {
        SceneBuilder::default()
    }
}

impl From<Scene> for SceneBuilder {
    /// A builder starting from `scene` (a file's, to change a few keys).
    fn from(scene: Scene) -> Self {
        SceneBuilder { scene }
    }
}

impl SceneBuilder {
    /// `[beam]`: the whole table.
    pub fn beam(mut self, beam: BeamSpec) -> Self {
        self.scene.beam = beam;
        self
    }

    /// `[mesh]`: the whole table.
    pub fn mesh(mut self, mesh: MeshSpec) -> Self {
        self.scene.mesh = mesh;
        self
    }

    /// `mesh.elements`: the number of elements N (1 ..= 1 000 000).
    pub fn elements(mut self, elements: usize) -> Self {
        self.scene.mesh.elements = elements;
        self
    }

    /// `[[carrier]]`: this one carrier instead of the scene's carriers.
    pub fn carrier(mut self, carrier: CarrierSpec) -> Self {
        self.scene.carriers = vec![carrier];
        self
    }

    /// `[[carrier]]`: one more carrier after the scene's carriers.
    pub fn add_carrier(mut self, carrier: CarrierSpec) -> Self {
        self.scene.carriers.push(carrier);
        self
    }

    /// `[contact]`: the whole table.
    pub fn contact(mut self, contact: ContactSpec) -> Self {
        self.scene.contact = contact;
        self
    }

    /// `contact.formulation`.
    pub fn formulation(mut self, formulation: Formulation) -> Self {
        self.scene.contact.formulation = formulation;
        self
    }

    /// `[time]`: the whole table.
    pub fn time(mut self, time: TimeSpec) -> Self {
        self.scene.time = time;
        self
    }

    /// `time.step`: Δt, s (> 0).
    pub fn step(mut self, step: f64) -> Self {
        self.scene.time.step = step;
        self
    }

    /// `time.end`: the end time, s (> 0; the default is
    /// `"carrier_leaves"`, [`EndTime::CarrierLeaves`]).
    pub fn end(mut self, seconds: f64) -> Self {
        self.scene.time.end = EndTime::Seconds(seconds);
        self
    }

    /// `[integrator]`: the whole table.
    pub fn integrator(mut self, integrator: IntegratorSpec) -> Self {
        self.scene.integrator = integrator;
        self
    }

    /// `integrator.method`: a built-in method's name or a registered one
    /// (`taut::integrate::register`), found when the scene is built.
    pub fn method(mut self, name: &str) -> Self {
        self.scene.integrator.method = name.to_string();
        self
    }

    /// `[gravity]`: the whole table.
    pub fn gravity(mut self, gravity: GravitySpec) -> Self {
        self.scene.gravity = gravity;
        self
    }

    /// The scene as set so far, unchecked (to write it out or change a
    /// table the builder has no setter for, then `SceneBuilder::from`).
    pub fn scene(self) -> Scene {
        self.scene
    }

    /// The scene checked by [`Scene::validate`]: a [`Resolved`] scene,
    /// ready for `taut::run`, or the first fault found (the key, its value
    /// and the allowed range).
    pub fn build(self) -> Result<Resolved> {
        self.scene.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default scene is the bundled reference case, table for table.
    #[test]
    fn default_is_the_reference_scene() {
        let mut file =
            crate::scene::scene_with_overrides(include_str!("../../scenes/reference.toml"), &[])
                .unwrap();
        // the file spells out ρ∞ = 1, the default the scene leaves unset
        assert_eq!(file.integrator.rho_inf, Some(1.0));
        file.integrator.rho_inf = None;
        assert_eq!(Scene::default(), file);
    }

    /// `build` reports `Scene::validate`'s error, naming the key.
    #[test]
    fn build_reports_the_validation_error() {
        let err = Scene::builder().step(-1.0).build().unwrap_err();
        assert!(err.to_string().contains("time.step"), "{err}");
        let err = Scene::builder().elements(0).build().unwrap_err();
        assert!(err.to_string().contains("mesh.elements"), "{err}");
    }

    /// Each setter reaches its key, and the result validates.
    #[test]
    fn setters_reach_their_keys() {
        let sc = Scene::builder()
            .elements(50)
            .step(2e-4)
            .end(0.01)
            .method("newmark")
            .formulation(Formulation::Penalty)
            .add_carrier(CarrierSpec {
                start: 10.0,
                ..CarrierSpec::default()
            })
            .build()
            .unwrap();
        assert_eq!(sc.scene.mesh.elements, 50);
        assert_eq!(sc.scene.time.end, EndTime::Seconds(0.01));
        assert_eq!(sc.scene.integrator.method, "newmark");
        assert_eq!(sc.scene.carriers.len(), 2);
        assert_eq!(sc.contact.formulation, Formulation::Penalty);
    }
}
