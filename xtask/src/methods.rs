//! The measured tables behind `docs/methods.md` (printed; `cargo xtask
//! methods > out/xtask/methods.md`): every time integrator on the
//! study's reference case (docs/targets.md; `scenes/reference.toml`, N = 400).
//!
//! 1. Headline at each method's working step: P_l (whole run and in-span),
//!    contact switches, the largest (re-contact) force, the 0–20 Hz contact
//!    force's relative RMS error against a converged reference, and cost.
//! 2. Convergence as Δt falls: the same quantities at Δt = 1e-4 … 1.25e-5 s.
//! 3. In-span contact loss at V0/c = 0.9 (N = 1600) under every method as
//!    Δt falls.
//! 4. The generalized-α family with a moving constraint: which parameter
//!    sets keep the reference case's contact (unilateral and bilateral)
//!    stable.
//!
//! Run: `cargo xtask methods` (about a minute);
//! it prints markdown tables. Wall times depend on the machine; all other
//! figures are deterministic.

use taut::resolve::{Resolved, resolve_scene};
use taut::run::{RunOutput, run};
use taut::study::tolerance::{FORCE_BAND_HZ, lowpass_zero_phase};

const REFERENCE: &str = include_str!("../../scenes/reference.toml");

/// In-span part of the span: x_m/L below this. The last 2 % (1 m, a few
/// bending lengths sqrt(EI/T) = 0.066 m and eight elements) is the carrier's
/// arrival at the pinned support, whose loss does not converge in Δt
/// (docs/convergence.md).
const SPAN_END: f64 = 0.98;

/// The filtered force is compared before x_m/L = 0.85: the 0–20 Hz
/// filter's impulse response (≈ 1/20 Hz = 50 ms, 5 m at 100 m/s) carries
/// the support-arrival impulse back to x/L ≈ 0.9.
const FORCE_SPAN_END: f64 = 0.85;

/// The converged reference: generalized-α at Δt = 6.25e-6 s (16 × finer
/// than the study's step; the filtered force changes by < 1e-4 between
/// 1.25e-5 and 6.25e-6 s).
const REFERENCE_DT: f64 = 6.25e-6;

/// A supercritical-ish case: V0/c = 0.9 on a fine mesh, where the
/// contact is lost in span (not only at the support).
pub const FAST: &[&str] = &["carrier.speed.cruise=134.92", "mesh.elements=1600"];

/// Timing repeats: the fastest of three runs.
const REPEATS: usize = 3;

struct Row {
    label: String,
    dt: f64,
    pl: f64,
    pl_span: f64,
    switches: usize,
    max_force: f64,
    ringing: f64,
    force_error: f64,
    wall: f64,
    rate: f64,
}

/// The reference scene under `[integrator] {method}` at step `dt`.
pub fn scene(method: &str, dt: f64, extra: &[&str]) -> Resolved {
    let mut o = vec![
        format!("integrator={{ {method} }}"),
        format!("time.step={dt:e}"),
    ];
    o.extend(extra.iter().map(|s| s.to_string()));
    resolve_scene(REFERENCE, &o).expect("the reference scene resolves")
}

/// The contact force's step-to-step (Nyquist) component: the RMS of
/// (λ_{n+1} − 2λ_n + λ_{n−1})/4 over the RMS of λ, on in-span steps where
/// the contact is closed three steps running (≈ 0 for a resolved force; an
/// alternation ±A about the mean gives A/RMS).
pub fn ringing(out: &RunOutput, length: f64) -> f64 {
    let tr = &out.history.carriers[0];
    let (mut num, mut den) = (0.0, 0.0);
    for i in 1..tr.force.len() - 1 {
        let closed = tr.in_contact[i - 1] && tr.in_contact[i] && tr.in_contact[i + 1];
        if closed && tr.x[i] / length < SPAN_END {
            let d2 = (tr.force[i + 1] - 2.0 * tr.force[i] + tr.force[i - 1]) / 4.0;
            num += d2 * d2;
            den += tr.force[i] * tr.force[i];
        }
    }
    if den > 0.0 { (num / den).sqrt() } else { 0.0 }
}

/// P_l over the in-span steps (x_m/L < SPAN_END) only.
pub fn in_span_loss(out: &RunOutput, length: f64) -> f64 {
    let tr = &out.history.carriers[0];
    let steps = tr.in_contact.len() - 1;
    let lost = (1..=steps)
        .filter(|&i| !tr.in_contact[i] && tr.x[i] / length < SPAN_END)
        .count();
    lost as f64 / steps as f64
}

