//! Writes its page of tables into the folder `out/xtask/`, in full: taut's refinement studies
//! (the tables behind the figures docs/convergence.md quotes),
//! run through the library (`taut::study::converge`, `taut::run`, the
//! analytic references of `taut::analytic` and `taut::model::modal`).
//!
//! ```text
//! cargo xtask convergence
//! ```
//!
//! Runs are sequential. The page holds only numbers that do not depend on
//! the machine; wall times go to the terminal (stderr) only.
//!
//! One section a file: [`time`] (§1), [`space`] (§2), [`string_limit`]
//! (§3), [`reference`] (§4); [`common`] holds what they share. This file
//! assembles the page.

/// `writeln!` into the page, the result ignored (a `String` cannot fail).
macro_rules! w {
    ($d:expr, $($arg:tt)*) => {
        let _ = writeln!($d, $($arg)*);
    };
}

mod common;
mod reference;
mod space;
mod string_limit;
mod time;

use common::*;
use reference::section_reference;
use space::section_space;
use string_limit::section_string_limit;
use time::section_time;
// ---------------------------------------------------------------- main

/// The section on `taut converge`'s regimes and flags (no computed numbers).
const READING_A_LADDER: &str = r#"## Reading a ladder: regimes and flags

`taut converge` reports, per level and quantity, two orders that answer
different questions, and says whether either can be trusted:

