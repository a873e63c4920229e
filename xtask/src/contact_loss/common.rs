//! What the parts of the contact-loss report share: imports, the study
//! settings, the runs and small numerics.

pub(super) use std::time::Instant;

pub(super) use rayon::prelude::*;
pub(super) use taut::resolve::{Resolved, resolve_scene};
pub(super) use taut::run::{RunOutput, run};
pub(super) use taut::scene::CarrierKind;

pub(super) const REFERENCE: &str = include_str!("../../../scenes/reference.toml");

// ---------------------------------------------------------------------------
// Study settings
// ---------------------------------------------------------------------------

/// V0/c = 0.9 (c = 149.9 m/s): contact is lost in the span, not only at the
/// support.
pub(super) const FAST_SPEED: f64 = 134.92;
/// The reference scene's own cruise speed (V0/c = 0.67).
pub(super) const SCENE_SPEED: f64 = 100.0;
/// The mesh of the Δt ladder (h = 0.031 m < ℓ_b = 0.066 m).
pub(super) const DT_LADDER_ELEMENTS: usize = 1600;
/// The step of the h ladder.
pub(super) const H_LADDER_DT: f64 = 2.5e-5;
/// Δt ladder (s). Four levels and two more, 6.25e-6 and
/// 3.125e-6 s, to give the peak and support fits more points and to test
/// the trend beyond the first four (the finest run takes about 2 s).
pub(super) const DT_LADDER: [f64; 6] = [1e-4, 5e-5, 2.5e-5, 1.25e-5, 6.25e-6, 3.125e-6];
pub(super) const DT_LADDER_QUICK: [f64; 3] = [1e-4, 5e-5, 2.5e-5];
/// h ladder (elements N): four levels and N = 6400, to check
/// the in-span part one level further (h/ℓ_b = 1.9 … 0.12).
pub(super) const H_LADDER: [usize; 5] = [400, 800, 1600, 3200, 6400];
pub(super) const H_LADDER_QUICK: [usize; 3] = [400, 800, 1600];
/// The in-span part counts as converged when it changes by less than this
/// fraction of its value between the two finest levels (2 %).
pub(super) const CONVERGED_CHANGE: f64 = 0.02;
/// Zone widths tried besides the default 4ℓ_b (in bending lengths).
pub(super) const ZONE_CANDIDATES: [f64; 5] = [2.0, 4.0, 6.0, 8.0, 12.0];
/// Bands of distance from the right support, in bending lengths, for the
/// table of where the lost steps lie.
pub(super) const DISTANCE_BANDS: [f64; 8] = [0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 16.0];

/// The re-contact's peak is the largest λ over its first PEAK_STEPS steps
/// (the rigid-impact spike sits in the first step or two).
pub(super) const PEAK_STEPS: usize = 3;
/// The fixed physical window of the re-contact impulse ∫λ dt, s. It is about
/// the decay time m/Z = 2.5 ms of a 1 kg mass on the string's impedance
/// (below), and it counts bounces after the re-contact with the re-contact,
/// so a spike split into a spike and bounces at a smaller Δt integrates alike.
pub(super) const IMPULSE_WINDOW: f64 = 2e-3;
/// A re-contact is "primary" when the loss before it lasted at least this
/// long; shorter losses are bounces after a re-contact (docs/convergence.md
/// §4e: their number grows as Δt falls). 0.2 ms = 2 steps at Δt = 1e-4 s,
/// so the closing speed can be estimated at every level.
pub(super) const MIN_LOSS_TIME: f64 = 2e-4;
/// The arrival-force law is fitted from this many carrier steps V·Δt before
/// the support (the last steps land at a Δt-dependent distance from L).
pub(super) const ARRIVAL_FIT_STEPS: f64 = 4.0;
/// Meshes for the peak's dependence on h at fixed Δt (full run only).
pub(super) const PEAK_MESHES: [usize; 3] = [800, 1600, 3200];
/// The Δt values of that check: one in the range where the peak follows
/// Δt^(−½) and the finest of the ladder.
pub(super) const PEAK_MESH_DTS: [f64; 2] = [2.5e-5, 3.125e-6];
/// Re-contacts of two runs are the same event when their times differ by
/// less than this (s); loss intervals at V0/c = 0.9 are ≥ several ms apart.
pub(super) const MATCH_TOLERANCE: f64 = 1e-3;

