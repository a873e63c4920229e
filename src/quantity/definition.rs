//! What a quantity is: its name, unit and meaning, the window it is taken
//! over, how its discretization error behaves, which tables offer it, and
//! how it is read from a run ([`Quantity`]).

use super::formal_orders::{
    MAX_MESH_ORDER, MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER, MAX_STEP_ORDER_CONTACT,
};
use super::reading::Reading;

/// Where in time (and along the span) a quantity is measured. Every
/// window is fixed by the scene's physics and end time, never by h, Δt or
/// J, so that every level of a refinement study measures the same thing
/// (docs/model.md, "Measured quantities").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Window {
    /// Over the run, t ∈ [0, t_end]: a time average, an extreme or a
    /// count over the whole run.
    Run,
    /// Over the run, split at the support zones, whose width
    /// (`[analysis] support_zone`) is a physical length (MODEL §7).
    RunSplitAtSupports,
    /// At the end time t_end.
    End,
    /// A property of the discretization itself (steps, unknowns): not a
    /// physical quantity, never refined.
    Discretization,
}

/// How a quantity's discretization error behaves: its formal orders in h
/// and Δt (MODEL §4, §5, §12).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// The beam's displacement and what is taken from it: Hermite O(h⁴)
    /// (strings O(h²)), the method's order in Δt while no contact
    /// switches, O(Δt) once one does.
    Displacement,
    /// The contact force and what is counted from it: O(h²), O(Δt).
    Contact,
    /// Exact for its discretization (a count of steps or unknowns): no
    /// error to estimate.
    Exact,
}

impl ErrorKind {
    /// Formal orders (space, time) for a run of `method_order` in Δt whose
    /// contacts `switch` (open or close somewhere in the study), on string
    /// elements when `string`; `None` for [`ErrorKind::Exact`].
    pub fn formal_orders(
        self,
        method_order: f64,
        switch: bool,
        string: bool,
    ) -> Option<(f64, f64)> {
        match self {
            ErrorKind::Displacement => Some((
                if string { 2.0 } else { MAX_MESH_ORDER },
                if switch {
                    MAX_STEP_ORDER_CONTACT
                } else {
                    method_order.min(MAX_STEP_ORDER)
                },
            )),
            ErrorKind::Contact => Some((MAX_MESH_ORDER_FORCE, MAX_STEP_ORDER_CONTACT)),
            ErrorKind::Exact => None,
        }
    }
}

/// The tables and studies that offer a quantity, as a set. A quantity
/// registered by a user is offered everywhere ([`Offer::ALL`]); the
/// built-ins say where each belongs. Every quantity can be gated (`taut
/// gate`) and is in `summary.json`'s `quantities`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Offer(u8);

impl Offer {
    /// Nowhere but the run summary and the gate.
    pub const NONE: Offer = Offer(0);
    /// The tables with one row per run: `compare.csv`, `precision.csv`,
    /// `sweep.csv` (and their JSON).
    pub const RUN_TABLES: Offer = Offer(1);
    /// `taut converge`: a row per level with its observed order.
    pub const CONVERGE: Offer = Offer(1 << 1);
    /// `taut uncertainty`, the accuracy-targeted sweep and `run
    /// --tolerance` (its targets are those of the run tables too): an
    /// error bar.
    pub const UNCERTAINTY: Offer = Offer(1 << 2);
    /// Every table and study.
    pub const ALL: Offer = Offer(0b111);

    /// Both sets.
    pub const fn and(self, other: Offer) -> Offer {
        Offer(self.0 | other.0)
    }

    /// Whether `self` holds every table of `other`.
    pub const fn has(self, other: Offer) -> bool {
        self.0 & other.0 == other.0
    }
}

/// One quantity, defined once: every table, study, gate, report and the
/// Python module read it from here (docs/architecture.md, "Adding a
/// statistic").
#[derive(Debug, Clone, Copy)]
pub struct Quantity {
    /// Its name: the CSV column, the JSON key, the gate's and Python's
    /// name (snake case).
    pub name: &'static str,
    /// Its label on the terminal.
    pub label: &'static str,
    /// Its unit (`N`, `m`, `x/L`, `s`, `-`).
    pub unit: &'static str,
    /// What it is, in one sentence (docs/model.md lists them).
    pub definition: &'static str,
    /// What it is measured over.
    pub window: Window,
    /// An integer count (steps, switches, intervals): written as one.
    pub count: bool,
    /// False for a count of events or an extreme of the raw force: it
    /// moves in jumps, not smoothly, as the resolution changes (MODEL
    /// §12), so error estimators treat it with the cautious factor of
    /// safety.
    pub smooth: bool,
    /// How its error behaves.
    pub error: ErrorKind,
    /// Where it is offered.
    pub offer: Offer,
    /// Its value in one run for one carrier (`None` where undefined: the
    /// first loss of a contact never lost, a scene without supports).
    pub read: fn(&Reading) -> Option<f64>,
}

impl Quantity {
    /// Whether a table or study of kind `offer` offers it.
    pub fn offered_in(&self, offer: Offer) -> bool {
        self.offer.has(offer)
    }

    /// Its value for `carrier` of `out` (`None` where undefined, or when
    /// the run has no such carrier).
    pub fn of(&self, out: &crate::run::RunOutput, carrier: usize) -> Option<f64> {
        Reading::new(out, carrier).and_then(|r| (self.read)(&r))
    }
}

impl PartialEq for Quantity {
    /// Two definitions are the same quantity when they have one name (the
    /// registry refuses a second definition of a name).
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl serde::Serialize for Quantity {
    /// By its name, as every table writes it.
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name)
    }
}
