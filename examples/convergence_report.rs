//! Regenerates `docs/convergence.md`, in full: taut's refinement studies,
//! run through the library (`taut::study::converge`, `taut::run`, the
//! analytic references of `taut::analytic` and `taut::model::modal`).
//!
//!     cargo run --release --example convergence_report
//!
//! Runs are sequential. The page holds only numbers that do not depend on
//! the machine; wall times go to the terminal (stderr) only.
//!
//! The pipeline lives in the library, `taut::pipelines::convergence`
//! (`src/pipelines/convergence/`), so tests can call its parts; this file is
//! its command.

fn main() {
    taut::pipelines::convergence::main()
}
