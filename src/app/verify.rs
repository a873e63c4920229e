//! `taut verify`: the verification matrix, each observed order beside the
//! expected one (verify.csv, verify.json, verify.md).

use std::path::PathBuf;
use std::time::Instant;

use crate::error::{Error, Result};
use crate::study::verify::{GOLDEN_FILE, Selection, VerifyRow, any_failed, cases::CASES};

use super::{Frontend, Writing, kept};
use crate::report::Outputs;

/// A run of the verification matrix.
pub struct VerifyRequest {
    /// Methods, discretizations and formulations to run, and whether the
    /// cut-down matrix.
    pub selection: Selection<'static>,
    /// Worker threads (none: one per core).
    pub threads: Option<usize>,
    /// Output folder.
    pub out: PathBuf,
    /// Accept the rows that ran as the golden errors: rewrite the
    /// repository's `golden/verify/quick_errors.json` (their constants
    /// replaced, the others kept) instead of failing rows on them.
    pub update_golden: bool,
}

/// What the matrix gives.
pub struct VerifyOutcome {
    /// One row a combination.
    pub rows: Vec<VerifyRow>,
    /// Wall time, s.
    pub wall_seconds: f64,
    /// Worker threads the runs had.
    pub threads: usize,
    /// Whether every row passed (or is known, cannot, reported).
    pub passed: bool,
    /// What the golden error check did (rows failed, rows without a
    /// constant; with `update_golden`, the diff of the file written).
    pub golden: crate::study::verify::GoldenOutcome,
}

/// Run the matrix and write its tables. The output folder is claimed (and
/// so known writable) before any combination runs; a matrix that stops
/// leaves its earlier outputs as they were.
pub fn verify(req: &VerifyRequest, fe: &dyn Frontend) -> Result<VerifyOutcome> {
    verify_in(req, fe).map_err(|e| kept(Some(&req.out), Outputs::Verify, e, fe))
}

/// [`verify`] but for the note of a matrix that stopped.
fn verify_in(req: &VerifyRequest, fe: &dyn Frontend) -> Result<VerifyOutcome> {
    let start = Instant::now();
    crate::report::check_out_dir(&req.out)?;
    if let Some(n) = req.threads {
        crate::study::threads::check_threads(n)?;
    }
    let writing = Writing::open(&req.out, Outputs::Verify, "taut verify")?;
    let (rows, threads) = crate::study::threads::in_pool(req.threads, || {
        let rows = crate::study::verify::verify_golden(
            &CASES,
            &req.selection,
            req.update_golden,
            &|d, t| fe.progress(d, t),
        );
        (rows, rayon::current_num_threads())
    })?;
    let (rows, golden) = rows?;
    if let Some(text) = &golden.updated {
        write_golden(text)?;
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    crate::report::write_verify(writing.stage(), &rows, wall_seconds)?;
    writing.finish(fe)?;
    Ok(VerifyOutcome {
        passed: !any_failed(&rows),
        rows,
        wall_seconds,
        threads,
        golden,
    })
}

/// Write the golden errors to the repository's file: the source tree this
/// binary was built from (a binary built elsewhere has none to update).
fn write_golden(text: &str) -> Result<()> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(GOLDEN_FILE);
    if !path.parent().is_some_and(|d| d.is_dir()) {
        return Err(Error::invalid(
            "--update-golden",
            path.display(),
            "needs the source tree taut was built from (its golden/verify/ folder is not there)",
        ));
    }
    std::fs::write(&path, text).map_err(|e| Error::io(&path, e))
}
