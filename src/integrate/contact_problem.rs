//! The contact problem of a step as numbers (MODEL §5, §6): the free gaps
//! `g_free` and the Delassus matrix `W` with `g = g_free + W λ`, at the
//! level a law works at. This file only forms the pair; which contacts are
//! closed, and the forces, are the law's (`crate::contact`).
//!
//! * **Acceleration level** ([`ProblemBuilder::acceleration`], MODEL §5:
//!   consistent initial accelerations): the beam is straight and at rest
//!   at t = 0, so g̈ = s rᵀa − q̈; g_free in m/s², W = s rᵀM⁻¹s r + 1/m in
//!   1/kg.
//! * **Position level** ([`ProblemBuilder::position`]): from a method's
//!   [`StepMap`], d_{n+1} = d̃ + c_d u with u = u★ + Σ λ_c z_c, so
//!   g_{n+1} = s rᵀd_{n+1} − q_{n+1} is affine in λ: g_free in m, W in
//!   m/N (impulses: m/(N·s)). With `contact.placement = "alpha"` the gap is
//!   imposed on (1 − α_f) y_{n+1} + α_f y_n along r_f (MODEL §5).
//! * **Velocity level** ([`ProblemBuilder::velocity`], MODEL §6 impact
//!   law, §9.1 Moreau–Jean): the gap rate of a moving contact has a
//!   convective part, ġ = s(r_gᵀv + V r_g'ᵀd) − q̇, and with
//!   v_{n+1} = ṽ + c_v u it is affine in λ too:
//!   W_v = s(c_v r_gᵀz + V c_d r_g'ᵀz) (+ c_v/A_q on the mass). The
//!   position gaps are formed as well: the impact law's index set reads
//!   them.

use crate::scene::Placement;

use super::carrier::Carrier;
use super::mass_dofs::MassDof;
use super::state::State;
use super::step_map::{Lanes, StepMap, VelocityPrediction};
use crate::model::banded::rhs_columns;

/// The pair (g_free, W) of a step, formed in place (no step allocates).
/// With tension-only droppers (`dropper.rs`) the problem has a row per
/// slack dropper after the contacts' (room for nt = nc + every
/// tension-only dropper; `size` rows in use, packed at that stride), which
/// `dropper.rs` fills; the velocity level has contacts only.
#[derive(Debug, Clone)]
pub(crate) struct ProblemBuilder {
    /// Contacts nc (mass–spring carriers).
    nc: usize,
    /// Free gaps, one per contact then one per dropper: m (m/s² at the
    /// acceleration level, contacts only).
    pub(crate) g_free: Vec<f64>,
    /// Delassus matrix, row-major nt × nt, `w[i·nt + j]` = ∂g_i/∂λ_j (at
    /// the acceleration level the contacts' nc × nc block, stride nc).
    pub(crate) w: Vec<f64>,
    /// Free gap rates ġ_free, m/s (velocity level).
    pub(crate) rate_free: Vec<f64>,
    /// The rows of the last pair formed: nt, or nc + the slack droppers'
    /// rows of a step with droppers (`dropper.rs`, packed at that stride).
    pub(crate) size: usize,
    /// Velocity-level Delassus matrix W_v, row-major nc × nc.
    pub(crate) w_v: Vec<f64>,
    /// 1/A_q of each mass dof (scratch).
    inv_a: Vec<f64>,
}

impl ProblemBuilder {
    /// Room for `nc` contacts and `nd` dropper rows.
    pub(crate) fn new(nc: usize, nd: usize) -> Self {
        let nt = nc + nd;
        ProblemBuilder {
            nc,
            g_free: vec![0.0; nt],
            w: vec![0.0; nt * nt],
            size: nt,
            rate_free: vec![0.0; nc],
            w_v: vec![0.0; nc * nc],
            inv_a: vec![0.0; nc],
        }
    }

