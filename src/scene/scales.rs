//! The scales a lumped stiffness, mass or dashpot is held to: those of the
//! step matrix of a wire (`crate::resolve::plausible`'s module docs give
//! the reasoning). Here, below the resolve layer, so that `[line]`'s
//! expansion checks the keys a user wrote against the same window before
//! it designs the line with them.

use super::BeamProps;
use crate::error::{Error, Result};

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
    /// S h, N: the force that moves one element by its length h.
    pub force: f64,
    /// Whose scales, for a message: "the wire's", "the messenger's".
    pub whose: &'static str,
}

impl Scales {
    /// The scales of a wire with `beam`'s properties on `elements` elements
    /// at step `dt`.
    pub fn of(beam: &BeamProps, elements: usize, dt: f64) -> Self {
        Self::wire(
            beam.length,
            (beam.rho_a, beam.tension, beam.ei),
            elements,
            dt,
        )
        .named("the wire's")
    }

    /// The scales of a wire of length `length` with (ρA, T, EI) on
    /// `elements` elements at step `dt`.
    pub fn wire(
        length: f64,
        (rho_a, tension, ei): (f64, f64, f64),
        elements: usize,
        dt: f64,
    ) -> Self {
        let h = length / elements.max(1) as f64;
        let mass = rho_a * h;
        let stiffness = mass / (dt * dt) + tension / h + ei / (h * h * h);
        Scales {
            stiffness,
            mass,
            damping: stiffness * dt,
            dt,
            force: stiffness * h,
            whose: "the wire's",
        }
    }

    /// These scales, said to be `whose` in messages.
    pub fn named(self, whose: &'static str) -> Self {
        Scales { whose, ..self }
    }

    pub(crate) fn stiffness(&self, field: &str, k: f64) -> Result<()> {
        let what = format!(
            "{} scale S = ρA h/Δt² + T/h + EI/h³ = {:.3e} N/m",
            self.whose, self.stiffness
        );
        check_window(field, k, self.stiffness, "N/m", &what)
    }

    pub(crate) fn mass(&self, field: &str, m: f64) -> Result<()> {
        let what = format!("{} element mass ρA h = {:.3e} kg", self.whose, self.mass);
        check_window(field, m, self.mass, "kg", &what)
    }

    pub(crate) fn damping(&self, field: &str, c: f64) -> Result<()> {
        let what = format!("{} scale S Δt = {:.3e} N·s/m", self.whose, self.damping);
        check_window(field, c, self.damping, "N·s/m", &what)
    }
}

/// Check one lumped quantity `value` (unit `unit`) of key `field`
/// against `scale` (`what` names the scale for the message): 0, or in
/// [ε·scale, scale/ε].
pub(crate) fn check_window(
    field: &str,
    value: f64,
    scale: f64,
    unit: &str,
    what: &str,
) -> Result<()> {
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
