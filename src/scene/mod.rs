//! Scene files: what a run needs, as plain serde data (MODEL.md §1–§5).
//!
//! A scene is TOML. Every table rejects unknown keys. Loading is three steps:
//! parse the text into a TOML tree, apply `--set` overrides on the tree
//! ([`load`]), then deserialize and `Scene::validate` (the resolve layer,
//! `crate::resolve`) into a `Resolved` set of physical parameters that the
//! model is built from. Every key, its unit, default and allowed range is
//! documented in `docs/scene.md`.
//!
//! The bottom of the house: this module imports only the crate's error and
//! input reading. It holds the scene's own checks (each value in its
//! range, `validate.rs`), the plain property structs the model is built
//! from ([`BeamProps`], [`MeshPlan`], [`CarrierProps`] with its
//! [`Motion`]), and the methods' descriptions (`method.rs`); checks that
//! need the model, a reference or the memory plan are the resolve layer's.

mod attachment;
mod damping;
mod discretization;
mod dropper;
mod external_force;
mod line;
mod line_design;
mod load;
pub mod manufactured;
mod messenger;
mod method;
mod motion;
mod pantograph;
mod speed;
mod table_files;
pub mod tables;
mod validate;

pub use attachment::{Attachment, AttachmentSpec, resolve_attachments};
pub use damping::{Rayleigh, RayleighSpec, resolve_rayleigh};
pub use discretization::{
    DEFAULT_GRADING_RATIO, Discretization, Grading, MAX_GRADING_RATIO, MeshPlan, fe_unknowns,
};
pub use dropper::{Anchor, AnchorSpec, Dropper, DropperSpec, resolve_droppers};
pub use external_force::{ExternalForceSpec, ForceSeries, MAX_SERIES_POINTS};
pub use line::{
    DesignedDropper, Generated, MAX_DROPPERS_PER_SPAN, MAX_SPANS, designed_droppers, expand_line,
    expand_line_with_origin,
};
pub use load::{
    UNSET, apply_override, check_is_scene, in_file, parse_scene, read_scene, scene_from_tree,
    scene_with_overrides, set_typed, with_table_files,
};
pub use manufactured::{Declared, ManufacturedSpec, ReferenceKind, ReferenceSpec};
pub use messenger::{Messenger, MessengerSpec};
pub(crate) use method::register_info;
pub use method::{
    DEFAULT_BATHE_GAMMA, DEFAULT_HHT_ALPHA, DEFAULT_THETA, GenAlphaParams, IntegratorSpec, Method,
    MethodInfo, Parameter, Scheme, method_info, method_names,
};
pub use motion::Motion;
pub(crate) use pantograph::check_chain_scene;
pub use pantograph::{ChainProps, MAX_CHAIN};
pub use speed::SpeedProfile;
pub use validate::{
    BeamProps, CarrierKind, CarrierProps, DEFAULT_PENALTY_RELATIVE, MAX_ELEMENTS, MAX_STEPS,
    STEP_COUNT_SLACK, TimeProps, check_speed_tables_cover, validate_contact,
};

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A whole scene file.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The tensioned beam (or string when EI = 0).
    pub beam: BeamSpec,
    /// The finite-element mesh.
    pub mesh: MeshSpec,
    /// One or more carriers: mass–springs or moving forces (`[[carrier]]`).
    #[serde(rename = "carrier")]
    pub carriers: Vec<CarrierSpec>,
    /// Contact kind, formulation and constraint placement.
    #[serde(default)]
    pub contact: ContactSpec,
    /// Time step and end time.
    pub time: TimeSpec,
    /// The time integrator and its parameters (MODEL §5, §9.1).
    #[serde(default)]
    pub integrator: IntegratorSpec,
    /// Gravity.
    #[serde(default)]
    pub gravity: GravitySpec,
    /// Points whose beam displacement is recorded (`[[probe]]`).
    #[serde(default, rename = "probe", skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<ProbeSpec>,
    /// Point attachments along the beam (`[[attachment]]`, MODEL §10):
    /// springs to a fixed anchor and lumped masses.
    #[serde(default, rename = "attachment", skip_serializing_if = "Vec::is_empty")]
    pub attachments: Vec<AttachmentSpec>,
    /// Droppers to fixed anchors (`[[dropper]]`, MODEL §10): tension-only
    /// links that go slack, solved with the contacts (`docs/lines.md`).
    #[serde(default, rename = "dropper", skip_serializing_if = "Vec::is_empty")]
    pub droppers: Vec<DropperSpec>,
    /// A messenger wire above the contact wire (`[messenger]`,
    /// `docs/lines.md` eq. W1–W6), coupled by droppers with
    /// `anchor = "messenger"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub messenger: Option<MessengerSpec>,
    /// What the history records (`[output]`).
    #[serde(default, skip_serializing_if = "OutputSpec::is_default")]
    pub output: OutputSpec,
    /// A manufactured solution (`[manufactured]`, MODEL §11): its source is
    /// added to the run and it is the scene's reference.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub manufactured: Option<ManufacturedSpec>,
    /// The reference the scene declares for `taut converge` and `taut
    /// verify` (`[reference]`; default: Richardson extrapolation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceSpec>,
    /// What `[line]` generated (nothing without one): errors found in the
    /// expanded scene name the keys a user wrote ([`Generated::user_path`]).
    #[serde(skip)]
    pub generated: Generated,
}

