//! `modal_exact`: exact propagation of every mode of a diagonal basis over
//! the step (MODEL §9.3; issue 24), on `mesh.kind = "galerkin"` or `"modal"`.
//!
//! In a mass-normalized diagonal basis each coordinate is an undamped
//! oscillator `η̈_j + ω_j² η_j = f_j(t)` (the beam has no damping, MODEL §1),
//! coupled to the others only through the contact force. Over a step its
//! motion is closed form once the load's shape within the step is fixed
//! ([`super::oscillator`]): the free vibration carries no time error and no
//! numerical dispersion, and the step is O(J) with no recurrence across
//! modes.
//!
//! ## The loads within a step, and the order
//!
//! * **Fixed loads** (the distributed load `p`, self-weight): held, exact.
//! * **A moving force F** (constant, a `force` carrier): its modal load
//!   `s F φ_j(x(t))` is taken linear in time between the samples at t_n
//!   and t_{n+1} (first-order hold of the path): second order in Δt, the
//!   error `∝ (β_j V Δt)²` largest in the highest modes; exact for a
//!   carrier at rest.
//! * **The contact force λ** of each mass carrier is **held over the step**:
//!   the unknown λ_{n+1} is its mean over [t_n, t_{n+1}], applied along the
//!   carrier's path (the same linear-in-time modal load as a moving force,
//!   `s λ (a0 φ(x_n) + a1 φ(x_{n+1}))` in η_{n+1}), and the gap is imposed
//!   at t_{n+1}. A force linear over the step, with the unknown its end
//!   sample, makes the multiplier obey λ_{n+1} ≈ −2 λ_n + … (the linear-
//!   acceleration weights of a compliant contact, 1/3 and 1/6): unstable,
//!   measured ×(−3.7) a step on the reference scene. Held, the
//!   multiplier recurrence has no λ_n term. Measured on the reference scene
//!   with a bilateral contact (tests/modal_exact.rs): the displacement
//!   under the carrier and the step-mean force both converge at **second
//!   order** in Δt (the mean force differs from the force at t_{n+1} by
//!   O(Δt): compare it as the step's mean, as generalized-α's force is the
//!   one at t_{n+1/2}).
//! * **The mass dof** `m q̈ + c q̇ + k q = k δ0 − s m g − λ` is propagated
//!   exactly under the held force ([`MassStep`]), dashpot included.
//!
//! So `g_{n+1} = g_free + W λ_{n+1}` with
//! `g_free = s φ(x_{n+1})ᵀ η_free − q_free` and
//! `W = s² Σ_j φ_j(x_{n+1}) (a0_j φ_j(x_n) + a1_j φ_j(x_{n+1})) + g_q`: sums
//! over modes, the pair every force-level law takes (Lagrange, penalty,
//! complementarity; MODEL §5, §6). The impact law is refused
//! (scene/validate.rs): an impulse on the gap rate has no place in a force
//! held over the step.
//!
//! ## One step, O(J) in three passes
//!
//! 1. Place each carrier: the previous `φ(x_{n+1})` becomes `φ(x_n)`
//!    (swapped, not copied) and `φ(x_{n+1})` is evaluated: without a
//!    transcendental call per mode on a galerkin basis
//!    ([`crate::analytic::FastShapes`]), from four rows of the FE modes on
//!    a modal one.
//! 2. The free step of every mode (and the moving forces), fused with the
//!    sums g_free and W when the scene has one contact and no moving force.
//! 3. The law, then every mode's update with the multipliers.
//!
//! Sums over modes are taken in [`LANES`] partial sums (mode j into lane
//! j mod 8) added in a fixed order, so the result does not depend on the
//! vector width the loop is compiled for; a run in a batch
//! ([`super::modal_batch`]) calls the same functions and gets the same
//! bits. Nothing is allocated after [`ModalExact::new`].

use std::sync::Arc;

use crate::analytic::FastShapes;
use crate::error::{Error, Result};
use crate::model::beam::{Basis, BeamModel, PointVector};
use crate::model::lanes::{self, LANES};
use crate::scene::CarrierKind;

