//! The application layer: one function a command, shared by both front
//! ends. `taut::app::compare(&request, &frontend)` is what `taut compare`
//! and Python's `taut.compare` both call: it clears the output folder of an
//! earlier call, reads the scene, checks the study's cost, runs the study,
//! writes its outputs through [`crate::report`] and returns the outcome
//! (what the CLI prints, what Python hands back).
//!
//! A request holds typed values (`&'static dyn MethodFactory`,
//! [`Formulation`](crate::scene::Formulation), [`SpaceChoice`](crate::study::space::SpaceChoice),
//! [`Axis`](crate::study::sweep::Axis), counts); the words of a front end
//! (`--methods newmark,bathe`, `methods="newmark,bathe"`) become those values
//! at the edge, in [`words`], once for both.
//!
//! What differs between the front ends comes in through a [`Frontend`]:
//! where progress goes, and what becomes of a [`Note`] (the CLI prints each
//! on stderr; Python prints the cleared-outputs note and keeps the saved
//! contact problem's path for its exception).

pub mod args;
pub mod compare;
pub mod converge;
pub mod gate;
pub mod line;
pub mod merge;
pub mod modes;
pub mod precision;
pub mod replay;
pub mod report;
pub mod run;
pub mod scene;
pub mod simulation;
pub mod sweep;
pub mod uncertainty;
pub mod verify;
pub mod words;

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::report::Outputs;
use crate::study::cost::Estimate;

pub use args::{
    CompareArgs, ConvergeArgs, GateArgs, ModesArgs, PrecisionArgs, ReplayArgs, RunArgs, SweepArgs,
    UncertaintyArgs, VerifyArgs, Word,
};
pub use compare::{CompareRequest, compare};
pub use converge::{ConvergeRequest, converge};
pub use gate::{GateOutcome, GateRequest, gate};
pub use merge::{MergeOutcome, merge};
pub use modes::{ModesRequest, mesh_nodes, modes};
pub use precision::{PrecisionRequest, precision};
pub use replay::{Replay, ReplayRequest, Solved, replay};
pub use report::{ReportRequest, report};
pub use run::{RunOutcome, RunRequest, Tolerance, run};
pub use scene::scene_tree;
pub use simulation::{CarrierState, ProbeState, Simulation, SimulationState};
pub use sweep::{SweepOutcome, SweepRequest, sweep};
pub use uncertainty::{UncertaintyRequest, uncertainty};
pub use verify::{VerifyOutcome, VerifyRequest, verify};

/// Where a scene comes from: a file (read by the command, after the output
/// folder is cleared, so that a parse error names it) or TOML text.
#[derive(Debug, Clone)]
pub enum SceneSource {
    /// A scene file.
    File(PathBuf),
    /// The scene's TOML text.
    Text(String),
}

impl SceneSource {
    /// The scene's text.
    pub fn read(&self) -> Result<String> {
        match self {
            SceneSource::File(p) => crate::scene::read_scene(p),
            // a text is held to a file's cap (Python's scenes as text or
            // dicts had none, issue 41); its table files are relative to
            // the working directory
            SceneSource::Text(t) if t.len() as u64 > crate::input::MAX_INPUT_BYTES => {
                Err(Error::invalid(
                    "scene",
                    format!("a text of {} MiB", t.len() >> 20),
                    format!(
                        "a scene is at most {} MiB, as a scene file is (input::MAX_INPUT_BYTES): give long series as table files",
                        crate::input::MAX_INPUT_BYTES >> 20
                    ),
                ))
            }
            SceneSource::Text(t) => crate::scene::with_table_files(t.clone(), Path::new(".")),
        }
    }

    /// The file, if there is one.
    pub fn path(&self) -> Option<&Path> {
        match self {
            SceneSource::File(p) => Some(p),
            SceneSource::Text(_) => None,
        }
    }

    /// Name the scene file, if there is one, in a parse error of its text.
    pub fn name(&self, e: Error) -> Error {
        match self.path() {
            Some(p) => crate::scene::in_file(e, p),
            None => e,
        }
    }
}

