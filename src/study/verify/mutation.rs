//! The harness tested against known defects (issue 38): each deliberate
//! defect of the test build ([`crate::defects`]) switched on in turn, and
//! `taut verify --quick`'s matrix run under it; the harness must fail at
//! least one row for each. The table of what each defect fails is in
//! `docs/verification.md` ("The harness tested against known defects"):
//!
//! ```sh
//! cargo test --release --lib study::verify::mutation -- --ignored --nocapture
//! ```
//!
//! The defect is a thread-local flag set on the threads of a rayon pool of
//! the test's own (its `start_handler`), so the other tests of the binary,
//! running beside it on their own threads, never see it.

use super::cases::CASES;
use super::row::{Status, VerifyRow};
use super::{selection, verify};
use crate::defects::{self, Defect};

/// `taut verify --quick`'s matrix (every method, discretization and
/// formulation of the cut-down cases) with `defect` switched on, on a pool
/// of two threads.
pub(super) fn quick_matrix_with(defect: Option<Defect>) -> Vec<VerifyRow> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .start_handler(move |_| defects::set(defect))
        .build()
        .expect("a pool of two threads");
    let sel = selection(None, None, None, true).expect("the default selection");
    pool.install(|| verify(&CASES, &sel, &|_, _| {}))
        .expect("the matrix runs")
}

/// One line of the mutation table: the failing rows' count, and the
/// first few of them.
fn summary(rows: &[VerifyRow]) -> (usize, String) {
    let failed: Vec<&VerifyRow> = rows.iter().filter(|r| r.status == Status::Fail).collect();
    let first = failed
        .iter()
        .take(3)
        .map(|r| {
            format!(
                "{} {} {} {} {} {} {}",
                r.case,
                r.method,
                r.discretization,
                r.formulation,
                r.supports,
                r.variable,
                r.quantity
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    (failed.len(), first)
}

/// Every defect makes `taut verify --quick` fail at least one row, and the
/// matrix without one fails none (so each failure is the defect's).
#[test]
#[ignore = "the quick matrix seven times: minutes in release (cargo test --release --lib study::verify::mutation -- --ignored --nocapture)"]
fn the_quick_matrix_flags_every_deliberate_defect() {
    let clean = quick_matrix_with(None);
    let (n, first) = summary(&clean);
    println!("no defect: {} rows, {n} fail {first}", clean.len());
    assert_eq!(n, 0, "the quick matrix fails without a defect: {first}");
    let mut missed = Vec::new();
    println!("| defect | rows failed (of {}) | e.g. |", clean.len());
    println!("|---|---|---|");
    for d in Defect::ALL {
        let rows = quick_matrix_with(Some(d));
        let (n, first) = summary(&rows);
        println!("| {d:?} | {n} | {first} |");
        if n == 0 {
            missed.push(d);
        }
    }
    assert!(missed.is_empty(), "not flagged: {missed:?}");
}

/// The flag stays on the pool's threads: a defect switched on there is off
/// on the caller's thread, and off again in a pool without one.
#[test]
fn a_defect_stays_on_its_own_pool() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .start_handler(|_| defects::set(Some(Defect::HalfDashpot)))
        .build()
        .unwrap();
    assert!(pool.install(|| defects::on(Defect::HalfDashpot)));
    assert!(!defects::on(Defect::HalfDashpot));
    assert!(!pool.install(|| defects::on(Defect::StepGamma)));
}
