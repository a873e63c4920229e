//! `taut precision`: error against cost for each time integrator and
//! formulation over a grid of (mesh, Δt) — a work–precision study.
//!
//! The reference is one Lagrange run under the scene's own method at the
//! finest mesh and step of the grid, each refined once more by `ratio` (so
//! every grid run is coarser than it).
//! Grid points run at N₀·r^i elements and Δt₀/r^j (i, j = 0 … levels−1).
//! Times nest (r is an integer), so errors are taken sample by sample on each
//! run's own time grid against the reference sampled there:
//!
//! * `force_error` — RMS of λ − λ_ref over the run's steps, relative to the
//!   RMS of λ_ref (carrier 0);
//! * `displacement_error` — the same for w under the carrier;
//! * `loss_fraction_error` — |P_l − P_l,ref|.
//!
//! Cost: wall seconds of the run (machine-dependent) and DOF-steps
//! (unknowns × steps, machine-independent). A point is on the Pareto front of
//! its formulation when no other point of that formulation has both a smaller
//! force error and a smaller wall time. A grid point a method cannot take (an
//! explicit method above its stability limit, a combination that means
//! nothing) is skipped with its reason; a run that stops is an error.

use std::sync::Arc;

use serde::Serialize;

use super::compare::{NotRun, Reason};
use super::grid::{Reach, nest, resample};
use super::relative_rms;
use super::space::SpaceChoice;
use super::variant::{RunVariant, base_scene};
use crate::error::{Error, Result};
use crate::integrate::MethodFactory;
use crate::resolve::{Resolved, resolve_scene};
use crate::run::{RunOutput, run};
use crate::scene::{Formulation, MeshKind};

/// One run of the study (a row of `precision.csv`).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PrecisionRow {
    /// Time integrator.
    pub method: String,
    /// Space discretization (`mesh.kind`).
    pub discretization: String,
    /// Formulation name.
    pub formulation: String,
    /// Mesh level i (N = N₀·rⁱ).
    pub mesh_level: usize,
    /// Step level j (Δt = Δt₀/rʲ).
    pub step_level: usize,
    /// Elements N.
    pub elements: usize,
    /// Modes J of a modal basis (its level parameter); `None` for elements.
    pub modes: Option<usize>,
    /// Time step, s.
    pub dt: f64,
    /// Unknowns.
    pub dofs: usize,
    /// Steps.
    pub steps: usize,
    /// dofs × steps.
    pub dof_steps: f64,
    /// Wall seconds (machine-dependent).
    pub wall_seconds: f64,
    /// Relative RMS error of the contact force.
    pub force_error: f64,
    /// Relative RMS error of w under the carrier.
    pub displacement_error: f64,
    /// |P_l − P_l,ref|.
    pub loss_fraction_error: f64,
    /// Carrier 0's values of the quantities the tables with one row per
    /// run offer ([`crate::quantity::Offer::RUN_TABLES`]), by name.
    #[serde(flatten)]
    pub quantities: crate::quantity::Values,
    /// On its formulation's Pareto front (force error vs wall time).
    pub pareto: bool,
}

/// A finished study.
pub struct Precision {
    /// Reference elements and step.
    pub reference: (usize, f64),
    /// Reference wall seconds.
    pub reference_wall: f64,
    /// The reference's method.
    pub reference_method: String,
    /// All rows: method-major, then formulation, mesh level, step level.
    pub rows: Vec<PrecisionRow>,
    /// Grid points that were not run, with the reason.
    pub skipped: Vec<NotRun>,
}

/// Grid levels per axis a precision study takes (`--levels`, Python
/// `levels=`): levels² grid points per formulation, method and
/// discretization.
pub(crate) const LEVELS: std::ops::RangeInclusive<usize> = 1..=5;

/// `levels` if within [`LEVELS`], else the error naming `--levels`.
/// Checked before the study's cost is estimated.
pub(crate) fn check_levels(levels: usize) -> Result<usize> {
    super::grid::in_range("--levels", levels, &LEVELS)
}

/// `ratio` if an integer ≥ 2, else the error naming `--ratio` (a ratio so
/// large that the reference mesh overflows is refused by
/// [`reference_elements`]).
pub(crate) fn check_ratio(ratio: usize) -> Result<usize> {
    if ratio >= 2 {
        Ok(ratio)
    } else {
        Err(Error::invalid("--ratio", ratio, "must be an integer ≥ 2"))
    }
}

