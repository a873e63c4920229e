//! The coverage tables behind `docs/verification.md` ("Solution
//! verification"; printed, `cargo xtask uncertainty > out/xtask/uncertainty.md`):
//! does `taut uncertainty`'s u_num cover the true error? (MODEL §12, "check
//! the estimator").
//!
//! For every case ([`cases`]) and every starting resolution (N₀ or J₀, Δt₀)
//! of its grid, one `taut uncertainty` family (K = 4 diagonal levels, 7
//! runs) is run and its finest value φ and u_num are held against the true
//! value ([`truth`]): the exact moving-force series, the riding mass's
//! Galerkin solution, or a refined `modal_exact` run. A pair is *covered*
//! when u_num ≥ |φ − φ_true|; its *sharpness* is u_num/|φ − φ_true|.
//! Targets: covered at ≥ [`COVERAGE_TARGET`] of the pairs,
//! sharpness ≤ [`SHARPNESS_LIMIT`] at ≥ [`SHARPNESS_TARGET`] of them.
//!
//! Run: `cargo xtask uncertainty` (every pair, about 6 minutes on an
//! AMD EPYC, 2 vCPUs), `cargo xtask uncertainty quick` (a few pairs a case), or with
//! words that pick cases by name (`cargo xtask uncertainty "reference
//! case"`). It prints
//! markdown tables to stdout; wall times go to stderr. `--dump FILE`
//! also writes every pair's family values and truth, and `cargo xtask
//! uncertainty replay FILE [--pairs OUT]` assesses them again with the
//! library's current estimators (milliseconds, no run; `--pairs` writes
//! each pair's u_num and errors for `scripts/sibling_spread.py`): a change
//! to an estimator is measured against the whole grid before the grid is
//! run again. The default test
//! suite runs a cut-down version (`tests/uncertainty.rs`). `cargo xtask
//! uncertainty heldout` runs and stores the held-out pairs ([`heldout`]),
//! which check the estimator chosen on these without choosing it.

pub mod cases;
pub mod heldout;
pub mod replay;
pub mod truth;

use std::time::Instant;

use taut::analytic::RidingMassHistory;
use taut::error::Result;
use taut::record::zone::support_zone_of;
use taut::resolve::resolve_scene;
use taut::study::uncertainty::{DEFAULT_LEVELS, Role, uncertainty};

pub use cases::{Case, Truth, cases};

/// Share of pairs whose u_num must cover the true error (95 %).
pub const COVERAGE_TARGET: f64 = 0.95;

/// The largest u_num / |true error| counted as sharp: an error bar ten
/// times the error it bounds says little more than "small".
pub const SHARPNESS_LIMIT: f64 = 10.0;

/// Share of pairs that must be sharp (80 %).
pub const SHARPNESS_TARGET: f64 = 0.8;

/// One pair's result.
#[derive(Debug, Clone)]
pub struct Row {
    /// The case's name.
    pub case: &'static str,
    /// The quantity.
    pub quantity: &'static str,
    /// Starting level parameter (N₀, or J₀) and Δt₀, s.
    pub start: (usize, f64),
    /// The finest level's parameter and Δt, s.
    pub finest: (usize, f64),
    /// The finest value.
    pub value: f64,
    /// Its u_num (NaN when none was given).
    pub u_num: f64,
    /// The bar of the family's level 0, the scene's own resolution
    /// (`u_scene`; NaN when none was given).
    pub u_scene: f64,
    /// The true value.
    pub truth: f64,
    /// The estimator and F_s.
    pub estimator: String,
    /// Its estimated error of the finest value, φ − φ_exact (NaN where it
    /// gives none).
    pub error_estimated: f64,
    /// F_s.
    pub safety_factor: f64,
    /// The observed order of the diagonal (NaN where the data support none).
    pub order: f64,
    /// How the diagonal's values behave.
    pub behaviour: &'static str,
    /// The truth's own accuracy: how far it moves when made at half its
    /// resolution (0 for the exact series; None until measured,
    /// [`truth::truth_spread`]).
    pub truth_spread: Option<f64>,
    /// The family's support zone, m (`analysis.support_zone`: the start
    /// scene's own), which a refined truth of P_l shares.
    pub support_zone: f64,
    /// The family's values along the diagonal, coarsest first, and of
    /// its space-only runs: what [`replay`] assesses again.
    pub diagonal: Vec<Option<f64>>,
    /// The space-only runs' values (level 1 first).
    pub space: Vec<Option<f64>>,
    /// The quantity's formal orders (space, time) in that family.
    pub formal: (f64, f64),
    /// The quantity is smooth in the resolution.
    pub smooth: bool,
}

