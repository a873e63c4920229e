//! A study's runs as typed changes to a base scene, not `--set` strings
//! formatted and parsed again for every run.
//!
//! A study parses its scene text and `--set`s once into a [`Scene`]
//! (`base_scene`), then each run is a `RunVariant`: the number of
//! elements, the time step, the contact formulation and the space
//! discretization set on a clone of that scene, which is validated once, so
//! every range check of a scene file applies and a study reports the error
//! a scene would.
//!
//! A time step set here is the very f64 the study computed: the string path
//! it replaces (`time.step={:e}` parsed as TOML) gave the same value, since
//! `{:e}` prints the shortest representation that reads back exactly.
//!
//! A method is a typed value too: a [`MethodFactory`] sets the base
//! scene's `[integrator]` to its own ([`MethodFactory::integrator`]: a
//! built-in method's name with the parameters it reads), or leaves it
//! (a method of one's own, run on the scene as it is by `run_with`).

use super::space::SpaceChoice;
use crate::error::Result;
use crate::integrate::MethodFactory;
use crate::record::zone::support_zone_of;
use crate::resolve::Resolved;
use crate::scene::{Formulation, Scene, scene_with_overrides};

/// One run of a study, as typed changes to a base scene (`None`: the base
/// scene's own).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct RunVariant {
    /// `mesh.elements`.
    pub elements: Option<usize>,
    /// `time.step`, s.
    pub dt: Option<f64>,
    /// `contact.formulation`.
    pub formulation: Option<Formulation>,
    /// A space discretization and the factor on its level parameter
    /// ([`SpaceChoice::set`]), applied after `elements`.
    pub space: Option<(SpaceChoice, f64)>,
    /// `analysis.support_zone`, m.
    pub support_zone: Option<f64>,
}

impl RunVariant {
    /// The base scene with these changes, validated.
    pub fn apply(&self, base: &Resolved) -> Result<Resolved> {
        self.apply_to(&base.scene)
    }

    /// [`RunVariant::apply`] on a scene not yet validated (a method's
    /// [`base_scene`], which may be valid only with this formulation).
    pub fn apply_to(&self, base: &Scene) -> Result<Resolved> {
        let mut scene = base.clone();
        if let Some(n) = self.elements {
            scene.mesh.elements = n;
        }
        if let Some(dt) = self.dt {
            scene.time.step = dt;
        }
        if let Some(f) = self.formulation {
            scene.contact.formulation = f;
        }
        if let Some((choice, factor)) = self.space {
            choice.set(&mut scene, factor)?;
        }
        if let Some(z) = self.support_zone {
            scene.analysis.support_zone = Some(z);
        }
        scene.validate()
    }

    /// These changes with `base`'s own support zone kept
    /// ([`support_zone_of`]): a refinement study's levels then measure P_l
    /// over the same part of the span, where the default zone,
    /// max(4ℓ_b, 4h, 4VΔt), would narrow as h and Δt fall and make each
    /// level's P_l,span a different quantity.
    pub fn keeping_zone_of(mut self, base: &Resolved) -> Self {
        // a scene without a carrier has no zone to keep
        self.support_zone = Some(support_zone_of(base)).filter(|&z| z > 0.0);
        self
    }
}

/// The scene text with its `--set`s and, when given, the method's
/// `[integrator]` ([`MethodFactory::integrator`]) in place of the scene's;
/// not validated (its runs' variants are).
pub(crate) fn base_scene(
    text: &str,
    overrides: &[String],
    method: Option<&dyn MethodFactory>,
) -> Result<Scene> {
    let mut scene = scene_with_overrides(text, overrides)?;
    if let Some(spec) = method.and_then(|m| m.integrator(&scene.integrator)) {
        scene.integrator = spec;
    }
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::resolve::resolve_scene;

    const REFERENCE: &str = include_str!("../../scenes/reference.toml");

    /// The typed changes give the scene the `--set` strings gave.
    #[test]
    fn typed_changes_are_the_override_strings() {
        let base = resolve_scene(REFERENCE, &[]).unwrap();
        for (n, dt) in [(37, 1e-4 / 3.0), (800, 2.5e-5), (50, 0.1 / 7.0)] {
            let v = RunVariant {
                elements: Some(n),
                dt: Some(dt),
                formulation: Some(Formulation::Penalty),
                space: None,
                support_zone: None,
            };
            let typed = v.apply(&base).unwrap();
            let strings = resolve_scene(
                REFERENCE,
                &[
                    format!("mesh.elements={n}"),
                    format!("time.step={dt:e}"),
                    "contact.formulation=penalty".to_string(),
                ],
            )
            .unwrap();
            assert_eq!(typed.scene, strings.scene);
            assert_eq!(typed.dt.to_bits(), strings.dt.to_bits());
            assert_eq!(
                (typed.steps, typed.elements),
                (strings.steps, strings.elements)
            );
        }
    }
}
