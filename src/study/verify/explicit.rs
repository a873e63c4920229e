//! An explicit method's ladder (central difference), held below its stable
//! step 2/ω_max (MODEL §9.1) within a step budget.

use super::case::{Ladder, Space, Variable};
use super::level::{level, scene_end};
use crate::integrate::central_difference_limit;
use crate::scene::Scene;
/// Most steps an explicit ladder's finest run may take: beyond it the
/// stable step of its mesh makes the ladder cost more than the matrix.
pub(crate) const MAX_EXPLICIT_STEPS: usize = 2_000_000;

/// Levels of an explicit ladder: below its stable step the time error
/// falls as Δt² ∝ h⁴ like the space error, so only the first two halvings
/// keep it ≥ 4× the space error on the bundled cases; an h or J ladder
/// runs at its finest mesh's stable step, whose cost grows as N³.
pub(crate) const EXPLICIT_LEVELS: usize = 3;

/// Fraction of the stable step 2/ω_max an explicit run is held to.
pub(crate) const EXPLICIT_MARGIN: f64 = 0.9;

/// Central difference is stable for Δt ≤ 2/ω_max (MODEL §9.1): halve a
/// ladder's Δt until every level and the dominance run are within
/// [`EXPLICIT_MARGIN`] of their meshes' limits (a Δt ladder's coarsest
/// step on its mesh and its finest on the refined mesh of the dominance
/// run; an h or J ladder's fixed step on its finest mesh), or say why not.
pub(super) fn fit_explicit(
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
pub(crate) const EXPLICIT_STEP_BUDGET: usize = 100_000;

/// [`fit_explicit`] for a given number of levels.
pub(super) fn fit_levels(
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
                // J×2 capped at the FE unknowns (the dominance run's); with
                // every mode already, the dominance run is N×2 with every mode
                Space::Modal => {
                    let unknowns = |n: usize| {
                        level(scene, Space::Hermite, n, l.dt, 0)
                            .map(|s| s.beam_unknowns())
                            .map_err(|e| e.to_string())
                    };
                    let here = unknowns(l.elements)?;
                    let refined = if l.modes >= here {
                        limit(l.elements * 2, unknowns(l.elements * 2)?)?
                    } else {
                        limit(l.elements, (l.modes * 2).min(here))?
                    };
                    limit(l.elements, l.modes)?.min(refined)
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
        // a κ ladder keeps its mesh and step; the dominance run's N×2 (J×2)
        Variable::Kappa => {
            let m = limit(l.elements * 2, l.modes)?.min(limit(l.elements, l.modes)?);
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
