//! `taut verify`: one harness that runs any method (a built-in one or a
//! [`MethodFactory`] of one's own), discretization, formulation and
//! support pair on the declared verification cases ([`cases`]) and reports
//! each observed order beside the expected one (MODEL §8, §11).
//!
//! A case is a scene that names its reference (`[manufactured]` or
//! `[reference]`), plus ladders that refine one variable — h, Δt or J —
//! with the others held fine, plus the order each combination should show
//! ([`case::Expect`]). For every ladder the harness
//!
//! 1. runs the levels and measures each level's error against the exact
//!    solution on the coarsest level's time grid (t > 0): the displacement
//!    (under the carrier, at the probes and of the mass) and the contact
//!    force at the time the method's multiplier acts ([`crate::RunOutput::force_lag`]);
//! 2. computes the orders between successive levels and the ladder's order
//!    (first to last level) with the one [`observed_order`];
//! 3. **shows that the refined variable dominates**: the finest level is run
//!    again with the fixed variables refined once more (N×2 or J×2 for a Δt
//!    ladder, Δt/2 for an h or J ladder), and `other_share = |e − e'|/e`
//!    is the part of the finest error that the fixed variables make; a row
//!    whose share exceeds [`DOMINANCE_LIMIT`] fails, since its order would
//!    not be the refined variable's;
//! 4. passes when the ladder's order is within the expectation's tolerance.
//!
//! `known` rows (a measured deviation from the formal order, documented
//! with its measurement), `cannot` rows (why the combination shows no
//! order in this variable) and `reported` rows (a method that declares no
//! formal order) do not fail; `fail` rows do, and `taut verify` exits with
//! status 1.

pub mod case;
pub mod cases;

use rayon::prelude::*;
use serde::Serialize;

use case::{Case, Combo, Expect, Ladder, Quantity, Space, Variable};

use super::grid::{Reach, nest, observed_order};
use super::reference::{Exact, exact};
use crate::error::{Error, Result};
use crate::integrate::{MethodFactory, central_difference_limit};
use crate::resolve::Resolved;
use crate::run::{RunOutput, run_with};
use crate::scene::{
    CarrierKind, Formulation, GradingKind, MeshKind, Scene, Scheme, Support, scene_with_overrides,
};

/// Largest share of the finest error the fixed variables may make (step 3
/// of the module docs): at 0.25 the refined variable makes ≥ 75 % of it,
/// and the order it shows is off by at most log2(1/(1 − 0.25)) ≈ 0.4 in
/// the worst case of a share that does not fall with the ladder (at the
/// coarser levels, where errors are larger, its share is smaller still).
pub const DOMINANCE_LIMIT: f64 = 0.25;

/// A combination's row status.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Observed order within tolerance, refined variable dominant.
    Pass,
    /// Outside tolerance, not dominant, or a run failed.
    Fail,
    /// A known deviation, reported (not failed).
    Known,
    /// Cannot show an order in this variable (the note says why).
    Cannot,
    /// No expectation declared: reported.
    Reported,
}

impl Status {
    /// `pass`, `fail`, `known`, `cannot`, `reported`.
    pub fn name(self) -> &'static str {
        match self {
            Status::Pass => "pass",
            Status::Fail => "fail",
            Status::Known => "known",
            Status::Cannot => "cannot",
            Status::Reported => "reported",
        }
    }
}

/// One row of `verify.csv`: a ladder's quantity under one combination.
#[derive(Debug, Clone, Serialize)]
pub struct VerifyRow {
    /// Case name.
    pub case: String,
    /// Method.
    pub method: String,
    /// Discretization (`string` for string elements).
    pub discretization: String,
    /// Contact formulation (`none` for a case without contact).
    pub formulation: String,
    /// Supports, `left-right`.
    pub supports: String,
    /// Refined variable: `h`, `dt`, `J`.
    pub variable: String,
    /// `displacement` or `force`.
    pub quantity: String,
    /// The refined variable's value per level: h (m), Δt (s) or J.
    pub levels: Vec<f64>,
    /// Absolute error per level (m or N).
    pub errors: Vec<f64>,
    /// The finest error relative to the exact solution's largest value.
    pub relative_error: f64,
    /// Orders between successive levels ([`observed_order`]).
    pub orders: Vec<f64>,
    /// The ladder's order, first to last level ([`observed_order`] over
    /// the whole ratio): what the expectation is checked against.
    pub observed: f64,
    /// The expected (formal) order; NaN when none.
    pub expected: f64,
    /// Allowed |observed − expected|; NaN when none.
    pub tolerance: f64,
    /// The range of the refined variable the expectation is declared over
    /// (the ladder's coarsest and finest values).
    pub range: (f64, f64),
    /// Share of the finest error made by the fixed variables (module docs).
    pub other_share: f64,
    /// ω_max·Δt at the finest level.
    pub omega_max_dt: f64,
    /// Status.
    pub status: Status,
    /// Why, for anything but a pass.
    pub note: String,
    /// Runs made for this ladder (levels and the dominance run).
    pub runs: usize,
    /// Their wall time, s.
    pub wall_seconds: f64,
}

