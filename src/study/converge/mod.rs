//! `taut converge`: a refinement study in mesh size, time step or both.
//!
//! Level ℓ = 0 … K−1 runs the scene with N_ℓ = N₀·r^ℓ elements (mesh) and/or
//! Δt_ℓ = Δt₀/r^ℓ (step). Every level records at t = nΔt_ℓ; the coarsest
//! level's times are a subset of every finer level's (r is an integer when the
//! step is refined), so histories are compared sample by sample on the
//! coarsest time grid.
//!
//! For each quantity, per level:
//! * `value` — the scalar (P_l, first loss position) or the norm of the
//!   history (displacement under the carrier, contact force);
//! * `error` — against the analytic solution when the scene has one,
//!   otherwise against a Richardson-extrapolated reference built from the
//!   two finest levels with the observed order of the three finest
//!   (u* = u_f + (u_f − u_m)/(r^p − 1), pointwise for histories);
//! * `observed_order` — p = ln(‖u_{ℓ−2} − u_{ℓ−1}‖/‖u_{ℓ−1} − u_ℓ‖)/ln r from
//!   successive differences (levels ℓ ≥ 2). They isolate the refined
//!   parameter: an error against the analytic solution also holds the
//!   unrefined one (the spatial error in a step refinement) and would mask it;
//! * `gci` — Roache's three-grid grid convergence index of level ℓ,
//!   GCI = F_s·|ε|/(r^p − 1), ε = (u_ℓ − u_{ℓ−1})/u_ℓ, F_s = 1.25 (levels ℓ ≥ 2).
//!
//! Norms of histories: max over samples, and L2 as the RMS over samples.
//!
//! Beside this file (the study and its drivers): `rows` (the rows of
//! `converge.csv` and how a study's runs become them) and `regime` (what
//! a level's errors say: asymptotic, stalled, pre-asymptotic, …).

mod regime;
mod rows;

use crate::record::zone::support_zone_of;
use serde::Serialize;

use super::compare::NotRun;
use super::grid::{Reach, nest};
use super::space::SpaceChoice;
use super::variant::{RunVariant, base_scene};
use crate::error::{Error, Result};
use crate::integrate::{MethodFactory, scene_method};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::{RunOutput, run, run_with};
use crate::scene::{Declared, Discretization};

pub(crate) use super::reference::AnalyticW;
use regime::Context;
pub use rows::ConvergeRow;
pub(crate) use rows::quantity_names;
use rows::{diverged_rows, tabulate};

/// What is refined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Refine {
    /// The number of elements.
    Mesh,
    /// The time step.
    Step,
    /// Both together.
    Both,
}

/// A refinement ladder: what is refined, how many levels, by what ratio
/// (`--refine`, `--levels`, `--ratio`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ladder {
    /// What is refined.
    pub refine: Refine,
    /// Levels, in `LEVELS` (3 or more for observed orders).
    pub levels: usize,
    /// The refinement ratio r > 1 (an integer ≥ 2 when the step is refined).
    pub ratio: f64,
}

impl std::str::FromStr for Refine {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "mesh" => Ok(Refine::Mesh),
            "step" => Ok(Refine::Step),
            "both" => Ok(Refine::Both),
            other => Err(Error::invalid(
                "--refine",
                other,
                "must be mesh, step or both",
            )),
        }
    }
}

/// A finished study.
pub struct Convergence {
    /// What was refined.
    pub refine: Refine,
    /// Refinement ratio r.
    pub ratio: f64,
    /// The resolved scene of each level.
    pub scenes: Vec<Resolved>,
    /// The runs, coarsest first.
    pub runs: Vec<RunOutput>,
    /// `--refine both`: level ℓ's mesh at level ℓ − 1's Δt, ℓ = 1 … K − 1
    /// (the split of each change into its mesh and Δt parts).
    pub split: Vec<RunOutput>,
    /// All rows, level-major.
    pub rows: Vec<ConvergeRow>,
    /// Wall seconds of each level.
    pub wall_seconds: Vec<f64>,
    /// The level whose run diverged, when one did (the ladder stops there).
    pub diverged: Option<Diverged>,
}

