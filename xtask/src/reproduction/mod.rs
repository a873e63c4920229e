//! Reproduces the source study's parameter studies (TARGETS T3–T7: Lee, Cho
//! & Chung 2012, Figs 8–12) through the library and writes
//! its page of tables into the folder `out/xtask/` (the tables behind the figures
//! docs/reproduction.md quotes) and its maps in `docs/reproduction/`:
//!
//! ```text
//! cargo xtask reproduction
//! cargo xtask reproduction --full     # T7 at 41 × 41 refined too
//! cargo xtask reproduction --resume   # keep finished runs
//! ```
//!
//! Every target is run twice: at a resolution like the study's (N = 400,
//! Δt = 1e-4 s) and at a refined one (N = 1600, Δt = 2.5e-5 s), each on a
//! grid like the study's, with `taut::study::sweep` (rayon over the cores).
//! The page sets the study's published statements beside what taut
//! measures, with the criteria of every verdict; nothing is tuned to a
//! published plot. Runs go to `target/reproduction/` (cleared at the start
//! unless `--resume`). Wall times go to the terminal only, so the page does
//! not depend on the machine. About 7 minutes on an AMD
//! EPYC, 2 vCPUs.

//!
//! One study a file: [`targets_1d`] (T3–T6), [`t7`] (T7), [`resolution`]
//! (the resolution check), [`findings`]; [`measures`] and [`common`] hold
//! what they share. This file runs them and writes the page.

mod common;
mod findings;
mod measures;
mod resolution;
mod t7;
mod targets_1d;

use common::*;
use findings::*;
use measures::*;
use resolution::*;
use t7::*;
use targets_1d::*;
// ------------------------------------------------------------ main

/// The report: what `cargo xtask reproduction` runs (its
/// command-line arguments, if any, are read here).
pub fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let full = args.iter().any(|a| a == "--full");
    let resume = args.iter().any(|a| a == "--resume");
    let clock = Clock {
        start: Instant::now(),
    };
    let work = root().join("target/reproduction");
    if !resume && work.exists() {
        std::fs::remove_dir_all(&work).expect("clear target/reproduction");
    }
    let maps = root().join("docs/reproduction");
    std::fs::create_dir_all(&maps).expect("docs/reproduction");
    // the folder holds only this page's maps: drop any stale ones
    for e in std::fs::read_dir(&maps)
        .expect("docs/reproduction")
        .flatten()
    {
        if e.path().extension().is_some_and(|x| x == "svg") {
            std::fs::remove_file(e.path()).expect("remove a stale map");
        }
    }
    eprintln!(
        "reproduction report: T3–T7 at two resolutions on {} threads{}",
        rayon::current_num_threads(),
        if resume { " (resuming)" } else { "" }
    );

    let checks = resolution_check(&clock);
    let mut results = Vec::new();
    for t in &TARGETS_1D {
        let s = run_1d(&clock, t, STUDY, &maps);
        let c = run_1d(&clock, t, CONVERGED, &maps);
        results.push((t, s, c));
    }
    let t7s = run_t7(&clock, STUDY, T7_STUDY_GRID, &maps);
    let t7c = run_t7(
        &clock,
        CONVERGED,
        if full {
            T7_STUDY_GRID
        } else {
            T7_CONVERGED_GRID
        },
        &maps,
    );

    let convergence_doc = root().join("docs/convergence.md").is_file();
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Reproduction of the study's parameter studies (TARGETS T3–T7)\n"
    );
    let _ = writeln!(
        md,
        "*Generated in full by `cargo xtask reproduction`{} (xtask/src/reproduction/), with the maps in `docs/reproduction/`. Do not edit by hand: change the pipeline and run it again.*\n",
        if full { " -- --full" } else { "" }
    );
    let _ = writeln!(
        md,
        "Source: Lee, Cho & Chung, *Dynamic contact analysis of a tensioned beam with a moving mass–spring system*, J. Sound Vib. 331 (2012) 2520–2531, Figs 8–12. \
Every run is the bundled reference scene (`scenes/reference.toml`: clamped–pinned wire, L = 50 m, T = 3e4 N, ρA = 1.335 kg/m, EI = 129.2 N·m², 1 kg on k = 987 N/m with δ0 = 0.05 m riding on top, smooth start to V0, Lagrange contact imposed at t_{{n+1}}, ρ∞ = 1) with one or two values swept by `taut sweep`. \
The published statements are the study's words and numbers as [targets.md](targets.md) records them; its figures can only be read approximately. Nothing here is tuned to match them: where taut differs, that is a finding, with the evidence beside it.\n"
    );
    let _ = writeln!(md, "**Terms.**\n");
    let every: Vec<&Point> = results
        .iter()
        .flat_map(|(_, s, c)| s.points.iter().chain(&c.points))
        .chain(&t7s.points)
        .chain(&t7c.points)
        .collect();
    let all_runs = every.len();
    let lose_at_end = every
        .iter()
        .filter(|p| p.first_loss.is_some() && p.pl > p.pl_span)
        .count();
    let slow = &results[0].2.points[0];
    let _ = writeln!(
        md,
        "- *P_l*: the fraction of the run's steps with the contact open (λ = 0, gap > 0), as the study defines it."
    );
    let _ = writeln!(
        md,
        "- *P_l,span*: the same, counting only the steps with x_m/L < {SPAN_END}. {} of the {} runs on this page lose contact at the end, as the carrier runs onto the pinned support (the beam under it must rise to v = 0 there, which launches the mass; at V0/c = {}, refined: first loss at x_m/L = {}, P_l = {}). P_l,span separates that from loss in the span. It is computed from the runs' {PROFILE_BINS}-bin loss profiles, weighted by the time spent in each bin.",
        lose_at_end,
        all_runs,
        g(slow.ratio, 2),
        opt(slow.first_loss, 4),
        g(slow.pl, 2)
    );
    let _ = writeln!(
        md,
        "- *loss in the span* at a grid value: P_l,span > 0. Loss maps are black where any step in the x_m/L bin had the contact open."
    );
    let _ = writeln!(
        md,
        "- *level*, *fluctuation*: the mean, and the max − min, of the {PROFILE_BINS}-bin mean forces over x_m/L ∈ [{}, {}) (past the start ramp, before the support); the whole-run mean and standard deviation include the re-contact spikes, whose size depends on Δt (no impact law: TARGETS), so the bin measures are the ones to trust.",
        MID.0, MID.1
    );
    let _ = writeln!(
        md,
        "- A published border *agrees* when taut's is within {BORDER_STEPS} grid steps of it; a published trend *agrees* when Spearman's rank correlation with the swept value has its sign and |ρ| ≥ {TREND_RHO}. *Survives refinement*: the verdict is the same at the refined resolution.\n"
    );

    // findings first: filled after the sections are written
    let mut body = String::new();
    write_check(&mut body, &checks, convergence_doc);
    for (t, s, c) in &results {
        write_1d(&mut body, t, s, c);
    }
    write_t7(&mut body, &t7s, &t7c);

    let _ = writeln!(md, "## Findings\n");
    findings(&mut md, &results, &t7s, &t7c, &checks);
    md.push_str(&body);

    let out = root().join("out/xtask");
    std::fs::create_dir_all(&out).expect("out/xtask");
    let path = out.join("reproduction.md");
    // the findings on the published band and T2's period are written by hand
    // in docs/reproduction.md from `cargo xtask published-band`'s tables
    std::fs::write(&path, md).expect("write out/xtask/reproduction.md");
    clock.say(&format!(
        "wrote {} and {}/*.svg",
        path.display(),
        maps.display()
    ));
}
