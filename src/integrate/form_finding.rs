//! Form-finding (`docs/lines.md` eq. F1–F5): the dropper lengths that put
//! the contact wire at its design heights in the line's exact static
//! equilibrium (both wires, droppers taken taut, attachments, self-weight,
//! no carriers) that `[time] initial = "static"` starts from.
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
//! One Newton step (F4) is exact in exact arithmetic, the ones after it take
//! up round-off; J costs one banded solve per design dropper with the
//! factored K and one dense LU. Each step rebuilds the load exactly as a run
//! does, so a scene carrying the found lengths (`taut line expand`) takes no
//! step and runs the same bytes. Accepted only when (F5) ℓ_d > 0 and, for a
//! tension-only dropper, N_d = k_d (H_d − ℓ_d − r_dᵀd) > 0; otherwise
//! refused naming the dropper's `design_height`.

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

/// Most droppers with a design height in one scene: J (F3) is dense,
/// |D|² numbers formed by |D| banded solves, and factored by a dense LU
/// (|D|³): 2000 droppers (222 spans of 9) is 32 MB and 5e9 operations
/// for the LU. Beyond it the scene is refused, naming the count.
pub const MAX_FORM_DROPPERS: usize = 2000;

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
    if design.len() > MAX_FORM_DROPPERS {
        let (i, v) = design[MAX_FORM_DROPPERS];
        let (field, value) = if sc.scene.generated.line {
            ("line.form_finding".to_string(), "true".to_string())
        } else {
            (format!("dropper.{i}.design_height"), v.to_string())
        };
        return Err(Error::invalid(
            field,
            value,
            format!(
                "is one of {} droppers with a design height: form-finding takes at most {MAX_FORM_DROPPERS} (its Jacobian is dense, |D|² numbers): form-find a shorter line, or give the lengths",
                design.len()
            ),
        ));
    }
    let field = |i: usize| {
        sc.scene
            .generated
            .user_path(&format!("dropper.{i}.design_height"))
    };
    // the value an error shows: the design height, and for a generated
    // dropper (named by `line.presag`, which set it) which one
    let value = |i: usize, v: f64| {
        if sc.scene.generated.line {
            format!("{v} m, the design height of {:?}", sc.droppers[i].name)
        } else {
            v.to_string()
        }
    };
    let beam = &physics.beam;
    let n = beam.n;
    let factor = BandedLdlt::factor(&beam.stiffness).map_err(|_| {
        Error::invalid(
            field(design[0].0),
            value(design[0].0, design[0].1),
            "needs a line held against rigid motion (K positive definite) to form-find: the supports, attachments and droppers leave it free",
        )
    })?;
    // f₀: the load without the droppers' preloads (F1)
    let Some(base) = physics.free_load.take() else {
        return Ok(None);
    };
    let points: Vec<_> = design
        .iter()
        .map(|&(i, _)| beam.point_vector(sc.droppers[i].x))
        .collect();
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
    if !met(error) {
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
        while !met(error) {
            if steps == MAX_STEPS {
                let (i, v) = design[worst_index(&rho)];
                return Err(Error::invalid(
                    field(i),
                    value(i, v),
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
                        value(design[0].0, design[0].1),
                        "cannot be form-found: the design heights' response to the dropper lengths is singular, or its Newton step not finite (a dropper at a support, two at one point, or a design the droppers cannot reach)",
                    )
                })?;
            for (&(i, v), dl) in design.iter().zip(step.iter()) {
                let l = lengths[i] + dl;
                if l.is_nan() || l <= 0.0 {
                    return Err(Error::invalid(
                        field(i),
                        value(i, v),
                        format!(
                            "is not reachable: dropper {:?} (x = {} m) would need a length of {l:.4} m (must be > 0): the wire cannot hang that high below its anchor; lower the design height or raise the anchor",
                            sc.droppers[i].name, sc.droppers[i].x
                        ),
                    ));
                }
                lengths[i] = l;
                let mut found = sc.droppers[i].clone();
                found.length = l;
                physics
                    .droppers
                    .set_rest_extension(i, found.rest_extension());
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
            if !dr.linear && (force.is_nan() || force <= 0.0) {
                return Err(Error::invalid(
                    field(i),
                    value(i, wanted.unwrap_or(f64::NAN)),
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

/// True when the heights meet the design: max |ρ| ≤ ε_F (false for NaN).
fn met(error: f64) -> bool {
    error <= FORM_TOLERANCE
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::System;
    use crate::resolve::resolve_scene;

    /// String elements are nodally exact for a string under a uniform load
    /// held at nodes: the found lengths and the hand's agree to the static
    /// solve's round-off (relative to the O(1) m lengths).
    const NODAL: f64 = 1e-12;

    /// A 10 m string (T = 1000 N, ρA = 1 kg/m, g = 10: w = 10 N/m) on 40
    /// linear elements, three tension-only droppers (k_d = 1e4 N/m) to fixed
    /// anchors at z_a = 1 m, at x = 2.5, 5, 7.5 m, with design heights
    /// `heights` (m).
    fn string_scene(heights: [f64; 3], extra: &str) -> String {
        let droppers: String = [2.5, 5.0, 7.5]
            .iter()
            .zip(heights)
            .map(|(x, v)| {
                format!(
                    "[[dropper]]\nx = {x}\nstiffness = 1.0e4\nanchor_height = 1.0\nlength = 1.0\ndesign_height = {v:e}\n{extra}\n"
                )
            })
            .collect();
        format!(
            r#"
[beam]
length = 10.0
mass_per_length = 1.0
bending_stiffness = 0.0
tension = 1000.0
left = "pinned"
right = "pinned"

[mesh]
elements = 40

[[carrier]]
force = 10.0
side = "below"
start = 0.0
speed = {{ profile = "constant", value = 0.0 }}

[time]
step = 1e-3
end = 0.002
initial = "static"

[gravity]
g = 10.0
beam_self_weight = true

{droppers}
"#
        )
    }

    fn found(text: &str) -> Result<FormFound> {
        let sc = resolve_scene(text, &[])?;
        let sys = System::new(&sc)?;
        Ok(sys.form_found().expect("design heights").clone())
    }

    #[test]
    fn a_string_held_at_design_heights_has_the_lengths_of_its_statics() {
        // By hand (G3 on the string held at the design points): chord
        // slopes −0.004, −0.004, 0.006, 0.002 on the four 2.5 m segments,
        // each segment's weight 25 N shared by its ends, so
        //   N₁ = (T s₀ + 12.5) + (−T s₁ + 12.5) = 8.5 + 16.5 = 25 N,
        //   N₂ = 8.5 + 6.5 = 15 N,  N₃ = 18.5 + 10.5 = 29 N,
        // and ℓ = z_a − V − N/k_d (the anchors are rigid).
        let v = [-0.01, -0.02, -0.005];
        let n = [25.0, 15.0, 29.0];
        let f = found(&string_scene(v, "")).unwrap();
        assert_eq!(f.steps, 1, "an affine problem: one Newton step");
        assert!(f.error <= NODAL, "{}", f.error);
        assert!(f.start_error > 1e-3, "the given lengths were off");
        for ((d, v), n) in f.droppers.iter().zip(v).zip(n) {
            let l = 1.0 - v - n / 1.0e4;
            assert!((d.length - l).abs() <= NODAL, "{d:?} against ℓ = {l}");
            assert!(
                (d.force - n).abs() <= NODAL * n * 1e3,
                "{d:?} against N = {n}"
            );
            assert!((d.height - v).abs() <= NODAL, "{d:?}");
        }
        // linear droppers: the same statics, the same lengths
        let g = found(&string_scene(v, "linear = true")).unwrap();
        for (a, b) in f.droppers.iter().zip(&g.droppers) {
            assert!((a.length - b.length).abs() <= NODAL);
        }
    }

    #[test]
    fn the_found_lengths_given_back_take_no_step_and_build_the_same_line() {
        let v = [-0.01, -0.02, -0.005];
        let text = string_scene(v, "");
        let f = found(&text).unwrap();
        let mut again = text.clone();
        for d in &f.droppers {
            again = again.replacen(
                "\nlength = 1.0\n",
                &format!("\nlength = {:?}\n", d.length),
                1,
            );
        }
        let g = found(&again).unwrap();
        assert_eq!(g.steps, 0, "{again}");
        assert_eq!(g.droppers, f.droppers, "the same bits");
        let (a, b) = (
            resolve_scene(&text, &[]).unwrap(),
            resolve_scene(&again, &[]).unwrap(),
        );
        let (a, b) = (System::new(&a).unwrap(), System::new(&b).unwrap());
        assert_eq!(a.beam().load, b.beam().load, "the same load, bit for bit");
    }

    #[test]
    fn an_unreachable_design_is_refused_naming_the_dropper() {
        // above its anchor: no length reaches it
        let e = found(&string_scene([-0.01, 1.5, -0.005], ""))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("dropper.1.design_height") && e.contains("1.5") && e.contains("> 0"),
            "{e}"
        );
        // far below the others: the middle dropper would have to push
        let e = found(&string_scene([-0.01, -0.5, -0.005], ""))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("dropper.1.design_height") && e.contains("push"),
            "{e}"
        );
        // a linear dropper may push: the same design is reached
        let f = found(&string_scene([-0.01, -0.5, -0.005], "linear = true")).unwrap();
        assert!(f.droppers[1].force < 0.0 && f.error <= FORM_TOLERANCE);
    }
}
