//! Warnings for runs that finish but whose numbers a resolution or modelling
//! choice makes suspect — so that no run is silently wrong. Each check is a
//! cheap, physically grounded test; found with the stability study
//! (`docs/stability.md`), which also lists what no cheap test catches (a
//! plain coarse mesh: use `taut converge`).

use crate::record::ContactStats;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, ContactKind, Formulation};

/// A time step longer than a wave's crossing time of one element (Courant
/// number c·Δt/h above this) cannot follow the waves the mesh carries; the
/// stability study found the reference case's contact loss vanish at
/// c·Δt/h = 1.2 (Δt = 1e-3 s on 400 elements).
pub const MAX_COURANT: f64 = 1.0;

/// A load moving faster than the waves (V > c, or any V when T = 0) sheds a
/// flexural wave of length ℓ = 2π·sqrt(EI/(ρA V² − T)); fewer elements than
/// this per ℓ cannot carry it (the study found 200 % error at 0.8 elements
/// per wavelength, 0.3 % at 13).
pub const MIN_ELEMENTS_PER_SHED_WAVE: f64 = 8.0;

/// Penalty penetration above this fraction of the largest beam deflection
/// under the carrier means κ is soft enough to change the answer (the
/// stability study: κ = 1e2 N/m sank the mass 11 cm and cut the mean force
/// by 89 %; κ ≥ ρ = 1e3 × 1/W keeps it below 1e-3). It judges κ as a
/// regularization of rigid contact; a κ the scene declares the physical
/// contact stiffness (`contact.penalty.physical`) is the model, and its
/// penetration is not checked against it.
pub const MAX_PENALTY_PENETRATION_FRACTION: f64 = 0.01;

/// The warnings of a finished run; `max_abs_w[c]` is the largest |w| under
/// carrier c over every step.
pub fn resolution_warnings(
    sc: &Resolved,
    max_abs_w: &[f64],
    stats: &[ContactStats],
) -> Vec<String> {
    let mut w = unresolved_loss_warnings(stats);
    let b = &sc.beam;
    let c = b.wave_speed();
    let el = sc.resolution();
    let courant = c * sc.dt / el;
    if courant > MAX_COURANT {
        w.push(format!(
            "time step: a wave crosses an element in {:.2e} s, less than time.step = {} s (Courant number c·Δt/h = {courant:.2} > {MAX_COURANT}): the waves the mesh carries are not followed in time, and contact loss driven by them can vanish; refine time.step",
            el / c,
            sc.dt
        ));
    }
    for (i, car) in sc.carriers.iter().enumerate() {
        let v = car.motion.profile.cruise_speed();
        let excess = b.rho_a * v * v - b.tension;
        if v > 0.0 && excess > 0.0 && b.ei > 0.0 {
            let shed = 2.0 * std::f64::consts::PI * (b.ei / excess).sqrt();
            if shed / el < MIN_ELEMENTS_PER_SHED_WAVE {
                w.push(format!(
                    "carrier {i}: moving at V = {v:.1} m/s, faster than the wave speed c = {c:.1} m/s, it sheds a flexural wave of length {shed:.3} m, carried by only {:.1} elements (h = {el:.3} m; at least {MIN_ELEMENTS_PER_SHED_WAVE} needed): refine mesh.elements",
                    shed / el
                ));
            }
        }
        if v > 0.0 && b.ei == 0.0 && c > 0.0 && v > c {
            w.push(format!(
                "carrier {i}: moving at V = {v:.1} m/s, faster than the string's wave speed c = {c:.1} m/s, it trails a Mach front (a moving kink) that string elements smear at first order in h (the stability study: 20 % error at 50 elements, 0.6 % at 400): check with taut converge"
            ));
        }
        if sc.contact.kind == ContactKind::Bilateral
            && matches!(car.kind, CarrierKind::MassSpring { .. })
            && c > 0.0
            && v > c
        {
            w.push(format!(
                "carrier {i}: a mass held on the beam (bilateral) at V = {v:.1} m/s > c = {c:.1} m/s: a moving inertial load above the wave speed can be physically unstable (anomalous Doppler waves), and its forces need not converge under refinement; check with taut converge"
            ));
        }
        if sc.contact.formulation == Formulation::Penalty
            && !sc.contact.penalty.physical
            && let (Some(st), Some(&wmax)) = (stats.get(i), max_abs_w.get(i))
            && wmax > 0.0
            && st.max_penetration > MAX_PENALTY_PENETRATION_FRACTION * wmax
        {
            w.push(format!(
                "carrier {i}: penalty penetration {:.3e} m is {:.1} % of the largest deflection under the carrier ({wmax:.3e} m): κ is soft enough to change the contact forces and loss; raise contact.penalty (or, if κ is the physical contact stiffness, say so: contact.penalty.physical = true)",
                st.max_penetration,
                100.0 * st.max_penetration / wmax
            ));
        }
    }
    w
}

/// A loss interval in the span shorter than the run resolves (fewer than
/// `MIN_RESOLVED_LOSS_STEPS` steps, or shorter than the time h/V the carrier
/// takes to cross an element): the reference scene's one-step loss at
/// x/L = 0.6512 is one, and it vanishes under refinement (`docs/contact_loss.md`).
fn unresolved_loss_warnings(stats: &[ContactStats]) -> Vec<String> {
    use crate::record::zone::MIN_RESOLVED_LOSS_STEPS;
    stats
        .iter()
        .enumerate()
        .filter(|(_, st)| st.suspect_loss_intervals > 0)
        .map(|(i, st)| {
            let in_span = st
                .loss_interval_class
                .iter()
                .filter(|c| **c != crate::record::LossClass::Support)
                .count();
            let first = match (st.loss_interval_class.first(), st.first_loss_position) {
                (Some(crate::record::LossClass::Unresolved), Some(x)) => {
                    format!(" (the first loss, at x/L = {x:.4}, is one of them)")
                }
                _ => String::new(),
            };
            format!(
                "carrier {i}: {} of the {in_span} loss intervals in the span (P_l {:.4} of its {:.4}) last fewer than {MIN_RESOLVED_LOSS_STEPS} steps or less than the time the carrier takes to cross an element{}: the run does not resolve them, and a resolution artefact is likely; refine mesh.elements and time.step (taut converge, taut sweep --check-refinement)",
                st.suspect_loss_intervals,
                st.suspect_loss_fraction,
                st.loss_fraction_span,
                first
            )
        })
        .collect()
}
