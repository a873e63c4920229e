//! Reproduces the source study's parameter studies (TARGETS T3–T7: Lee, Cho
//! & Chung 2012, Figs 8–12) through the library and writes
//! `docs/reproduction.md` and its maps in `docs/reproduction/`, in full:
//!
//!     cargo run --release --example reproduction_report
//!     cargo run --release --example reproduction_report -- --full     # T7 at 41 × 41 refined too
//!     cargo run --release --example reproduction_report -- --resume   # keep finished runs
//!
//! Every target is run twice: at a resolution like the study's (N = 400,
//! Δt = 1e-4 s) and at a refined one (N = 1600, Δt = 2.5e-5 s), each on a
//! grid like the study's, with `taut::study::sweep` (rayon over the cores).
//! The page sets the study's published statements beside what taut
//! measures, with the criteria of every verdict; nothing is tuned to a
//! published plot. Runs go to `target/reproduction/` (cleared at the start
//! unless `--resume`). Wall times go to the terminal only, so the page does
//! not depend on the machine. About 7 minutes on two free cores (10 while
//! a build shares them).
//!
//! The pipeline lives in the library, `taut::pipelines::reproduction`
//! (`src/pipelines/reproduction/`), so tests can call its parts; this file is
//! its command.

fn main() {
    taut::pipelines::reproduction::main()
}
