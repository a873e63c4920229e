//! Stability at the extremes: runs the reference case (and other bundled
//! scenes where more apt) at extreme parameters and resolutions, for each
//! contact formulation where it makes sense, and writes `docs/stability.md`.
//!
//!     cargo run --release --example stability_report
//!
//! Every row is one `taut run` (its command is written next to it). Its
//! outcome is one of: ran, ran with warnings, stopped with a diagnosis, or
//! rejected as invalid input. Where a reference exists (a better-resolved
//! Lagrange run of the same physics, the bundled reference case, or the
//! analytic solution of a moving-force scene), the row is scored for accuracy;
//! a run that finishes without warning yet is clearly off its reference is
//! listed under "Findings" as silently wrong. Runs are sequential and take
//! a little over a minute on two cores.
//!
//! The pipeline lives in the library, `taut::pipelines::stability`
//! (`src/pipelines/stability/`), so tests can call its parts; this file is
//! its command.

fn main() {
    taut::pipelines::stability::main()
}
