//! The findings: what the studies show, in words.

use super::{common::*, measures::*, resolution::*, t7::*, targets_1d::*};

/// A trend in words from Spearman's ρ.
pub(super) fn trend_word(rho: f64) -> &'static str {
    if rho >= TREND_RHO {
        "rises"
    } else if rho <= -TREND_RHO {
        "falls"
    } else {
        "shows no clear trend"
    }
}

/// The first swept value above the main loss band (contact kept again).
pub(super) fn kept_above(r: &Run1) -> Option<f64> {
    let (_, b) = r.main_band()?;
    r.xs.iter().copied().find(|&x| x > b)
}

/// The summary at the top: every statement from the numbers below it.
pub(super) fn findings(
    md: &mut String,
    results: &[(&Target1, Run1, Run1)],
    t7s: &Run2,
    t7c: &Run2,
    checks: &[Check],
) {
    let t3 = &results[0];
    let (s3, c3) = (&t3.1, &t3.2);
    let lower = |r: &Run1| r.main_band().map(|iv| iv.0);
    let tol3 = BORDER_STEPS * c3.step;
    let near = |r: &Run1, v: f64| {
        r.points
            .iter()
            .min_by(|a, b| (a.ratio - v).abs().total_cmp(&(b.ratio - v).abs()))
            .map_or(f64::NAN, |p| p.pl)
    };
    let upper_text = match (kept_above(c3), kept_above(s3)) {
        (None, None) => format!(
            "Above it contact is not kept again anywhere up to V0/c = {}, at either resolution: P_l grows with speed (refined: {} at V0/c = 0.9, {} at 1, {} at 1.3). **The published upper border (contact kept for V0/c > 0.9, or > 0.96 in Fig. 12) is not reproduced.**",
            g(*c3.xs.last().unwrap(), 3),
            g(near(c3, 0.9), 3),
            g(near(c3, 1.0), 3),
            g(near(c3, 1.3), 3)
        ),
        (u, v) => format!(
            "Contact is kept again above the band from V0/c = {} (refined; study-like: {}), against the published 0.9–0.96.",
            opt(u, 3),
            opt(v, 3)
        ),
    };
    let _ = writeln!(
        md,
        "1. **Loss band (T3).** Refined, contact is lost in the span from V0/c = {} (study-like: {}). The published band starts at 0.7 (Fig. 8) or 0.64 (Fig. 12); within {BORDER_STEPS} grid steps ({}) the refined lower border {} 0.7 and {} 0.64. {upper_text}",
        opt(lower(c3), 3),
        opt(lower(s3), 3),
        g(tol3, 2),
        if lower(c3).is_some_and(|x| (x - 0.7).abs() <= tol3) {
            "agrees with"
        } else {
            "**differs from**"
        },
        if lower(c3).is_some_and(|x| (x - 0.64).abs() <= tol3) {
            "agrees with"
        } else {
            "**differs from**"
        },
    );
    let mid_loss = |r: &Run1| {
        r.points
            .iter()
            .filter(|p| p.ratio < 1.0 && p.first_loss.is_some_and(|x| x < 0.8))
            .count()
    };
    let (ms, mc) = (mid_loss(s3), mid_loss(c3));
    let band: Vec<&Point> = c3
        .points
        .iter()
        .filter(|p| (0.7..=0.9).contains(&p.ratio))
        .collect();
    let firsts: Vec<f64> = band.iter().filter_map(|p| p.first_loss).collect();
    let all_near = band.iter().all(|p| p.pl_span > 0.0)
        && firsts.len() == band.len()
        && firsts.iter().all(|&x| x >= 0.9);
    let _ = writeln!(
        md,
        "2. **Where the loss is (T3).** {} {}",
        match (ms, mc) {
            (m, 0) if m > 0 => format!(
                "At the study-like resolution {m} runs below V0/c = 1 first lose contact in mid-span (x_m/L < 0.8); refined, none do: those scattered losses (the T3 study-like loss map) are a resolution artefact."
            ),
            (m, n) => format!(
                "Runs below V0/c = 1 with a first loss before x_m/L = 0.8: {m} study-like, {n} refined."
            ),
        },
        if all_near {
            format!(
                "Loss near the right support for V0/c ≈ 0.7–0.9, the published feature, is there: refined, every run in that range loses contact, first at x_m/L = {}–{}.",
                g(firsts.iter().copied().fold(f64::INFINITY, f64::min), 3),
                g(firsts.iter().copied().fold(f64::NEG_INFINITY, f64::max), 3)
            )
        } else {
            "Loss near the right support for V0/c ≈ 0.7–0.9 is **not** found in every run of that range (refined).".to_string()
        }
    );
    let lag = ridge_lag(c3);
    let _ = writeln!(
        md,
        "3. **Force ridge (T3).** The force turns from falling to rising where the carrier meets the front its start launched, reflected at x = L: refined, the onset {} (slope {} against the plain-string prediction x_m = 2L − ct over V0/c ≤ 0.9), {} L after it (median; {}). Its rise is largest at V0/c = {} (refined; study-like {}), {}.",
        if ridge_tracks(c3) {
            "moves with the encounter"
        } else {
            "**does not move with the encounter**"
        },
        opt(ridge_slope(c3), 2),
        lag.map_or("—".into(), |l| g(l.0, 2)),
        lag.map_or("—".into(), |l| format!(
            "{} to {} over {} runs",
            g(l.1, 2),
            g(l.2, 2),
            l.3
        )),
        opt(ridge_peak(c3).map(|p| p.2), 3),
        opt(ridge_peak(s3).map(|p| p.2), 3),
        if ridge_near_one(c3) {
            "near V0/c ≈ 1 as published"
        } else {
            "**away from V0/c ≈ 1**"
        }
    );
    let t4 = &results[1];
    let c4 = &t4.2;
    let spec = SweepSpec {
        scene_text: reference_text(),
        set: vec![],
        axes: vec![Axis::parse("tension_ratio=0.001:0.001:1", false).unwrap()],
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let cw = spec.resolve(0).unwrap().beam.wave_speed();

    let ratio_at = |r: &Run1, x: f64| {
        r.points
            .iter()
            .zip(&r.xs)
            .find(|(_, v)| **v == x)
            .map(|(p, _)| p.ratio)
    };
    let (rl, rf) = (c4.rho(|p| p.level), c4.rho(|p| p.range));
    let _ = writeln!(
        md,
        "4. **Tension (T4).** c = {} m/s at T/EA = 0.001 ({} the published 122.7). Refined, contact is lost in the span for T/EA in {} (published 0.0010–0.0012){}. With tension the mid-span force level {} (ρ = {:.2}) and its fluctuation {} (ρ = {:.2}); published: both fall.",
        g(cw, 4),
        if (cw - 122.7).abs() < 0.05 {
            "reproduces"
        } else {
            "**differs from**"
        },
        show_intervals(&c4.span_loss(), 4),
        c4.main_band().map_or(String::new(), |(_, b)| {
            let r = ratio_at(c4, b).unwrap_or(f64::NAN);
            format!(
                "; at V0 = 100 m/s its main band ends at V0/c = {}{}",
                g(r, 3),
                match lower(c3) {
                    Some(l) if (r - l).abs() <= tol3 => ", the T3 band's lower border again",
                    _ => "",
                }
            )
        }),
        trend_word(rl),
        rl,
        trend_word(rf),
        rf
    );
    let c5 = &results[2].2;
    let (rl, rf) = (c5.rho(|p| p.level), c5.rho(|p| p.range));
    let _ = writeln!(
        md,
        "5. **Mass (T5).** Refined, with the mass the mid-span force level {} (ρ = {:.2}) and its fluctuation {} (ρ = {:.2}) (published: both grow); contact is lost in the span for m/M in {} (published: at the larger masses).",
        trend_word(rl),
        rl,
        trend_word(rf),
        rf,
        show_intervals(&c5.span_loss(), 3)
    );
    let c6 = &results[3].2;
    let rl = c6.rho(|p| p.level);
    let firsts6: Vec<f64> = c6
        .points
        .iter()
        .filter(|p| p.pl_span > 0.0)
        .filter_map(|p| p.first_loss)
        .collect();
    let _ = writeln!(
        md,
        "6. **Stiffness (T6).** Refined, the mid-span force level {} with k/(T/L) (ρ = {:.2}; published: grows); contact is lost in the span for k/(T/L) in {} (published 0.1–1.7){}.",
        trend_word(rl),
        rl,
        show_intervals(&c6.span_loss(), 3),
        if firsts6.is_empty() {
            String::new()
        } else {
            format!(
                ", first at x_m/L = {}–{}; V0 = 100 m/s is V0/c = {} here, {} the T3 band's lower border ({})",
                g(firsts6.iter().copied().fold(f64::INFINITY, f64::min), 3),
                g(firsts6.iter().copied().fold(f64::NEG_INFINITY, f64::max), 3),
                g(c6.points[0].ratio, 3),
                if lower(c3).is_some_and(|l| c6.points[0].ratio >= l) {
                    "above"
                } else {
                    "below"
                },
                opt(lower(c3), 3)
            )
        }
    );
    let b = borders(t7c, |p| p.pl_span);
    let lows: Vec<f64> = b
        .iter()
        .filter_map(|x| Some(0.5 * (x.below? + x.above?)))
        .collect();
    let bs = borders(t7s, |p| p.pl_span);
    let lows_s: Vec<f64> = bs
        .iter()
        .filter_map(|x| Some(0.5 * (x.below? + x.above?)))
        .collect();
    let free_above = b.iter().filter(|x| x.upper_free.is_some()).count();
    let all_pl = t7c.points.iter().all(|p| p.pl > 0.0);
    let _ = writeln!(
        md,
        "7. **Map (T7).** The lower border of P_l,span lies at V0/c = {} (median over the tensions, refined; study-like {}; range {}–{}), against the published 0.64. {} {}",
        g(median(lows.clone()), 3),
        g(median(lows_s), 3),
        g(lows.iter().copied().fold(f64::INFINITY, f64::min), 3),
        g(lows.iter().copied().fold(f64::NEG_INFINITY, f64::max), 3),
        if free_above == 0 {
            format!(
                "Above it loss continues to the top of every column ({} tensions, refined): the published upper border at V0/c ≈ 0.96 is **not found**.",
                b.len()
            )
        } else {
            format!(
                "{free_above} of {} tensions have loss-free speeds above the band (refined).",
                b.len()
            )
        },
        if all_pl {
            "The whole-run P_l is > 0 at every grid point, from the launch at the support."
        } else {
            ""
        }
    );
    let grows = CHECK_RATIOS.iter().all(|&r| {
        let v: Vec<&Check> = checks.iter().filter(|c| c.ratio == r).collect();
        v.last().unwrap().max >= v[0].max || v[0].pl_span == 0.0
    });
    let maxes: Vec<String> = CHECK_RATIOS
        .iter()
        .map(|&r| {
            let v: Vec<&Check> = checks.iter().filter(|c| c.ratio == r).collect();
            format!(
                "{} → {} N at V0/c = {}",
                g(v[0].max, 2),
                g(v[v.len() - 1].max, 2),
                g(r, 2)
            )
        })
        .collect();
    let _ = writeln!(
        md,
        "8. **Not converged, by the model's nature.** The peak contact force from N = {} to {} (Δt with h): {}. {}Without an impact law the re-contact force is a Δt-dependent spike (TARGETS; [convergence.md](convergence.md) shows the same for the reference case), so the whole-run force statistics where contact is lost (near V0/c ≈ 1 above all) carry it; no finding above rests on them.\n",
        CHECK_LEVELS[0].0,
        CHECK_LEVELS[3].0,
        maxes.join("; "),
        if grows {
            "Where contact is lost in the span it grows as Δt shrinks. "
        } else {
            ""
        }
    );
}