/// A level of a ladder whose run blew up.
#[derive(Debug, Clone, Serialize)]
pub struct Diverged {
    /// The level.
    pub level: usize,
    /// The run's diagnosis (step, time, quantity, likely cause).
    pub reason: String,
}

/// One method's (or discretization's) refinement study in a `--methods`
/// or `--discretizations` comparison.
pub struct MethodStudy {
    /// The method's name, `discretization` or `method/discretization`
    /// when both vary.
    pub method: String,
    /// Its study.
    pub study: Convergence,
}

/// Run the refinement sequence once per method (`taut converge --methods`):
/// the same levels, each method selected by its [`MethodFactory::integrator`].
/// A method that cannot run the ladder (a scene error naming both keys, an
/// explicit method above its stability limit at the coarse levels, a run
/// that stops) is listed in the second vector with its reason; it is an
/// error only when no method runs.
pub fn converge_methods(
    text: &str,
    overrides: &[String],
    methods: &[&dyn MethodFactory],
    ladder: Ladder,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<MethodStudy>, Vec<NotRun>)> {
    converge_variants(text, overrides, methods, &[], ladder, analytic, progress)
}

/// Run the refinement sequence once per method × discretization
/// (`taut converge --methods … --discretizations …`; either list may be
/// empty for the scene's own). A discretization's level parameter is its
/// own: N for `hermite`, J for `galerkin` and `modal` (module docs of
/// [`super::space`]); with `--refine step` only Δt is refined. Skipped
/// variants as in [`converge_methods`].
pub(crate) fn converge_variants(
    text: &str,
    overrides: &[String],
    methods: &[&dyn MethodFactory],
    spaces: &[SpaceChoice],
    ladder: Ladder,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<MethodStudy>, Vec<NotRun>)> {
    let levels = ladder.levels;
    let ms: Vec<Option<&dyn MethodFactory>> = if methods.is_empty() {
        vec![None]
    } else {
        methods.iter().copied().map(Some).collect()
    };
    let ss: Vec<Option<SpaceChoice>> = if spaces.is_empty() {
        vec![None]
    } else {
        spaces.iter().copied().map(Some).collect()
    };
    let total = levels * ms.len() * ss.len();
    let (mut done, mut skipped) = (Vec::new(), Vec::new());
    let mut i = 0;
    for &m in &ms {
        for &s in &ss {
            let label = match (m, s) {
                (Some(m), Some(s)) if ms.len() > 1 => format!("{}/{}", m.name(), s.name()),
                (_, Some(s)) => s.name().to_string(),
                (Some(m), None) => m.name(),
                (None, None) => String::new(),
            };
            let mut inner = |l: usize, _: usize| progress(i * levels + l, total);
            let variant = Variant {
                method: m,
                space: s,
            };
            match converge_with(text, overrides, variant, ladder, analytic, &mut inner) {
                Ok(study) => done.push(MethodStudy {
                    method: label,
                    study,
                }),
                // stopped on request: not this variant's failure
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(e) => skipped.push(NotRun {
                    method: m.map_or_else(String::new, |m| m.name()),
                    discretization: s.map_or_else(String::new, |s| s.name().to_string()),
                    formulation: String::new(),
                    reason: super::compare::Reason::new(e.in_run(&label)),
                }),
            }
            i += 1;
            progress(i * levels, total);
        }
    }
    if done.is_empty() {
        let why: Vec<String> = skipped.iter().map(|n| n.reason.to_string()).collect();
        let (field, list) = if spaces.is_empty() {
            (
                "--methods",
                methods
                    .iter()
                    .map(|m| m.name())
                    .collect::<Vec<_>>()
                    .join(","),
            )
        } else {
            (
                "--discretizations",
                spaces
                    .iter()
                    .map(|s| s.name())
                    .collect::<Vec<_>>()
                    .join(","),
            )
        };
        return Err(Error::invalid(
            field,
            list,
            format!("no variant ran the ladder: {}", why.join("; ")),
        ));
    }
    Ok((done, skipped))
}

/// Levels a convergence study takes (`--levels`, Python `levels=`): at
/// least 2 (one difference), 3 for an observed order; at most 12 (a ratio of
/// 2 refines 2¹¹ = 2048 times on the finest level).
pub(crate) const LEVELS: std::ops::RangeInclusive<usize> = 2..=12;

