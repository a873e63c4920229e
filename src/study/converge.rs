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

use serde::Serialize;

use super::compare::NotRun;
use super::grid::{Reach, nest, observed_order, resample};
use super::scalars::Scalar;
use super::space::SpaceChoice;
use super::variant::{RunVariant, base_scene};
use crate::error::{Error, Result};
use crate::integrate::MethodFactory;
use crate::run::{RunOutput, run, run_with};
use crate::scene::{Resolved, resolve_scene};

/// Roache's safety factor for a three-grid study.
pub const GCI_SAFETY_FACTOR: f64 = 1.25;

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

/// A reference solution for the displacement under the carrier,
/// w(x_m(t), t) as a function of t (m), when the scene has one.
pub type AnalyticW = Box<dyn Fn(f64) -> f64 + Sync>;

/// One row of `converge.csv`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergeRow {
    /// Time integrator.
    pub method: String,
    /// Space discretization (`mesh.kind`).
    pub discretization: String,
    /// Level ℓ (0 = coarsest).
    pub level: usize,
    /// The length the discretization resolves, m: the element length h
    /// (the longest of a graded mesh), L/J for a modal basis
    /// ([`Resolved::resolution`]).
    pub h: f64,
    /// Modes J of a modal basis (the level parameter of `galerkin` and
    /// `modal`); `None` for elements.
    pub modes: Option<usize>,
    /// Time step, s.
    pub dt: f64,
    /// Quantity name.
    pub quantity: String,
    /// Value at this level (scalar, or norm of the history).
    pub value: f64,
    /// Error against the reference (analytic or Richardson); NaN when unknown.
    pub error: f64,
    /// Observed order at this level; NaN when not yet defined.
    pub observed_order: f64,
    /// Grid convergence index (relative); NaN when not defined.
    pub gci: f64,
    /// "analytic" or "richardson" (or "finest" when no order could be observed).
    pub reference: String,
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
    /// All rows, level-major.
    pub rows: Vec<ConvergeRow>,
    /// Wall seconds of each level.
    pub wall_seconds: Vec<f64>,
}

/// Quantities reported, in order.
pub const QUANTITIES: [&str; 8] = [
    "displacement_max",
    "displacement_l2",
    "force_max",
    "force_l2",
    "loss_fraction",
    "loss_fraction_span",
    "loss_fraction_support",
    "first_loss_position",
];

/// The scalar outputs ([`Scalar`]) among [`QUANTITIES`], in that order.
pub const SCALARS: [Scalar; 4] = [
    Scalar::LossFraction,
    Scalar::LossFractionSpan,
    Scalar::LossFractionSupport,
    Scalar::FirstLossPosition,
];

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
/// the same levels, each method selected by its [`MethodFactory::overrides`].
/// A method that cannot run the ladder (a scene error naming both keys, an
/// explicit method above its stability limit at the coarse levels, a run
/// that stops) is listed in the second vector with its reason; it is an
/// error only when no method runs.
#[allow(clippy::too_many_arguments)]
pub fn converge_methods(
    text: &str,
    overrides: &[String],
    methods: &[&dyn MethodFactory],
    refine: Refine,
    levels: usize,
    ratio: f64,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<MethodStudy>, Vec<NotRun>)> {
    converge_variants(
        text,
        overrides,
        methods,
        &[],
        refine,
        levels,
        ratio,
        analytic,
        progress,
    )
}

/// Run the refinement sequence once per method × discretization
/// (`taut converge --methods … --discretizations …`; either list may be
/// empty for the scene's own). A discretization's level parameter is its
/// own: N for `hermite`, J for `galerkin` and `modal` (module docs of
/// [`super::space`]); with `--refine step` only Δt is refined. Skipped
/// variants as in [`converge_methods`].
#[allow(clippy::too_many_arguments)]
pub fn converge_variants(
    text: &str,
    overrides: &[String],
    methods: &[&dyn MethodFactory],
    spaces: &[SpaceChoice],
    refine: Refine,
    levels: usize,
    ratio: f64,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<MethodStudy>, Vec<NotRun>)> {
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
            match converge_with(
                text, overrides, m, s, refine, levels, ratio, analytic, &mut inner,
            ) {
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
                    reason: e.in_run(&label).to_string(),
                }),
            }
            i += 1;
            progress(i * levels, total);
        }
    }
    if done.is_empty() {
        let why: Vec<String> = skipped.iter().map(|n| n.reason.clone()).collect();
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
    converge_with(
        text, overrides, None, None, refine, levels, ratio, analytic, progress,
    )
}

