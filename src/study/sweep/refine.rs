//! `--check-refinement`: a sweep point run again refined (N × 2, Δt / 2)
//! and whether its P_l is converged.

use serde::{Deserialize, Serialize};
use toml::Table;

use super::nan_as_null;
use super::spec::SweepSpec;
use crate::error::Error;
use crate::run::run;
/// A sweep point run again refined (`--check-refinement`): twice the
/// elements (modes on a modal basis), half the step.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Refined {
    /// Elements of the refined run.
    pub elements: usize,
    /// Its modes J, on a `galerkin` or `modal` basis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Its time step, s.
    pub dt: f64,
    /// Its P_l (null when it stopped).
    #[serde(with = "nan_as_null")]
    pub loss_fraction: f64,
    /// Its in-span P_l (null when it stopped).
    #[serde(with = "nan_as_null")]
    pub loss_fraction_span: f64,
    /// Why it stopped, if it did.
    pub error: Option<String>,
}

/// An error of the refined run's scene, named by the flag that made it
/// (`--check-refinement`): the doubled value is not one the user gave, so
/// naming only its key (`mesh.elements` = 2000002) sent them looking for it.
pub fn in_refined_run(e: Error) -> Error {
    const WHY: &str = "the refined run of --check-refinement (twice mesh.elements, twice mesh.modes on a modal or galerkin basis, half time.step)";
    const FIX: &str = "refine a coarser scene, or leave out --check-refinement";
    match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::invalid(
            "--check-refinement",
            format!("`{field}` = {value} in {WHY}"),
            format!("{allowed}; {FIX}"),
        ),
        other => other.explained(&format!(" (in {WHY}: {FIX})")),
    }
}

/// Whether a P_l is converged under one refinement: the change is at most
/// [`REFINEMENT_REL`] of the refined value or [`REFINEMENT_ABS`] (None when
/// either run stopped).
pub(crate) fn refinement_converged(base: f64, refined: f64) -> Option<bool> {
    let d = (refined - base).abs();
    d.is_finite()
        .then(|| d <= (REFINEMENT_REL * refined.abs()).max(REFINEMENT_ABS))
}

/// Relative change of P_l under one refinement (N × 2, Δt / 2) taken as
/// converged: the in-span P_l of the reference case changes by 0.02–4 %
/// between its finest levels (`docs/contact_loss.md`), a non-converged one
/// by tens of per cent.
pub(crate) const REFINEMENT_REL: f64 = 0.05;

/// Absolute change of P_l taken as converged whatever its size: 5e-4 is
/// three steps of loss in the reference run's 6000, below what a loss map
/// resolves.
pub(crate) const REFINEMENT_ABS: f64 = 5e-4;

/// Run point `index` refined (`base`: the spec's [`SweepSpec::base_tree`],
/// when made), with the run's unknowns × steps (0 when it did not start).
pub(super) fn refined(spec: &SweepSpec, base: Option<&Table>, index: usize) -> (Refined, f64) {
    let stopped = |elements, modes, dt, e: Error| Refined {
        elements,
        modes,
        dt,
        loss_fraction: f64::NAN,
        loss_fraction_span: f64::NAN,
        error: Some(e.to_string()),
    };
    let sc = match spec.resolve_refined_with(base, index) {
        Ok(sc) => sc,
        Err(e) => return (stopped(0, None, f64::NAN, e), 0.0),
    };
    let modes = sc.discretization.modes();
    match run(&sc, &mut |_, _| {}) {
        Ok(o) => (
            Refined {
                elements: sc.elements,
                modes,
                dt: sc.dt,
                loss_fraction: o.stats[0].loss_fraction,
                loss_fraction_span: o.stats[0].loss_fraction_span,
                error: None,
            },
            o.dofs as f64 * o.steps as f64,
        ),
        // a run that stopped: its work up to the stop is not reported
        Err(e) => (stopped(sc.elements, modes, sc.dt, e), 0.0),
    }
}
