//! What the sections of `docs/convergence.md` share: imports, constants,
//! the study runner and small numeric and formatting helpers.
pub(super) use std::collections::HashMap;
pub(super) use std::fmt::Write as _;
pub(super) use std::time::Instant;

pub(super) use taut::analytic::{
    ClampedPinnedModes, MovingForceBeam, MovingForceString, PinnedPinnedModes, StaticPointLoad,
};
pub(super) use taut::model::modal::fe_frequencies;
pub(super) use taut::record::CarrierTrace;
pub(super) use taut::resolve::{Resolved, resolve_scene};
pub(super) use taut::run::{RunOutput, run};
pub(super) use taut::scene::{BeamProps, CarrierKind, SpeedProfile, Support};
pub(super) use taut::study::converge::{ConvergeRow, Convergence, Refine, converge};
pub(super) use taut::study::reference::analytic_w;

/// Refinement ratio of every study here (the CLI default).
pub(super) const RATIO: f64 = 2.0;
/// Grid (s) on which the analytic moving-force references are evaluated:
/// the moving-force scenes' own step, a subset of every level's times.
pub(super) const EXACT_DT: f64 = 4e-4;
/// Grid (s) of the string-limit comparison (§3).
pub(super) const LIMIT_DT: f64 = 1e-3;
/// Truncation tolerance of the analytic beam series in §3, relative to the
/// static midspan deflection under F (the library default is 1e-9; the
/// differences measured there are ≥ 1e-6 m, so 1e-7 keeps the series cheap).
pub(super) const LIMIT_REL_TOL: f64 = 1e-7;
/// Reference case: the comparison window before the loss region, x_m/L ≤ this.
pub(super) const PRE_LOSS_X: f64 = 0.98;
/// Reference case: loss intervals longer than this (s) count as "long".
pub(super) const LONG_LOSS: f64 = 1e-4;
/// The convergence target of the brief.
pub(super) const TARGET: f64 = 0.01;

// ---------------------------------------------------------------- helpers

pub(super) fn scene_text(name: &str) -> String {
    let path = format!("{}/scenes/{name}.toml", crate::ROOT);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

pub(super) fn refine_name(r: Refine) -> &'static str {
    match r {
        Refine::Mesh => "mesh",
        Refine::Step => "step",
        Refine::Both => "both",
    }
}

/// Wall-clock bookkeeping, printed to stderr only.
pub(super) struct Clock {
    pub(super) start: Instant,
    pub(super) lap: Instant,
}

impl Clock {
    pub(super) fn new() -> Self {
        Clock {
            start: Instant::now(),
            lap: Instant::now(),
        }
    }
    pub(super) fn lap(&mut self, what: &str) {
        eprintln!(
            "  {:6.1} s  {what}  (total {:.1} s)",
            self.lap.elapsed().as_secs_f64(),
            self.start.elapsed().as_secs_f64()
        );
        self.lap = Instant::now();
    }
}

/// One `converge` study and the command that reproduces it.
pub(super) struct Study {
    pub(super) cmd: String,
    pub(super) c: Convergence,
}

pub(super) fn study(
    scene: &str,
    sets: &[String],
    refine: Refine,
    levels: usize,
    with_analytic: bool,
    clock: &mut Clock,
) -> Study {
    let text = scene_text(scene);
    let reference = |sc: &Resolved| if with_analytic { analytic_w(sc) } else { None };
    let c = converge(
        &text,
        sets,
        refine,
        levels,
        RATIO,
        &reference,
        &mut |_, _| {},
    )
    .unwrap_or_else(|e| panic!("{scene}: {e}"));
    let mut cmd = format!(
        "taut converge scenes/{scene}.toml --refine {} --levels {levels}",
        refine_name(refine)
    );
    for s in sets {
        let _ = write!(cmd, " --set {s}");
    }
    clock.lap(&cmd);
    Study { cmd, c }
}

pub(super) fn set(k: &str, v: impl std::fmt::Display) -> String {
    format!("{k}={v}")
}