/// What to run (`taut verify --methods --discretizations --formulations`).
pub struct Selection<'a> {
    /// Methods (built-in or custom).
    pub methods: Vec<&'a dyn MethodFactory>,
    /// Discretizations (each case runs those it declares).
    pub spaces: Vec<Space>,
    /// Formulations (cases with contact).
    pub formulations: Vec<Formulation>,
    /// Only the cases of the cut-down matrix, with two support pairs.
    pub quick: bool,
}

/// Parse `hermite,graded,galerkin,modal` (`--discretizations`).
pub fn parse_spaces(list: &str) -> Result<Vec<Space>> {
    let mut out = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let s = Space::ALL
            .into_iter()
            .find(|s| s.name() == item)
            .ok_or_else(|| {
                Error::invalid(
                    "--discretizations",
                    item,
                    "each item must be hermite, graded, galerkin or modal (taut verify sets J and N itself)",
                )
            })?;
        if out.contains(&s) {
            return Err(Error::invalid("--discretizations", item, "is listed twice"));
        }
        out.push(s);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            "--discretizations",
            list,
            "name at least one of hermite, graded, galerkin, modal",
        ));
    }
    Ok(out)
}

/// The methods, discretizations and formulations of a `taut verify`
/// request (`None`: every built-in method, every discretization and
/// formulation), and whether to run the cut-down matrix. Listed built-in
/// methods run in their own order, then listed registered ones.
pub fn selection(
    methods: Option<&str>,
    spaces: Option<&str>,
    formulations: Option<&str>,
    quick: bool,
) -> Result<Selection<'static>> {
    static ALL: [crate::scene::Method; crate::scene::Method::ALL.len()] = crate::scene::Method::ALL;
    let methods: Vec<&'static dyn MethodFactory> = match methods {
        None => ALL.iter().map(|m| m as &dyn MethodFactory).collect(),
        Some(list) => {
            let chosen = crate::integrate::parse_methods(list)?;
            let named = |n: &str| chosen.iter().any(|m| m.name() == n);
            let builtin = ALL.iter().filter(|m| named(m.name()));
            let registered = chosen
                .iter()
                .copied()
                .filter(|m| crate::scene::Method::from_name(&m.name()).is_none());
            builtin
                .map(|m| m as &dyn MethodFactory)
                .chain(registered)
                .collect()
        }
    };
    Ok(Selection {
        methods,
        spaces: spaces.map_or(Ok(Space::ALL.to_vec()), parse_spaces)?,
        formulations: formulations.map_or(Ok(Formulation::ALL.to_vec()), |f| {
            super::compare::parse_formulations(f)
        })?,
        quick,
    })
}

/// The support pair's name, `pinned-free`.
fn supports_name((l, r): (Support, Support)) -> String {
    format!("{l:?}-{r:?}").to_lowercase()
}

/// A job: one case under one combination.
struct Job<'a> {
    case: &'a Case,
    factory: &'a dyn MethodFactory,
    space: Space,
    formulation: Option<Formulation>,
    supports: Option<(Support, Support)>,
}