    /// The acceleration-level problem at t = 0 (module docs) from the
    /// solved M⁻¹ columns `solved` (k columns: the free accelerations a★ in
    /// column 0, M⁻¹ s_c r_f,c in column 1 + c).
    pub(crate) fn acceleration(
        &mut self,
        carriers: &[Carrier],
        masses: &[MassDof],
        placement: Placement,
        solved: &[f64],
        k: usize,
    ) {
        for c in carriers {
            let Some(j) = c.contact else { continue };
            let m = masses[j];
            let aq_free = m.f0 / m.m;
            self.g_free[j] = c.s * c.pv_g.dot_strided(solved, k, 0) - aq_free;
        }
        for (j, m) in masses.iter().enumerate() {
            self.inv_a[j] = 1.0 / m.m;
        }
        let solved = Solved {
            columns: solved,
            k,
            lanes: Lanes::ONE,
        };
        fill_delassus(
            carriers,
            placement,
            solved,
            1.0,
            self.nc,
            &self.inv_a,
            &mut self.w,
        );
    }

    /// The free gaps of a step at the placement's point (module docs):
    /// `map`'s columns and beam vectors may hold several runs side by side
    /// ([`Lanes`]); `st` (the state at t_n) is read for the `alpha`
    /// placement's y_n only.
    pub(crate) fn gaps(
        &mut self,
        carriers: &[Carrier],
        placement: Placement,
        map: &StepMap,
        lanes: Lanes,
        st: &State,
    ) {
        let k = rhs_columns(self.nc) * lanes.count;
        let col0 = lanes.col(0);
        let (c_d, w_a) = (map.c_d, map.alpha_weight);
        for c in carriers {
            let Some(j) = c.contact else { continue };
            let m = &map.masses[j];
            self.g_free[j] = match placement {
                Placement::End => {
                    c.s * (lanes.dot(&c.pv_g, map.d_pred)
                        + c_d * c.pv_g.dot_strided(map.solved, k, col0))
                        - (m.q + c_d * m.u)
                }
                Placement::Alpha => {
                    let wb = (1.0 - w_a)
                        * (lanes.dot(&c.pv_f, map.d_pred)
                            + c_d * c.pv_f.dot_strided(map.solved, k, col0))
                        + w_a * lanes.dot(&c.pv_f, &st.d);
                    let wq = (1.0 - w_a) * (m.q + c_d * m.u) + w_a * st.q[j];
                    c.s * wb - wq
                }
            };
        }
    }

    /// The position-level Delassus matrix of a step (module docs), after
    /// [`ProblemBuilder::gaps`].
    pub(crate) fn position(
        &mut self,
        carriers: &[Carrier],
        placement: Placement,
        map: &StepMap,
        lanes: Lanes,
    ) {
        let k = rhs_columns(self.nc) * lanes.count;
        let coef = contact_coef(placement, map);
        for (j, m) in map.masses.iter().enumerate() {
            self.inv_a[j] = 1.0 / m.a_eff;
        }
        let solved = Solved {
            columns: map.solved,
            k,
            lanes,
        };
        let stride = self.g_free.len();
        fill_delassus(
            carriers,
            placement,
            solved,
            coef,
            stride,
            &self.inv_a,
            &mut self.w,
        );
    }

    /// The velocity-level problem of a step (module docs): free gap rates
    /// and W_v of every contact, for a run alone; `st` is the state at t_n
    /// (its v_n for a shifted ṽ).
    pub(crate) fn velocity(&mut self, carriers: &[Carrier], map: &StepMap, st: &State) {
        let nc = self.nc;
        let k = rhs_columns(nc);
        let (c_d, c_v) = (map.c_d, map.c_v);
        for c in carriers {
            let Some(j) = c.contact else { continue };
            let m = &map.masses[j];
            let u_star = c.pv_g.dot_strided(map.solved, k, 0);
            let s_star = c.pv_s.dot_strided(map.solved, k, 0);
            let v_pred = match map.v_pred {
                VelocityPrediction::Vector(v) => c.pv_g.dot(v),
                VelocityPrediction::Shifted { shift, coef } => {
                    c.pv_g.dot(&st.v) + coef * c.pv_g.dot(shift)
                }
            };
            self.rate_free[j] = c.s
                * (v_pred + c_v * u_star + c.speed * (c.pv_s.dot(map.d_pred) + c_d * s_star))
                - (m.q_dot + c_v * m.u);
            for jj in 0..nc {
                let mut wv = c.s
                    * (c_v * c.pv_g.dot_strided(map.solved, k, 1 + jj)
                        + c.speed * c_d * c.pv_s.dot_strided(map.solved, k, 1 + jj));
                if jj == j {
                    wv += c_v / m.a_eff;
                }
                self.w_v[j * nc + jj] = wv;
            }
        }
    }