/// Support condition at a beam end (MODEL §1).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// v = 0 and v' = 0.
    Clamped,
    /// v = 0, moment free.
    Pinned,
    /// No constraint.
    Free,
}

/// `[beam]`: geometry, material, tension and supports.
///
/// Mass per length is either `mass_per_length` or `density`·`area`; bending
/// stiffness is either `bending_stiffness` or `youngs_modulus`·`second_moment`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BeamSpec {
    /// Span L, m (> 0).
    pub length: f64,
    /// Axial tension T, N (≥ 0).
    pub tension: f64,
    /// Support at x = 0.
    pub left: Support,
    /// Support at x = L.
    pub right: Support,
    /// Density ρ, kg/m³ (with `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// Cross-section area A, m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area: Option<f64>,
    /// Young's modulus E, Pa (with `second_moment`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<f64>,
    /// Second moment of area I, m⁴.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_moment: Option<f64>,
    /// Mass per length ρA, kg/m (instead of `density`·`area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_per_length: Option<f64>,
    /// Bending stiffness EI, N·m² (instead of `youngs_modulus`·`second_moment`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    /// Rayleigh damping `C = α M + β K` (`{ mass = α, stiffness = β }`,
    /// 1/s and s, each ≥ 0; absent: no damping).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<RayleighSpec>,
}

/// `[mesh]`: the space discretization (MODEL §4, §9.2).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Number of elements N (1 ..= 1 000 000): the Hermite (or string)
    /// mesh, and the mesh a `modal` basis is taken from; `galerkin` has no
    /// mesh and does not use it.
    pub elements: usize,
    /// The discretization: `hermite` (default), `galerkin`, `modal`.
    #[serde(default, skip_serializing_if = "MeshKind::is_default")]
    pub kind: MeshKind,
    /// Number of modes J for `galerkin` and `modal`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Where elements shrink toward: `uniform` (default), `supports`,
    /// `left`, `right`, `point` (Hermite and modal meshes).
    #[serde(default, skip_serializing_if = "GradingKind::is_default")]
    pub grading: GradingKind,
    /// Size ratio h_max/h_min of a graded mesh, in [1, 1000] (default 4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading_ratio: Option<f64>,
    /// The point x_p a `point` grading shrinks toward, m, in (0, L).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading_at: Option<f64>,
}

