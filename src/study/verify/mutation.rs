//! The harness tested against known defects: each deliberate
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
use super::golden::{self, key};
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

/// One line of the mutation table: the rows failing that do not fail in
/// `clean` (the defect's own), and the first few of them.
fn summary(rows: &[VerifyRow], clean: &[VerifyRow]) -> (usize, String) {
    let clean_failed: std::collections::HashSet<String> = clean
        .iter()
        .filter(|r| r.status == Status::Fail)
        .map(key)
        .collect();
    let failed: Vec<String> = rows
        .iter()
        .filter(|r| r.status == Status::Fail)
        .map(key)
        .filter(|k| !clean_failed.contains(k))
        .collect();
    (
        failed.len(),
        failed
            .iter()
            .take(3)
            .cloned()
            .collect::<Vec<_>>()
            .join("; "),
    )
}

/// Every defect makes `taut verify --quick` fail at least one row that
/// does not fail without it (the golden errors ([`golden`]) are part of its
/// judge: a pass row above its constant fails), and the matrix without one
/// fails none (so each failure is the defect's). The clean matrix's failures, if any, are
/// printed first and fail the test at its end, after every defect is
/// measured against them.
///
/// `TAUT_DEFECTS=HermiteMass,BatheC1` runs those defects only (the clean
/// matrix still first); `TAUT_VERIFY_DUMP=dir` writes each matrix's
/// `verify.csv` under `dir/<defect or clean>/`.
// (this whole file is the test build's: the attribute below says so to
// tests/layers.rs, which reads a file's imports up to it, so that the
// dump's use of the report layer above is a test's)
#[cfg(test)]
#[test]
#[ignore = "the quick matrix thirteen times: about an hour in release (cargo test --release --lib study::verify::mutation -- --ignored --nocapture)"]
fn the_quick_matrix_flags_every_deliberate_defect() {
    let dump = |name: &str, rows: &[VerifyRow]| {
        if let Ok(dir) = std::env::var("TAUT_VERIFY_DUMP") {
            let dir = std::path::Path::new(&dir).join(name);
            std::fs::create_dir_all(&dir).expect("the dump directory");
            crate::report::write_verify(&dir, rows, 0.0).expect("verify.csv");
        }
    };
    let defects: Vec<Defect> = match std::env::var("TAUT_DEFECTS") {
        Ok(list) => list
            .split(',')
            .map(|n| Defect::named(n.trim()).unwrap_or_else(|| panic!("no defect {n}")))
            .collect(),
        Err(_) => Defect::ALL.to_vec(),
    };
    let clean = quick_matrix_with(None);
    dump("clean", &clean);
    let clean_failed: Vec<String> = clean
        .iter()
        .filter(|r| r.status == Status::Fail)
        .map(|r| format!("{}: {}", key(r), r.note))
        .collect();
    println!(
        "no defect: {} rows, {} fail",
        clean.len(),
        clean_failed.len()
    );
    for f in &clean_failed {
        println!("  clean FAIL {f}");
    }
    let mut missed = Vec::new();
    println!(
        "| defect | rows failed that do not fail without it (of {}) | of them, above {}× their golden error alone | e.g. |",
        clean.len(),
        golden::GOLDEN_FACTOR
    );
    println!("|---|---|---|---|");
    for d in defects {
        let rows = quick_matrix_with(Some(d));
        dump(&format!("{d:?}"), &rows);
        let (n, first) = summary(&rows, &clean);
        let by_golden = rows
            .iter()
            .filter(|r| r.status == Status::Fail && r.note.starts_with("above its golden error"))
            .count();
        println!("| {d:?} | {n} | {by_golden} | {first} |");
        if n == 0 {
            missed.push(d);
        }
    }
    assert!(missed.is_empty(), "not flagged: {missed:?}");
    assert!(
        clean_failed.is_empty(),
        "the quick matrix fails without a defect: {clean_failed:#?}"
    );
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
