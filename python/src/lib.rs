//! `taut._taut`: the native half of the `taut` Python package.
//!
//! A thin layer over the Rust library: every function here computes nothing
//! of its own. It reads the caller's options as the library declares them
//! (`taut::app::args`: the struct the CLI's subcommand takes, here from the
//! keyword arguments as JSON), makes the typed request, calls the same
//! `taut::app` function the CLI calls, and hands back the same tables the
//! CLI writes as CSV (`taut::report::Table`), column by column, so that the
//! numbers are the CLI's bit for bit. The Pythonic surface (keyword
//! arguments, numpy arrays, exceptions with attributes, tqdm) is
//! `python/taut/__init__.py`.
//!
//! Three things only a binding has to do are done here:
//! * the GIL is released while runs execute: the work runs on a thread of
//!   its own while the calling thread waits without the GIL ([`work`]);
//! * progress reaches the Python callback on the calling thread, which is
//!   also where Ctrl-C is noticed (`Python::check_signals`, main thread
//!   only); a Ctrl-C or a callback that raises asks every run to stop at its
//!   next step ([`taut::interrupt`]) and the call raises once they have;
//! * `taut::Error` becomes an exception of `taut._errors` with the error's
//!   fields as attributes ([`to_py_err`]).

use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList};

use taut::app::{self, Frontend, Note, SceneSource};
use taut::report::{Column, Table};

mod scenes;
mod simulation;

/// How often the waiting thread wakes to deliver progress and to look for
/// Ctrl-C: a tenth of a second is below what a person notices and costs
/// nothing against runs of milliseconds to hours.
const POLL: Duration = Duration::from_millis(100);

/// Where a scene comes from: a file (read by the call, so that a parse
/// error names it as the CLI's does) or TOML text given directly.
fn scene(path: Option<&str>, text: Option<String>) -> taut::Result<SceneSource> {
    match (path, text) {
        (Some(p), _) => Ok(SceneSource::File(PathBuf::from(p))),
        (None, Some(t)) => Ok(SceneSource::Text(t)),
        (None, None) => Err(taut::Error::invalid(
            "scene",
            "none",
            "a path to a scene file or the scene's TOML text",
        )),
    }
}

/// An exception of `taut._errors` built from `args`.
fn raise<'py>(py: Python<'py>, class: &str, args: impl pyo3::call::PyCallArgs<'py>) -> PyErr {
    let made = py
        .import("taut._errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1(args));
    match made {
        Ok(exc) => PyErr::from_value(exc),
        Err(e) => e,
    }
}

/// The Python name of a CLI flag named in an error (`--batch` → `batch`).
fn python_name(field: &str) -> Option<String> {
    field.strip_prefix("--").map(|flag| flag.replace('-', "_"))
}

/// `taut::Error` as a Python exception with the error's fields as
/// attributes (classes in `python/taut/_errors.py`, docs/python.md).
fn to_py_err(py: Python<'_>, e: taut::Error) -> PyErr {
    failed(py, e, None)
}

