//! `[time] initial = "static"` (`docs/lines.md` eq. W6–W8): the wire
//! system and its carriers start at their static equilibrium instead of
//! straight (MODEL §5).
//!
//! d₀ solves
//!
//! ```text
//!   (K + Σ_taut k_d r_d r_dᵀ) d₀ = f + Σ_taut k_d e₀,d r_d + Σ_F s F r_b(x_F)
//!                                    + Σ_c s λ_c r_b(x_c)                    (W6)
//! ```
//!
//! (the Σ_taut terms are already in K and f: every dropper's spring and
//! preload is, D7), where K holds both lines, the attachments and the
//! droppers' springs (and ties), f the constant loads of the model (self-weight of
//! both lines, the linear droppers' preloads), every tension-only dropper
//! is taken taut (a spring with its preload), a moving force F presses at
//! its start point x_F, and each mass–spring carrier c presses with its
//! static contact force at its start point x_c. That force follows from
//! the carrier's own statics with its head at the wire's height
//! w_c = s r_b(x_c)ᵀd₀ (MODEL §2 at rest; a multi-mass pantograph through
//! its lower masses' equilibrium, `chain.rs`); W7 and W8, the carriers'
//! static forces through the wire, and what is refused are on `static_start`.

use crate::error::{Error, Result};
use crate::model::banded::BandedLdlt;
use crate::resolve::Resolved;
use crate::scene::{CarrierKind, Formulation};

use super::state::State;
use super::system::System;

