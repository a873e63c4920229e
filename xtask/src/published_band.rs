//! The published loss band above V0/c ≈ 0.96 (TARGETS T7, Fig. 12) and T2's
//! period: the tables behind the findings at the end of docs/reproduction.md.
//!
//! ```sh
//! cargo xtask published-band
//! ```
//!
//! Prints four tables (about a minute on an AMD EPYC, 2 vCPUs; sweep folders go to
//! `target/published_band/`):
//!
//! 1. speed sweeps V0/c ∈ [0.5, 1.3] of `scenes/reference.toml` at several
//!    resolutions and schemes: where contact is lost in the span, and whether
//!    it is kept above V0/c = 0.96;
//! 2. the largest phase speed a tensioned Euler–Bernoulli beam can carry under
//!    the trapezoidal rule (generalized-α at ρ∞ = 1) at step Δt, against the
//!    upper border of in-span loss of a (T/EA, V0/c) sweep at Δt = 1e-3 s;
//! 3. the flexural precursor ahead of the carrier at V0/c = 1.1 (probes on the
//!    wire ahead of it): its amplitude and frequency at a fine and a large Δt;
//! 4. T2: the first return of the contact-force pulse and the recurrence
//!    period, with the discrete group speed of the wave carrying the pulse.
//!
//! Nothing is tuned: every run is the bundled scene with the named overrides.

use std::f64::consts::PI;
use std::path::PathBuf;

use taut::study::sweep::{Axis, SweepRecord, SweepSpec, sweep};
use taut::{resolve_scene, run};

/// The published upper border of the loss band (Fig. 12): contact kept above.
const PUBLISHED_UPPER: f64 = 0.96;
/// The speed grid: V0/c from 0.5 to 1.3 in steps of 0.025 (33 points), fine
/// enough to place a border to ±0.0125 and coarse enough for many sweeps.
const SPEED_AXIS: &str = "speed_ratio=0.5:1.3:33";
/// The tension grid of Fig. 12 (T/EA from 0.001 to 0.002).
const TENSION_AXIS: &str = "tension_ratio=0.001:0.002:11";
/// Speeds printed in the sweep table.
const SHOWN_SPEEDS: [f64; 3] = [0.8, 1.0, 1.2];
/// V0/c of the precursor study (above c, inside taut's fine-Δt loss region).
const PRECURSOR_RATIO: f64 = 1.1;
/// Probe positions ahead of the carrier, m (the last near the pinned end).
const PROBES: [f64; 3] = [40.0, 44.0, 48.0];
/// Window before the carrier passes a probe in which the precursor is
/// measured, s (long enough for a few periods of a 100 Hz wave).
const PRECURSOR_WINDOW: f64 = 0.06;
/// Frequency scan of the precursor, Hz: range and step of the direct DFT.
const SCAN_HZ: (f64, f64, f64) = (20.0, 1000.0, 1.0);
/// T2: the window that holds the first return of the pulse, s (it arrives at
/// 2(L − x0)/c = 0.654 s; the wave reflected at the clamped end follows at
/// 2L/c = 0.667 s with the opposite sign).
const FIRST_RETURN: (f64, f64) = (0.63, 0.665);
/// T2: lags searched for the recurrence period, s.
const PERIOD_LAGS: (f64, f64) = (0.6, 0.72);
/// T2: the force is resampled to this spacing for the autocorrelation, s.
const ACF_SPACING: f64 = 1e-4;
/// Frequencies at which the discrete group speed is reported, Hz: the bulk of
/// the T2 force spectrum lies below 100 Hz (median ≈ 28 Hz at N = 1600).
const PULSE_HZ: [f64; 3] = [10.0, 30.0, 60.0];
/// Wavenumber samples for the dispersion searches.
const K_SAMPLES: usize = 20_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scene(name: &str) -> String {
    std::fs::read_to_string(root().join("scenes").join(name)).expect("scene")
}

fn run_sweep(name: &str, set: &[&str], axes: &[&str]) -> Vec<SweepRecord> {
    let spec = SweepSpec {
        scene_text: scene("reference.toml"),
        set: set.iter().map(|s| s.to_string()).collect(),
        axes: axes
            .iter()
            .map(|a| Axis::parse(a, false).expect("axis"))
            .collect(),
        check_refinement: false,
        paired: false,
        tolerance: None,
    };
    let dir = root().join("target/published_band").join(name);
    // A fresh folder: the sweep is cheap, and a stale one may hold another spec.
    let _ = std::fs::remove_dir_all(&dir);
    let recs = sweep(&spec, &dir, None, &|_, _| {}).expect("sweep");
    assert!(
        recs.iter().all(|r| r.error.is_none()),
        "{name}: a run failed"
    );
    recs
}