/// Run the matrix of `sel` over `cases` on the current rayon pool;
/// `progress(done, total)` after each combination. Rows in a fixed order
/// (case, supports, discretization, formulation, method, ladder, quantity),
/// whatever the thread count.
pub fn verify(
    cases: &[Case],
    sel: &Selection,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<VerifyRow>> {
    let mut jobs = Vec::new();
    for case in cases.iter().filter(|c| !sel.quick || c.quick) {
        let supports: Vec<Option<(Support, Support)>> = if case.supports.is_empty() {
            vec![None]
        } else if sel.quick {
            case.supports.iter().take(2).copied().map(Some).collect()
        } else {
            case.supports.iter().copied().map(Some).collect()
        };
        for &s in &supports {
            for &space in case.spaces.iter().filter(|s| sel.spaces.contains(s)) {
                let forms: Vec<Option<Formulation>> = if case.contact {
                    sel.formulations.iter().copied().map(Some).collect()
                } else {
                    vec![None]
                };
                for &f in &forms {
                    for &m in sel.methods.iter().filter(|m| case.runs(&m.name())) {
                        jobs.push(Job {
                            case,
                            factory: m,
                            space,
                            formulation: f,
                            supports: s,
                        });
                    }
                }
            }
        }
    }
    let total = jobs.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Result<Vec<VerifyRow>>> = jobs
        .par_iter()
        .map(|j| {
            if crate::interrupt::requested() {
                return Err(Error::Interrupted);
            }
            let r = run_job(j);
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, total);
            r
        })
        .collect();
    let mut out = Vec::new();
    for r in rows {
        out.extend(r?);
    }
    Ok(out)
}

/// The scene of one combination, before its ladder's levels.
fn base_scene(j: &Job) -> Result<Scene> {
    let mut o: Vec<String> = Vec::new();
    if let Some((l, r)) = j.supports {
        o.push(format!("beam.left={}", format!("{l:?}").to_lowercase()));
        o.push(format!("beam.right={}", format!("{r:?}").to_lowercase()));
    }
    if let Some(f) = j.formulation {
        o.push(format!("contact.formulation={}", f.name()));
    }
    let mut scene = scene_with_overrides(j.case.text, &o)?;
    if let Some(spec) = j.factory.integrator(&scene.integrator) {
        scene.integrator = spec;
    }
    Ok(scene)
}

/// `scene` at one level: N, Δt and J set, the discretization's keys.
fn level(scene: &Scene, space: Space, n: usize, dt: f64, j: usize) -> Result<Resolved> {
    let mut s = scene.clone();
    s.mesh.elements = n;
    s.time.step = dt;
    s.mesh.grading = GradingKind::Uniform;
    s.mesh.grading_ratio = None;
    s.mesh.grading_at = None;
    match space {
        Space::Hermite => {
            s.mesh.kind = MeshKind::Hermite;
            s.mesh.modes = None;
        }
        Space::Graded => {
            s.mesh.kind = MeshKind::Hermite;
            s.mesh.modes = None;
            s.mesh.grading = GradingKind::Supports;
        }
        Space::Galerkin => {
            s.mesh.kind = MeshKind::Galerkin;
            s.mesh.modes = Some(j);
        }
        Space::Modal => {
            s.mesh.kind = MeshKind::Modal;
            s.mesh.modes = Some(j);
        }
    }
    s.validate()
}