/// `mesh.kind` (MODEL §9.2).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum MeshKind {
    /// Hermite beam elements (string elements when EI = 0).
    #[default]
    Hermite,
    /// The J exact modes of the continuous beam.
    Galerkin,
    /// The J lowest modes of the Hermite model.
    Modal,
}

impl MeshKind {
    fn is_default(&self) -> bool {
        *self == MeshKind::Hermite
    }

    /// The scene's name of this kind.
    pub fn name(&self) -> &'static str {
        match self {
            MeshKind::Hermite => "hermite",
            MeshKind::Galerkin => "galerkin",
            MeshKind::Modal => "modal",
        }
    }
}

/// `mesh.grading`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum GradingKind {
    /// Equal elements.
    #[default]
    Uniform,
    /// Toward both supports.
    Supports,
    /// Toward x = 0.
    Left,
    /// Toward x = L.
    Right,
    /// Toward `grading_at`.
    Point,
}

impl GradingKind {
    fn is_default(&self) -> bool {
        *self == GradingKind::Uniform
    }
}

/// Which side of the beam the carrier's mass sits on (MODEL §2).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// The mass is above the beam and pushes it down (s = −1).
    Above,
    /// The mass is below the beam and pushes it up (s = +1).
    Below,
}

impl Side {
    /// The sign `s` of MODEL §2: +1 below, −1 above.
    pub fn sign(self) -> f64 {
        match self {
            Side::Above => -1.0,
            Side::Below => 1.0,
        }
    }
}

/// `[[carrier]]`: a mass–spring (`mass`, `stiffness`, …) or a moving
/// constant force (`force`, no mass).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CarrierSpec {
    /// Mass m, kg (> 0). Absent for a moving force.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Spring stiffness k, N/m (≥ 0; 0 = a riding mass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Dashpot c_s, N·s/m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Spring preload δ0, m (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<f64>,
    /// Moving constant force F, N (≥ 0, pressing into the beam from `side`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force: Option<f64>,
    /// A multi-mass pantograph's masses m₁ (head) … m_n, kg (2 or 3, each
    /// > 0; `scene/pantograph.rs`). Replaces `mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub masses: Option<Vec<f64>>,
    /// Its springs k₁ … k_n, N/m: k_i between m_i and m_{i+1}, k_n to the roof.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffnesses: Option<Vec<f64>>,
    /// Its dashpots c₁ … c_n, N·s/m, placed like the springs (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dampings: Option<Vec<f64>>,
    /// Its static uplift F₀ on m_n, N (≥ 0, default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uplift: Option<f64>,
    /// Side of the beam the carrier is on.
    pub side: Side,
    /// Initial position x_m(0), m (0 ≤ start ≤ L).
    pub start: f64,
    /// Speed profile (MODEL §3).
    pub speed: SpeedProfile,
    /// An external force on the mass, N in +v, piecewise linear in t
    /// (`external_force.rs`; mass–spring carriers only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub external_force: Option<ExternalForceSpec>,
}

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

/// `[time]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Time step Δt, s (> 0).
    pub step: f64,
    /// End time, s, or `"carrier_leaves"`.
    pub end: EndTime,
    /// The initial state: `"rest"` (default, MODEL §5: d₀ = 0, ḋ₀ = 0) or
    /// `"static"` (d₀ solves K d₀ = f, `docs/lines.md` eq. W6).
    #[serde(default, skip_serializing_if = "Initial::is_rest")]
    pub initial: Initial,
}

/// `[time] initial`: where the wire starts.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Initial {
    /// Straight and at rest (MODEL §5).
    #[default]
    Rest,
    /// At its static equilibrium under the constant loads, at rest.
    Static,
}

impl Initial {
    /// True for the default.
    pub fn is_rest(&self) -> bool {
        *self == Initial::Rest
    }
}

/// When a run stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndTime {
    /// At this time, s.
    Seconds(f64),
    /// When the first moving carrier reaches a beam end.
    CarrierLeaves,
}