fn fmt_range(v: &[f64]) -> String {
    match (v.first(), v.last()) {
        (Some(a), Some(b)) => format!("{a:.3}–{b:.3} ({} pts)", v.len()),
        _ => "none".into(),
    }
}

/// Table 1: speed sweeps at several resolutions and schemes.
fn speed_sweeps() {
    let cases: &[(&str, &[&str])] = &[
        ("N=50, Δt=1e-3", &["mesh.elements=50", "time.step=1e-3"]),
        ("N=100, Δt=5e-4", &["mesh.elements=100", "time.step=5e-4"]),
        ("N=100, Δt=1e-3", &["mesh.elements=100", "time.step=1e-3"]),
        ("N=200, Δt=1e-3", &["mesh.elements=200", "time.step=1e-3"]),
        ("N=400, Δt=1e-4 (reference)", &[]),
        ("N=400, Δt=1e-4, ρ∞=0", &["integrator.rho_inf=0"]),
        (
            "N=400, Δt=1e-4, Bathe",
            &["integrator={ method = \"bathe\" }"],
        ),
        (
            "N=400, Δt=1e-4, alpha placement",
            &["contact.placement=alpha"],
        ),
        ("N=400, Δt=5e-4", &["time.step=5e-4"]),
        ("N=400, Δt=7e-4", &["time.step=7e-4"]),
        ("N=400, Δt=1e-3", &["time.step=1e-3"]),
        (
            "N=400, Δt=1e-3, ρ∞=0",
            &["time.step=1e-3", "integrator.rho_inf=0"],
        ),
        (
            "N=400, Δt=1e-3, Bathe",
            &["time.step=1e-3", "integrator={ method = \"bathe\" }"],
        ),
        ("N=1600, Δt=1e-3", &["mesh.elements=1600", "time.step=1e-3"]),
        (
            "N=1600, Δt=2.5e-5 (refined)",
            &["mesh.elements=1600", "time.step=2.5e-5"],
        ),
    ];
    println!("## 1. Speed sweeps, V0/c = 0.5 … 1.3 (step 0.025), reference scene\n");
    println!(
        "| resolution / scheme | V0/c with in-span loss | V0/c with P_l > 0 | V0/c > {PUBLISHED_UPPER} with P_l,span = 0 | P_l,span at {:?} |",
        SHOWN_SPEEDS
    );
    println!("|---|---|---|---|---|");
    for (i, (label, set)) in cases.iter().enumerate() {
        let recs = run_sweep(&format!("speed_{i}"), set, &[SPEED_AXIS]);
        let ratio = |r: &SweepRecord| r.values[0];
        let span: Vec<f64> = recs
            .iter()
            .filter(|r| r.loss_fraction_span() > 0.0)
            .map(ratio)
            .collect();
        let any: Vec<f64> = recs
            .iter()
            .filter(|r| r.loss_fraction() > 0.0)
            .map(ratio)
            .collect();
        let above: Vec<&SweepRecord> = recs
            .iter()
            .filter(|r| ratio(r) > PUBLISHED_UPPER + 1e-9)
            .collect();
        let kept = above
            .iter()
            .filter(|r| r.loss_fraction_span() == 0.0)
            .count();
        let shown: Vec<String> = SHOWN_SPEEDS
            .iter()
            .map(|&v| {
                let r = recs
                    .iter()
                    .find(|r| (ratio(r) - v).abs() < 1e-6)
                    .expect("grid point");
                format!("{:.4}", r.loss_fraction_span())
            })
            .collect();
        println!(
            "| {label} | {} | {} | {kept}/{} | {} |",
            fmt_range(&span),
            fmt_range(&any),
            above.len(),
            shown.join(", ")
        );
    }
    println!();
}

/// Beam constants of the reference scene.
struct Beam {
    tension: f64,
    rho_a: f64,
    ei: f64,
    length: f64,
}

fn reference_beam() -> Beam {
    let sc = resolve_scene(&scene("reference.toml"), &[]).expect("scene");
    let b = &sc.beam;
    Beam {
        tension: b.tension,
        rho_a: b.rho_a,
        ei: b.ei,
        length: b.length,
    }
}

/// ω of the continuous tensioned beam at wavenumber k, rad/s.
fn omega(beam: &Beam, k: f64) -> f64 {
    ((beam.tension * k * k + beam.ei * k.powi(4)) / beam.rho_a).sqrt()
}