/// The rows of one job: every ladder × quantity of its case.
fn run_job(j: &Job) -> Result<Vec<VerifyRow>> {
    let scene = base_scene(j);
    let name_of_space = |sc: Option<&Scene>| {
        let string = sc.is_some_and(|s| s.beam.bending_stiffness == Some(0.0));
        if string && j.space == Space::Hermite {
            "string".to_string()
        } else {
            j.space.name().to_string()
        }
    };
    let supports = j.supports.map_or_else(
        || {
            scene.as_ref().map_or_else(
                |_| String::new(),
                |s| supports_name((s.beam.left, s.beam.right)),
            )
        },
        supports_name,
    );
    let formulation = j
        .formulation
        .map_or_else(|| "none".to_string(), |f| f.name().to_string());
    let discretization = name_of_space(scene.as_ref().ok());
    let blank = |variable: Variable, quantity: Quantity, status: Status, note: String| VerifyRow {
        case: j.case.name.to_string(),
        method: j.factory.name(),
        discretization: discretization.clone(),
        formulation: formulation.clone(),
        supports: supports.clone(),
        variable: variable.name().to_string(),
        quantity: quantity.name().to_string(),
        levels: Vec::new(),
        errors: Vec::new(),
        relative_error: f64::NAN,
        orders: Vec::new(),
        observed: f64::NAN,
        expected: f64::NAN,
        tolerance: f64::NAN,
        range: (f64::NAN, f64::NAN),
        other_share: f64::NAN,
        omega_max_dt: f64::NAN,
        status,
        note,
        runs: 0,
        wall_seconds: 0.0,
    };
    // the case's own ladder variables (a combination that cannot be made
    // is a `cannot` in each)
    let placeholder = Combo {
        method: &j.factory.name(),
        time_order: None,
        space: j.space,
        formulation: j.formulation.unwrap_or_default(),
        supports: j.supports.unwrap_or((Support::Pinned, Support::Pinned)),
    };
    let variables: Vec<Variable> = (j.case.ladders)(j.space, &placeholder)
        .iter()
        .map(|l| l.variable)
        .collect();
    // a scene this combination cannot make (a formulation the method
    // refuses, a basis without free ends) is a `cannot` in every variable
    let probe = scene.and_then(|scene| {
        let resolved = level(&scene, j.space, scene.mesh.elements, scene.time.step, 8)?;
        Ok((scene, resolved))
    });
    let (scene, resolved) = match probe {
        Ok(p) => p,
        Err(e) => {
            return Ok(variables
                .iter()
                .flat_map(|&v| j.case.quantities.iter().map(move |&q| (v, q)))
                .map(|(v, q)| blank(v, q, Status::Cannot, e.to_string()))
                .collect());
        }
    };
    let combo = Combo {
        method: &j.factory.name(),
        time_order: j.factory.time_order(&resolved),
        space: j.space,
        formulation: resolved.contact.formulation,
        supports: (resolved.beam.left, resolved.beam.right),
    };
    let explicit = matches!(resolved.scheme, Scheme::CentralDifference);
    let mut rows = Vec::new();
    for ladder in (j.case.ladders)(j.space, &combo) {
        let ladder = if explicit {
            match fit_explicit(&scene, j.space, ladder) {
                Ok(l) => l,
                Err(why) => {
                    for &q in j.case.quantities {
                        rows.push(blank(ladder.variable, q, Status::Cannot, why.clone()));
                    }
                    continue;
                }
            }
        } else {
            ladder
        };
        let expects: Vec<(Quantity, Expect)> = j
            .case
            .quantities
            .iter()
            .map(|&q| (q, (j.case.expect)(&combo, ladder.variable, q)))
            .collect();
        // nothing to run when every quantity cannot
        if expects.iter().all(|(_, e)| matches!(e, Expect::Cannot(_))) {
            for (q, e) in expects {
                let Expect::Cannot(why) = e else {
                    unreachable!()
                };
                rows.push(blank(ladder.variable, q, Status::Cannot, why));
            }
            continue;
        }
        let started = std::time::Instant::now();
        let measured = measure(&scene, j, &ladder);
        let wall = started.elapsed().as_secs_f64();
        for (q, e) in expects {
            let mut row = blank(ladder.variable, q, Status::Fail, String::new());
            row.wall_seconds = wall;
            judge(&mut row, &measured, q, e, &ladder);
            rows.push(row);
        }
    }
    Ok(rows)
}

/// Most steps an explicit ladder's finest run may take: beyond it the
/// stable step of its mesh makes the ladder cost more than the matrix.
pub const MAX_EXPLICIT_STEPS: usize = 2_000_000;

/// Levels of an explicit ladder: below its stable step the time error
/// falls as Δt² ∝ h⁴ like the space error, so only the first two halvings
/// keep it ≥ 4× the space error on the bundled cases; an h or J ladder
/// runs at its finest mesh's stable step, whose cost grows as N³.
pub const EXPLICIT_LEVELS: usize = 3;

/// Fraction of the stable step 2/ω_max an explicit run is held to.
pub const EXPLICIT_MARGIN: f64 = 0.9;

