//! `modal_exact` with an impact law (`contact.formulation = "impact"`;
//! MODEL §6's impact-capable variant, §9.3): each re-contact located within
//! its step and taken as a Newton impact there.
//!
//! Why: a held force shuts a gap closing at t* = t_n + θΔt with a force
//! that acted from t_n, an impact of restitution 1 − 2θ set by the step
//! boundary, so P_l after a re-contact has no limit as Δt falls
//! (docs/contact_loss.md §3). Here a re-contact step (the last step open,
//! g_n > 0, the free gap at t_{n+1} closed) is re-taken:
//!
//! 1. `θ = g_n/(g_n − g_free)`, the free step's gap line;
//! 2. the free motion at t* from the free state at t_{n+1}, carried back by
//!    τ = (1 − θ)Δt (each mode's exact map at −τ, held load included; the
//!    mass dof's exponential);
//! 3. the impulse `P = −(1 + e) ġ*/(Σ_j φ_j(x*)² + 1/m)` (zero unless the
//!    gap closes), `ġ* = s(φ(x*)·η̇* + V φ'(x*)·η*) − q̇*`, e the
//!    restitution; the modes take `s P φ(x*)`, the mass `−P/m` in velocity,
//!    carried to t_{n+1} by the maps over τ;
//! 4. the force held over [t*, t_{n+1}] along φ(x*) → φ(x_{n+1}), the gap
//!    imposed at t_{n+1} by the same law (`g = g_free + W λ`, λ ≥ 0).
//!
//! The step settles at once. Its reported force is its mean, `(λτ + P)/Δt`,
//! so ∫λ dt keeps the impact's momentum as `moreau_jean`'s impulses do.
//! Every other step is the study's. With e = 0 the limit is the plastic one
//! `moreau_jean` (e = 0) converges to. An event costs O(J) (a few
//! trigonometric functions a mode, the slopes at x*); nothing is allocated
//! after [`LocatedImpact::new`].

use crate::error::{Error, Result};
use crate::model::beam::{BeamModel, PointVector};
use crate::scene::impact_refusal;

use super::oscillator::{MassStep, ModeStep};
use super::state::State;
use super::system::System;

/// A re-contact instant within this fraction of Δt of the step's end
/// (1 − θ below it) is left to the held step: over so short a τ the held
/// force's W vanishes to round-off (W ∝ τ², below 1e-18 of its size over
/// Δt) and the law cannot impose the gap with it. Such an event keeps the
/// held step's restitution; with θ spread over the step, about this
/// fraction of the events falls there.
const AT_STEP_END: f64 = 1e-9;

/// The re-contact events of one `modal_exact` run (module docs).
#[derive(Debug, Clone)]
pub(crate) struct LocatedImpact {
    /// Newton's coefficient of restitution e, in [0, 1].
    restitution: f64,
    /// The last step ended with the contact open (the law left it
    /// inactive).
    open: bool,
    /// The gap at the last step's end, m.
    gap: f64,
    /// φ(x*) and φ'(x*) at a re-contact instant (J each; scratch).
    at: PointVector,
    slope: PointVector,
    /// Each mode's map over τ (J; scratch).
    maps: Vec<ModeStep>,
    /// ω_j of the J modes, rad/s.
    omega: Vec<f64>,
}

impl LocatedImpact {
    /// The events of a run on a basis of modes with angular frequencies
    /// `omega` (rad/s; `damped`: with their own damping) whose contact
    /// settings ask for an impact law; `None` for any other formulation.
    /// Refuses a scene this representation does not carry, naming the key.
    pub fn new(omega: &[f64], damped: bool, sys: &mut System) -> Result<Option<Self>> {
        let Some(restitution) = sys.take_impacts() else {
            return Ok(None);
        };
        let carriers = sys.physics.carriers.len();
        let source = sys.has_source() && !sys.law.bilateral;
        let why = impact_refusal(carriers, sys.contacts(), source, damped);
        if let Some(why) = why {
            return Err(Error::invalid("contact.formulation", "\"impact\"", why));
        }
        let beam = sys.beam();
        let x0 = sys.physics.carriers[0].props.motion.position(0.0);
        let mut at = PointVector::default();
        let mut slope = PointVector::default();
        // sized once here: later evaluations refill the buffers in place
        beam.point_vector_into(x0, false, &mut at);
        beam.point_vector_into(x0, true, &mut slope);
        Ok(Some(LocatedImpact {
            restitution,
            open: false,
            gap: 0.0,
            at,
            slope,
            maps: vec![ModeStep::of(0.0, 0.0); omega.len()],
            omega: omega.to_vec(),
        }))
    }

