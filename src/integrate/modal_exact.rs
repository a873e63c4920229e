//! `modal_exact`: exact propagation of every mode of a diagonal basis over
//! the step (MODEL §9.3), on `mesh.kind = "galerkin"` or `"modal"`.
//!
//! In a mass-normalized diagonal basis each coordinate is an oscillator
//! `η̈_j + c_j η̇_j + ω_j² η_j = f_j(t)` (MODEL §1; c_j = 0 undamped, Rayleigh
//! damping in `damped_modes.rs`), coupled to the others only through the
//! contact force. Once the load's shape within the step is fixed its motion
//! is closed form ([`super::oscillator`]): no time error and no dispersion in
//! the free vibration, and a step is O(J). Fixed loads are held (exact);
//! moving forces and a manufactured source (MODEL §11) are linear in time
//! between t_n and t_{n+1} (second order in Δt); the mass dof is propagated
//! exactly under the held force ([`MassStep`]).
//!
//! Key decision: the contact force λ is **held over the step** (λ_{n+1} its
//! mean) with the gap imposed at t_{n+1}, so `g_{n+1} = g_free + W λ_{n+1}`,
//! the pair every force-level law takes (MODEL §5, §6); a force linear over
//! the step makes the multiplier recurrence unstable. The held force keeps a
//! neutral (−1)ⁿ zigzag of amplitude O(Δt), so the **reported** force is the
//! mean of the two held forces around t_n (`Multipliers::Held`): second
//! order, as tests/modal_exact.rs asserts. The impact law re-takes a
//! re-contact step with the instant located and an impulse there
//! (`modal_impact.rs`).
//!
//! With one contact the update with λ is deferred into the next step's single
//! pass over the modes ([`ModalExact::step_deferred`]); a whole run
//! (`crate::run`, alone or in a batch, `modal_batch.rs`) defers and reads
//! its samples through [`ModalExact::displacement_at`], a step taken by
//! [`Stepper::step`] settles at once ([`ModalExact::settle`]): the same
//! bits either way, as are AVX2 + FMA and `mul_add` lanes
//! (`crate::numeric::lanes`). Nothing is allocated after [`ModalExact::new`].

use std::ops::Range;
use std::sync::Arc;

use crate::analytic::FastShapes;
use crate::error::{Error, Result};
use crate::model::banded::SymBand;
use crate::model::beam::{Basis, BeamModel, PointVector};
use crate::numeric::lanes::{self, LANES};
use crate::scene::CarrierKind;

use super::modal_cruise::Cruise;
use super::modal_impact::LocatedImpact;
use super::modal_kernels::{
    CoefBlock, FusedPass, HeldStep, ModeState, PairSums, PathShapes, Phasors, add_path_load,
    coef_blocks, free, free_with_pair, path, path_dot,
};
#[cfg(target_arch = "x86_64")]
use super::modal_kernels::{fused_free_pair_avx2, fused_free_pair_avx512, shapes_free_pair_avx2};
#[cfg(target_arch = "x86_64")]
use super::modal_table_avx512::shapes_free_pair_avx512;
use super::oscillator::{MassStep, ModeSteps};
use super::state::State;
use super::step_map::Multipliers;
use super::stepper::Stepper;
use super::system::System;
#[cfg(target_arch = "x86_64")]
use crate::analytic::Blocks;

/// What every run on one basis at one Δt shares (module docs): the modes'
/// step maps, the fixed load's share of them, and the fast shapes.
#[derive(Debug)]
pub(crate) struct ModalCoefs {
    /// The exact step maps of the J modes.
    pub steps: ModeSteps,
    /// (a0 + a1) p_j and (b0 + b1) p_j: the held distributed load's step
    /// (None when p = 0).
    held: Option<(Vec<f64>, Vec<f64>)>,
    /// The fast evaluator on a galerkin basis; `None` on a modal basis
    /// (its point vectors are four rows of the FE modes already).
    shapes: Option<FastShapes>,
    /// True when the modes are damped (`[beam] damping`): their velocity
    /// row has its own diagonal, which only the scalar free step reads.
    damped: bool,
    /// `steps`' coefficients in blocks of eight modes, for the AVX-512
    /// cruise pass ([`coef_blocks`]).
    blocks: Vec<CoefBlock>,
    /// ω_j, rad/s (a located re-contact's maps over its own sub-steps,
    /// `modal_impact.rs`).
    omega: Vec<f64>,
}

impl ModalCoefs {
    /// Build the shared data for a diagonal basis (`beam`) at `dt`.
    pub fn new(beam: &BeamModel, dt: f64) -> Result<Self> {
        Self::with_damping(beam, None, dt)
    }

