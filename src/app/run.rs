//! `taut run` / `taut.run`: one scene, or with a tolerance an
//! accuracy-targeted run (history.csv, summary.json, force.svg, and
//! accuracy.csv for a tolerance run).

use std::path::PathBuf;

use crate::error::Result;
use crate::report::{Outputs, Summary};
use crate::run::RunOutput;
use crate::study::sweep::SweepTolerance;
use crate::study::tolerance::{Accuracy, tolerance_run};

use super::{Frontend, SceneSource, Writing, kept, save_failure};

/// An error target: refine mesh and Δt until the u_num of the quantity is
/// within the tolerance, as a one-point `taut sweep --tolerance` does
/// (docs/accuracy.md).
pub type Tolerance = SweepTolerance;

/// One run of a scene.
#[derive(Debug, Clone)]
pub struct RunRequest {
    /// The scene.
    pub scene: SceneSource,
    /// Scene overrides, `key.path=value` (`--set`).
    pub set: Vec<String>,
    /// Output folder (none: nothing written).
    pub out: Option<PathBuf>,
    /// An error target (`--tolerance`, `--quantity`), or the scene's own
    /// mesh and Δt.
    pub tolerance: Option<Tolerance>,
}

/// What a run gives.
pub struct RunOutcome {
    /// `summary.json` (without the accuracy).
    pub summary: Summary,
    /// The run itself (histories, statistics, warnings).
    pub output: RunOutput,
    /// How mesh and Δt were chosen and the estimated errors (a tolerance run).
    pub accuracy: Option<Accuracy>,
}

/// Run the scene and write its outputs. The scene is read and checked
/// before the output folder is claimed; the outputs are written beside the
/// folder's earlier ones and put in place once the run has succeeded. A
/// run that is refused, fails or is interrupted leaves the folder's
/// earlier outputs as they were, and says so (a failed contact solve's
/// problem is saved there, for `taut replay`).
pub fn run(req: &RunRequest, fe: &dyn Frontend) -> Result<RunOutcome> {
    run_in(req, fe).map_err(|e| kept(req.out.as_deref(), Outputs::Run, e, fe))
}

/// [`run`] but for the note of a run that stopped.
fn run_in(req: &RunRequest, fe: &dyn Frontend) -> Result<RunOutcome> {
    let dir = req.out.as_deref();
    if let Some(d) = dir {
        crate::report::check_out_dir(d)?;
    }
    let text = req.scene.read()?;
    let progress = &mut |d, t| fe.progress(d, t);
    if let Some(tol) = &req.tolerance {
        crate::study::tolerance::check_start(&text, &req.set, tol)
            .map_err(|e| req.scene.name(e))?;
        let writing = Writing::open_some(dir, Outputs::Run, "taut run --tolerance")?;
        let r = tolerance_run(&text, &req.set, tol, progress)
            .map_err(|e| req.scene.name(e))
            .map_err(|e| save_failure(dir, e, fe))?;
        let summary = match writing {
            Some(w) => {
                let summary = crate::report::write_tolerant_run(w.stage(), &r)?;
                w.finish(fe)?;
                summary
            }
            None => Summary::new(&r.scene, &r.output),
        };
        return Ok(RunOutcome {
            summary,
            output: r.output,
            accuracy: Some(r.accuracy),
        });
    }
    let sc = crate::resolve::resolve_scene(&text, &req.set).map_err(|e| req.scene.name(e))?;
    let writing = Writing::open_some(dir, Outputs::Run, "taut run")?;
    let output = crate::run::run(&sc, progress).map_err(|e| save_failure(dir, e, fe))?;
    let summary = match writing {
        Some(w) => {
            let summary = crate::report::write_run(w.stage(), &sc, &output)?;
            w.finish(fe)?;
            summary
        }
        None => Summary::new(&sc, &output),
    };
    Ok(RunOutcome {
        summary,
        output,
        accuracy: None,
    })
}