/// [`to_py_err`] for an error of a call that saved the failed contact
/// problem at `saved` (into its output folder, as the CLI does).
fn failed(py: Python<'_>, e: taut::Error, saved: Option<PathBuf>) -> PyErr {
    use taut::Error as E;
    let message = e.to_string();
    match e {
        E::Invalid {
            field,
            value,
            allowed,
        } => match python_name(&field) {
            Some(name) => raise(
                py,
                "SceneError",
                (
                    format!("invalid argument: `{name}` = {value}: {allowed}"),
                    name,
                    Some(value),
                    Some(allowed),
                ),
            ),
            None => raise(
                py,
                "SceneError",
                (message, field, Some(value), Some(allowed)),
            ),
        },
        E::Parse { field, .. } => raise(
            py,
            "SceneError",
            (message, field, None::<String>, None::<String>),
        ),
        E::Override { spec, reason } => {
            // `unset KEY` is the removal of KEY (Python's `set={KEY: None}`):
            // the field is the key
            let (key, value) = match spec.split_once('=') {
                Some((k, v)) => (k.trim().to_string(), Some(v.trim().to_string())),
                None => match spec.strip_prefix(taut::scene::UNSET) {
                    Some(k) => (k.trim().to_string(), None),
                    None => (spec.clone(), None),
                },
            };
            raise(py, "SceneError", (message, key, value, Some(reason)))
        }
        E::Diverged {
            step,
            time,
            quantity,
            value,
            cause,
        } => raise(
            py,
            "DivergedError",
            (message, step, time, quantity, value, cause),
        ),
        E::Contact {
            step,
            time,
            run,
            failure,
        } => {
            // the law's failure with its problem (`taut::contact::ContactFailed`)
            let problem = failure
                .downcast_ref::<taut::contact::ContactFailed>()
                .and_then(|f| serde_json::to_string(&f.problem).ok())
                .unwrap_or_default();
            let run = run.trim_end_matches(": ").to_string();
            let saved = saved.map(|p| p.to_string_lossy().into_owned());
            raise(
                py,
                "ContactError",
                (
                    message,
                    step,
                    time,
                    run,
                    failure.to_string(),
                    problem,
                    saved,
                ),
            )
        }
        E::Tolerance {
            quantity,
            tolerance,
            reason,
        } => raise(py, "ToleranceError", (message, quantity, tolerance, reason)),
        E::Io { path, .. } | E::Output { path, .. } | E::Replay { path, .. } => raise(
            py,
            "OutputError",
            (message, path.to_string_lossy().into_owned()),
        ),
        E::Interrupted => PyKeyboardInterrupt::new_err(message),
    }
}

/// Run `job` on a thread of its own while this thread, without the GIL,
/// waits for it; deliver its progress reports to `progress` (on this
/// thread, with the GIL), and turn a Ctrl-C or an exception in `progress`
/// into a stop request ([`taut::interrupt`]) and, once the job has
/// stopped, into that exception. A panic in the job is a `RuntimeError`
/// (never an abort of the interpreter).
///
/// Reports are delivered in order of `done` (workers of a sweep may send
/// theirs out of order; a smaller one after a larger is dropped), at most
/// one per [`POLL`], and the last one always.
fn work<R: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    job: impl FnOnce(&(dyn Fn(usize, usize) + Sync)) -> R + Send,
) -> PyResult<R> {
    let call = taut::interrupt::Call::enter();
    let (tx, mut rx) = mpsc::channel::<(usize, usize)>();
    let (outcome, failure) = std::thread::scope(|s| {
        let handle = s.spawn(move || {
            let report = move |done: usize, total: usize| {
                // the receiver lives until the job ends: a send cannot fail
                let _ = tx.send((done, total));
            };
            job(&report)
        });
        let mut failure: Option<PyErr> = None;
        let mut pending: Option<(usize, usize)> = None;
        let mut delivered: Option<(usize, usize)> = None;
        let mut last: Option<Instant> = None;
        loop {
            let (back, msg) = py.detach(move || {
                let msg = rx.recv_timeout(POLL);
                (rx, msg)
            });
            rx = back;
            let finished = match msg {
                Ok(m) => {
                    pending = pending.max(Some(m));
                    while let Ok(m) = rx.try_recv() {
                        pending = pending.max(Some(m));
                    }
                    false
                }
                Err(RecvTimeoutError::Timeout) => false,
                Err(RecvTimeoutError::Disconnected) => true,
            };
            let due = finished || last.is_none_or(|t| t.elapsed() >= POLL);
            if let (true, None, Some(cb), Some(m)) = (due, &failure, progress, pending)
                && pending > delivered
            {
                last = Some(Instant::now());
                delivered = pending;
                if let Err(e) = cb.call1(m) {
                    failure = Some(e);
                    // the last report comes after the work: nothing to stop
                    if !finished {
                        taut::interrupt::request();
                    }
                }
            }
            // a Ctrl-C stops the work; a second one while it stops is the same request
            if let Err(e) = py.check_signals()
                && failure.is_none()
            {
                failure = Some(e);
                taut::interrupt::request();
            }
            if finished {
                break;
            }
        }
        (py.detach(move || handle.join()), failure)
    });
    // a stop requested while this call worked (here or by another call)
    // means some of its runs may have been cut short: never return them
    let interrupted = taut::interrupt::requested();
    drop(call);
    if let Some(e) = failure {
        return Err(e);
    }
    let out = outcome.map_err(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        PyRuntimeError::new_err(format!(
            "internal error (a panic in taut, please report it): {what}"
        ))
    })?;
    if interrupted {
        return Err(PyKeyboardInterrupt::new_err(
            "taut: stopped by a stop request (Ctrl-C or an exception in a progress callback) made during this call",
        ));
    }
    Ok(out)
}

