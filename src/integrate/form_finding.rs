//! Form-finding (`docs/lines.md` eq. F1–F5): the dropper lengths that put
//! the contact wire at its design heights in the line's exact static
//! equilibrium — both wires with their EI, every dropper's spring (a
//! tension-only one taken taut), the attachments (steady arms), the
//! self-weight — the equilibrium `[time] initial = "static"` starts from,
//! without the carriers (the line is designed unloaded).
//!
//! A dropper's length ℓ_d enters the model only through its preload
//! k_d (H_d − ℓ_d) r_d (H_d the anchor height z_a, or h_m on the
//! messenger; D2, W4), so the line at rest
//!
//! ```text
//!   (F1) K d = f₀ + Σ_d k_d (H_d − ℓ_d) r_d
//! ```
//!
//! (K and f₀ the run's stiffness and constant load without the preloads)
//! is **affine in the lengths**, and so is the contact wire's height at each
//! dropper with a design height V_i (`design_height`), i ∈ D:
//!
//! ```text
//!   (F2) ρ_i = V_i − r_c(x_i)ᵀ d(ℓ)
//!   (F3) J_ij = ∂ r_c(x_i)ᵀd / ∂ℓ_j = −k_j r_c(x_i)ᵀ K⁻¹ r_j      (i, j ∈ D)
//!   (F4) J Δℓ = ρ,   ℓ ← ℓ + Δℓ,   until max_i |ρ_i| ≤ ε_F
//! ```
//!
//! One Newton step (F4) is exact in exact arithmetic; the ones after it take
//! up round-off. J costs one banded solve per design dropper with the
//! factored K (|D| ≪ unknowns) and one dense |D| × |D| LU, once. Each
//! step rebuilds the load from f₀ and the new preloads exactly as a run
//! does from given lengths, so a scene carrying the found lengths (`taut
//! line expand`'s text) starts its correction loop already within ε_F,
//! takes no step and runs the same bytes. Accepted only when
//!
//! ```text
//!   (F5) ℓ_d > 0 and, for a tension-only dropper, N_d = k_d (H_d − ℓ_d − r_dᵀd) > 0
//! ```
//!
//! (a design that needs a dropper to push, or of no length, is not
//! reachable: refused naming the dropper's `design_height`).

use crate::error::{Error, Result};
use crate::model::banded::BandedLdlt;
use crate::resolve::Resolved;

use super::physics::Physics;

/// ε_F, m: the largest |v_c(x_d) − V_d| form-finding accepts. A thousandth
/// of a millimetre: three orders below the millimetre to which contact
/// wires are built and their heights measured, and well above the static
/// solve's round-off (the found heights of the bundled
/// `catenary_designed.toml` are within 1e-12 m of the design,
/// `docs/lines.md` "Form-finding").
pub const FORM_TOLERANCE: f64 = 1e-6;

/// Most Newton steps (F4). The problem is affine, so the first step lands
/// within round-off; more than this means J is near-singular (two design
/// points that cannot move apart), reported as not reachable.
const MAX_STEPS: usize = 4;

/// One dropper of the line at rest after form-finding.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticDropper {
    /// ℓ_0, the length the run uses, m (found, or as given).
    pub length: f64,
    /// N_d at rest, N (k_d e_d, tension positive; every dropper taut).
    pub force: f64,
    /// The contact wire's height v_c(x_d) at rest, m (v up).
    pub height: f64,
    /// The design height V_d, m (`None`: the length was given, not found).
    pub design: Option<f64>,
}

/// The line at rest after form-finding (eq. F1–F5), for the outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct FormFound {
    /// Every dropper, in scene order.
    pub droppers: Vec<StaticDropper>,
    /// max |v_c(x_d) − V_d| over the design droppers with the lengths as
    /// given (before any step), m.
    pub start_error: f64,
    /// The same after form-finding, m (≤ [`FORM_TOLERANCE`]).
    pub error: f64,
    /// Newton steps taken (0: the given lengths already met the design).
    pub steps: usize,
}

