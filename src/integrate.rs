//! Generalized-α time integration with point contact (MODEL §5).
//!
//! The system is `d = [d_b; q]`: beam dofs and one dof per mass carrier. M and
//! K do not couple the beam with the masses (only the contact does), so the
//! effective matrix `A = (1 − α_m)M + (1 − α_f)γΔt C + (1 − α_f)βΔt²K` is the
//! banded beam block, factored once per run, plus one scalar per mass. The
//! beam has no damping matrix (MODEL §1, eq. 1; only a carrier's dashpot c_s damps), so
//! its block is `(1 − α_m)M + (1 − α_f)βΔt²K`; `step`'s one-product residual
//! relies on that and would need a C term if beam damping were added. Each
//! step is the spelled-out step of MODEL §5: predictors, the free right-hand
//! side F, one fused banded sweep for `A⁻¹F` and `A⁻¹r_f` of every contact
//! (F is computed inside its forward pass), the free gaps and the Delassus
//! matrix W, the contact law, the update (which also forms the next step's
//! predictors). The step allocates nothing and does O(n) work: zeroing the
//! right-hand side, the fused forward sweep, the backward sweep and the update
//! pass.

#![allow(non_snake_case)]

use crate::contact::{ContactLaw, law_for};
use crate::error::{Error, Result};
use crate::model::banded::{BandedLdlt, Residual, SymBand};
use crate::model::beam::{BeamModel, PointVector};
use crate::scene::{CarrierKind, CarrierProps, Placement, Resolved};

/// Generalized-α parameters from ρ∞ (Chung & Hulbert 1993, MODEL §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenAlpha {
    /// α_m = (2ρ∞ − 1)/(ρ∞ + 1).
    pub alpha_m: f64,
    /// α_f = ρ∞/(ρ∞ + 1).
    pub alpha_f: f64,
    /// β = (1 − α_m + α_f)²/4.
    pub beta: f64,
    /// γ = 1/2 − α_m + α_f.
    pub gamma: f64,
}

impl GenAlpha {
    /// The parameters for spectral radius ρ∞ ∈ [0, 1].
    pub fn from_rho_inf(rho: f64) -> Self {
        let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
        let alpha_f = rho / (rho + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
        GenAlpha {
            alpha_m,
            alpha_f,
            beta,
            gamma,
        }
    }
}

/// Displacements beyond this many beam lengths are not a small-deflection
/// answer: a linear model that gets there has blown up.
const DISPLACEMENT_BOUND_IN_LENGTHS: f64 = 1.0;

/// Contact forces beyond this multiple of the carriers' force scale
/// (k(δ0 + L) + m g + F) are taken as a blow-up: no physical run of this model
/// comes within orders of magnitude of it.
const FORCE_BOUND_FACTOR: f64 = 1e3;

/// Columns of the right-hand side for `nc` contacts: the free step and one
/// per contact, rounded up to an even number (at least two). The sweeps carry
/// the columns side by side in two-wide SIMD lanes: with one column the
/// compiler packs the sweep's window into vectors through general registers,
/// three extra moves on the dependency chain (measured: one-column sweeps took
/// 2.7× as long as two-column ones, `examples/step_profile.rs`); with three, a
/// half-empty lane and register spills (two carriers at N = 800: 1.16 × 10⁸
/// DOF-steps/s with three columns, 1.55 × 10⁸ with four). A padding column
/// stays zero (A⁻¹0 = 0) and enters the update with weight 0.
fn rhs_columns(nc: usize) -> usize {
    (1 + nc).max(2).next_multiple_of(2)
}

/// The single mass dof of a mass–spring carrier.
#[derive(Debug, Clone, Copy)]
struct MassDof {
    m: f64,
    k: f64,
    c: f64,
    /// Constant force on q: k δ0 − s m g (MODEL §2).
    f0: f64,
    /// A_q = (1 − α_m)m + (1 − α_f)γΔt c + (1 − α_f)βΔt² k.
    a_eff: f64,
    q: f64,
    v: f64,
    a: f64,
}

/// One carrier's state during a run.
#[derive(Debug, Clone)]
struct CarrierState {
    props: CarrierProps,
    /// Side sign s.
    s: f64,
    mass: Option<MassDof>,
    /// Index among the contacts (mass carriers), if any.
    contact: Option<usize>,
    /// r_b at x_m(t_{n+1−α_f}) and at x_m(t_{n+1}).
    pv_f: PointVector,
    pv_g: PointVector,
    /// r_b' at x_m(t_{n+1}) and V(t_{n+1}) (velocity-level law only).
    pv_s: PointVector,
    speed: f64,
}

/// The parts of the discrete energy (see [`Integrator::energy`]), J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    /// ½vᵀMv + Σ ½m q̇².
    pub kinetic: f64,
    /// ½dᵀKd + Σ ½k q².
    pub strain: f64,
    /// −(constant loads)ᵀd.
    pub load_potential: f64,
}

