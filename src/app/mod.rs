//! The application layer: one function a command, shared by both front
//! ends. `taut::app::compare(&request, &frontend)` is what `taut compare`
//! and Python's `taut.compare` both call: it reads and checks the scene and
//! the study's cost, claims the output folder, runs the study, writes its
//! outputs through [`crate::report`] beside the folder's earlier ones and
//! puts them in place, and returns the outcome (what the CLI prints, what
//! Python hands back). A command that stops leaves the folder as it was.
//!
//! A request holds typed values (`&'static dyn MethodFactory`,
//! [`Formulation`](crate::scene::Formulation), [`SpaceChoice`](crate::study::space::SpaceChoice),
//! [`Axis`](crate::study::sweep::Axis), counts); the words of a front end
//! (`--methods newmark,bathe`, `methods="newmark,bathe"`) become those values
//! at the edge, in [`words`], once for both.
//!
//! What differs between the front ends comes in through a [`Frontend`]:
//! where progress goes, and what becomes of a [`Note`] (the CLI prints each
//! on stderr; Python prints the notes on the output folder and keeps the
//! saved contact problem's path for its exception).

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
    CompareArgs, ConvergeArgs, CostBound, FormulationList, GateArgs, ModesArgs, PrecisionArgs,
    ReplayArgs, RunArgs, Runs, SweepArgs, UncertaintyArgs, VerifyArgs, Word, Workers,
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

/// Where a scene comes from: a file (read by the command, so that a parse
/// error names it) or TOML text.
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
            // dicts had none); its table files are relative to
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
    /// A command's new outputs replaced those of an earlier command in
    /// the output folder (the text of `crate::report::replaced_note`).
    Replaced(String),
    /// A command that stopped (refused, failed, interrupted) left the
    /// earlier outputs of its output folder as they were (the text of
    /// `crate::report::kept_note`).
    Kept(String),
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

/// An output folder held for one command: claimed against every other
/// writer ([`crate::report::claim_folder`]), with a staging folder its new
/// outputs are written into and put in place from when the command has
/// succeeded ([`crate::report::Staged`]). Dropped unfinished, the folder is
/// as it was: the staging folder removed, the claim given back, and a
/// folder the claim created removed again if it is empty.
struct Writing {
    // dropped first: the staging folder is removed while the claim holds
    staged: Option<crate::report::Staged>,
    lock: Option<crate::report::FolderLock>,
    /// The folder, when the claim created it.
    created: Option<PathBuf>,
}

impl Writing {
    /// Claim `dir` for `what` (`taut run`) writing outputs of `kind`, and
    /// open its staging folder: a folder that another command holds, or
    /// that cannot be written, is refused here, before any work.
    fn open(dir: &Path, kind: Outputs, what: &str) -> Result<Writing> {
        let created = (!dir.exists()).then(|| dir.to_path_buf());
        let mut w = Writing {
            staged: None,
            lock: None,
            created,
        };
        let lock = w.lock.insert(crate::report::claim_folder(dir, what)?);
        w.staged = Some(crate::report::Staged::open(lock, kind, what)?);
        Ok(w)
    }

    /// [`Writing::open`] for an optional folder.
    fn open_some(dir: Option<&Path>, kind: Outputs, what: &str) -> Result<Option<Writing>> {
        dir.map(|d| Writing::open(d, kind, what)).transpose()
    }

    /// Where the command writes its outputs.
    fn stage(&self) -> &Path {
        self.staged.as_ref().expect("open until finished").path()
    }

    /// Put the outputs in place, with a note of the earlier ones replaced.
    /// A stop requested meanwhile ([`crate::interrupt`]) stops here too: a
    /// command whose work took no step to notice it (`modes`) leaves the
    /// folder as it was, as one stopped mid-run does.
    fn finish(mut self, fe: &dyn Frontend) -> Result<()> {
        if crate::interrupt::requested() {
            return Err(Error::Interrupted);
        }
        self.created = None;
        let staged = self.staged.take().expect("open until finished");
        let dir = staged.dir().to_path_buf();
        let removed = staged.commit()?;
        if let Some(note) = crate::report::replaced_note(&dir, &removed) {
            fe.note(Note::Replaced(note));
        }
        Ok(())
    }
}

impl Drop for Writing {
    fn drop(&mut self) {
        drop(self.staged.take());
        drop(self.lock.take());
        if let Some(dir) = &self.created {
            // only if empty: a saved failing contact problem stays
            let _ = std::fs::remove_dir(dir);
        }
    }
}

