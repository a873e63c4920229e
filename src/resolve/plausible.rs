//! Lumped stiffnesses, masses and dashpots a model of this kind can
//! compute, relative to the scene's own scales.
//!
//! A range check "> 0" lets through values no run can use:
//! `dropper.0.stiffness = 5e-324` passed, and the run failed at step 1 with
//! a singular Delassus matrix that named no key (issue 41). Every lumped
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
//! dashpot c against S Δt (it contributes c/Δt). The window is 32 decades
//! wide around the wire's scale: the stability report's extremes (κ up to
//! 1e16 N/m, m = 1e-6 kg on the reference wire, S ≈ 1.7e7 N/m) are well
//! inside it. A value of exactly 0, where a key allows it, is no element
//! and always accepted.

use crate::error::{Error, Result};
use crate::scene::{Attachment, BeamProps, CarrierKind, CarrierProps, Dropper, Rayleigh};

/// Relative width of the window on each side of a scale: the machine
/// epsilon, below which an entry added to the step matrix's changes none
/// of its bits (module docs).
pub(crate) const PLAUSIBLE_RELATIVE: f64 = f64::EPSILON;

/// The scales of a scene's step matrix (module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scales {
    /// S = ρA h/Δt² + T/h + EI/h³, N/m.
    pub stiffness: f64,
    /// ρA h, kg.
    pub mass: f64,
    /// S Δt, N·s/m.
    pub damping: f64,
    /// Δt, s.
    pub dt: f64,
}

impl Scales {
    /// The scales of a wire with `beam`'s properties on `elements` elements
    /// at step `dt`.
    pub fn of(beam: &BeamProps, elements: usize, dt: f64) -> Self {
        let h = beam.length / elements.max(1) as f64;
        let mass = beam.rho_a * h;
        let stiffness = mass / (dt * dt) + beam.tension / h + beam.ei / (h * h * h);
        Scales {
            stiffness,
            mass,
            damping: stiffness * dt,
            dt,
        }
    }

    fn stiffness(&self, field: &str, k: f64) -> Result<()> {
        let what = format!(
            "the wire's scale S = ρA h/Δt² + T/h + EI/h³ = {:.3e} N/m",
            self.stiffness
        );
        check_window(field, k, self.stiffness, "N/m", &what)
    }

    fn mass(&self, field: &str, m: f64) -> Result<()> {
        let what = format!("the wire's element mass ρA h = {:.3e} kg", self.mass);
        check_window(field, m, self.mass, "kg", &what)
    }

    fn damping(&self, field: &str, c: f64) -> Result<()> {
        let what = format!("the wire's scale S Δt = {:.3e} N·s/m", self.damping);
        check_window(field, c, self.damping, "N·s/m", &what)
    }
}

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

/// Check one lumped quantity `value` (unit `unit`) of key `field`
/// against `scale` (`what` names the scale for the message): 0, or in
/// [ε·scale, scale/ε].
fn check_window(field: &str, value: f64, scale: f64, unit: &str, what: &str) -> Result<()> {
    if value == 0.0 || !scale.is_finite() || scale <= 0.0 {
        return Ok(());
    }
    let (low, high) = (PLAUSIBLE_RELATIVE * scale, scale / PLAUSIBLE_RELATIVE);
    if value.abs() < low {
        return Err(Error::invalid(
            field,
            value,
            format!(
                "is below ε × {what} = {low:.3e} {unit} (ε = 2.2e-16): an element that small changes no bit of the step matrix, so the run could not tell it from 0 (and a tension-only dropper that soft leaves its problem singular); give a value in [{low:.3e}, {high:.3e}] {unit}, or leave it out"
            ),
        ));
    }
    if value.abs() > high {
        return Err(Error::invalid(
            field,
            value,
            format!(
                "is above {what} / ε = {high:.3e} {unit} (ε = 2.2e-16): beside it the wire's own entries of the step matrix are lost in round-off; give a value in [{low:.3e}, {high:.3e}] {unit}"
            ),
        ));
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