// ---------------------------------------------------------------------------
// Runs
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Case {
    pub(super) speed: f64,
    pub(super) elements: usize,
    pub(super) dt: f64,
}

pub(super) struct Done {
    pub(super) case: Case,
    pub(super) sc: Resolved,
    pub(super) out: RunOutput,
}

/// Run every case, in parallel, in order.
pub(super) fn run_all(cases: &[Case]) -> Vec<Done> {
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

pub(super) fn scene(case: Case) -> Resolved {
    let o = vec![
        format!("carrier.speed.cruise={}", case.speed),
        format!("mesh.elements={}", case.elements),
        format!("time.step={:e}", case.dt),
    ];
    resolve_scene(REFERENCE, &o).expect("the reference scene resolves")
}

pub(super) fn command(case: Case) -> String {
    format!(
        "`taut run scenes/reference.toml --set carrier.speed.cruise={} --set mesh.elements={} --set time.step={:e}`",
        case.speed, case.elements, case.dt
    )
}

/// Beam and carrier numbers every table uses.
#[derive(Debug, Clone, Copy)]
pub(super) struct Props {
    pub(super) length: f64,
    pub(super) ei: f64,
    pub(super) tension: f64,
    pub(super) rho_a: f64,
    pub(super) mass: f64,
}

impl Props {
    pub(super) fn of(sc: &Resolved) -> Self {
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
    pub(super) fn bending_length(&self) -> f64 {
        (self.ei / self.tension).sqrt()
    }
    /// The taut string's drive-point impedance Z = 2 sqrt(T ρA), N·s/m
    /// (a wave leaves each side with impedance sqrt(T ρA)).
    pub(super) fn string_impedance(&self) -> f64 {
        2.0 * (self.tension * self.rho_a).sqrt()
    }
    /// The crossover time t_c = 2 sqrt(EI ρA)/(π T), s: for an imposed
    /// velocity step Δv, the infinite Euler–Bernoulli beam's force
    /// 2 (EI)^¼ (ρA)^¾ sqrt(2/π) Δv t^(−½) equals the string's Z·Δv at
    /// t = t_c. Before t_c the beam is stiffer than the string.
    pub(super) fn crossover_time(&self) -> f64 {
        2.0 * (self.ei * self.rho_a).sqrt() / (std::f64::consts::PI * self.tension)
    }
}

// ---------------------------------------------------------------------------
// Small numerics
// ---------------------------------------------------------------------------

/// Least-squares slope of log y against log x over the points with y > 0.
pub(super) fn log_slope(x: &[f64], y: &[f64]) -> Option<f64> {
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
pub(super) fn successive_slopes(x: &[f64], y: &[f64]) -> Vec<Option<f64>> {
    (1..x.len())
        .map(|i| {
            // the slope is the observed order of y "refined" by x_i/x_{i−1}
            let p = taut::study::uncertainty::observed_order(y[i], y[i - 1], x[i] / x[i - 1]);
            p.is_finite().then_some(p)
        })
        .collect()
}

pub(super) fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("—".to_string(), |v| format!("{v:.digits$}"))
}

pub(super) fn rel_change(new: f64, old: f64) -> Option<f64> {
    (old != 0.0).then(|| (new - old) / old)
}

pub(super) fn pct(v: Option<f64>) -> String {
    v.map_or("—".to_string(), |v| format!("{:+.2} %", 100.0 * v))
}

pub(super) fn median(v: &mut [f64]) -> Option<f64> {
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
