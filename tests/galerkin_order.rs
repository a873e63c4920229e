//! The `galerkin` discretization's order in J on the moving force
//! (docs/discretizations.md, "Order in J").
//!
//! On a pinned–pinned beam the `galerkin` basis is the moving-force
//! series' own (MODEL §8), so with J modes its spatial error is the
//! series' tail beyond J, exactly:
//! `w − w_J = Σ_{j>J} q_j(t) sin(κ_j x_m)`, κ_j = jπ/L. While the force is
//! on, q_j is its quasi-static part `K sin(Ω_j t)/(ω_j² − Ω_j²)` plus free
//! vibration, with `ω_j² − Ω_j² = κ_j²(EIκ_j² + T_e)/ρA`, T_e = T − ρAV².
//! Under the force (x_m = Vt) the quasi-static terms are
//! `K sin²(κ_j x_m)/(ω_j² − Ω_j²) ≥ 0`: they do not cancel, and they fall
//! like j⁻² where tension dominates (κ_j² < T_e/EI) and like j⁻⁴ where
//! bending does. So the error under the load falls like J⁻¹ below the
//! crossover `j_c = (L/π)·sqrt(T_e/EI)` (210 for this beam at V = 75 m/s;
//! 243 with T in place of T_e) and like J⁻³ above it. The displacement
//! field's L2 norm over the span squares the coefficients before summing:
//! J^(−3/2) and J^(−7/2).
//!
//! The transition is broad: the tail `S(J) = Σ_{j>J} 1/(κ_j²(EIκ_j² +
//! T_e))` has local order 1.07 at J = 10 → 20, 1.55 at 50 → 100, 2.53 at
//! 200 → 400 and 2.96 at 800 → 1600. The default test checks taut's
//! `galerkin` runs against it at both ends (J = 10 → 20 → 40, and 300 →
//! 600), with the time step small enough that the time error is a tenth
//! of the truncation error or less. The table of the docs is an `#[ignore]`d
//! study: `cargo test --release --test numerics galerkin_order:: -- --ignored --nocapture`.

use crate::common;

use std::f64::consts::PI;

use common::{run, scene};
use taut::analytic::{MovingForceBeam, PinnedPinnedModes};
use taut::study::uncertainty::observed_order;

const MOVING_FORCE: &str = "moving_force_beam.toml";

/// The moving force of the scene: F (N) at V (m/s).
const FORCE: f64 = 100.0;
const SPEED: f64 = 75.0;

/// Sampling interval of the error, s.
const SAMPLE: f64 = 2e-4;

/// Observed orders within this of the quasi-static tail's local order
/// ([`model_order`]): measured within 0.20 of it over J = 10 … 640 (the
/// max over t of a tail weighted by sin²(κ_j x_m), with free vibration on
/// top, against a plain sum); 0.3 still tells 1 from 2 from 3.
const ORDER_TOL: f64 = 0.3;

/// The time error of a run may be at most this fraction of the truncation
/// error it sits on (both measured per run; see the test).
const TIME_ERROR_FRACTION: f64 = 0.1;

/// w under the force every [`SAMPLE`] to `end`: the series with all modes
/// (`None`) or the first J.
fn series(end: f64, modes: Option<usize>) -> Vec<f64> {
    let sc = scene(MOVING_FORCE, &[]);
    let b = &sc.beam;
    let s = MovingForceBeam::new(b.ei, b.tension, b.rho_a, b.length, FORCE, SPEED).unwrap();
    let n = (end / SAMPLE).round() as usize;
    (0..=n)
        .map(|i| {
            let t = i as f64 * SAMPLE;
            match modes {
                Some(j) => s.deflection_series(SPEED * t, t, j),
                None => s.deflection(SPEED * t, t),
            }
        })
        .collect()
}

