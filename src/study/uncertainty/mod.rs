//! Solution verification (MODEL §12): the numerical uncertainty of what a
//! user reports of their own scene, which has no exact solution.
//!
//! The field's estimators, one concept a file, used by every study that
//! estimates an error (`taut uncertainty`, `taut converge`, `run
//! --tolerance`, the accuracy-targeted sweep):
//!
//! * [`order`]: observed orders (two levels, and fitted over a ladder),
//!   Richardson's error, Roache's convergence ratio and a ladder's
//!   behaviour (monotone, oscillatory, diverging, scattered);
//! * [`gci`]: Roache's grid convergence index;
//! * [`least_squares`]: Eça & Hoekstra's least-squares estimator (J.
//!   Comput. Phys. 262 (2014) 104–130) for scattered or non-monotone data;
//! * `assess`: which of them a quantity's values call for, the orders the
//!   data support, and the split of the error between space and time;
//! * [`family`]: the family of runs of `taut uncertainty` (h and Δt refined
//!   together, and apart);
//! * `engine`: what `taut uncertainty` and the accuracy engine share —
//!   a family's runs, its formal orders and its assessment;
//! * [`mod@quantity`]: what is given an error bar.
//!
//! This file runs the family and assesses every quantity
//! ([`uncertainty`]).

pub mod assess;
pub(crate) mod engine;
pub mod family;
pub mod gci;
pub mod least_squares;
pub mod order;
pub mod quantity;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::resolve::{Resolved, resolve_scene};
use crate::run::run;
use crate::study::cost::{Estimate, run_dof_steps};
use crate::study::level::Level;

pub use assess::{Assessment, Estimator, Inputs, assess};
pub(crate) use family::check_levels;
pub use family::{DEFAULT_LEVELS, Member, RATIO, Role};
pub use gci::{FS_ASYMPTOTIC, FS_CAUTIOUS, Gci};
pub(crate) use order::richardson_error;
pub use order::{Behaviour, behaviour, fitted_order, observed_order};
pub use quantity::{quantities, quantity};

/// One quantity's row: what it is and its assessment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct QuantityUncertainty {
    /// Its name.
    pub quantity: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Smooth in the resolution ([`crate::quantity::Quantity::smooth`]).
    pub smooth: bool,
    /// The formal orders (space, time).
    pub formal: (f64, f64),
    /// The scene's own value (the coarsest level).
    pub value_scene: Option<f64>,
    /// Its U: at least |value_scene − value| + u_num, so it covers
    /// whenever u_num does ([`assess::cover_coarser_levels`]).
    pub u_scene: Option<f64>,
    /// The values of the diagonal, coarsest first.
    pub diagonal: Vec<Option<f64>>,
    /// The values of the split runs (level 1 first).
    pub space: Vec<Option<f64>>,
    /// The assessment of the finest value.
    #[serde(flatten)]
    pub assessment: Assessment,
}

/// A finished `taut uncertainty`.
#[derive(Debug, Clone, Serialize)]
pub struct Uncertainty {
    /// The scene as given (its own resolution: the family's level 0).
    #[serde(skip)]
    pub scene: crate::scene::Scene,
    /// `N` or `J`: the level parameter refined in space.
    pub level_symbol: &'static str,
    /// Diagonal levels K (with any added).
    pub levels: usize,
    /// Finer levels added beyond `--levels` because level 0 was
    /// pre-asymptotic ([`uncertainty_within`]): 0 or 1.
    pub levels_added: usize,
    /// The runs, in `family::plan`'s order (the diagonal, then the split).
    pub family: Vec<Member>,
    /// One row a quantity, in the registry's order (uplift only with
    /// `[output] supports`).
    pub quantities: Vec<QuantityUncertainty>,
    /// Things the numbers do not say by themselves.
    pub notes: Vec<String>,
    /// Wall seconds of the whole family (runs in parallel).
    pub wall_seconds: f64,
    /// The first divergence of a run of the family, naming the run: then
    /// nothing is estimated (every quantity is `diverged`), and a command
    /// that writes the study fails with it (`crate::app::uncertainty`).
    #[serde(skip)]
    pub stopped: Option<std::sync::Arc<Error>>,
}