/// Central difference is stable for Δt ≤ 2/ω_max (MODEL §9.1): halve a
/// ladder's Δt until every level and the dominance run are within
/// [`EXPLICIT_MARGIN`] of their meshes' limits (a Δt ladder's coarsest
/// step on its mesh and its finest on the refined mesh of the dominance
/// run; an h or J ladder's fixed step on its finest mesh), or say why not.
fn fit_explicit(
    scene: &Scene,
    space: Space,
    ladder: Ladder,
) -> std::result::Result<Ladder, String> {
    let limit = |n: usize, j: usize| -> std::result::Result<f64, String> {
        let sc = level(scene, space, n, ladder.dt, j).map_err(|e| e.to_string())?;
        central_difference_limit(&sc)
            .map(|l| EXPLICIT_MARGIN * l.dt_max)
            .map_err(|e| e.to_string())
    };
    let mut l = ladder;
    // Δt² ∝ h⁴ at the stable step: a Δt ladder spans two halvings, where
    // the time error still dominates (docs/verification.md)
    if l.variable == Variable::Dt {
        l.levels = l.levels.min(EXPLICIT_LEVELS);
    }
    let fitted = fit_levels(scene, space, l, &limit)?;
    // an h or J ladder runs at its finest mesh's stable step: when that
    // costs more than the budget, one level fewer (the finest mesh halved)
    if fitted.variable != Variable::Dt
        && scene_end(scene) / fitted.dt > EXPLICIT_STEP_BUDGET as f64
        && fitted.levels > EXPLICIT_LEVELS
    {
        l.levels = EXPLICIT_LEVELS;
        l.dt = ladder.dt;
        return fit_levels(scene, space, l, &limit);
    }
    Ok(fitted)
}

/// Steps above which an explicit h or J ladder drops its finest level.
pub const EXPLICIT_STEP_BUDGET: usize = 100_000;

/// [`fit_explicit`] for a given number of levels.
fn fit_levels(
    scene: &Scene,
    space: Space,
    ladder: Ladder,
    limit: &dyn Fn(usize, usize) -> std::result::Result<f64, String>,
) -> std::result::Result<Ladder, String> {
    let mut l = ladder;
    let last = l.levels - 1;
    let (need_first, need_last) = match l.variable {
        Variable::Dt => {
            let refined = match space {
                Space::Galerkin => limit(l.elements, l.modes * 2)?,
                // J×2 capped at the FE unknowns (the dominance run's)
                Space::Modal => {
                    let unknowns = level(scene, space, l.elements, l.dt, l.modes)
                        .map_err(|e| e.to_string())?
                        .beam_unknowns();
                    limit(l.elements, l.modes)?.min(limit(l.elements, (l.modes * 2).min(unknowns))?)
                }
                _ => limit(l.elements * 2, l.modes)?,
            };
            (
                limit(l.elements, l.modes)?,
                refined * (1usize << last) as f64,
            )
        }
        Variable::H => {
            let m = limit(l.elements << last, l.modes)?;
            (m, m)
        }
        Variable::J => {
            let m = limit(l.elements, l.modes << last)?;
            (m, m)
        }
    };
    let need = need_first.min(need_last);
    while l.dt > need {
        l.dt /= 2.0;
    }
    let t_end = scene_end(scene);
    let finest = match l.variable {
        Variable::Dt => l.dt / (1usize << last) as f64,
        _ => l.dt,
    };
    if t_end / finest > MAX_EXPLICIT_STEPS as f64 {
        return Err(format!(
            "central_difference: the stable step on this ladder's finest mesh ({need:.3e} s) needs more than {MAX_EXPLICIT_STEPS} steps"
        ));
    }
    Ok(l)
}

/// A scene's end time in seconds (a carrier-leaves end taken as 1 s: the
/// cases give seconds).
fn scene_end(scene: &Scene) -> f64 {
    match scene.time.end {
        crate::scene::EndTime::Seconds(t) => t,
        crate::scene::EndTime::CarrierLeaves => 1.0,
    }
}

/// A ladder's measurements.
struct Measured {
    /// The refined variable per level.
    levels: Vec<f64>,
    /// Displacement and force errors per level.
    displacement: Vec<f64>,
    force: Vec<f64>,
    /// The exact solution's largest displacement and force.
    scale: (f64, f64),
    /// The dominance run's errors (NaN when it could not run).
    refined: (f64, f64),
    omega_max_dt: f64,
    runs: usize,
    /// A run that failed, and why.
    failed: Option<String>,
    /// The exact solution's modal tail per J level (J ladders).
    tail: Option<Vec<f64>>,
}

/// The per-level value of the refined variable, and the level's (N, Δt, J).
fn level_params(l: &Ladder, k: usize) -> (f64, usize, f64, usize) {
    let f = 1usize << k;
    match l.variable {
        Variable::H => (f64::NAN, l.elements * f, l.dt, l.modes),
        Variable::Dt => (l.dt / f as f64, l.elements, l.dt / f as f64, l.modes),
        Variable::J => ((l.modes * f) as f64, l.elements, l.dt, l.modes * f),
    }
}