/// [`converge`] with the method `method` builds (`None`: the scene's own).
#[allow(clippy::too_many_arguments)]
fn converge_with(
    text: &str,
    overrides: &[String],
    method: Option<&dyn MethodFactory>,
    space: Option<SpaceChoice>,
    refine: Refine,
    levels: usize,
    ratio: f64,
    analytic: &dyn Fn(&Resolved) -> Option<AnalyticW>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Convergence> {
    if !(2..=12).contains(&levels) {
        return Err(Error::invalid("--levels", levels, "must be in 2 ..= 12"));
    }
    if !(ratio > 1.0 && ratio.is_finite()) {
        return Err(Error::invalid("--ratio", ratio, "must be > 1"));
    }
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
        Some(m) => base_scene(text, overrides, Some((m, &base.integrator)))?.validate()?,
    };
    base.require_every_step("taut converge")?;
    let mut scenes = Vec::with_capacity(levels);
    let modal = space.is_some_and(|s| s.is_modal());
    for l in 0..levels {
        let f = ratio.powi(l as i32);
        let variant = RunVariant {
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
        };
        scenes.push(variant.apply(&base)?);
    }
    let base = &scenes[0];
    // the coarse time grid must be a subset of every level's
    let stride = scenes
        .iter()
        .map(|s| nest((base.steps, base.dt), (s.steps, s.dt), Reach::SameEnd))
        .collect::<Result<Vec<usize>>>()?;
    let mut runs = Vec::with_capacity(levels);
    let mut wall = Vec::with_capacity(levels);
    for (l, s) in scenes.iter().enumerate() {
        let out = match method {
            None => run(s, &mut |_, _| {})?,
            Some(m) => run_with(s, m, &mut |_, _| {})?,
        };
        wall.push(out.wall_seconds);
        runs.push(out);
        progress(l + 1, levels);
    }
    let reference = analytic(&scenes[levels - 1]);
    let name = method.map_or_else(|| base.integrator.method.name().to_string(), |m| m.name());
    let mut rows = tabulate(&scenes, &runs, &stride, ratio, reference.as_deref());
    for r in &mut rows {
        r.method.clone_from(&name);
    }
    Ok(Convergence {
        refine,
        ratio,
        scenes,
        runs,
        rows,
        wall_seconds: wall,
    })
}