/// A `galerkin` run with J modes and step `dt` to `end`, w under the force
/// every [`SAMPLE`].
fn galerkin(modes: usize, dt: f64, end: f64) -> Vec<f64> {
    let sc = scene(
        MOVING_FORCE,
        &[
            "mesh.kind=galerkin",
            &format!("mesh.modes={modes}"),
            &format!("time.step={dt:e}"),
            &format!("time.end={end}"),
        ],
    );
    let out = run(&sc);
    let stride = (SAMPLE / sc.dt).round() as usize;
    out.history.carriers[0]
        .w
        .iter()
        .step_by(stride)
        .copied()
        .collect()
}

/// max |a − b| / max |b|.
fn rel_max(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let peak = b[..n].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    (0..n).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max) / peak
}

/// RMS(a − b) / RMS(b).
fn rel_rms(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let d: f64 = (0..n).map(|i| (a[i] - b[i]).powi(2)).sum();
    let r: f64 = b[..n].iter().map(|x| x * x).sum();
    (d / r).sqrt()
}

/// The crossover mode j_c = (L/π)·sqrt(T_e/EI) of the scene's beam at the
/// force's speed.
fn crossover() -> f64 {
    let sc = scene(MOVING_FORCE, &[]);
    let b = &sc.beam;
    let te = b.tension - b.rho_a * SPEED * SPEED;
    b.length / PI * (te / b.ei).sqrt()
}

/// Terms summed for the model's tail: they fall like j⁻⁴, so the rest is
/// below 1e-13 of the smallest tail used.
const MODEL_TERMS: usize = 2_000_000;

/// The quasi-static tail the error follows (module docs),
/// `S(J) = Σ_{j>J} 1/(κ_j²(EIκ_j² + T_e))`, and so the model's local order
/// from J to 2J, log2(S(J)/S(2J)): 1 for J ≪ j_c, 3 for J ≫ j_c, and a
/// broad transition between (1.26 at J = 25 → 50, 2.53 at 200 → 400).
fn model_order(j: usize) -> f64 {
    let sc = scene(MOVING_FORCE, &[]);
    let b = &sc.beam;
    let te = b.tension - b.rho_a * SPEED * SPEED;
    let tail = |from: usize| -> f64 {
        (from + 1..MODEL_TERMS)
            .map(|m| {
                let k = m as f64 * PI / b.length;
                1.0 / (k * k * (b.ei * k * k + te))
            })
            .sum()
    };
    (tail(j) / tail(2 * j)).log2()
}

/// Error of galerkin runs at J modes and Δt against the full series, with
/// the time error (against the series truncated at J) and the truncation
/// error (the truncated series against the full one) beside it.
struct Level {
    total: f64,
    time: f64,
    truncation: f64,
}

fn level(modes: usize, dt: f64, end: f64, full: &[f64]) -> Level {
    let w = galerkin(modes, dt, end);
    let truncated = series(end, Some(modes));
    Level {
        total: rel_max(&w, full),
        time: rel_max(&w, &truncated),
        truncation: rel_max(&truncated, full),
    }
}

#[test]
fn galerkin_order_in_j_follows_the_point_load_s_tail() {
    let jc = crossover();
    for (modes, dt, end) in [
        ([10usize, 20, 40], 1e-4, 0.6),
        ([300, 600, 0], 6.25e-6, 0.2),
    ] {
        let modes: Vec<usize> = modes.into_iter().filter(|&j| j > 0).collect();
        let full = series(end, None);
        let levels: Vec<Level> = modes.iter().map(|&j| level(j, dt, end, &full)).collect();
        for (j, l) in modes.iter().zip(&levels) {
            println!(
                "J = {j} (j_c = {jc:.0}), Δt = {dt:e}: error {:.3e} (time {:.2e}, truncation {:.3e})",
                l.total, l.time, l.truncation
            );
            assert!(
                l.time <= TIME_ERROR_FRACTION * l.truncation,
                "J = {j}: the time error {:.2e} is not negligible against the truncation {:.2e}",
                l.time,
                l.truncation
            );
        }
        for (p, l) in modes.windows(2).zip(levels.windows(2)) {
            let order = observed_order(l[0].total, l[1].total, 2.0);
            let model = model_order(p[0]);
            println!(
                "J = {} → {}: order {order:.2} (model {model:.2})",
                p[0], p[1]
            );
            assert!(
                (order - model).abs() <= ORDER_TOL,
                "J = {} → {}: order {order}, the tail's {model}",
                p[0],
                p[1]
            );
        }
    }
}

