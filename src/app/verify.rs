//! `taut verify`: the verification matrix, each observed order beside the
//! expected one (verify.csv, verify.json, verify.md).

use std::path::PathBuf;
use std::time::Instant;

use crate::error::Result;
use crate::study::verify::{Selection, VerifyRow, any_failed, cases::CASES};

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
        let rows = crate::study::verify::verify(&CASES, &req.selection, &|d, t| fe.progress(d, t));
        (rows, rayon::current_num_threads())
    })?;
    let rows = rows?;
    let wall_seconds = start.elapsed().as_secs_f64();
    crate::report::write_verify(writing.stage(), &rows, wall_seconds)?;
    writing.finish(fe)?;
    Ok(VerifyOutcome {
        passed: !any_failed(&rows),
        rows,
        wall_seconds,
        threads,
    })
}