/// `f64`s as little-endian bytes (`numpy.frombuffer(b, "<f8")`): one copy,
/// and no build-time dependency on numpy's C API, so one abi3 wheel serves
/// every Python ≥ 3.9 and numpy ≥ 1.21.
fn f64_bytes<'py>(py: Python<'py>, v: impl ExactSizeIterator<Item = f64>) -> Bound<'py, PyBytes> {
    let mut b = Vec::with_capacity(8 * v.len());
    for x in v {
        b.extend_from_slice(&x.to_le_bytes());
    }
    PyBytes::new(py, &b)
}

/// A table as a list of `(name, kind, data)`: `kind` says how
/// `taut._table` makes the array (docs/python.md), `data` is bytes for
/// numbers and a list for text.
fn table_to_py<'py>(py: Python<'py>, t: &Table) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for (name, col) in &t.columns {
        let (kind, data): (&str, Bound<'py, PyAny>) = match col {
            Column::Real(v) | Column::RealOrNone(v) => {
                // RealOrNone's "none" is its non-finite values: NaN in Python
                let none = matches!(col, Column::RealOrNone(_));
                let it = v
                    .iter()
                    .map(move |&x| if none && !x.is_finite() { f64::NAN } else { x });
                ("f8", f64_bytes(py, it).into_any())
            }
            Column::Count(v) => {
                let mut b = Vec::with_capacity(8 * v.len());
                for x in v {
                    b.extend_from_slice(&(*x as i64).to_le_bytes());
                }
                ("i8", PyBytes::new(py, &b).into_any())
            }
            Column::CountOrNone(v) => (
                "f8",
                f64_bytes(py, v.iter().map(|x| x.map_or(f64::NAN, |n| n as f64))).into_any(),
            ),
            Column::Bit(v) | Column::Bool(v) => {
                let b: Vec<u8> = v.iter().map(|&x| u8::from(x)).collect();
                ("b1", PyBytes::new(py, &b).into_any())
            }
            Column::Label(v) => ("str", PyList::new(py, v)?.into_any()),
            Column::Text(v) => ("str", PyList::new(py, v)?.into_any()),
        };
        out.append((name, kind, data))?;
    }
    Ok(out)
}

/// A run a study could not make: `(method, discretization, formulation,
/// reason)`.
type NotRunTuple = (String, String, String, String);

fn not_run(n: &taut::study::compare::NotRun) -> NotRunTuple {
    (
        n.method.clone(),
        n.discretization.clone(),
        n.formulation.clone(),
        n.reason.to_string(),
    )
}

/// The binding as the application layer's front end: progress to the
/// waiting thread ([`work`]); of the notes, those on the output folder on stderr
/// (as the CLI) and the saved contact problem kept for the exception.
struct Binding<'a> {
    report: &'a (dyn Fn(usize, usize) + Sync),
    saved: Mutex<Option<PathBuf>>,
}

impl Frontend for Binding<'_> {
    fn progress(&self, done: usize, total: usize) {
        (self.report)(done, total)
    }

    fn note(&self, note: Note<'_>) {
        match note {
            Note::Replaced(text) | Note::Kept(text) => eprintln!("{text}"),
            Note::AboveBound(_) => {}
            Note::FailureSaved(path) => {
                if let Ok(mut saved) = self.saved.lock() {
                    *saved = Some(path.to_path_buf());
                }
            }
        }
    }
}

