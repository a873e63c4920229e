//! A whole scene file (docs/model.md §1–§5): every table of it, as plain serde
//! data; each table's own type lives in its own file.

use serde::{Deserialize, Serialize};

use super::analysis::AnalysisSpec;
use super::attachment::AttachmentSpec;
use super::beam::BeamSpec;
use super::carrier::CarrierSpec;
use super::contact::ContactSpec;
use super::dropper::DropperSpec;
use super::generated::Generated;
use super::gravity::GravitySpec;
use super::integrator::IntegratorSpec;
use super::manufactured::{ManufacturedSpec, ReferenceSpec};
use super::mesh::MeshSpec;
use super::messenger::MessengerSpec;
use super::output::{OutputSpec, ProbeSpec};
use super::time::TimeSpec;

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
    /// The filtered force's band and the analysis section of the
    /// standards' statistics (`[analysis]`; `standard.csv`).
    #[serde(default, skip_serializing_if = "AnalysisSpec::is_default")]
    pub analysis: AnalysisSpec,
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

/// The source study's reference case (MODEL §1–§5, docs/targets.md; the
/// same scene as `scenes/reference.toml`): each table's own default, one
/// reference carrier, and the defaults of every optional table. Build a
/// scene in code from it with [`Scene::builder`].
impl Default for Scene {
    fn default() -> Self {
        Scene {
            beam: BeamSpec::default(),
            mesh: MeshSpec::default(),
            carriers: vec![CarrierSpec::default()],
            contact: ContactSpec::default(),
            time: TimeSpec::default(),
            integrator: IntegratorSpec::default(),
            gravity: GravitySpec::default(),
            probes: Vec::new(),
            attachments: Vec::new(),
            droppers: Vec::new(),
            messenger: None,
            output: OutputSpec::default(),
            analysis: AnalysisSpec::default(),
            manufactured: None,
            reference: None,
            generated: Generated::default(),
        }
    }
}