/// The reference run's mesh, N₀ × ratio^levels (one level beyond the
/// grid's finest), checked: a ratio so large it overflows would wrap to a
/// meaningless mesh in a release build. Also what the study's cost
/// estimate checks first ([`super::request::PrecisionStudy::estimate`]).
pub(crate) fn reference_elements(n0: usize, ratio: usize, levels: usize) -> Result<usize> {
    u32::try_from(levels)
        .ok()
        .and_then(|l| ratio.checked_pow(l))
        .and_then(|p| n0.checked_mul(p))
        .ok_or_else(|| {
            Error::invalid(
                "--ratio",
                ratio,
                format!("too large: the reference mesh, N₀ = {n0} × ratio^{levels}, overflows"),
            )
        })
}

/// Run the study under the scene's own method. `progress(done, total)`
/// after each run.
pub fn precision(
    text: &str,
    overrides: &[String],
    formulations: &[Formulation],
    levels: usize,
    ratio: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Precision> {
    precision_methods(text, overrides, &[], formulations, levels, ratio, progress)
}

/// Run the study for every method × formulation (`methods` empty: the
/// scene's own). `progress(done, total)` after each run.
pub fn precision_methods(
    text: &str,
    overrides: &[String],
    methods: &[&dyn MethodFactory],
    formulations: &[Formulation],
    levels: usize,
    ratio: usize,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Precision> {
    precision_variants(
        text,
        overrides,
        (methods, &[]),
        formulations,
        (levels, ratio, crate::study::sweep::AUTO_BATCH_LANES),
        progress,
    )
}

/// Run the study for every method × discretization × formulation (either
/// list empty: the scene's own). A discretization's mesh level is its own
/// level parameter: N₀·rⁱ elements for `hermite`, J₀·rⁱ modes for
/// `galerkin` and `modal` (on the scene's mesh). The reference is the
/// Hermite one of the module docs. `progress(done, total)` after each run.
pub fn precision_variants(
    text: &str,
    overrides: &[String],
    (methods, spaces): (&[&dyn MethodFactory], &[SpaceChoice]),
    formulations: &[Formulation],
    (levels, ratio, batch): (usize, usize, usize),
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Precision> {
    check_levels(levels)?;
    check_ratio(ratio)?;
    let base = resolve_scene(text, overrides)?;
    base.require_every_step("taut precision")?;
    let own = crate::integrate::scene_method(&base);
    let methods: Vec<&dyn MethodFactory> = if methods.is_empty() {
        vec![own]
    } else {
        methods.to_vec()
    };
    let (n0, dt0) = (base.elements, base.dt);
    let r = ratio as f64;
    let fine = levels as i32; // one beyond the grid's finest
    let ref_n = reference_elements(n0, ratio, levels)?;
    let ref_dt = dt0 / r.powi(fine);
    let spaces: Vec<Option<SpaceChoice>> = if spaces.is_empty() {
        vec![None]
    } else {
        spaces.iter().copied().map(Some).collect()
    };
    let total = 1 + methods.len() * spaces.len() * formulations.len() * levels * levels;
    let mut done = 0;
    // the reference is a Hermite run whatever the scene's own kind
    let ref_sc = RunVariant {
        elements: Some(ref_n),
        dt: Some(ref_dt),
        formulation: Some(Formulation::Lagrange),
        space: Some((
            SpaceChoice {
                kind: MeshKind::Hermite,
                modes: None,
            },
            1.0,
        )),
        support_zone: None,
    }
    .apply(&base)?;
    let reference = run(&ref_sc, &mut |_, _| {})?;
    done += 1;
    progress(done, total);
    let (mut rows, mut skipped) = (Vec::new(), Vec::new());
    // every grid point's scene first (in the study's order), then the runs
    // together: the formulations of one point share a matrix and step in
    // batches (`--batch`), each bit-identical to the run alone
    struct Point<'a> {
        m: &'a dyn MethodFactory,
        space: Option<SpaceChoice>,
        f: Formulation,
        at: (usize, usize, f64),
        scene: std::result::Result<(Resolved, usize), Arc<Error>>,
    }
    let mut points: Vec<Point> = Vec::new();
    for &m in &methods {
        // the method's scene, parsed once (an error is each point's reason)
        let method_scene = base_scene(text, overrides, Some(m)).map_err(Arc::new);
        for &space in &spaces {
            let modal = space.is_some_and(|s| s.is_modal());
            for &f in formulations {
                for i in 0..levels {
                    for j in 0..levels {
                        let factor = ratio.pow(i as u32);
                        let n = if modal { n0 } else { n0 * factor };
                        let dt = dt0 / r.powi(j as i32);
                        let variant = RunVariant {
                            elements: Some(n),
                            dt: Some(dt),
                            formulation: Some(f),
                            space: space.map(|s| (s, if modal { factor as f64 } else { 1.0 })),
                            support_zone: None,
                        };
                        let scene = match &method_scene {
                            Ok(scene) => variant.apply_to(scene).map_err(Arc::new),
                            Err(e) => Err(e.clone()),
                        };
                        let scene = match scene {
                            Ok(sc) => {
                                let stride = nest(
                                    (sc.steps, dt),
                                    (reference.steps, ref_dt),
                                    Reach::SameEnd,
                                )?;
                                Ok((sc, stride))
                            }
                            Err(e) => Err(e),
                        };
                        points.push(Point {
                            m,
                            space,
                            f,
                            at: (i, j, dt),
                            scene,
                        });
                    }
                }
            }
        }
    }
    let jobs: Vec<(Resolved, &dyn MethodFactory)> = points
        .iter()
        .filter_map(|p| p.scene.as_ref().ok().map(|(sc, _)| (sc.clone(), p.m)))
        .collect();
    let mut outputs = crate::run::run_many(&jobs, batch, &mut |_| {
        done += 1;
        progress(done, total);
    })
    .into_iter();
    let mut first = 0;
    for (k, p) in points.iter().enumerate() {
        let (i, j, dt) = p.at;
        let not_run = |error: Arc<Error>| NotRun {
            method: p.m.name(),
            discretization: p.space.map_or_else(String::new, |s| s.name().to_string()),
            formulation: p.f.name().to_string(),
            reason: Reason {
                at: Some((i, dt)),
                error,
            },
        };
        match &p.scene {
            Err(e) => skipped.push(not_run(e.clone())),
            Ok((sc, stride)) => match outputs.next().expect("one output per scene") {
                Ok(out) => rows.push(row(&p.m.name(), p.f, (i, j), &out, &reference, *stride, sc)),
                Err(e @ Error::Invalid { .. }) => skipped.push(not_run(Arc::new(e))),
                Err(e) => {
                    return Err(e.in_run(&format!("{}/{}", p.m.name(), p.f.name())));
                }
            },
        }
        // the last grid point of a method/discretization/formulation
        if (k + 1) % (levels * levels) == 0 {
            mark_pareto(&mut rows[first..]);
            first = rows.len();
        }
    }
    done = total;
    progress(done, total);
    Ok(Precision {
        reference: (ref_n, ref_dt),
        reference_wall: reference.wall_seconds,
        reference_method: own.name(),
        rows,
        skipped,
    })
}

fn row(
    method: &str,
    f: Formulation,
    (i, j): (usize, usize),
    out: &RunOutput,
    reference: &RunOutput,
    stride: usize,
    sc: &Resolved,
) -> PrecisionRow {
    let (t, tr) = (&out.history.carriers[0], &reference.history.carriers[0]);
    let sample = |v: &[f64]| resample(v, stride, 1..t.force.len());
    PrecisionRow {
        method: method.to_string(),
        discretization: sc.discretization.name().to_string(),
        formulation: f.name().to_string(),
        mesh_level: i,
        step_level: j,
        elements: sc.elements,
        modes: sc.discretization.modes(),
        dt: out.dt,
        dofs: out.dofs,
        steps: out.steps,
        dof_steps: out.dofs as f64 * out.steps as f64,
        wall_seconds: out.wall_seconds,
        force_error: relative_rms(&t.force[1..], &sample(&tr.force)),
        displacement_error: relative_rms(&t.w[1..], &sample(&tr.w)),
        loss_fraction_error: (out.stats[0].loss_fraction - reference.stats[0].loss_fraction).abs(),
        quantities: crate::quantity::Values::of(out, 0, crate::quantity::Offer::RUN_TABLES),
        pareto: false,
    }
}

/// Mark the points that no other point beats in both error and wall time.
fn mark_pareto(rows: &mut [PrecisionRow]) {
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.force_error, r.wall_seconds))
        .collect();
    for (k, r) in rows.iter_mut().enumerate() {
        r.pareto = !pts.iter().enumerate().any(|(m, &(e, w))| {
            m != k && e <= pts[k].0 && w <= pts[k].1 && (e < pts[k].0 || w < pts[k].1)
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(e: f64, w: f64) -> PrecisionRow {
        PrecisionRow {
            method: "m".into(),
            discretization: "hermite".into(),
            formulation: "x".into(),
            mesh_level: 0,
            step_level: 0,
            elements: 1,
            modes: None,
            dt: 1.0,
            dofs: 1,
            steps: 1,
            dof_steps: 1.0,
            wall_seconds: w,
            force_error: e,
            displacement_error: 0.0,
            loss_fraction_error: 0.0,
            quantities: Default::default(),
            pareto: false,
        }
    }

    #[test]
    fn pareto_front_keeps_the_undominated() {
        let mut rows = vec![r(1.0, 1.0), r(0.5, 2.0), r(0.8, 3.0), r(0.1, 10.0)];
        mark_pareto(&mut rows);
        let front: Vec<bool> = rows.iter().map(|x| x.pareto).collect();
        assert_eq!(front, [true, true, false, true]);
    }
}
