//! The measured tables of `docs/methods.md`: every time integrator on the
//! study's reference case (TARGETS.md; `scenes/reference.toml`, N = 400).
//!
//! 1. Headline at each method's working step: P_l (whole run and in-span),
//!    contact switches, the largest (re-contact) force, the 0–20 Hz contact
//!    force's relative RMS error against a converged reference, and cost.
//! 2. Convergence as Δt falls: the same quantities at Δt = 1e-4 … 1.25e-5 s.
//! 3. In-span contact loss at V0/c = 0.9 (N = 1600) under every method as
//!    Δt falls.
//! 4. The generalized-α family with a moving constraint: which parameter
//!    sets keep the reference case's contact (unilateral and bilateral)
//!    stable.
//!
//! Run: `cargo run --release --example methods_report` (about a minute);
//! it prints markdown tables. Wall times are this machine's; all other
//! figures are deterministic.
//!
//! The pipeline lives in the library, `taut::pipelines::methods`
//! (`src/pipelines/methods.rs`), so tests can call its parts; this file is
//! its command.

fn main() {
    taut::pipelines::methods::main()
}
