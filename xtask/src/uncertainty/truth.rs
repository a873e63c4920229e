//! The true values the coverage study holds each `taut uncertainty`
//! estimate against ([`super::cases::Truth`]).

use taut::analytic::RidingMassHistory;
use taut::error::Result;
use taut::resolve::{Resolved, resolve_scene};
use taut::run::run;
use taut::study::uncertainty::quantity;

use super::cases::{RIDING_MASS_MODES, Truth};

/// Sampling step of a continuous maximum's first scan, s: a tenth of the
/// ~1 ms period of the fastest modes that shape w under the carrier; the
/// maximum is then refined by golden section between the neighbours of
/// the best sample.
const SCAN_DT: f64 = 1e-4;

/// Sampling interval of the riding-mass reference, s (w between samples by
/// cubic Hermite interpolation, O(dt⁴)).
const RIDING_MASS_DT: f64 = 1e-5;

/// The largest value of `w` over [0, `t_end`]: a scan every [`SCAN_DT`],
/// then golden section.
pub fn continuous_max(w: &dyn Fn(f64) -> f64, t_end: f64) -> f64 {
    let n = (t_end / SCAN_DT).ceil() as usize;
    let at = |k: usize| (k as f64 * SCAN_DT).min(t_end);
    let k = (0..=n)
        .max_by(|&a, &b| w(at(a)).total_cmp(&w(at(b))))
        .expect("one sample");
    let (mut a, mut b) = (at(k.saturating_sub(1)), at((k + 1).min(n)));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if w(c) >= w(d) {
            b = d;
        } else {
            a = c;
        }
    }
    w(0.5 * (a + b)).max(w(at(k)))
}

/// The RMS of `w` over [0, `t_end`], sqrt((1/T)∫w² dt), by Simpson's rule
/// on [`SIMPSON_POINTS`] intervals.
pub fn continuous_rms(w: &dyn Fn(f64) -> f64, t_end: f64) -> f64 {
    let n = SIMPSON_POINTS;
    let h = t_end / n as f64;
    let f = |k: usize| w(k as f64 * h).powi(2);
    let inner: f64 = (1..n)
        .map(|k| if k % 2 == 1 { 4.0 * f(k) } else { 2.0 * f(k) })
        .sum();
    ((f(0) + inner + f(n)) * h / 3.0 / t_end).sqrt()
}

/// Simpson intervals of [`continuous_rms`] (even): 20 000 over the runs'
/// 0.4–0.6 s, 20–30 µs each, a thirtieth of the ~1 ms period of the
/// fastest modes that shape w: the rule's error is far below the finest
/// run's.
const SIMPSON_POINTS: usize = 20_000;

/// The riding-mass reference of scene `sc` (its beam, mass and speed) up
/// to its end, J = [`RIDING_MASS_MODES`].
pub fn riding_mass(sc: &Resolved) -> Result<RidingMassHistory> {
    riding_mass_with(sc, RIDING_MASS_MODES)
}

/// [`riding_mass`] with J = `modes` (the truth's own check: J/2).
pub fn riding_mass_with(sc: &Resolved, modes: usize) -> Result<RidingMassHistory> {
    let r = taut::study::reference::riding_mass_beam(sc).expect("a riding-mass scene");
    r.solve(modes, r.max_step(modes), RIDING_MASS_DT, sc.t_end)
}

/// The truth's own accuracy: its value made once more at half the
/// resolution (J/2; and 2Δt for a refined run), against the full one; 0
/// for the exact series.
pub fn truth_spread(
    truth: Truth,
    quantity_name: &str,
    sc: &Resolved,
    text: &str,
    set: &[String],
) -> Result<f64> {
    let half = match truth {
        Truth::Series => return Ok(0.0),
        Truth::RidingMass => Truth::RidingMass,
        Truth::Refined { modes, dt } => Truth::Refined {
            modes: modes / 2,
            dt: 2.0 * dt,
        },
    };
    let (full, coarse) = match truth {
        Truth::RidingMass => {
            let a = riding_mass(sc)?;
            let b = riding_mass_with(sc, RIDING_MASS_MODES / 2)?;
            (
                true_value(truth, quantity_name, sc, text, set, Some(&a))?,
                true_value(half, quantity_name, sc, text, set, Some(&b))?,
            )
        }
        _ => (
            true_value(truth, quantity_name, sc, text, set, None)?,
            true_value(half, quantity_name, sc, text, set, None)?,
        ),
    };
    Ok((full - coarse).abs())
}

/// The true value of `quantity` for the finest run `finest` of a family
/// (its end time is the one that counts), from `truth`; `rm`: the
/// riding-mass reference when the case has one (computed once).
pub fn true_value(
    truth: Truth,
    quantity_name: &str,
    finest: &Resolved,
    text: &str,
    set: &[String],
    rm: Option<&RidingMassHistory>,
) -> Result<f64> {
    // every time statistic's window is [0, T], T the scene's end time,
    // whatever the step (MODEL §7)
    let t_end = finest.t_end;
    match truth {
        Truth::Series => {
            let e = taut::study::reference::exact(finest)?.expect("a declared series");
            Ok(match quantity_name {
                "displacement_max" => continuous_max(&*e.w, t_end),
                "displacement_rms" => continuous_rms(&*e.w, t_end),
                other => panic!("no series truth for {other}"),
            })
        }
        Truth::RidingMass => {
            let h = rm.expect("the reference was solved");
            match quantity_name {
                "displacement_max" => Ok(continuous_max(&|t| h.w_at(t), t_end)),
                "displacement_rms" => Ok(continuous_rms(&|t| h.w_at(t), t_end)),
                "force_mean" => {
                    // (1/T)∫₀ᵀ λ dt by the trapezoidal rule on the samples
                    let n = ((t_end / h.dt) * (1.0 + 1e-12)).floor() as usize;
                    let f = &h.force[..=n];
                    let sum: f64 = f.windows(2).map(|p| 0.5 * (p[0] + p[1])).sum();
                    Ok(sum * h.dt / (n as f64 * h.dt))
                }
                other => panic!("no riding-mass truth for {other}"),
            }
        }
        Truth::Refined { modes, dt } => {
            let mut s: Vec<String> = set.to_vec();
            s.extend([
                "mesh.kind=galerkin".to_string(),
                format!("mesh.modes={modes}"),
                format!("time.step={dt:e}"),
                "integrator={ method = \"modal_exact\" }".to_string(),
                "reference.kind=\"richardson\"".to_string(),
            ]);
            let sc = resolve_scene(text, &s).or_else(|_| {
                // a scene without a [reference] table
                s.pop();
                resolve_scene(text, &s)
            })?;
            let out = run(&sc, &mut |_, _| {})?;
            let q = quantity::quantity(quantity_name).expect("a listed quantity");
            Ok(q.of(&out, 0).expect("defined on the refined run"))
        }
    }
}