pub(super) fn max_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// L2 as the RMS over samples (the library's definition).
pub(super) fn l2_norm(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

pub(super) fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    assert_eq!(a.len(), b.len(), "histories on different grids");
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

pub(super) fn order(coarse: f64, fine: f64) -> f64 {
    taut::study::uncertainty::observed_order(coarse, fine, RATIO)
}

/// Carrier 0's history of level `l` on the coarsest level's times (as the
/// library samples it).
pub(super) fn coarse(
    c: &Convergence,
    l: usize,
    pick: impl Fn(&CarrierTrace, usize) -> f64,
) -> Vec<f64> {
    let stride = (c.scenes[0].dt / c.scenes[l].dt).round() as usize;
    let tr = &c.runs[l].history.carriers[0];
    (0..c.runs[l].history.len())
        .step_by(stride)
        .map(|i| pick(tr, i))
        .collect()
}

/// Successive differences ‖u_ℓ − u_ℓ−1‖ (NaN at level 0).
pub(super) fn successive(h: &[Vec<f64>], norm: fn(&[f64]) -> f64) -> Vec<f64> {
    (0..h.len())
        .map(|l| {
            if l == 0 {
                f64::NAN
            } else {
                norm(&sub(&h[l], &h[l - 1]))
            }
        })
        .collect()
}

/// Observed orders from successive differences (NaN below level 2).
pub(super) fn orders(d: &[f64]) -> Vec<f64> {
    (0..d.len())
        .map(|l| {
            if l >= 2 {
                order(d[l - 1], d[l])
            } else {
                f64::NAN
            }
        })
        .collect()
}

pub(super) fn row<'a>(c: &'a Convergence, level: usize, quantity: &str) -> &'a ConvergeRow {
    c.rows
        .iter()
        .find(|r| r.level == level && r.quantity == quantity)
        .unwrap_or_else(|| panic!("no row {quantity} at level {level}"))
}

/// The orders printed here are the library's; this recomputes them from the
/// histories and insists that they agree.
pub(super) fn check_orders(c: &Convergence, quantity: &str, mine: &[f64]) {
    for (l, &p) in mine.iter().enumerate() {
        let lib = row(c, l, quantity).observed_order;
        assert!(
            (p.is_nan() && lib.is_nan()) || (p - lib).abs() <= 1e-9 * p.abs().max(1.0),
            "{quantity} level {l}: recomputed order {p} vs library {lib}"
        );
    }
}

/// Carrier 0's history of a run on the grid k·grid_dt.
pub(super) fn on_grid(
    out: &RunOutput,
    grid_dt: f64,
    pick: impl Fn(&CarrierTrace, usize) -> f64,
) -> Vec<f64> {
    let stride = (grid_dt / out.dt).round() as usize;
    assert!(
        stride >= 1 && (stride as f64 * out.dt - grid_dt).abs() <= 1e-9 * grid_dt,
        "Δt = {} does not divide the grid {grid_dt}",
        out.dt
    );
    let tr = &out.history.carriers[0];
    (0..out.history.len())
        .step_by(stride)
        .map(|i| pick(tr, i))
        .collect()
}

pub(super) fn e3(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3e}")
    } else {
        "—".into()
    }
}

pub(super) fn f2(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "—".into()
    }
}

pub(super) fn pct(x: f64) -> String {
    if !x.is_finite() {
        "—".into()
    } else if x.abs() < 1e-3 {
        format!("{:.3} %", 100.0 * x)
    } else {
        format!("{:.2} %", 100.0 * x)
    }
}

pub(super) fn table(d: &mut String, head: &[&str], rows: &[Vec<String>]) {
    let _ = writeln!(d, "| {} |", head.join(" | "));
    let _ = writeln!(
        d,
        "|{}|",
        head.iter().map(|_| "---").collect::<Vec<_>>().join("|")
    );
    for r in rows {
        assert_eq!(r.len(), head.len());
        let _ = writeln!(d, "| {} |", r.join(" | "));
    }
    let _ = writeln!(d);
}

pub(super) fn lsq_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

pub(super) fn joined(v: impl IntoIterator<Item = String>, sep: &str) -> String {
    v.into_iter().collect::<Vec<_>>().join(sep)
}

/// The finite orders of a study, "a, b, c".
pub(super) fn finite_f2(p: &[f64]) -> String {
    joined(
        p.iter()
            .filter(|x| x.is_finite())
            .map(|x| format!("{x:.2}")),
        ", ",
    )
}

/// Constant force and speed of carrier 0 of a moving-force scene.
pub(super) fn force_and_speed(sc: &Resolved) -> (f64, f64) {
    match (&sc.carriers[0].kind, &sc.carriers[0].motion.profile) {
        (CarrierKind::Force { force }, SpeedProfile::Constant { value }) => (*force, *value),
        _ => panic!("expected a constant force at constant speed"),
    }
}