/// Relative RMS of the 0–20 Hz force against the reference's, on the
/// coarser time grid, before x_m/L = FORCE_SPAN_END.
pub fn force_error(out: &RunOutput, reference: &RunOutput, length: f64) -> f64 {
    let stride = (out.dt / reference.dt).round() as usize;
    let f = lowpass_zero_phase(&out.history.carriers[0].force, out.dt, FORCE_BAND_HZ);
    let r = lowpass_zero_phase(
        &reference.history.carriers[0].force,
        reference.dt,
        FORCE_BAND_HZ,
    );
    let r: Vec<f64> = r.iter().step_by(stride).copied().collect();
    let x = &out.history.carriers[0].x;
    let n = (1..f.len().min(r.len()))
        .find(|&i| x[i] / length >= FORCE_SPAN_END)
        .unwrap_or(f.len().min(r.len()));
    taut::study::relative_rms(&f[1..n], &r[1..n])
}

fn measure(label: &str, sc: &Resolved, reference: &RunOutput) -> Row {
    let mut best: Option<RunOutput> = None;
    for _ in 0..REPEATS {
        let out = run(sc, &mut |_, _| {}).unwrap_or_else(|e| panic!("{label}: {e}"));
        if best
            .as_ref()
            .is_none_or(|b| out.wall_seconds < b.wall_seconds)
        {
            best = Some(out);
        }
    }
    let out = best.expect("one run");
    let st = &out.stats[0];
    Row {
        label: label.to_string(),
        dt: sc.dt,
        pl: st.loss_fraction,
        pl_span: in_span_loss(&out, sc.beam.length),
        switches: st.contact_switches,
        max_force: st.force.max,
        ringing: ringing(&out, sc.beam.length),
        force_error: force_error(&out, reference, sc.beam.length),
        wall: out.wall_seconds,
        rate: out.dofs as f64 * out.steps as f64 / out.wall_seconds,
    }
}

fn table(rows: &[Row]) {
    println!(
        "| method | Δt (s) | P_l | P_l in span | switches | max λ (N) | ringing | 0–20 Hz force error (x/L < 0.85) | wall (s) | DOF-steps/s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        println!(
            "| {} | {:.3e} | {:.4} | {:.4} | {} | {:.0} | {:.3} | {:.2e} | {:.3} | {:.2e} |",
            r.label,
            r.dt,
            r.pl,
            r.pl_span,
            r.switches,
            r.max_force,
            r.ringing,
            r.force_error,
            r.wall,
            r.rate
        );
    }
    println!();
}

/// The methods of the tables: a label and the `[integrator]` table's body.
pub const METHODS: [(&str, &str); 7] = [
    (
        "generalized_alpha (ρ∞ = 1)",
        "method = \"generalized_alpha\"",
    ),
    (
        "generalized_alpha (ρ∞ = 0.8)",
        "method = \"generalized_alpha\", rho_inf = 0.8",
    ),
    ("hht (α = 0.3)", "method = \"hht\", alpha = 0.3"),
    ("wbz (ρ∞ = 0.5)", "method = \"wbz\", rho_inf = 0.5"),
    ("bathe", "method = \"bathe\""),
    ("central_difference", "method = \"central_difference\""),
    ("moreau_jean (θ = ½)", "method = \"moreau_jean\""),
];

