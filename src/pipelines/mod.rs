//! Report pipelines: the programs that generate the measured pages of
//! `docs/`, each a `main` that `examples/<name>_report.rs` calls
//! (`cargo run --release --example <name>_report`), and parts that tests
//! call as a library (e.g. [`methods::scene`], [`methods::force_error`]).
//!
//! They sit above every other module (they run scenes, studies and reports
//! and print or write the results); nothing in the library imports them.
//!
//! | module | page | command |
//! |---|---|---|
//! | [`methods`] | `docs/methods.md` (measured tables) | `cargo run --release --example methods_report` |
//! | [`contact_loss`] | `docs/contact_loss.md` (measured tables) | `cargo run --release --example contact_loss_report` |
//! | [`convergence`] | `docs/convergence.md` (written in full) | `cargo run --release --example convergence_report` |
//! | [`stability`] | `docs/stability.md` (written in full) | `cargo run --release --example stability_report` |
//! | [`reproduction`] | `docs/reproduction.md` and `docs/reproduction/` | `cargo run --release --example reproduction_report` |

pub mod contact_loss;
pub mod convergence;
pub mod methods;
pub mod reproduction;
pub mod stability;
