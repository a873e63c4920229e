//! The seam between a method's step and the contact problem (MODEL §5,
//! §6): what a method hands over once it has solved its step with the
//! contact multipliers as unknowns.
//!
//! A method's unknown vector `u` (an acceleration, a displacement or a
//! velocity, depending on the method) is `u = u★ + Σ_c λ_c z_c`, with `u★`
//! the free solution and `z_c = A⁻¹ s_c r_f,c` the response to a unit
//! multiplier of contact c, and the step's end state is affine in it:
//! `d_{n+1} = d̃ + c_d u`, `v_{n+1} = ṽ + c_v u` (the same for each mass dof,
//! whose own unknown is `u_q = u★_q − λ/A_q`). The method describes that in
//! a [`StepMap`]; the contact-problem builder (`contact_problem.rs`) forms
//! from it the pair `(g_free, W)` a contact law needs. [`Lanes`] says where
//! one run's columns sit when several runs step together, and
//! [`Multipliers`] how a method's multipliers are read.

use crate::model::beam::PointVector;

/// What a method predicts for one mass dof this step (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassPrediction {
    /// q̃: the part of q_{n+1} independent of the unknown, m.
    pub q: f64,
    /// q̇̃: the part of q̇_{n+1} independent of the unknown, m/s.
    pub q_dot: f64,
    /// u★_q: the free unknown (λ = 0).
    pub u: f64,
    /// A_q: the method's effective scalar, u_q = u★_q − λ/A_q.
    pub a_eff: f64,
}

impl MassPrediction {
    /// The mass dof's unknown once its multiplier λ is known:
    /// u_q = u★_q − λ/A_q (the contact pushes the mass with −λ).
    #[inline]
    pub fn unknown(&self, lambda: f64) -> f64 {
        self.u - lambda / self.a_eff
    }
}

/// The beam unknown of each row once the multipliers are known,
/// u = u★ + Σ_c λ_c z_c, from the solved right-hand sides (`k` columns,
/// row-major: column 0 u★, column 1 + c z_c).
pub fn combine<'a>(
    solved: &'a [f64],
    k: usize,
    lambda: &'a [f64],
) -> impl Iterator<Item = f64> + 'a {
    solved.chunks_exact(k).map(move |row| {
        let mut u = row[0];
        for (l, z) in lambda.iter().zip(&row[1..]) {
            u += l * z;
        }
        u
    })
}

/// ṽ of the beam, as the method keeps it.
#[derive(Debug, Clone, Copy)]
pub enum VelocityPrediction<'a> {
    /// ṽ stored as a vector.
    Vector(&'a [f64]),
    /// ṽ = v_n + coef·shift (generalized-α: v_n + (1 − γ)Δt a_n), so the
    /// method need not form it.
    Shifted {
        /// The vector added to v_n.
        shift: &'a [f64],
        /// Its coefficient.
        coef: f64,
    },
}

/// A method's step as the contact problem sees it (module docs).
#[derive(Debug, Clone, Copy)]
pub struct StepMap<'a> {
    /// The solved right-hand sides, n × k row-major
    /// ([`super::System::columns`] = k): column 0 is u★, column 1 + c is z_c.
    pub solved: &'a [f64],
    /// c_d in d_{n+1} = d̃ + c_d u.
    pub c_d: f64,
    /// c_v in v_{n+1} = ṽ + c_v u.
    pub c_v: f64,
    /// d̃ of the beam.
    pub d_pred: &'a [f64],
    /// ṽ of the beam.
    pub v_pred: VelocityPrediction<'a>,
    /// For `contact.placement = "alpha"`: the gap is imposed on
    /// (1 − w) y_{n+1} + w y_n with w = α_f, along r_f (MODEL §5); 0 otherwise.
    pub alpha_weight: f64,
    /// One prediction per contact.
    pub masses: &'a [MassPrediction],
}

/// Where one run's columns and vectors sit when several runs step together
/// (batched stepping, `integrate::batch`): `count` runs side by side, this
/// one at `lane`. A right-hand side then has `k·count` columns (column c of
/// this run at `c·count + lane`) and a beam vector holds the runs
/// interleaved (`x[i·count + lane]`). [`Lanes::ONE`] is a run alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Lanes {
    /// Runs side by side.
    pub count: usize,
    /// This run's lane.
    pub lane: usize,
}

impl Lanes {
    /// A run alone.
    pub const ONE: Lanes = Lanes { count: 1, lane: 0 };

    /// The column of this run's column c.
    #[inline]
    pub fn col(&self, c: usize) -> usize {
        c * self.count + self.lane
    }

    /// rᵀx for this run's part of an interleaved vector (the run's own
    /// vector when alone): bit-identical either way.
    #[inline]
    pub fn dot(&self, pv: &PointVector, x: &[f64]) -> f64 {
        if self.count == 1 {
            pv.dot(x)
        } else {
            pv.dot_lane(x, self.count, self.lane)
        }
    }
}

/// How a method's multipliers are to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Multipliers {
    /// Forces, N: the contact law works at its own level.
    Forces,
    /// Impulses over the step, N·s (Moreau–Jean): the law works at
    /// velocity level and the reported force is P/Δt.
    Impulses,
    /// Forces held over each step with the gap imposed at its end
    /// (`modal_exact`, MODEL §9.3). Such a sequence carries a neutral
    /// (−1)ⁿ mode: a held force is the step's mean only up to a zigzag of
    /// amplitude O(Δt) that the start (and every closing of the contact)
    /// excites and nothing damps (for a rigid follower of a path X(t),
    /// `(λ_{n−1/2} + λ_{n+1/2})/2 = m δ²X/Δt²` exactly, while each λ alone
    /// is off by `±m Δt X‴/6`). The reported force at t_n is the mean of
    /// the two held forces on either side, second order, recorded one step
    /// late (lag 1).
    Held,
}
