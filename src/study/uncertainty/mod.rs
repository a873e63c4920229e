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
//! * [`mod@quantity`]: what is given an error bar.
//!
//! This file runs the family and assesses every quantity
//! ([`uncertainty`]).

pub mod assess;
pub mod family;
pub mod gci;
pub mod least_squares;
pub mod order;
pub mod quantity;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::integrate::scene_method;
use crate::quantity::formal_orders::MAX_STEP_ORDER;
use crate::resolve::resolve_scene;
use crate::run::run;
use crate::scene::Discretization;
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
    /// Diagonal levels K.
    pub levels: usize,
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

/// Whether a contact opens or closes in any run of the family (a loss
/// interval), read from the values of `qs`.
fn outs_switch(values: &[Vec<Option<f64>>], qs: &[&crate::quantity::Quantity]) -> bool {
    let loss = qs
        .iter()
        .position(|q| q.name == crate::quantity::LOSS_INTERVAL_COUNT.name)
        .expect("loss_interval_count is given an error bar");
    values.iter().any(|v| v[loss].is_some_and(|n| n > 0.0))
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
/// levels, and assess every quantity. `progress(done, runs)` as runs
/// finish. A run that stops on a divergence makes every quantity
/// `diverged`, naming it; any other error of a run is the study's.
pub fn uncertainty(
    text: &str,
    overrides: &[String],
    levels: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Uncertainty> {
    check_levels(levels)?;
    let start = std::time::Instant::now();
    let base = resolve_scene(text, overrides)?;
    base.require_every_step("taut uncertainty")?;
    let scenes = family::scenes(&base, levels)?;
    let plan = family::plan(levels);
    let outs = crate::study::threads::map_with_progress(
        &scenes,
        run_dof_steps,
        |sc| run(sc, &mut |_, _| {}),
        progress,
    );
    let mut family: Vec<Member> = plan
        .iter()
        .zip(&scenes)
        .map(|(&(role, l, _, _), sc)| Member::of(role, l, sc))
        .collect();
    let qs = quantities();
    let mut values: Vec<Vec<Option<f64>>> = Vec::with_capacity(outs.len());
    let mut stopped: Option<String> = None;
    let mut first_divergence: Option<Error> = None;
    for (m, out) in family.iter_mut().zip(outs) {
        match out {
            Ok(o) => {
                m.steps = o.steps;
                m.dofs = o.dofs;
                m.wall_seconds = o.wall_seconds;
                values.push(quantity::all_values(&o, &qs));
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
                stopped.get_or_insert_with(|| format!("{run}: {e}"));
                if first_divergence.is_none() {
                    first_divergence = Some(e.in_run(&format!("the family's {run}")));
                }
                values.push(vec![None; qs.len()]);
            }
            Err(e) => {
                return Err(e.in_run(&format!(
                    "the family's {:?} run of level {}",
                    m.role, m.level
                )));
            }
        }
    }
    // an opening or closing contact (a loss interval) makes the
    // displacement's Δt order 1
    let switch = outs_switch(&values, &qs);
    let method_order = scene_method(&base)
        .time_order(&base)
        .unwrap_or(MAX_STEP_ORDER);
    let string = base.beam.is_string() && base.discretization == Discretization::Hermite;
    let has_supports = !base.wire.supports.is_empty();
    let mut quantities = Vec::new();
    for (i, q) in qs.iter().enumerate() {
        if q.name == crate::quantity::UPLIFT_MAX.name && !has_supports {
            continue;
        }
        let column = |role: Role| -> Vec<Option<f64>> {
            family
                .iter()
                .zip(&values)
                .filter(|(m, _)| m.role == role)
                .map(|(_, v)| v[i])
                .collect()
        };
        let (diagonal, space) = (column(Role::Diagonal), column(Role::Space));
        let formal = quantity::formal_orders(q, method_order, switch, string);
        let inputs = Inputs {
            diagonal: &diagonal,
            space: &space,
            ratio: RATIO as f64,
            formal,
            smooth: q.smooth,
        };
        let assessment = match &stopped {
            Some(why) => Assessment::diverged(&inputs, why),
            None => assess(&inputs),
        };
        quantities.push(QuantityUncertainty {
            quantity: q.name,
            unit: q.unit,
            smooth: q.smooth,
            formal,
            value_scene: diagonal[0],
            u_scene: assessment.u_levels.first().copied().flatten(),
            diagonal,
            space,
            assessment,
        });
    }
    let mut notes = Vec::new();
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
        levels,
        family,
        quantities,
        notes,
        wall_seconds: start.elapsed().as_secs_f64(),
        stopped: first_divergence.map(std::sync::Arc::new),
    })
}