impl Serialize for EndTime {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            EndTime::Seconds(t) => s.serialize_f64(*t),
            EndTime::CarrierLeaves => s.serialize_str("carrier_leaves"),
        }
    }
}

impl<'de> Deserialize<'de> for EndTime {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = EndTime;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a time in seconds or the string \"carrier_leaves\"")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<EndTime, E> {
                Ok(EndTime::Seconds(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<EndTime, E> {
                if v == "carrier_leaves" {
                    Ok(EndTime::CarrierLeaves)
                } else {
                    Err(E::invalid_value(serde::de::Unexpected::Str(v), &self))
                }
            }
        }
        d.deserialize_any(V)
    }
}

fn standard_gravity() -> f64 {
    9.81
}

/// `[gravity]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GravitySpec {
    /// Gravitational acceleration g, m/s² (≥ 0, default 9.81). Acts on carrier masses.
    #[serde(default = "standard_gravity")]
    pub g: f64,
    /// Also load the beam with its self-weight −ρA g (default false, MODEL §1).
    #[serde(default)]
    pub beam_self_weight: bool,
}

impl Default for GravitySpec {
    fn default() -> Self {
        GravitySpec {
            g: standard_gravity(),
            beam_self_weight: false,
        }
    }
}

/// `[[probe]]`: a point whose beam displacement v (positive up) is recorded.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Column name in `history.csv` (letters, digits, `_`, `-`).
    pub name: String,
    /// Position, m (0 ≤ x ≤ L).
    pub x: f64,
    /// The line it reads: `"contact"` (default) or `"messenger"` (v_m,
    /// from the messenger's rest line, positive up; needs `[messenger]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wire: Option<Wire>,
}

/// `[[probe]] wire`: which line a probe reads.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Wire {
    /// The contact wire (the beam).
    Contact,
    /// The messenger wire (`[messenger]`).
    Messenger,
}

/// `[output]`: what the run's history (`history.csv`) keeps.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Record every K-th step in the history (K ≥ 1, default 1); the last
    /// step is always recorded. Statistics are computed from every step
    /// whatever K.
    #[serde(default = "every_step")]
    pub record_every: u64,
    /// Times at which the wire's displacement v(x) along the span is
    /// recorded (`snapshots.csv`), s; each at the step nearest to it
    /// (0 ≤ t ≤ the run's end). Empty: none (and no cost).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub snapshots: Vec<f64>,
    /// Points of a snapshot, equally spaced over [0, L] (≥ 2); default: the
    /// mesh nodes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot_points: Option<u64>,
    /// The space–time field v(x, t) (`field.csv`); absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldSpec>,
    /// Positions of the line's supports (masts), m: strictly increasing in
    /// [0, L]; consecutive pairs are spans. Gives the contact force's
    /// statistics per span (`spans.csv`) and the uplift at each support
    /// (`supports.csv`). Empty: none (and no cost).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub supports: Vec<f64>,
    /// Record the range of v over time at every mesh node (`envelope.csv`,
    /// `line.svg`; default false: not recorded, no cost).
    #[serde(default, skip_serializing_if = "is_false")]
    pub envelope: bool,
}

/// serde's test for a flag left out when false.
fn is_false(b: &bool) -> bool {
    !*b
}

/// `[output] field = { every = K, points = n }`: v(x, t) at every K-th step
/// (t = 0 included) on n points.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FieldSpec {
    /// Record every K-th step (K ≥ 1).
    pub every: u64,
    /// Points, equally spaced over [0, L] (≥ 2); default: the mesh nodes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<u64>,
}

fn every_step() -> u64 {
    1
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            record_every: every_step(),
            snapshots: Vec::new(),
            snapshot_points: None,
            field: None,
            supports: Vec::new(),
            envelope: false,
        }
    }
}

impl OutputSpec {
    /// True for the defaults (then `[output]` is left out when serialized).
    pub fn is_default(&self) -> bool {
        *self == OutputSpec::default()
    }
}
