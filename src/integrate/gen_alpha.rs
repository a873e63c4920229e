//! The generalized-α family (Chung & Hulbert 1993; MODEL §5): the study's
//! method, and Newmark, HHT and WBZ as named parameter sets of it.
//!
//! M and K do not couple the beam with the masses (only the contact does),
//! so the effective matrix `A = (1 − α_m)M + (1 − α_f)γΔt C + (1 − α_f)βΔt²K`
//! is the banded beam block, factored once per run, plus one scalar per
//! mass. The beam has no damping matrix (MODEL §1, eq. 1; only a carrier's
//! dashpot c_s damps), so its block is `(1 − α_m)M + (1 − α_f)βΔt²K`; the
//! one-product residual below relies on that and would need a C term if beam
//! damping were added.
//!
//! Each step is the spelled-out step of MODEL §5: predictors, the free
//! right-hand side F, one fused banded sweep for `A⁻¹F` and `A⁻¹r_f` of
//! every contact (F is computed inside its forward pass), the contact
//! problem through the [`System`] (free gaps, Delassus matrix, the law), the
//! update (which also forms the next step's predictors). The step allocates
//! nothing and does O(n) work: zeroing the right-hand side, the fused
//! forward sweep, the backward sweep and the update pass.
//!
//! **The residual in one band product.** F = f − α_m M a_n − K u with
//! u = (1 − α_f) d̃ + α_f d_n takes two band products; with
//! M a_n = (A a_n − c_k K a_n)/(1 − α_m), c_k = (1 − α_f)βΔt²,
//!
//! ```text
//!   F = (f − α′ A a_n) − K (u − α′ c_k a_n) = h − K ũ,   α′ = α_m/(1 − α_m),
//! ```
//!
//! one product, because A a_n needs none: it is the right-hand side the last
//! step solved, b₀ + Σ λ_c s_c r_f,c. The two differ by that solve's backward
//! error, ε|A||a_n|: an error every solve makes anyway, and which a's own
//! round-off already carries into the step. h and ũ are formed in the update
//! pass ([`Rows::update`]); the banded kernel computes h − Kũ row by row
//! inside its forward sweep ([`BandedLdlt::solve_affine`]).

#![allow(non_snake_case)]

use crate::error::Result;
use crate::model::banded::{Affine, BandedLdlt, SymBand};
use crate::scene::{GenAlphaParams, Placement};

use super::{
    Initial, MassPrediction, State, StepMap, Stepper, System, VelocityPrediction, rhs_columns,
};

/// A generalized-α stepper for one run.
pub struct GenAlpha {
    p: GenAlphaParams,
    dt: f64,
    ldlt: BandedLdlt,
    /// Beam accelerations a_n.
    a: Vec<f64>,
    /// Mass accelerations q̈_n, one per contact.
    aq: Vec<f64>,
    /// A_q = (1 − α_m)m + (1 − α_f)γΔt c + (1 − α_f)βΔt² k per contact.
    a_eff: Vec<f64>,
    mass_pred: Vec<MassPrediction>,
    d_pred: Vec<f64>,
    /// ũ = u − α′ c_k a_n with u = (1 − α_f) d̃ + α_f d_n (module docs), m.
    u_shift: Vec<f64>,
    /// h = f − α′ A a_n, N (module docs).
    h: Vec<f64>,
    /// Column 0 of the last step's right-hand side before the solve, N.
    b0: Vec<f64>,
    /// α′ = α_m/(1 − α_m).
    alpha_p: f64,
    /// c_k = (1 − α_f)βΔt², s².
    c_k: f64,
    /// n × k right-hand sides, row-major: column 0 the free step,
    /// column 1 + c the direction s_c r_b of contact c.
    rhs: Vec<f64>,
}