use super::oscillator::{MassStep, ModeSteps};
use super::{State, Stepper, System};

/// What every run on one basis at one Δt shares (module docs): the modes'
/// step maps, the fixed load's share of them, and the fast shapes.
#[derive(Debug)]
pub struct ModalCoefs {
    /// The exact step maps of the J modes.
    pub steps: ModeSteps,
    /// (a0 + a1) p_j and (b0 + b1) p_j: the held distributed load's step
    /// (None when p = 0).
    held: Option<(Vec<f64>, Vec<f64>)>,
    /// The fast evaluator on a galerkin basis; `None` on a modal basis
    /// (its point vectors are four rows of the FE modes already).
    shapes: Option<FastShapes>,
}

impl ModalCoefs {
    /// Build the shared data for a diagonal basis (`beam`) at `dt`.
    pub fn new(beam: &BeamModel, dt: f64) -> Result<Self> {
        let shapes = match &beam.basis {
            Basis::Galerkin(m) => Some(FastShapes::new(m)),
            Basis::Modal { .. } => None,
            Basis::Elements => {
                return Err(Error::invalid(
                    "integrator.method",
                    "\"modal_exact\"",
                    "needs a diagonal basis (mesh.kind = \"galerkin\" or \"modal\")",
                ));
            }
        };
        let omega: Vec<f64> = (0..beam.n)
            .map(|j| (beam.stiffness.get(j, j) / beam.mass.get(j, j)).sqrt())
            .collect();
        let steps = ModeSteps::new(&omega, dt);
        let held = beam.load.iter().any(|p| *p != 0.0).then(|| {
            let a = (0..beam.n)
                .map(|j| (steps.a0[j] + steps.a1[j]) * beam.load[j])
                .collect();
            let b = (0..beam.n)
                .map(|j| (steps.b0[j] + steps.b1[j]) * beam.load[j])
                .collect();
            (a, b)
        });
        Ok(ModalCoefs {
            steps,
            held,
            shapes,
        })
    }

    /// J.
    pub fn modes(&self) -> usize {
        self.steps.len()
    }

    /// `φ(x)` of the basis into `pv` (the fast shapes, or the FE modes'
    /// interpolation on a modal basis).
    #[inline]
    pub fn place(&self, beam: &BeamModel, x: f64, pv: &mut PointVector) {
        match &self.shapes {
            Some(f) => f.values_into(x, pv.dense_mut()),
            None => beam.point_vector_into(x, false, pv),
        }
    }
}

/// A `modal_exact` stepper for one run (module docs).
pub struct ModalExact {
    coefs: Arc<ModalCoefs>,
    /// The exact step of each contact's mass dof under a held force.
    mass_steps: Vec<MassStep>,
    /// Free gaps and Delassus matrix of the step (scratch).
    g: Vec<f64>,
    w: Vec<f64>,
}

impl ModalExact {
    /// The stepper for a run on a diagonal basis, its coefficients built
    /// here (a run alone).
    pub fn new(sys: &mut System) -> Result<Self> {
        let coefs = Arc::new(ModalCoefs::new(sys.beam(), sys.dt())?);
        Ok(Self::with_coefs(coefs, sys))
    }

    /// The stepper with coefficients shared by several runs on the same
    /// basis and Δt (a batch). Re-evaluates the carriers' point vectors at
    /// t = 0 with the basis's fast shapes, so every step reads shapes of one
    /// kind.
    pub fn with_coefs(coefs: Arc<ModalCoefs>, sys: &mut System) -> Self {
        let dt = sys.dt();
        let mass_steps = sys
            .masses()
            .iter()
            .map(|m| MassStep::new(m.m, m.k, m.c, dt))
            .collect();
        let nc = sys.contacts();
        let beam = &sys.beam;
        for c in sys.carriers.iter_mut() {
            let x0 = c.props.motion.position(0.0);
            coefs.place(beam, x0, &mut c.pv_f);
            coefs.place(beam, x0, &mut c.pv_g);
        }
        ModalExact {
            coefs,
            mass_steps,
            g: vec![0.0; nc],
            w: vec![0.0; nc * nc],
        }
    }
}

