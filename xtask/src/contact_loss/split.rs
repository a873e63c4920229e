//! Part 1 of the report: P_l split into its in-span and support parts.

use super::{common::*, recontact::*, zone::*};
// ---------------------------------------------------------------------------
// Part 1: the split
// ---------------------------------------------------------------------------

pub(super) struct SplitRow {
    pub(super) case: Case,
    pub(super) h: f64,
    pub(super) zone: f64,
    pub(super) pl: f64,
    pub(super) split: LossSplit,
    /// The bands of x_m/L: < 0.98, 0.98–0.995, ≥ 0.995.
    pub(super) bands: [f64; 3],
    /// Time with the contact open in the support zone, s.
    pub(super) support_time: f64,
}

pub(super) fn split_row(d: &Done) -> SplitRow {
    let p = Props::of(&d.sc);
    let tr = &d.out.history.carriers[0];
    let h = p.length / d.case.elements as f64;
    let zone = support_zone(p.ei, p.tension, h, d.case.speed, d.case.dt);
    let split = split_loss(&tr.x, &tr.in_contact, p.length, zone);
    // the two parts add up to the library's P_l (same steps, same denominator)
    let pl = d.out.stats[0].loss_fraction;
    assert!(
        (split.in_span + split.support - pl).abs() <= PARTS_SUM_TOLERANCE * pl.max(1.0),
        "{:?}: in-span {} + support {} ≠ P_l {pl}",
        d.case,
        split.in_span,
        split.support
    );
    // and this split is the library's own (taut::record::LossGeometry)
    let lib = &d.out.stats[0];
    assert!(
        (split.in_span - lib.loss_fraction_span).abs() <= PARTS_SUM_TOLERANCE
            && (zone - lib.support_zone).abs() <= PARTS_SUM_TOLERANCE * zone,
        "{:?}: in-span {} (zone {zone} m) ≠ the library's {} (zone {} m)",
        d.case,
        split.in_span,
        lib.loss_fraction_span,
        lib.support_zone
    );
    let steps = (tr.x.len() - 1) as f64;
    let mut bands = [0.0; 3];
    for i in 1..tr.x.len() {
        if !tr.in_contact[i] {
            let r = tr.x[i] / p.length;
            let b = if r < 0.98 {
                0
            } else if r < 0.995 {
                1
            } else {
                2
            };
            bands[b] += 1.0 / steps;
        }
    }
    SplitRow {
        case: d.case,
        h,
        zone,
        pl: d.out.stats[0].loss_fraction,
        split,
        bands,
        support_time: split.support * steps * d.case.dt,
    }
}