    /// True when the step whose free gap is `g_free` (m) is a re-contact
    /// to locate: the last step ended open with its gap open, this one's
    /// free step closes it before the step's end ([`AT_STEP_END`]), and no
    /// update is pending.
    #[inline]
    pub fn fires(&self, g_free: f64, deferred: bool) -> bool {
        self.open
            && self.gap > 0.0
            && g_free < 0.0
            && !deferred
            && -g_free > AT_STEP_END * (self.gap - g_free)
    }

    /// Keep what the next step's test needs: whether the law left the
    /// contact open, and the gap `gap` (m) at the step's end.
    #[inline]
    pub fn end_step(&mut self, open: bool, gap: f64) {
        self.open = open;
        self.gap = gap;
    }

    /// Re-take the step from t_n to t_{n+1} as a located impact (module
    /// docs). `st` holds the free state at t_{n+1} (modes) and the mass at
    /// t_n is `mass_n` = (q, q̇); `g_free` is the free gap at t_{n+1} (m),
    /// `mass` the mass dof's map over Δt; `place` puts the basis's `φ(x)`
    /// into a point vector (the run's own shapes). On return `st` is the step's
    /// settled state, the law holds the step's mean force, and the result
    /// is `r_gᵀd` at t_{n+1}.
    pub fn recontact(
        &mut self,
        place: impl Fn(&BeamModel, f64, &mut PointVector),
        mass: &MassStep,
        mass_n: (f64, f64),
        g_free: f64,
        sys: &mut System,
        st: &mut State,
    ) -> Result<f64> {
        let dt = sys.physics.dt;
        let theta = self.gap / (self.gap - g_free);
        let tau = (1.0 - theta) * dt;
        let t_star = st.t + theta * dt;
        let beam = &sys.physics.beam;
        let c = &sys.physics.carriers[0];
        let s = c.s;
        let motion = &c.props.motion;
        let x_star = motion.position(t_star);
        let speed = motion.speed(t_star);
        place(beam, x_star, &mut self.at);
        beam.point_vector_into(x_star, true, &mut self.slope);
        let j = self.omega.len();
        let (at, slope) = (&self.at.dense()[..j], &self.slope.dense()[..j]);
        let load = &beam.load[..];
        let omega = &self.omega[..];
        // 2. the free motion at t*: each mode's map at −τ (cos even; sin/ω,
        // −ω sin and the held load's velocity share odd; its displacement
        // share even)
        let (mut rate_w, mut rate_x, mut mobility) = (0.0, 0.0, 0.0);
        for i in 0..j {
            let k = ModeStep::of(omega[i], tau);
            self.maps[i] = k;
            let (eta, eta_dot) = (st.d[i], st.v[i]);
            let p = load.get(i).copied().unwrap_or(0.0);
            let eta_star = k.cos * eta - k.sin_over_omega * eta_dot + (k.a0 + k.a1) * p;
            let eta_dot_star = -k.minus_omega_sin * eta + k.cos * eta_dot - (k.b0 + k.b1) * p;
            rate_w += at[i] * eta_dot_star;
            rate_x += slope[i] * eta_star;
            mobility += at[i] * at[i];
        }
        let dof = sys.masses()[0];
        let (q_free, q_dot_free) = mass.apply(mass_n.0, mass_n.1, dof.f0);
        let back = MassStep::new(dof.m, dof.k, dof.c, -tau);
        let (_, q_dot_star) = back.apply(q_free, q_dot_free, dof.f0);
        // 3. the impulse at t*
        let rate = s * (rate_w + speed * rate_x) - q_dot_star;
        let impulse = newton_impulse(rate, s * s * mobility + 1.0 / dof.m, self.restitution);
        // carried to t_{n+1}; 4. the held force's path over [t*, t_{n+1}]
        let pn1 = &c.pv_g.dense()[..j];
        let fp = s * impulse;
        let (mut dg, mut dw) = (0.0, 0.0);
        for i in 0..j {
            let k = &self.maps[i];
            let kick = fp * at[i];
            st.d[i] = k.sin_over_omega.mul_add(kick, st.d[i]);
            st.v[i] = k.cos.mul_add(kick, st.v[i]);
            dg += pn1[i] * st.d[i];
            dw += pn1[i] * (k.a0 * at[i] + k.a1 * pn1[i]);
        }
        let fwd = MassStep::new(dof.m, dof.k, dof.c, tau);
        let kick = -impulse / dof.m;
        let mut q = fwd.e[0][1].mul_add(kick, q_free);
        let mut q_dot = fwd.e[1][1].mul_add(kick, q_dot_free);
        let g = [s * dg - q];
        let w = [s * s * dw + fwd.g[0]];
        sys.solve_formed(&g, &w, st)?;
        let lambda = sys.law.lambda[0];
        let mut rd = dg;
        if lambda != 0.0 {
            let f = s * lambda;
            let pn1 = &sys.physics.carriers[0].pv_g.dense()[..j];
            for i in 0..j {
                let k = &self.maps[i];
                st.d[i] = f.mul_add(k.a0 * at[i] + k.a1 * pn1[i], st.d[i]);
                st.v[i] = f.mul_add(k.b0 * at[i] + k.b1 * pn1[i], st.v[i]);
            }
            q -= fwd.g[0] * lambda;
            q_dot -= fwd.g[1] * lambda;
            rd = f.mul_add(dw, dg);
        }
        st.q[0] = q;
        st.q_dot[0] = q_dot;
        // the step's mean force, the impact's momentum included
        sys.law.lambda[0] = (lambda * tau + impulse) / dt;
        Ok(rd)
    }
}