impl GenAlpha {
    /// Factor A once and form the first predictors from the initial state.
    pub fn new(p: GenAlphaParams, sys: &System, st: &State, init: Initial) -> Result<Self> {
        let dt = sys.dt();
        let beam = sys.beam();
        let n = beam.n;
        let c_k = (1.0 - p.alpha_f) * p.beta * dt * dt;
        let A: SymBand = beam.mass.combine(1.0 - p.alpha_m, &beam.stiffness, c_k);
        let ldlt = BandedLdlt::factor(&A)?;
        let a_eff = sys
            .masses()
            .iter()
            .map(|m| (1.0 - p.alpha_m) * m.m + (1.0 - p.alpha_f) * p.gamma * dt * m.c + c_k * m.k)
            .collect();
        let nc = sys.contacts();
        let mut ga = GenAlpha {
            p,
            dt,
            ldlt,
            a: init.a,
            aq: init.aq,
            a_eff,
            mass_pred: vec![MassPrediction::default(); nc],
            d_pred: vec![0.0; n],
            u_shift: vec![0.0; n],
            h: vec![0.0; n],
            b0: vec![0.0; n],
            alpha_p: p.alpha_m / (1.0 - p.alpha_m),
            c_k,
            rhs: vec![0.0; n * rhs_columns(nc)],
        };
        ga.predict(sys, st);
        Ok(ga)
    }

    /// Predictors of the next step from the current state (MODEL §5):
    /// d̃ = d + Δt v + (½ − β)Δt² a, u = (1 − α_f) d̃ + α_f d, and the
    /// residual's operands ũ and h (module docs). `step` keeps them current
    /// in its update pass; this computes them at t = 0, with A a₀ formed
    /// explicitly (the only time it is: afterwards A a_n is the last solve's
    /// right-hand side).
    fn predict(&mut self, sys: &System, st: &State) {
        let GenAlphaParams {
            alpha_m: am,
            alpha_f: af,
            beta,
            ..
        } = self.p;
        let dt = self.dt;
        let beam = sys.beam();
        let c_pred = (0.5 - beta) * dt * dt;
        let mut a_a = vec![0.0; beam.n];
        beam.mass.mul_acc(&self.a, 1.0 - am, &mut a_a);
        beam.stiffness.mul_acc(&self.a, self.c_k, &mut a_a);
        for i in 0..beam.n {
            let dp = st.d[i] + dt * st.v[i] + c_pred * self.a[i];
            self.d_pred[i] = dp;
            let u = (1.0 - af) * dp + af * st.d[i];
            self.u_shift[i] = u - self.alpha_p * self.c_k * self.a[i];
            self.h[i] = beam.load[i] - self.alpha_p * a_a[i];
        }
    }
}

impl Stepper for GenAlpha {
    /// Advance one step, t_n → t_{n+1} (MODEL §5, "One step, spelled out").
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        let GenAlphaParams {
            alpha_m: _,
            alpha_f: af,
            beta,
            gamma,
        } = self.p;
        let dt = self.dt;
        let k = sys.columns();
        let t1 = st.next_time(dt);
        let tf = t1 - af * dt;
        let bdt2 = beta * dt * dt;
        sys.place(tf, tf, t1);

        // the predictors d̃ and u = (1 − α_f) d̃ + α_f d_n were computed by the
        // previous step's update pass (or by `predict` at t = 0)
        let c_pred = (0.5 - beta) * dt * dt;
        // B: the moving forces in column 0 and the contact directions s_c r_f,c
        // in columns 1 + c, zero elsewhere
        self.rhs.fill(0.0);
        sys.scatter_loads(&mut self.rhs, k, 1.0);
        // a★ = A⁻¹(F + moving forces) and z_c = A⁻¹(s_c r_f,c) in one sweep,
        // F = h − K ũ computed inside its forward pass (module docs)
        let residual = Affine {
            h: &self.h,
            k: &sys.beam().stiffness,
            u: &self.u_shift,
        };
        self.ldlt
            .solve_affine(&mut self.rhs, k, &residual, &mut self.b0);