impl Stepper for ModalExact {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        step(
            &self.coefs,
            &self.mass_steps,
            (&mut self.g, &mut self.w),
            sys,
            st,
        )
    }
}

/// One step of one run (module docs), for a run alone and each run of a
/// batch alike.
pub(crate) fn step(
    coefs: &ModalCoefs,
    mass_steps: &[MassStep],
    (g, w): (&mut [f64], &mut [f64]),
    sys: &mut System,
    st: &mut State,
) -> Result<()> {
    let t1 = st.next_time(sys.dt);
    // 1. place: φ(x_n) ← φ(x_{n+1}) of the last step, then φ(x_{n+1})
    {
        let beam = &sys.beam;
        for c in sys.carriers.iter_mut() {
            std::mem::swap(&mut c.pv_f, &mut c.pv_g);
            coefs.place(beam, c.props.motion.position(t1), &mut c.pv_g);
        }
    }
    let m = &coefs.steps;
    let nc = sys.contacts();
    let single = nc == 1 && sys.carriers.len() == 1;
    // 2. the free step (and, for one contact alone, its g_free and W sums)
    let mut pair = (0.0, 0.0);
    if single {
        let c = &sys.carriers[0];
        pair = free_with_pair(m, coefs.held.as_ref(), st, c.pv_f.dense(), c.pv_g.dense());
    } else {
        free(m, coefs.held.as_ref(), st);
        for c in &sys.carriers {
            if let CarrierKind::Force { force } = c.props.kind {
                add_path_load(m, c.s * force, c.pv_f.dense(), c.pv_g.dense(), st);
            }
        }
    }
    if nc > 0 {
        // the mass dofs' free step (their constant force held)
        for (j, (ms, dof)) in mass_steps.iter().zip(sys.masses()).enumerate() {
            (st.q[j], st.q_dot[j]) = ms.apply((st.q[j], st.q_dot[j]), dof.f0);
        }
        if single {
            let s = sys.carriers[0].s;
            g[0] = s * pair.0 - st.q[0];
            w[0] = s * s * pair.1 + mass_steps[0].g[0];
        } else {
            for ci in &sys.carriers {
                let Some(i) = ci.contact else { continue };
                g[i] = ci.s * lanes::dot(ci.pv_g.dense(), &st.d) - st.q[i];
                for cj in &sys.carriers {
                    let Some(j) = cj.contact else { continue };
                    let wij = path_dot(m, ci.pv_g.dense(), cj.pv_f.dense(), cj.pv_g.dense());
                    w[i * nc + j] =
                        ci.s * cj.s * wij + if i == j { mass_steps[i].g[0] } else { 0.0 };
                }
            }
        }
        // 3. the law, then the update with the multipliers
        sys.solve_formed(g, w, st)?;
        for c in &sys.carriers {
            let Some(j) = c.contact else { continue };
            let lambda = sys.lambda[j];
            if lambda != 0.0 {
                add_path_load(m, c.s * lambda, c.pv_f.dense(), c.pv_g.dense(), st);
            }
            st.q[j] -= mass_steps[j].g[0] * lambda;
            st.q_dot[j] -= mass_steps[j].g[1] * lambda;
        }
    }
    Ok(())
}