/// Newton's impact law at a point of mobility `mobility` (the gap rate's
/// change per unit impulse, `Σ_j φ_j(x*)² + 1/m`, 1/kg): the impulse
/// (N·s, ≥ 0) that turns a closing gap rate `rate` (m/s) into `−e·rate`;
/// none for a gap not closing.
#[inline]
fn newton_impulse(rate: f64, mobility: f64, e: f64) -> f64 {
    if rate < 0.0 {
        -(1.0 + e) * rate / mobility
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rate after the impulse against `−e·rate`: a few ulps of the rate.
    const ROUND_OFF: f64 = 1e-14;

    /// An open step whose free step closes the gap: an event, unless the
    /// instant falls at the step's end to round-off (θ = 1, τ = 0).
    #[test]
    fn a_re_contact_at_the_step_s_end_is_left_to_the_held_step() {
        let mut ev = LocatedImpact {
            restitution: 0.0,
            open: true,
            gap: 1e-4,
            at: PointVector::default(),
            slope: PointVector::default(),
            maps: Vec::new(),
            omega: Vec::new(),
        };
        assert!(ev.fires(-1e-6, false));
        assert!(!ev.fires(-1e-21, false), "θ rounds to 1: τ = 0");
        assert!(!ev.fires(1e-6, false), "the free step leaves the gap open");
        assert!(!ev.fires(-1e-6, true), "an update is pending");
        ev.end_step(false, 1e-4);
        assert!(!ev.fires(-1e-6, false), "the last step ended closed");
    }

    #[test]
    fn the_impulse_turns_a_closing_rate_into_minus_e_times_it() {
        for e in [0.0, 0.3, 1.0] {
            for (rate, mobility) in [(-0.2, 7.0), (-3e-4, 1.2e3), (-1.5, 0.9)] {
                let p = newton_impulse(rate, mobility, e);
                assert!(p > 0.0);
                let after = rate + p * mobility;
                assert!(
                    (after + e * rate).abs() <= ROUND_OFF * rate.abs(),
                    "e = {e}: {after} against {}",
                    -e * rate
                );
            }
            // an opening or still gap takes no impulse
            assert_eq!(newton_impulse(0.1, 7.0, e), 0.0);
            assert_eq!(newton_impulse(0.0, 7.0, e), 0.0);
        }
    }
}