/// The trapezoidal rule's apparent frequency of a mode of frequency ω.
fn trapezoidal(w: f64, dt: f64) -> f64 {
    2.0 / dt * (w * dt / 2.0).atan()
}

/// max over k of ω_d(k)/k: the fastest phase speed the time-discrete beam
/// carries (space continuous), m/s. A carrier faster than this cannot shed a
/// steady wave ahead of itself.
fn phase_speed_cap(beam: &Beam, dt: f64) -> f64 {
    // Beyond this wavenumber ω_d ≤ π/Δt makes ω_d/k fall: 10 π/(cΔt).
    let c = (beam.tension / beam.rho_a).sqrt();
    let k_max = 10.0 * PI / (c * dt);
    (1..=K_SAMPLES)
        .map(|i| {
            let k = k_max * i as f64 / K_SAMPLES as f64;
            trapezoidal(omega(beam, k), dt) / k
        })
        .fold(0.0, f64::max)
}

/// Table 2: the phase-speed cap against the upper border of loss.
fn phase_speed_caps() {
    let beam = reference_beam();
    let c = (beam.tension / beam.rho_a).sqrt();
    println!("## 2. Fastest wave of the time-discrete beam (trapezoidal rule, ρ∞ = 1)\n");
    println!("| Δt (s) | max phase speed / c |");
    println!("|---|---|");
    for dt in [2.5e-5, 1e-4, 5e-4, 7e-4, 8e-4, 1e-3, 1.5e-3] {
        println!("| {dt:e} | {:.4} |", phase_speed_cap(&beam, dt) / c);
    }
    println!();
    let recs = run_sweep(
        "map_dt1e-3",
        &["time.step=1e-3"],
        &[TENSION_AXIS, SPEED_AXIS],
    );
    let ea = resolve_scene(&scene("reference.toml"), &[])
        .expect("scene")
        .beam
        .ea
        .expect("EA of the reference scene");
    println!("(T/EA, V0/c) sweep at N = 400, Δt = 1e-3 s:\n");
    println!("| T/EA | c (m/s) | cap / c | highest V0/c with in-span loss | lowest |");
    println!("|---|---|---|---|---|");
    let mut tensions: Vec<f64> = recs.iter().map(|r| r.values[0]).collect();
    tensions.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    for t in tensions {
        let b = Beam {
            tension: t * ea,
            ..reference_beam()
        };
        let ct = (b.tension / b.rho_a).sqrt();
        let lost: Vec<f64> = recs
            .iter()
            .filter(|r| (r.values[0] - t).abs() < 1e-12 && r.loss_fraction_span() > 0.0)
            .map(|r| r.values[1])
            .collect();
        let hi = lost.iter().cloned().fold(f64::NAN, f64::max);
        let lo = lost.iter().cloned().fold(f64::NAN, f64::min);
        println!(
            "| {t:.4} | {ct:.1} | {:.4} | {hi:.3} | {lo:.3} |",
            phase_speed_cap(&b, 1e-3) / ct
        );
    }
    println!();
}

/// Largest |DFT| over the scan: the dominant frequency of `y` sampled at dt.
fn dominant_frequency(y: &[f64], dt: f64) -> f64 {
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    let (lo, hi, step) = SCAN_HZ;
    let mut best = (0.0, lo);
    let mut f = lo;
    while f <= hi {
        let (mut re, mut im) = (0.0, 0.0);
        for (i, v) in y.iter().enumerate() {
            let ph = 2.0 * PI * f * i as f64 * dt;
            re += (v - mean) * ph.cos();
            im += (v - mean) * ph.sin();
        }
        let a = re * re + im * im;
        if a > best.0 {
            best = (a, f);
        }
        f += step;
    }
    best.1
}

