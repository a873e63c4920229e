//! The family of solutions `taut uncertainty` runs from a scene (MODEL
//! §12, "space and time together"): from the scene's own level (N₀ or J₀)
//! and step Δt₀,
//!
//! * the **diagonal**: level ℓ = 0 … K − 1 at N₀·2^ℓ (or J₀·2^ℓ) and
//!   Δt₀/2^ℓ, h and Δt refined together at the fixed ratio Δt/h of the
//!   scene (Eça et al.'s refinement of space and time together);
//! * the **split**: for ℓ = 1 … K − 1, level ℓ's mesh at level ℓ − 1's Δt,
//!   which divides each diagonal change into its space part (mesh refined
//!   at a fixed Δt) and its time part (Δt refined on a fixed mesh).
//!
//! 2K − 1 runs, of cost Σ 4^ℓ + Σ 2·4^(ℓ−1) scene runs (31 for K = 3, 127
//! for K = 4). The runs are independent and run in parallel. Each ends at
//! the scene's end time (its last whole step before it, as any run), and
//! only their scalars are compared, so any end time works.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::study::level::Level;

/// Refinement ratio between diagonal levels (in N or J, and in Δt).
pub const RATIO: usize = 2;

/// Levels of the diagonal (`--levels`): three for a GCI, four (the
/// default) for a least-squares fit with a degree of freedom, at most six
/// (4⁵ = 1024 times the scene's run on the finest level).
pub(crate) const LEVELS: std::ops::RangeInclusive<usize> = 3..=6;

/// Levels when none are asked for: the fewest for which the least-squares
/// estimator of a three-parameter fit has a degree of freedom.
pub const DEFAULT_LEVELS: usize = 4;

/// `levels` if within [`LEVELS`], else the error naming `--levels`.
pub(crate) fn check_levels(levels: usize) -> Result<usize> {
    crate::study::grid::in_range("--levels", levels, &LEVELS)
}

/// Where a run sits in the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Level ℓ of the diagonal: mesh and Δt both refined ℓ times.
    Diagonal,
    /// The split run of level ℓ: mesh refined ℓ times, Δt ℓ − 1 times.
    Space,
}

/// One run of the family (a row of the family table).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Member {
    /// Its role.
    pub role: Role,
    /// Its level ℓ.
    pub level: usize,
    /// Elements N.
    pub elements: usize,
    /// Modes J of a `galerkin` or `modal` basis.
    pub modes: Option<usize>,
    /// The length it resolves, m ([`Resolved::resolution`]).
    pub h: f64,
    /// Time step, s.
    pub dt: f64,
    /// Steps taken (0 before it runs).
    pub steps: usize,
    /// Unknowns.
    pub dofs: usize,
    /// Wall seconds of its run (machine-dependent).
    pub wall_seconds: f64,
}

/// The family's runs, planned: (role, level, level parameter factor, Δt
/// divisor), diagonal first, coarsest first.
pub(crate) fn plan(levels: usize) -> Vec<(Role, usize, usize, usize)> {
    let p = |l: usize| RATIO.pow(l as u32);
    let diagonal = (0..levels).map(|l| (Role::Diagonal, l, p(l), p(l)));
    let space = (1..levels).map(|l| (Role::Space, l, p(l), p(l - 1)));
    diagonal.chain(space).collect()
}

/// The scenes of the family of `base` with `levels` diagonal levels, in
/// `plan`'s order.
pub fn scenes(base: &Resolved, levels: usize) -> Result<Vec<Resolved>> {
    let level = Level::of(base);
    let n0 = level.start();
    let log2 = |x: usize| x.ilog(RATIO) as i32;
    plan(levels)
        .into_iter()
        .map(|(role, l, f, d)| {
            let n = super::engine::level_parameter(n0, log2(f)).ok_or_else(|| {
                Error::invalid(
                    "--levels",
                    levels,
                    format!("{} = {n0} × {f} is too large", level.symbol()),
                )
            })?;
            // the runs the accuracy engine makes: every level measures P_l
            // over the scene's own support zone
            super::engine::member_scene(base, level, n, log2(d))
                .map_err(|e| at_level(e, (role, l, f, d), (level.symbol(), n0)))
        })
        .collect()
}

/// An error of the family's run `(role, l, f, d)` (its level parameter
/// `f` times the scene's `given` = (symbol, n0), its step the scene's ÷
/// `d`): a value it names is that level's, not the one the user wrote,
/// and says so; a divergence or failed contact names the run.
fn at_level(e: Error, (role, l, f, d): (Role, usize, usize, usize), given: (&str, usize)) -> Error {
    match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::Invalid {
            field,
            value: format!(
                "{value} at level {l} of the family ({role:?} run: {} = {} × {f} from the given {}, Δt = the given ÷ {d})",
                given.0,
                given.1.saturating_mul(f),
                given.1
            ),
            allowed,
        },
        e => e.in_run(&format!("the family's {role:?} run of level {l}")),
    }
}

impl Member {
    /// The member of role `role` and level `l` for scene `sc`, not yet run.
    pub fn of(role: Role, l: usize, sc: &Resolved) -> Self {
        Member {
            role,
            level: l,
            elements: sc.elements,
            modes: sc.discretization.modes(),
            h: sc.resolution(),
            dt: sc.dt,
            steps: 0,
            dofs: 0,
            wall_seconds: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_is_the_diagonal_then_the_split() {
        let p = plan(3);
        assert_eq!(
            p,
            [
                (Role::Diagonal, 0, 1, 1),
                (Role::Diagonal, 1, 2, 2),
                (Role::Diagonal, 2, 4, 4),
                (Role::Space, 1, 2, 1),
                (Role::Space, 2, 4, 2),
            ]
        );
        // cost in scene runs: 31 for three levels, 127 for four
        let cost = |k| plan(k).iter().map(|(_, _, f, d)| f * d).sum::<usize>();
        assert_eq!((cost(3), cost(4)), (31, 127));
        assert!(check_levels(2).is_err() && check_levels(7).is_err());
    }

    /// Every member measures P_l over the scene's own support zone, a
    /// length of the physics: on the reference scene 4ℓ_b = 0.2625 m,
    /// whatever N and Δt.
    #[test]
    fn every_member_keeps_the_scene_s_support_zone() {
        use crate::record::zone::{LossGeometry, support_zone_of};
        let base =
            crate::resolve::resolve_scene(include_str!("../../../scenes/reference.toml"), &[])
                .unwrap();
        let zone = support_zone_of(&base);
        let bending_length = (base.beam.ei / base.beam.tension).sqrt();
        assert!((zone - 4.0 * bending_length).abs() < 1e-12, "{zone}");
        let family = scenes(&base, 3).unwrap();
        for sc in &family {
            assert_eq!(sc.analysis.support_zone, Some(zone));
            assert_eq!(LossGeometry::of(sc, 0).support_zone, zone);
        }
        // and the finest level's own default is the same length
        let mut finest = family[2].clone();
        finest.analysis.support_zone = None;
        assert_eq!(LossGeometry::of(&finest, 0).support_zone, zone);
    }
}