    /// The velocity-level problem of a step whose displacement advances by
    /// its own half-step velocity, d_{n+1} = d_n + Δt v_{n+1/2} (central
    /// difference; [`super::System::set_increment_rates`]), after
    /// [`ProblemBuilder::gaps`] and [`ProblemBuilder::position`]: the gap
    /// rate is the gap's increment over the step,
    /// `ġ_{n+1/2} = (g_{n+1} − g_n)/Δt`, with `g_{n+1} = g_free + Wλ` the
    /// position-level pair and `g_n = s r_fᵀd_n − q_n` read along the force
    /// row r_f, which central difference places at t_n (its forward
    /// increment). So `ġ_free = (g_free − g_n)/Δt` and `W_v = W/Δt`: the
    /// carrier's motion over the step is in g_{n+1} − g_n exactly, and a
    /// contact held at ġ = 0 keeps its gap to round-off.
    pub(crate) fn increment(&mut self, carriers: &[Carrier], st: &State, dt: f64) {
        let nc = self.nc;
        let stride = self.g_free.len();
        for c in carriers {
            let Some(j) = c.contact else { continue };
            let g_n = c.s * c.pv_f.dot(&st.d) - st.q[j];
            self.rate_free[j] = (self.g_free[j] - g_n) / dt;
            for jj in 0..nc {
                self.w_v[j * nc + jj] = self.w[j * stride + jj] / dt;
            }
        }
    }

    /// The gap rates ġ = ġ_free + W_v λ of the velocity-level problem just
    /// solved with the multipliers `lambda`, into `rates` (one per contact).
    pub(crate) fn rates_after(&self, lambda: &[f64], rates: &mut [f64]) {
        let nc = self.nc;
        for (j, r) in rates.iter_mut().enumerate().take(nc) {
            *r = self.rate_free[j]
                + (0..nc)
                    .map(|jj| self.w_v[j * nc + jj] * lambda[jj])
                    .sum::<f64>();
        }
    }

    /// A pair a method formed itself (`modal_exact`, MODEL §9.3: sums over
    /// modes), at position level: `g_free` (one per contact, m) and `w`
    /// (row-major nc × nc, m/N).
    ///
    /// One contact (a run's usual case, every step) by two moves, not
    /// two calls to the library's `memcpy`.
    #[inline]
    pub(crate) fn set(&mut self, g_free: &[f64], w: &[f64]) {
        let nc = self.nc;
        if nc == 1 {
            self.g_free[0] = g_free[0];
            self.w[0] = w[0];
            return;
        }
        self.g_free.copy_from_slice(&g_free[..nc]);
        self.w.copy_from_slice(&w[..nc * nc]);
    }
}

/// The coefficient of a contact's gap row in W: c_d at the `end`, (1 − α)
/// c_d at the `alpha` placement (module docs).
pub(crate) fn contact_coef(placement: Placement, map: &StepMap) -> f64 {
    match placement {
        Placement::End => map.c_d,
        Placement::Alpha => (1.0 - map.alpha_weight) * map.c_d,
    }
}

/// A step's solved right-hand sides as the Delassus matrix reads them:
/// `k` columns a run, this run's [`Lanes`].
#[derive(Debug, Clone, Copy)]
struct Solved<'a> {
    columns: &'a [f64],
    k: usize,
    lanes: Lanes,
}

/// W[i][j] = coef · (s_i r_iᵀ z_j + δ_ij · inv_a[i]) for the contacts i, j,
/// at `w[i·stride + j]`, reading the solved directions z_j from column
/// 1 + j of `solved` and the gap rows r_i at the placement's point (r_g,
/// or r_f for `alpha`).
fn fill_delassus(
    carriers: &[Carrier],
    placement: Placement,
    solved: Solved,
    coef: f64,
    stride: usize,
    inv_a: &[f64],
    w: &mut [f64],
) {
    let Solved { columns, k, lanes } = solved;
    let nc = inv_a.len();
    for ci in carriers {
        let Some(i) = ci.contact else { continue };
        let pv = match placement {
            Placement::End => &ci.pv_g,
            Placement::Alpha => &ci.pv_f,
        };
        for j in 0..nc {
            let mut wij = ci.s * pv.dot_strided(columns, k, lanes.col(1 + j));
            if i == j {
                wij += inv_a[i];
            }
            w[i * stride + j] = coef * wij;
        }
    }
}