/// Table 3: the precursor ahead of the carrier at V0/c = 1.1.
fn precursor() {
    let mut text = scene("reference.toml");
    for (i, x) in PROBES.iter().enumerate() {
        text.push_str(&format!("\n[[probe]]\nname = \"p{i}\"\nx = {x}\n"));
    }
    let c = resolve_scene(&text, &[]).expect("scene").beam.wave_speed();
    let beam = reference_beam();
    let k = ((PRECURSOR_RATIO.powi(2) - 1.0) * c * c * beam.rho_a / beam.ei).sqrt();
    println!(
        "## 3. Precursor ahead of the carrier, V0/c = {PRECURSOR_RATIO}\n\nContinuous beam: the steady wave with phase speed V has k = {k:.2} rad/m (wavelength {:.2} m), f = kV/2π = {:.0} Hz.\n",
        2.0 * PI / k,
        k * PRECURSOR_RATIO * c / (2.0 * PI)
    );
    println!(
        "| N, Δt | probe x (m) | max |v| before the carrier passes (mm) | dominant frequency there (Hz) | P_l,span |"
    );
    println!("|---|---|---|---|---|");
    for (n, dt) in [(1600, 2.5e-5), (400, 1e-4), (400, 5e-4), (400, 1e-3)] {
        let sets = vec![
            format!("mesh.elements={n}"),
            format!("time.step={dt:e}"),
            format!("carrier.speed.cruise={:e}", PRECURSOR_RATIO * c),
        ];
        let sc = resolve_scene(&text, &sets).expect("scene");
        let o = run(&sc, &mut |_, _| {}).expect("run");
        let h = &o.history;
        let tr = &h.carriers[0];
        let rec_dt = h.t[1] - h.t[0];
        for (i, xp) in PROBES.iter().enumerate() {
            let v = &h.probes[i].1;
            let pass = tr.x.iter().position(|&x| x >= *xp).unwrap_or(tr.x.len());
            let before = &v[..pass];
            let amp = before.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            let from = pass.saturating_sub((PRECURSOR_WINDOW / rec_dt) as usize);
            let f = dominant_frequency(&v[from..pass], rec_dt);
            println!(
                "| {n}, {dt:e} | {xp} | {:.3} | {f:.0} | {:.4} |",
                amp * 1e3,
                o.stats[0].loss_fraction_span
            );
        }
    }
    println!();
}

