//! Part 2 of the report: re-contact force peaks and impulses.

use super::{common::*, zone::*};
// ---------------------------------------------------------------------------
// Part 2: re-contacts
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy)]
pub(super) struct Recontact {
    /// Time of the step end where the contact closes, s.
    pub(super) t: f64,
    /// x_m/L there.
    pub(super) x_over_l: f64,
    /// In the support zone.
    pub(super) support: bool,
    /// Duration of the loss before it, s.
    pub(super) loss: f64,
    /// Closing speed Δv = −dg/dt over the last open step, m/s.
    pub(super) dv: f64,
    /// Largest λ over the first PEAK_STEPS steps (while closed), N.
    pub(super) peak: f64,
    /// ∫λ dt over IMPULSE_WINDOW from the re-contact step, N·s.
    pub(super) impulse_window: f64,
    /// The run ends inside the impulse window (the carrier reaches x = L).
    pub(super) truncated: bool,
    /// ∫λ dt over the first closed interval, N·s.
    pub(super) impulse_closed: f64,
}

/// Primary re-contacts of one run (after a loss ≥ MIN_LOSS_TIME), and the
/// number of all re-contacts.
pub(super) fn recontacts(d: &Done) -> (Vec<Recontact>, usize) {
    let p = Props::of(&d.sc);
    let tr = &d.out.history.carriers[0];
    let t = &d.out.history.t;
    let dt = d.case.dt;
    let h = p.length / d.case.elements as f64;
    let zone = support_zone(p.ei, p.tension, h, d.case.speed, dt);
    let n = t.len();
    let window_steps = (IMPULSE_WINDOW / dt).round() as usize;
    let mut out = Vec::new();
    let mut all = 0;
    let mut open_since: Option<usize> = None;
    for i in 1..n {
        if !tr.in_contact[i] {
            open_since.get_or_insert(i);
            continue;
        }
        let Some(s) = open_since.take() else {
            continue;
        };
        all += 1;
        // the loss covered steps s..i−1, i.e. from t[s−1] to t[i−1]
        let loss = t[i - 1] - t[s - 1];
        if loss + 0.5 * dt < MIN_LOSS_TIME || i < 3 || i - 1 < s + 1 {
            continue;
        }
        let dv = -(tr.gap[i - 1] - tr.gap[i - 2]) / dt;
        let peak = (i..(i + PEAK_STEPS).min(n))
            .take_while(|&j| tr.in_contact[j])
            .map(|j| tr.force[j])
            .fold(f64::NEG_INFINITY, f64::max);
        let impulse_window: f64 = (i..(i + window_steps).min(n))
            .map(|j| tr.force[j] * dt)
            .sum();
        let impulse_closed: f64 = (i..n)
            .take_while(|&j| tr.in_contact[j])
            .map(|j| tr.force[j] * dt)
            .sum();
        let x = tr.x[i];
        out.push(Recontact {
            t: t[i],
            x_over_l: x / p.length,
            support: x < zone || x > p.length - zone,
            loss,
            dv,
            peak,
            impulse_window,
            truncated: i + window_steps > n,
            impulse_closed,
        });
    }
    (out, all)
}

