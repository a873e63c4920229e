//! The library's numerical tests in one binary (one link, not
//! nineteen): verification against analytic and manufactured references,
//! methods, discretizations, contact laws, batches and properties. Each
//! file below is a module, run with its name as a filter, e.g.
//! `cargo test --release --test numerics modal_exact::`. A new test file
//! joins a group here or in `front.rs`, whose
//! `every_test_file_runs_in_some_binary` fails on a file in no group.

/// Shared helpers (one copy for the whole binary).
mod common;

/// The backward-Euler example (examples/custom_method.rs), used by the
/// manufactured and methods tests.
#[path = "../examples/custom_method.rs"]
mod custom_method;

#[path = "attachments.rs"]
mod attachments;
#[path = "banded_faer.rs"]
mod banded_faer;
#[path = "batch.rs"]
mod batch;
#[path = "carriers.rs"]
mod carriers;
#[path = "contact_loss.rs"]
mod contact_loss;
#[path = "convergence.rs"]
mod convergence;
#[path = "damping.rs"]
mod damping;
#[path = "discretizations.rs"]
mod discretizations;
#[path = "dropper_damping.rs"]
mod dropper_damping;
#[path = "droppers.rs"]
mod droppers;
#[path = "elastic_supports.rs"]
mod elastic_supports;
#[path = "form_finding.rs"]
mod form_finding;
#[path = "formulations.rs"]
mod formulations;
#[path = "galerkin_order.rs"]
mod galerkin_order;
#[path = "invariants.rs"]
mod invariants;
#[path = "line_outputs.rs"]
mod line_outputs;
#[path = "manufactured.rs"]
mod manufactured;
#[path = "messenger.rs"]
mod messenger;
#[path = "methods.rs"]
mod methods;
#[path = "mms_attachments.rs"]
mod mms_attachments;
#[path = "mms_two_wires.rs"]
mod mms_two_wires;
#[path = "modal_exact.rs"]
mod modal_exact;
#[path = "modal_impact.rs"]
mod modal_impact;
#[path = "pantograph_chain.rs"]
mod pantograph_chain;
#[path = "pantograph_uplift.rs"]
mod pantograph_uplift;
#[path = "properties.rs"]
mod properties;
#[path = "static_start.rs"]
mod static_start;
#[path = "subnormal.rs"]
mod subnormal;
#[path = "time_orders.rs"]
mod time_orders;
#[path = "uncertainty.rs"]
mod uncertainty;
#[path = "verification_contact.rs"]
mod verification_contact;
#[path = "verification_riding_mass.rs"]
mod verification_riding_mass;
#[path = "verification_t1_cantilever.rs"]
mod verification_t1_cantilever;
#[path = "verification_t2_wave_travel.rs"]
mod verification_t2_wave_travel;
#[path = "wire.rs"]
mod wire;