        // free mass accelerations
        for (j, m) in sys.masses().iter().enumerate() {
            self.mass_pred[j] = mass_prediction(
                self.p,
                dt,
                m,
                (st.q[j], st.q_dot[j], self.aq[j]),
                self.a_eff[j],
            );
        }
        let alpha_weight = match sys.placement {
            Placement::End => 0.0,
            Placement::Alpha => af,
        };
        let map = StepMap {
            solved: &self.rhs,
            c_d: bdt2,
            c_v: gamma * dt,
            d_pred: &self.d_pred,
            v_pred: VelocityPrediction::Shifted {
                shift: &self.a,
                coef: (1.0 - gamma) * dt,
            },
            alpha_weight,
            masses: &self.mass_pred,
        };
        sys.solve_contact(&map, st)?;

        // update: a = a★ + Σ λ_c z_c; d = d̃ + βΔt² a; v = v_n + Δt((1−γ)a_n + γa),
        // and in the same pass the next step's predictors and residual
        // operands ũ and h (one sweep over memory)
        let lambda = sys.multipliers();
        let alpha_p = self.alpha_p;
        let coefs = UpdateCoefs {
            dt,
            gamma,
            bdt2,
            c_pred,
            alpha_f: af,
            c_shift: alpha_p * self.c_k,
            alpha_p,
        };
        let rows = Rows {
            d: &mut st.d,
            v: &mut st.v,
            a: &mut self.a,
            d_pred: &mut self.d_pred,
            u_shift: &mut self.u_shift,
            h: &mut self.h,
            b0: &self.b0,
            f: &sys.beam().load,
        };
        // a = a★ + Σ λ_c z_c per row; k is a compile-time constant for up to
        // five contacts, so the pass vectorizes across rows
        macro_rules! combine {
            ($($k:literal),*) => {
                match k {
                    $($k => {
                        let lk: [f64; $k] =
                            core::array::from_fn(|c| match c {
                                0 => 1.0,
                                _ => lambda.get(c - 1).copied().unwrap_or(0.0),
                            });
                        let (chunks, _) = self.rhs.as_chunks::<$k>();
                        let combine = |row: &[f64; $k]| {
                            let mut acc = row[0];
                            for c in 1..$k {
                                acc += lk[c] * row[c];
                            }
                            acc
                        };
                        rows.update(chunks.iter().map(combine), coefs)
                    })*
                    _ => rows.update(self.rhs.chunks_exact(k).map(|row| {
                        let mut acc = row[0];
                        for (l, z) in lambda.iter().zip(&row[1..]) {
                            acc += l * z;
                        }
                        acc
                    }), coefs),
                }
            };
        }
        combine!(2, 4, 6);
        // A a_{n+1} = b₀ + Σ λ_c s_c r_f,c: the contact columns' part of h
        sys.scatter_contact_directions(&mut self.h, -alpha_p);
        for (j, m) in self.mass_pred.iter().enumerate() {
            let lambda = sys.multipliers()[j];
            let (a, acc) = (self.aq[j], m.u - lambda / m.a_eff);
            st.q[j] += dt * st.q_dot[j] + c_pred * a + bdt2 * acc;
            st.q_dot[j] += dt * ((1.0 - gamma) * a + gamma * acc);
            self.aq[j] = acc;
        }
        Ok(())
    }
}

