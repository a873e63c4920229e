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

use std::time::Instant;

use rayon::prelude::*;
use taut::scene::CarrierKind;
use taut::{Resolved, RunOutput, resolve_scene, run};

const REFERENCE: &str = include_str!("../scenes/reference.toml");

// ---------------------------------------------------------------------------
// The support zone: the library's constants (taut::record::zone), with the
// width in bending lengths left free so other widths can be tried; every run
// checks that this split at 4 ℓ_b is the library's loss_fraction_span.
// ---------------------------------------------------------------------------

use taut::record::zone::{SUPPORT_BENDING_LENGTHS, SUPPORT_ELEMENTS, SUPPORT_STEPS};

/// Width z (m) of the support zone at each end support, with `bending`
/// bending lengths: z = max(bending·ℓ_b, 4h, 4VΔt). ℓ_b = 0 for a string.
pub fn support_zone_with(bending: f64, ei: f64, tension: f64, h: f64, speed: f64, dt: f64) -> f64 {
    let lb = if ei > 0.0 && tension > 0.0 {
        (ei / tension).sqrt()
    } else {
        0.0
    };
    (bending * lb)
        .max(SUPPORT_ELEMENTS * h)
        .max(SUPPORT_STEPS * speed * dt)
}

/// The support zone z = max(4ℓ_b, 4h, 4VΔt), m.
pub fn support_zone(ei: f64, tension: f64, h: f64, speed: f64, dt: f64) -> f64 {
    support_zone_with(SUPPORT_BENDING_LENGTHS, ei, tension, h, speed, dt)
}

/// P_l split in two parts over the same denominator (all steps), so that
/// `in_span + support` = P_l.
#[derive(Debug, Clone, Copy)]
pub struct LossSplit {
    /// Steps with the contact open and x_m in [z, L − z], over all steps.
    pub in_span: f64,
    /// Steps with the contact open and x_m < z or x_m > L − z, over all steps.
    pub support: f64,
}

/// Split P_l of one carrier's trace (row 0 = t = 0, rows 1.. = step ends;
/// a step is located by x_m at its end) at support-zone width `zone`.
pub fn split_loss(x: &[f64], in_contact: &[bool], length: f64, zone: f64) -> LossSplit {
    let steps = in_contact.len().saturating_sub(1).max(1) as f64;
    let (mut span, mut support) = (0usize, 0usize);
    for i in 1..in_contact.len() {
        if !in_contact[i] {
            if x[i] < zone || x[i] > length - zone {
                support += 1;
            } else {
                span += 1;
            }
        }
    }
    LossSplit {
        in_span: span as f64 / steps,
        support: support as f64 / steps,
    }
}

/// The two parts are sums of 1/steps over disjoint sets of steps; their sum
/// differs from the library's count/steps by round-off only.
const PARTS_SUM_TOLERANCE: f64 = 1e-12;

// ---------------------------------------------------------------------------
// Study settings
// ---------------------------------------------------------------------------

/// V0/c = 0.9 (c = 149.9 m/s): contact is lost in the span, not only at the
/// support (the case).
const FAST_SPEED: f64 = 134.92;
/// The reference scene's own cruise speed (V0/c = 0.67).
const SCENE_SPEED: f64 = 100.0;
/// The mesh of the Δt ladder (h = 0.031 m < ℓ_b = 0.066 m).
const DT_LADDER_ELEMENTS: usize = 1600;
/// The step of the h ladder.
const H_LADDER_DT: f64 = 2.5e-5;
/// Δt ladder (s). The four levels and two more, 6.25e-6 and
/// 3.125e-6 s, to give the peak and support fits more points and to test
/// the trend beyond the range (the finest run takes about 2 s).
const DT_LADDER: [f64; 6] = [1e-4, 5e-5, 2.5e-5, 1.25e-5, 6.25e-6, 3.125e-6];
const DT_LADDER_QUICK: [f64; 3] = [1e-4, 5e-5, 2.5e-5];
/// h ladder (elements N): the four levels and N = 6400, to check
/// the in-span part one level further (h/ℓ_b = 1.9 … 0.12).
const H_LADDER: [usize; 5] = [400, 800, 1600, 3200, 6400];
const H_LADDER_QUICK: [usize; 3] = [400, 800, 1600];
/// The in-span part counts as converged when it changes by less than this
/// fraction of its value between the two finest levels (the 2 %).
const CONVERGED_CHANGE: f64 = 0.02;
/// Zone widths tried besides the 4ℓ_b (in bending lengths).
const ZONE_CANDIDATES: [f64; 5] = [2.0, 4.0, 6.0, 8.0, 12.0];
/// Bands of distance from the right support, in bending lengths, for the
/// table of where the lost steps lie.
const DISTANCE_BANDS: [f64; 8] = [0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 16.0];

