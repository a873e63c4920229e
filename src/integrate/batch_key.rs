//! Which runs may step together, as a typed value ([`BatchKey`]): runs
//! with equal keys share what a batch builds once — the effective matrix
//! A = (1 − α_m)M + (1 − α_f)βΔt²K and the right-hand-side columns of a
//! generalized-α batch (MODEL §5, `integrate::batch`), or the basis and
//! its exact step maps of a `modal_exact` batch (MODEL §9.3,
//! `integrate::modal_batch`).
//!
//! Every float enters by its bits (`f64::to_bits`): two runs batch only
//! when what they share is the same number, not merely equal when printed.
//! The key derives `Eq`, `Hash` and `Ord`, so a caller may group runs with
//! a map or a sort as well as by comparison.

use crate::resolve::Resolved;
use crate::scene::{
    BeamProps, CarrierKind, Discretization, Formulation, Grading, Placement, Scheme, Support,
};

use crate::model::banded::rhs_columns;

/// The key of the runs that may step together; `None` from [`batch_key`]
/// when a run steps alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BatchKey {
    /// Generalized-α runs sharing one factorization ([`super::Batch`]).
    GenAlpha(GenAlphaKey),
    /// `modal_exact` runs sharing one basis (`super::ModalBatch`).
    Modal(ModalKey),
}

/// What the beam's matrices and distributed load are made of (MODEL §1),
/// bit for bit: part of every key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BeamKey {
    /// The supports at x = 0 and x = L (0 clamped, 1 pinned, 2 free).
    supports: (u8, u8),
    /// Bits of L, m.
    length: u64,
    /// Bits of ρA, kg/m.
    rho_a: u64,
    /// Bits of EI, N·m².
    ei: u64,
    /// Bits of T, N.
    tension: u64,
    /// Bits of the distributed load, N/m.
    distributed_load: u64,
}

/// A mesh grading (MODEL §9.2) by the bits of its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GradingKey {
    /// Equal elements.
    Uniform,
    /// Toward both supports: bits of R.
    Supports(u64),
    /// Toward x = 0: bits of R.
    Left(u64),
    /// Toward x = L: bits of R.
    Right(u64),
    /// Toward x_p: bits of R and of x_p.
    Point(u64, u64),
}

/// Generalized-α runs that share A and their columns (`integrate::batch`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GenAlphaKey {
    beam: BeamKey,
    grading: GradingKey,
    /// Elements N.
    elements: usize,
    /// Bits of Δt, s.
    dt: u64,
    /// Bits of α_m, α_f, β, γ.
    params: [u64; 4],
    /// Right-hand-side columns per run ([`rhs_columns`]).
    columns: usize,
}

/// `modal_exact` runs that share a basis and Δt (`integrate::modal_batch`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ModalKey {
    beam: BeamKey,
    /// The basis: 0 Hermite, 1 Galerkin, 2 modal; and J (0 for Hermite).
    basis: (u8, usize),
    /// The FE mesh a `modal` basis is drawn from: N and its grading.
    mesh: Option<(usize, GradingKey)>,
    /// Bits of Δt, s.
    dt: u64,
}

/// The key of the runs that may step together: `None` when `sc` cannot
/// batch. Generalized-α runs with equal keys share their effective matrix
/// and right-hand-side columns (`integrate::batch`); `modal_exact` runs
/// their basis and Δt (`integrate::modal_batch`). A scene with a
/// multi-mass pantograph (`carrier.masses`, MODEL §10) does not batch: its
/// runs step alone, where the method's own check refuses or carries the
/// chain.
pub fn batch_key(sc: &Resolved) -> Option<BatchKey> {
    // a multi-mass pantograph steps alone; an external force series is a
    // time-dependent load of its own: alone too
    if sc.carriers.iter().any(|c| c.chain.is_some())
        || sc.external_forces.iter().any(Option::is_some)
    {
        return None;
    }
    gen_alpha_key(sc)
        .map(BatchKey::GenAlpha)
        .or_else(|| modal_key(sc).map(BatchKey::Modal))
}