impl Energy {
    /// The total.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.load_potential
    }

    /// The size of its parts, for round-off bounds.
    pub fn scale(&self) -> f64 {
        self.kinetic.abs() + self.strain.abs() + self.load_potential.abs()
    }
}

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
    /// Contact force λ, N (the applied F for a moving force).
    pub force: f64,
    /// Contact closed this step.
    pub in_contact: bool,
}

/// A generalized-α integrator for one scene.
pub struct Integrator {
    ga: GenAlpha,
    dt: f64,
    t: f64,
    step: usize,
    placement: Placement,
    beam: BeamModel,
    ldlt: BandedLdlt,
    carriers: Vec<CarrierState>,
    nc: usize,
    law: Box<dyn ContactLaw>,
    bilateral: bool,
    length: f64,
    /// Supports at x = 0 and x = L.
    supports: (crate::scene::Support, crate::scene::Support),
    /// String wave speed c = sqrt(T/ρA), m/s.
    wave_speed: f64,
    force_bound: f64,
    // state (beam)
    d: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    // scratch, allocated once
    d_pred: Vec<f64>,
    /// ũ = u − α′ c_k a_n with u = (1 − α_f) d̃ + α_f d_n (see `step`), m.
    u_shift: Vec<f64>,
    /// h = f − α′ A a_n, N (see `step`).
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
    g_free: Vec<f64>,
    w: Vec<f64>,
    lambda: Vec<f64>,
    active: Vec<bool>,
    /// Free accelerations of the mass dofs, per contact.
    aq_free: Vec<f64>,
    /// Velocity-level law (`impact`): restitution e and the gap rates ġ_n.
    velocity: Option<f64>,
    gap_rate: Vec<f64>,
    /// Reduced problem over Moreau's index set (velocity level).
    red_idx: Vec<usize>,
    red_g: Vec<f64>,
    red_w: Vec<f64>,
    red_l: Vec<f64>,
    red_a: Vec<bool>,
}

