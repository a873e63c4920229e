//! A sweep point's scene: the scene text parsed once into a TOML tree with
//! the fixed `--set` overrides applied, then each point's axis values set
//! as typed variations on a copy of that tree ([`Variation`]): a scene key
//! takes its value, a dimensionless axis the scene values it fixes, read
//! off the point's beam and carriers (the scene's own resolution of those
//! two tables, not a whole validation); the point's scene is then
//! validated once. No number is written as text and read back.
//!
//! The variations act on the tree, not on a typed `Scene`, because a
//! scene's `[line]` is expanded from the tree when it is read
//! (`scene_from_tree`) and reads keys an axis may set (the tension sets
//! the messenger's sag): set on the tree, every axis reaches the line as a
//! `--set` would.

use toml::{Table, Value};

use super::axis::{AxisTarget, Ratio};
use super::spec::SweepSpec;
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::scene::{
    BeamProps, CarrierKind, CarrierProps, Discretization, SpeedProfile, apply_override,
    check_is_scene, parse_scene, scene_from_tree, set_typed,
};

/// One axis value of a point, as what it sets on the point's scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Variation<'a> {
    /// A scene key (`--vary carrier.speed.cruise=…`) takes the value.
    Path {
        /// The dotted key.
        path: &'a str,
        /// The value.
        value: f64,
    },
    /// A dimensionless axis: the scene values it fixes (MODEL §3; e.g.
    /// `speed_ratio` sets every carrier's speed to ratio × c).
    Ratio {
        /// Which ratio.
        ratio: Ratio,
        /// Its value.
        value: f64,
    },
}
/// Whole numbers below 2^53 are exact as both i64 and f64.
const EXACT_WHOLE: f64 = 9_007_199_254_740_992.0;

/// A grid value as a TOML value: a whole number as an integer (so an
/// integer key such as `mesh.elements` takes it, and a real key reads the
/// same number), anything else as the float itself.
fn grid_value(v: f64) -> Value {
    if v.fract() == 0.0 && v.abs() < EXACT_WHOLE {
        Value::Integer(v as i64)
    } else {
        Value::Float(v)
    }
}

/// A grid value spelled as a `--set` would take it, for an error message
/// only (the spelling earlier binaries used for the value itself).
fn grid_text(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < EXACT_WHOLE {
        format!("{}", v as i64)
    } else {
        format!("{v:e}")
    }
}

/// Set a derived real value (a ratio's scene value, a refined step) at `path`.
fn set_real(tree: &mut Table, path: &str, v: f64) -> Result<()> {
    set_typed(tree, path, Value::Float(v), || format!("{path}={v:e}"))
}

/// Deserialize and validate a point's tree (a copy: the tree goes on).
fn resolve_tree(tree: &Table) -> Result<Resolved> {
    scene_from_tree(tree.clone())?.validate()
}

impl SweepSpec {
    /// The scene text parsed into a tree with the fixed `--set` overrides
    /// applied: the common start of every point. Parse it once and give it
    /// to [`SweepSpec::resolve_on`] for each point.
    pub fn base_tree(&self) -> Result<Table> {
        let mut tree = parse_scene(&self.scene_text)?;
        check_is_scene(&tree)?;
        for spec in &self.set {
            apply_override(&mut tree, spec)?;
        }
        Ok(tree)
    }

    /// The resolved scene of point `index`, refined (`--check-refinement`):
    /// half the time step, and twice the space discretization's level
    /// parameter — the elements N of a Hermite mesh, the modes J of a
    /// `galerkin` basis, both N and J of a `modal` one (J may not exceed the
    /// FE unknowns).
    pub fn resolve_refined(&self, index: usize) -> Result<Resolved> {
        self.resolve_refined_on(&self.base_tree()?, index)
    }

    /// [`SweepSpec::resolve_refined`] from the [`SweepSpec::base_tree`].
    pub fn resolve_refined_on(&self, base: &Table, index: usize) -> Result<Resolved> {
        let (sc, mut tree) = self.point_tree(base, index)?;
        if !matches!(sc.discretization, Discretization::Galerkin { .. }) {
            let n = 2 * sc.elements;
            set_typed(&mut tree, "mesh.elements", Value::Integer(n as i64), || {
                format!("mesh.elements={n}")
            })?;
        }
        if let Some(j) = sc.discretization.modes() {
            set_typed(
                &mut tree,
                "mesh.modes",
                Value::Integer(2 * j as i64),
                || format!("mesh.modes={}", 2 * j),
            )?;
        }
        set_real(&mut tree, "time.step", sc.dt / 2.0)?;
        resolve_tree(&tree).map_err(super::refine::in_refined_run)
    }

    /// The resolved scene of point `index`.
    pub fn resolve(&self, index: usize) -> Result<Resolved> {
        self.resolve_on(&self.base_tree()?, index)
    }

    /// [`SweepSpec::resolve`] from the [`SweepSpec::base_tree`].
    pub fn resolve_on(&self, base: &Table, index: usize) -> Result<Resolved> {
        self.point_tree(base, index).map(|(sc, _)| sc)
    }

