//! A carrier during a run (MODEL §2, §3): its side sign, its contact index
//! when it is a mass–spring carrier (its mass dofs are `mass_dofs.rs`), and
//! its contact kinematics — the point
//! vectors at which its force acts and its gap is measured, placed anew
//! each step at the times the method asks for.

use crate::model::beam::{BeamModel, PointVector};
use crate::scene::CarrierProps;

/// When a step places its carriers (s): moving forces (and a manufactured
/// source's loads) at x_m(`load`), contact force directions at
/// x_m(`force`), gap rows at x_m(`gap`) — each method's own times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlaceTimes {
    pub(crate) load: f64,
    pub(crate) force: f64,
    pub(crate) gap: f64,
}

/// One carrier during a run.
#[derive(Debug, Clone)]
pub(crate) struct Carrier {
    pub(crate) props: CarrierProps,
    /// Side sign s.
    pub(crate) s: f64,
    /// Index among the contacts (mass carriers), if any.
    pub(crate) contact: Option<usize>,
    /// r_b where the force acts (x_m at the method's force time), and the
    /// gap row (x_m at t_{n+1}).
    pub(crate) pv_f: PointVector,
    pub(crate) pv_g: PointVector,
    /// r_b' at the gap point, and V there (velocity level only).
    pub(crate) pv_s: PointVector,
    /// V = ẋ_m at the gap time, m/s (velocity level only).
    pub(crate) speed: f64,
    /// A manufactured source's point load at this carrier (MODEL §11): its
    /// magnitude at the step's load time, N in +v, and, for a contact, r_b
    /// there (a force's load point is `pv_f`). Unused without a source.
    pub(crate) pv_l: PointVector,
    pub(crate) point: f64,
    /// `r_gᵀd` after step n, when the step computed it in passing (the
    /// `modal_exact` update, `modal_exact.rs` "The sample"), with that n:
    /// the same bits as [`PointVector::dot`] on the state, so a sample
    /// reads it instead of a pass over the modes. `None` otherwise.
    pub(crate) gap_dot: Option<(usize, f64)>,
}

impl Carrier {
    /// A carrier of side sign `s` (contact index `contact` for a mass
    /// carrier), its point vectors sized for the basis now (a modal basis's
    /// are dense J-vectors), so that no step allocates.
    pub(crate) fn new(props: CarrierProps, contact: Option<usize>, beam: &BeamModel) -> Self {
        let x0 = props.motion.position(0.0);
        Carrier {
            s: props.side.sign(),
            props,
            contact,
            pv_f: beam.point_vector(x0),
            pv_g: beam.point_vector(x0),
            pv_s: beam.slope_vector(x0),
            speed: 0.0,
            pv_l: beam.point_vector(x0),
            point: 0.0,
            gap_dot: None,
        }
    }

    /// Place the carrier for a step: its force at x_m(t_force) (a contact)
    /// or x_m(t_load) (a moving force), its gap row r_g at x_m(t_gap), and,
    /// for a velocity-level law, the slope row r_g' and V there.
    #[inline]
    pub(crate) fn place(&mut self, beam: &BeamModel, at: PlaceTimes, velocity: bool) {
        let PlaceTimes {
            load: t_load,
            force: t_force,
            gap: t_gap,
        } = at;
        let tf = if self.contact.is_some() {
            t_force
        } else {
            t_load
        };
        beam.point_vector_into(self.props.motion.position(tf), false, &mut self.pv_f);
        let xg = self.props.motion.position(t_gap);
        beam.point_vector_into(xg, false, &mut self.pv_g);
        if velocity {
            beam.point_vector_into(xg, true, &mut self.pv_s);
            self.speed = self.props.motion.speed(t_gap);
        }
    }

    /// The gap rate ġ = s(r_gᵀv + V r_g'ᵀd) − q̇ of a state (MODEL §6: the
    /// convective part V r_g'ᵀd of a moving contact), with `q_dot` this
    /// carrier's mass velocity.
    #[inline]
    pub(crate) fn gap_rate(&self, d: &[f64], v: &[f64], q_dot: f64) -> f64 {
        self.s * (self.pv_g.dot(v) + self.speed * self.pv_s.dot(d)) - q_dot
    }
}