fn max_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn l2_norm(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

fn tabulate(
    scenes: &[Resolved],
    runs: &[RunOutput],
    stride: &[usize],
    r: f64,
    analytic: Option<&(dyn Fn(f64) -> f64 + Sync)>,
) -> Vec<ConvergeRow> {
    let k = runs.len();
    let t0: Vec<f64> = runs[0].history.t.clone();
    let coarse = 0..runs[0].history.len();
    let on_coarse = |pick: fn(&crate::record::CarrierTrace) -> &[f64]| -> Vec<Vec<f64>> {
        (0..k)
            .map(|l| {
                resample(
                    pick(&runs[l].history.carriers[0]),
                    stride[l],
                    coarse.clone(),
                )
            })
            .collect()
    };
    let w = on_coarse(|c| &c.w);
    let f = on_coarse(|c| &c.force);
    let w_exact: Option<Vec<f64>> = analytic.map(|a| t0.iter().map(|&t| a(t)).collect());

    let mut rows = Vec::new();
    let mut push_fn =
        |name: &str, hist: &[Vec<f64>], norm: fn(&[f64]) -> f64, exact: Option<&Vec<f64>>| {
            // successive differences ‖u_{ℓ−1} − u_ℓ‖
            let d: Vec<f64> = (1..k)
                .map(|l| norm(&diff(&hist[l - 1], &hist[l])))
                .collect();
            let (reference, refvec): (&str, Option<Vec<f64>>) = match exact {
                Some(e) => ("analytic", Some(e.clone())),
                None if k >= 3 => {
                    let p = observed_order(d[k - 3], d[k - 2], r);
                    if p.is_finite() && p > 0.0 {
                        let fac = 1.0 / (r.powf(p) - 1.0);
                        let ext = hist[k - 1]
                            .iter()
                            .zip(&hist[k - 2])
                            .map(|(fine, mid)| fine + (fine - mid) * fac)
                            .collect();
                        ("richardson", Some(ext))
                    } else {
                        ("finest", Some(hist[k - 1].clone()))
                    }
                }
                None => ("finest", Some(hist[k - 1].clone())),
            };
            let errors: Vec<f64> = (0..k)
                .map(|l| {
                    refvec
                        .as_ref()
                        .map_or(f64::NAN, |rv| norm(&diff(&hist[l], rv)))
                })
                .collect();
            for l in 0..k {
                // from successive differences, which isolate what is refined
                // (against an analytic solution the unrefined error would mask it)
                let observed = if l >= 2 {
                    observed_order(d[l - 2], d[l - 1], r)
                } else {
                    f64::NAN
                };
                let value = norm(&hist[l]);
                let gci = if l >= 2 && observed.is_finite() && observed > 0.0 && value != 0.0 {
                    GCI_SAFETY_FACTOR * (d[l - 1] / value) / (r.powf(observed) - 1.0)
                } else {
                    f64::NAN
                };
                rows.push((
                    l,
                    name.to_string(),
                    value,
                    errors[l],
                    observed,
                    gci,
                    reference.to_string(),
                ));
            }
        };
    push_fn("displacement_max", &w, max_norm, w_exact.as_ref());
    push_fn("displacement_l2", &w, l2_norm, w_exact.as_ref());
    push_fn("force_max", &f, max_norm, None);
    push_fn("force_l2", &f, l2_norm, None);

    // scalars
    let scalar = |name: &str, vals: Vec<f64>| -> Vec<(usize, String, f64, f64, f64, f64, String)> {
        let d: Vec<f64> = (1..k).map(|l| (vals[l - 1] - vals[l]).abs()).collect();
        let (reference, refval) = if k >= 3 {
            let p = observed_order(d[k - 3], d[k - 2], r);
            if p.is_finite() && p > 0.0 {
                (
                    "richardson",
                    vals[k - 1] + (vals[k - 1] - vals[k - 2]) / (r.powf(p) - 1.0),
                )
            } else {
                ("finest", vals[k - 1])
            }
        } else {
            ("finest", vals[k - 1])
        };
        (0..k)
            .map(|l| {
                let observed = if l >= 2 {
                    observed_order(d[l - 2], d[l - 1], r)
                } else {
                    f64::NAN
                };
                let gci = if l >= 2 && observed.is_finite() && observed > 0.0 && vals[l] != 0.0 {
                    GCI_SAFETY_FACTOR * (d[l - 1] / vals[l].abs()) / (r.powf(observed) - 1.0)
                } else {
                    f64::NAN
                };
                (
                    l,
                    name.to_string(),
                    vals[l],
                    (vals[l] - refval).abs(),
                    observed,
                    gci,
                    reference.to_string(),
                )
            })
            .collect()
    };
    // a value a run does not have (no first loss) is NaN: an empty cell, JSON null
    let mut all: Vec<_> = Vec::new();
    for q in SCALARS {
        let vals = runs
            .iter()
            .map(|o| q.of(o, 0).unwrap_or(f64::NAN))
            .collect();
        all.extend(scalar(q.name(), vals));
    }

    let mut out: Vec<ConvergeRow> = rows
        .into_iter()
        .chain(all)
        .map(
            |(l, quantity, value, error, observed_order, gci, reference)| ConvergeRow {
                method: String::new(),
                discretization: scenes[l].discretization.name().to_string(),
                level: l,
                h: scenes[l].resolution(),
                modes: scenes[l].discretization.modes(),
                dt: scenes[l].dt,
                quantity,
                value,
                error,
                observed_order,
                gci,
                reference,
            },
        )
        .collect();
    out.sort_by_key(|r| (r.level, QUANTITIES.iter().position(|q| *q == r.quantity)));
    out
}