/// Something a command says on the way, beside its outcome.
#[derive(Debug)]
pub enum Note<'a> {
    /// Outputs of an earlier command were removed from the output folder
    /// (the text of `crate::report::cleared_note`).
    Cleared(String),
    /// The study's estimated cost is above the bound, and `yes` was given.
    AboveBound(&'a Estimate),
    /// A contact solve failed and its problem was saved here, for `taut replay`.
    FailureSaved(&'a Path),
}

/// What a front end does with a command's progress and notes.
pub trait Frontend: Sync {
    /// `done` of `total` (runs, steps, cases or combinations) finished.
    fn progress(&self, done: usize, total: usize);
    /// A note (see [`Note`]).
    fn note(&self, note: Note<'_>);
}

/// A front end that shows nothing (tests, programs that link taut).
pub struct Silent;

impl Frontend for Silent {
    fn progress(&self, _: usize, _: usize) {}
    fn note(&self, _: Note<'_>) {}
}

/// Remove the outputs an earlier command of this kind left in `dir`, with a
/// note: a folder holds one run's outputs ([`crate::report::clear_earlier`]).
fn fresh(dir: &Path, kind: Outputs, fe: &dyn Frontend) -> Result<()> {
    let removed = crate::report::clear_earlier(dir, kind)?;
    if let Some(note) = crate::report::cleared_note(dir, &removed) {
        fe.note(Note::Cleared(note));
    }
    Ok(())
}

/// Refuse a study above the cost bound unless `yes` ([`crate::study::cost`]);
/// with `yes`, a note of what is being started.
fn started(estimate: &Estimate, yes: bool, fe: &dyn Frontend) -> Result<()> {
    estimate.check(yes)?;
    if estimate.over() {
        fe.note(Note::AboveBound(estimate));
    }
    Ok(())
}

/// Save a failing contact problem next to the outputs so it can be
/// replayed, with a note.
fn save_failure(dir: Option<&Path>, e: Error, fe: &dyn Frontend) -> Error {
    if let Some(path) = dir.and_then(|d| crate::report::save_failed_contact(d, &e)) {
        fe.note(Note::FailureSaved(&path));
    }
    e
}

/// A study of one scene as a front end asks for it (`compare`, `converge`,
/// `precision`).
pub struct StudyRequest<S> {
    /// The scene.
    pub scene: SceneSource,
    /// Scene overrides, `key.path=value` (`--set`).
    pub set: Vec<String>,
    /// What to study (typed: methods, formulations, discretizations, grid).
    pub study: S,
    /// Output folder (none: nothing written).
    pub out: Option<PathBuf>,
}

/// What the application layer needs of a study of one scene.
pub trait Study {
    /// What the study gives.
    type Outcome;
    /// The files it writes (cleared first when left by an earlier call).
    const OUTPUTS: Outputs;
    /// Start even above the cost bound.
    fn yes(&self) -> bool;
    /// Its estimated cost on scene `text` with `set`.
    fn estimate(&self, text: &str, set: &[String]) -> Result<Estimate>;
    /// Run it (the cost is checked again).
    fn run(
        &self,
        text: &str,
        set: &[String],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Self::Outcome>;
    /// Write its outputs into `dir`.
    fn write(dir: &Path, outcome: &Self::Outcome) -> Result<()>;
}

/// The course of every study of one scene: clear the folder of an earlier
/// call, read the scene, check the cost, run (a parse error naming the
/// scene file, a failed contact problem saved for `taut replay`), write.
fn run_study<S: Study>(req: &StudyRequest<S>, fe: &dyn Frontend) -> Result<S::Outcome> {
    let dir = req.out.as_deref();
    if let Some(d) = dir {
        fresh(d, S::OUTPUTS, fe)?;
    }
    let text = req.scene.read()?;
    let estimate = req
        .study
        .estimate(&text, &req.set)
        .map_err(|e| req.scene.name(e))?;
    started(&estimate, req.study.yes(), fe)?;
    let outcome = req
        .study
        .run(&text, &req.set, &mut |d, t| fe.progress(d, t))
        .map_err(|e| req.scene.name(e))
        .map_err(|e| save_failure(dir, e, fe))?;
    if let Some(d) = dir {
        crate::report::write_whole(d, "taut study", || S::write(d, &outcome))?;
    }
    Ok(outcome)
}
