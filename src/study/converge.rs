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
use crate::integrate::{MethodFactory, scene_method};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::{RunOutput, run, run_with};
use crate::scene::{Declared, Discretization};

pub use super::grid::GCI_SAFETY_FACTOR;
pub use super::reference::AnalyticW;

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
    /// What `error` is against: the scene's declared reference
    /// (`manufactured`, `moving_force_series`, `riding_mass_galerkin`,
    /// `standing_force_modes`), else `richardson`, or `finest` when no
    /// order could be observed for an extrapolation.
    pub reference: String,
    /// Order of `error` between levels ℓ−1 and ℓ, against an exact
    /// reference only (NaN for `richardson` and `finest`, whose error is
    /// built from the same runs).
    pub error_order: f64,
    /// Ratio of successive error ratios (e_{ℓ−2}/e_{ℓ−1})/(e_{ℓ−1}/e_ℓ),
    /// from the errors against an exact reference, else from successive
    /// differences: 1 in the asymptotic range ([`ORDER_DRIFT`]).
    pub ratio_change: f64,
    /// The formal order of the displacement in the refined variable
    /// (Δt: the method's; h: Hermite 4, string elements 2; `both`: the
    /// smaller), NaN when unknown (a modal basis's J, other quantities).
    pub formal_order: f64,
    /// `asymptotic`, `pre-asymptotic`, `limited by …` (the error against
    /// an exact reference does not fall with the refined variable),
    /// `growing: round-off or an instability` (it rises as the refined
    /// variable falls), `not converging` (successive differences do not
    /// fall, or rise), `exact`, or empty before a level can tell
    /// (`docs/convergence.md`).
    pub regime: String,
    /// ω_max·Δt of the level's model (ω_max: the highest natural
    /// frequency, `central_difference_limit`): above 1 its top modes are
    /// not resolved in time, which caps a moving load's Δt order.
    pub omega_max_dt: f64,
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
/// the same levels, each method selected by its [`MethodFactory::integrator`].
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

/// Levels a convergence study takes (`--levels`, Python `levels=`): at
/// least 2 (one difference), 3 for an observed order; at most 12 (a ratio of
/// 2 refines 2¹¹ = 2048 times on the finest level).
pub const LEVELS: std::ops::RangeInclusive<usize> = 2..=12;

/// `levels` if within [`LEVELS`], else the error naming `--levels`. Checked
/// before the study's cost is estimated (which loops over the levels).
pub fn check_levels(levels: usize) -> Result<usize> {
    super::grid::in_range("--levels", levels, &LEVELS)
}

