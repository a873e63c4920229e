//! `[[probe]]` and `[output]`: what a run records besides the carriers
//! (docs/output.md).

use serde::{Deserialize, Serialize};

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
