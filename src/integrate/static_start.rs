//! `[time] initial = "static"` (`docs/lines.md` eq. W6): the wire system
//! starts at its static equilibrium instead of straight (MODEL §5).
//!
//! d₀ solves
//!
//! ```text
//!   (K + Σ_taut k_d r_d r_dᵀ) d₀ = f + Σ_taut k_d e₀,d r_d          (W6)
//! ```
//!
//! where K holds both lines, the attachments and the linear droppers'
//! springs (and ties), f the constant loads of the model (self-weight of
//! both lines, the linear droppers' preloads), and every tension-only
//! dropper is taken taut (a spring with its preload). Each tension-only
//! dropper's force k_d (e₀,d − r_dᵀd₀) must then be > 0: a slack one is an
//! error naming it and its force (the equilibrium with it slack would be a
//! different problem, and a line whose dropper hangs slack at rest is
//! mis-specified). The wire starts at rest (ḋ₀ = 0).
//!
//! Each mass–spring carrier starts at rest with its mass at the wire's
//! static height at its start point, q₀ = s r_b(x_m(0))ᵀ d₀, so its gap
//! is 0; its spring then acts at q₀ (force k(preload) − k q₀ − s m g).
//! **Not in equilibrium at t = 0**: the carriers' contact forces are not
//! in d₀ (the wire is not pre-deflected by the pantographs), nor are
//! moving forces, external force series or a manufactured source; the
//! initial accelerations (MODEL §5) take them up from the static shape,
//! without the convective gap acceleration V² v₀''(x_m) of the sagged
//! shape. A multi-mass pantograph's lower masses start in their own static
//! state against a straight wire (`chain.rs`), so it is accepted only where
//! d₀ leaves its head at q₀ = 0 exactly (a pinned or clamped end of the
//! contact wire, x = 0 or L: interior supports hold the messenger, not the
//! contact wire), and refused elsewhere.

use crate::error::{Error, Result};
use crate::model::banded::BandedLdlt;
use crate::scene::Dropper;

use super::{State, System};

/// Move `st` (at rest, straight) to the static start (module docs): d₀
/// into `st.d`, q₀ into `st.q`. `droppers` are the scene's, for names.
pub(crate) fn static_start(sys: &System, droppers: &[Dropper], st: &mut State) -> Result<()> {
    let beam = sys.beam();
    // K and f hold every dropper's spring and preload (`dropper.rs`, D7)
    let mut d = beam.load.clone();
    let factor = BandedLdlt::factor(&beam.stiffness).map_err(|_| {
        Error::invalid(
            "time.initial",
            "\"static\"",
            "needs a wire system held against rigid motion (K positive definite): the supports, attachments and droppers leave it free",
        )
    })?;
    factor.solve(&mut d);
    for (i, force) in sys.droppers.taut_forces(&d) {
        if force.is_nan() || force <= 0.0 {
            return Err(Error::invalid(
                format!("dropper.{i}"),
                format!("{:?} with force {force:e} N", droppers[i].name),
                "must be taut (force > 0) at the static start: it would hang slack under the static loads; shorten it (length), or start at rest (time.initial = \"rest\")",
            ));
        }
    }
    for (i, c) in sys.carriers.iter().enumerate() {
        if let Some(j) = c.contact {
            let pv = beam.point_vector(c.props.motion.position(0.0));
            let q0 = c.s * pv.dot(&d);
            // a chain's lower masses start in their own static state against
            // the straight wire (chain.rs); that is the static state against
            // d₀ only where d₀ does not move the head (a wire end: q₀ = 0)
            if q0 != 0.0 && sys.chains.get(j).is_some_and(Option::is_some) {
                return Err(Error::invalid(
                    "time.initial",
                    "\"static\"",
                    format!(
                        "starts a multi-mass pantograph (carrier {i}) only where the static wire does not move its head, at a pinned or clamped end of the contact wire (x = 0 or L; here v₀ = {:e} m at its start x = {} m): start it there, use initial = \"rest\", or a single mass–spring carrier",
                        q0 * c.s,
                        c.props.motion.position(0.0)
                    ),
                ));
            }
            st.q[j] = q0;
        }
    }
    st.d = d;
    Ok(())
}