/// Run a ladder and its dominance run; errors against the exact solution.
fn measure(scene: &Scene, j: &Job, ladder: &Ladder) -> Measured {
    let mut m = Measured {
        levels: Vec::new(),
        displacement: Vec::new(),
        force: Vec::new(),
        scale: (0.0, 0.0),
        refined: (f64::NAN, f64::NAN),
        omega_max_dt: f64::NAN,
        runs: 0,
        failed: None,
        tail: None,
    };
    let owned;
    let scene = match ladder.end {
        None => scene,
        Some(t) => {
            let mut s = scene.clone();
            s.time.end = crate::scene::EndTime::Seconds(t);
            owned = s;
            &owned
        }
    };
    let mut scenes = Vec::with_capacity(ladder.levels);
    for k in 0..ladder.levels {
        let (_, n, dt, jm) = level_params(ladder, k);
        match level(scene, j.space, n, dt, jm) {
            Ok(s) => scenes.push(s),
            Err(e) => {
                m.failed = Some(e.to_string());
                return m;
            }
        }
    }
    let finest = scenes.last().expect("a ladder has levels");
    let ex = match exact(finest) {
        Ok(Some(e)) => e,
        Ok(None) => {
            m.failed = Some("the case's scene declares no exact reference".into());
            return m;
        }
        Err(e) => {
            m.failed = Some(e.to_string());
            return m;
        }
    };
    m.omega_max_dt = central_difference_limit(finest).map_or(f64::NAN, |l| l.omega_max * finest.dt);
    let coarse = (scenes[0].steps, scenes[0].dt);
    for (k, sc) in scenes.iter().enumerate() {
        m.levels.push(match ladder.variable {
            Variable::H => sc.resolution(),
            Variable::Dt => sc.dt,
            Variable::J => sc.discretization.modes().unwrap_or(0) as f64,
        });
        let out = match run_with(sc, j.factory, &mut |_, _| {}) {
            Ok(o) => o,
            Err(e) => {
                m.failed = Some(format!("level {k}: {e}"));
                return m;
            }
        };
        m.runs += 1;
        let Ok(stride) = nest(coarse, (sc.steps, sc.dt), Reach::SameEnd) else {
            m.failed = Some("the levels' time grids do not nest".into());
            return m;
        };
        let (d, f, scale) = errors(sc, &out, &ex, stride, coarse.0);
        m.displacement.push(d);
        m.force.push(f);
        m.scale = scale;
    }
    if ladder.variable == Variable::J
        && let Some(mf) = &finest.manufactured
    {
        m.tail = modal_tail(&scenes, mf, j.space).ok();
    }
    if ladder.fixed_exact {
        m.refined = (
            m.displacement[ladder.levels - 1],
            m.force[ladder.levels - 1],
        );
        return m;
    }
    // the dominance run: the finest level with the fixed variables refined
    // (a modal basis's FE mesh stays in a Δt ladder: its error is the
    // hermite ladder's at that N, which that ladder shows)
    let (_, n, dt, jm) = level_params(ladder, ladder.levels - 1);
    let (n2, dt2, j2) = match ladder.variable {
        Variable::Dt => match j.space {
            Space::Galerkin => (n, dt, jm * 2),
            Space::Modal => (n, dt, (jm * 2).min(finest.beam_unknowns())),
            _ => (n * 2, dt, jm),
        },
        // a modal basis's FE mesh stays in its J ladder too: refining it
        // makes the dense eigenvectors less accurate (ε·ω_max²/Δω²), which
        // docs/verification.md shows on its own
        Variable::H | Variable::J => (n, dt / 2.0, jm),
    };
    if let Ok(sc) = level(scene, j.space, n2, dt2, j2)
        && let Ok(out) = run_with(&sc, j.factory, &mut |_, _| {})
        && let Ok(stride) = nest(coarse, (sc.steps, sc.dt), Reach::SameEnd)
    {
        m.runs += 1;
        let (d, f, _) = errors(&sc, &out, &ex, stride, coarse.0);
        m.refined = (d, f);
    }
    m
}

/// Times at which a modal tail is sampled (evenly over the run, t > 0).
pub const TAIL_TIMES: usize = 8;