/// Right-hand-side columns of a scene's runs: the free step and one per
/// contact (mass–spring carrier), [`rhs_columns`].
pub(crate) fn scene_columns(sc: &Resolved) -> usize {
    rhs_columns(
        sc.carriers
            .iter()
            .filter(|c| matches!(c.kind, CarrierKind::MassSpring { .. }))
            .count(),
    )
}

/// The key of the generalized-α runs that may step together: `None` when
/// `sc` cannot batch this way (`integrate::batch`'s module docs: no point
/// attachments, no damping, the `end` placement, a force-level law, Hermite elements, no
/// manufactured source, at most four columns).
pub(crate) fn gen_alpha_key(sc: &Resolved) -> Option<GenAlphaKey> {
    let Scheme::GenAlpha(p) = sc.method.scheme else {
        return None;
    };
    if sc.is_damped() {
        // a damped run steps alone (docs/lines.md §10.4): the batch kernel
        // does not do the damping's product
        return None;
    }
    if sc.contact.placement != Placement::End
        || sc.contact.formulation == Formulation::Impact
        || sc.discretization != Discretization::Hermite
        // a manufactured source is a time-dependent load: alone
        || sc.manufactured.is_some()
        // droppers: their responses are a run's own (`dropper.rs`): alone
        || !sc.droppers.is_empty()
        // a messenger: its own band (7 or 3) and static start: alone
        || sc.beam.messenger.is_some()
        || !sc.scene.time.initial.is_rest()
    {
        return None;
    }
    let columns = scene_columns(sc);
    if columns > 4 {
        return None;
    }
    Some(GenAlphaKey {
        beam: beam_key(&sc.beam)?,
        grading: grading_key(sc.grading),
        elements: sc.elements,
        dt: sc.dt.to_bits(),
        params: [p.alpha_m, p.alpha_f, p.beta, p.gamma].map(f64::to_bits),
        columns,
    })
}

/// The key of `modal_exact` runs that may step together: `None` for any
/// other method, for a beam with point attachments and for a damped run.
pub(crate) fn modal_key(sc: &Resolved) -> Option<ModalKey> {
    if sc.method.scheme != Scheme::ModalExact || sc.is_damped() || !sc.droppers.is_empty() {
        // a damped run steps alone (docs/lines.md §10.4): the shared step
        // maps are the undamped ones
        return None;
    }
    let (basis, mesh) = match sc.discretization {
        Discretization::Hermite => ((0, 0), None),
        Discretization::Galerkin { modes } => ((1, modes), None),
        Discretization::Modal { modes } => {
            ((2, modes), Some((sc.elements, grading_key(sc.grading))))
        }
    };
    Some(ModalKey {
        beam: beam_key(&sc.beam)?,
        basis,
        mesh,
        dt: sc.dt.to_bits(),
    })
}

/// `None` for a beam with point attachments (`[[attachment]]`, MODEL §10):
/// their springs and masses are part of K and M, and such runs step alone
/// rather than have the key carry a list (a sweep over an attachment's
/// stiffness must not share the first run's matrices).
fn beam_key(b: &BeamProps) -> Option<BeamKey> {
    if !b.attachments.is_empty() {
        return None;
    }
    let support = |s: Support| match s {
        Support::Clamped => 0,
        Support::Pinned => 1,
        Support::Free => 2,
    };
    Some(BeamKey {
        supports: (support(b.left), support(b.right)),
        length: b.length.to_bits(),
        rho_a: b.rho_a.to_bits(),
        ei: b.ei.to_bits(),
        tension: b.tension.to_bits(),
        distributed_load: b.distributed_load.to_bits(),
    })
}

fn grading_key(g: Grading) -> GradingKey {
    match g {
        Grading::Uniform => GradingKey::Uniform,
        Grading::Supports { ratio } => GradingKey::Supports(ratio.to_bits()),
        Grading::Left { ratio } => GradingKey::Left(ratio.to_bits()),
        Grading::Right { ratio } => GradingKey::Right(ratio.to_bits()),
        Grading::Point { ratio, at } => GradingKey::Point(ratio.to_bits(), at.to_bits()),
    }
}