/// The study's estimated work: every run of the family.
pub fn estimate(text: &str, overrides: &[String], levels: usize) -> Result<Estimate> {
    check_levels(levels)?;
    let base = resolve_scene(text, overrides)?;
    let mut e = Estimate::new("taut uncertainty");
    for sc in family::scenes(&base, levels)? {
        e.add(1, run_dof_steps(&sc));
    }
    Ok(e)
}

/// Run the family of scene `text` with `overrides` and `levels` diagonal
/// levels, and assess every quantity ([`uncertainty_within`] adding no
/// level: a pre-asymptotic level 0 is stated, not refined past).
pub fn uncertainty(
    text: &str,
    overrides: &[String],
    levels: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Uncertainty> {
    uncertainty_within(text, overrides, levels, 0.0, progress)
}

/// The most a family may cost by default, in runs of the scene
/// (`--max-cost`), once a pre-asymptotic level 0 calls for one more
/// level: 128, so a three-level family (31 runs of the scene) may grow to
/// the default four (127); a larger one grows only when asked.
pub const DEFAULT_MAX_COST: f64 = 128.0;

/// What `--max-cost` of `taut uncertainty` allows.
pub const MAX_COST_ALLOWED: &str = "must be a finite number ≥ 0: the most the family may cost, in runs of the scene (unknowns × steps)";

/// `--max-cost` if finite and ≥ 0, else the error naming it.
pub fn check_max_cost(f: f64) -> Result<f64> {
    if f.is_finite() && f >= 0.0 {
        Ok(f)
    } else {
        Err(Error::invalid("--max-cost", f, MAX_COST_ALLOWED))
    }
}

/// The family's cost in runs of the scene (unknowns × steps): Σ f·d over
/// [`family::plan`].
fn family_cost(levels: usize) -> f64 {
    family::plan(levels)
        .iter()
        .map(|&(_, _, f, d)| (f * d) as f64)
        .sum()
}

/// The family's runs made: each member, its values of `qs`, whether a
/// contact switched in it, and the first divergence (named).
struct Ran {
    family: Vec<Member>,
    values: Vec<Vec<Option<f64>>>,
    switch: bool,
    stopped: Option<String>,
    first_divergence: Option<Error>,
}

/// Run `scenes` (members `plan` of the family), appending to `ran`.
fn run_members(
    ran: &mut Ran,
    scenes: &[Resolved],
    plan: &[(Role, usize, usize, usize)],
    qs: &[&crate::quantity::Quantity],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<()> {
    let outs = crate::study::threads::map_with_progress(
        scenes,
        run_dof_steps,
        |sc| run(sc, &mut |_, _| {}),
        progress,
    );
    for ((&(role, l, _, _), sc), out) in plan.iter().zip(scenes).zip(outs) {
        let mut m = Member::of(role, l, sc);
        match out {
            Ok(o) => {
                m.steps = o.steps;
                m.dofs = o.dofs;
                m.wall_seconds = o.wall_seconds;
                ran.switch |= engine::switches(&o);
                ran.values.push(quantity::all_values(&o, qs));
            }
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(e @ Error::Diverged { .. }) => {
                let run = format!(
                    "{:?} level {} (N = {}{}, Δt = {:e} s)",
                    m.role,
                    m.level,
                    m.elements,
                    m.modes.map_or(String::new(), |j| format!(", J = {j}")),
                    m.dt
                );
                ran.stopped.get_or_insert_with(|| format!("{run}: {e}"));
                if ran.first_divergence.is_none() {
                    ran.first_divergence = Some(e.in_run(&format!("the family's {run}")));
                }
                ran.values.push(vec![None; qs.len()]);
            }
            Err(e) => {
                return Err(e.in_run(&format!(
                    "the family's {:?} run of level {}",
                    m.role, m.level
                )));
            }
        }
        ran.family.push(m);
    }
    Ok(())
}

/// Every quantity of `qs` assessed on the family `ran`
/// ([`engine::assess_family`]).
fn assess_all(
    base: &Resolved,
    ran: &Ran,
    qs: &[&crate::quantity::Quantity],
    without_start: &[(&'static str, f64)],
) -> Vec<QuantityUncertainty> {
    let has_supports = !base.wire.supports.is_empty();
    let mut quantities = Vec::new();
    for (i, q) in qs.iter().enumerate() {
        if q.name == crate::quantity::UPLIFT_MAX.name && !has_supports {
            continue;
        }
        let column = |role: Role| -> Vec<Option<f64>> {
            ran.family
                .iter()
                .zip(&ran.values)
                .filter(|(m, _)| m.role == role)
                .map(|(_, v)| v[i])
                .collect()
        };
        let (diagonal, space) = (column(Role::Diagonal), column(Role::Space));
        let inputs = engine::inputs(base, q, &diagonal, &space, ran.switch);
        let start = without_start.iter().find(|(name, _)| *name == q.name);
        let assessment = match (&ran.stopped, start) {
            (Some(why), _) => Assessment::diverged(&inputs, why),
            (None, Some(&(_, excess))) => {
                assess::assess_without_start(&inputs, excess, engine::ADD_LEVEL_MARGIN)
            }
            (None, None) => assess(&inputs),
        };
        // a loss fraction 0 at every run: what the finest Δt cannot see
        let finest_dt = ran
            .family
            .iter()
            .map(|m| m.dt)
            .fold(f64::INFINITY, f64::min);
        let assessment =
            engine::unseen_loss_floor(assessment, q, &diagonal, &space, finest_dt, base.t_end);
        quantities.push(QuantityUncertainty {
            quantity: q.name,
            unit: q.unit,
            smooth: q.smooth,
            formal: inputs.formal,
            value_scene: diagonal[0],
            u_scene: assessment.u_levels.first().copied().flatten(),
            diagonal,
            space,
            assessment,
        });
    }
    quantities
}

/// The quantities of a three-level family whose level 0 is pre-asymptotic
/// ([`engine::dominated_start`]), each with its excess, largest first.
fn dominated(quantities: &[QuantityUncertainty], ratio: f64) -> Vec<(&'static str, f64)> {
    let mut found: Vec<(&'static str, f64)> = quantities
        .iter()
        .filter(|r| r.assessment.u_num.is_some())
        .filter_map(|r| {
            let inputs = Inputs {
                diagonal: &r.diagonal,
                space: &r.space,
                ratio,
                formal: r.formal,
                smooth: r.smooth,
            };
            engine::dominated_start(&inputs).map(|x| (r.quantity, x))
        })
        .collect();
    found.sort_by(|a, b| b.1.total_cmp(&a.1));
    found
}

/// Run the family of scene `text` with `overrides` and `levels` diagonal
/// levels, and assess every quantity. `progress(done, runs)` as runs
/// finish. A run that stops on a divergence makes every quantity
/// `diverged`, naming it; any other error of a run is the study's.
///
/// A three-level family whose level 0 is pre-asymptotic for some quantity
/// (its change [`assess::PRE_ASYMPTOTIC_MARGIN`] times beyond what the
/// finer change allows) gets one finer level, diagonal and split, as the
/// accuracy engine refines a point further, when the grown family costs at
/// most `max_cost` runs of the scene; the assessment then drops level 0
/// from the fit. Otherwise a note says the bar is dominated by that level
/// and what to run instead.
pub fn uncertainty_within(
    text: &str,
    overrides: &[String],
    levels: usize,
    max_cost: f64,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Uncertainty> {
    check_levels(levels)?;
    let start = std::time::Instant::now();
    let base = resolve_scene(text, overrides)?;
    base.require_every_step("taut uncertainty")?;
    let scenes = family::scenes(&base, levels)?;
    let plan = family::plan(levels);
    let qs = quantities();
    let mut ran = Ran {
        family: Vec::new(),
        values: Vec::new(),
        switch: false,
        stopped: None,
        first_divergence: None,
    };
    run_members(&mut ran, &scenes, &plan, &qs, progress)?;
    let mut quantities = assess_all(&base, &ran, &qs, &[]);
    let mut levels_added = 0;
    let mut notes = Vec::new();
    let found = if ran.stopped.is_none() {
        dominated(&quantities, RATIO as f64)
    } else {
        Vec::new()
    };
    if !found.is_empty() {
        let grown = family_cost(levels + 1);
        let names: Vec<&str> = found.iter().map(|f| f.0).collect();
        let why = format!(
            "level 0 is pre-asymptotic for {}: it changes faster than the fastest formal order allows (up to {:.2}× r^p times the next change)",
            names.join(", "),
            found[0].1
        );
        // the grown family's scenes, when it is one the model takes and
        // within the study's cost bound (`--yes` does not lift it here)
        let built = (levels < *family::LEVELS.end() && grown <= max_cost)
            .then(|| family::scenes(&base, levels + 1));
        // a finer level the model refuses (J beyond the exact modes' range,
        // an N too large) is named, not blamed on the cost
        let unbuildable = match &built {
            Some(Err(e)) => Some(e.to_string()),
            _ => None,
        };
        let all = built.and_then(|r| r.ok()).filter(|all| {
            all.iter().map(run_dof_steps).sum::<f64>() <= crate::study::cost::MAX_DOF_STEPS
        });
        if let Some(all) = all {
            let wider = family::plan(levels + 1);
            let added: Vec<usize> = (0..wider.len()).filter(|&i| wider[i].1 == levels).collect();
            let scenes: Vec<Resolved> = added.iter().map(|&i| all[i].clone()).collect();
            let plan: Vec<_> = added.iter().map(|&i| wider[i]).collect();
            let done = ran.family.len();
            let total = done + added.len();
            run_members(&mut ran, &scenes, &plan, &qs, &mut |d, _| {
                progress(done + d, total)
            })?;
            // back in the grown family's order: the diagonal, then the split
            let mut order: Vec<usize> = (0..ran.family.len()).collect();
            order.sort_by_key(|&i| (ran.family[i].role == Role::Space, ran.family[i].level));
            ran.family = order.iter().map(|&i| ran.family[i].clone()).collect();
            ran.values = order.iter().map(|&i| ran.values[i].clone()).collect();
            levels_added = 1;
            quantities = assess_all(&base, &ran, &qs, &found);
            notes.push(format!(
                "{why}: one finer level added ({} runs; the family {grown:.0} runs of the scene, within --max-cost {max_cost}), and level 0 dropped from their fits",
                added.len()
            ));
        } else {
            let note = format!(
                "{why}, so their bars are dominated by it: run --levels {} (the family {grown:.0} runs of the scene{}), or start from a finer scene ({} × 2, time.step ÷ 2)",
                levels + 1,
                if let Some(e) = &unbuildable {
                    format!("; its finer level cannot be built: {e}")
                } else if grown > max_cost && max_cost > 0.0 {
                    format!(", above --max-cost {max_cost}")
                } else if grown <= max_cost {
                    format!(
                        ", above the cost bound of {:e} DOF-steps: add --yes",
                        crate::study::cost::MAX_DOF_STEPS
                    )
                } else {
                    String::new()
                },
                if Level::of(&base).symbol() == "J" {
                    "mesh.modes"
                } else {
                    "mesh.elements"
                }
            );
            for r in quantities
                .iter_mut()
                .filter(|r| names.contains(&r.quantity))
            {
                r.assessment.note = format!("{note}; {}", r.assessment.note);
            }
            notes.push(note);
        }
    }
    let (family, switch, stopped, first_divergence) =
        (ran.family, ran.switch, ran.stopped, ran.first_divergence);
    if let Some(why) = &stopped {
        notes.push(format!(
            "a run of the family stopped, so nothing is estimated: {why}"
        ));
    }
    if switch {
        notes.push("contact opens or closes in the family: the displacement's formal order in Δt is 1 (an event's time is O(Δt))".into());
        notes.push(format!(
            "every run splits P_l at the scene's own support zone, {:.4} m from each held end (analysis.support_zone), so every level measures the same P_l,span",
            crate::record::zone::support_zone_of(&base)
        ));
    }
    Ok(Uncertainty {
        scene: base.scene.clone(),
        level_symbol: Level::of(&base).symbol(),
        levels: levels + levels_added,
        levels_added,
        family,
        quantities,
        notes,
        wall_seconds: start.elapsed().as_secs_f64(),
        stopped: first_divergence.map(std::sync::Arc::new),
    })
}
