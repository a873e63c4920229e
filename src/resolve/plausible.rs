//! Lumped stiffnesses, masses and dashpots a model of this kind can
//! compute, relative to the scene's own scales.
//!
//! A range check "> 0" lets through values no run can use:
//! `dropper.0.stiffness = 5e-324` passed, and the run failed at step 1 with
//! a singular Delassus matrix that named no key. Every lumped
//! element enters the step matrix beside the wire's own entries, whose
//! scale is that of one element at the run's step,
//!
//! ```text
//!   S = ρA h/Δt² + T/h + EI/h³     (N/m; h = L/N)
//! ```
//!
//! (the mass term is M/(βΔt²) up to the method's constant, the others the
//! element stiffness of MODEL §4). In floating point a spring k with
//! k < ε S changes no entry of that matrix (ε = 2.2e-16, the machine
//! epsilon): the run cannot tell it from 0, and a tension-only dropper that
//! weak makes the droppers' problem singular (its compliance 1/k
//! overflows the rest). A spring with k > S/ε swamps the wire: its own
//! stiffness is lost in the round-off of that entry. So a non-zero
//! stiffness must lie in [ε S, S/ε]; a mass likewise against the element's
//! mass ρA h (a mass m contributes m/Δt² to the same entries), and a
//! dashpot c against S Δt (it contributes c/Δt): a window 32 decades wide
//! around the wire's scale. A value of exactly 0, where a key allows it, is
//! no element and always accepted.
//!
//! The messenger's own elements are held to the messenger's scales. A
//! pantograph's uplift F₀ + c_a V² is a load, not a matrix entry: only its
//! top is bounded, by the force S h / ε that would move one element by h/ε,
//! at the carrier's top speed.

pub(crate) use crate::scene::scales::{PLAUSIBLE_RELATIVE, Scales, check_window};

use crate::error::{Error, Result};
use crate::scene::{
    Attachment, CarrierKind, CarrierProps, Dropper, Messenger, Rayleigh, SpeedProfile,
};

/// Check every lumped stiffness, mass and dashpot of a scene against its
/// scales (module docs): the carriers' (a pantograph's every mass, spring
/// and dashpot), the attachments', the droppers', the penalty stiffness
/// and the Rayleigh coefficients (α Δt and β/Δt are the shares of M and K
/// they add).
pub(crate) fn check_plausible(
    scales: &Scales,
    carriers: &[CarrierProps],
    own: &[usize],
    attachments: &[Attachment],
    droppers: &[Dropper],
    penalty: Option<f64>,
    rayleigh: Rayleigh,
) -> Result<()> {
    for (i, c) in carriers.iter().enumerate() {
        let key = |k: &str| format!("carrier.{i}.{k}");
        if let Some(chain) = &c.chain {
            for j in 0..chain.n {
                scales.mass(&format!("{}.{j}", key("masses")), chain.masses[j])?;
                scales.stiffness(&format!("{}.{j}", key("stiffnesses")), chain.stiffnesses[j])?;
                scales.damping(&format!("{}.{j}", key("dampings")), chain.dampings[j])?;
            }
        } else if let CarrierKind::MassSpring {
            mass,
            stiffness,
            damping,
            ..
        } = c.kind
        {
            scales.mass(&key("mass"), mass)?;
            scales.stiffness(&key("stiffness"), stiffness)?;
            scales.damping(&key("damping"), damping)?;
        }
    }
    for (&i, a) in own.iter().zip(attachments) {
        scales.stiffness(&format!("attachment.{i}.stiffness"), a.stiffness)?;
        scales.mass(&format!("attachment.{i}.mass"), a.mass)?;
        scales.damping(&format!("attachment.{i}.damping"), a.damping)?;
    }
    for (i, d) in droppers.iter().enumerate() {
        scales.stiffness(&format!("dropper.{i}.stiffness"), d.stiffness)?;
        scales.damping(&format!("dropper.{i}.damping"), d.damping)?;
    }
    if let Some(k) = penalty {
        scales.stiffness("contact.penalty.stiffness", k)?;
    }
    // C = αM + βK enters the step matrix as ~Δt C beside M and Δt² K:
    // αM is α Δt of M, βK is β/Δt of Δt² K
    let dt = scales.dt;
    check_window(
        "beam.damping.mass",
        rayleigh.alpha,
        1.0 / dt,
        "1/s",
        &format!("1/Δt = {:.3e} 1/s (αM beside the step's M/Δt)", 1.0 / dt),
    )?;
    check_window(
        "beam.damping.stiffness",
        rayleigh.beta,
        dt,
        "s",
        &format!("Δt = {dt:.3e} s (βK beside the step's K Δt)"),
    )
}