/// `levels` if within [`LEVELS`], else the error naming `--levels`. Checked
/// before the study's cost is estimated (which loops over the levels).
pub(crate) fn check_levels(levels: usize) -> Result<usize> {
    super::grid::in_range("--levels", levels, &LEVELS)
}

/// `ratio` if finite and > 1, else the error naming `--ratio`.
pub(crate) fn check_ratio(ratio: f64) -> Result<f64> {
    if ratio > 1.0 && ratio.is_finite() {
        Ok(ratio)
    } else {
        Err(Error::invalid("--ratio", ratio, "must be > 1"))
    }
}

/// Run the refinement sequence.
///
/// * `text`, `overrides`: the scene and its `--set`s (level 0);
/// * `levels` ≥ 2 (3 for observed orders), `ratio` r > 1 (an integer ≥ 2 when
///   the step is refined);
/// * `analytic`: builds a reference w(t) from a level's scene, if it has one;
/// * `progress(done, total)` after each level.
pub fn converge(
    text: &str,
    overrides: &[String],
    refine: Refine,
    levels: usize,
    ratio: f64,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Convergence> {
    let ladder = Ladder {
        refine,
        levels,
        ratio,
    };
    let own = Variant {
        method: None,
        space: None,
    };
    converge_with(text, overrides, own, ladder, analytic, progress)
}

/// One variant of a study: the method it steps and its space
/// discretization (`None`: the scene's own).
#[derive(Clone, Copy)]
struct Variant<'a> {
    method: Option<&'a dyn MethodFactory>,
    space: Option<SpaceChoice>,
}

