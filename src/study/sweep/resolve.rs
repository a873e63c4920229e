//! A sweep point's scene: the axis values as `--set` overrides of the scene
//! text, the dimensionless axes turned into the scene values they fix, and
//! the refined scene of `--check-refinement`.

use super::spec::SweepSpec;
use crate::error::{Error, Result};
use crate::resolve::{Resolved, resolve_scene};
use crate::scene::{CarrierKind, Discretization};
/// The study's dimensionless axes.
pub const DIMENSIONLESS: [&str; 4] = [
    "speed_ratio",
    "tension_ratio",
    "mass_ratio",
    "stiffness_ratio",
];

/// A grid value as a `--set` value: whole numbers as TOML integers (so an
/// integer key such as `mesh.elements` takes them, and a real key reads the
/// same number), anything else in exponent notation (exact round trip).
fn set_value(v: f64) -> String {
    /// Whole numbers below 2^53 are exact as both i64 and f64.
    const EXACT_WHOLE: f64 = 9_007_199_254_740_992.0;
    if v.fract() == 0.0 && v.abs() < EXACT_WHOLE {
        format!("{}", v as i64)
    } else {
        format!("{v:e}")
    }
}

impl SweepSpec {
    /// The resolved scene of point `index`, refined (`--check-refinement`):
    /// half the time step, and twice the space discretization's level
    /// parameter — the elements N of a Hermite mesh, the modes J of a
    /// `galerkin` basis, both N and J of a `modal` one (J may not exceed the
    /// FE unknowns).
    pub fn resolve_refined(&self, index: usize) -> Result<Resolved> {
        let (sc, mut o) = self.resolve_with_overrides(index)?;
        let modes = sc.discretization.modes();
        if !matches!(sc.discretization, Discretization::Galerkin { .. }) {
            o.push(format!("mesh.elements={}", 2 * sc.elements));
        }
        if let Some(j) = modes {
            o.push(format!("mesh.modes={}", 2 * j));
        }
        o.push(format!("time.step={:e}", sc.dt / 2.0));
        resolve_scene(&self.scene_text, &o)
    }

    /// The resolved scene of point `index`.
    pub fn resolve(&self, index: usize) -> Result<Resolved> {
        self.resolve_with_overrides(index).map(|(sc, _)| sc)
    }

    /// The resolved scene of point `index` and the overrides that make it.
    fn resolve_with_overrides(&self, index: usize) -> Result<(Resolved, Vec<String>)> {
        let values = self.point(index);
        let mut o = self.set.clone();
        let mut ratios: Vec<(&str, f64)> = Vec::new();
        for (a, v) in self.axes.iter().zip(&values) {
            if DIMENSIONLESS.contains(&a.key.as_str()) {
                ratios.push((a.key.as_str(), *v));
            } else {
                o.push(format!("{}={}", a.key, set_value(*v)));
            }
        }
        // tension first: the others depend on T
        ratios.sort_by_key(|(k, _)| *k != "tension_ratio");
        for (key, v) in ratios {
            let sc = resolve_scene(&self.scene_text, &o)?;
            match key {
                "tension_ratio" => {
                    let ea = sc.beam.ea.ok_or_else(|| {
                        Error::invalid(
                            "--vary tension_ratio",
                            v,
                            "needs EA: give beam.youngs_modulus and beam.area",
                        )
                    })?;
                    o.push(format!("beam.tension={:e}", v * ea));
                }
                "speed_ratio" => {
                    let c = sc.beam.wave_speed();
                    if c <= 0.0 {
                        return Err(Error::invalid(
                            "--vary speed_ratio",
                            v,
                            "needs a wave speed c = sqrt(T/ρA) > 0, and the scene has T = 0: \
                             vary the carrier's speed itself",
                        ));
                    }
                    for (i, car) in sc.carriers.iter().enumerate() {
                        let path = match car.motion.profile {
                            crate::scene::SpeedProfile::Constant { .. } => "value",
                            crate::scene::SpeedProfile::SmoothRamp { .. } => "cruise",
                        };
                        o.push(format!("carrier.{i}.speed.{path}={:e}", v * c));
                    }
                }
                "mass_ratio" | "stiffness_ratio" => {
                    let scale = if key == "mass_ratio" {
                        sc.beam.total_mass()
                    } else {
                        sc.beam.tension / sc.beam.length
                    };
                    let field = if key == "mass_ratio" {
                        "mass"
                    } else {
                        "stiffness"
                    };
                    if !sc
                        .carriers
                        .iter()
                        .any(|c| matches!(c.kind, CarrierKind::MassSpring { .. }))
                    {
                        return Err(Error::invalid(
                            format!("--vary {key}"),
                            v,
                            format!(
                                "sets the {field} of every mass–spring carrier, and the scene \
                                 has none (only moving forces): the axis would change nothing"
                            ),
                        ));
                    }
                    if scale <= 0.0 {
                        return Err(Error::invalid(
                            format!("--vary {key}"),
                            v,
                            "is k/(T/L), and the scene has T = 0: the axis would set k = 0 at \
                             every point; vary carrier.stiffness itself",
                        ));
                    }
                    for (i, car) in sc.carriers.iter().enumerate() {
                        if matches!(car.kind, CarrierKind::MassSpring { .. }) {
                            o.push(format!("carrier.{i}.{field}={:e}", v * scale));
                        }
                    }
                }
                _ => unreachable!("DIMENSIONLESS"),
            }
        }
        let sc = resolve_scene(&self.scene_text, &o)?;
        Ok((sc, o))
    }

    /// The resolved scene at per-axis indices `at`.
    pub(super) fn resolve_at(&self, at: &[usize]) -> Result<Resolved> {
        let index = at
            .iter()
            .zip(&self.axes)
            .fold(0, |acc, (&i, a)| acc * a.count + i);
        self.resolve(index)
    }
}
