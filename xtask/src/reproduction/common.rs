//! What the studies of `docs/reproduction.md` share: imports, the two
//! resolutions, the sweep runner with its progress, and formatting.

pub(super) use std::fmt::Write as _;
pub(super) use std::path::{Path, PathBuf};
pub(super) use std::sync::Mutex;
pub(super) use std::time::Instant;

pub(super) use rayon::prelude::*;
pub(super) use taut::report::{
    SPEED_RATIO_LEVELS, write_force_map, write_loss_fraction_map, write_loss_map,
};
pub(super) use taut::resolve::{Resolved, resolve_scene};
pub(super) use taut::run::run;
pub(super) use taut::study::sweep::{Axis, PROFILE_BINS, SweepRecord, SweepSpec, sweep};

/// A resolution: mesh and step.
#[derive(Clone, Copy)]
pub(super) struct Res {
    pub(super) tag: &'static str,
    pub(super) label: &'static str,
    pub(super) elements: usize,
    pub(super) dt: f64,
}

/// Like the study's (its mesh and step are not given; TARGETS "What the
/// study does not settle"): N = 400, Δt = 1e-4 s.
pub(super) const STUDY: Res = Res {
    tag: "study",
    label: "study-like (N = 400, Δt = 1e-4 s)",
    elements: 400,
    dt: 1e-4,
};

/// Refined: two refinements of both mesh and step (§ Resolution below
/// shows the features compared here do not move at N = 3200, Δt = 1.25e-5 s;
/// docs/convergence.md why no resolution gives P_l to 1 %).
pub(super) const CONVERGED: Res = Res {
    tag: "refined",
    label: "refined (N = 1600, Δt = 2.5e-5 s)",
    elements: 1600,
    dt: 2.5e-5,
};

/// Loss before this x_m/L counts as loss "in the span". Every run loses
/// contact in its last few steps as the carrier runs onto the pinned
/// support (the beam under it must rise to v = 0 there and launches the
/// mass: first loss at x_m/L ≈ 0.999 at low speed). 0.99 excludes the last
/// two of the 200 profile bins.
pub(super) const SPAN_END: f64 = 0.99;

/// Mid-span window of the force level and its fluctuation, x_m/L: past the
/// start ramp (L/5) and before the loss region near the right support.
pub(super) const MID: (f64, f64) = (0.2, 0.8);

/// A published border (in V0/c or another swept parameter) is matched when
/// taut's border is within this many grid steps of it: the published
/// figures are read from plots, and a border is only known to a grid step.
pub(super) const BORDER_STEPS: f64 = 2.5;

/// A trend is said to hold when Spearman's rank correlation of the
/// quantity with the swept parameter has the published sign and |ρ| ≥ this.
pub(super) const TREND_RHO: f64 = 0.5;

/// Half-width (x_m/L) of the window around the predicted encounter in which
/// the ridge's onset is sought, and length of the window after it in which
/// its height is taken: about ten bins, wider than the onset's lag.
pub(super) const RIDGE_WINDOW: f64 = 0.06;
/// The ridge is only sought where the encounter is before this x_m/L (later
/// ones run into the support's loss region).
pub(super) const RIDGE_LAST: f64 = 0.95;

/// Over V0/c = 0.4–0.9 the predicted encounter moves from x_m/L = 0.43 to
/// 0.84; a ridge made by it moves with it (slope 1 against it), one tied to
/// a place (slope 0) or to a wave of another speed would not. Within this
/// of 1 the onset is said to track the encounter.
pub(super) const TRACK_SLOPE_TOL: f64 = 0.2;

/// A T7 border agrees with the published one within this, in V0/c: about
/// one V0 step of the refined 21-point map (9 m/s at c = 150 m/s is 0.06).
pub(super) const T7_BORDER_TOL: f64 = 0.05;

/// T7 grid at the study-like resolution (per axis).
pub(super) const T7_STUDY_GRID: usize = 41;
/// T7 grid at the refined resolution (per axis) by default: 41 × 41
/// there takes ≈ 15 min on two free cores by itself (docs/sweeps.md), beyond
/// this page's budget; `--full` runs it.
pub(super) const T7_CONVERGED_GRID: usize = 21;

/// The resolution check: speed ratios and resolutions (N, Δt).
pub(super) const CHECK_RATIOS: [f64; 5] = [0.5, 0.6, 0.7, 0.8, 0.9];
pub(super) const CHECK_LEVELS: [(usize, f64); 4] =
    [(400, 1e-4), (800, 5e-5), (1600, 2.5e-5), (3200, 1.25e-5)];

pub(super) fn root() -> PathBuf {
    PathBuf::from(crate::ROOT)
}

pub(super) fn reference_text() -> String {
    let p = root().join("scenes/reference.toml");
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

pub(super) fn res_sets(r: Res) -> Vec<String> {
    vec![
        format!("mesh.elements={}", r.elements),
        format!("time.step={:e}", r.dt),
    ]
}

// ------------------------------------------------------------ progress

pub(super) struct Clock {
    pub(super) start: Instant,
}

impl Clock {
    pub(super) fn say(&self, what: &str) {
        eprintln!("[{:7.1} s] {what}", self.start.elapsed().as_secs_f64());
    }
}

/// Run (or resume) a sweep in `target/reproduction/<name>`, printing progress.
pub(super) fn run_sweep(clock: &Clock, name: &str, spec: &SweepSpec) -> Vec<SweepRecord> {
    let dir = root().join("target/reproduction").join(name);
    let t = Instant::now();
    let step = (spec.len() / 10).max(1);
    let last = Mutex::new(0usize);
    clock.say(&format!("{name}: {} runs …", spec.len()));
    let recs = sweep(spec, &dir, None, &|done, total| {
        let mut l = last.lock().unwrap();
        if done >= *l + step || done == total {
            *l = done;
            eprintln!(
                "            {name}: {done}/{total} ({:.0} s)",
                t.elapsed().as_secs_f64()
            );
        }
    })
    .unwrap_or_else(|e| panic!("sweep {name}: {e}"));
    taut::report::write_sweep(&dir, spec, &recs).expect("sweep tables");
    let failed = recs.iter().filter(|r| r.error.is_some()).count();
    clock.say(&format!(
        "{name}: done in {:.1} s ({failed} runs stopped with an error)",
        t.elapsed().as_secs_f64()
    ));
    recs
}
