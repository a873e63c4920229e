//! What a run records of each carrier after a step (MODEL §2):
//! [`CarrierSample`], read from a run's system and state, alone or as one
//! lane of a batch.

use crate::model::beam::PointVector;
use crate::scene::CarrierKind;

use super::state::State;
use super::system::System;

/// The per-carrier values recorded after each step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CarrierSample {
    /// Position x_m, m.
    pub x: f64,
    /// Beam displacement under the carrier, w = s·v(x_m), m (positive into the beam).
    pub w: f64,
    /// Mass displacement q = s·ξ, m (positive into the beam; = w for a force).
    pub q: f64,
    /// Gap g = w − q, m.
    pub gap: f64,
    /// Contact force λ, N (the applied F for a moving force; P/Δt for a
    /// method working with impulses).
    pub force: f64,
    /// Contact closed this step.
    pub in_contact: bool,
}

/// The values of carrier `i` of a run: its system, its state, and `dot`,
/// which takes rᵀd of the run's beam displacements (its own vector, or its
/// lane of a batch's).
pub(crate) fn sample_of(
    sys: &System,
    st: &State,
    i: usize,
    dot: impl Fn(&PointVector) -> f64,
) -> CarrierSample {
    let c = &sys.physics.carriers[i];
    let x = c.props.motion.position(st.t);
    let pv = if st.step == 0 { &c.pv_f } else { &c.pv_g };
    // r_gᵀd as the step computed it (modal_exact: from its pass's sums,
    // within round-off of the dot; `modal_exact.rs` tests)
    let rd = match c.gap_dot {
        Some((n, rd)) if n == st.step && n != 0 => rd,
        _ => dot(pv),
    };
    let w = c.s * rd;
    match (c.props.kind, c.contact) {
        (CarrierKind::Force { force }, _) => CarrierSample {
            x,
            w,
            q: w,
            gap: 0.0,
            force,
            in_contact: true,
        },
        (_, Some(j)) => {
            let force = sys.reported_force(j, st.step);
            CarrierSample {
                x,
                w,
                q: st.q[j],
                gap: w - st.q[j],
                force,
                in_contact: sys.law.active[j],
            }
        }
        _ => unreachable!("a mass carrier always has a contact"),
    }
}
