//! The reference a scene declares (`[reference]`, or its manufactured
//! solution), its assumptions checked against the resolved beam and
//! carriers (MODEL §8; `docs/scene.md`, `[reference]`).

use crate::error::{Error, Result};
use crate::scene::{
    BeamProps, CarrierKind, CarrierProps, ContactKind, Declared, ReferenceKind, Scene,
    SpeedProfile, Support,
};

/// The reference the scene declares, its assumptions checked (MODEL §8;
/// `docs/scene.md`, `[reference]`): a declaration that does not fit the
/// scene is refused naming `reference.kind` and the key that breaks it.
pub(crate) fn declared_reference(
    scene: &Scene,
    beam: &BeamProps,
    carriers: &[CarrierProps],
) -> Result<Declared> {
    if scene.manufactured.is_some() {
        if let Some(r) = &scene.reference {
            return Err(Error::invalid(
                "reference.kind",
                format!("\"{}\"", r.kind.name()),
                "must be left out with [manufactured]: the manufactured solution is the scene's reference",
            ));
        }
        return Ok(Declared::Manufactured);
    }
    let Some(spec) = &scene.reference else {
        return Ok(Declared::Richardson);
    };
    let kind = spec.kind;
    let refuse = |key: &str, value: String, why: &str| {
        Err(Error::invalid(
            "reference.kind",
            format!("\"{}\"", kind.name()),
            format!("needs {why}, but {key} = {value}"),
        ))
    };
    if spec.modes.is_some() && kind != ReferenceKind::RidingMassGalerkin {
        return Err(Error::invalid(
            "reference.modes",
            spec.modes.unwrap_or(0),
            "is read only by kind = \"riding_mass_galerkin\": leave it out",
        ));
    }
    let pinned = beam.left == Support::Pinned && beam.right == Support::Pinned;
    let supports = || format!("{:?}–{:?}", beam.left, beam.right).to_lowercase();
    match kind {
        ReferenceKind::Richardson => Ok(Declared::Richardson),
        ReferenceKind::MovingForceSeries | ReferenceKind::RidingMassGalerkin => {
            if carriers.len() != 1 {
                return refuse(
                    "carrier",
                    format!("{} carriers", carriers.len()),
                    "exactly one carrier",
                );
            }
            let c = &carriers[0];
            let SpeedProfile::Constant { value: speed } = c.motion.profile else {
                return refuse(
                    "carrier.speed.profile",
                    "\"smooth_ramp\"".into(),
                    "a constant speed",
                );
            };
            if !pinned {
                return refuse("beam.left/right", supports(), "pinned–pinned supports");
            }
            if beam.distributed_load != 0.0 {
                return refuse(
                    "gravity.beam_self_weight",
                    "true".into(),
                    "no distributed load",
                );
            }
            if kind == ReferenceKind::MovingForceSeries {
                if !matches!(c.kind, CarrierKind::Force { .. }) {
                    return refuse(
                        "carrier.mass",
                        "given".into(),
                        "a moving force (carrier.force)",
                    );
                }
                if speed <= 0.0 {
                    return refuse("carrier.speed.value", speed.to_string(), "a speed > 0");
                }
                if c.motion.start != 0.0 {
                    return refuse("carrier.start", c.motion.start.to_string(), "start = 0");
                }
                return Ok(Declared::MovingForceSeries);
            }
            let CarrierKind::MassSpring {
                stiffness, damping, ..
            } = c.kind
            else {
                return refuse("carrier.force", "given".into(), "a mass carrier");
            };
            if stiffness != 0.0 {
                return refuse(
                    "carrier.stiffness",
                    stiffness.to_string(),
                    "a riding mass (stiffness = 0)",
                );
            }
            if damping != 0.0 {
                return refuse("carrier.damping", damping.to_string(), "no dashpot");
            }
            if scene.contact.kind != ContactKind::Bilateral {
                return refuse(
                    "contact.kind",
                    "\"unilateral\"".into(),
                    "a bilateral contact",
                );
            }
            if beam.is_string() {
                return refuse(
                    "beam.bending_stiffness",
                    "0".into(),
                    "EI > 0 (a string's curvature under a mass has no limit)",
                );
            }
            if let Some(j) = spec.modes
                && !(1..=crate::analytic::MAX_MODES * 4).contains(&j)
            {
                return Err(Error::invalid(
                    "reference.modes",
                    j,
                    format!("must be in 1 ..= {}", crate::analytic::MAX_MODES * 4),
                ));
            }
            Ok(Declared::RidingMassGalerkin { modes: spec.modes })
        }
        ReferenceKind::StandingForceModes => {
            for (i, c) in carriers.iter().enumerate() {
                if !matches!(c.kind, CarrierKind::Force { .. }) {
                    return refuse(
                        &format!("carrier.{i}.mass"),
                        "given".into(),
                        "standing forces only (carrier.force)",
                    );
                }
                if !c.motion.is_stationary() {
                    return refuse(
                        &format!("carrier.{i}.speed"),
                        c.motion.profile.cruise_speed().to_string(),
                        "standing forces (speed 0)",
                    );
                }
            }
            Ok(Declared::StandingForceModes)
        }
    }
}
