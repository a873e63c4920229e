//! taut's tools for its own repository (the `xtask` pattern): the programs
//! that regenerate the measured pages of `docs/`, run as
//! `cargo xtask <page>` (an alias of `cargo run --release -p xtask --`, in
//! `.cargo/config.toml`). They are users of the `taut` library like any
//! other: they import only its public API, and nothing in the library or
//! the CLI imports them. Tests call some of their parts (e.g.
//! [`methods::scene`], [`methods::force_error`]) to check a page's claims
//! in the default suite.
//!
//! | module | page | command |
//! |---|---|---|
//! | [`methods`] | the tables behind `docs/methods.md` (printed) | `cargo xtask methods > out/xtask/methods.md` |
//! | [`contact_loss`] | the tables behind `docs/contact_loss.md` (printed) | `cargo xtask contact-loss [quick] > out/xtask/contact_loss.md` |
//! | [`convergence`] | the folder `out/xtask/`: the tables `docs/convergence.md` quotes | `cargo xtask convergence` |
//! | [`stability`] | `out/xtask/stability.md` (written in full; explained in `docs/stability.md`) | `cargo xtask stability` |
//! | [`reproduction`] | the folder `out/xtask/`: the tables `docs/reproduction.md` quotes; the maps in `docs/reproduction/` | `cargo xtask reproduction [--full] [--resume]` |
//! | [`published_band`] | the tables of `docs/reproduction.md`'s last section (printed) | `cargo xtask published-band` |
//! | [`accuracy_check`] | the tables of `docs/accuracy.md` (printed) | `cargo xtask accuracy-check grid\|check …` |
//! | [`uncertainty`] | the coverage tables behind `docs/verification.md` ("Solution verification"; printed) | `cargo xtask uncertainty [quick] [--dump FILE] > out/xtask/uncertainty.md`, `cargo xtask uncertainty replay FILE [--pairs OUT]` |

/// The repository's top folder (scenes/, docs/): this crate sits one below it.
pub const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

pub mod accuracy_check;
pub mod contact_loss;
pub mod convergence;
pub mod methods;
pub mod published_band;
pub mod reproduction;
pub mod stability;
pub mod uncertainty;
