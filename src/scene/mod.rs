//! Scene files: what a run needs, as plain serde data (docs/model.md §1–§5).
//!
//! A scene is TOML. Every table rejects unknown keys. Loading is three steps:
//! parse the text into a TOML tree, apply `--set` overrides on the tree
//! (`load`), then deserialize and `Scene::validate` (the resolve layer,
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

mod analysis;
mod attachment;
mod beam;
mod carrier;
mod contact;
mod damping;
mod discretization;
mod dropper;
mod external_force;
mod generated;
mod gravity;
mod integrator;
mod line;
mod line_design;
mod line_props;
mod line_supports;
mod load;
pub mod manufactured;
mod mesh;
mod messenger;
mod messenger_support;
mod method;
mod method_choice;
mod method_registry;
mod motion;
mod output;
mod pantograph;
mod props;
mod range;
pub(crate) mod scales;
mod scene_file;
mod scheme;
mod speed;
mod steady_arm;
mod table_files;
pub mod tables;
mod time;
mod validate;

pub use analysis::{AnalysisSpec, speed_unit};
pub(crate) use attachment::contact_indices;
pub use attachment::{Attachment, AttachmentSpec};
pub use beam::{BeamSpec, Support};
pub use carrier::{CarrierSpec, Side};
pub use contact::{
    ComplementaritySolver, ComplementaritySpec, ContactKind, ContactSpec, Formulation, ImpactSpec,
    PenaltySpec, Placement,
};
pub(crate) use damping::resolve_rayleigh;
pub use damping::{Rayleigh, RayleighSpec};
pub(crate) use discretization::{DEFAULT_GRADING_RATIO, MAX_GRADING_RATIO, fe_unknowns};
pub use discretization::{Discretization, Grading, MeshPlan};
pub(crate) use dropper::resolve_droppers;
pub use dropper::{Anchor, AnchorSpec, Dropper, DropperSpec};
pub use external_force::{ExternalForceSpec, ForceSeries};
pub use generated::Generated;
pub use gravity::GravitySpec;
pub use integrator::{IntegratorSpec, Key};
pub(crate) use line::expand_line;
pub use load::UNSET;
pub(crate) use load::{
    apply_override, check_is_scene, in_file, parse_scene, read_scene, scene_from_tree,
    scene_with_overrides, set_typed, with_table_files,
};
pub use manufactured::{Declared, ManufacturedSpec, ReferenceKind, ReferenceSpec};
pub use mesh::{GradingKind, MeshKind, MeshSpec};
pub use messenger::{Messenger, MessengerSpec};
pub use messenger_support::ElasticSupport;
pub(crate) use method::impact_refusal;
pub use method::{Method, MethodInfo, Parameter};
pub use method_choice::ResolvedMethod;
pub use method_registry::MethodRef;
pub(crate) use method_registry::{method_names, method_ref, register_method};
pub use motion::Motion;
pub use output::{FieldSpec, OutputSpec, ProbeSpec, Wire};
pub use pantograph::ChainProps;
pub(crate) use pantograph::MAX_CHAIN;
pub use props::{BeamProps, CarrierKind, CarrierProps, TimeProps};
pub use scene_file::Scene;
pub use scheme::{GenAlphaParams, ParameterValues, Scheme};
pub use speed::SpeedProfile;
pub use time::{EndTime, Initial, TimeSpec};
pub use validate::MAX_STEPS;
pub(crate) use validate::check_chain_scene;
pub(crate) use validate::{DEFAULT_PENALTY_RELATIVE, check_speed_tables_cover, validate_contact};