/// The re-contact's peak is the largest λ over its first PEAK_STEPS steps
/// (the rigid-impact spike sits in the first step or two).
const PEAK_STEPS: usize = 3;
/// The fixed physical window of the re-contact impulse ∫λ dt, s. It is about
/// the decay time m/Z = 2.5 ms of a 1 kg mass on the string's impedance
/// (below), and it counts bounces after the re-contact with the re-contact,
/// so a spike split into a spike and bounces at a smaller Δt integrates alike.
const IMPULSE_WINDOW: f64 = 2e-3;
/// A re-contact is "primary" when the loss before it lasted at least this
/// long; shorter losses are bounces after a re-contact (docs/convergence.md
/// §4e: their number grows as Δt falls). 0.2 ms = 2 steps at Δt = 1e-4 s,
/// so the closing speed can be estimated at every level.
const MIN_LOSS_TIME: f64 = 2e-4;
/// The arrival-force law is fitted from this many carrier steps V·Δt before
/// the support (the last steps land at a Δt-dependent distance from L).
const ARRIVAL_FIT_STEPS: f64 = 4.0;
/// Meshes for the peak's dependence on h at fixed Δt (full run only).
const PEAK_MESHES: [usize; 3] = [800, 1600, 3200];
/// The Δt values of that check: one in the range where the peak follows
/// Δt^(−½) and the finest of the ladder.
const PEAK_MESH_DTS: [f64; 2] = [2.5e-5, 3.125e-6];
/// Re-contacts of two runs are the same event when their times differ by
/// less than this (s); loss intervals at V0/c = 0.9 are ≥ several ms apart.
const MATCH_TOLERANCE: f64 = 1e-3;

// ---------------------------------------------------------------------------
// Runs
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq)]
struct Case {
    speed: f64,
    elements: usize,
    dt: f64,
}

struct Done {
    case: Case,
    sc: Resolved,
    out: RunOutput,
}

/// Run every case, in parallel, in order.
fn run_all(cases: &[Case]) -> Vec<Done> {
    cases
        .par_iter()
        .map(|&case| {
            let sc = scene(case);
            let out = run(&sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("{case:?}: {e}"));
            eprintln!(
                "ran V = {} m/s, N = {}, Δt = {:e} s: {} steps in {:.2} s",
                case.speed, case.elements, case.dt, out.steps, out.wall_seconds
            );
            Done { case, sc, out }
        })
        .collect()
}

fn scene(case: Case) -> Resolved {
    let o = vec![
        format!("carrier.speed.cruise={}", case.speed),
        format!("mesh.elements={}", case.elements),
        format!("time.step={:e}", case.dt),
    ];
    resolve_scene(REFERENCE, &o).expect("the reference scene resolves")
}

fn command(case: Case) -> String {
    format!(
        "`taut run scenes/reference.toml --set carrier.speed.cruise={} --set mesh.elements={} --set time.step={:e}`",
        case.speed, case.elements, case.dt
    )
}

/// Beam and carrier numbers every table uses.
#[derive(Debug, Clone, Copy)]
struct Props {
    length: f64,
    ei: f64,
    tension: f64,
    rho_a: f64,
    mass: f64,
}

impl Props {
    fn of(sc: &Resolved) -> Self {
        let mass = match sc.carriers[0].kind {
            CarrierKind::MassSpring { mass, .. } => mass,
            CarrierKind::Force { .. } => 0.0,
        };
        Props {
            length: sc.beam.length,
            ei: sc.beam.ei,
            tension: sc.beam.tension,
            rho_a: sc.beam.rho_a,
            mass,
        }
    }
    /// ℓ_b = sqrt(EI/T), m.
    fn bending_length(&self) -> f64 {
        (self.ei / self.tension).sqrt()
    }
    /// The taut string's drive-point impedance Z = 2 sqrt(T ρA), N·s/m
    /// (a wave leaves each side with impedance sqrt(T ρA)).
    fn string_impedance(&self) -> f64 {
        2.0 * (self.tension * self.rho_a).sqrt()
    }
    /// The crossover time t_c = 2 sqrt(EI ρA)/(π T), s: for an imposed
    /// velocity step Δv, the infinite Euler–Bernoulli beam's force
    /// 2 (EI)^¼ (ρA)^¾ sqrt(2/π) Δv t^(−½) equals the string's Z·Δv at
    /// t = t_c. Before t_c the beam is stiffer than the string.
    fn crossover_time(&self) -> f64 {
        2.0 * (self.ei * self.rho_a).sqrt() / (std::f64::consts::PI * self.tension)
    }
}

// ---------------------------------------------------------------------------
// Small numerics
// ---------------------------------------------------------------------------

/// Least-squares slope of log y against log x over the points with y > 0.
fn log_slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(_, y)| **y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