/// The course every call takes: run `command` ([`work`]: without the GIL,
/// with progress and Ctrl-C) and make its error an exception.
fn call<R: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    command: impl FnOnce(&dyn Frontend) -> taut::Result<R> + Send,
) -> PyResult<R> {
    let (result, saved) = work(py, progress, |report| {
        let binding = Binding {
            report,
            saved: Mutex::new(None),
        };
        let result = command(&binding);
        (result, binding.saved.into_inner().ok().flatten())
    })?;
    result.map_err(|e| failed(py, e, saved))
}

/// What `run` hands back: `(summary_json, history_columns, warnings,
/// accuracy_columns, (snapshots, field), (spans, supports, envelope))`,
/// accuracy for a `tolerance` run only, snapshots and field when the scene
/// asks for them ([`wire_to_py`]), the line's tables likewise
/// ([`line_to_py`]).
type RunTuple<'py> = (
    String,
    Bound<'py, PyList>,
    Vec<String>,
    Option<Bound<'py, PyList>>,
    (Option<WireTuple<'py>>, Option<WireTuple<'py>>),
    LineTuple<'py>,
);

/// The line's tables (`spans.csv`, `supports.csv`, `envelope.csv`), each
/// `None` when the scene does not ask for it, and `standard.csv` (always).
pub(crate) type LineTuple<'py> = (
    Option<Bound<'py, PyList>>,
    Option<Bound<'py, PyList>>,
    Option<Bound<'py, PyList>>,
    Bound<'py, PyList>,
);

/// A run's line tables ([`LineTuple`]): the summary's spans (the filtered
/// force's included), the supports' uplift, the envelope and the
/// standards' statistics (`standard.csv`), as the CLI writes them.
pub(crate) fn line_to_py<'py>(
    py: Python<'py>,
    summary: &taut::report::Summary,
    h: &taut::record::History,
) -> PyResult<LineTuple<'py>> {
    let spans = match summary.spans.is_empty() {
        true => None,
        false => Some(table_to_py(py, &taut::report::spans_table(&summary.spans))?),
    };
    let supports = match h.supports.is_empty() {
        true => None,
        false => Some(table_to_py(py, &taut::report::supports_table(&h.supports))?),
    };
    let envelope = match h.envelope.is_empty() {
        true => None,
        false => Some(table_to_py(py, &taut::report::envelope_table(&h.envelope))?),
    };
    let standard = table_to_py(py, &taut::report::standard_table(&summary.standard))?;
    Ok((spans, supports, envelope, standard))
}

/// A recorded wire series (`taut::record::WireSeries`) as f64 bytes:
/// `(requested, t, x, v)`, v row-major (len(t) × len(x)).
type WireTuple<'py> = (
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
);

/// A run's snapshots and field ([`WireTuple`]; `None` when not recorded).
fn wire_to_py<'py>(
    py: Python<'py>,
    h: &taut::record::History,
) -> (Option<WireTuple<'py>>, Option<WireTuple<'py>>) {
    let one = |s: &taut::record::WireSeries| {
        (!s.is_empty()).then(|| {
            (
                f64_bytes(py, s.requested.iter().copied()),
                f64_bytes(py, s.t.iter().copied()),
                f64_bytes(py, s.x.iter().copied()),
                f64_bytes(py, s.v.iter().copied()),
            )
        })
    };
    (one(&h.snapshots), one(&h.field))
}

/// Where a call's scene comes from, as Python passes it: `(path, text,
/// set)`, a scene file or its TOML text, and the overrides (`set=`, as the
/// CLI's `--set`).
#[derive(FromPyObject)]
struct SceneArg(Option<String>, Option<String>, Vec<String>);

impl SceneArg {
    /// The scene and its overrides.
    fn source(self, py: Python<'_>) -> PyResult<(SceneSource, Vec<String>)> {
        let SceneArg(path, text, set) = self;
        let source = scene(path.as_deref(), text).map_err(|e| to_py_err(py, e))?;
        Ok((source, set))
    }
}

/// A command's options, the keyword arguments of the Python function as
/// JSON ([`taut::app::args`]: the struct the CLI's subcommand takes).
fn options<A: taut::app::args::CommandArgs>(py: Python<'_>, json: &str) -> PyResult<A> {
    taut::app::args::from_json(json).map_err(|e| to_py_err(py, e))
}

