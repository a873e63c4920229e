//! One definition per quantity.
//!
//! A number taut reports — P_l, the mean contact force, the largest
//! displacement under the carrier — is defined once, here, by a
//! [`Quantity`]: its name (the CSV column, JSON key, gate name and Python
//! key), unit, definition, the window it is measured over, whether it is
//! smooth in the resolution, how its discretization error behaves (its
//! formal orders), which tables offer it, and how it is read from a run.
//! Run summaries, the compare, precision, sweep, converge, uncertainty and
//! `run --tolerance` tables, the gate, the report and the Python module all
//! read the [`registry`]; none keeps a list of its own. Adding a statistic
//! is one definition and one registration (docs/architecture.md, "Adding a
//! statistic").
//!
//! A quantity's definition never depends on h, Δt or J: its window is the
//! scene's end time and its sections are physical lengths (MODEL §7), so a
//! refinement study refines one quantity, not a family of them.

mod builtin;
mod definition;
pub mod formal_orders;
mod reading;
pub mod registry;
mod values;

/// The generation of the quantities' definitions. It changes when a
/// definition does (2: time statistics over [0, T], P_l a located time, a
/// physical support zone), so that what was stored under another — a
/// sweep's records — is never mixed with what is computed now.
pub const DEFINITIONS: u32 = 2;

pub use builtin::*;
pub use definition::{ErrorKind, Offer, Quantity, Window};
pub use reading::Reading;
pub use registry::{all, by_name, estimated, offered, register};
pub use values::{Values, values};
