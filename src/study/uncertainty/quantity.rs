//! The quantities `taut uncertainty` gives an error bar (MODEL §7, §12):
//! those the registry offers to error estimation
//! ([`crate::quantity::Offer::UNCERTAINTY`]), each with whether it is smooth
//! in the resolution and its formal orders ([`crate::quantity::Quantity`]).
//! A quantity exact for its discretization (a count of steps) has no error
//! to estimate and is never among them.

use crate::quantity::{Offer, Quantity, estimated};
use crate::run::RunOutput;

pub use crate::quantity::peak;

/// The quantities given an error bar, in the registry's order.
pub fn quantities() -> Vec<&'static Quantity> {
    estimated(Offer::UNCERTAINTY)
}

/// The quantity called `name`, when it is given an error bar.
pub fn quantity(name: &str) -> Option<&'static Quantity> {
    quantities().into_iter().find(|q| q.name == name)
}

/// The names of [`quantities`], comma-separated (an error's allowed values).
pub fn names() -> String {
    quantities()
        .iter()
        .map(|q| q.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Formal orders (space, time) of `q` for a run of `method_order` in Δt
/// whose contacts `switch` (open or close somewhere in the family), on
/// string elements when `string` (MODEL §4, §5; the caps of `run
/// --tolerance`).
pub fn formal_orders(q: &Quantity, method_order: f64, switch: bool, string: bool) -> (f64, f64) {
    q.error
        .formal_orders(method_order, switch, string)
        .expect("quantities() has no exact quantity")
}

/// The value of every quantity of `qs` in `out`, carrier 0, in that order
/// (the 0–20 Hz force filtered once).
pub(crate) fn all_values(out: &RunOutput, qs: &[&Quantity]) -> Vec<Option<f64>> {
    crate::quantity::values(out, 0, qs)
}
