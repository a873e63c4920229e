//! `[contact]`: the contact kind, formulation and placement, and each
//! formulation's settings (MODEL §5, §6).

use serde::{Deserialize, Serialize};

/// Unilateral (Signorini) or bilateral (always attached) contact.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum ContactKind {
    /// λ ≥ 0, g ≥ 0, λ·g = 0: contact can be lost and regained.
    #[default]
    Unilateral,
    /// g = 0 always; λ may be negative.
    Bilateral,
}

/// How the contact force is computed each step (MODEL §6).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    /// Lagrange multiplier with an active set (the study's).
    #[default]
    Lagrange,
    /// Penalty λ = κ·max(0, −g), solved exactly per step (`[contact.penalty]`).
    Penalty,
    /// The per-step LCP (the QP of MODEL §6), solved directly or by clarabel
    /// (`[contact.complementarity]`).
    Complementarity,
    /// Velocity-level (Moreau–Jean style) contact with restitution (`[contact.impact]`).
    Impact,
}

impl Formulation {
    /// Every formulation, in the order `taut compare` lists them.
    pub const ALL: [Formulation; 4] = [
        Formulation::Lagrange,
        Formulation::Penalty,
        Formulation::Complementarity,
        Formulation::Impact,
    ];

    /// The scene name (`"lagrange"`, …).
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Lagrange => "lagrange",
            Formulation::Penalty => "penalty",
            Formulation::Complementarity => "complementarity",
            Formulation::Impact => "impact",
        }
    }
}

/// `[contact.penalty]`: the penalty stiffness κ, in N/m or relative to the
/// step's contact stiffness 1/W (give at most one; default `relative = 1000`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct PenaltySpec {
    /// κ, N/m (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// κ = relative / W_cc, dimensionless (> 0); the force is then
    /// relative/(1 + relative) of the Lagrange force for the same free gap.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative: Option<f64>,
    /// κ (`stiffness`, N/m) is the modelled contact stiffness — a
    /// pantograph strip's compliance, as in the EN 50318 reference models —
    /// not a regularization of rigid contact: its penetration λ/κ is part
    /// of the model, so the warning that κ is soft enough to change the
    /// answer does not apply (default false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub physical: bool,
}

/// Which solver answers the complementarity law's per-step LCP
/// (`contact.complementarity.solver`).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum ComplementaritySolver {
    /// Exact principal pivoting (Murty) on preallocated scratch: no
    /// allocation per step (default).
    #[default]
    Direct,
    /// clarabel's interior-point QP solver (the general-QP-solver reference;
    /// the tolerances and `max_iter` below apply to it).
    Clarabel,
}

/// `[contact.complementarity]`: the solver of the per-step LCP and clarabel's
/// settings.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ComplementaritySpec {
    /// `direct` (default) or `clarabel`.
    #[serde(default)]
    pub solver: ComplementaritySolver,
    /// Absolute duality-gap tolerance (default 1e-12).
    #[serde(default = "qp_tol")]
    pub tol_gap_abs: f64,
    /// Relative duality-gap tolerance (default 1e-12).
    #[serde(default = "qp_tol")]
    pub tol_gap_rel: f64,
    /// Feasibility tolerance (default 1e-12).
    #[serde(default = "qp_tol")]
    pub tol_feas: f64,
    /// Iteration limit (default 100).
    #[serde(default = "qp_max_iter")]
    pub max_iter: u32,
}

fn qp_tol() -> f64 {
    1e-12
}

fn qp_max_iter() -> u32 {
    100
}

impl Default for ComplementaritySpec {
    fn default() -> Self {
        ComplementaritySpec {
            solver: ComplementaritySolver::default(),
            tol_gap_abs: qp_tol(),
            tol_gap_rel: qp_tol(),
            tol_feas: qp_tol(),
            max_iter: qp_max_iter(),
        }
    }
}

/// `[contact.impact]`: the velocity-level formulation's impact law.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct ImpactSpec {
    /// Newton restitution coefficient e ∈ [0, 1] (default 0: plastic impact).
    #[serde(default)]
    pub restitution: f64,
}

/// Where the gap condition is imposed (MODEL §5).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// g_{n+1} = 0 at the end of the step (default; stable).
    #[default]
    End,
    /// g_{n+1−α_f} = 0 at the α-level (the study's literal statement).
    Alpha,
}

/// `[contact]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// `unilateral` (default) or `bilateral`.
    #[serde(default)]
    pub kind: ContactKind,
    /// `lagrange` (default), `penalty`, `complementarity` or `impact`.
    #[serde(default)]
    pub formulation: Formulation,
    /// `end` (default) or `alpha`.
    #[serde(default)]
    pub placement: Placement,
    /// Penalty settings (used when `formulation = "penalty"`).
    #[serde(default)]
    pub penalty: PenaltySpec,
    /// QP solver settings (used when `formulation = "complementarity"`).
    #[serde(default)]
    pub complementarity: ComplementaritySpec,
    /// Impact law (used when `formulation = "impact"`).
    #[serde(default)]
    pub impact: ImpactSpec,
}