pub(super) fn split_table(rows: &[SplitRow], lb: f64, by_dt: bool) {
    println!(
        "| {} | z (m) | z/ℓ_b | P_l | in-span | change | support | change | support time (ms) | x/L < 0.98 | 0.98–0.995 | ≥ 0.995 |",
        if by_dt { "Δt (s)" } else { "N (h, m)" }
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (i, r) in rows.iter().enumerate() {
        let (cs, cp) = if i == 0 {
            (None, None)
        } else {
            (
                rel_change(r.split.in_span, rows[i - 1].split.in_span),
                rel_change(r.split.support, rows[i - 1].split.support),
            )
        };
        let lead = if by_dt {
            format!("{:e}", r.case.dt)
        } else {
            format!("{} ({:.4})", r.case.elements, r.h)
        };
        println!(
            "| {lead} | {:.4} | {:.2} | {:.5} | {:.5} | {} | {:.5} | {} | {:.3} | {:.4} | {:.4} | {:.4} |",
            r.zone,
            r.zone / lb,
            r.pl,
            r.split.in_span,
            pct(cs),
            r.split.support,
            pct(cp),
            1e3 * r.support_time,
            r.bands[0],
            r.bands[1],
            r.bands[2]
        );
    }
    println!();
}

/// Fit line for the support part against x (Δt or h).
pub(super) fn fit_line(label: &str, x: &[f64], y: &[f64]) -> Option<f64> {
    let s = log_slope(x, y);
    let succ: Vec<String> = successive_slopes(x, y)
        .into_iter()
        .map(|v| fmt_opt(v, 2))
        .collect();
    println!(
        "* support part ∝ {label}^p: least-squares p = {} over all levels; over the first four (the issue's ladder) p = {}; successive p = {}; over the three finest levels p = {}",
        fmt_opt(s, 2),
        fmt_opt(
            if x.len() >= 4 {
                log_slope(&x[..4], &y[..4])
            } else {
                None
            },
            2
        ),
        succ.join(", "),
        fmt_opt(
            if x.len() >= 3 {
                log_slope(&x[x.len() - 3..], &y[y.len() - 3..])
            } else {
                None
            },
            2
        )
    );
    s
}

/// Lost steps by distance from the right support, in bending lengths, as
/// fractions of all steps (their sum over bands is the P_l of the last
/// DISTANCE_BANDS.last() bending lengths; the last column is the rest).
pub(super) fn distance_table(runs: &[&Done], by_dt: bool) {
    let mut head = String::from(if by_dt { "| Δt (s) |" } else { "| N |" });
    for w in DISTANCE_BANDS.windows(2) {
        head.push_str(&format!(" {}–{} ℓ_b |", w[0], w[1]));
    }
    head.push_str(&format!(
        " ≥ {} ℓ_b |",
        DISTANCE_BANDS[DISTANCE_BANDS.len() - 1]
    ));
    println!("{head}");
    println!("|---{}|", "|---".repeat(DISTANCE_BANDS.len()));
    for d in runs {
        let p = Props::of(&d.sc);
        let lb = p.bending_length();
        let tr = &d.out.history.carriers[0];
        let steps = (tr.x.len() - 1) as f64;
        let mut counts = vec![0.0; DISTANCE_BANDS.len()];
        for i in 1..tr.x.len() {
            if !tr.in_contact[i] {
                let dist = (p.length - tr.x[i]) / lb;
                let b = DISTANCE_BANDS
                    .windows(2)
                    .position(|w| dist >= w[0] && dist < w[1])
                    .unwrap_or(DISTANCE_BANDS.len() - 1);
                counts[b] += 1.0 / steps;
            }
        }
        let lead = if by_dt {
            format!("{:e}", d.case.dt)
        } else {
            format!("{}", d.case.elements)
        };
        let cells: Vec<String> = counts.iter().map(|c| format!("{c:.5}")).collect();
        println!("| {lead} | {} |", cells.join(" | "));
    }
    println!();
}

/// The in-span part under other zone constants (bending lengths), and its
/// change between the two finest levels of a ladder.
pub(super) fn candidates_table(runs: &[&Done], by_dt: bool) -> Vec<(f64, f64, bool)> {
    let mut head = String::from("| zone | ");
    for d in runs {
        if by_dt {
            head.push_str(&format!("Δt = {:e} | ", d.case.dt));
        } else {
            head.push_str(&format!("N = {} | ", d.case.elements));
        }
    }
    head.push_str("change, two finest | largest change, three finest | converged (< 2 %) |");
    println!("{head}");
    println!("|---{}|---|---|---|", "|---".repeat(runs.len()));
    let mut verdicts = Vec::new();
    for &k in &ZONE_CANDIDATES {
        let vals: Vec<f64> = runs
            .iter()
            .map(|d| {
                let p = Props::of(&d.sc);
                let h = p.length / d.case.elements as f64;
                let z = support_zone_with(k, p.ei, p.tension, h, d.case.speed, d.case.dt);
                let tr = &d.out.history.carriers[0];
                split_loss(&tr.x, &tr.in_contact, p.length, z).in_span
            })
            .collect();
        let n = vals.len();
        let change = rel_change(vals[n - 1], vals[n - 2]);
        let ok = change.is_none_or(|c| c.abs() < CONVERGED_CHANGE);
        let worst = (n.saturating_sub(3) + 1..n)
            .filter_map(|i| rel_change(vals[i], vals[i - 1]))
            .map(f64::abs)
            .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
        let cells: Vec<String> = vals.iter().map(|v| format!("{v:.5}")).collect();
        println!(
            "| max({k}ℓ_b, 4h, 4VΔt) | {} | {} | {} | {} |",
            cells.join(" | "),
            pct(change),
            worst.map_or("—".into(), |w| format!("{:.2} %", 100.0 * w)),
            if ok { "yes" } else { "no" }
        );
        verdicts.push((k, change.unwrap_or(0.0), ok));
    }
    println!();
    verdicts
}

/// The carrier's arrival at the right support, run by run: where the last
/// step lands, the force there, the largest force and ∫λ dt in the right
/// support zone, and the mass's vertical speed at the last step. Then, in
/// the finest run, the law of λ against the distance L − x_m over the last
/// element (rows with L − x_m between ARRIVAL_FIT_STEPS·VΔt and h).
pub(super) fn arrival_table(runs: &[&Done], by_dt: bool) -> Option<f64> {
    println!(
        "| {} | L − x_m at the last step (mm) | λ at the last step (N) | max λ in the zone (N) | ∫λ dt in the zone (N·s) | ∫λ dt in the last element (N·s) | q̇ at the last step (m/s) |",
        if by_dt { "Δt (s)" } else { "N" }
    );
    println!("|---|---|---|---|---|---|---|");
    for d in runs {
        let p = Props::of(&d.sc);
        let tr = &d.out.history.carriers[0];
        let n = tr.x.len();
        let h = p.length / d.case.elements as f64;
        let zone = support_zone(p.ei, p.tension, h, d.case.speed, d.case.dt);
        let in_zone = |i: &usize| tr.x[*i] > p.length - zone;
        let max_zone = (1..n)
            .filter(in_zone)
            .map(|i| tr.force[i])
            .fold(0.0, f64::max);
        let imp_zone: f64 = (1..n)
            .filter(in_zone)
            .map(|i| tr.force[i] * d.case.dt)
            .sum();
        let imp_elem: f64 = (1..n)
            .filter(|&i| tr.x[i] > p.length - h)
            .map(|i| tr.force[i] * d.case.dt)
            .sum();
        let lead = if by_dt {
            format!("{:e}", d.case.dt)
        } else {
            format!("{}", d.case.elements)
        };
        println!(
            "| {lead} | {:.3} | {:.4e} | {:.4e} | {:.4} | {:.4} | {:.3} |",
            1e3 * (p.length - tr.x[n - 1]),
            tr.force[n - 1],
            max_zone,
            imp_zone,
            imp_elem,
            (tr.q[n - 1] - tr.q[n - 2]) / d.case.dt
        );
    }
    println!();
    if !by_dt {
        return None;
    }
    let d = runs[runs.len() - 1];
    let p = Props::of(&d.sc);
    let tr = &d.out.history.carriers[0];
    let h = p.length / d.case.elements as f64;
    let lo = ARRIVAL_FIT_STEPS * d.case.speed * d.case.dt;
    let (x, y): (Vec<f64>, Vec<f64>) = (1..tr.x.len())
        .filter(|&i| {
            let dist = p.length - tr.x[i];
            tr.in_contact[i] && dist >= lo && dist <= h
        })
        .map(|i| (p.length - tr.x[i], tr.force[i]))
        .unzip();
    let slope = log_slope(&x, &y);
    println!(
        "In the finest run (Δt = {:e} s), over the last element (L − x_m from {:.2} mm to h = {:.2} mm, {} steps, contact closed): λ ∝ (L − x_m)^({}) (least squares).\n",
        d.case.dt,
        1e3 * lo,
        1e3 * h,
        x.len(),
        fmt_opt(slope, 2)
    );
    slope
}

/// The peak of each primary re-contact at a fixed Δt over the meshes of
/// PEAK_MESHES: whether the peak at small Δt is the mesh's as well.
pub(super) fn peak_mesh_table(speed: f64, dts: &[f64]) {
    let cases: Vec<Case> = dts
        .iter()
        .flat_map(|&dt| {
            PEAK_MESHES.iter().map(move |&elements| Case {
                speed,
                elements,
                dt,
            })
        })
        .collect();
    let done = run_all(&cases);
    let p = Props::of(&done[0].sc);
    let omegas: Vec<String> = PEAK_MESHES
        .iter()
        .map(|&n| {
            let h = p.length / n as f64;
            let w = (p.ei / p.rho_a).sqrt() * (std::f64::consts::PI / h).powi(2);
            format!("N = {n}: ω_2h = {w:.3e} rad/s, 1/ω_2h = {:.2e} s", 1.0 / w)
        })
        .collect();
    println!(
        "The bending frequency of a wave of length 2h, ω_2h = sqrt(EI/ρA)·(π/h)², is the highest the mesh carries as a beam: {}.\n",
        omegas.join("; ")
    );
    let heads: Vec<String> = PEAK_MESHES.iter().map(|n| format!("N = {n}")).collect();
    println!(
        "| Δt (s) | # | t (s) | zone | {} | a_h = slope of log peak against log h |",
        heads.join(" | ")
    );
    println!("|---|---|---|---|{}---|", "---|".repeat(PEAK_MESHES.len()));
    for &dt in dts {
        let row: Vec<&Done> = done.iter().filter(|d| d.case.dt == dt).collect();
        let anchor = row
            .iter()
            .find(|d| d.case.elements == DT_LADDER_ELEMENTS)
            .expect("the N of the Δt ladder is among PEAK_MESHES");
        let per: Vec<Vec<Recontact>> = row.iter().map(|d| recontacts(d).0).collect();
        for (k, e) in recontacts(anchor).0.iter().enumerate() {
            let peaks: Vec<Option<f64>> = per
                .iter()
                .map(|ev| {
                    ev.iter()
                        .filter(|o| (o.t - e.t).abs() < MATCH_TOLERANCE)
                        .min_by(|a, b| (a.t - e.t).abs().total_cmp(&(b.t - e.t).abs()))
                        .map(|o| o.peak)
                })
                .collect();
            let (hx, py): (Vec<f64>, Vec<f64>) = row
                .iter()
                .zip(&peaks)
                .filter_map(|(d, p)| p.map(|p| (50.0 / d.case.elements as f64, p)))
                .unzip();
            println!(
                "| {dt:e} | {} | {:.4} | {} | {} | {} |",
                k + 1,
                e.t,
                if e.support { "support" } else { "span" },
                peaks
                    .iter()
                    .map(|p| p.map_or("—".into(), |p| format!("{p:.0}")))
                    .collect::<Vec<_>>()
                    .join(" | "),
                fmt_opt(log_slope(&hx, &py), 2)
            );
        }
    }
    println!();
}
