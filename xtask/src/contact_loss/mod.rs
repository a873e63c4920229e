//! The measured tables behind `docs/contact_loss.md` (printed; `cargo
//! xtask contact-loss > out/xtask/contact_loss.md`): contact loss you can
//! trust on the study's reference case (docs/targets.md; `scenes/reference.toml`).
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
//! Run: `cargo xtask contact-loss` (full), or
//! `cargo xtask contact-loss quick` (a cut-down
//! ladder). It prints markdown tables to stdout; wall times go to stderr.
//! All printed figures are deterministic.

//!
//! One part a file: [`zone`] (the support zone and the split), [`split`]
//! (part 1), [`recontact`] (part 2); [`common`] holds what they share. This
//! file runs the report.

mod common;
mod recontact;
mod split;
mod zone;

use common::*;
use recontact::*;
use split::*;
use taut::record::zone::SUPPORT_BENDING_LENGTHS;
pub use zone::{LossSplit, split_loss, support_zone, support_zone_with};
use zone::{SUPPORT_ELEMENTS, SUPPORT_STEPS};
// ---------------------------------------------------------------------------

/// The report: what `cargo xtask contact-loss` runs (its
/// command-line arguments, if any, are read here).
pub fn main() {
    let quick = std::env::args().any(|a| a == "quick");
    let dts: &[f64] = if quick { &DT_LADDER_QUICK } else { &DT_LADDER };
    let ns: &[usize] = if quick { &H_LADDER_QUICK } else { &H_LADDER };
    let speeds: &[f64] = if quick {
        &[FAST_SPEED]
    } else {
        &[FAST_SPEED, SCENE_SPEED]
    };

    // every distinct (speed, N, Δt), run in parallel
    let mut cases: Vec<Case> = Vec::new();
    for &speed in speeds {
        for &dt in dts {
            cases.push(Case {
                speed,
                elements: DT_LADDER_ELEMENTS,
                dt,
            });
        }
        for &elements in ns {
            let c = Case {
                speed,
                elements,
                dt: H_LADDER_DT,
            };
            if !cases.contains(&c) {
                cases.push(c);
            }
        }
    }
    let clock = Instant::now();
    let done = run_all(&cases);
    eprintln!(
        "{} runs in {:.1} s wall",
        done.len(),
        clock.elapsed().as_secs_f64()
    );
    let find = |c: Case| done.iter().find(|d| d.case == c).expect("case ran");

    let p = Props::of(&done[0].sc);
    let lb = p.bending_length();
    println!(
        "# Contact loss report{}\n",
        if quick { " (quick)" } else { "" }
    );
    println!(
        "Reference scene (`scenes/reference.toml`): L = {} m, EI = {:.1} N·m², T = {} N, ρA = {:.4} kg/m, m = {} kg; ℓ_b = sqrt(EI/T) = {:.4} m; Z = 2 sqrt(T ρA) = {:.1} N·s/m; t_c = {:.3e} s. Zone z = max({}ℓ_b, {}h, {}VΔt) from each end support.\n",
        p.length,
        p.ei,
        p.tension,
        p.rho_a,
        p.mass,
        lb,
        p.string_impedance(),
        p.crossover_time(),
        SUPPORT_BENDING_LENGTHS,
        SUPPORT_ELEMENTS,
        SUPPORT_STEPS
    );

    let mut summaries = Vec::new();
    for &speed in speeds {
        let c = (p.tension / p.rho_a).sqrt();
        println!("## V0 = {speed} m/s (V0/c = {:.3})\n", speed / c);

        let dt_runs: Vec<&Done> = dts
            .iter()
            .map(|&dt| {
                find(Case {
                    speed,
                    elements: DT_LADDER_ELEMENTS,
                    dt,
                })
            })
            .collect();
        let h_runs: Vec<&Done> = ns
            .iter()
            .map(|&elements| {
                find(Case {
                    speed,
                    elements,
                    dt: H_LADDER_DT,
                })
            })
            .collect();

        println!(
            "### 1a. Δt ladder at N = {DT_LADDER_ELEMENTS}\n\nEach row: {} with the Δt of the row. \"change\": relative to the previous row.\n",
            command(dt_runs[0].case)
        );
        let dt_rows: Vec<SplitRow> = dt_runs.iter().map(|d| split_row(d)).collect();
        split_table(&dt_rows, lb, true);
        let dt_x: Vec<f64> = dt_rows.iter().map(|r| r.case.dt).collect();
        let sup: Vec<f64> = dt_rows.iter().map(|r| r.split.support).collect();
        let span: Vec<f64> = dt_rows.iter().map(|r| r.split.in_span).collect();
        let p_dt = fit_line("Δt", &dt_x, &sup);
        let sup_t: Vec<f64> = dt_rows.iter().map(|r| r.support_time).collect();
        println!(
            "* support loss time ∝ Δt^p: least-squares p = {}",
            fmt_opt(log_slope(&dt_x, &sup_t), 2)
        );
        let n = span.len();
        let span_change_dt = rel_change(span[n - 1], span[n - 2]);
        println!(
            "* in-span part, change between the two finest Δt: {} (criterion {:.0} %)\n",
            pct(span_change_dt),
            100.0 * CONVERGED_CHANGE
        );

        println!(
            "### 1b. h ladder at Δt = {H_LADDER_DT:e} s\n\nEach row: {} with the N of the row.\n",
            command(h_runs[0].case)
        );
        let h_rows: Vec<SplitRow> = h_runs.iter().map(|d| split_row(d)).collect();
        split_table(&h_rows, lb, false);
        let h_x: Vec<f64> = h_rows.iter().map(|r| r.h).collect();
        let sup_h: Vec<f64> = h_rows.iter().map(|r| r.split.support).collect();
        let span_h: Vec<f64> = h_rows.iter().map(|r| r.split.in_span).collect();
        let p_h = fit_line("h", &h_x, &sup_h);
        let n = span_h.len();
        let span_change_h = rel_change(span_h[n - 1], span_h[n - 2]);
        println!(
            "* in-span part, change between the two finest N: {}\n",
            pct(span_change_h)
        );

        println!(
            "### 1c. Where the lost steps lie: distance from the right support L − x_m in bending lengths (fraction of all steps)\n\nΔt ladder, N = {DT_LADDER_ELEMENTS}:\n"
        );
        distance_table(&dt_runs, true);
        println!("h ladder, Δt = {H_LADDER_DT:e} s:\n");
        distance_table(&h_runs, false);

        println!(
            "### 1d. The in-span part under other zone widths\n\nΔt ladder, N = {DT_LADDER_ELEMENTS}:\n"
        );
        let v_dt = candidates_table(&dt_runs, true);
        println!("h ladder, Δt = {H_LADDER_DT:e} s:\n");
        let v_h = candidates_table(&h_runs, false);

        println!(
            "### 1e. The arrival at the right support (x = L, pinned)\n\nΔt ladder, N = {DT_LADDER_ELEMENTS}; the zone is the right support zone (x_m > L − z):\n"
        );
        let arrival = arrival_table(&dt_runs, true);
        println!("h ladder, Δt = {H_LADDER_DT:e} s:\n");
        arrival_table(&h_runs, false);

        println!("### 2. Re-contacts over the Δt ladder (N = {DT_LADDER_ELEMENTS})\n");
        let rs = recontact_study(&dt_runs);
        if !quick && speed == FAST_SPEED {
            println!(
                "**Peak λ (N) over the mesh at fixed Δt** (primary re-contacts of the N = {DT_LADDER_ELEMENTS} run, matched by time):\n"
            );
            peak_mesh_table(speed, &PEAK_MESH_DTS);
        }
        summaries.push((
            speed,
            p_dt,
            p_h,
            span_change_dt,
            span_change_h,
            v_dt,
            v_h,
            rs,
            arrival,
        ));
    }

    println!("## Summary\n");
    for (speed, p_dt, p_h, cdt, ch, v_dt, v_h, rs, arrival) in &summaries {
        let ok = |v: &Vec<(f64, f64, bool)>| {
            v.iter()
                .filter(|x| x.2)
                .map(|x| format!("{}ℓ_b", x.0))
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!(
            "* V0 = {speed} m/s: support part ∝ Δt^{} (least squares), ∝ h^{}; in-span change between the two finest levels: {} (Δt), {} (h). Zone widths with the in-span part converged (< 2 %) in Δt: [{}]; in h: [{}].",
            fmt_opt(*p_dt, 2),
            fmt_opt(*p_h, 2),
            pct(*cdt),
            pct(*ch),
            ok(v_dt),
            ok(v_h)
        );
        println!(
            "* V0 = {speed} m/s: peak ∝ Δt^(−a), median a = {} over in-span primary re-contacts (range {}), {} over the levels with Δt ≥ 1/ω_2h, {} in the support zone; median peak/(ZΔv) ∝ Δt^(−{}); impulse over {IMPULSE_WINDOW:e} s, |change| between the two finest Δt: median {}, max {} (span), max {} (support).",
            fmt_opt(rs.a_span, 2),
            rs.a_span_range
                .map_or("—".into(), |(a, b)| format!("{a:.2}–{b:.2}")),
            fmt_opt(rs.a_span_resolved, 2),
            fmt_opt(rs.a_support, 2),
            fmt_opt(rs.ratio_slope, 2),
            pct(rs.median_change_span),
            pct(rs.max_change_span),
            pct(rs.max_change_support)
        );
        println!(
            "* V0 = {speed} m/s: at the arrival, λ ∝ (L − x_m)^({}) over the last element (finest Δt).",
            fmt_opt(*arrival, 2)
        );
    }
}
