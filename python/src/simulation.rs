//! `taut._taut.Simulation`: one run stepped on request
//! (`taut::app::Simulation`), for `taut.Simulation` (python/taut/_simulation.py).
//!
//! Steps run without the GIL, in chunks of [`CHUNK`] steps, with Ctrl-C
//! looked for between chunks (`Python::check_signals`): a long `step(k)`
//! stops within a chunk and leaves the simulation usable, at the step it
//! reached. A `step(1)` costs one chunk: a GIL release and a signal check.

use std::sync::Mutex;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyList;

use taut::app::{self, Silent};

use crate::{RunTuple, line_to_py, pretty, scene, table_to_py, to_py_err, wire_to_py};

/// Steps taken between two looks for Ctrl-C: a few milliseconds of a
/// large scene's steps, a negligible share of a small scene's call.
const CHUNK: usize = 256;

/// A carrier's state: `(x, w, q, q_dot, gap, force, in_contact, applied)`
/// (`q_dot` None for a moving force).
type CarrierTuple = (f64, f64, f64, Option<f64>, f64, f64, bool, f64);
/// A probe's state: `(name, x, v, v_dot)`.
type ProbeTuple = (String, f64, f64, f64);
/// The state: `(t, step, carriers, probes)`.
type StateTuple = (f64, usize, Vec<CarrierTuple>, Vec<ProbeTuple>);

/// One run stepped on request (module docs).
#[pyclass(module = "taut._taut")]
pub(crate) struct Simulation {
    /// `None` once finished into its result.
    inner: Mutex<Option<app::Simulation>>,
}

impl Simulation {
    /// `f` on the simulation: a Python error when it is finished, else
    /// `f`'s own result (made an exception by the caller, with the GIL).
    fn with<R>(
        &self,
        f: impl FnOnce(&mut app::Simulation) -> taut::Result<R>,
    ) -> PyResult<taut::Result<R>> {
        let mut guard = self
            .inner
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the simulation's lock is poisoned"))?;
        let sim = guard
            .as_mut()
            .ok_or_else(|| PyRuntimeError::new_err("the simulation was finished by result()"))?;
        Ok(f(sim))
    }
}

#[pymethods]
impl Simulation {
    /// Build the run of a scene (a path or TOML text, with `set`), its
    /// state at t = 0 recorded; `out` gets `run`'s files at `finish`.
    #[new]
    #[pyo3(signature = (path, text, set, out))]
    fn new(
        py: Python<'_>,
        path: Option<&str>,
        text: Option<String>,
        set: Vec<String>,
        out: Option<std::path::PathBuf>,
    ) -> PyResult<Self> {
        let err = |e| to_py_err(py, e);
        let request = app::RunRequest {
            scene: scene(path, text).map_err(err)?,
            set,
            out,
            tolerance: None,
        };
        let sim = py
            .detach(|| app::Simulation::new(&request, &Silent))
            .map_err(err)?;
        Ok(Simulation {
            inner: Mutex::new(Some(sim)),
        })
    }

    /// Advance up to `k` steps (fewer at the run's end); the number taken.
    fn step(&self, py: Python<'_>, k: usize) -> PyResult<usize> {
        let mut taken = 0;
        while taken < k {
            let chunk = (k - taken).min(CHUNK);
            let n = py
                .detach(|| self.with(|s| s.step(chunk)))?
                .map_err(|e| to_py_err(py, e))?;
            taken += n;
            if n < chunk {
                break;
            }
            py.check_signals()?;
        }
        Ok(taken)
    }

    /// True once the run has ended.
    fn done(&self, py: Python<'_>) -> PyResult<bool> {
        self.with(|s| Ok(s.done()))?.map_err(|e| to_py_err(py, e))
    }

    /// `(steps, dt)`: the run's number of steps and its time step, s.
    fn steps_dt(&self, py: Python<'_>) -> PyResult<(usize, f64)> {
        self.with(|s| Ok((s.steps(), s.dt())))?
            .map_err(|e| to_py_err(py, e))
    }

    /// Hold `newtons` (+ up) on carrier `carrier`'s mass from the next step.
    fn apply_force(&self, py: Python<'_>, carrier: usize, newtons: f64) -> PyResult<()> {
        self.with(|s| s.apply_force(carrier, newtons))?
            .map_err(|e| to_py_err(py, e))
    }

    /// `(t, step, carriers, probes)` at the current time.
    fn state(&self, py: Python<'_>) -> PyResult<StateTuple> {
        self.with(|s| {
            let st = s.state()?;
            let carriers = st
                .carriers
                .iter()
                .map(|c| {
                    (
                        c.x,
                        c.w,
                        c.q,
                        c.q_dot,
                        c.gap,
                        c.force,
                        c.in_contact,
                        c.applied,
                    )
                })
                .collect();
            let probes = st
                .probes
                .into_iter()
                .map(|p| (p.name, p.x, p.v, p.v_dot))
                .collect();
            Ok((st.t, st.step, carriers, probes))
        })?
        .map_err(|e| to_py_err(py, e))
    }

    /// The beam displacement v(x), m (+ up), at the current time.
    fn w_at(&self, py: Python<'_>, x: f64) -> PyResult<f64> {
        self.with(|s| s.w_at(x))?.map_err(|e| to_py_err(py, e))
    }

    /// The run's result once every step is taken: what `run` returns
    /// (`(summary_json, history_columns, warnings, None)`), `out`'s files
    /// written. Ends the simulation.
    fn finish<'py>(&self, py: Python<'py>) -> PyResult<RunTuple<'py>> {
        let mut guard = self
            .inner
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the simulation's lock is poisoned"))?;
        let sim = guard
            .take()
            .ok_or_else(|| PyRuntimeError::new_err("the simulation was finished by result()"))?;
        if !sim.done() {
            // refused before the end: keep the simulation for more steps
            let left = sim.steps() - sim.state().map_or(0, |s| s.step);
            *guard = Some(sim);
            return Err(to_py_err(
                py,
                taut::Error::invalid(
                    "simulation",
                    format!("{left} steps before its end"),
                    "gives its result once every step is taken: step it to the end first",
                ),
            ));
        }
        let r = py.detach(|| sim.finish()).map_err(|e| to_py_err(py, e))?;
        let history = table_to_py(py, &taut::report::history_table(&r.output))?;
        let empty: Option<Bound<'py, PyList>> = None;
        let wire = wire_to_py(py, &r.output.history);
        let line = line_to_py(py, &r.summary, &r.output.history)?;
        Ok((
            pretty(&r.summary)?,
            history,
            r.output.warnings,
            empty,
            wire,
            line,
        ))
    }
}