/// What generalized-α predicts for one mass dof (q, q̇, q̈ at t_n = `s`)
/// this step: q̃, q̇̃ and the free acceleration u★ = F_q/A_q (MODEL §2, §5);
/// shared by a run alone and a batch of runs (`integrate::batch`).
#[inline]
pub(crate) fn mass_prediction(
    p: GenAlphaParams,
    dt: f64,
    m: &super::MassDof,
    (q, v, a): (f64, f64, f64),
    a_eff: f64,
) -> MassPrediction {
    let (am, af) = (p.alpha_m, p.alpha_f);
    let c_pred = (0.5 - p.beta) * dt * dt;
    let q_pred = q + dt * v + c_pred * a;
    let v_pred = v + (1.0 - p.gamma) * dt * a;
    let fq = m.f0
        - am * m.m * a
        - m.c * ((1.0 - af) * v_pred + af * v)
        - m.k * ((1.0 - af) * q_pred + af * q);
    MassPrediction {
        q: q_pred,
        q_dot: v_pred,
        u: fq / a_eff,
        a_eff,
    }
}

/// The constants of the update pass (MODEL §5, update and predictors).
#[derive(Debug, Clone, Copy)]
pub(crate) struct UpdateCoefs {
    pub(crate) dt: f64,
    pub(crate) gamma: f64,
    /// βΔt².
    pub(crate) bdt2: f64,
    /// (½ − β)Δt².
    pub(crate) c_pred: f64,
    pub(crate) alpha_f: f64,
    /// α′(1 − α_f)βΔt², the shift of ũ.
    pub(crate) c_shift: f64,
    /// α′ = α_m/(1 − α_m).
    pub(crate) alpha_p: f64,
}

/// One row's state in the update pass: d, v, a, d̃, ũ, h (written) and the
/// solve's b₀ and the load f (read).
pub(crate) struct RowState<'a> {
    pub(crate) d: &'a mut f64,
    pub(crate) v: &'a mut f64,
    pub(crate) a: &'a mut f64,
    pub(crate) dp: &'a mut f64,
    pub(crate) u: &'a mut f64,
    pub(crate) h: &'a mut f64,
}

impl UpdateCoefs {
    /// The update of one row from its new acceleration `acc` (a run alone
    /// and every lane of a batch use this, so their bits agree):
    /// v += Δt((1−γ)a + γ acc), d = d̃ + βΔt² acc, a = acc, then the next
    /// step's d̃, ũ and h (module docs).
    #[inline(always)]
    pub(crate) fn row(&self, acc: f64, r: RowState, b0: f64, f: f64) {
        *r.v += self.dt * ((1.0 - self.gamma) * *r.a + self.gamma * acc);
        *r.d = *r.dp + self.bdt2 * acc;
        *r.a = acc;
        let next = *r.d + self.dt * *r.v + self.c_pred * acc;
        *r.dp = next;
        *r.u = (1.0 - self.alpha_f) * next + self.alpha_f * *r.d - self.c_shift * acc;
        *r.h = f - self.alpha_p * b0;
    }
}

/// The beam rows the update pass reads and writes.
struct Rows<'a> {
    d: &'a mut [f64],
    v: &'a mut [f64],
    a: &'a mut [f64],
    d_pred: &'a mut [f64],
    u_shift: &'a mut [f64],
    h: &'a mut [f64],
    b0: &'a [f64],
    f: &'a [f64],
}

impl Rows<'_> {
    /// One pass: from each row's new acceleration a, d = d̃ + βΔt² a,
    /// v = v_n + Δt((1−γ)a_n + γa), then the next step's d̃, ũ and h (the
    /// residual's operands, module docs). Element-wise, so it vectorizes
    /// when `acc` does.
    #[inline(always)]
    fn update(self, acc: impl Iterator<Item = f64>, c: UpdateCoefs) {
        let state = self
            .d
            .iter_mut()
            .zip(self.v.iter_mut())
            .zip(self.a.iter_mut());
        let pred = self.d_pred.iter_mut().zip(self.u_shift.iter_mut());
        let load = self.h.iter_mut().zip(self.b0).zip(self.f);
        for (((acc, ((d, v), a)), (dp, u)), ((h, b0), f)) in acc.zip(state).zip(pred).zip(load) {
            c.row(acc, RowState { d, v, a, dp, u, h }, *b0, *f);
        }
    }
}