* **`error` and `error_order`**: the error against the scene's declared
  reference ([scene.md](scene.md#reference): `manufactured`,
  `moving_force_series`, `riding_mass_galerkin`, `standing_force_modes`) and
  its order between successive levels. This is the order of the error a
  user has. Without an exact reference `error` is against a Richardson
  extrapolation of the same runs, and no `error_order` is given; the
  `reference` column then says what that estimate measures:
  `richardson (Δt error only)` for a Δt ladder, `(mesh error only)` or
  `(J error only)` for a space ladder (the other variable's error is
  **unmeasured**, and the `regime` says so), `(mesh and Δt)` for
  `--refine both`. On `scenes/moving_force_beam.toml` without its
  `[reference]` (N = 50, three levels from Δt = 4e-4 s) the Δt ladder's
  estimate at the finest level is 5.4e-6 m (L2) while the true error is
  1.33e-4 m: the mesh's, which a Δt ladder cannot see (`taut converge
  scenes/moving_force_beam.toml --refine step --levels 3 --set
  'reference.kind="richardson"'`, and without the `--set` for the true
  error).
* **`observed_order`**: from successive differences of the runs. It isolates
  the refined variable, but it can look asymptotic while the error stalls:
  on `scenes/moving_force_beam.toml` (N = 50) a Δt ladder shows a difference
  order of 1.62 while its error against the series does not move
  (`error_order` −0.01) — the mesh makes the error. It is never called
  `analytic`.
* **`gci` and `u_num`**: Roache's grid convergence index of the level
  (relative, with F_s = 1.25 when the observed order is within ±0.5 of
  `formal_order`, 3 otherwise; `taut::study::uncertainty::Gci`) and the
  level's numerical uncertainty in the quantity's unit, from the
  estimators of `taut uncertainty` ([verification.md](verification.md#solution-verification-taut-uncertainty)):
  of the refined variable's error only unless both are refined.
* **`mesh_share`** (`--refine both`): each level ℓ ≥ 1 is run once more
  with its mesh (or J) and the previous level's Δt, which splits the
  level's change into its mesh part and its Δt part; the column is the
  mesh's share.

Each level ends at its last whole step before the scene's end time, so
any `time.end` works: the levels are compared at the coarsest level's
times, which every level reaches (the runs' ends differ by less than the
coarsest Δt).

`regime` names what a level shows, by these criteria (constants in
`taut::study::converge`):

| regime | criterion | why this threshold |
|---|---|---|
| `limited by the mesh` / `by Δt` / `by J` | the error against the exact reference falls by less than `STALL_RATIO` = 1.25 from the previous level (order < 0.32 at r = 2); names what the ladder does not refine | between the slowest useful rate (first order, ×2 per halving) and the ±10 % a stalled error wanders by |
| `growing: round-off or an instability` | the error against the exact reference rises by more than `STALL_RATIO` as the refined variable falls: a fixed mesh makes a floor, not a rise; a contact force at small Δt has a round-off floor ∝ ε\|w\|/Δt² (the multiplier is −g_free/W with W ∝ Δt²) | as above |
| `not converging` | the same on successive differences (falling by less than 1.25× or rising), when there is no exact reference | |
| `pre-asymptotic` | successive orders differ by more than `ORDER_DRIFT` = 0.3 (the ratio of successive error ratios, column `ratio_change`, outside r^(±0.3) = 0.81 … 1.23 at r = 2), or the order is more than `FORMAL_GAP` = 0.3 from `formal_order` | the leading error term does not yet dominate the next; ±0.3 is what `taut verify` allows a smooth case |
| `asymptotic` | neither | |
| `diverged` | a run of the ladder blew up (the ladder stops there; the level's row names the step, time and quantity), or a level's error (difference, without a reference) is at least `DIVERGED_RELATIVE` = 1 times the quantity itself | an error as large as the quantity is no discretization error: a Newmark ladder's force error of 250 N on a 15 N force was once called `limited by the mesh` |

Without an exact reference, a one-variable ladder's regime ends with
"the error of the mesh is unmeasured" (or of Δt, of J): its `asymptotic`
is the refined variable's, not the result's.

`omega_max_dt` is ω_max·Δt of each level's model. Above 1 its top modes are
not resolved in time; a moving point load excites them, so its Δt order
falls towards 1.5 on fine meshes. The manufactured ladders of
[verification.md](verification.md#code-verification-manufactured-solutions-and-taut-verify)
show order 2 at ω_max·Δt ≈ 10–170, since a smooth source does not excite
them. On `scenes/verify/mms_beam_time.toml` (N = 64) the Δt ladder's
displacement error falls at 2.00 at ω_max·Δt = 84 … 10; its force error at
1.89–1.99 against the manufactured λ\* at the time the multiplier acts,
while successive differences of the recorded forces say 1.00 (they compare
forces acting half a step apart). With a galerkin basis (J = 32) and Δt
from 4e-5 s down, the force error grows (7.3e-7, 2.1e-7, 4.3e-7, 1.4e-6 N):
`growing`, the round-off floor.

    taut converge scenes/moving_force_beam.toml --refine step --levels 3
    taut converge scenes/verify/mms_beam_time.toml --refine step --levels 4 --set mesh.elements=64
    taut converge scenes/verify/mms_beam_time.toml --refine step --levels 4 --set time.step=4e-5 --set mesh.kind=galerkin --set mesh.modes=32

"#;

/// The report: what `cargo xtask convergence` runs (its
/// command-line arguments, if any, are read here).
pub fn main() {
    let mut clock = Clock::new();

    // the analytic reference of the moving-force beam, shared by §1 and §2b
    let beam = resolve_scene(&scene_text("moving_force_beam"), &[]).expect("moving_force_beam");
    let reference = analytic_w(&beam).expect("the moving-force beam has an analytic reference");
    let samples = (beam.steps as f64 * beam.dt / EXACT_DT).round() as usize;
    let exact: Vec<f64> = (0..=samples)
        .map(|i| reference(i as f64 * EXACT_DT))
        .collect();
    clock.lap("analytic moving-force beam");

    let mut body = String::new();
    let mut summary = Vec::new();
    summary.extend(section_time(&mut body, &mut clock, &exact));
    summary.extend(section_space(&mut body, &mut clock, &exact));
    summary.extend(section_string_limit(&mut body, &mut clock));
    summary.extend(section_reference(&mut body, &mut clock));

    let mut doc = String::new();
    let d = &mut doc;
    w!(d, "# Convergence: what refinement shows\n");
    w!(
        d,
        "*This page is generated, in full, by `cargo xtask convergence` \
         (`xtask/src/convergence/`), taut {}. Do not edit it by \
         hand: run that command again. Every number on it is computed by that run through \
         the library (`taut::study::converge`, `taut::run`, `taut::analytic`, \
         `taut::model::modal`), and none depends on the machine: wall times go to the \
         terminal only. Each table names the CLI command that reproduces its runs.*\n",
        taut::VERSION
    );
    w!(
        d,
        "[Reading a ladder](#reading-a-ladder-regimes-and-flags) · [Summary](#summary) · \
         [1. Time](#1-time) · [2. Space](#2-space) · \
         [3. The string limit](#3-the-string-limit) · \
         [4. Contact loss](#4-contact-loss-the-reference-case)\n"
    );
    // the regimes of `taut converge` (static text: the criteria, not numbers)
    d.push_str(READING_A_LADDER);
    w!(d, "## Summary\n");
    for s in &summary {
        w!(d, "* {s}");
    }
    w!(d, "");
    d.push_str(&body);

    let dir = format!("{}/out/xtask", crate::ROOT);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{dir}: {e}"));
    let path = format!("{dir}/convergence.md");
    std::fs::write(&path, doc).unwrap_or_else(|e| panic!("{path}: {e}"));
    eprintln!(
        "wrote {path} in {:.1} s",
        clock.start.elapsed().as_secs_f64()
    );
}