/// A command's scene, its overrides and its options made typed: the
/// options (`args`, JSON of the command's `*Args`) read and checked by
/// [`taut::app::args::CommandArgs::typed`] (`CompareArgs::study`,
/// `RunArgs::tolerance`, …): the glue every function shares, written once.
fn typed<A: taut::app::args::CommandArgs>(
    py: Python<'_>,
    on: SceneArg,
    args: &str,
) -> PyResult<(SceneSource, Vec<String>, A::Typed)> {
    let (scene, set) = on.source(py)?;
    let typed = options::<A>(py, args)?
        .typed()
        .map_err(|e| to_py_err(py, e))?;
    Ok((scene, set, typed))
}

/// A study of one scene as `app` takes it ([`typed`]).
fn study_request<A: taut::app::args::CommandArgs>(
    py: Python<'_>,
    on: SceneArg,
    out: Option<PathBuf>,
    args: &str,
) -> PyResult<app::StudyRequest<A::Typed>> {
    let (scene, set, study) = typed::<A>(py, on, args)?;
    Ok(app::StudyRequest {
        scene,
        set,
        study,
        out,
    })
}

/// One run (`taut run`), or with `tolerance` an accuracy-targeted one
/// (`taut run --tolerance TOL --quantity Q`); with `out` the CLI's files
/// (`history.csv`, `summary.json`, `force.svg`, and `accuracy.csv`) are
/// written too. `args`: [`taut::app::RunArgs`] as JSON.
#[pyfunction]
fn run<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<RunTuple<'py>> {
    let (scene, set, tolerance) = typed::<taut::app::RunArgs>(py, on, args)?;
    let request = app::RunRequest {
        scene,
        set,
        out,
        tolerance,
    };
    let r = call(py, progress.as_ref(), |fe| app::run(&request, fe))?;
    let history = table_to_py(py, &taut::report::history_table(&r.output))?;
    let wire = wire_to_py(py, &r.output.history);
    let line = line_to_py(py, &r.summary, &r.output.history)?;
    let Some(accuracy) = &r.accuracy else {
        return Ok((
            pretty(&r.summary)?,
            history,
            r.output.warnings,
            None,
            wire,
            line,
        ));
    };
    let doc = taut::report::WithAccuracy {
        summary: &r.summary,
        accuracy,
    };
    Ok((
        pretty(&doc)?,
        history,
        r.output.warnings.clone(),
        Some(table_to_py(py, &taut::report::accuracy_table(accuracy))?),
        wire,
        line,
    ))
}

/// A summary as `summary.json` holds it.
fn pretty(value: &impl serde::Serialize) -> PyResult<String> {
    serde_json::to_string_pretty(value)
        .map_err(|e| PyRuntimeError::new_err(format!("summary as JSON: {e}")))
}

/// A sweep into folder `out` (resumable: finished points are kept there);
/// returns the columns of `sweep.csv`. `files` writes the CLI's tables and
/// maps into `out` as well. `args`: [`taut::app::SweepArgs`] as JSON (the
/// module writes a list of points as `vary` lists with `paired`).
#[pyfunction]
fn sweep<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: PathBuf,
    files: bool,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<Bound<'py, PyList>> {
    let (source, set, study) = typed::<taut::app::SweepArgs>(py, on, args)?;
    let mut request = app::SweepRequest::new(source, set, study, out);
    request.files = files;
    let s = call(py, progress.as_ref(), |fe| app::sweep(&request, fe))?;
    table_to_py(py, &taut::report::sweep_table(&s.spec, &s.records))
}

/// A comparison: `(compare.csv columns, failed, skipped)`: the runs that
/// stopped and the combinations that could not run; with `out` the CLI's
/// files too. `args`: [`taut::app::CompareArgs`] as JSON.
#[pyfunction]
fn compare<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<(Bound<'py, PyList>, Vec<NotRunTuple>, Vec<NotRunTuple>)> {
    let c = study::<taut::study::request::CompareStudy>(py, on, out, progress, args)?;
    Ok((
        table_to_py(py, &taut::report::compare_rows(&c))?,
        c.failed.iter().map(not_run).collect(),
        c.skipped.iter().map(not_run).collect(),
    ))
}