/// Calls the `$kernel` (an `#[inline(always)]` function) through a copy of
/// it compiled for AVX2 when the CPU has it: the same operations in the
/// same order either way (no fused multiply–add), so the same bits.
macro_rules! with_avx2 {
    ($(#[$doc:meta])* fn $name:ident => $kernel:ident ($($arg:ident: $ty:ty),*) $(-> $ret:ty)?) => {
        $(#[$doc])*
        fn $name($($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                fn avx2($($arg: $ty),*) $(-> $ret)? {
                    $kernel($($arg),*)
                }
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU supports AVX2 (checked just above).
                    return unsafe { avx2($($arg),*) };
                }
            }
            $kernel($($arg),*)
        }
    };
}

with_avx2! {
    /// The free step of every mode: `[η, η̇] ← E [η, η̇]` plus the held load.
    fn free => free_kernel(m: &ModeSteps, held: Option<&(Vec<f64>, Vec<f64>)>, st: &mut State)
}

#[inline(always)]
fn free_kernel(m: &ModeSteps, held: Option<&(Vec<f64>, Vec<f64>)>, st: &mut State) {
    let j = m.len();
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    let (c, sw, ws) = (&m.cos[..j], &m.sin_over_omega[..j], &m.minus_omega_sin[..j]);
    for i in 0..j {
        let (e, ev) = (d[i], v[i]);
        d[i] = c[i] * e + sw[i] * ev;
        v[i] = ws[i] * e + c[i] * ev;
    }
    if let Some((hp, hv)) = held {
        for i in 0..j {
            d[i] += hp[i];
            v[i] += hv[i];
        }
    }
}

/// [`free`] fused with the two sums a single contact needs:
/// `Σ φ_j(x_{n+1}) η_free,j` and `Σ φ_j(x_{n+1}) (a0_j φ_j(x_n) + a1_j φ_j(x_{n+1}))`,
/// in [`LANES`] partial sums; AVX2 where the CPU has it, the same
/// operations lane by lane either way.
fn free_with_pair(
    m: &ModeSteps,
    held: Option<&(Vec<f64>, Vec<f64>)>,
    st: &mut State,
    pn: &[f64],
    pn1: &[f64],
) -> (f64, f64) {
    if held.is_some() {
        // with a distributed load: the free step, then the two sums apart
        free(m, held, st);
        return (lanes::dot(pn1, &st.d), path_dot(m, pn1, pn, pn1));
    }
    let j = m.len();
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    let (pn, pn1) = (&pn[..j], &pn1[..j]);
    let (mut gs, mut ws) = ([0.0; LANES], [0.0; LANES]);
    let full = j / LANES * LANES;
    #[cfg(target_arch = "x86_64")]
    let avx2 = std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    let avx2 = false;
    if avx2 {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: the CPU supports AVX2 (checked just above); every slice
        // has at least `full` entries.
        unsafe {
            free_with_pair_avx2(m, (d, v), (pn, pn1), full, (&mut gs, &mut ws))
        };
    } else {
        for i in 0..full {
            let l = i % LANES;
            let (e, ev) = (d[i], v[i]);
            let e1 = m.cos[i] * e + m.sin_over_omega[i] * ev;
            d[i] = e1;
            v[i] = m.minus_omega_sin[i] * e + m.cos[i] * ev;
            gs[l] += pn1[i] * e1;
            ws[l] += pn1[i] * (m.a0[i] * pn[i] + m.a1[i] * pn1[i]);
        }
    }
    for i in full..j {
        let (e, ev) = (d[i], v[i]);
        let e1 = m.cos[i] * e + m.sin_over_omega[i] * ev;
        d[i] = e1;
        v[i] = m.minus_omega_sin[i] * e + m.cos[i] * ev;
        gs[i - full] += pn1[i] * e1;
        ws[i - full] += pn1[i] * (m.a0[i] * pn[i] + m.a1[i] * pn1[i]);
    }
    (lanes::reduce(&gs), lanes::reduce(&ws))
}

/// The first `full` modes of [`free_with_pair`], four at a time.
///
/// # Safety
/// The CPU supports AVX2 and every slice has at least `full` entries
/// (`full` a multiple of [`LANES`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn free_with_pair_avx2(
    m: &ModeSteps,
    (d, v): (&mut [f64], &mut [f64]),
    (pn, pn1): (&[f64], &[f64]),
    full: usize,
    (gs, ws): (&mut [f64; LANES], &mut [f64; LANES]),
) {
    use std::arch::x86_64::*;
    // SAFETY (whole body): loads and stores at i .. i + 4 < full.
    unsafe {
        let ld = |x: &[f64], i: usize| _mm256_loadu_pd(x.as_ptr().add(i));
        let mut g = [
            _mm256_loadu_pd(gs.as_ptr()),
            _mm256_loadu_pd(gs.as_ptr().add(4)),
        ];
        let mut w = [
            _mm256_loadu_pd(ws.as_ptr()),
            _mm256_loadu_pd(ws.as_ptr().add(4)),
        ];
        let mut i = 0;
        while i < full {
            for h in 0..2 {
                let k = i + 4 * h;
                let (e, ev) = (ld(d, k), ld(v, k));
                let c = ld(&m.cos, k);
                let e1 = _mm256_add_pd(
                    _mm256_mul_pd(c, e),
                    _mm256_mul_pd(ld(&m.sin_over_omega, k), ev),
                );
                let v1 = _mm256_add_pd(
                    _mm256_mul_pd(ld(&m.minus_omega_sin, k), e),
                    _mm256_mul_pd(c, ev),
                );
                _mm256_storeu_pd(d.as_mut_ptr().add(k), e1);
                _mm256_storeu_pd(v.as_mut_ptr().add(k), v1);
                let q = ld(pn1, k);
                g[h] = _mm256_add_pd(g[h], _mm256_mul_pd(q, e1));
                let z = _mm256_add_pd(
                    _mm256_mul_pd(ld(&m.a0, k), ld(pn, k)),
                    _mm256_mul_pd(ld(&m.a1, k), q),
                );
                w[h] = _mm256_add_pd(w[h], _mm256_mul_pd(q, z));
            }
            i += LANES;
        }
        _mm256_storeu_pd(gs.as_mut_ptr(), g[0]);
        _mm256_storeu_pd(gs.as_mut_ptr().add(4), g[1]);
        _mm256_storeu_pd(ws.as_mut_ptr(), w[0]);
        _mm256_storeu_pd(ws.as_mut_ptr().add(4), w[1]);
    }
}