pub(super) fn recontact_study(runs: &[&Done]) -> RecontactSummary {
    let p = Props::of(&runs[0].sc);
    let z = p.string_impedance();
    let tc = p.crossover_time();
    let per_run: Vec<(Vec<Recontact>, usize)> = runs.iter().map(|d| recontacts(d)).collect();
    let dts: Vec<f64> = runs.iter().map(|d| d.case.dt).collect();
    let finest = &per_run[per_run.len() - 1].0;

    println!("Re-contacts per run (all / primary, after a loss ≥ {MIN_LOSS_TIME:e} s):\n");
    println!("| Δt (s) | re-contacts | primary | primary in span | primary in support zone |");
    println!("|---|---|---|---|---|");
    for (d, (ev, all)) in runs.iter().zip(&per_run) {
        let sp = ev.iter().filter(|e| e.support).count();
        println!(
            "| {:e} | {all} | {} | {} | {sp} |",
            d.case.dt,
            ev.len(),
            ev.len() - sp
        );
    }
    println!();

    // match the finest run's primary events in every run
    let matched: Vec<(Recontact, Vec<Option<Recontact>>)> = finest
        .iter()
        .map(|e| {
            let row = per_run
                .iter()
                .map(|(ev, _)| {
                    ev.iter()
                        .filter(|o| (o.t - e.t).abs() < MATCH_TOLERANCE)
                        .min_by(|a, b| (a.t - e.t).abs().total_cmp(&(b.t - e.t).abs()))
                        .copied()
                })
                .collect();
            (*e, row)
        })
        .collect();

    let dt_head: Vec<String> = dts.iter().map(|d| format!("{d:e}")).collect();
    println!(
        "**Peak λ (N)** over the first {PEAK_STEPS} steps of each primary re-contact of the finest run, matched by time (±{MATCH_TOLERANCE:e} s) in the others; a = −(least-squares slope of log peak against log Δt) over the levels where the event is found:\n"
    );
    println!(
        "| # | t (s) | x_m/L | zone | loss before (ms) | {} | a | a (Δt ≥ 1/ω_2h) |",
        dt_head.join(" | ")
    );
    println!("|---|---|---|---|---|{}---|---|", "---|".repeat(dts.len()));
    // the mesh's highest beam frequency (a wave of length 2h): below
    // Δt = 1/ω_2h the step resolves times the mesh does not (section 2b)
    let h = p.length / runs[0].case.elements as f64;
    let w2h = (p.ei / p.rho_a).sqrt() * (std::f64::consts::PI / h).powi(2);
    let mut a_span = Vec::new();
    let mut a_span_resolved = Vec::new();
    let mut a_support = Vec::new();
    for (k, (e, row)) in matched.iter().enumerate() {
        let (x, y): (Vec<f64>, Vec<f64>) = dts
            .iter()
            .zip(row)
            .filter_map(|(dt, r)| r.map(|r| (*dt, r.peak)))
            .unzip();
        let a = (x.len() >= 3)
            .then(|| log_slope(&x, &y))
            .flatten()
            .map(|s| -s);
        let (xr, yr): (Vec<f64>, Vec<f64>) = x
            .iter()
            .zip(&y)
            .filter(|(dt, _)| **dt * w2h >= 1.0)
            .map(|(a, b)| (*a, *b))
            .unzip();
        let a_res = (xr.len() >= 3)
            .then(|| log_slope(&xr, &yr))
            .flatten()
            .map(|s| -s);
        if let (Some(a), false) = (a_res, e.support) {
            a_span_resolved.push(a);
        }
        if let Some(a) = a {
            if e.support {
                a_support.push(a);
            } else {
                a_span.push(a);
            }
        }
        let cells: Vec<String> = row
            .iter()
            .map(|r| r.map_or("—".into(), |r| format!("{:.0}", r.peak)))
            .collect();
        println!(
            "| {} | {:.4} | {:.4} | {} | {:.2} | {} | {} | {} |",
            k + 1,
            e.t,
            e.x_over_l,
            if e.support { "support" } else { "span" },
            1e3 * e.loss,
            cells.join(" | "),
            fmt_opt(a, 2),
            fmt_opt(a_res, 2)
        );
    }
    println!();

    println!(
        "**Impulse ∫λ dt (N·s) over {IMPULSE_WINDOW:e} s from the re-contact step** (bounces inside the window included), and its relative change from the previous Δt; † the run ends (the carrier reaches x = L) inside the window:\n"
    );
    println!(
        "| # | zone | {} | change, two finest |",
        dt_head.join(" | ")
    );
    println!("|---|---|{}---|", "---|".repeat(dts.len()));
    let mut ch_span = Vec::new();
    let mut ch_support = Vec::new();
    for (k, (e, row)) in matched.iter().enumerate() {
        let cells: Vec<String> = row
            .iter()
            .enumerate()
            .map(|(j, r)| match r {
                None => "—".into(),
                Some(r) => {
                    let prev = (j > 0).then(|| row[j - 1]).flatten();
                    let mark = if r.truncated { "†" } else { "" };
                    match prev {
                        Some(p) => format!(
                            "{:.4}{mark} ({})",
                            r.impulse_window,
                            pct(rel_change(r.impulse_window, p.impulse_window))
                        ),
                        None => format!("{:.4}{mark}", r.impulse_window),
                    }
                }
            })
            .collect();
        let n = row.len();
        let ch = match (row[n - 2], row[n - 1]) {
            (Some(a), Some(b)) => rel_change(b.impulse_window, a.impulse_window),
            _ => None,
        };
        if let Some(c) = ch {
            if e.support {
                ch_support.push(c.abs());
            } else {
                ch_span.push(c.abs());
            }
        }
        println!(
            "| {} | {} | {} | {} |",
            k + 1,
            if e.support { "support" } else { "span" },
            cells.join(" | "),
            pct(ch)
        );
    }
    println!();

    println!(
        "**Impulse over the first closed interval (N·s)** (ends at the first bounce, so it depends on how the spike splits):\n"
    );
    println!("| # | zone | {} |", dt_head.join(" | "));
    println!("|---|---|{}", "---|".repeat(dts.len()));
    for (k, (e, row)) in matched.iter().enumerate() {
        let cells: Vec<String> = row
            .iter()
            .map(|r| r.map_or("—".into(), |r| format!("{:.4}", r.impulse_closed)))
            .collect();
        println!(
            "| {} | {} | {} |",
            k + 1,
            if e.support { "support" } else { "span" },
            cells.join(" | ")
        );
    }
    println!();

    println!(
        "**Closing speed and impedance.** Δv = −(g_(i−1) − g_(i−2))/Δt over the last open step (m/s); Z = 2 sqrt(T ρA) = {z:.1} N·s/m (taut string); peak/(Z·Δv) against the Euler–Bernoulli estimate 2 sqrt(t_c/Δt), t_c = 2 sqrt(EI ρA)/(π T) = {tc:.3e} s; m·Δv (N·s) is the momentum the impulse must take out of a rigid 1 kg mass:\n"
    );
    println!(
        "| # | zone | Δv at {} | Δv at {} (m/s) | m·Δv (N·s) | {} |",
        dt_head[0],
        dt_head[dts.len() - 1],
        dts.iter()
            .map(|d| format!("peak/(ZΔv) at {d:e}"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|---|---|---|---|{}", "---|".repeat(dts.len()));
    let mut ratios: Vec<Vec<f64>> = vec![Vec::new(); dts.len()];
    for (k, (e, row)) in matched.iter().enumerate() {
        let cells: Vec<String> = row
            .iter()
            .enumerate()
            .map(|(j, r)| match r {
                Some(r) if r.dv > 0.0 => {
                    let q = r.peak / (z * r.dv);
                    if !e.support {
                        ratios[j].push(q);
                    }
                    format!("{q:.2}")
                }
                _ => "—".into(),
            })
            .collect();
        println!(
            "| {} | {} | {} | {:.4} | {:.4} | {} |",
            k + 1,
            if e.support { "support" } else { "span" },
            row[0].map_or("—".into(), |r| format!("{:.4}", r.dv)),
            e.dv,
            p.mass * e.dv,
            cells.join(" | ")
        );
    }
    let med: Vec<Option<f64>> = ratios.iter_mut().map(|v| median(v)).collect();
    println!(
        "| median (span) | | | | | {} |",
        med.iter()
            .map(|m| fmt_opt(*m, 2))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!(
        "| 2 sqrt(t_c/Δt) | | | | | {} |",
        dts.iter()
            .map(|d| format!("{:.2}", 2.0 * (tc / d).sqrt()))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!();
    let (mx, my): (Vec<f64>, Vec<f64>) = dts
        .iter()
        .zip(&med)
        .filter_map(|(d, m)| m.map(|m| (*d, m)))
        .unzip();
    println!(
        "Median peak/(ZΔv) (span): successive exponents a = {}; 1/ω_2h = {:.2e} s at N = {} (ω_2h = sqrt(EI/ρA)(π/h)²). Median a over in-span events, levels with Δt ≥ 1/ω_2h only: {}.\n",
        successive_slopes(&mx, &my)
            .into_iter()
            .map(|v| fmt_opt(v.map(|v| -v), 2))
            .collect::<Vec<_>>()
            .join(", "),
        1.0 / w2h,
        runs[0].case.elements,
        fmt_opt(median(&mut a_span_resolved.clone()), 2)
    );

    RecontactSummary {
        a_span_resolved: median(&mut a_span_resolved),
        a_span: median(&mut a_span),
        a_support: median(&mut a_support),
        a_span_range: range(&a_span),
        max_change_span: ch_span
            .iter()
            .copied()
            .fold(None, |m, v| Some(m.map_or(v, |m: f64| m.max(v)))),
        median_change_span: median(&mut ch_span),
        max_change_support: ch_support
            .iter()
            .copied()
            .fold(None, |m, v| Some(m.map_or(v, |m: f64| m.max(v)))),
        ratio_slope: {
            let (x, y): (Vec<f64>, Vec<f64>) = dts
                .iter()
                .zip(&med)
                .filter_map(|(d, m)| m.map(|m| (*d, m)))
                .unzip();
            log_slope(&x, &y).map(|s| -s)
        },
    }
}

pub(super) fn range(v: &[f64]) -> Option<(f64, f64)> {
    if v.is_empty() {
        return None;
    }
    Some((
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    ))
}

pub(super) struct RecontactSummary {
    pub(super) a_span_resolved: Option<f64>,
    pub(super) a_span: Option<f64>,
    pub(super) a_support: Option<f64>,
    pub(super) a_span_range: Option<(f64, f64)>,
    pub(super) max_change_span: Option<f64>,
    pub(super) median_change_span: Option<f64>,
    pub(super) max_change_support: Option<f64>,
    pub(super) ratio_slope: Option<f64>,
}
