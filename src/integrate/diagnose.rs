//! Divergence diagnosis: a run whose recorded values leave their sane range
//! stops with the step, the time, the quantity and a likely cause, whatever
//! the method. The method's own cause (an undamped constraint mode of a
//! generalized-α member) comes from the method
//! ([`super::MethodFactory::constraint_note`]).

use crate::error::{Error, Result};
use crate::scene::{Placement, Support};

use super::sample::CarrierSample;
use super::state::State;
use super::system::System;

/// Displacements beyond this many beam lengths are not a small-deflection
/// answer: a linear model that gets there has blown up.
const DISPLACEMENT_BOUND_IN_LENGTHS: f64 = 1.0;

/// True when x lies in the last element before a supported end (v = 0
/// there): a carrier arriving at a support meets the beam's support corner,
/// an impact the model has no law for (MODEL §6).
#[inline]
pub(crate) fn near_support(sys: &System, x: f64) -> bool {
    let h = sys.physics.beam.h;
    let held = |s: Support| s != Support::Free;
    (held(sys.physics.supports.0) && x < h)
        || (held(sys.physics.supports.1) && x > sys.physics.length - h)
}

/// Stop with a diagnosis if a recorded value is non-finite or absurd.
///
/// The force bound is not applied in the last element before a support:
/// there a mass that arrives with the beam under it still deflected is
/// forced to w = 0 within one element, a genuine (refinement-dependent)
/// impact of the model; `run` reports it as a warning instead. `note` is
/// the method's likely cause with a moving contact, if it has one.
pub(crate) fn check(
    sys: &System,
    st: &State,
    s: &CarrierSample,
    carrier: usize,
    note: Option<&str>,
) -> Result<()> {
    check_near(sys, st, s, carrier, note, near_support(sys, s.x))
}

/// [`check`] with `near` = [`near_support`] at `s.x` already known (a
/// recorder takes it once a step for both). The sane values, every step's
/// case, pass without building the diagnosis; [`diagnose`] builds it.
#[inline]
pub(crate) fn check_near(
    sys: &System,
    st: &State,
    s: &CarrierSample,
    carrier: usize,
    note: Option<&str>,
    near: bool,
) -> Result<()> {
    let bound = DISPLACEMENT_BOUND_IN_LENGTHS * sys.physics.length;
    let force_limit = if near {
        f64::INFINITY
    } else {
        sys.law.force_bound
    };
    let sane = |value: f64, limit: f64| value.is_finite() && value.abs() <= limit;
    if sane(s.force, force_limit) && sane(s.w, bound) && sane(s.q, bound) {
        return Ok(());
    }
    diagnose(sys, st, s, carrier, note, bound, force_limit)
}

/// The diagnosis of a sample [`check_near`] found absurd: the first value
/// out of its range (force, w, q) with its likely cause.
#[cold]
#[inline(never)]
fn diagnose(
    sys: &System,
    st: &State,
    s: &CarrierSample,
    carrier: usize,
    note: Option<&str>,
    bound: f64,
    force_limit: f64,
) -> Result<()> {
    let checks = [
        ("contact force λ (N)", s.force, force_limit),
        ("beam displacement under the carrier w (m)", s.w, bound),
        ("mass displacement q (m)", s.q, bound),
    ];
    for (name, value, limit) in checks {
        if value.is_finite() && value.abs() <= limit {
            continue;
        }
        let c = &sys.physics.carriers[carrier];
        let moving = !c.props.motion.is_stationary();
        let speed = c.props.motion.speed(st.t);
        let supersonic_mass = sys.law.bilateral
            && c.contact.is_some()
            && sys.physics.wave_speed > 0.0
            && speed > sys.physics.wave_speed;
        let weak = note.filter(|_| moving && c.contact.is_some());
        let cause = if st.step == 0 {
            // nothing has been integrated yet: no step or contact law is to blame
            format!(
                "the initial state at t = 0 is already {}, before any step: the model built from the scene (its mass, stiffness and basis, the carriers' static equilibrium) does not hold at these magnitudes; check the scene's values (beam.youngs_modulus × beam.second_moment, beam.tension, carrier masses and stiffnesses) for extremes",
                if value.is_finite() {
                    "out of range"
                } else {
                    "not finite"
                }
            )
        } else if sys.law.placement == Placement::Alpha && moving {
            "the gap is imposed at the α-level (contact.placement = \"alpha\"), which leaves an undamped step-to-step oscillation that a moving contact point drives unstable (MODEL §5); use contact.placement = \"end\"".to_string()
        } else if supersonic_mass {
            format!(
                "a mass held on the beam (bilateral) moves at V = {speed:.1} m/s, faster than the wave speed c = {:.1} m/s: a moving inertial load above the wave speed can be genuinely unstable (anomalous Doppler waves; Metrikine & Dieterman); growth that quickens as the mesh and step are refined is that instability, not the integrator",
                sys.physics.wave_speed
            )
        } else {
            let step = if !value.is_finite() {
                format!(
                    "a non-finite value: check the scene's magnitudes and time.step = {} s",
                    sys.physics.dt
                )
            } else {
                format!(
                    "|{name}| exceeds {limit:e}: time.step = {} s may be too coarse for the contact dynamics, or the scene is physically unbounded",
                    sys.physics.dt
                )
            };
            match weak {
                Some(weak) => format!("{weak}; or {step}"),
                None => step,
            }
        };
        return Err(Error::Diverged {
            step: st.step,
            time: st.t,
            quantity: format!("carrier {carrier}: {name}"),
            value,
            cause,
        });
    }
    Ok(())
}

/// `Integrator::constraint_damping_note` of a run's system (alone or in
/// a batch) whose method notes `note` (`MethodFactory::constraint_note`):
/// the note when some contact carrier moves.
pub(crate) fn damping_note(sys: &System, note: Option<&str>) -> Option<String> {
    let moving = sys
        .physics
        .carriers
        .iter()
        .any(|c| c.contact.is_some() && !c.props.motion.is_stationary());
    moving.then(|| note.map(str::to_string)).flatten()
}