    /// [`ModalCoefs::new`] with the basis's damping matrix C, diagonal
    /// (Rayleigh damping, `c_j = α + βω_j²`; docs/lines.md §10.4): each
    /// mode is then propagated as an exact damped oscillator
    /// ([`ModeSteps::damped`]).
    pub fn with_damping(beam: &BeamModel, damping: Option<&SymBand>, dt: f64) -> Result<Self> {
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
            .map(|j| {
                (beam.stiffness.get(j, j) / beam.mass.get(j, j))
                    .max(0.0)
                    .sqrt()
            })
            .collect();
        let steps = match damping {
            None => ModeSteps::new(&omega, dt),
            Some(c) => {
                debug_assert_eq!(c.bandwidth(), 0, "C is diagonal in a modal basis");
                let c: Vec<f64> = (0..beam.n).map(|j| c.get(j, j)).collect();
                ModeSteps::damped(&omega, &c, dt)
            }
        };
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
            blocks: coef_blocks(&steps),
            steps,
            held,
            shapes,
            damped: damping.is_some(),
            omega,
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
pub(crate) struct ModalExact {
    coefs: Arc<ModalCoefs>,
    /// The exact step of each contact's mass dof under a held force.
    mass_steps: Vec<MassStep>,
    /// Free gaps and Delassus matrix of the step (scratch).
    g: Vec<f64>,
    w: Vec<f64>,
    /// The phasors of a single contact's carrier at constant speed (fast
    /// shapes only; `modal_cruise.rs`).
    cruise: Option<Cruise>,
    /// A boundary layer's shapes `φ(x_{n+1})` before its fused pass
    /// stores them (J; scratch, fast shapes only).
    layered: Vec<f64>,
    /// The last step's contact force f = sλ (N), held along the carrier's
    /// path from `pv_f` to `pv_g`, not yet added into `d` and `v` (a step
    /// taken by [`ModalExact::step_deferred`]; module docs, "Deferred
    /// update").
    pending: Option<f64>,
    /// A manufactured scene's source samples (`None` without one).
    source: Option<SourceLoads>,
    /// The located re-contacts of an impact law (`contact.formulation =
    /// "impact"`, `modal_impact.rs`); `None` for the study's law.
    impact: Option<LocatedImpact>,
}

/// A manufactured source's modal load sampled at t_n and t_{n+1} (MODEL
/// §11): the smooth part plus each carrier's point load at its position,
/// applied with the first-order hold of a moving force (second order in
/// Δt, exact for a load linear in time). J each; a step's sample at
/// t_{n+1} is the next step's at t_n, so each step evaluates one.
#[derive(Debug, Clone)]
struct SourceLoads {
    at_n: Vec<f64>,
    at_n1: Vec<f64>,
    /// The time `at_n1` was sampled at, s (NaN before the first step).
    t_n1: f64,
}

impl ModalExact {
    /// The stepper for a run on a diagonal basis, its coefficients built
    /// here (a run alone).
    pub fn new(sys: &mut System) -> Result<Self> {
        let coefs = Arc::new(ModalCoefs::with_damping(
            sys.beam(),
            sys.damping(),
            sys.dt(),
        )?);
        Self::with_coefs(coefs, sys)
    }

    /// The stepper with coefficients shared by several runs on the same
    /// basis and Δt (a batch). Re-evaluates the carriers' point vectors at
    /// t = 0 with the basis's fast shapes, so every step reads shapes of one
    /// kind. Refuses an impact law on a scene it does not carry
    /// ([`LocatedImpact::new`]).
    pub fn with_coefs(coefs: Arc<ModalCoefs>, sys: &mut System) -> Result<Self> {
        let dt = sys.dt();
        let mass_steps = sys
            .masses()
            .iter()
            .map(|m| MassStep::new(m.m, m.k, m.c, dt))
            .collect();
        let nc = sys.contacts();
        sys.set_multipliers(Multipliers::Held);
        let beam = &sys.physics.beam;
        for c in sys.physics.carriers.iter_mut() {
            let x0 = c.props.motion.position(0.0);
            coefs.place(beam, x0, &mut c.pv_f);
            coefs.place(beam, x0, &mut c.pv_g);
        }
        let j = coefs.modes();
        let source = sys.has_source().then(|| SourceLoads {
            at_n: vec![0.0; j],
            at_n1: vec![0.0; j],
            t_n1: f64::NAN,
        });
        let cruise = coefs.shapes.as_ref().map(|_| Cruise::new(j));
        let impact = LocatedImpact::new(&coefs.omega, coefs.damped, sys)?;
        Ok(ModalExact {
            coefs,
            mass_steps,
            g: vec![0.0; nc],
            w: vec![0.0; nc * nc],
            cruise,
            layered: vec![0.0; j],
            pending: None,
            source,
            impact,
        })
    }
}

impl ModalExact {
    /// One step whose contact update may be left pending: the next step's
    /// first pass adds it on its way (one pass over the modes a step, not
    /// two), so `st.d` and `st.v` are not the step's state until
    /// [`ModalExact::settle`]; the carrier's sample (`r_gᵀd`) and
    /// [`ModalExact::displacement_at`] account for it. The same bits as
    /// [`Stepper::step`] once settled (a batch's runs, `modal_batch.rs`).
    pub fn step_deferred(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        step(self, sys, st)
    }

    /// Add a pending contact update into `st` (module docs, "Deferred
    /// update"): the operations a step would have taken, so the same bits.
    pub fn settle(&mut self, sys: &System, st: &mut State) {
        if let Some(f) = self.pending.take() {
            let c = &sys.physics.carriers[0];
            let all = 0..self.coefs.modes();
            let path = PathShapes::of(c);
            add_path_load(&self.coefs.steps, f, path, st, all, lanes::avx2_fma());
        }
    }

    /// `rᵀd` of the run's state as settled ([`ModalExact::settle`]), without
    /// settling it: each entry as the update would leave it, summed as
    /// [`PointVector::dot`] sums (the same bits).
    pub fn displacement_at(&self, sys: &System, st: &State, pv: &PointVector) -> f64 {
        let Some(f) = self.pending else {
            return pv.dot(&st.d);
        };
        let m = &self.coefs.steps;
        let c = &sys.physics.carriers[0];
        let (p, q) = (c.pv_f.dense(), c.pv_g.dense());
        let j = m.len();
        let settled = |i: usize| {
            if i < j {
                f.mul_add(path(m.a0[i], p[i], m.a1[i], q[i]), st.d[i])
            } else {
                st.d[i]
            }
        };
        pv.dot_by(settled)
    }
}

impl Stepper for ModalExact {
    fn step(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        step(self, sys, st)?;
        ModalExact::settle(self, sys, st);
        Ok(())
    }

    fn step_deferred(&mut self, sys: &mut System, st: &mut State) -> Result<()> {
        ModalExact::step_deferred(self, sys, st)
    }

    fn settle(&mut self, sys: &System, st: &mut State) {
        ModalExact::settle(self, sys, st)
    }

    fn displacement_at(&self, sys: &System, st: &State, pv: &PointVector) -> f64 {
        ModalExact::displacement_at(self, sys, st, pv)
    }
}

/// True when a run's step takes the fused single-contact path (one
/// carrier, a mass on a spring): the free step and its two sums in one
/// pass.
#[inline(always)]
fn is_single(sys: &System) -> bool {
    sys.contacts() == 1 && sys.physics.carriers.len() == 1
}

/// Phase 1: each carrier's previous `φ(x_{n+1})` becomes `φ(x_n)` (swapped,
/// not copied) and `φ(x_{n+1})` is evaluated at t_{n+1}.
#[inline(always)]
fn place(coefs: &ModalCoefs, sys: &mut System, st: &State) {
    let t1 = st.next_time(sys.physics.dt);
    let beam = &sys.physics.beam;
    for c in sys.physics.carriers.iter_mut() {
        std::mem::swap(&mut c.pv_f, &mut c.pv_g);
        coefs.place(beam, c.props.motion.position(t1), &mut c.pv_g);
    }
}

/// Phase 2 of a single-contact run over modes `range` (its start a
/// multiple of [`LANES`]): the free step and the pair's partial sums.
#[inline(always)]
fn free_pair_range(
    coefs: &ModalCoefs,
    sys: &System,
    st: &mut State,
    range: Range<usize>,
    sums: &mut PairSums,
    vector: bool,
) {
    let c = &sys.physics.carriers[0];
    let path = PathShapes::of(c);
    free_with_pair(
        &coefs.steps,
        coefs.held.as_ref(),
        st,
        path,
        range,
        sums,
        vector,
    );
}

/// Phases 1 and 2 of a single-contact run: place the carrier and take the
/// free step with its two sums. On a galerkin basis with AVX2 + FMA in one
/// pass: each block of [`crate::analytic::SHAPE_BLOCK`] shapes `φ(x_{n+1})`
/// is stored and used by the free step of its modes while in registers
/// (module docs, "One step"); within a clamped end's boundary layer, the
/// blocks a layer row reaches take their shapes whole first, then their
/// fused pass (with AVX-512F one pass of eight modes a register, the layer
/// terms added in registers: `modal_table_avx512.rs`); at constant speed the shapes are rotated phasors
/// ([`rotate_free_pair`]). A deferred update (`pass.deferred`) is added by
/// the same passes. The same operations as separate passes, so the same
/// bits.
#[inline(always)]
fn place_free_pair(
    coefs: &ModalCoefs,
    pass: Pass,
    sys: &mut System,
    st: &mut State,
    sums: &mut PairSums,
    vector: bool,
) {
    let Pass {
        cruise,
        layered,
        deferred,
    } = pass;
    let (Some(shapes), Some(cruise)) = (&coefs.shapes, cruise) else {
        place_free_pair_tables(coefs, deferred, layered, sys, st, sums, vector);
        return;
    };
    let t1 = st.next_time(sys.physics.dt);
    let motion = &sys.physics.carriers[0].props.motion;
    let x1 = motion.position(t1);
    match motion.uniform_speed(st.t, t1) {
        Some(speed) if !shapes.in_layer(x1) => {
            if cruise.can_rotate(st.step, speed) {
                rotate_free_pair(coefs, cruise, deferred, sys, st, sums, vector);
            } else {
                place_free_pair_tables(coefs, deferred, layered, sys, st, sums, vector);
                cruise.restart(shapes, x1, st.step, speed, sys.physics.dt);
            }
        }
        _ => {
            cruise.invalidate();
            place_free_pair_tables(coefs, deferred, layered, sys, st, sums, vector);
        }
    }
}

/// Phases 1 and 2 of a single-contact run at constant speed
/// (`modal_cruise.rs`): each mode's shape by one complex product of its
/// phasor, used at once by its free step and the two sums (AVX2 + FMA,
/// eight modes at a time, where `vector`), the last J mod 8 modes by the
/// same operations in scalar: the same bits either way.
#[inline(always)]
fn rotate_free_pair(
    coefs: &ModalCoefs,
    cruise: &mut Cruise,
    deferred: Option<f64>,
    sys: &mut System,
    st: &mut State,
    sums: &mut PairSums,
    vector: bool,
) {
    let j = coefs.modes();
    let c = &mut sys.physics.carriers[0];
    std::mem::swap(&mut c.pv_f, &mut c.pv_g);
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if vector {
        let full = j / LANES * LANES;
        let (fi, rr, ri) = cruise.parts();
        let pass = FusedPass {
            m: &coefs.steps,
            modes: ModeState {
                d: &mut st.d[..j],
                v: &mut st.v[..j],
            },
            pn: &c.pv_f.dense()[..j],
            pn1: &mut c.pv_g.dense_mut()[..j],
            held: HeldStep::of(coefs.held.as_ref(), j),
            sums: &mut *sums,
        };
        let phasors = Phasors {
            fi: &mut fi[..j],
            rr: &rr[..j],
            ri: &ri[..j],
        };
        let blocks = &coefs.blocks[..];
        // SAFETY: `vector` is true only where the CPU has AVX2 and FMA,
        // the AVX-512 kernel only where it has AVX-512F too; every slice
        // holds J ≥ full, a multiple of LANES.
        unsafe {
            match (deferred, lanes::avx512()) {
                (Some(f), true) => {
                    fused_free_pair_avx512::<true, true>(pass, blocks, phasors, full, f)
                }
                (None, true) => {
                    fused_free_pair_avx512::<true, false>(pass, blocks, phasors, full, 0.0)
                }
                (Some(f), false) => fused_free_pair_avx2::<true, true>(pass, phasors, full, f),
                (None, false) => fused_free_pair_avx2::<true, false>(pass, phasors, full, 0.0),
            }
        };
        done = full;
    }
    cruise.rotated(st.step);
    if done == j {
        // J a multiple of LANES: no last partial vector
        return;
    }
    if let Some(f) = deferred {
        // the rest of the deferred update, before their shapes overwrite
        // φ(x_{n−1}): from φ(x_{n−1}) (now pv_g) to φ(x_n) (now pv_f)
        let path = PathShapes {
            at_n: c.pv_g.dense(),
            at_n1: c.pv_f.dense(),
        };
        add_path_load(&coefs.steps, f, path, st, done..j, false);
    }
    cruise.rotate_range(c.pv_f.dense(), c.pv_g.dense_mut(), done..j);
    free_pair_range(coefs, sys, st, done..j, sums, vector);
}

/// What a single-contact step's first pass carries besides the state: the
/// carrier's cruise, room for a boundary layer's shapes, and the last
/// step's deferred update.
struct Pass<'a> {
    cruise: Option<&'a mut Cruise>,
    layered: &'a mut [f64],
    deferred: Option<f64>,
}

/// [`place_free_pair`] with the shapes from the tables.
#[inline(always)]
fn place_free_pair_tables(
    coefs: &ModalCoefs,
    deferred: Option<f64>,
    layered: &mut [f64],
    sys: &mut System,
    st: &mut State,
    sums: &mut PairSums,
    vector: bool,
) {
    let j = coefs.modes();
    #[cfg(target_arch = "x86_64")]
    if vector && let Some(shapes) = &coefs.shapes {
        let t1 = st.next_time(sys.physics.dt);
        let c = &mut sys.physics.carriers[0];
        if let Some(mut blocks) = shapes.blocks_at(c.props.motion.position(t1)) {
            std::mem::swap(&mut c.pv_f, &mut c.pv_g);
            let full = blocks.full();
            if let Some(f) = deferred {
                // the deferred update of the tail, whose shapes are stored
                // before its free step: from φ(x_{n−1}) (now pv_g) to
                // φ(x_n) (now pv_f); the blocks add theirs in their pass
                let path = PathShapes {
                    at_n: c.pv_g.dense(),
                    at_n1: c.pv_f.dense(),
                };
                add_path_load(&coefs.steps, f, path, st, full..j, vector);
            }
            let pn1 = &mut c.pv_g.dense_mut()[..j];
            let pn = &c.pv_f.dense()[..j];
            if lanes::avx512() {
                // one pass in AVX-512 registers, the boundary layer's
                // terms added to each block as it is made
                let pass = FusedPass {
                    m: &coefs.steps,
                    modes: ModeState {
                        d: &mut st.d[..j],
                        v: &mut st.v[..j],
                    },
                    pn,
                    pn1: &mut *pn1,
                    held: HeldStep::of(coefs.held.as_ref(), j),
                    sums: &mut *sums,
                };
                let table = &coefs.blocks[..];
                // SAFETY: the CPU has AVX-512F (checked just above); every
                // slice holds J ≥ full, `table` ⌊J/8⌋ ≥ full / 8 blocks.
                unsafe {
                    match deferred {
                        Some(f) => shapes_free_pair_avx512::<true>(&mut blocks, pass, table, f),
                        None => shapes_free_pair_avx512::<false>(&mut blocks, pass, table, 0.0),
                    }
                };
            } else {
                let path = (pn, &mut *pn1);
                // SAFETY: `vector` is true only where the CPU has AVX2 and
                // FMA; `layered` and every slice hold J.
                unsafe {
                    place_layered_blocks(coefs, deferred, layered, &mut blocks, st, path, sums)
                };
            }
            blocks.tail_into(&mut pn1[full..]);
            let c = &sys.physics.carriers[0];
            free_with_pair(
                &coefs.steps,
                coefs.held.as_ref(),
                st,
                PathShapes::of(c),
                full..j,
                sums,
                vector,
            );
            return;
        }
    }
    if let Some(f) = deferred {
        // settled first: φ(x_{n−1}) in pv_f, φ(x_n) in pv_g before `place`
        let c = &sys.physics.carriers[0];
        add_path_load(&coefs.steps, f, PathShapes::of(c), st, 0..j, vector);
    }
    place(coefs, sys, st);
    free_pair_range(coefs, sys, st, 0..j, sums, vector);
}

/// Modes `0 .. blocks.full()` of [`place_free_pair_tables`] in AVX2
/// registers: within a clamped end's boundary layer the blocks a layer
/// row reaches take their shapes whole first (into `layered`), then one
/// fused pass; the other blocks are evaluated and taken block by block.
///
/// # Safety
/// The CPU supports AVX2 and FMA; `layered` and every slice hold J.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn place_layered_blocks(
    coefs: &ModalCoefs,
    deferred: Option<f64>,
    layered: &mut [f64],
    blocks: &mut Blocks,
    st: &mut State,
    (pn, pn1): (&[f64], &mut [f64]),
    sums: &mut PairSums,
) {
    let j = coefs.modes();
    let held = HeldStep::of(coefs.held.as_ref(), j);
    // within a clamped end's boundary layer, the blocks a layer row
    // reaches first: their shapes whole (into `layered`), then one fused
    // pass (the deferred update, the free step, the sums, the shapes
    // stored)
    // SAFETY: AVX2 and FMA (the caller's contract); `layered` holds J ≥
    // the blocks' end.
    let lo = unsafe { blocks.layered_into(&mut layered[..j]) };
    let (d, v) = (&mut st.d[..j], &mut st.v[..j]);
    if lo > 0 {
        let pass = FusedPass {
            m: &coefs.steps,
            modes: ModeState {
                d: &mut *d,
                v: &mut *v,
            },
            pn,
            pn1: &mut *pn1,
            held,
            sums: &mut *sums,
        };
        // the shapes stored in `layered`, not rotated
        let stored = Phasors {
            fi: &mut layered[..j],
            rr: &[],
            ri: &[],
        };
        // SAFETY: as above; lo is a multiple of SHAPE_BLOCK (so of LANES)
        // and every slice holds J ≥ lo.
        unsafe {
            match deferred {
                Some(f) => fused_free_pair_avx2::<false, true>(pass, stored, lo, f),
                None => fused_free_pair_avx2::<false, false>(pass, stored, lo, 0.0),
            }
        };
    }
    let pass = FusedPass {
        m: &coefs.steps,
        modes: ModeState { d, v },
        pn,
        pn1,
        held,
        sums,
    };
    // SAFETY: as above; every slice holds J ≥ full, lo and full are
    // multiples of SHAPE_BLOCK.
    unsafe {
        match deferred {
            Some(f) => shapes_free_pair_avx2::<true>(blocks, lo, pass, f),
            None => shapes_free_pair_avx2::<false>(blocks, lo, pass, 0.0),
        }
    };
}