/// A convergence study: `(converge.csv columns, skipped)`; with `out` the
/// CLI's files too. `args`: [`taut::app::ConvergeArgs`] as JSON.
#[pyfunction]
fn converge<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<(Bound<'py, PyList>, Vec<NotRunTuple>)> {
    let outcome = study::<taut::study::request::ConvergeStudy>(py, on, out, progress, args)?;
    let skipped = outcome.skipped().iter().map(not_run).collect();
    let rows = taut::report::converge_rows(&outcome.rows());
    Ok((table_to_py(py, &rows)?, skipped))
}

/// A solution verification (`taut uncertainty`): `(uncertainty.csv
/// columns, the family's runs)`; with `out` the CLI's files too. `args`:
/// [`taut::app::UncertaintyArgs`] as JSON.
#[pyfunction]
fn uncertainty<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<(Bound<'py, PyList>, Bound<'py, PyList>)> {
    let u = study::<taut::study::request::UncertaintyStudy>(py, on, out, progress, args)?;
    Ok((
        table_to_py(py, &taut::report::uncertainty_table(&u))?,
        table_to_py(py, &taut::report::family_table(&u))?,
    ))
}

/// A work–precision study: `(precision.csv columns, skipped)`; with `out`
/// the CLI's files too. `args`: [`taut::app::PrecisionArgs`] as JSON.
#[pyfunction]
fn precision<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<(Bound<'py, PyList>, Vec<NotRunTuple>)> {
    let p = study::<taut::study::request::PrecisionStudy>(py, on, out, progress, args)?;
    Ok((
        table_to_py(py, &taut::report::precision_rows(&p))?,
        p.skipped.iter().map(not_run).collect(),
    ))
}

/// A study of one scene of the library's list (`taut::app::each_study`)
/// run as its command runs it ([`study_request`], [`call`]): the glue of
/// every study, written once.
fn study<'py, S: taut::app::StudyCommand>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<S::Outcome>
where
    S::Outcome: Send,
{
    let request = study_request::<S::Args>(py, on, out, args)?;
    call(py, progress.as_ref(), |fe| S::command(&request, fe))
}

