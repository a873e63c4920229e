//! Deliberate defects, compiled into test builds only, that the
//! verification harness must flag (`docs/verification.md`, "The
//! harness tested against known defects").
//!
//! Each [`Defect`] is a small, plausible mistake at one place of the code:
//! in the step, the contact force, the manufactured source, the sampling of
//! the history, the boundary terms, the damping, the element mass, the mass
//! dofs' predictor, a method parameter's coefficient, the modal hold, the
//! penalty's scaling and the graded mesh's lookup. A test switches one on
//! for the threads of a rayon pool of its own (a thread-local flag, so the
//! other tests of the binary, running beside it, never see it) and runs
//! `taut verify --quick`'s matrix there; each defect must make at least one
//! row fail (`study::verify::mutation`).
//!
//! Outside `cfg(test)` [`on`] is the constant `false` and every hook folds
//! away: release builds carry none of it.

/// A deliberate defect (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Defect {
    /// The step: generalized-α's γ is 0.01 above 1/2 − α_m + α_f, so its
    /// velocity update is only first-order consistent.
    StepGamma,
    /// The contact force: its direction r_f is taken at the carrier's
    /// position one step behind, x_m(t_force − Δt).
    ForceBehind,
    /// The source: the manufactured loads sampled half a step late,
    /// t_load + Δt/2.
    SourceLate,
    /// The sampling: the recorded force labelled half a step off the time
    /// its multiplier acts (`RunOutput::force_lag` + ½).
    SamplingLag,
    /// The boundary terms: a clamped end keeps its rotation free (pinned).
    ClampedRotationFree,
    /// The damping: a mass–spring's dashpot acts at half its c_s.
    HalfDashpot,
    /// The element mass: the Hermite element's M[1][1] 5h² for 4h² (its
    /// rotation's inertia 25 % high at the left node only).
    HermiteMass,
    /// The mass dofs' predictor: generalized-α's spring acts at
    /// (1 − α_f)q̃, its α_f·z_n term dropped.
    PredictorSpring,
    /// Bathe's second sub-step: c₁ = γ/((1 − γ)Δt) for (1 − γ)/(γΔt)
    /// (identical at γ = ½).
    BatheC1,
    /// `modal_exact`'s first-order hold: the load samples' two
    /// coefficients a0, a1 swapped (the sum, the held load's, unchanged).
    HoldSwapped,
    /// The penalty: `contact.penalty.relative` taken as κ itself, not
    /// divided by the compliance W_cc.
    PenaltyUnscaled,
    /// The graded mesh: `locate`'s local coordinate divided by the previous
    /// element's length.
    LocatePrevious,
}

#[cfg(test)]
impl Defect {
    /// Every defect, in the table's order.
    pub const ALL: [Defect; 12] = [
        Defect::StepGamma,
        Defect::ForceBehind,
        Defect::SourceLate,
        Defect::SamplingLag,
        Defect::ClampedRotationFree,
        Defect::HalfDashpot,
        Defect::HermiteMass,
        Defect::PredictorSpring,
        Defect::BatheC1,
        Defect::HoldSwapped,
        Defect::PenaltyUnscaled,
        Defect::LocatePrevious,
    ];

    /// The defect named `name` (its variant's name), for a run of one.
    pub fn named(name: &str) -> Option<Defect> {
        Defect::ALL.into_iter().find(|d| format!("{d:?}") == name)
    }
}

#[cfg(test)]
thread_local! {
    /// The defect switched on for this thread, if any.
    static ACTIVE: std::cell::Cell<Option<Defect>> = const { std::cell::Cell::new(None) };
}

/// Switch `d` on (or every defect off) for this thread (test builds only).
#[cfg(test)]
pub(crate) fn set(d: Option<Defect>) {
    ACTIVE.with(|a| a.set(d));
}

/// True when `d` is switched on for this thread (test builds only).
#[cfg(test)]
#[inline]
pub(crate) fn on(d: Defect) -> bool {
    ACTIVE.with(|a| a.get() == Some(d))
}

/// Always false outside test builds: every hook folds away.
#[cfg(not(test))]
#[inline(always)]
pub(crate) fn on(_: Defect) -> bool {
    false
}