/// Phase 3: the mass dofs' free step, the contact problem (g_free and W,
/// MODEL §9.3), the law, and the mass dofs' update. `pair` carries the two
/// sums of a single-contact run; the general path forms them here.
#[inline(always)]
fn contact(
    coefs: &ModalCoefs,
    mass_steps: &[MassStep],
    g: &mut [f64],
    w: &mut [f64],
    pair: Option<(f64, f64)>,
    sys: &mut System,
    st: &mut State,
) -> Result<()> {
    let nc = sys.contacts();
    if nc == 0 {
        return Ok(());
    }
    let m = &coefs.steps;
    // the mass dofs' free step (their constant force held)
    for (j, (ms, dof)) in mass_steps.iter().zip(sys.masses()).enumerate() {
        (st.q[j], st.q_dot[j]) = ms.apply(st.q[j], st.q_dot[j], dof.f0);
    }
    match pair {
        Some((dg, dw)) => {
            let s = sys.physics.carriers[0].s;
            g[0] = s * dg - st.q[0];
            w[0] = s * s * dw + mass_steps[0].g[0];
        }
        None => {
            for ci in &sys.physics.carriers {
                let Some(i) = ci.contact else { continue };
                g[i] = ci.s * lanes::dot(ci.pv_g.dense(), &st.d) - st.q[i];
                for cj in &sys.physics.carriers {
                    let Some(j) = cj.contact else { continue };
                    let wij = path_dot(m, ci.pv_g.dense(), cj.pv_f.dense(), cj.pv_g.dense());
                    w[i * nc + j] =
                        ci.s * cj.s * wij + if i == j { mass_steps[i].g[0] } else { 0.0 };
                }
            }
        }
    }
    sys.hold_multipliers();
    sys.solve_formed(g, w, st)?;
    for c in &sys.physics.carriers {
        let Some(j) = c.contact else { continue };
        let lambda = sys.law.lambda[j];
        st.q[j] -= mass_steps[j].g[0] * lambda;
        st.q_dot[j] -= mass_steps[j].g[1] * lambda;
    }
    Ok(())
}