/// The exact solution's own modal tail at each J level of a ladder: the
/// largest |v* − Σ_{j ≤ J} c_j φ_j| over the probes and the carrier's
/// position at [`TAIL_TIMES`] times, with c_j = ∫ρA φ_j v* dx the exact
/// modal coefficients (galerkin: the exact modes, by their own quadrature;
/// modal: the FE modes of the level's mesh, applied to the nodal
/// interpolant of v*, so the FE interpolation error is left out).
fn modal_tail(
    scenes: &[Resolved],
    mf: &crate::manufactured::Manufactured,
    space: Space,
) -> Result<Vec<f64>> {
    let finest = scenes.last().expect("levels");
    let js: Vec<usize> = scenes
        .iter()
        .map(|s| s.discretization.modes().unwrap_or(0))
        .collect();
    let jmax = *js.last().unwrap_or(&0);
    let t_end = finest.steps as f64 * finest.dt;
    let times: Vec<f64> = (1..=TAIL_TIMES)
        .map(|k| t_end * k as f64 / TAIL_TIMES as f64)
        .collect();
    let points = |t: f64| -> Vec<f64> {
        let mut p: Vec<f64> = finest.probes.iter().map(|(_, x)| *x).collect();
        p.extend((0..mf.carriers()).map(|c| mf.position(c, t)));
        p
    };
    let mut tail = vec![0.0f64; js.len()];
    match space {
        Space::Galerkin => {
            let shapes = crate::analytic::ModeShapes::new(&finest.beam, jmax)?;
            let quad = shapes.quadrature(finest.beam.length / 400.0);
            let mut phi = vec![0.0; jmax];
            for &t in &times {
                let mut c = vec![0.0; jmax];
                for &(x, w) in &quad {
                    shapes.values_into(x, &mut phi);
                    let v = finest.beam.rho_a * mf.v(x, t) * w;
                    for (cj, p) in c.iter_mut().zip(&phi) {
                        *cj += v * p;
                    }
                }
                for x in points(t) {
                    shapes.values_into(x, &mut phi);
                    let exact = mf.v(x, t);
                    for (k, &j) in js.iter().enumerate() {
                        let sum: f64 = c[..j].iter().zip(&phi[..j]).map(|(a, b)| a * b).sum();
                        tail[k] = tail[k].max((exact - sum).abs());
                    }
                }
            }
        }
        Space::Modal => {
            use crate::model::beam::BeamModel;
            let mesh =
                crate::model::mesh::Mesh::new(finest.beam.length, finest.elements, finest.grading)?;
            let fe = BeamModel::on_mesh(&finest.beam, mesh);
            let pairs = crate::model::eigen::lowest_eigenpairs(&fe.mass, &fe.stiffness, jmax)?;
            let n = fe.n;
            for &t in &times {
                // the nodal interpolant d* of v*(·, t)
                let mut d = vec![0.0; n];
                let per_node = if finest.beam.is_string() { 1 } else { 2 };
                for node in 0..=fe.mesh.elements() {
                    let x = fe.mesh.node(node);
                    let f = mf.fields(x, t);
                    if let Some(i) = fe.dof_of[per_node * node] {
                        d[i] = f.v;
                    }
                    if per_node == 2
                        && let Some(i) = fe.dof_of[2 * node + 1]
                    {
                        d[i] = f.v_x;
                    }
                }
                let mut md = vec![0.0; n];
                fe.mass.mul_acc(&d, 1.0, &mut md);
                let c: Vec<f64> = (0..jmax)
                    .map(|j| pairs.shape(j).iter().zip(&md).map(|(a, b)| a * b).sum())
                    .collect();
                for x in points(t) {
                    let r = fe.point_vector(x);
                    let full = r.dot(&d);
                    let modes: Vec<f64> = (0..jmax).map(|j| r.dot(pairs.shape(j))).collect();
                    for (k, &j) in js.iter().enumerate() {
                        let sum: f64 = c[..j].iter().zip(&modes[..j]).map(|(a, b)| a * b).sum();
                        tail[k] = tail[k].max((full - sum).abs());
                    }
                }
            }
        }
        _ => {}
    }
    Ok(tail)
}

