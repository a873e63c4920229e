//! `taut verify`: one harness that runs any method (a built-in one or a
//! [`MethodFactory`](crate::integrate::MethodFactory) of one's own), discretization, formulation and
//! support pair on the declared verification cases ([`cases`]) and reports
//! each observed order beside the expected one (MODEL §8, §11).
//!
//! A case is a scene that names its reference (`[manufactured]` or
//! `[reference]`), plus ladders that refine one variable — h, Δt or J —
//! with the others held fine, plus the order each combination should show
//! ([`case::Expect`]). For every ladder the harness
//!
//! 1. runs the levels and measures each level's error against the exact
//!    solution on the coarsest level's time grid (t > 0): the displacement
//!    (under the carrier, at the probes and of the mass) and the contact
//!    force at the time the method's multiplier acts ([`crate::RunOutput::force_lag`]);
//! 2. computes the orders between successive levels and the ladder's order
//!    (first to last level) with the one `observed_order`;
//! 3. **shows that the refined variable dominates**: the finest level run
//!    again with the fixed variables refined once more gives the share of
//!    the finest error they make; above `DOMINANCE_LIMIT` the row fails;
//! 4. passes when the ladder's order is within the expectation's tolerance.
//!
//! `known` rows (a measured deviation from the formal order, documented
//! with its measurement), `cannot` rows (why the combination shows no
//! order in this variable) and `reported` rows (a method that declares no
//! formal order) do not fail; `fail` rows do, and `taut verify` exits with
//! status 1.
//!
//! One job a file: `select`, `job`, `run_job`, `level`, `explicit` (a
//! ladder held below the stable step), `measure`, `judge` (a row's orders
//! and status), `row` (`verify.csv`); the cases are [`case`] and [`cases`].

pub mod case;
pub mod cases;
mod explicit;
mod golden;
mod job;
mod judge;
mod level;
mod measure;
#[cfg(test)]
mod mutation;
mod row;
mod run_job;
mod select;
pub(crate) mod tuned;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::scene::Formulation;
use crate::scene::Support;
use case::Case;
use job::Job;
use run_job::run_job;

pub use golden::{GOLDEN_FILE, GoldenOutcome};
pub use row::{Status, VerifyRow, any_failed};
pub use select::{Selection, selection};

/// Largest share of the finest error the fixed variables may make (step 3
/// of the module docs): at 0.25 the refined variable makes ≥ 75 % of it,
/// and the order it shows is off by at most log2(1/(1 − 0.25)) ≈ 0.4 in
/// the worst case of a share that does not fall with the ladder (at the
/// coarser levels, where errors are larger, its share is smaller still).
pub(crate) const DOMINANCE_LIMIT: f64 = 0.25;

/// How much stiffer the penalty of the compliance's share run is (a
/// penalty row's finest level rerun with κ × 16, `measure.rs`): a penalty
/// error ∝ 1/κ falls to 1/16 of itself, so the share it measures is 15/16
/// of the compliance's part.
pub(crate) const PENALTY_STIFFEN: f64 = 16.0;

/// The start window of a penalty row judged after the start
/// (`Expect::AfterStart`), s: an unloaded penalty's start jump rings for
/// tens of steps at its method's spectral radius per step (HHT α = 0.05:
/// 0.905, so 40 steps to fall below 2 %, 0.04 s at the coarsest Δt of the
/// matrix, 1e-3 s), a fifth of the cases' 0.25 s.
pub(crate) const START_WINDOW: f64 = 0.05;

/// The order below which a pair of a ladder declared to possibly diverge
/// (`Expect::MayDiverge`) counts as not converging: the error falls less
/// than √2 per halving there, or rises.
pub(crate) const STALL_ORDER: f64 = 0.5;

/// How far below its expected order a coarser pair of a ladder may fall
/// beyond the pair allowance and still count as approaching (`judge.rs`):
/// a pre-asymptotic pair a few tenths low is the start of a ladder, a pair
/// more than this low is a stall or a rise.
pub(crate) const APPROACH_SLACK: f64 = 0.5;

/// A finest error this small relative to the exact solution's largest
/// value is at the round-off floor (`judge.rs`): ≈ 10⁶ ε, what 10⁴–10⁵
/// steps of sums of unit-size terms leave (measured: the smallest errors
/// any ladder of the matrix reached stop falling there). Levels below it
/// are not held to an order.
pub(crate) const ROUND_OFF_FLOOR: f64 = 2e-10;

/// Run the matrix of `sel` over `cases` on the current rayon pool;
/// `progress(done, total)` after each combination. Rows in a fixed order
/// (case, supports, discretization, formulation, method, ladder, quantity),
/// whatever the thread count. Each `pass` row is then held to its golden
/// error (`golden`: fails above `GOLDEN_FACTOR` times the constant bundled
/// from `golden/verify/quick_errors.json`; a row with no constant is noted),
/// before the `diverges` rows look for their witnesses.
pub fn verify(
    cases: &[Case],
    sel: &Selection,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<VerifyRow>> {
    Ok(verify_golden(cases, sel, false, progress)?.0)
}

/// [`verify`], with what the golden check did; `update`: the rows that ran
/// become the golden constants instead (each judged against its new one,
/// so none fails on it), the new file text and the diff in the outcome
/// (the caller writes it to `golden/verify/quick_errors.json`).
pub fn verify_golden(
    cases: &[Case],
    sel: &Selection,
    update: bool,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Vec<VerifyRow>, GoldenOutcome)> {
    let mut out = run_matrix(cases, sel, progress)?;
    let before = golden::bundled()?;
    let outcome = if update {
        let (now, diff) = golden::update(&out, before);
        let mut o = golden::judge(&mut out, &now);
        o.diff = diff;
        o.updated = Some(golden::text(&now));
        o
    } else {
        golden::judge(&mut out, before)
    };
    judge::witness_divergences(&mut out);
    Ok((out, outcome))
}

/// The matrix's rows, each judged on its own ladder.
fn run_matrix(
    cases: &[Case],
    sel: &Selection,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<VerifyRow>> {
    let mut jobs = Vec::new();
    for case in cases.iter().filter(|c| !sel.quick || c.quick) {
        let supports: Vec<Option<(Support, Support)>> = if case.supports.is_empty() {
            vec![None]
        } else if sel.quick {
            case.supports.iter().take(2).copied().map(Some).collect()
        } else {
            case.supports.iter().copied().map(Some).collect()
        };
        for &s in &supports {
            for &space in case.spaces.iter().filter(|s| sel.spaces.contains(s)) {
                let forms: Vec<Option<Formulation>> = if case.contact {
                    sel.formulations.iter().copied().map(Some).collect()
                } else {
                    vec![None]
                };
                for &f in &forms {
                    for &m in sel.methods.iter().filter(|m| case.runs(&m.name())) {
                        jobs.push(Job {
                            case,
                            factory: m,
                            space,
                            formulation: f,
                            supports: s,
                        });
                    }
                }
            }
        }
    }
    let total = jobs.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Result<Vec<VerifyRow>>> = jobs
        .par_iter()
        // one job a task: jobs differ in cost, and a leaf of several jobs
        // is stepped by one thread alone (see study::sweep)
        .with_max_len(1)
        .map(|j| {
            if crate::interrupt::requested() {
                return Err(Error::Interrupted);
            }
            let r = run_job(j);
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, total);
            r
        })
        .collect();
    let mut out = Vec::new();
    for r in rows {
        out.extend(r?);
    }
    Ok(out)
}