/// A manufactured source's loads over the step (MODEL §11; scalar, a
/// verification path): the modal load sampled at t_n and t_{n+1} with the
/// first-order hold `η += a0 L_n + a1 L_{n+1}`, `η̇ += b0 L_n + b1 L_{n+1}`
/// (second order), and the mass dofs' source held at the step's midpoint
/// (the midpoint hold of a smooth force is second order too).
fn add_source(m: &ModeSteps, src: &mut SourceLoads, sys: &mut System, st: &mut State) {
    let (t0, t1) = (st.t, st.next_time(sys.physics.dt));
    if src.t_n1 == t0 {
        std::mem::swap(&mut src.at_n, &mut src.at_n1);
    } else {
        sys.source_load_into(t0, &mut src.at_n);
    }
    sys.source_load_into(t1, &mut src.at_n1);
    src.t_n1 = t1;
    for i in 0..m.len() {
        let (p, q) = (src.at_n[i], src.at_n1[i]);
        st.d[i] += path(m.a0[i], p, m.a1[i], q);
        st.v[i] += path(m.b0[i], p, m.b1[i], q);
    }
    sys.set_mass_source(0.5 * (t0 + t1));
}

/// Phase 4 over modes `range`: each contact force, held over the step
/// along its carrier's path, into every mode.
#[inline(always)]
fn update_range(
    coefs: &ModalCoefs,
    sys: &System,
    st: &mut State,
    range: Range<usize>,
    vector: bool,
) {
    for c in &sys.physics.carriers {
        let Some(j) = c.contact else { continue };
        let lambda = sys.law.lambda[j];
        if lambda != 0.0 {
            let path = PathShapes::of(c);
            add_path_load(&coefs.steps, c.s * lambda, path, st, range.clone(), vector);
        }
    }
}

