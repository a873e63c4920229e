//! # taut
//!
//! A verification-first testbed for the dynamic contact between a tensioned
//! beam and a moving mass–spring. The physics contract is MODEL.md (in the
//! project's shared spec, summarized in `docs/model.md`):
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
//! what each may import: `docs/architecture.md`. Above them all,
//! [`pipelines`]: the programs that generate the measured pages of `docs/`.

// Numerical kernels index several arrays in lockstep (A[i][k], x[i − k], …);
// index loops say that more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]

pub mod analytic;
pub mod app;
pub mod budget;
pub mod contact;
pub(crate) mod defects;
pub mod error;
pub mod input;
pub mod integrate;
pub mod interrupt;
pub mod json_keys;
pub mod manufactured;
pub mod model;
pub mod numeric;
pub mod pipelines;
pub mod record;
pub mod report;
pub mod resolve;
pub mod run;
pub mod scene;
pub mod study;
pub mod warnings;

/// The library's version (`taut --version`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub use error::{Error, Result};
pub use resolve::{Resolved, load_scene, resolve_scene};
pub use run::{RunOutput, run, run_batch, run_with};
pub use scene::Scene;