/// Max errors over the coarse grid's rows 1 ..= `rows` of a run: the
/// displacement (under carrier 0, at the probes, of its mass) and the force
/// (at the time the multiplier acts); and the exact solution's largest
/// values there.
fn errors(
    sc: &Resolved,
    out: &RunOutput,
    ex: &Exact,
    stride: usize,
    rows: usize,
) -> (f64, f64, (f64, f64)) {
    let h = &out.history;
    let c = &h.carriers[0];
    let lag = out.force_lag * sc.dt;
    let has_force =
        ex.force.is_some() && matches!(sc.carriers[0].kind, CarrierKind::MassSpring { .. });
    let (mut ed, mut ef, mut sd, mut sf) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for k in 1..=rows {
        let i = k * stride;
        let t = h.t[i];
        let w = (ex.w)(t);
        sd = sd.max(w.abs());
        ed = ed.max((c.w[i] - w).abs());
        if let Some(q) = &ex.mass {
            ed = ed.max((c.q[i] - q(t)).abs());
        }
        if let Some(field) = &ex.field {
            for ((_, x), (_, col)) in sc.probes.iter().zip(&h.probes) {
                let v = field(*x, t);
                sd = sd.max(v.abs());
                ed = ed.max((col[i] - v).abs());
            }
        }
        if has_force && let Some(f) = &ex.force {
            let l = f(t - lag);
            sf = sf.max(l.abs());
            ef = ef.max((c.force[i] - l).abs());
        }
    }
    if !has_force {
        ef = f64::NAN;
    }
    (ed, ef, (sd, sf))
}

/// Fill a row from a ladder's measurements and its expectation.
fn judge(row: &mut VerifyRow, m: &Measured, q: Quantity, e: Expect, ladder: &Ladder) {
    let (errors, refined, scale) = match q {
        Quantity::Displacement => (&m.displacement, m.refined.0, m.scale.0),
        Quantity::Force => (&m.force, m.refined.1, m.scale.1),
    };
    row.levels = m.levels.clone();
    row.errors = errors.clone();
    row.runs = m.runs;
    row.omega_max_dt = m.omega_max_dt;
    if let (Some(&a), Some(&b)) = (m.levels.first(), m.levels.last()) {
        row.range = (a, b);
    }
    let r = 2.0;
    row.orders = errors
        .windows(2)
        .map(|w| observed_order(w[0], w[1], r))
        .collect();
    let k = errors.len();
    if k >= 2 {
        row.observed = observed_order(errors[0], errors[k - 1], r.powi(k as i32 - 1));
        row.relative_error = errors[k - 1] / scale.max(f64::MIN_POSITIVE);
        row.other_share = (errors[k - 1] - refined).abs() / errors[k - 1];
    }
    let measured_ok = m.failed.is_none() && k == ladder.levels;
    let e = match e {
        Expect::ModalTail { tol } => match &m.tail {
            Some(t) if t.len() >= 2 && m.failed.is_none() => Expect::Order {
                order: observed_order(t[0], t[t.len() - 1], r.powi(t.len() as i32 - 1)),
                tol,
            },
            _ => Expect::Report(
                "the order of v*'s modal tail could not be computed for this basis".into(),
            ),
        },
        e => e,
    };
    match e {
        Expect::ModalTail { .. } => unreachable!("replaced above"),
        Expect::Order { order, tol } => {
            row.expected = order;
            row.tolerance = tol;
            if let Some(f) = &m.failed {
                row.status = Status::Fail;
                row.note = format!("a run failed: {f}");
            } else if !measured_ok || !row.observed.is_finite() {
                row.status = Status::Fail;
                row.note = "no order: an error is zero or not finite".into();
            } else if (row.observed - order).abs() > tol {
                row.status = Status::Fail;
                row.note = format!(
                    "observed order {:.2} is outside {order} ± {tol}",
                    row.observed
                );
            } else if row.other_share.is_nan() || row.other_share > DOMINANCE_LIMIT {
                row.status = Status::Fail;
                row.note = format!(
                    "the fixed variables ({}) make {:.0} % of the finest error (limit {:.0} %): the order is not the refined variable's",
                    match ladder.variable {
                        Variable::Dt => "the mesh",
                        _ => "Δt",
                    },
                    100.0 * row.other_share,
                    100.0 * DOMINANCE_LIMIT
                );
            } else {
                row.status = Status::Pass;
            }
        }
        Expect::Known { order, why } => {
            row.expected = order;
            row.status = Status::Known;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
        Expect::Cannot(why) => {
            row.status = Status::Cannot;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
        Expect::Report(why) => {
            row.status = Status::Reported;
            row.note = match &m.failed {
                Some(f) => format!("{why} (a run failed: {f})"),
                None => why,
            };
        }
    }
}

/// True when any row failed.
pub fn any_failed(rows: &[VerifyRow]) -> bool {
    rows.iter().any(|r| r.status == Status::Fail)
}