impl Integrator {
    /// Build the model for a validated scene, factor A once, and set the
    /// initial state (MODEL §5: beam straight and at rest, masses touching,
    /// loads switched on at t = 0, accelerations consistent with contact).
    pub fn new(sc: &Resolved) -> Result<Self> {
        let ga = GenAlpha::from_rho_inf(sc.integrator.rho_inf);
        let dt = sc.dt;
        let beam = BeamModel::new(&sc.beam, sc.elements);
        let n = beam.n;
        let c_k = (1.0 - ga.alpha_f) * ga.beta * dt * dt;
        let A: SymBand = beam.mass.combine(1.0 - ga.alpha_m, &beam.stiffness, c_k);
        let ldlt = BandedLdlt::factor(&A)?;

        let mut nc = 0;
        let mut force_scale: f64 = 0.0;
        let carriers: Vec<CarrierState> = sc
            .carriers
            .iter()
            .map(|p| {
                let s = p.side.sign();
                let (mass, contact) = match p.kind {
                    CarrierKind::MassSpring {
                        mass,
                        stiffness,
                        damping,
                        preload,
                    } => {
                        let idx = nc;
                        nc += 1;
                        force_scale =
                            force_scale.max(stiffness * (preload + sc.beam.length) + mass * sc.g);
                        let a_eff = (1.0 - ga.alpha_m) * mass
                            + (1.0 - ga.alpha_f) * ga.gamma * dt * damping
                            + c_k * stiffness;
                        (
                            Some(MassDof {
                                m: mass,
                                k: stiffness,
                                c: damping,
                                f0: stiffness * preload - s * mass * sc.g,
                                a_eff,
                                q: 0.0,
                                v: 0.0,
                                a: 0.0,
                            }),
                            Some(idx),
                        )
                    }
                    CarrierKind::Force { force } => {
                        force_scale = force_scale.max(force);
                        (None, None)
                    }
                };
                CarrierState {
                    props: *p,
                    s,
                    mass,
                    contact,
                    pv_f: PointVector::default(),
                    pv_g: PointVector::default(),
                    pv_s: PointVector::default(),
                    speed: 0.0,
                }
            })
            .collect();
        let k = rhs_columns(nc);
        let law = law_for(&sc.contact, nc);
        let velocity = law
            .velocity_level()
            .then_some(sc.contact.impact.restitution);
        let mut it = Integrator {
            ga,
            dt,
            t: 0.0,
            step: 0,
            placement: sc.contact.placement,
            ldlt,
            carriers,
            nc,
            law,
            bilateral: sc.contact.kind == crate::scene::ContactKind::Bilateral,
            velocity,
            gap_rate: vec![0.0; nc],
            red_idx: Vec::with_capacity(nc),
            red_g: vec![0.0; nc],
            red_w: vec![0.0; nc * nc],
            red_l: vec![0.0; nc],
            red_a: vec![false; nc],
            length: sc.beam.length,
            supports: (sc.beam.left, sc.beam.right),
            wave_speed: sc.beam.wave_speed(),
            force_bound: FORCE_BOUND_FACTOR * force_scale.max(f64::MIN_POSITIVE),
            d: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            d_pred: vec![0.0; n],
            u_shift: vec![0.0; n],
            h: vec![0.0; n],
            b0: vec![0.0; n],
            alpha_p: ga.alpha_m / (1.0 - ga.alpha_m),
            c_k,
            rhs: vec![0.0; n * k],
            g_free: vec![0.0; nc],
            w: vec![0.0; nc * nc],
            lambda: vec![0.0; nc],
            active: vec![false; nc],
            aq_free: vec![0.0; nc],
            beam,
        };
        it.initial_accelerations()?;
        Ok(it)
    }

    /// Number of unknowns: free beam dofs plus one per mass carrier.
    pub fn dofs(&self) -> usize {
        self.beam.n + self.nc
    }