/// One step of one run (module docs), for a run alone and each run of a
/// batch: phases 1–4 over all modes. Where the CPU has AVX2 and FMA the
/// whole step is compiled for them, so the scalar parts (a last partial
/// vector, the general path of several carriers) use the FMA instruction
/// rather than its software emulation; the bits are the same either way.
fn step(me: &mut ModalExact, sys: &mut System, st: &mut State) -> Result<()> {
    #[cfg(target_arch = "x86_64")]
    if lanes::avx2_fma() {
        // SAFETY: the CPU supports AVX2 and FMA (checked just above).
        return unsafe { step_fma(me, sys, st) };
    }
    step_kernel(me, sys, st, false)
}

/// # Safety
/// The CPU supports AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn step_fma(me: &mut ModalExact, sys: &mut System, st: &mut State) -> Result<()> {
    step_kernel(me, sys, st, true)
}

#[inline(always)]
fn step_kernel(me: &mut ModalExact, sys: &mut System, st: &mut State, vector: bool) -> Result<()> {
    let ModalExact {
        coefs,
        mass_steps,
        g,
        w,
        cruise,
        layered,
        pending,
        source,
        impact,
    } = me;
    let deferred = pending.take();
    let (coefs, source) = (&**coefs, source.as_mut());
    let m = &coefs.steps;
    let all = 0..m.len();
    // the vector free steps are of undamped modes (cos_v = cos)
    let vector_free = vector && !coefs.damped;
    let pair = if is_single(sys) && source.is_none() {
        let mut sums = PairSums::default();
        let pass = Pass {
            cruise: cruise.as_mut(),
            layered,
            deferred,
        };
        place_free_pair(coefs, pass, sys, st, &mut sums, vector_free);
        Some(sums.total())
    } else {
        if let Some(f) = deferred {
            // the general path updates in its step: nothing was deferred
            // unless the run changed path (it does not); settle regardless
            let c = &sys.physics.carriers[0];
            add_path_load(m, f, PathShapes::of(c), st, all.clone(), vector);
        }
        place(coefs, sys, st);
        free(m, coefs.held.as_ref(), st, vector_free);
        for c in &sys.physics.carriers {
            if let CarrierKind::Force { force } = c.props.kind {
                let path = PathShapes::of(c);
                add_path_load(m, c.s * force, path, st, all.clone(), vector);
            }
        }
        None
    };
    if let Some(src) = source {
        add_source(m, src, sys, st);
    } else if sys.has_external_force() {
        // external forces on the masses, held at the step's midpoint
        sys.set_mass_source(0.5 * (st.t + st.next_time(sys.physics.dt)));
    }
    let mass_n = impact.as_ref().map(|_| (st.q[0], st.q_dot[0]));
    contact(coefs, mass_steps, g, w, pair, sys, st)?;
    match pair {
        Some((dg, dw)) => {
            // one contact: its update deferred to the next step's pass
            // (or `settle`), the sample's r_gᵀd from the pass's two sums:
            // r_g·(η_free + f z) = dg + f dw
            let rd = match (impact.as_mut(), mass_n) {
                (Some(ev), Some(mass_n)) if ev.fires(g[0], deferred.is_some()) => {
                    // a re-contact located within the step, settled at once
                    let place = |b: &BeamModel, x, pv: &mut PointVector| coefs.place(b, x, pv);
                    ev.recontact(place, &mass_steps[0], mass_n, g[0], sys, st)?
                }
                _ => {
                    let lambda = sys.law.lambda[0];
                    if lambda != 0.0 {
                        let f = sys.physics.carriers[0].s * lambda;
                        *pending = Some(f);
                        f.mul_add(dw, dg)
                    } else {
                        dg
                    }
                }
            };
            if let Some(ev) = impact.as_mut() {
                let gap = sys.physics.carriers[0].s * rd - st.q[0];
                ev.end_step(!sys.law.active[0], gap);
            }
            sys.physics.carriers[0].gap_dot = Some((st.step + 1, rd));
        }
        None => update_range(coefs, sys, st, all, vector),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::modal_kernels::samples;

    /// A run agrees with its shapes taken from the tables at every step,
    /// step by step up to its first re-contact after a loss (the cases of
    /// the test below, 1/4 to 9/10 of their steps rotated): the
    /// displacements within a measured 1.4·10⁻¹⁴ of their largest value
    /// (the shapes' own difference is ≤ 5.4·10⁻¹³ of the amplitude,
    /// `modal_cruise.rs`); 10⁻¹³ leaves a factor of 7.
    const CRUISE_RUN_DISPLACEMENT: f64 = 1e-13;

    /// The same runs' multipliers: measured within 4.0·10⁻⁹ of max |λ|. λ
    /// solves `g_free + W λ = 0` with `g_free` the small difference of the
    /// beam under the carrier and the mass (each ≈ 0.03 m; W λ, what one
    /// step's force adds, is far smaller), which amplifies the shapes'
    /// round-off by about 10⁴; 10⁻⁸ leaves a factor of 2.5. (A re-contact
    /// after a loss is worse conditioned still: its force, which grows as
    /// Δt falls, differs by 2·10⁻⁵ of itself on the clamped–clamped case,
    /// and the bounces after it part; the comparison stops there.)
    const CRUISE_RUN_MULTIPLIER: f64 = 1e-8;

    #[test]
    fn a_cruise_gives_the_run_of_the_tables_to_round_off() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/reference.toml");
        // every support pair (a mirrored basis among them), a constant and
        // a tabulated profile (flat, sloped, flat), Rayleigh damping (the
        // scalar free step) and J not a multiple of 8
        let cases: [&[&str]; 6] = [
            &[],
            &["beam.left=\"pinned\""],
            &["beam.left=\"pinned\"", "beam.right=\"clamped\""],
            &[
                "beam.right=\"clamped\"",
                "carrier.speed={ profile = \"constant\", value = 80.0 }",
            ],
            &[
                "carrier.speed={ profile = \"table\", time = [0.0, 0.2, 0.4, 2.0], speed = [60.0, 60.0, 90.0, 90.0] }",
            ],
            &[
                "beam.damping={ mass = 0.5, stiffness = 1e-5 }",
                "mesh.modes=203",
            ],
        ];
        for case in cases {
            let mut o: Vec<String> = [
                "mesh.kind=galerkin",
                "mesh.modes=400",
                "time.step=6.25e-5",
                "integrator={ method = \"modal_exact\" }",
                "carrier.speed.cruise=80",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            if case.iter().any(|c| c.starts_with("carrier.speed=")) {
                o.pop();
            }
            o.extend(case.iter().map(|s| s.to_string()));
            let sc = crate::load_scene(&path, &o).unwrap();
            let start = |cruise: bool| {
                let mut sys = System::new(&sc).unwrap();
                let st = State::at_rest(sys.beam().n, sys.contacts());
                sys.initial().unwrap();
                let mut stepper = ModalExact::new(&mut sys).unwrap();
                if !cruise {
                    stepper.cruise = None;
                }
                (sys, st, stepper)
            };
            // both in lockstep, compared up to the first re-contact after a
            // loss: its force is ill-conditioned (it grows as Δt falls,
            // contact_loss.md), and bounces after it part at round-off
            let (mut sa, mut a, mut tables) = start(false);
            let (mut sb, mut b, mut rotating) = start(true);
            let (mut rotated, mut lost) = (0, false);
            let (mut dd, mut dmax, mut dl, mut lmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            while sa.physics.carriers[0]
                .props
                .motion
                .position(a.next_time(sa.physics.dt))
                < 50.0
            {
                let before = rotating.cruise.as_ref().map(|c| c.rotations());
                tables.step(&mut sa, &mut a).unwrap();
                rotating.step(&mut sb, &mut b).unwrap();
                if let (Some(r), Some(c)) = (before, &rotating.cruise) {
                    rotated += usize::from(c.rotations() > r);
                }
                for (s, st) in [(&mut sa, &mut a), (&mut sb, &mut b)] {
                    st.step += 1;
                    st.t = st.step as f64 * s.physics.dt;
                    s.end_step(st);
                }
                let (la, lb) = (sa.law.lambda[0], sb.law.lambda[0]);
                if lost && la != 0.0 {
                    break;
                }
                lost |= la == 0.0;
                dl = dl.max((la - lb).abs());
                lmax = lmax.max(la.abs());
                for (x, y) in a.d.iter().zip(&b.d) {
                    dd = dd.max((x - y).abs());
                    dmax = dmax.max(x.abs());
                }
            }
            assert_eq!(tables.cruise.as_ref().map(Cruise::rotations), None);
            let steps = a.step;
            assert!(
                rotated > steps / 4,
                "{case:?}: {rotated} of {steps} steps rotated"
            );
            let (ed, el) = (dd / dmax, dl / lmax);
            println!(
                "{case:?}: {rotated} of {steps} steps rotated; max |Δd|/max|d| {ed:.1e}, max |Δλ|/max|λ| {el:.1e}"
            );
            assert!(ed <= CRUISE_RUN_DISPLACEMENT, "{case:?}: {ed:e}");
            assert!(el <= CRUISE_RUN_MULTIPLIER, "{case:?}: {el:e}");
        }
    }

    /// The vector and scalar paths of each kernel give the same bits.
    #[test]
    fn the_vector_and_scalar_kernels_agree_bit_for_bit() {
        if !lanes::avx2_fma() {
            return;
        }
        for j in [3, 8, 13, 64, 803] {
            let omega: Vec<f64> = (1..=j)
                .map(|i| 9.4 * i as f64 * (1.0 + 1e-3 * i as f64))
                .collect();
            let m = ModeSteps::new(&omega, 6.25e-5);
            let wave =
                |k: f64| -> Vec<f64> { (0..j).map(|i| (k * (i + 1) as f64).sin()).collect() };
            let (pn, pn1) = (wave(0.37), wave(0.371));
            let path = PathShapes {
                at_n: &pn,
                at_n1: &pn1,
            };
            let st0 = State {
                step: 3,
                t: 0.0,
                d: wave(1.3).iter().map(|x| 1e-3 * x).collect(),
                v: wave(0.7).into(),
                q: vec![],
                q_dot: vec![],
            };
            let held = (wave(0.2), wave(0.9));
            for h in [None, Some(&held)] {
                let (mut a, mut b, mut c) = (st0.clone(), st0.clone(), st0.clone());
                let (mut sa, mut sb, mut sc) = (
                    PairSums::default(),
                    PairSums::default(),
                    PairSums::default(),
                );
                free_with_pair(&m, h, &mut a, path, 0..j, &mut sa, true);
                free_with_pair(&m, h, &mut b, path, 0..j, &mut sb, false);
                // by ranges, as a batch takes them
                for lo in (0..j).step_by(16) {
                    let r = lo..(lo + 16).min(j);
                    free_with_pair(&m, h, &mut c, path, r, &mut sc, true);
                }
                let bits = |s: &PairSums| {
                    let (g, w) = s.total();
                    (g.to_bits(), w.to_bits())
                };
                assert_eq!(bits(&sa), bits(&sb), "J = {j}");
                assert_eq!(bits(&sa), bits(&sc), "J = {j}");
                assert_eq!(a, b);
                assert_eq!(a, c);
                add_path_load(&m, -37.5, path, &mut a, 0..j, true);
                add_path_load(&m, -37.5, path, &mut b, 0..j, false);
                for lo in (0..j).step_by(16) {
                    let r = lo..(lo + 16).min(j);
                    add_path_load(&m, -37.5, path, &mut c, r, true);
                }
                assert_eq!(a, b, "J = {j}");
                assert_eq!(a, c, "J = {j}");
            }
        }
    }

    /// The cruise pass in AVX-512 registers gives the bits of the AVX2
    /// one: the shapes stored, the phasors advanced, the state and the
    /// pair's partial sums, with and without a deferred update and a held
    /// load, rotated and from stored shapes.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_avx512_fused_pass_gives_the_bits_of_the_avx2_one() {
        if !lanes::avx512() {
            return;
        }
        let j = 808;
        let m = samples::steps(j);
        let blocks = coef_blocks(&m);
        let wave = |k: f64| samples::wave(j, k);
        let held = (wave(0.2), wave(0.9));
        let (rr, ri) = (wave(0.05), wave(0.06));
        type Run = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, PairSums);
        let pass = |wide: bool, rotate: bool, f: Option<f64>, h: bool| -> Run {
            let (mut d, mut v, mut pn1, mut fi) = (wave(1.3), wave(0.7), wave(0.33), wave(0.41));
            let pn = wave(0.37);
            let mut sums = PairSums {
                g: [0.5; LANES],
                w: [-0.25; LANES],
            };
            let fp = FusedPass {
                m: &m,
                modes: ModeState {
                    d: &mut d,
                    v: &mut v,
                },
                pn: &pn,
                pn1: &mut pn1,
                held: HeldStep::of(h.then_some(&held), j),
                sums: &mut sums,
            };
            let ph = Phasors {
                fi: &mut fi,
                rr: if rotate { &rr } else { &[] },
                ri: if rotate { &ri } else { &[] },
            };
            // SAFETY: AVX-512F (so AVX2 and FMA) checked above; J a
            // multiple of LANES, every slice holds J.
            unsafe {
                match (wide, rotate, f) {
                    (true, true, Some(f)) => {
                        fused_free_pair_avx512::<true, true>(fp, &blocks, ph, j, f)
                    }
                    (true, true, None) => {
                        fused_free_pair_avx512::<true, false>(fp, &blocks, ph, j, 0.0)
                    }
                    (true, false, Some(f)) => {
                        fused_free_pair_avx512::<false, true>(fp, &blocks, ph, j, f)
                    }
                    (true, false, None) => {
                        fused_free_pair_avx512::<false, false>(fp, &blocks, ph, j, 0.0)
                    }
                    (false, true, Some(f)) => fused_free_pair_avx2::<true, true>(fp, ph, j, f),
                    (false, true, None) => fused_free_pair_avx2::<true, false>(fp, ph, j, 0.0),
                    (false, false, Some(f)) => fused_free_pair_avx2::<false, true>(fp, ph, j, f),
                    (false, false, None) => fused_free_pair_avx2::<false, false>(fp, ph, j, 0.0),
                }
            }
            (d, v, pn1, fi, sums)
        };
        let bits = |x: &[f64]| -> Vec<u64> { x.iter().map(|y| y.to_bits()).collect() };
        for rotate in [true, false] {
            for f in [None, Some(-37.5)] {
                for h in [false, true] {
                    let (a, b) = (pass(true, rotate, f, h), pass(false, rotate, f, h));
                    let case = format!("rotate {rotate}, deferred {f:?}, held {h}");
                    assert_eq!(bits(&a.0), bits(&b.0), "d, {case}");
                    assert_eq!(bits(&a.1), bits(&b.1), "v, {case}");
                    assert_eq!(bits(&a.2), bits(&b.2), "shapes, {case}");
                    assert_eq!(bits(&a.3), bits(&b.3), "phasors, {case}");
                    assert_eq!(bits(&a.4.g), bits(&b.4.g), "g, {case}");
                    assert_eq!(bits(&a.4.w), bits(&b.4.w), "w, {case}");
                }
            }
        }
    }

    /// The sample's `r_gᵀd` from the pass's sums (`dg + f·dw`) against
    /// the dot on the settled state: measured within 3.2·10⁻¹⁵ of the
    /// largest |w| (J = 203; the two ways round J products and partial
    /// sums differently); 2·10⁻¹⁴ leaves a factor of 6.
    const SAMPLE_AGREEMENT: f64 = 2e-14;

    /// A step whose update is deferred settles to the bits of a step that
    /// takes it at once, whichever path each step takes (the tables, a
    /// cruise's rotation, λ = 0 steps after a loss): the multipliers, the
    /// state once settled, and `displacement_at` before settling all agree
    /// bit for bit; the sample agrees to round-off.
    #[test]
    fn a_deferred_update_settles_to_the_bits_of_a_step() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/reference.toml");
        // J = 203: a partial vector and a partial block; 170 m/s: losses
        let o: Vec<String> = [
            "mesh.kind=galerkin",
            "mesh.modes=203",
            "time.step=6.25e-5",
            "integrator={ method = \"modal_exact\" }",
            "carrier.speed.cruise=170",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let sc = crate::load_scene(&path, &o).unwrap();
        let start = || {
            let mut sys = System::new(&sc).unwrap();
            let st = State::at_rest(sys.beam().n, sys.contacts());
            sys.initial().unwrap();
            let stepper = ModalExact::new(&mut sys).unwrap();
            (sys, st, stepper)
        };
        let (mut sa, mut a, mut now) = start();
        let (mut sb, mut b, mut later) = start();
        let (mut worst, mut losses, mut largest) = (0.0f64, 0, 0.0f64);
        while sa.physics.carriers[0]
            .props
            .motion
            .position(a.next_time(sa.physics.dt))
            < 50.0
        {
            now.step(&mut sa, &mut a).unwrap();
            later.step_deferred(&mut sb, &mut b).unwrap();
            for (s, st) in [(&mut sa, &mut a), (&mut sb, &mut b)] {
                st.step += 1;
                st.t = st.step as f64 * s.physics.dt;
                s.end_step(st);
            }
            assert_eq!(
                sa.law.lambda[0].to_bits(),
                sb.law.lambda[0].to_bits(),
                "step {}",
                a.step
            );
            losses += usize::from(sa.law.lambda[0] == 0.0);
            let pv = &sa.physics.carriers[0].pv_g;
            let settled = pv.dot(&a.d);
            let pending = later.displacement_at(&sb, &b, &sb.physics.carriers[0].pv_g);
            assert_eq!(settled.to_bits(), pending.to_bits(), "step {}", a.step);
            let (_, rd) = sb.physics.carriers[0].gap_dot.unwrap();
            worst = worst.max((rd - settled).abs());
            largest = largest.max(settled.abs());
        }
        later.settle(&sb, &mut b);
        assert_eq!(a, b, "the settled state");
        assert!(losses > 100, "{losses} steps without contact");
        let rel = worst / largest;
        println!(
            "{} steps, {losses} without contact; sample within {rel:.1e} of max |w|",
            a.step
        );
        assert!(rel <= SAMPLE_AGREEMENT, "{rel:e}");
    }
}