/// `ratio` if finite and > 1, else the error naming `--ratio`.
pub fn check_ratio(ratio: f64) -> Result<f64> {
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
    let finest = &scenes[levels - 1];
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
    let name = method.map_or_else(|| base.integrator.method.clone(), |m| m.name());
    let time_order = match method {
        Some(m) => m.time_order(base),
        None => scene_method(base)?.time_order(base),
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
    let omega_dt = scenes
        .iter()
        .map(|s| {
            crate::integrate::central_difference_limit(s).map_or(f64::NAN, |l| l.omega_max * s.dt)
        })
        .collect();
    let ctx = Context {
        w: reference.as_deref(),
        force: exact.as_ref().and_then(|e| e.force.as_deref()),
        name: finest.reference.name(),
        formal,
        unrefined,
        omega_dt,
    };
    let mut rows = tabulate(&scenes, &runs, &stride, ratio, &ctx);
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

/// What a study knows beyond its runs: the exact histories of its declared
/// reference (if any), the orders the refined variable should show, and
/// what stays fixed.
struct Context<'a> {
    /// w(t) under carrier 0, exact.
    w: Option<&'a (dyn Fn(f64) -> f64 + Sync)>,
    /// λ(t) of carrier 0, exact (compared at t − lag·Δt of each run).
    force: Option<&'a (dyn Fn(f64) -> f64 + Sync)>,
    /// The declared reference's name, for the `reference` column.
    name: &'static str,
    /// The displacement's formal order in the refined variable, if known.
    formal: Option<f64>,
    /// What the ladder does not refine ("the mesh", "Δt", "J", …).
    unrefined: &'static str,
    /// ω_max·Δt of each level.
    omega_dt: Vec<f64>,
}

/// An error falling by less than this factor per level (order < 0.32 at
/// r = 2) is not falling with the refined variable: a ladder limited by
/// what it does not refine. Chosen between a converging ladder's slowest
/// useful rate (first order: ×2 per halving) and the ±10 % a stalled error
/// wanders by.
pub const STALL_RATIO: f64 = 1.25;

/// Successive observed orders differing by more than this are not yet in
/// the asymptotic range: the ratio of successive error ratios is outside
/// r^(±0.3) (0.81 … 1.23 at r = 2), where the leading error term does not
/// yet dominate the next one.
pub const ORDER_DRIFT: f64 = 0.3;

/// An observed order this far from the formal one is pre-asymptotic (or
/// the formal order does not hold for this solution: the regime says which
/// to suspect, the numbers show it). The same ±0.3 the verification
/// harness allows a smooth case.
pub const FORMAL_GAP: f64 = 0.3;

/// The regime of a level from the errors of its ladder (`e`, against an
/// exact reference, or successive differences when `exact` is false) and
/// the orders between levels (module docs, `docs/convergence.md`).
fn regime(e: &[f64], orders: &[f64], l: usize, ctx: &Context, exact: bool) -> String {
    // with differences, level ℓ's difference is index ℓ − 1
    let (prev, cur) = if exact {
        if l == 0 {
            return String::new();
        }
        (e[l - 1], e[l])
    } else {
        if l < 2 {
            return String::new();
        }
        (e[l - 2], e[l - 1])
    };
    if !(prev.is_finite() && cur.is_finite()) || prev == 0.0 {
        return String::new();
    }
    if cur == 0.0 {
        return "exact".into();
    }
    if prev / cur < 1.0 / STALL_RATIO {
        return if exact {
            "growing: round-off or an instability".into()
        } else {
            "not converging".into()
        };
    }
    if prev / cur < STALL_RATIO {
        return if exact {
            format!("limited by {}", ctx.unrefined)
        } else {
            "not converging".into()
        };
    }
    let p = orders[l];
    let drift = l >= 2 && orders[l - 1].is_finite() && (p - orders[l - 1]).abs() > ORDER_DRIFT;
    let off = ctx.formal.is_some_and(|f| (p - f).abs() > FORMAL_GAP);
    if drift || off {
        "pre-asymptotic".into()
    } else if l >= 2 || ctx.formal.is_some() {
        "asymptotic".into()
    } else {
        String::new()
    }
}

/// Ratio of successive error ratios (e_{ℓ−2}/e_{ℓ−1})/(e_{ℓ−1}/e_ℓ): 1 in
/// the asymptotic range ([`ORDER_DRIFT`]).
fn ratio_change(a: f64, b: f64, c: f64) -> f64 {
    if a > 0.0 && b > 0.0 && c > 0.0 {
        (a / b) / (b / c)
    } else {
        f64::NAN
    }
}

/// The rows of one quantity over the levels.
struct Rows {
    value: Vec<f64>,
    error: Vec<f64>,
    error_order: Vec<f64>,
    observed: Vec<f64>,
    gci: Vec<f64>,
    ratio_change: Vec<f64>,
    regime: Vec<String>,
    reference: String,
}

/// Orders between successive entries of `e` (NaN at index 0).
fn orders_of(e: &[f64], r: f64) -> Vec<f64> {
    (0..e.len())
        .map(|l| {
            if l == 0 {
                f64::NAN
            } else {
                observed_order(e[l - 1], e[l], r)
            }
        })
        .collect()
}

/// Errors, orders, GCI and regime of a quantity given per level as
/// `values` (a scalar, or the norm of a history) and the successive
/// differences `d` (`d[ℓ−1]` between levels ℓ−1 and ℓ); `errors` against
/// an exact reference when known, else built from Richardson or the finest.
fn quantity_rows(
    values: Vec<f64>,
    d: Vec<f64>,
    errors: Option<Vec<f64>>,
    richardson: &dyn Fn(f64) -> Vec<f64>,
    r: f64,
    ctx: &Context,
    formal: Option<f64>,
) -> Rows {
    let k = values.len();
    // the successive-difference order of level ℓ (ℓ ≥ 2)
    let observed: Vec<f64> = (0..k)
        .map(|l| {
            if l >= 2 {
                observed_order(d[l - 2], d[l - 1], r)
            } else {
                f64::NAN
            }
        })
        .collect();
    let gci: Vec<f64> = (0..k)
        .map(|l| {
            let p = observed[l];
            if l >= 2 && p.is_finite() && p > 0.0 && values[l] != 0.0 {
                GCI_SAFETY_FACTOR * (d[l - 1] / values[l].abs()) / (r.powf(p) - 1.0)
            } else {
                f64::NAN
            }
        })
        .collect();
    let ctx = Context {
        formal,
        omega_dt: Vec::new(),
        ..*ctx
    };
    match errors {
        Some(e) => {
            let error_order = orders_of(&e, r);
            let regime = (0..k)
                .map(|l| regime(&e, &error_order, l, &ctx, true))
                .collect();
            let ratio_change = (0..k)
                .map(|l| {
                    if l >= 2 {
                        ratio_change(e[l - 2], e[l - 1], e[l])
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            Rows {
                value: values,
                error: e,
                error_order,
                observed,
                gci,
                ratio_change,
                regime,
                reference: ctx.name.to_string(),
            }
        }
        None => {
            let (reference, error) = if k >= 3 {
                let p = observed_order(d[k - 3], d[k - 2], r);
                if p.is_finite() && p > 0.0 {
                    ("richardson", richardson(p))
                } else {
                    ("finest", richardson(f64::NAN))
                }
            } else {
                ("finest", richardson(f64::NAN))
            };
            // orders from successive differences: the regime reads them
            let regime = (0..k)
                .map(|l| regime(&d_padded(&d), &observed, l, &ctx, false))
                .collect();
            let ratio_change = (0..k)
                .map(|l| {
                    if l >= 3 {
                        ratio_change(d[l - 3], d[l - 2], d[l - 1])
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            Rows {
                value: values,
                error,
                error_order: vec![f64::NAN; k],
                observed,
                gci,
                ratio_change,
                regime,
                reference: reference.to_string(),
            }
        }
    }
}

/// The differences as the regime reads them without an exact reference
/// (index ℓ − 1 for level ℓ): as given.
fn d_padded(d: &[f64]) -> Vec<f64> {
    d.to_vec()
}

#[allow(clippy::too_many_arguments)]
fn tabulate(
    scenes: &[Resolved],
    runs: &[RunOutput],
    stride: &[usize],
    r: f64,
    ctx: &Context,
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
    let w_exact: Option<Vec<f64>> = ctx.w.map(|a| t0.iter().map(|&t| a(t)).collect());
    // each level's force against the exact one at the time it acts
    let f_exact: Option<Vec<Vec<f64>>> = ctx.force.map(|a| {
        (0..k)
            .map(|l| {
                let lag = runs[l].force_lag * scenes[l].dt;
                t0.iter()
                    .enumerate()
                    .map(|(i, &t)| if i == 0 { a(0.0) } else { a(t - lag) })
                    .collect()
            })
            .collect()
    });

    let mut all: Vec<(String, Rows)> = Vec::new();
    let hist = |name: &str,
                h: &[Vec<f64>],
                norm: fn(&[f64]) -> f64,
                exact: Option<Vec<Vec<f64>>>,
                formal: Option<f64>|
     -> (String, Rows) {
        let d: Vec<f64> = (1..k).map(|l| norm(&diff(&h[l - 1], &h[l]))).collect();
        let values: Vec<f64> = h.iter().map(|x| norm(x)).collect();
        let errors = exact.map(|e| (0..k).map(|l| norm(&diff(&h[l], &e[l]))).collect());
        let richardson = |p: f64| -> Vec<f64> {
            let refvec: Vec<f64> = if p.is_finite() {
                let fac = 1.0 / (r.powf(p) - 1.0);
                h[k - 1]
                    .iter()
                    .zip(&h[k - 2])
                    .map(|(fine, mid)| fine + (fine - mid) * fac)
                    .collect()
            } else {
                h[k - 1].clone()
            };
            (0..k).map(|l| norm(&diff(&h[l], &refvec))).collect()
        };
        (
            name.to_string(),
            quantity_rows(values, d, errors, &richardson, r, ctx, formal),
        )
    };
    let same = |e: &Vec<f64>| Some(vec![e.clone(); k]);
    all.push(hist(
        "displacement_max",
        &w,
        max_norm,
        w_exact.as_ref().and_then(same),
        ctx.formal,
    ));
    all.push(hist(
        "displacement_l2",
        &w,
        l2_norm,
        w_exact.as_ref().and_then(same),
        ctx.formal,
    ));
    all.push(hist("force_max", &f, max_norm, f_exact.clone(), None));
    all.push(hist("force_l2", &f, l2_norm, f_exact, None));

    // scalars: a value a run does not have (no first loss) is NaN: an
    // empty cell, JSON null
    for q in SCALARS {
        let vals: Vec<f64> = runs
            .iter()
            .map(|o| q.of(o, 0).unwrap_or(f64::NAN))
            .collect();
        let d: Vec<f64> = (1..k).map(|l| (vals[l - 1] - vals[l]).abs()).collect();
        let richardson = |p: f64| -> Vec<f64> {
            let refval = if p.is_finite() {
                vals[k - 1] + (vals[k - 1] - vals[k - 2]) / (r.powf(p) - 1.0)
            } else {
                vals[k - 1]
            };
            vals.iter().map(|v| (v - refval).abs()).collect()
        };
        all.push((
            q.name().to_string(),
            quantity_rows(vals.clone(), d, None, &richardson, r, ctx, None),
        ));
    }

    let mut out: Vec<ConvergeRow> = Vec::with_capacity(all.len() * k);
    for (quantity, rows) in &all {
        for l in 0..k {
            out.push(ConvergeRow {
                method: String::new(),
                discretization: scenes[l].discretization.name().to_string(),
                level: l,
                h: scenes[l].resolution(),
                modes: scenes[l].discretization.modes(),
                dt: scenes[l].dt,
                quantity: quantity.clone(),
                value: rows.value[l],
                error: rows.error[l],
                observed_order: rows.observed[l],
                gci: rows.gci[l],
                reference: rows.reference.clone(),
                error_order: rows.error_order[l],
                ratio_change: rows.ratio_change[l],
                formal_order: if quantity.starts_with("displacement") {
                    ctx.formal.unwrap_or(f64::NAN)
                } else {
                    f64::NAN
                },
                regime: rows.regime[l].clone(),
                omega_max_dt: ctx.omega_dt[l],
            });
        }
    }
    out.sort_by_key(|r| (r.level, QUANTITIES.iter().position(|q| *q == r.quantity)));
    out
}