/// Successive exponents log(y_i/y_{i−1}) / log(x_i/x_{i−1}).
fn successive_slopes(x: &[f64], y: &[f64]) -> Vec<Option<f64>> {
    (1..x.len())
        .map(|i| {
            // the slope is the observed order of y "refined" by x_i/x_{i−1}
            let p = taut::study::grid::observed_order(y[i], y[i - 1], x[i] / x[i - 1]);
            p.is_finite().then_some(p)
        })
        .collect()
}

fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("—".to_string(), |v| format!("{v:.digits$}"))
}

fn rel_change(new: f64, old: f64) -> Option<f64> {
    (old != 0.0).then(|| (new - old) / old)
}

fn pct(v: Option<f64>) -> String {
    v.map_or("—".to_string(), |v| format!("{:+.2} %", 100.0 * v))
}

fn median(v: &mut [f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

// ---------------------------------------------------------------------------
// Part 1: the split
// ---------------------------------------------------------------------------

struct SplitRow {
    case: Case,
    h: f64,
    zone: f64,
    pl: f64,
    split: LossSplit,
    /// The bands of x_m/L: < 0.98, 0.98–0.995, ≥ 0.995.
    bands: [f64; 3],
    /// Time with the contact open in the support zone, s.
    support_time: f64,
}

fn split_row(d: &Done) -> SplitRow {
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

fn split_table(rows: &[SplitRow], lb: f64, by_dt: bool) {
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
fn fit_line(label: &str, x: &[f64], y: &[f64]) -> Option<f64> {
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
fn distance_table(runs: &[&Done], by_dt: bool) {
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
fn candidates_table(runs: &[&Done], by_dt: bool) -> Vec<(f64, f64, bool)> {
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
fn arrival_table(runs: &[&Done], by_dt: bool) -> Option<f64> {
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
fn peak_mesh_table(speed: f64, dts: &[f64]) {
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

// ---------------------------------------------------------------------------
// Part 2: re-contacts
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy)]
struct Recontact {
    /// Time of the step end where the contact closes, s.
    t: f64,
    /// x_m/L there.
    x_over_l: f64,
    /// In the support zone.
    support: bool,
    /// Duration of the loss before it, s.
    loss: f64,
    /// Closing speed Δv = −dg/dt over the last open step, m/s.
    dv: f64,
    /// Largest λ over the first PEAK_STEPS steps (while closed), N.
    peak: f64,
    /// ∫λ dt over IMPULSE_WINDOW from the re-contact step, N·s.
    impulse_window: f64,
    /// The run ends inside the impulse window (the carrier reaches x = L).
    truncated: bool,
    /// ∫λ dt over the first closed interval, N·s.
    impulse_closed: f64,
}

/// Primary re-contacts of one run (after a loss ≥ MIN_LOSS_TIME), and the
/// number of all re-contacts.
fn recontacts(d: &Done) -> (Vec<Recontact>, usize) {
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

fn recontact_study(runs: &[&Done]) -> RecontactSummary {
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

fn range(v: &[f64]) -> Option<(f64, f64)> {
    if v.is_empty() {
        return None;
    }
    Some((
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    ))
}

struct RecontactSummary {
    a_span_resolved: Option<f64>,
    a_span: Option<f64>,
    a_support: Option<f64>,
    a_span_range: Option<(f64, f64)>,
    max_change_span: Option<f64>,
    median_change_span: Option<f64>,
    max_change_support: Option<f64>,
    ratio_slope: Option<f64>,
}

// ---------------------------------------------------------------------------

fn main() {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zone_takes_the_largest_of_its_three_widths() {
        // reference beam: ℓ_b = sqrt(129.2/30000) = 0.0656 m
        let (ei, t): (f64, f64) = (129.2, 30000.0);
        let lb = (ei / t).sqrt();
        assert_eq!(support_zone(ei, t, 0.03125, 134.92, 2.5e-5), 4.0 * lb);
        assert_eq!(support_zone(ei, t, 0.125, 134.92, 2.5e-5), 0.5);
        assert_eq!(support_zone(ei, t, 0.01, 100.0, 1e-3), 0.4);
        // a string has no bending length
        assert_eq!(support_zone(0.0, t, 0.01, 100.0, 1e-5), 0.04);
    }

    #[test]
    fn parts_add_up_and_fall_where_the_zone_says() {
        // L = 10, z = 1: rows 1..=6 at x = 0.5 (support), 2, 5, 8 (span), 9.5, 9.9 (support)
        let x = [0.0, 0.5, 2.0, 5.0, 8.0, 9.5, 9.9];
        let c = [true, false, true, false, false, false, true];
        let s = split_loss(&x, &c, 10.0, 1.0);
        assert_eq!(s.support, 2.0 / 6.0);
        assert_eq!(s.in_span, 2.0 / 6.0);
    }
}
