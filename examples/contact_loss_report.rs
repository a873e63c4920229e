//! The measured tables of `docs/contact_loss.md`: contact loss you can
//! trust on the study's reference case (TARGETS.md; `scenes/reference.toml`).
//!
//! 1. P_l split into an in-span part and a support part (the carrier's
//!    arrival at a support, inside the support zone of width
//!    z = max(4ℓ_b, 4h, 4VΔt) from each end), over a Δt ladder at N = 1600
//!    and an h ladder at Δt = 2.5e-5 s, at V0/c = 0.9 and at the scene's own
//!    100 m/s; observed exponents of the support part in Δt and h; where
//!    (in bending lengths from the support) the lost steps lie; other zone
//!    constants tried.
//! 2. Re-contact force peaks and impulses over the Δt ladder: the peak's
//!    power law in Δt, the impulse's convergence, the closing speed Δv and
//!    the string impedance Z·Δv.
//!
//! Run: `cargo run --release --example contact_loss_report` (full), or
//! `cargo run --release --example contact_loss_report -- quick` (a cut-down
//! ladder). It prints markdown tables to stdout; wall times go to stderr.
//! All printed figures are deterministic.
//!
//! The pipeline lives in the library, `taut::pipelines::contact_loss`
//! (`src/pipelines/contact_loss/`), so tests can call its parts; this file is
//! its command.

fn main() {
    taut::pipelines::contact_loss::main()
}