/// A command's error, after a note that the earlier outputs of its output
/// folder `dir`, if any, are as they were (`crate::report::kept_note`).
fn kept(dir: Option<&Path>, kind: Outputs, e: Error, fe: &dyn Frontend) -> Error {
    if let Some(note) = dir.and_then(|d| crate::report::kept_note(d, kind)) {
        fe.note(Note::Kept(note));
    }
    e
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
    /// The files it writes (replacing those an earlier call left).
    const OUTPUTS: Outputs;
    /// The command, as the folder's lock and marker name it (`taut compare`).
    const COMMAND: &'static str;
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
    /// The failure of an outcome that estimated nothing (every run of the
    /// study stopped): the command then fails, its folder untouched.
    fn nothing(_outcome: &mut Self::Outcome) -> Option<Error> {
        None
    }
    /// The failure of an outcome that is only part of what was asked for
    /// (a comparison some of whose runs stopped), when it would be written
    /// to a folder: its tables would replace whole ones, so the command
    /// fails and the folder keeps its earlier outputs. Without a folder the
    /// partial outcome is returned (its `failed` says what is missing).
    fn partial(_outcome: &Self::Outcome, _dir: &Path) -> Option<Error> {
        None
    }
    /// Write its outputs into `dir`.
    fn write(dir: &Path, outcome: &Self::Outcome) -> Result<()>;
}

/// The course of every study of one scene: read the scene, check it and
/// the cost, claim the output folder (refused before any run when another
/// command holds it or it cannot be written), run (a parse error naming
/// the scene file, a failed contact problem saved for `taut replay`),
/// write into the staging folder, and put the outputs in place. A study
/// that stops leaves the folder's earlier outputs as they were, and says so.
fn run_study<S: Study>(req: &StudyRequest<S>, fe: &dyn Frontend) -> Result<S::Outcome> {
    let dir = req.out.as_deref();
    study_in(req, fe).map_err(|e| kept(dir, S::OUTPUTS, e, fe))
}

/// [`run_study`] but for the note of a study that stopped.
fn study_in<S: Study>(req: &StudyRequest<S>, fe: &dyn Frontend) -> Result<S::Outcome> {
    let dir = req.out.as_deref();
    if let Some(d) = dir {
        crate::report::check_out_dir(d)?;
    }
    let text = req.scene.read()?;
    let estimate = req
        .study
        .estimate(&text, &req.set)
        .map_err(|e| req.scene.name(e))?;
    started(&estimate, req.study.yes(), fe)?;
    let writing = Writing::open_some(dir, S::OUTPUTS, S::COMMAND)?;
    let mut outcome = req
        .study
        .run(&text, &req.set, &mut |d, t| fe.progress(d, t))
        .map_err(|e| req.scene.name(e))
        .map_err(|e| save_failure(dir, e, fe))?;
    if let Some(e) = S::nothing(&mut outcome) {
        return Err(e);
    }
    if let (Some(w), Some(d)) = (writing, dir) {
        if let Some(e) = S::partial(&outcome, d) {
            return Err(e);
        }
        S::write(w.stage(), &outcome)?;
        w.finish(fe)?;
    }
    Ok(outcome)
}

/// A study of one scene offered as a command: what the front ends need of
/// it beyond [`Study`], declared with the study, so that the `taut`
/// subcommand (its options, default folder, progress and printed text)
/// and the Python function (`taut.study(name, …)`) are made from
/// [`each_study`] and a new study edits neither front end.
#[cfg(feature = "clap")]
pub trait StudyCommand: Study + Send + Sync + Sized
where
    Self::Outcome: Send,
{
    /// Its options, which make it ([`args::CommandArgs::typed`]); their
    /// `COMMAND` is the subcommand's name (`taut compare`).
    type Args: args::CommandArgs<Typed = Self>;
    /// The subcommand's help line (`taut --help`, `taut compare --help`).
    const ABOUT: &'static str;
    /// The default output folder's suffix: out/<scene stem><suffix>.
    const SUFFIX: &'static str;
    /// What the progress bar counts.
    const UNIT: &'static str = "runs";
    /// What the terminal prints of an outcome: the kind of study (after
    /// `taut <version> — `) and its table.
    fn terminal(&self, outcome: &Self::Outcome) -> (String, String);
    /// Whether the outcome is whole (the exit code is 1 when not: a run
    /// stopped, its table written for the others).
    fn whole(_outcome: &Self::Outcome) -> bool {
        true
    }
    /// Its tables by name (the file each is written as), as Python's
    /// `taut.study` hands them back.
    fn tables(outcome: &Self::Outcome) -> Vec<(&'static str, crate::report::Table)>;
    /// Run it and write its outputs (the course of every study of one
    /// scene: scene read, cost checked, folder claimed, outputs put in
    /// place).
    fn command(req: &StudyRequest<Self>, fe: &dyn Frontend) -> Result<Self::Outcome> {
        run_study(req, fe)
    }
}

/// What a front end does with each study of [`each_study`]: add it as a
/// subcommand, run the one asked for, register its function.
#[cfg(feature = "clap")]
pub trait StudyVisitor {
    /// One study command.
    fn visit<S: StudyCommand>(&mut self)
    where
        S::Outcome: Send;
}

/// The studies of one scene offered as commands, the one list both front
/// ends are made from (in the order `taut --help` lists them): a new study
/// command is one line here and its [`StudyCommand`].
#[cfg(feature = "clap")]
pub fn each_study(v: &mut impl StudyVisitor) {
    use crate::study::request::{CompareStudy, ConvergeStudy, PrecisionStudy, UncertaintyStudy};
    v.visit::<ConvergeStudy>();
    v.visit::<UncertaintyStudy>();
    v.visit::<PrecisionStudy>();
    v.visit::<CompareStudy>();
}