/// The report: what `cargo xtask methods` runs (its
/// command-line arguments, if any, are read here).
pub fn main() {
    let methods = METHODS;
    let reference = run(
        &scene("method = \"generalized_alpha\"", REFERENCE_DT, &[]),
        &mut |_, _| {},
    )
    .expect("the reference runs");
    println!(
        "reference: generalized_alpha, Δt = {REFERENCE_DT:e} s: P_l = {:.4}, in span {:.4}\n",
        reference.stats[0].loss_fraction,
        in_span_loss(&reference, 50.0)
    );

    println!(
        "## 1. Headline (N = 400; central difference at its largest power-of-two step below 2/ω_max)\n"
    );
    let headline: Vec<Row> = methods
        .iter()
        .map(|(label, m)| {
            let dt = if label.starts_with("central") {
                5e-5
            } else {
                1e-4
            };
            measure(label, &scene(m, dt, &[]), &reference)
        })
        .collect();
    table(&headline);

    println!("## 2. As Δt falls\n");
    let mut ladder = Vec::new();
    for (label, m) in methods {
        for dt in [1e-4, 5e-5, 2.5e-5, 1.25e-5] {
            if label.starts_with("central") && dt > 6e-5 {
                continue;
            }
            ladder.push(measure(label, &scene(m, dt, &[]), &reference));
        }
    }
    table(&ladder);

    println!(
        "## 3. In-span contact loss at V0/c = 0.9 (cruise 134.92 m/s, N = 1600): P_l in span as Δt falls\n"
    );
    println!("| method | Δt = 1e-4 | 5e-5 | 2.5e-5 | 1.25e-5 |");
    println!("|---|---|---|---|---|");
    let in_span = |m: &str, dt: f64| -> String {
        let sc = scene(m, dt, FAST);
        match run(&sc, &mut |_, _| {}) {
            Ok(o) => format!("{:.4}", in_span_loss(&o, sc.beam.length)),
            Err(e @ taut::Error::Invalid { .. }) => format!("refused ({})", short(&e.to_string())),
            Err(e) => format!("stopped: {}", short(&e.to_string())),
        }
    };
    for (label, m) in methods {
        if label.starts_with("central") {
            continue;
        }
        let cells: Vec<String> = [1e-4, 5e-5, 2.5e-5, 1.25e-5]
            .iter()
            .map(|&dt| in_span(m, dt))
            .collect();
        println!("| {label} | {} |", cells.join(" | "));
    }
    // central difference: ω_max grows like N² for the bending-dominated top
    // modes, so at N = 1600 it needs the steps below 2/ω_max
    let cd = "method = \"central_difference\"";
    let limit = {
        let sc = scene(cd, 1e-6, FAST);
        taut::integrate::central_difference_limit(&sc)
            .expect("M factors")
            .dt_max
    };
    let stable: Vec<f64> = (0..12)
        .map(|k| 1e-4 / 2f64.powi(k))
        .filter(|&dt| dt <= limit)
        .take(2)
        .collect();
    println!(
        "\ncentral_difference (2/ω_max = {limit:.3e} s): {}\n",
        stable
            .iter()
            .map(|&dt| format!("Δt = {dt:.4e}: {}", in_span(cd, dt)))
            .collect::<Vec<_>>()
            .join("; ")
    );

    println!("## 4. The generalized-α family with a moving constraint (Δt = 1e-4 s)\n");
    println!("| method | α_f | unilateral: switches, P_l | bilateral |");
    println!("|---|---|---|---|");
    let family: [(&str, &str); 10] = [
        (
            "generalized_alpha ρ∞ = 1",
            "method = \"generalized_alpha\", rho_inf = 1.0",
        ),
        (
            "generalized_alpha ρ∞ = 0.9",
            "method = \"generalized_alpha\", rho_inf = 0.9",
        ),
        (
            "generalized_alpha ρ∞ = 0.5",
            "method = \"generalized_alpha\", rho_inf = 0.5",
        ),
        ("newmark", "method = \"newmark\""),
        ("hht α = 0.05", "method = \"hht\", alpha = 0.05"),
        ("hht α = 0.1", "method = \"hht\", alpha = 0.1"),
        ("hht α = 0.2", "method = \"hht\", alpha = 0.2"),
        ("wbz ρ∞ = 0.8", "method = \"wbz\", rho_inf = 0.8"),
        ("wbz ρ∞ = 0.5", "method = \"wbz\", rho_inf = 0.5"),
        ("wbz ρ∞ = 0", "method = \"wbz\", rho_inf = 0.0"),
    ];
    for (label, m) in family {
        let sc = scene(m, 1e-4, &[]);
        let taut::scene::Scheme::GenAlpha(p) = sc.method.scheme else {
            unreachable!("the generalized-α family")
        };
        let uni = match run(&sc, &mut |_, _| {}) {
            Ok(o) => format!(
                "{}, {:.4}",
                o.stats[0].contact_switches, o.stats[0].loss_fraction
            ),
            Err(e) => format!("stopped: {}", short(&e.to_string())),
        };
        let bi = match run(
            &scene(m, 1e-4, &["contact.kind=bilateral", "time.end=0.4"]),
            &mut |_, _| {},
        ) {
            Ok(_) => "runs".to_string(),
            Err(e) => format!("diverges: {}", short(&e.to_string())),
        };
        println!("| {label} | {:.3} | {uni} | {bi} |", p.alpha_f);
    }
}

/// The step and time of an error message.
fn short(e: &str) -> String {
    e.split(": carrier")
        .next()
        .unwrap_or(e)
        .replace("run diverged ", "")
}