/// Form-find the lengths of `sc`'s droppers with a design height (module
/// docs) in `physics` (built from `sc`, its load holding the given
/// lengths' preloads): their e₀ and the load are set to the found lengths.
/// `None` (and nothing done) without a design height.
pub(crate) fn form_find(sc: &Resolved, physics: &mut Physics) -> Result<Option<FormFound>> {
    let design: Vec<(usize, f64)> = sc
        .droppers
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.design_height.map(|v| (i, v)))
        .collect();
    if design.is_empty() {
        return Ok(None);
    }
    let field = |i: usize| {
        sc.scene
            .generated
            .user_path(&format!("dropper.{i}.design_height"))
    };
    let beam = &physics.beam;
    let n = beam.n;
    let factor = BandedLdlt::factor(&beam.stiffness).map_err(|_| {
        Error::invalid(
            field(design[0].0),
            design[0].1,
            "needs a line held against rigid motion (K positive definite) to form-find: the supports, attachments and droppers leave it free",
        )
    })?;
    // f₀: the load without the droppers' preloads (F1)
    let Some(base) = physics.free_load.take() else {
        return Ok(None);
    };
    let points: Vec<_> = design.iter().map(|&(i, _)| beam.point_vector(sc.droppers[i].x)).collect();
    let heights = |d: &[f64]| -> Vec<f64> { points.iter().map(|p| p.dot(d)).collect() };
    let at_rest = |load: &[f64]| -> Vec<f64> {
        let mut d = load.to_vec();
        factor.solve(&mut d);
        d
    };
    let residual = |d: &[f64]| -> (Vec<f64>, f64) {
        let r: Vec<f64> = heights(d)
            .iter()
            .zip(&design)
            .map(|(h, &(_, v))| v - h)
            .collect();
        let worst = r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        (r, worst)
    };
    let mut d = at_rest(&beam.load);
    let (mut rho, start_error) = residual(&d);
    let mut error = start_error;
    let mut lengths: Vec<f64> = sc.droppers.iter().map(|d| d.length).collect();
    let mut steps = 0;
    if !(error <= FORM_TOLERANCE) {
        // J (F3): one solve per design dropper
        let m = design.len();
        let mut jac = nalgebra::DMatrix::<f64>::zeros(m, m);
        let mut z = vec![0.0; n];
        for (j, &(dj, _)) in design.iter().enumerate() {
            z.fill(0.0);
            physics.droppers.scatter_direction(dj, 1.0, &mut z);
            factor.solve(&mut z);
            let k = physics.droppers.stiffness(dj);
            for (i, p) in points.iter().enumerate() {
                jac[(i, j)] = -k * p.dot(&z);
            }
        }
        let lu = jac.lu();
        while !(error <= FORM_TOLERANCE) {
            if steps == MAX_STEPS {
                let (i, v) = design[worst_index(&rho)];
                return Err(Error::invalid(
                    field(i),
                    v,
                    format!(
                        "is not reachable: after {MAX_STEPS} Newton steps of form-finding the contact wire at dropper {:?} (x = {} m) is still {error:.3e} m from the design (tolerance {FORM_TOLERANCE:e} m): two design points the line cannot set apart",
                        sc.droppers[i].name, sc.droppers[i].x
                    ),
                ));
            }
            let step = lu
                .solve(&nalgebra::DVector::from_column_slice(&rho))
                .filter(|s| s.iter().all(|x| x.is_finite()))
                .ok_or_else(|| {
                    Error::invalid(
                        field(design[0].0),
                        design[0].1,
                        "cannot be form-found: the design heights' response to the dropper lengths is singular (a dropper at a support, or two at one point)",
                    )
                })?;
            for (&(i, v), dl) in design.iter().zip(step.iter()) {
                let l = lengths[i] + dl;
                if !(l > 0.0) {
                    return Err(Error::invalid(
                        field(i),
                        v,
                        format!(
                            "is not reachable: dropper {:?} (x = {} m) would need a length of {l:.4} m (must be > 0): the wire cannot hang that high below its anchor; lower the design height or raise the anchor",
                            sc.droppers[i].name, sc.droppers[i].x
                        ),
                    ));
                }
                lengths[i] = l;
                let mut found = sc.droppers[i].clone();
                found.length = l;
                physics.droppers.set_rest_extension(i, found.rest_extension());
            }
            // the load as a run from these lengths builds it (Physics::new)
            physics.beam.load.copy_from_slice(&base);
            physics.droppers.add_preloads(&mut physics.beam.load);
            d = at_rest(&physics.beam.load);
            (rho, error) = residual(&d);
            steps += 1;
        }
    }
    let mut droppers = Vec::with_capacity(sc.droppers.len());
    let mut k = 0;
    for (i, dr) in sc.droppers.iter().enumerate() {
        let force = physics.droppers.taut_force(i, &d);
        let wanted = design.get(k).filter(|&&(j, _)| j == i).map(|&(_, v)| v);
        if wanted.is_some() {
            k += 1;
            if !dr.linear && !(force > 0.0) {
                return Err(Error::invalid(
                    field(i),
                    wanted.unwrap_or(f64::NAN),
                    format!(
                        "is not reachable: dropper {:?} (x = {} m) would have to push ({force:.4} N at rest) to hold the wire there: the design needs a strut, not a tension-only dropper (lower the pre-sag, or make the dropper linear)",
                        dr.name, dr.x
                    ),
                ));
            }
        }
        droppers.push(StaticDropper {
            length: lengths[i],
            force,
            height: beam_height(physics, dr.x, &d),
            design: wanted,
        });
    }
    Ok(Some(FormFound {
        droppers,
        start_error,
        error,
        steps,
    }))
}

/// v_c(x) at `d`, m.
fn beam_height(physics: &Physics, x: f64, d: &[f64]) -> f64 {
    physics.beam.point_vector(x).dot(d)
}

/// The index of the largest |ρ_i|.
fn worst_index(rho: &[f64]) -> usize {
    rho.iter()
        .enumerate()
        .fold((0, -1.0f64), |(bi, bv), (i, r)| {
            if r.abs() > bv { (i, r.abs()) } else { (bi, bv) }
        })
        .0
}