// ---------------------------------------------------------------------------

/// K sin(Ω_j t)/(ω_j² − Ω_j²) and the free vibration, q_j(t) while the
/// force is on (MODEL §8; no resonance at V = 75 m/s < c).
fn modal_coordinate(modes: &PinnedPinnedModes, j: usize, t: f64) -> f64 {
    let k = 2.0 * FORCE / (modes.rho_a * modes.length);
    let big = j as f64 * PI * SPEED / modes.length;
    let w = modes.omega(j);
    k * ((big * t).sin() - big / w * (w * t).sin()) / (w * w - big * big)
}

/// Modes summed for the field norm's reference: the coefficients fall like
/// j⁻⁴ in the bending range, so the tail beyond this is below 1e-12 of the
/// norm.
const FIELD_MODES: usize = 20_000;

/// Times at which the field norm is evaluated, s (its largest over these).
const FIELD_SAMPLE: f64 = 0.01;

#[test]
#[ignore = "the table of docs/discretizations.md, about a minute in release: cargo test --release --test numerics galerkin_order:: -- --ignored --nocapture"]
fn galerkin_order_in_j_table() {
    let sc = scene(MOVING_FORCE, &[]);
    let b = &sc.beam;
    let modes = PinnedPinnedModes::new(b.ei, b.tension, b.rho_a, b.length).unwrap();
    let end = sc.steps as f64 * sc.dt;
    println!(
        "crossover j_c = (L/π)·sqrt(T_e/EI) = {:.0} (with T: {:.0})",
        crossover(),
        b.length / PI * (b.tension / b.ei).sqrt()
    );
    let full = series(end, None);
    let js = [10usize, 20, 40, 80, 160, 320, 640];
    let dt = 3.125e-6;

    println!(
        "\n| J | ω_J (rad/s) | galerkin run, Δt = {dt:e} s: max error under the load | its time error | series tail under the load: max | RMS over t | field L2 over x (max over t) |"
    );
    // q_j² at every FIELD_SAMPLE, j ≤ FIELD_MODES
    let field_sq: Vec<Vec<f64>> = (1..=(end / FIELD_SAMPLE).round() as usize)
        .map(|i| {
            let t = i as f64 * FIELD_SAMPLE;
            (1..=FIELD_MODES)
                .map(|m| modal_coordinate(&modes, m, t).powi(2))
                .collect()
        })
        .collect();
    let mut rows = Vec::new();
    for &j in &js {
        let l = level(j, dt, end, &full);
        let truncated = series(end, Some(j));
        let rms = rel_rms(&truncated, &full);
        // the field's L2 norm over the span, sqrt(L/2 Σ q_j²): the largest
        // tail over the field times, relative to the largest norm
        let norm = field_sq
            .iter()
            .map(|q| q.iter().sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let field = field_sq
            .iter()
            .map(|q| q[j..].iter().sum::<f64>().sqrt())
            .fold(0.0, f64::max)
            / norm;
        println!(
            "| {j} | {:.2e} | {:.3e} | {:.1e} | {:.3e} | {:.3e} | {:.3e} |",
            modes.omega(j),
            l.total,
            l.time,
            l.truncation,
            rms,
            field
        );
        rows.push([l.total, l.truncation, rms, field]);
    }
    println!("\nobserved orders (J doubling):");
    println!("| J | run, max | tail, max | tail, RMS | field L2 | model (quasi-static tail) |");
    for (p, r) in js.windows(2).zip(rows.windows(2)) {
        let o: Vec<String> = (0..4)
            .map(|c| format!("{:.2}", observed_order(r[0][c], r[1][c], 2.0)))
            .collect();
        println!(
            "| {} → {} | {} | {:.2} |",
            p[0],
            p[1],
            o.join(" | "),
            model_order(p[0])
        );
    }
}
