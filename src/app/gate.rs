//! `taut gate`: a golden suite run again, each quantity compared with its
//! reference (gate.json, junit.xml).

use std::path::PathBuf;

use crate::error::Result;
use crate::report::Outputs;
use crate::study::gate::{GateReport, gate_batched};

use super::{Frontend, Writing, kept};

/// A gate over a suite of golden cases.
#[derive(Debug, Clone)]
pub struct GateRequest {
    /// The suite's folder of case files (`*.json`).
    pub suite: PathBuf,
    /// Output folder for gate.json and junit.xml.
    pub out: PathBuf,
    /// Accept this run's values as the new references.
    pub update: bool,
    /// Cases stepped together (lanes).
    pub batch: usize,
}

/// What a gate gives.
pub struct GateOutcome {
    /// Every check and every case that could not run.
    pub report: GateReport,
    /// Whether the gate passed (an update passes unless a case could not run).
    pub passed: bool,
}

/// Run the suite and write gate.json and junit.xml. The output folder is
/// claimed (and so known writable) before any case runs; a gate that stops
/// leaves its earlier outputs as they were.
pub fn gate(req: &GateRequest, fe: &dyn Frontend) -> Result<GateOutcome> {
    gate_in(req, fe).map_err(|e| kept(Some(&req.out), Outputs::Gate, e, fe))
}

/// [`gate`] but for the note of a gate that stopped.
fn gate_in(req: &GateRequest, fe: &dyn Frontend) -> Result<GateOutcome> {
    crate::report::check_out_dir(&req.out)?;
    let writing = Writing::open(&req.out, Outputs::Gate, "taut gate")?;
    let report = gate_batched(&req.suite, req.update, req.batch, &mut |d, t, _| {
        fe.progress(d, t)
    })?;
    crate::report::write_gate(writing.stage(), &report)?;
    writing.finish(fe)?;
    // an update accepts the new values: it passes unless a case could not run
    let passed = if req.update {
        report.errors.is_empty() && !report.checks.is_empty()
    } else {
        report.passed()
    };
    Ok(GateOutcome { report, passed })
}