/// Check the messenger's own lumped elements against its scales (module
/// docs): its elastic supports (`messenger.support`, one table for every
/// support when `one_table`, else a list) and the scene's attachments on it
/// (`on_messenger`: their indices in `[[attachment]]`, in order).
pub(crate) fn check_messenger(
    m: &Messenger,
    one_table: bool,
    on_messenger: &[usize],
    length: f64,
    elements: usize,
    dt: f64,
) -> Result<()> {
    let scales =
        Scales::wire(length, (m.rho_a, m.tension, m.ei), elements, dt).named("the messenger's");
    for (i, e) in m.elastic.iter().enumerate() {
        let Some(e) = e else { continue };
        let key = |k: &str| {
            if one_table {
                format!("messenger.support.{k}")
            } else {
                format!("messenger.support.{i}.{k}")
            }
        };
        scales.stiffness(&key("stiffness"), e.stiffness)?;
        scales.mass(&key("mass"), e.mass)?;
        scales.damping(&key("damping"), e.damping)?;
    }
    let supports = m.elastic.iter().filter(|e| e.is_some()).count();
    let own = m.attachments.get(supports..).unwrap_or(&[]);
    for (&i, a) in on_messenger.iter().zip(own) {
        scales.stiffness(&format!("attachment.{i}.stiffness"), a.stiffness)?;
        scales.mass(&format!("attachment.{i}.mass"), a.mass)?;
        scales.damping(&format!("attachment.{i}.damping"), a.damping)?;
    }
    Ok(())
}

/// Speeds sampled over a run to find a carrier's top speed for
/// [`check_uplift`] (a table's knots are taken as well): the bound it
/// checks is sixteen decades wide, so a sampled top is close enough.
const SPEED_SAMPLES: usize = 64;

/// Check each pantograph's uplift F₀ + c_a V², at the carrier's top speed
/// over `t_end`, against the wire's force scale (module docs).
pub(crate) fn check_uplift(scales: &Scales, carriers: &[CarrierProps], t_end: f64) -> Result<()> {
    let high = scales.force / PLAUSIBLE_RELATIVE;
    for (i, c) in carriers.iter().enumerate() {
        let Some(chain) = &c.chain else { continue };
        let mut v_max = (0..=SPEED_SAMPLES)
            .map(|k| {
                c.motion
                    .speed(t_end * k as f64 / SPEED_SAMPLES as f64)
                    .abs()
            })
            .fold(0.0_f64, f64::max);
        if let SpeedProfile::Table { speed, .. } = &c.motion.profile {
            v_max = speed.iter().fold(v_max, |a, v| a.max(v.abs()));
        }
        let force = chain.uplift_coefficient * v_max * v_max;
        let why = |what: &str| {
            format!(
                "{what} is above the wire's force scale S h / ε = {high:.3e} N (S h = {:.3e} N, the force that moves one element by its length; ε = 2.2e-16): the wire's response to it would be round-off; give a value that keeps it below",
                scales.force
            )
        };
        if chain.uplift.is_nan() || chain.uplift.abs() > high {
            return Err(Error::invalid(
                format!("carrier.{i}.uplift"),
                chain.uplift,
                why("the uplift F₀"),
            ));
        }
        if force.is_nan() || force.abs() > high {
            return Err(Error::invalid(
                format!("carrier.{i}.uplift_coefficient"),
                chain.uplift_coefficient,
                why(&format!(
                    "the aerodynamic uplift c_a V² at the run's top speed V = {v_max:.4} m/s ({force:.3e} N)"
                )),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_window_is_epsilon_either_side_of_the_scale() {
        let s = Scales {
            stiffness: 1e7,
            mass: 0.2,
            damping: 1e3,
            dt: 1e-4,
            force: 1e6,
            whose: "the wire's",
        };
        assert!(s.stiffness("k", 0.0).is_ok());
        assert!(s.stiffness("k", 1e-8).is_ok());
        assert!(s.stiffness("k", 1e16).is_ok());
        let e = s
            .stiffness("dropper.0.stiffness", 5e-324)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`dropper.0.stiffness` = 5e-324") && e.contains("could not tell it from 0"),
            "{e}"
        );
        let e = s.stiffness("k", 1e300).unwrap_err().to_string();
        assert!(e.contains("lost in round-off"), "{e}");
        assert!(s.mass("m", 1e-6).is_ok() && s.mass("m", 1e-30).is_err());
        assert!(s.damping("c", 1e-20).is_err() && s.damping("c", 50.0).is_ok());
    }
}