impl Row {
    /// |φ − φ_true|.
    pub fn error(&self) -> f64 {
        (self.value - self.truth).abs()
    }

    /// u_num ≥ |φ − φ_true| (a pair without u_num is not covered).
    pub fn covered(&self) -> bool {
        self.u_num >= self.error()
    }

    /// u_num / |φ − φ_true| (∞ when the error is 0 and u_num is not).
    pub fn sharpness(&self) -> f64 {
        self.u_num / self.error()
    }

    /// Sharpness within [`SHARPNESS_LIMIT`] (an exact value with u_num = 0
    /// counts as sharp).
    pub fn sharp(&self) -> bool {
        self.sharpness() <= SHARPNESS_LIMIT || (self.u_num == 0.0 && self.error() == 0.0)
    }

    /// The truth resolves the error: |φ − φ_true| is larger than the
    /// truth's own change at half its resolution. Where it is not, the
    /// error measured is the truth's as much as the family's, and
    /// u_num / error says nothing about the estimator's sharpness.
    pub fn resolved(&self) -> bool {
        self.truth_spread.is_none_or(|d| self.error() > d)
    }
}

/// The scene text of a case.
pub fn scene_text(case: &Case) -> String {
    scene_text_of(case.scene)
}

/// The text of scene file `scene`, relative to the repository.
pub fn scene_text_of(scene: &str) -> String {
    let path = format!("{}/{scene}", crate::ROOT);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The overrides of a case at starting resolution `start`.
pub fn overrides(case: &Case, start: (usize, f64)) -> Vec<String> {
    let mut s: Vec<String> = case.set.iter().map(|x| x.to_string()).collect();
    let modal = case.set.iter().any(|x| x.contains("galerkin"));
    s.push(if modal {
        format!("mesh.modes={}", start.0)
    } else {
        format!("mesh.elements={}", start.0)
    });
    s.push(format!("time.step={:e}", start.1));
    s
}

/// The riding-mass reference of a case's scene, when its truth is one
/// (solved once a scene: its cost grows like J³).
pub fn riding_mass_of(case: &Case) -> Result<Option<RidingMassHistory>> {
    match case.truth {
        Truth::RidingMass => {
            let set: Vec<String> = case.set.iter().map(|x| x.to_string()).collect();
            Ok(Some(truth::riding_mass(&resolve_scene(
                &scene_text(case),
                &set,
            )?)?))
        }
        _ => Ok(None),
    }
}

/// Run one case at every starting resolution: its rows (`rm`: its
/// riding-mass reference, [`riding_mass_of`]).
pub fn run_case(case: &Case, levels: usize, rm: Option<&RidingMassHistory>) -> Result<Vec<Row>> {
    let text = scene_text(case);
    let base_set = case.set.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    // the truth depends on the pair only through the finest run's end
    // time (a refined truth not even on that): computed once per end time
    let mut known: Vec<(f64, f64, f64)> = Vec::new();
    let mut rows = Vec::new();
    for &start in &case.starts {
        let set = overrides(case, start);
        // the family measures P_l over its start's support zone: so does
        // the truth
        let zone = support_zone_of(&resolve_scene(&text, &set)?);
        let truth_set = truth_set(&base_set, zone);
        let u = uncertainty(&text, &set, levels, &mut |_, _| {})?;
        let q = u
            .quantities
            .iter()
            .find(|q| q.quantity == case.quantity)
            .expect("a listed quantity");
        let fine = u
            .family
            .iter()
            .rfind(|m| m.role == Role::Diagonal)
            .expect("a diagonal");
        let finest_level = fine.modes.unwrap_or(fine.elements);
        let mut fset = set.clone();
        let modal = fine.modes.is_some();
        fset.push(if modal {
            format!("mesh.modes={finest_level}")
        } else {
            format!("mesh.elements={finest_level}")
        });
        fset.push(format!("time.step={:e}", fine.dt));
        let finest = resolve_scene(&text, &fset)?;
        // the window's end, the scene's end time whatever the step (MODEL §7)
        let t_end = match case.truth {
            Truth::Refined { .. } => 0.0,
            _ => finest.t_end,
        };
        let t = match known.iter().find(|(t, z, _)| *t == t_end && *z == zone) {
            Some(&(_, _, v)) => v,
            None => {
                let v =
                    truth::true_value(case.truth, case.quantity, &finest, &text, &truth_set, rm)?;
                known.push((t_end, zone, v));
                v
            }
        };
        let a = &q.assessment;
        rows.push(Row {
            case: case.name,
            quantity: q.quantity,
            start,
            finest: (finest_level, fine.dt),
            value: a.value.unwrap_or(f64::NAN),
            u_num: a.u_num.unwrap_or(f64::NAN),
            u_scene: q.u_scene.unwrap_or(f64::NAN),
            truth: t,
            estimator: a.estimator.name().to_string(),
            error_estimated: a.error.unwrap_or(f64::NAN),
            safety_factor: a.safety_factor.unwrap_or(f64::NAN),
            order: a.observed_order.unwrap_or(f64::NAN),
            behaviour: a.behaviour.name(),
            truth_spread: (case.truth == Truth::Series).then_some(0.0),
            support_zone: zone,
            diagonal: q.diagonal.clone(),
            space: q.space.clone(),
            formal: q.formal,
            smooth: q.smooth,
        });
    }
    Ok(rows)
}

/// A case's overrides with the family's support zone `zone` (m) set, for
/// its truth.
pub fn truth_set(base: &[String], zone: f64) -> Vec<String> {
    let mut s = base.to_vec();
    s.push(format!("analysis.support_zone={zone:e}"));
    s
}

/// Coverage and sharpness of `rows`: (covered share, sharp share).
pub fn shares(rows: &[Row]) -> (f64, f64) {
    let n = rows.len().max(1) as f64;
    (
        rows.iter().filter(|r| r.covered()).count() as f64 / n,
        rows.iter().filter(|r| r.sharp()).count() as f64 / n,
    )
}

/// Sharpness over the pairs whose error the truth resolves
/// ([`Row::resolved`]): (sharp share, their count).
pub fn resolved_sharpness(rows: &[Row]) -> (f64, usize) {
    let resolved: Vec<&Row> = rows.iter().filter(|r| r.resolved()).collect();
    let n = resolved.len();
    (
        resolved.iter().filter(|r| r.sharp()).count() as f64 / n.max(1) as f64,
        n,
    )
}

/// Measure the truth's own accuracy ([`truth::truth_spread`]) for `rows`
/// and set it on each: once a case, or once for each support zone of its
/// families when the truth is a run that splits P_l itself. Returns the
/// largest (the one printed under the case's table).
fn set_truth_spreads(case: &Case, rows: &mut [Row]) -> Result<f64> {
    let text = scene_text(case);
    let refined = matches!(case.truth, Truth::Refined { .. });
    // the zone matters only to a refined truth
    let key = |r: &Row| refined.then_some(r.support_zone);
    let mut widest: Result<f64> = Ok(0.0);
    let mut done: Vec<Option<f64>> = Vec::new();
    for i in 0..rows.len() {
        let k = key(&rows[i]);
        if done.contains(&k) {
            continue;
        }
        done.push(k);
        let set = truth_set(&overrides(case, rows[i].start), rows[i].support_zone);
        let sc = resolve_scene(&text, &set)?;
        let d = truth::truth_spread(case.truth, case.quantity, &sc, &text, &set);
        if let Ok(d) = d {
            for r in rows.iter_mut().filter(|r| key(r) == k) {
                r.truth_spread = Some(d);
            }
        }
        widest = match (widest, d) {
            (Ok(a), Ok(b)) => Ok(a.max(b)),
            (Err(e), _) | (_, Err(e)) => Err(e),
        };
    }
    widest
}

/// The report: what `cargo xtask uncertainty` runs.
pub fn main() {
    let args: Vec<String> = std::env::args().skip(2).collect();
    if args.first().is_some_and(|a| a == "replay") {
        match args.as_slice() {
            [_, file] => replay::main(file, None),
            [_, file, flag, out] if flag == "--pairs" => replay::main(file, Some(out)),
            _ => panic!("usage: cargo xtask uncertainty replay FILE [--pairs OUT]"),
        }
        return;
    }
    if args.first().is_some_and(|a| a == "heldout") {
        heldout::main(args.get(1).map(String::as_str));
        return;
    }
    let quick = args.iter().any(|a| a == "quick");
    // `--dump FILE`: every pair's family values and truth, one JSON line
    // each, for `cargo xtask uncertainty replay FILE`
    let dump = args
        .iter()
        .position(|a| a == "--dump")
        .map(|i| args.get(i + 1).expect("--dump FILE").clone());
    // any other argument keeps the cases whose name contains it
    let only: Vec<String> = args
        .iter()
        .enumerate()
        .filter(|&(i, a)| a != "quick" && a != "--dump" && (i == 0 || args[i - 1] != "--dump"))
        .map(|(_, a)| a.clone())
        .collect();
    let mut all = Vec::new();
    let mut rm: Option<(&str, RidingMassHistory)> = None;
    let keep = |c: &Case| only.is_empty() || only.iter().any(|o| c.name.contains(o.as_str()));
    for case in cases(quick).into_iter().filter(keep) {
        let clock = Instant::now();
        if case.truth == Truth::RidingMass && rm.as_ref().is_none_or(|(s, _)| *s != case.scene) {
            let h = riding_mass_of(&case).unwrap_or_else(|e| panic!("{}: {e}", case.name));
            rm = h.map(|h| (case.scene, h));
        }
        let reference = rm
            .as_ref()
            .filter(|(s, _)| *s == case.scene)
            .map(|(_, h)| h);
        let mut rows = run_case(&case, DEFAULT_LEVELS, reference)
            .unwrap_or_else(|e| panic!("{}: {e}", case.name));
        let spread = set_truth_spreads(&case, &mut rows);
        eprintln!(
            "{} ({}): {} pairs in {:.1} s wall",
            case.name,
            case.quantity,
            rows.len(),
            clock.elapsed().as_secs_f64()
        );
        print!("{}", table(&case, &rows));
        match spread {
            Ok(0.0) => println!("the truth is exact"),
            Ok(d) => println!(
                "the truth's own accuracy: it moves by {d:.2e} when made at half its resolution (J/2{})",
                if matches!(case.truth, Truth::Refined { .. }) {
                    ", 2Δt"
                } else {
                    ""
                }
            ),
            Err(e) => println!("the truth's own accuracy: not measured ({e})"),
        }
        all.extend(rows);
    }
    print!("{}", summary(&all));
    if let Some(path) = dump {
        replay::write(&path, &all).unwrap_or_else(|e| panic!("{path}: {e}"));
        eprintln!("wrote {path}");
    }
}

/// One case's markdown table.
pub fn table(case: &Case, rows: &[Row]) -> String {
    let sym = if case.set.iter().any(|x| x.contains("galerkin")) {
        "J"
    } else {
        "N"
    };
    let mut s = format!(
        "\n**{}**, `{}` (`{}`{}{}); truth: {}\n\n",
        case.name,
        case.quantity,
        case.scene,
        if case.set.is_empty() { "" } else { " " },
        case.set
            .iter()
            .map(|x| format!("--set '{x}'"))
            .collect::<Vec<_>>()
            .join(" "),
        match case.truth {
            Truth::Series => "the exact series".to_string(),
            Truth::RidingMass => format!(
                "the riding-mass Galerkin solution, J = {}",
                cases::RIDING_MASS_MODES
            ),
            Truth::Refined { modes, dt } =>
                format!("`modal_exact` on the exact modes, J = {modes}, Δt = {dt:e} s"),
        }
    );
    s.push_str(&table_rows_with(sym, rows));
    s
}

/// A table's rows and its share line (`N` for the level symbol).
pub fn table_rows(rows: &[Row]) -> String {
    table_rows_with("N", rows)
}

/// A table's rows and its share line, with level symbol `sym`.
fn table_rows_with(sym: &str, rows: &[Row]) -> String {
    let mut s = format!(
        "| {sym}₀ | Δt₀ (s) | finest {sym} | finest Δt (s) | value | u_num | F_s | estimator | data | p | true error | u_num / error | covered |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {:e} | {} | {:e} | {:.6e} | {:.2e} | {:.2} | {} | {} | {} | {:.2e} | {:.2} | {} |\n",
            r.start.0,
            r.start.1,
            r.finest.0,
            r.finest.1,
            r.value,
            r.u_num,
            r.safety_factor,
            r.estimator,
            r.behaviour,
            if r.order.is_finite() { format!("{:.2}", r.order) } else { "—".into() },
            r.error(),
            r.sharpness(),
            if r.covered() { "yes" } else { "**no**" }
        ));
        if !r.resolved() {
            // the ratio measures the truth as much as the family
            s.truncate(s.len() - "|\n".len());
            s.push_str("(error below the truth's own accuracy) |\n");
        }
    }
    let (c, sh) = shares(rows);
    let (rsh, rn) = resolved_sharpness(rows);
    s.push_str(&format!(
        "\ncovered {:.0} % of {} pairs; u_num ≤ {SHARPNESS_LIMIT}× the error at {:.0} % ({:.0} % of the {rn} whose error the truth resolves)\n",
        100.0 * c,
        rows.len(),
        100.0 * sh,
        100.0 * rsh
    ));
    s
}

/// The summary over every case: smooth references and P_l apart.
pub fn summary(all: &[Row]) -> String {
    let (pl, smooth): (Vec<Row>, Vec<Row>) = all
        .iter()
        .cloned()
        .partition(|r| r.quantity == "loss_fraction_span");
    let line = |name: &str, rows: &[Row]| {
        let (c, sh) = shares(rows);
        let (rsh, rn) = resolved_sharpness(rows);
        format!(
            "| {name} | {} | {:.0} % | {:.0} % | {:.0} % of {rn} |\n",
            rows.len(),
            100.0 * c,
            100.0 * sh,
            100.0 * rsh
        )
    };
    let mut s = format!(
        "\n| pairs | count | covered (target ≥ {:.0} %) | u_num ≤ {SHARPNESS_LIMIT}× error (target ≥ {:.0} %) | the same where the truth resolves the error |\n|---|---|---|---|---|\n",
        100.0 * COVERAGE_TARGET,
        100.0 * SHARPNESS_TARGET
    );
    s.push_str(&line(
        "exact references (series, riding mass, refined modal)",
        &smooth,
    ));
    s.push_str(&line("P_l in the span against a refined run", &pl));
    s.push_str(&line("all", all));
    s
}