/// Any study of one scene of the library's list by its command's name
/// (`taut.study("converge", …)`): `[(name, columns)]`, its tables by the
/// file each is written as ([`taut::app::StudyCommand::tables`]); with
/// `out` the CLI's files too. `args`: the study's options as JSON. A study
/// added to the list is offered here with no edit of this module.
#[pyfunction]
fn study_tables<'py>(
    py: Python<'py>,
    name: &str,
    on: SceneArg,
    out: Option<PathBuf>,
    progress: Option<Bound<'py, PyAny>>,
    args: &str,
) -> PyResult<Vec<(String, Bound<'py, PyList>)>> {
    struct Named<'a, 'py> {
        py: Python<'py>,
        name: &'a str,
        given: Option<(SceneArg, Option<PathBuf>, Option<Bound<'py, PyAny>>)>,
        args: &'a str,
        found: Option<PyResult<Vec<(&'static str, Table)>>>,
    }
    impl taut::app::StudyVisitor for Named<'_, '_> {
        fn visit<S: taut::app::StudyCommand>(&mut self)
        where
            S::Outcome: Send,
        {
            use taut::app::args::CommandArgs;
            if <S::Args as CommandArgs>::COMMAND != self.name {
                return;
            }
            let (on, out, progress) = self.given.take().expect("one study of a name");
            let outcome = study::<S>(self.py, on, out, progress, self.args);
            self.found = Some(outcome.map(|o| S::tables(&o)));
        }
    }
    let mut named = Named {
        py,
        name,
        given: Some((on, out, progress)),
        args,
        found: None,
    };
    taut::app::each_study(&mut named);
    let Some(found) = named.found else {
        let known: Vec<String> = studies().into_iter().map(|(n, _)| n).collect();
        let allowed = format!("one of {}", known.join(", "));
        return Err(to_py_err(py, taut::Error::invalid("study", name, allowed)));
    };
    found?
        .into_iter()
        .map(|(n, t)| Ok((n.to_string(), table_to_py(py, &t)?)))
        .collect()
}

/// The studies of one scene of the library's list: `[(name, help)]`, the
/// command and its help line (`taut.studies()`).
#[pyfunction]
fn studies() -> Vec<(String, String)> {
    struct Names(Vec<(String, String)>);
    impl taut::app::StudyVisitor for Names {
        fn visit<S: taut::app::StudyCommand>(&mut self)
        where
            S::Outcome: Send,
        {
            use taut::app::args::CommandArgs;
            let name = <S::Args as CommandArgs>::COMMAND;
            self.0.push((name.to_string(), S::ABOUT.to_string()));
        }
    }
    let mut names = Names(Vec::new());
    taut::app::each_study(&mut names);
    names.0
}

/// One option: `(name, default, help)` ([`taut::app::args::OptionSchema`]).
type OptionTuple = (String, Option<String>, String);

/// Every command's options as the library declares them
/// ([`taut::app::args::schema`]): `[(command, [(name, default, help)])]`,
/// what the module's tests hold its functions' signatures against.
#[pyfunction]
fn schema() -> Vec<(String, Vec<OptionTuple>)> {
    taut::app::args::schema()
        .into_iter()
        .map(|(command, options)| {
            let options = options
                .into_iter()
                .map(|o| (o.name, o.default, o.help))
                .collect();
            (command.to_string(), options)
        })
        .collect()
}

/// The scene's TOML tree after `set` (`taut.load_scene`), as JSON text:
/// integers stay integers and floats floats, so the dict made of it
/// writes back to the same TOML values.
#[pyfunction]
#[pyo3(signature = (path, text, set))]
fn scene_json(
    py: Python<'_>,
    path: Option<&str>,
    text: Option<String>,
    set: Vec<String>,
) -> PyResult<String> {
    let err = |e| to_py_err(py, e);
    let tree = app::scene_tree(&scene(path, text).map_err(err)?, &set).map_err(err)?;
    serde_json::to_string(&tree).map_err(|e| {
        to_py_err(
            py,
            taut::Error::invalid(
                "scene",
                e,
                "a scene whose values JSON can hold (finite numbers)",
            ),
        )
    })
}

/// The natural frequencies and mode shapes of a scene's beam (`taut
/// modes`): `(modes_columns, mode_shapes_columns)`, the CLI's `modes.csv`
/// and `mode_shapes.csv`; with `out` those files are written too.
#[pyfunction]
fn modes<'py>(
    py: Python<'py>,
    on: SceneArg,
    out: Option<PathBuf>,
    args: &str,
) -> PyResult<(Bound<'py, PyList>, Bound<'py, PyList>)> {
    let (scene, set, count) = typed::<taut::app::ModesArgs>(py, on, args)?;
    let request = app::ModesRequest {
        scene,
        set,
        count,
        out,
    };
    let m = call(py, None, |fe| app::modes(&request, fe))?;
    Ok((
        table_to_py(py, &taut::report::modes_table(&m))?,
        table_to_py(py, &taut::report::mode_shapes_table(&m))?,
    ))
}

/// The mesh nodes of a scene, m, as f64 bytes (`taut.mesh`; for
/// `galerkin`, the nodes of the uniform mesh of `mesh.elements` elements,
/// where its snapshots and mode shapes are sampled by default).
#[pyfunction]
#[pyo3(signature = (path, text, set))]
fn mesh<'py>(
    py: Python<'py>,
    path: Option<&str>,
    text: Option<String>,
    set: Vec<String>,
) -> PyResult<Bound<'py, PyBytes>> {
    let err = |e| to_py_err(py, e);
    let x = app::mesh_nodes(&scene(path, text).map_err(err)?, &set).map_err(err)?;
    Ok(f64_bytes(py, x.into_iter()))
}

