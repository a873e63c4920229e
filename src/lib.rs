//! # taut
//!
//! A verification-first testbed for the dynamic contact between a tensioned
//! beam and a moving mass–spring. The physics contract is `docs/model.md`
//! (cited as MODEL §N):
//!
//! * §1 the continuum `ρA v_tt + EI v_xxxx − T v_xx = p + λ δ(x − x_m)`;
//! * §2 the carrier `m q_tt + c_s q_t + k q = k δ0 − s m g − λ` and the gap
//!   `g = w − q ≥ 0` with Signorini conditions;
//! * §3 speed profiles and the carrier's motion ([`scene::Motion`]);
//! * §4 Hermite beam elements with tension ([`model::element`], [`model::beam`]);
//! * §5 generalized-α with contact, A factored once per run, and §9.1 the
//!   other time integrators behind one seam ([`integrate`]);
//! * §6 contact formulations ([`contact`]) and string elements for EI = 0;
//! * §7 measured quantities ([`record`]).
//!
//! The flow of a run: [`scene`] (parsed, plain data) → [`resolve`]
//! (checked against the model: a [`Resolved`]) → [`integrate::Integrator`]
//! → [`record::History`] → [`report`] (CSV / JSON / SVG). The layers and
//! what each may import: `docs/architecture.md`. The `taut` command line
//! (crate `taut-cli`), the Python module (`taut-python`) and the programs
//! that regenerate `docs/` (`xtask`) are crates of their own over this one.

// Numerical kernels index several arrays in lockstep (A[i][k], x[i − k], …);
// index loops say that more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]
// every public item says what it is (docs/api.md lists the surface)
#![warn(missing_docs)]

pub mod analytic;
pub mod app;
pub(crate) mod budget;
pub mod contact;
pub(crate) mod defects;
pub mod error;
pub(crate) mod input;
pub mod integrate;
pub mod interrupt;
pub(crate) mod json_keys;
pub(crate) mod manufactured;
pub mod model;
pub(crate) mod numeric;
pub mod quantity;

pub mod record;
pub mod report;
pub mod resolve;
pub mod run;
pub mod scene;
pub mod study;
pub(crate) mod warnings;

/// The library's version (`taut --version`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub use error::{Error, Result};
pub use resolve::{Resolved, load_scene, resolve_scene};
pub use run::{RunOutput, run, run_batch, run_with};
pub use scene::Scene;

// docs/api.md's count of public items, held to the sources
#[cfg(test)]
mod api_surface;

// docs/api.md's examples, one per entry point, run as doc tests
// (`cargo test --doc -p taut`)
#[cfg(doctest)]
#[doc = include_str!("../docs/api.md")]
struct ApiDocTests;