/// Acoustic-branch ω(k) of an infinite mesh of Hermite cubic elements
/// (consistent mass, bending and geometric stiffness), rad/s.
fn fe_omega(beam: &Beam, h: f64, k: f64) -> f64 {
    let (t, ei, ra) = (beam.tension, beam.ei, beam.rho_a);
    // Element matrices, dofs (w_i, θ_i, w_j, θ_j).
    let kb = |p: usize, q: usize| -> f64 {
        let m = [
            [12.0, 6.0 * h, -12.0, 6.0 * h],
            [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
            [-12.0, -6.0 * h, 12.0, -6.0 * h],
            [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
        ];
        ei / h.powi(3) * m[p][q]
    };
    let kg = |p: usize, q: usize| -> f64 {
        let m = [
            [36.0, 3.0 * h, -36.0, 3.0 * h],
            [3.0 * h, 4.0 * h * h, -3.0 * h, -h * h],
            [-36.0, -3.0 * h, 36.0, -3.0 * h],
            [3.0 * h, -h * h, -3.0 * h, 4.0 * h * h],
        ];
        t / (30.0 * h) * m[p][q]
    };
    let mm = |p: usize, q: usize| -> f64 {
        let m = [
            [156.0, 22.0 * h, 54.0, -13.0 * h],
            [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
            [54.0, 13.0 * h, 156.0, -22.0 * h],
            [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
        ];
        ra * h / 420.0 * m[p][q]
    };
    let (cs, sn) = ((k * h).cos(), (k * h).sin());
    // Bloch 2×2 Hermitian matrix: diagonal real, off-diagonal (re, im).
    let bloch = |a: &dyn Fn(usize, usize) -> f64| {
        let d0 = a(0, 0) + a(2, 2) + 2.0 * a(0, 2) * cs;
        let d1 = a(1, 1) + a(3, 3) + 2.0 * a(1, 3) * cs;
        let re = a(0, 1) + a(2, 3) + (a(0, 3) + a(2, 1)) * cs;
        let im = (a(0, 3) - a(2, 1)) * sn;
        (d0, d1, re, im)
    };
    let kk = |p: usize, q: usize| kb(p, q) + kg(p, q);
    let (k0, k1, kr, ki) = bloch(&kk);
    let (m0, m1, mr, mi) = bloch(&mm);
    // det(K − sM) = 0: a s² + b s + c = 0.
    let a = m0 * m1 - (mr * mr + mi * mi);
    let b = -(k0 * m1 + k1 * m0) + 2.0 * (kr * mr + ki * mi);
    let c = k0 * k1 - (kr * kr + ki * ki);
    let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
    let s = (-b - disc) / (2.0 * a);
    s.max(0.0).sqrt()
}

/// Group speed dω_d/dk of the discrete (mesh + trapezoidal) beam at the
/// frequency f, m/s; None when the acoustic branch does not reach f.
fn discrete_group_speed(beam: &Beam, n: usize, dt: f64, f: f64) -> Option<f64> {
    let h = beam.length / n as f64;
    let w = 2.0 * PI * f;
    let wd = |k: f64| trapezoidal(fe_omega(beam, h, k), dt);
    let k_top = 0.999 * PI / h;
    if wd(k_top) < w {
        return None;
    }
    let (mut lo, mut hi) = (1e-6, k_top);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if wd(mid) < w { lo = mid } else { hi = mid }
    }
    let k = 0.5 * (lo + hi);
    let dk = k * 1e-4;
    Some((wd(k + dk) - wd(k - dk)) / (2.0 * dk))
}

/// Table 4: T2's first return and period.
fn t2_period() {
    let beam = reference_beam();
    let c = (beam.tension / beam.rho_a).sqrt();
    let x0 = 1.0;
    println!(
        "## 4. T2: first return and period\n\n2(L − x0)/c = {:.4} s, 2L/c = {:.4} s, published 0.657 s.\n",
        2.0 * (beam.length - x0) / c,
        2.0 * beam.length / c
    );
    println!(
        "| scene | N, Δt | first-return peak time (s) | recurrence period, autocorrelation (s) | mean force t > 0.3 s (N) |"
    );
    println!("|---|---|---|---|---|");
    for name in ["t2_stationary_mass.toml", "t2_stationary_mass_string.toml"] {
        for (n, dt) in [(1600, 2.5e-5), (400, 1e-4), (100, 5e-4), (50, 1e-3)] {
            let sets = vec![format!("mesh.elements={n}"), format!("time.step={dt:e}")];
            let sc = resolve_scene(&scene(name), &sets).expect("scene");
            let o = run(&sc, &mut |_, _| {}).expect("run");
            let t = &o.history.t;
            let f = &o.history.carriers[0].force;
            let peak = (0..t.len())
                .filter(|&i| (FIRST_RETURN.0..FIRST_RETURN.1).contains(&t[i]))
                .max_by(|&a, &b| f[a].total_cmp(&f[b]))
                .map(|i| t[i])
                .unwrap_or(f64::NAN);
            let rec_dt = t[1] - t[0];
            let stride = ((ACF_SPACING / rec_dt).round() as usize).max(1);
            let y: Vec<f64> = f.iter().step_by(stride).cloned().collect();
            let dy = rec_dt * stride as f64;
            let mean = y.iter().sum::<f64>() / y.len() as f64;
            let acf = |lag: usize| -> f64 {
                (0..y.len() - lag)
                    .map(|i| (y[i] - mean) * (y[i + lag] - mean))
                    .sum()
            };
            let (l0, l1) = ((PERIOD_LAGS.0 / dy) as usize, (PERIOD_LAGS.1 / dy) as usize);
            let best = (l0..=l1)
                .max_by(|&a, &b| acf(a).total_cmp(&acf(b)))
                .expect("lags");
            let (a, b, cc) = (acf(best - 1), acf(best), acf(best + 1));
            let period = (best as f64 + 0.5 * (a - cc) / (a - 2.0 * b + cc)) * dy;
            let late: Vec<f64> = (0..t.len()).filter(|&i| t[i] > 0.3).map(|i| f[i]).collect();
            println!(
                "| {name} | {n}, {dt:e} | {peak:.4} | {period:.4} | {:.2} |",
                late.iter().sum::<f64>() / late.len() as f64
            );
        }
    }
    println!();
    println!(
        "Discrete group speed of the wave carrying the pulse (Hermite mesh, trapezoidal rule), m/s; c = {c:.2}:\n"
    );
    println!(
        "| N, Δt | {} |",
        PULSE_HZ.map(|f| format!("{f} Hz")).join(" | ")
    );
    println!("|---|---|---|---|");
    for (n, dt) in [
        (50, 1e-3),
        (100, 1e-3),
        (100, 5e-4),
        (400, 1e-4),
        (1600, 2.5e-5),
    ] {
        let row: Vec<String> = PULSE_HZ
            .iter()
            .map(|&f| match discrete_group_speed(&beam, n, dt, f) {
                Some(v) => format!("{v:.2}"),
                None => "—".into(),
            })
            .collect();
        println!("| {n}, {dt:e} | {} |", row.join(" | "));
    }
    println!();
}

/// The command: `cargo xtask published-band`.
pub fn main() {
    speed_sweeps();
    phase_speed_caps();
    precursor();
    t2_period();
}