with_avx2! {
    /// Add a force `f` (N) held over the step along the carrier's path into
    /// every mode: `η += f (a0 φ(x_n) + a1 φ(x_{n+1}))`, `η̇ += f (b0 φ(x_n) + b1 φ(x_{n+1}))`.
    fn add_path_load => add_path_load_kernel(m: &ModeSteps, f: f64, pn: &[f64], pn1: &[f64], st: &mut State)
}

#[inline(always)]
fn add_path_load_kernel(m: &ModeSteps, f: f64, pn: &[f64], pn1: &[f64], st: &mut State) {
    let j = m.len();
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    let (a0, a1, b0, b1) = (&m.a0[..j], &m.a1[..j], &m.b0[..j], &m.b1[..j]);
    let (pn, pn1) = (&pn[..j], &pn1[..j]);
    for i in 0..j {
        d[i] += f * (a0[i] * pn[i] + a1[i] * pn1[i]);
        v[i] += f * (b0[i] * pn[i] + b1[i] * pn1[i]);
    }
}

with_avx2! {
    /// `Σ_j r_j (a0_j p_j + a1_j q_j)`: a contact row against a unit force
    /// held along a carrier's path (φ(x_n) = p, φ(x_{n+1}) = q), in
    /// [`LANES`] partial sums.
    fn path_dot => path_dot_kernel(m: &ModeSteps, r: &[f64], p: &[f64], q: &[f64]) -> f64
}

#[inline(always)]
fn path_dot_kernel(m: &ModeSteps, r: &[f64], p: &[f64], q: &[f64]) -> f64 {
    let j = m.len();
    let mut acc = [0.0; LANES];
    let full = j / LANES * LANES;
    for i in 0..full {
        acc[i % LANES] += r[i] * (m.a0[i] * p[i] + m.a1[i] * q[i]);
    }
    for i in full..j {
        acc[i - full] += r[i] * (m.a0[i] * p[i] + m.a1[i] * q[i]);
    }
    lanes::reduce(&acc)
}