/// Move `st` (at rest, straight) to the static start (W6): d₀
/// into `st.d`, q₀ into `st.q`, a chain's lower masses into its
/// [`super::chain::Chain::z_start`].
///
/// ```text
///   λ_c = λ₀,c − S_c q_c,   q_c = w_c + λ_c/κ                            (W7)
/// ```
///
/// with λ₀ = k δ0 − s m g (a single mass; the chain's static force P2 for a
/// pantograph), S the carrier's static stiffness seen from its head (k; the
/// chain's Schur complement S = K₁₁ − K₁ₗK'⁻¹Kₗ₁) and κ the contact's
/// stiffness (`contact.penalty.stiffness`; rigid, 1/κ = 0, for every other
/// law and for a penalty given `relative` to the step, whose penetration
/// λW/ρ is a property of the step, not of the statics: its head starts at
/// the rigid equilibrium with its static force, and that penetration builds
/// over the first steps). Eliminating q_c, λ_c = a_c − b_c w_c with
/// b_c = S κ/(S + κ), a_c = λ₀ κ/(S + κ). The carriers couple through the
/// wire, so with z_c = K'⁻¹ s r_b(x_c) (one banded solve per carrier) and
/// d₀ = d_f + Σ λ_c z_c, the contact forces solve the small system
///
/// ```text
///   λ_c + b_c Σ_j G_cj λ_j = a_c − b_c w_f,c,   G_cj = s r_b(x_c)ᵀ z_j     (W8)
/// ```
///
/// (G symmetric positive semi-definite, b ≥ 0, so I + diag(b) G is
/// invertible). Each tension-only dropper's force k_d (e₀,d − r_dᵀd₀) must
/// then be > 0, and each unilateral carrier's λ_c ≥ 0: a slack dropper or a
/// carrier that would not press at rest is an error naming it (the
/// equilibrium with it slack or lifted is a different problem). The wire
/// and the carriers start at rest (ḋ₀ = 0, q̇₀ = 0), a chain's lower masses
/// at their equilibrium against the held head. A mass–spring's external
/// force series is in its free force f₀ at its value at t = 0
/// (`System::new`), so d₀ is static under it. A manufactured scene is
/// refused (`resolve`: its lines start straight and at rest). At a speed
/// V > 0 the initial
/// accelerations (MODEL §5) take up the convective gap acceleration
/// V² v₀''(x_c) of the sagged shape.
pub(crate) fn static_start(sys: &mut System, sc: &Resolved, st: &mut State) -> Result<()> {
    let beam = sys.beam();
    let n = beam.n;
    // K and f hold every dropper's spring and preload (`dropper.rs`, D7)
    let mut d = beam.load.clone();
    let factor = BandedLdlt::factor(&beam.stiffness).map_err(|_| {
        Error::invalid(
            "time.initial",
            "\"static\"",
            "needs a wire system held against rigid motion (K positive definite): the supports, attachments and droppers leave it free",
        )
    })?;
    // moving forces at their start points (W6)
    for c in &sys.physics.carriers {
        if let CarrierKind::Force { force } = c.props.kind {
            beam.point_vector(c.props.motion.position(0.0))
                .scatter(c.s * force, &mut d, 1, 0);
        }
    }
    factor.solve(&mut d);
    // the contacts' static forces (W7–W8)
    let nc = sys.contacts();
    let kappa = match (sc.contact.formulation, sc.contact.penalty.stiffness) {
        (Formulation::Penalty, Some(kappa)) => kappa,
        _ => f64::INFINITY,
    };
    // (scene carrier index, r_b(x_c), s, a_c, b_c) of each contact, in contact order
    let mut rows = Vec::with_capacity(nc);
    for (i, c) in sys.physics.carriers.iter().enumerate() {
        if let Some(j) = c.contact {
            let pv = beam.point_vector(c.props.motion.position(0.0));
            let (lambda0, stiffness) = match &sys.physics.masses.chains[j] {
                Some(ch) => (ch.static_force, ch.head_stiffness()),
                None => (
                    sys.physics.masses.heads[j].f0,
                    sys.physics.masses.heads[j].k,
                ),
            };
            let (a, b) = if kappa.is_finite() {
                let share = kappa / (stiffness + kappa);
                (lambda0 * share, stiffness * share)
            } else {
                (lambda0, stiffness)
            };
            debug_assert_eq!(rows.len(), j, "contacts are numbered in carrier order");
            rows.push((i, pv, c.s, a, b));
        }
    }
    if !rows.is_empty() {
        let z: Vec<Vec<f64>> = rows
            .iter()
            .map(|(_, pv, s, _, _)| {
                let mut z = vec![0.0; n];
                pv.scatter(*s, &mut z, 1, 0);
                factor.solve(&mut z);
                z
            })
            .collect();
        let m = nalgebra::DMatrix::from_fn(nc, nc, |c, j| {
            let (_, pv, s, _, b) = &rows[c];
            b * s * pv.dot(&z[j]) + if c == j { 1.0 } else { 0.0 }
        });
        let rhs = nalgebra::DVector::from_fn(nc, |c, _| {
            let (_, pv, s, a, b) = &rows[c];
            a - b * s * pv.dot(&d)
        });
        let lambda = m.lu().solve(&rhs).ok_or_else(|| {
            Error::invalid(
                "time.initial",
                "\"static\"",
                "found no static equilibrium of the carriers on the wire (a singular contact system)",
            )
        })?;
        for (l, zj) in lambda.iter().zip(&z) {
            for (di, zi) in d.iter_mut().zip(zj) {
                *di += l * zi;
            }
        }
        for (j, (i, pv, s, _, _)) in rows.iter().enumerate() {
            let l = lambda[j];
            if !l.is_finite() || (!sys.law.bilateral && l < 0.0) {
                return Err(Error::invalid(
                    format!("carrier.{i}"),
                    format!("a static contact force {l:e} N"),
                    "must press on the wire (≥ 0) at the static start (time.initial = \"static\"): raise its preload or uplift, make the contact bilateral, or start at rest (time.initial = \"rest\")",
                ));
            }
            let w = s * pv.dot(&d);
            let q0 = if kappa.is_finite() { w + l / kappa } else { w };
            if let Some(ch) = sys.physics.masses.chains[j].as_mut() {
                ch.hold_head(q0);
            }
            st.q[j] = q0;
        }
        sys.law.static_forces = lambda.iter().copied().collect();
    }
    for (i, force) in sys.physics.droppers.taut_forces(&d) {
        if force.is_nan() || force <= 0.0 {
            return Err(Error::invalid(
                sc.scene.generated.user_path(&format!("dropper.{i}")),
                format!("{:?} with force {force:e} N", sc.droppers[i].name),
                "must be taut (force > 0) at the static start: it would hang slack under the static loads; shorten it (length), or start at rest (time.initial = \"rest\")",
            ));
        }
    }
    st.d = d.into();
    Ok(())
}