    /// The variations of point `index`, in the order they are applied:
    /// the scene keys first, then the ratios, tension first (the others
    /// depend on T).
    pub fn variations(&self, index: usize) -> Vec<Variation<'_>> {
        let values = self.point(index);
        let mut out: Vec<Variation<'_>> = Vec::with_capacity(values.len());
        for (a, &value) in self.axes.iter().zip(&values) {
            if let AxisTarget::Path(path) = a.target() {
                out.push(Variation::Path { path, value });
            }
        }
        let mut ratios: Vec<Variation<'_>> = self
            .axes
            .iter()
            .zip(&values)
            .filter_map(|(a, &value)| match a.target() {
                AxisTarget::Ratio(ratio) => Some(Variation::Ratio { ratio, value }),
                AxisTarget::Path(_) => None,
            })
            .collect();
        ratios.sort_by_key(|v| {
            !matches!(
                v,
                Variation::Ratio {
                    ratio: Ratio::Tension,
                    ..
                }
            )
        });
        out.extend(ratios);
        out
    }

    /// The resolved scene of point `index` and the tree that makes it: the
    /// base with the point's [`Variation`]s applied, validated once.
    fn point_tree(&self, base: &Table, index: usize) -> Result<(Resolved, Table)> {
        let mut tree = base.clone();
        for v in self.variations(index) {
            v.apply(&mut tree)?;
        }
        let sc = resolve_tree(&tree)?;
        Ok((sc, tree))
    }

    /// [`SweepSpec::resolve_on`] when the base tree was made, else
    /// [`SweepSpec::resolve`] (which gives the point the base's error).
    pub(super) fn resolve_with(&self, base: Option<&Table>, index: usize) -> Result<Resolved> {
        match base {
            Some(b) => self.resolve_on(b, index),
            None => self.resolve(index),
        }
    }

    /// [`SweepSpec::resolve_with`], refined.
    pub(super) fn resolve_refined_with(
        &self,
        base: Option<&Table>,
        index: usize,
    ) -> Result<Resolved> {
        match base {
            Some(b) => self.resolve_refined_on(b, index),
            None => self.resolve_refined(index),
        }
    }

    /// The resolved scene at per-axis indices `at`.
    pub(super) fn resolve_at(&self, base: &Table, at: &[usize]) -> Result<Resolved> {
        let index = at
            .iter()
            .zip(&self.axes)
            .fold(0, |acc, (&i, a)| acc * a.count + i);
        self.resolve_on(base, index)
    }
}

impl Variation<'_> {
    /// Set what this variation sets on a point's `tree`.
    pub fn apply(self, tree: &mut Table) -> Result<()> {
        match self {
            Variation::Path { path, value } => set_typed(tree, path, grid_value(value), || {
                format!("{path}={}", grid_text(value))
            }),
            Variation::Ratio { ratio, value } => {
                // the point so far: its beam and carriers as the scene
                // resolves them (what a ratio is relative to)
                let scene = scene_from_tree(tree.clone())?;
                let beam = scene.resolve_beam()?;
                let carriers = scene.resolve_carriers(beam.length)?;
                set_ratio(tree, &beam, &carriers, ratio, value)
            }
        }
    }
}

/// Set the scene values ratio `ratio` = `v` fixes, read off the point's
/// `beam` and `carriers` so far.
fn set_ratio(
    tree: &mut Table,
    beam: &BeamProps,
    carriers: &[CarrierProps],
    ratio: Ratio,
    v: f64,
) -> Result<()> {
    let key = ratio.key();
    match ratio {
        Ratio::Tension => {
            let ea = beam.ea.ok_or_else(|| {
                Error::invalid(
                    "--vary tension_ratio",
                    v,
                    "needs EA: give beam.youngs_modulus and beam.area",
                )
            })?;
            set_real(tree, "beam.tension", v * ea)
        }
        Ratio::Speed => {
            let c = beam.wave_speed();
            if c <= 0.0 {
                return Err(Error::invalid(
                    "--vary speed_ratio",
                    v,
                    "needs a wave speed c = sqrt(T/ρA) > 0, and the scene has T = 0: \
                     vary the carrier's speed itself",
                ));
            }
            for (i, car) in carriers.iter().enumerate() {
                let field = match car.motion.profile {
                    SpeedProfile::Constant { .. } => "value",
                    SpeedProfile::SmoothRamp { .. } => "cruise",
                    SpeedProfile::Table { .. } => {
                        return Err(Error::invalid(
                            "--vary speed_ratio",
                            v,
                            format!(
                                "carrier {i} follows a speed table (speed.profile = \"table\"), which has no one speed to set: give it a constant or smooth_ramp profile, or vary the table's knots with --set"
                            ),
                        ));
                    }
                };
                set_real(tree, &format!("carrier.{i}.speed.{field}"), v * c)?;
            }
            Ok(())
        }
        Ratio::Mass | Ratio::Stiffness => {
            let (scale, field) = if ratio == Ratio::Mass {
                (beam.total_mass(), "mass")
            } else {
                (beam.tension / beam.length, "stiffness")
            };
            if !carriers
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
            for (i, car) in carriers.iter().enumerate() {
                if matches!(car.kind, CarrierKind::MassSpring { .. }) {
                    set_real(tree, &format!("carrier.{i}.{field}"), v * scale)?;
                }
            }
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A typed grid value is the value the `--set` text of earlier
    /// binaries read back to, bit for bit (the same-bytes promise of a
    /// resumed sweep rests on it).
    #[test]
    fn typed_values_equal_the_text_round_trip() {
        let read = |text: String| -> Value {
            format!("v = {text}")
                .parse::<Table>()
                .unwrap()
                .remove("v")
                .unwrap()
        };
        for v in [
            0.0,
            -0.0,
            1.0,
            200.0,
            0.1,
            1.0 / 3.0,
            199.99999999999997,
            -2.5e-300,
            1.7976931348623157e308,
            5e-324,
            9_007_199_254_740_992.0,
        ] {
            let typed = grid_value(v);
            let text = read(grid_text(v));
            match (&typed, &text) {
                (Value::Float(a), Value::Float(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{v}"),
                _ => assert_eq!(typed, text, "{v}"),
            }
            let (Value::Float(b), x) = (read(format!("{v:e}")), v) else {
                panic!("{v}")
            };
            assert_eq!(b.to_bits(), x.to_bits(), "{v}");
        }
    }
}