/// [`converge`] of one variant.
fn converge_with(
    text: &str,
    overrides: &[String],
    variant: Variant,
    ladder: Ladder,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Convergence> {
    let Ladder {
        refine,
        levels,
        ratio,
    } = ladder;
    let Variant { method, space } = variant;
    check_levels(levels)?;
    check_ratio(ratio)?;
    let refines_step = refine != Refine::Mesh;
    if refines_step && (ratio.fract() != 0.0) {
        return Err(Error::invalid(
            "--ratio",
            ratio,
            "must be an integer ≥ 2 when the step is refined (so coarse times are fine times)",
        ));
    }
    let base = resolve_scene(text, overrides)?;
    let base = match method {
        None => base,
        Some(m) => base_scene(text, overrides, Some(m))?.validate()?,
    };
    base.require_every_step("taut converge")?;
    let modal = space.is_some_and(|s| s.is_modal());
    // level ℓ: N₀·r^ℓ elements (or J₀·r^ℓ modes) and/or Δt₀/r^ℓ
    let level_variant = |l: usize, zone: Option<f64>| {
        let f = ratio.powi(l as i32);
        RunVariant {
            elements: (refine != Refine::Step && !modal)
                .then(|| (base.elements as f64 * f).round() as usize),
            dt: refines_step.then(|| base.dt / f),
            formulation: None,
            // a modal basis's level parameter is J (its mesh stays)
            space: space.map(|s| {
                (
                    s,
                    if modal && refine != Refine::Step {
                        f
                    } else {
                        1.0
                    },
                )
            }),
            support_zone: zone,
        }
    };
    // every level measures P_l over level 0's support zone (the default
    // zone narrows with h and Δt: each level would split P_l elsewhere)
    let zone = Some(support_zone_of(&level_variant(0, None).apply(&base)?)).filter(|&z| z > 0.0);
    let level_variant = |l: usize| level_variant(l, zone);
    let mut scenes = (0..levels)
        .map(|l| level_variant(l).apply(&base))
        .collect::<Result<Vec<Resolved>>>()?;
    let base = &scenes[0];
    // the coarse time grid must be a subset of every level's; each level
    // ends at its last whole step before the scene's end, so the levels
    // are compared at the coarse grid's times, which every level reaches
    let stride = scenes
        .iter()
        .map(|s| nest((base.steps, base.dt), (s.steps, s.dt), Reach::AtLeast))
        .collect::<Result<Vec<usize>>>()?;
    let go = |s: &Resolved| match method {
        None => run(s, &mut |_, _| {}),
        Some(m) => run_with(s, m, &mut |_, _| {}),
    };
    let mut runs = Vec::with_capacity(levels);
    let mut wall = Vec::with_capacity(levels);
    let mut diverged = None;
    for (l, s) in scenes.iter().enumerate() {
        match go(s) {
            Ok(out) => {
                wall.push(out.wall_seconds);
                runs.push(out);
            }
            // a level that blows up ends the ladder: the levels before it
            // are kept and the study says where and how it diverged
            Err(e @ Error::Diverged { .. }) if l > 0 => {
                diverged = Some(Diverged {
                    level: l,
                    reason: e.to_string(),
                });
                break;
            }
            Err(e) => return Err(e),
        }
        progress(l + 1, levels);
    }
    let done = runs.len();
    let stride = &stride[..done];
    // --refine both: level ℓ's mesh at level ℓ − 1's Δt splits each
    // change into its mesh part and its Δt part
    let mut split = Vec::new();
    if refine == Refine::Both && diverged.is_none() {
        for l in 1..done {
            let variant = RunVariant {
                dt: Some(scenes[l - 1].dt),
                ..level_variant(l)
            };
            let sc = variant.apply(&scenes[0])?;
            match go(&sc) {
                Ok(out) => split.push(out),
                Err(e @ Error::Diverged { .. }) => {
                    diverged = Some(Diverged {
                        level: l,
                        reason: format!("its mesh-only split run: {e}"),
                    });
                    split.clear();
                    break;
                }
                Err(e) => return Err(e),
            }
        }
    }
    let finest = &scenes[done - 1];
    let reference = analytic(finest);
    // the exact force of a reference that has one (manufactured, a force's)
    let exact = match finest.reference {
        Declared::Manufactured | Declared::MovingForceSeries | Declared::StandingForceModes
            if reference.is_some() =>
        {
            crate::study::reference::exact(finest).ok().flatten()
        }
        _ => None,
    };
    let name = method.map_or_else(|| base.method.name().to_string(), |m| m.name());
    let time_order = match method {
        Some(m) => m.time_order(base),
        None => scene_method(base).time_order(base),
    };
    let space_order = match base.discretization {
        Discretization::Hermite if base.beam.is_string() => Some(2.0),
        Discretization::Hermite => Some(4.0),
        _ => None,
    };
    let (formal, unrefined) = match refine {
        Refine::Step => (
            time_order,
            match base.discretization {
                Discretization::Hermite => "the mesh",
                Discretization::Galerkin { .. } => "J",
                Discretization::Modal { .. } => "J or the modal basis's FE mesh",
            },
        ),
        Refine::Mesh => (space_order, "Δt"),
        Refine::Both => (
            match (time_order, space_order) {
                (Some(a), Some(b)) => Some(a.min(b)),
                _ => None,
            },
            "neither refined variable (a floor: the reference's accuracy or a fixed parameter)",
        ),
    };
    let omega_dt = scenes[..done]
        .iter()
        .map(|s| {
            crate::integrate::central_difference_limit(s).map_or(f64::NAN, |l| l.omega_max * s.dt)
        })
        .collect();
    let ctx = Context {
        w: reference.as_deref(),
        force: exact.as_ref().and_then(|e| e.force.as_deref()),
        name: finest.reference.name(),
        refine,
        refined: match (refine, modal) {
            (Refine::Step, _) => "Δt",
            (Refine::Mesh, false) => "mesh",
            (Refine::Mesh, true) => "J",
            (Refine::Both, false) => "mesh and Δt",
            (Refine::Both, true) => "J and Δt",
        },
        formal,
        unrefined,
        omega_dt,
    };
    let mut rows = tabulate(&scenes[..done], &runs, stride, &split, ratio, &ctx);
    if let Some(d) = &diverged {
        let at = scenes.get(d.level).unwrap_or(&scenes[done - 1]);
        rows.extend(diverged_rows(at, d));
    }
    for r in &mut rows {
        r.method.clone_from(&name);
    }
    scenes.truncate(done);
    Ok(Convergence {
        refine,
        ratio,
        scenes,
        runs,
        split,
        rows,
        wall_seconds: wall,
        diverged,
    })
}