/// One self-contained `report.html` from output folders (`taut report`):
/// returns the page's path, its numbers of plots and tables, and what it
/// leaves out ([`ReportTuple`]).
#[pyfunction]
#[pyo3(signature = (dirs, out))]
fn report(py: Python<'_>, dirs: Vec<PathBuf>, out: Option<PathBuf>) -> PyResult<ReportTuple> {
    let r = app::report(&app::ReportRequest { dirs, out }).map_err(|e| to_py_err(py, e))?;
    Ok((
        r.path.display().to_string(),
        r.plots,
        r.tables,
        r.left_out,
        r.not_shown,
        r.incomplete
            .iter()
            .map(|d| d.display().to_string())
            .collect(),
    ))
}

/// What `report` hands Python: the page, plots and tables shown, the files
/// left out (could not be shown) and not shown (by design), each
/// `path: reason`, and the folders marked incomplete.
type ReportTuple = (String, usize, usize, Vec<String>, Vec<String>, Vec<String>);

/// The most keys a list of points may set
/// (`taut::study::sweep::MAX_POINT_KEYS`), so that the Python layer
/// refuses a wider one before building its axes.
#[pyfunction]
fn most_point_keys() -> usize {
    taut::study::sweep::MAX_POINT_KEYS
}

/// Ask every taut call at work in the process to stop at its next step
/// (`taut::interrupt::request_if_working`); whether one was. The package's
/// SIGINT handler calls it, so that a Ctrl-C stops calls made from any
/// thread (a thread pool's workers never see a signal themselves).
#[pyfunction]
fn stop_running_calls() -> bool {
    taut::interrupt::request_if_working(STOP_HOLD)
}

/// How long a Ctrl-C keeps stopping calls that start after it
/// ([`taut::interrupt::request_if_working`]): a thread pool that shuts down
/// starts its queued calls within milliseconds of the running ones'
/// stop; 2 s covers that on a loaded machine, and a call started later
/// runs as usual.
const STOP_HOLD: Duration = Duration::from_secs(2);

/// The registry of quantities (`taut::quantity::all`) as JSON: one object
/// a quantity, with its name (the column and key in every table and
/// summary), label, unit, definition, window, smoothness, error kind and
/// whether it is a count. The package's labels and docs read it, so a
/// quantity registered in the library is known here without a list of
/// its own.
#[pyfunction]
fn quantities() -> String {
    let all: Vec<serde_json::Value> = taut::quantity::all()
        .into_iter()
        .map(|q| {
            serde_json::json!({
                "name": q.name,
                "label": q.label,
                "unit": q.unit,
                "definition": q.definition,
                "window": q.window,
                "smooth": q.smooth,
                "error": q.error,
                "count": q.count,
            })
        })
        .collect();
    serde_json::Value::Array(all).to_string()
}

/// The native module.
#[pymodule]
fn _taut(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("taut_version", taut::VERSION)?;
    // every contact formulation, in the library's order (`taut.ALL_FORMULATIONS`)
    m.add(
        "formulations",
        taut::scene::Formulation::ALL.map(|f| f.name()).to_vec(),
    )?;
    // the built-in time integrators and the mesh kinds, in the library's
    // order (`Method::ALL`, `MeshKind::ALL`): the lists `taut.compare`'s
    // help gives
    m.add(
        "methods",
        taut::scene::Method::ALL.map(|x| x.name()).to_vec(),
    )?;
    m.add(
        "mesh_kinds",
        taut::scene::MeshKind::ALL.map(|k| k.name()).to_vec(),
    )?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(converge, m)?)?;
    m.add_function(wrap_pyfunction!(precision, m)?)?;
    m.add_function(wrap_pyfunction!(uncertainty, m)?)?;
    m.add_function(wrap_pyfunction!(study_tables, m)?)?;
    m.add_function(wrap_pyfunction!(studies, m)?)?;
    m.add_function(wrap_pyfunction!(scene_json, m)?)?;
    m.add_function(wrap_pyfunction!(schema, m)?)?;
    m.add_function(wrap_pyfunction!(scenes::bundled_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(mesh, m)?)?;
    m.add_function(wrap_pyfunction!(report, m)?)?;
    m.add_function(wrap_pyfunction!(stop_running_calls, m)?)?;
    m.add_function(wrap_pyfunction!(most_point_keys, m)?)?;
    m.add_function(wrap_pyfunction!(quantities, m)?)?;
    m.add_class::<simulation::Simulation>()?;
    Ok(())
}