    /// The beam model.
    pub fn beam(&self) -> &BeamModel {
        &self.beam
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Steps taken.
    pub fn steps_taken(&self) -> usize {
        self.step
    }

    /// Current beam dofs d_b.
    pub fn beam_dofs(&self) -> &[f64] {
        &self.d
    }

    /// Beam displacement v(x) (positive up), m, for a precomputed point vector.
    pub fn displacement_at(&self, pv: &PointVector) -> f64 {
        pv.dot(&self.d)
    }

    /// Consistent initial accelerations: M a₀ = f(0) + Σ λ r, with the gap
    /// acceleration of each closed contact zero (the beam is straight and at
    /// rest, so g̈ = rᵀa). Uses the same contact law at acceleration level.
    fn initial_accelerations(&mut self) -> Result<()> {
        let n = self.beam.n;
        let k = rhs_columns(self.nc);
        let mfac = BandedLdlt::factor(&self.beam.mass)?;
        for c in self.carriers.iter_mut() {
            let x = c.props.motion.position(0.0);
            c.pv_f = self.beam.point_vector(x);
            c.pv_g = c.pv_f;
        }
        self.rhs.fill(0.0);
        for i in 0..n {
            self.rhs[i * k] = self.beam.load[i];
        }
        self.scatter_loads(k);
        mfac.solve_many(&mut self.rhs, k);
        for c in &self.carriers {
            let (Some(j), Some(m)) = (c.contact, c.mass) else {
                continue;
            };
            self.aq_free[j] = m.f0 / m.m;
            self.g_free[j] = c.s * c.pv_g.dot_strided(&self.rhs, k, 0) - self.aq_free[j];
        }
        self.fill_delassus(1.0, |m| m.m);
        self.law
            .initial(&self.g_free, &self.w, &mut self.lambda, &mut self.active)
            .map_err(|reason| Error::Contact {
                step: 0,
                time: 0.0,
                reason,
                problem: self.law.failed_problem(),
            })?;
        for i in 0..n {
            let mut acc = self.rhs[i * k];
            for (j, l) in self.lambda.iter().enumerate() {
                acc += l * self.rhs[i * k + 1 + j];
            }
            self.a[i] = acc;
        }
        for c in self.carriers.iter_mut() {
            if let (Some(j), Some(m)) = (c.contact, c.mass.as_mut()) {
                m.a = (m.f0 - self.lambda[j]) / m.m;
            }
        }
        self.predict();
        Ok(())
    }

    /// Predictors of the next step from the current state (MODEL §5):
    /// d̃ = d + Δt v + (½ − β)Δt² a, u = (1 − α_f) d̃ + α_f d, and the
    /// residual's operands ũ and h (see `step`). `step` keeps them current in
    /// its update pass; this computes them at t = 0, with A a₀ formed
    /// explicitly (the only time it is: afterwards A a_n is the last solve's
    /// right-hand side).
    fn predict(&mut self) {
        let GenAlpha {
            alpha_m: am,
            alpha_f: af,
            beta,
            ..
        } = self.ga;
        let dt = self.dt;
        let c_pred = (0.5 - beta) * dt * dt;
        let mut a_a = vec![0.0; self.beam.n];
        self.beam.mass.mul_acc(&self.a, 1.0 - am, &mut a_a);
        self.beam.stiffness.mul_acc(&self.a, self.c_k, &mut a_a);
        for i in 0..self.beam.n {
            let dp = self.d[i] + dt * self.v[i] + c_pred * self.a[i];
            self.d_pred[i] = dp;
            let u = (1.0 - af) * dp + af * self.d[i];
            self.u_shift[i] = u - self.alpha_p * self.c_k * self.a[i];
            self.h[i] = self.beam.load[i] - self.alpha_p * a_a[i];
        }
    }

    /// Scatter the moving forces into column 0 and the contact directions
    /// s_c r_b(x_f) into columns 1 + c of `rhs`.
    fn scatter_loads(&mut self, k: usize) {
        for c in &self.carriers {
            match (c.props.kind, c.contact) {
                (CarrierKind::Force { force }, _) => {
                    c.pv_f.scatter(c.s * force, &mut self.rhs, k, 0)
                }
                (_, Some(j)) => c.pv_f.scatter(c.s, &mut self.rhs, k, 1 + j),
                _ => {}
            }
        }
    }

    /// W[i][j] = coef · (s_i s_j r_g,iᵀ A⁻¹ r_f,j + δ_ij / a_q,i), reading the
    /// solved directions from `rhs`; `a_q` picks the scalar "A" of each mass.
    fn fill_delassus(&mut self, coef: f64, a_q: impl Fn(&MassDof) -> f64) {
        let k = rhs_columns(self.nc);
        let nc = self.nc;
        for ci in &self.carriers {
            let (Some(i), Some(mi)) = (ci.contact, ci.mass) else {
                continue;
            };
            let pv = match self.placement {
                Placement::End => ci.pv_g,
                Placement::Alpha => ci.pv_f,
            };
            for j in 0..nc {
                let mut wij = ci.s * pv.dot_strided(&self.rhs, k, 1 + j);
                if i == j {
                    wij += 1.0 / a_q(&mi);
                }
                self.w[i * nc + j] = coef * wij;
            }
        }
    }

    /// Advance one step, t_n → t_{n+1} (MODEL §5, "One step, spelled out").
    pub fn step(&mut self) -> Result<()> {
        let GenAlpha {
            alpha_m: am,
            alpha_f: af,
            beta,
            gamma,
        } = self.ga;
        let dt = self.dt;
        let k = rhs_columns(self.nc);
        // time from the step count (t_n = n·Δt, one rounding), not accumulated
        let t1 = (self.step + 1) as f64 * dt;
        let tf = t1 - af * dt;
        let bdt2 = beta * dt * dt;

        for c in self.carriers.iter_mut() {
            c.pv_f = self.beam.point_vector(c.props.motion.position(tf));
            let xg = c.props.motion.position(t1);
            c.pv_g = self.beam.point_vector(xg);
            if self.velocity.is_some() {
                c.pv_s = self.beam.slope_vector(xg);
                c.speed = c.props.motion.speed(t1);
            }
        }

        // the predictors d̃ and u = (1 − α_f) d̃ + α_f d_n were computed by the
        // previous step's update pass (or by `predict` at t = 0)
        let c_pred = (0.5 - beta) * dt * dt;
        // B: the moving forces in column 0 and the contact directions s_c r_f,c
        // in columns 1 + c, zero elsewhere
        self.rhs.fill(0.0);
        self.scatter_loads(k);
        // a★ = A⁻¹(F + moving forces) and z_c = A⁻¹(s_c r_f,c) in one sweep,
        // F computed inside its forward pass. F = f − α_m M a_n − K u takes
        // two band products; with M a_n = (A a_n − c_k K a_n)/(1 − α_m) it is
        //   F = (f − α′ A a_n) − K (u − α′ c_k a_n) = h − K ũ,  α′ = α_m/(1 − α_m),
        // one product, because A a_n needs none: it is the right-hand side the
        // last step solved, b₀ + Σ λ_c s_c r_f,c. The two differ by that
        // solve's backward error, ε|A||a_n|: an error every solve makes anyway,
        // and which a's own round-off already carries into the step.
        let residual = Residual {
            h: &self.h,
            k: &self.beam.stiffness,
            u: &self.u_shift,
        };
        self.ldlt
            .solve_residual(&mut self.rhs, k, &residual, &mut self.b0);

        // free mass accelerations and free gaps
        let gap_coef = match self.placement {
            Placement::End => bdt2,
            Placement::Alpha => (1.0 - af) * bdt2,
        };
        for c in &self.carriers {
            let (Some(j), Some(m)) = (c.contact, c.mass) else {
                continue;
            };
            let q_pred = m.q + dt * m.v + c_pred * m.a;
            let v_pred = m.v + (1.0 - gamma) * dt * m.a;
            let fq = m.f0
                - am * m.m * m.a
                - m.c * ((1.0 - af) * v_pred + af * m.v)
                - m.k * ((1.0 - af) * q_pred + af * m.q);
            let aq = fq / m.a_eff;
            self.aq_free[j] = aq;
            self.g_free[j] = match self.placement {
                Placement::End => {
                    c.s * (c.pv_g.dot(&self.d_pred) + bdt2 * c.pv_g.dot_strided(&self.rhs, k, 0))
                        - (q_pred + bdt2 * aq)
                }
                Placement::Alpha => {
                    let wb = (1.0 - af)
                        * (c.pv_f.dot(&self.d_pred) + bdt2 * c.pv_f.dot_strided(&self.rhs, k, 0))
                        + af * c.pv_f.dot(&self.d);
                    let wq = (1.0 - af) * (q_pred + bdt2 * aq) + af * m.q;
                    c.s * wb - wq
                }
            };
        }
        self.fill_delassus(gap_coef, |m| m.a_eff);
        let solved = match self.velocity {
            None => self
                .law
                .solve(&self.g_free, &self.w, &mut self.lambda, &mut self.active),
            Some(e) => self.solve_velocity_level(e),
        };
        solved.map_err(|reason| Error::Contact {
            step: self.step + 1,
            time: t1,
            reason,
            problem: self.law.failed_problem(),
        })?;

        // update: a = a★ + Σ λ_c z_c; d = d̃ + βΔt² a; v = v_n + Δt((1−γ)a_n + γa),
        // and in the same pass the next step's predictors and residual
        // operands ũ and h (one sweep over memory)
        let lambda = &self.lambda[..];
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
            d: &mut self.d,
            v: &mut self.v,
            a: &mut self.a,
            d_pred: &mut self.d_pred,
            u_shift: &mut self.u_shift,
            h: &mut self.h,
            b0: &self.b0,
            f: &self.beam.load,
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
        for c in &self.carriers {
            if let Some(j) = c.contact {
                c.pv_f
                    .scatter(-alpha_p * lambda[j] * c.s, &mut self.h, 1, 0);
            }
        }
        for c in self.carriers.iter_mut() {
            let (Some(j), Some(m)) = (c.contact, c.mass.as_mut()) else {
                continue;
            };
            let acc = self.aq_free[j] - self.lambda[j] / m.a_eff;
            m.q += dt * m.v + c_pred * m.a + bdt2 * acc;
            m.v += dt * ((1.0 - gamma) * m.a + gamma * acc);
            m.a = acc;
        }
        self.t = t1;
        self.step += 1;
        if self.velocity.is_some() {
            for c in &self.carriers {
                let (Some(j), Some(m)) = (c.contact, c.mass) else {
                    continue;
                };
                self.gap_rate[j] =
                    c.s * (c.pv_g.dot(&self.v) + c.speed * c.pv_s.dot(&self.d)) - m.v;
            }
        }
        Ok(())
    }

    /// The velocity-level (Moreau–Jean style) contact problem of a step.
    ///
    /// Index set: the contacts whose free step would close the gap
    /// (g_free ≤ 0; all of them when bilateral). On it, Signorini at velocity
    /// level with Newton's impact law: ġ_{n+1} + e·ġ_n ≥ 0, λ ≥ 0,
    /// complementary. The gap rate of a moving contact has a convective part,
    /// ġ = s(r_bᵀv + V r_b'ᵀd) − q̇, and with v_{n+1} = ṽ + γΔt a,
    /// d_{n+1} = d̃ + βΔt² a it is linear in λ:
    /// ġ = ġ_free + W_v λ, W_v = γΔt r_gᵀz + V βΔt² r_g'ᵀz (+ γΔt/A_q on the mass).
    /// The position gap is not imposed: it drifts by O(Δt²) per step, and
    /// the largest penetration is reported.
    fn solve_velocity_level(&mut self, e: f64) -> std::result::Result<(), String> {
        let GenAlpha { beta, gamma, .. } = self.ga;
        let dt = self.dt;
        let k = rhs_columns(self.nc);
        let nc = self.nc;
        let bdt2 = beta * dt * dt;
        let gdt = gamma * dt;
        let bilateral = self.bilateral;
        self.red_idx.clear();
        for j in 0..nc {
            if bilateral || self.g_free[j] <= 0.0 {
                self.red_idx.push(j);
            }
        }
        let na = self.red_idx.len();
        for c in &self.carriers {
            let (Some(j), Some(m)) = (c.contact, c.mass) else {
                continue;
            };
            let Some(r) = self.red_idx.iter().position(|&i| i == j) else {
                continue;
            };
            let a_star = c.pv_g.dot_strided(&self.rhs, k, 0);
            let s_star = c.pv_s.dot_strided(&self.rhs, k, 0);
            let v_pred = c.pv_g.dot(&self.v) + (1.0 - gamma) * dt * c.pv_g.dot(&self.a);
            let vq_pred = m.v + (1.0 - gamma) * dt * m.a;
            let rate_free = c.s
                * (v_pred + gdt * a_star + c.speed * (c.pv_s.dot(&self.d_pred) + bdt2 * s_star))
                - (vq_pred + gdt * self.aq_free[j]);
            self.red_g[r] = rate_free + e * self.gap_rate[j];
            for (rr, &jj) in self.red_idx.iter().enumerate() {
                let mut wv = c.s
                    * (gdt * c.pv_g.dot_strided(&self.rhs, k, 1 + jj)
                        + c.speed * bdt2 * c.pv_s.dot_strided(&self.rhs, k, 1 + jj));
                if jj == j {
                    wv += gdt / m.a_eff;
                }
                self.red_w[r * na + rr] = wv;
            }
        }
        for r in 0..na {
            let wv = self.red_w[r * na + r];
            if wv.is_nan() || wv <= 0.0 {
                let j = self.red_idx[r];
                let speed = self
                    .carriers
                    .iter()
                    .find(|c| c.contact == Some(j))
                    .map_or(0.0, |c| c.speed);
                return Err(format!(
                    "velocity-level Delassus W = {wv:e} s/kg is not positive: the convective term V·r'ᵀz outweighs γΔt·rᵀz, the carrier moving V·Δt = {:.3e} m per step on elements of h = {:.3e} m; reduce time.step (the impact law needs V·Δt well below h)",
                    speed * dt,
                    self.beam.h
                ));
            }
        }
        self.law.solve(
            &self.red_g[..na],
            &self.red_w[..na * na],
            &mut self.red_l[..na],
            &mut self.red_a[..na],
        )?;
        self.lambda.fill(0.0);
        self.active.fill(false);
        for (r, &j) in self.red_idx.iter().enumerate() {
            self.lambda[j] = self.red_l[r];
            self.active[j] = self.red_a[r];
        }
        Ok(())
    }

    /// The values of carrier `i` at the current time.
    pub fn sample(&self, i: usize) -> CarrierSample {
        let c = &self.carriers[i];
        let x = c.props.motion.position(self.t);
        let pv = if self.step == 0 { c.pv_f } else { c.pv_g };
        let w = c.s * pv.dot(&self.d);
        match (c.props.kind, c.contact, c.mass) {
            (CarrierKind::Force { force }, _, _) => CarrierSample {
                x,
                w,
                q: w,
                gap: 0.0,
                force,
                in_contact: true,
            },
            (_, Some(j), Some(m)) => CarrierSample {
                x,
                w,
                q: m.q,
                gap: w - m.q,
                force: self.lambda[j],
                in_contact: self.active[j],
            },
            _ => unreachable!("a mass carrier always has a contact"),
        }
    }

    /// Number of carriers.
    pub fn carriers(&self) -> usize {
        self.carriers.len()
    }

    /// The discrete energy, J: ½vᵀMv + ½dᵀKd of the beam, ½m q̇² + ½k q²
    /// of each mass, minus the potential of the constant loads (distributed
    /// load, preload and gravity on the masses, standing forces).
    ///
    /// With ρ∞ = 1 generalized-α is the trapezoidal rule, for which
    /// E_{n+1} − E_n = Δdᵀ f̄ exactly (linear system); a contact force whose
    /// point does not move and that closes g_{n+1} = g_n = 0 does no work, so
    /// E is conserved to round-off while contacts do not switch; with ρ∞ < 1
    /// it does not grow. Moving loads do work, so E is not conserved then.
    /// Allocates a scratch vector: for checks, not for the step loop.
    pub fn energy(&self) -> Energy {
        let n = self.beam.n;
        let mut mv = vec![0.0; n];
        self.beam.mass.mul_acc(&self.v, 1.0, &mut mv);
        let mut kd = vec![0.0; n];
        self.beam.stiffness.mul_acc(&self.d, 1.0, &mut kd);
        let mut e = Energy::default();
        for i in 0..n {
            e.kinetic += 0.5 * self.v[i] * mv[i];
            e.strain += 0.5 * self.d[i] * kd[i];
            e.load_potential -= self.beam.load[i] * self.d[i];
        }
        for c in &self.carriers {
            match (c.props.kind, c.mass) {
                (_, Some(m)) => {
                    e.kinetic += 0.5 * m.m * m.v * m.v;
                    e.strain += 0.5 * m.k * m.q * m.q;
                    e.load_potential -= m.f0 * m.q;
                }
                (CarrierKind::Force { force }, None) => {
                    e.load_potential -= c.s * force * c.pv_g.dot(&self.d)
                }
                _ => {}
            }
        }
        e
    }

    /// Largest |λ| accepted before a run is taken as diverged, N.
    pub fn force_bound(&self) -> f64 {
        self.force_bound
    }

    /// True when x lies in the last element before a supported end (v = 0
    /// there): a carrier arriving at a support meets the beam's support
    /// corner, an impact the model has no law for (MODEL §6).
    pub fn near_support(&self, x: f64) -> bool {
        let h = self.beam.h;
        let held = |s: crate::scene::Support| s != crate::scene::Support::Free;
        (held(self.supports.0) && x < h) || (held(self.supports.1) && x > self.length - h)
    }

    /// Stop with a diagnosis if a recorded value is non-finite or absurd.
    ///
    /// The force bound is not applied in the last element before a support:
    /// there a mass that arrives with the beam under it still deflected is
    /// forced to w = 0 within one element, a genuine (refinement-dependent)
    /// impact of the model; `run` reports it as a warning instead.
    pub fn check(&self, s: &CarrierSample, carrier: usize) -> Result<()> {
        let bound = DISPLACEMENT_BOUND_IN_LENGTHS * self.length;
        let force_limit = if self.near_support(s.x) {
            f64::INFINITY
        } else {
            self.force_bound
        };
        let checks = [
            ("contact force λ (N)", s.force, force_limit),
            ("beam displacement under the carrier w (m)", s.w, bound),
            ("mass displacement q (m)", s.q, bound),
        ];
        for (name, value, limit) in checks {
            if !value.is_finite() || value.abs() > limit {
                let c = &self.carriers[carrier];
                let moving = !c.props.motion.is_stationary();
                let speed = c.props.motion.speed(self.t);
                let supersonic_mass = self.bilateral
                    && c.mass.is_some()
                    && self.wave_speed > 0.0
                    && speed > self.wave_speed;
                let cause = if self.placement == Placement::Alpha && moving {
                    "the gap is imposed at the α-level (contact.placement = \"alpha\"), which leaves an undamped step-to-step oscillation that a moving contact point drives unstable (MODEL §5); use contact.placement = \"end\"".to_string()
                } else if supersonic_mass {
                    format!(
                        "a mass held on the beam (bilateral) moves at V = {speed:.1} m/s, faster than the wave speed c = {:.1} m/s: a moving inertial load above the wave speed can be genuinely unstable (anomalous Doppler waves; Metrikine & Dieterman); growth that quickens as the mesh and step are refined is that instability, not the integrator",
                        self.wave_speed
                    )
                } else if !value.is_finite() {
                    format!(
                        "a non-finite value: check the scene's magnitudes and time.step = {} s",
                        self.dt
                    )
                } else {
                    format!(
                        "|{name}| exceeds {limit:e}: time.step = {} s may be too coarse for the contact dynamics, or the scene is physically unbounded",
                        self.dt
                    )
                };
                return Err(Error::Diverged {
                    step: self.step,
                    time: self.t,
                    quantity: format!("carrier {carrier}: {name}"),
                    value,
                    cause,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rho_one_is_the_study_s_parameter_set() {
        let ga = GenAlpha::from_rho_inf(1.0);
        assert_eq!(
            (ga.alpha_m, ga.alpha_f, ga.beta, ga.gamma),
            (0.5, 0.5, 0.25, 0.5)
        );
    }

    #[test]
    fn rho_zero_is_asymptotically_annihilating() {
        let ga = GenAlpha::from_rho_inf(0.0);
        assert_eq!((ga.alpha_m, ga.alpha_f), (-1.0, 0.0));
        assert_eq!(ga.gamma, 1.5);
        assert_eq!(ga.beta, 1.0);
    }
}

/// The constants of the update pass (MODEL §5, update and predictors).
#[derive(Debug, Clone, Copy)]
struct UpdateCoefs {
    dt: f64,
    gamma: f64,
    /// βΔt².
    bdt2: f64,
    /// (½ − β)Δt².
    c_pred: f64,
    alpha_f: f64,
    /// α′(1 − α_f)βΔt², the shift of ũ.
    c_shift: f64,
    /// α′ = α_m/(1 − α_m).
    alpha_p: f64,
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
    /// residual's operands, see `Integrator::step`). Element-wise, so it
    /// vectorizes when `acc` does.
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
            *v += c.dt * ((1.0 - c.gamma) * *a + c.gamma * acc);
            *d = *dp + c.bdt2 * acc;
            *a = acc;
            let next = *d + c.dt * *v + c.c_pred * acc;
            *dp = next;
            *u = (1.0 - c.alpha_f) * next + c.alpha_f * *d - c.c_shift * acc;
            *h = f - c.alpha_p * b0;
        }
    }
}
