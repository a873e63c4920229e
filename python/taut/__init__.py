"""taut from Python: the runs and studies of the `taut` command line, as numpy
arrays, computed by the same Rust library.

    >>> import taut
    >>> r = taut.run("scenes/reference.toml", set={"mesh.elements": 200})
    >>> r.summary["carriers"][0]["loss_fraction"]
    >>> t = taut.sweep("scenes/reference.toml", vary={"carrier.speed.cruise": (50, 230, 10)})
    >>> t["loss_fraction_span"]

Every function takes a scene as a path (str or os.PathLike) or as TOML text,
and `set`, a dict of dotted keys to values: the CLI's `--set`. The numbers
are the CLI's for the same scene, bit for bit (the module calls the same
library functions and reads the same tables the CLI writes as CSV).

While runs execute the GIL is released. Progress goes to `progress`: a
callable `progress(done, total)`, False for none, or by default a tqdm bar
when tqdm is installed. Ctrl-C stops the work at the next step of every run
and raises KeyboardInterrupt; nothing half-written is left behind (a sweep
into `out` keeps the points it finished, and resumes from them).

Errors are exceptions with the fields of the error as attributes:
SceneError (field, value, allowed), DivergedError (step, time, quantity,
value, cause), ContactError, ToleranceError, OutputError; all derive from
TautError. The API is documented in docs/python.md.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

from . import _taut
from ._errors import (
    ContactError,
    DivergedError,
    OutputError,
    SceneError,
    TautError,
    ToleranceError,
)
from ._simulation import CarrierState, ProbeState, Simulation, SimulationState
from ._table import Table, _not_run, table

__all__ = [
    "run",
    "sweep",
    "compare",
    "converge",
    "precision",
    "Run",
    "Simulation",
    "SimulationState",
    "CarrierState",
    "ProbeState",
    "Table",
    "TautError",
    "SceneError",
    "DivergedError",
    "ContactError",
    "ToleranceError",
    "OutputError",
    "__version__",
]

__version__: str = _taut.__version__

Scene = Union[str, "os.PathLike[str]"]
"""A path to a scene file, or the scene's TOML text."""

Progress = Union[None, bool, Callable[[int, int], Any]]
"""None: a tqdm bar if tqdm is installed; False: none; True: tqdm (if
installed); a callable: called as progress(done, total) on the calling
thread."""

ALL_FORMULATIONS = ("lagrange", "penalty", "complementarity", "impact")


class Run:
    """One run's results.

    Attributes:
        summary: the dict of the CLI's `summary.json` (scene, derived
            quantities, per-carrier statistics, warnings, wall time).
        history: the columns of `history.csv` as a Table of arrays (`t`,
            `x_m`, `beam_w`, `mass_q`, `gap`, `force`, `in_contact`, probes;
            suffixed `_0`, `_1`, ... with several carriers).
        warnings: findings that make the numbers suspect, as the CLI prints them.
        accuracy: for a run with `tolerance`, the columns of the CLI's
            `accuracy.csv` (the pilot runs, then the chosen one, with their
            estimated errors; summary["accuracy"] has the whole account);
            None otherwise.
    """

    def __init__(
        self,
        summary: Dict[str, Any],
        history: Table,
        warnings: List[str],
        accuracy: Optional[Table] = None,
    ) -> None:
        self.summary: Dict[str, Any] = summary
        self.history: Table = history
        self.warnings: List[str] = warnings
        self.accuracy: Optional[Table] = accuracy

    def __repr__(self) -> str:
        loss = [c.get("loss_fraction") for c in self.summary.get("carriers", [])]
        return f"taut.Run({self.history.rows} rows, P_l = {loss}, {len(self.warnings)} warnings)"


def _scene(scene: Scene) -> Tuple[Optional[str], Optional[str]]:
    """(path, text): a PathLike or a one-line str is a path; a str with a
    line break or starting with a TOML table is the scene's text."""
    if isinstance(scene, os.PathLike):
        return os.fspath(scene), None
    if isinstance(scene, str):
        if "\n" in scene or scene.lstrip().startswith("["):
            return None, scene
        return scene, None
    raise TypeError(
        f"scene: expected a path (str or os.PathLike) or TOML text, got {type(scene).__name__}"
    )


def _toml(value: Any) -> str:
    """A Python value as the TOML value `--set` reads."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(int(value))
    if isinstance(value, float):
        # repr is the shortest text that reads back as the same float (a
        # numpy float64 too, once a float); nan and inf are TOML as well,
        # and the scene check names the key they are refused for
        return repr(float(value))
    if isinstance(value, str):
        return value
    if isinstance(value, Mapping):
        inner = ", ".join(f"{_key(str(k))} = {_toml_quoted(v)}" for k, v in value.items())
        return "{ " + inner + " }"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_quoted(v) for v in value) + "]"
    if hasattr(value, "tolist"):  # a numpy scalar (a number) or array (a list)
        try:
            return _toml(value.tolist())
        except SceneError:
            raise
        except Exception as e:  # an array numpy cannot turn into a list
            raise SceneError(
                f"set: a value of type {type(value).__name__} cannot be a scene value ({e})",
                field="set",
                value=_short(repr(value)),
                allowed="a bool, number, str, list or dict (a numpy array becomes a list)",
            ) from None
    raise SceneError(
        f"set: a value of type {type(value).__name__} cannot be a scene value",
        field="set",
        value=repr(value),
        allowed="a bool, number, str, list or dict",
    )


def _key(key: str) -> str:
    """A TOML key: bare when it may be, else quoted."""
    return key if key and all(c.isascii() and (c.isalnum() or c in "_-") for c in key) else json.dumps(key)


# the largest integer the library takes (a 64-bit size)
_LARGEST = 2**63 - 1


def _opt_ranged(name: str, value: Optional[int]) -> Optional[int]:
    """`threads` or `batch`: None (the default) or an int in the range the
    library allows (1 ..= its limit), refused with that range."""
    if value is None:
        return None
    threads, batch = _taut.limits()
    return _count(name, value, 1, threads if name == "threads" else batch)


def _count(name: str, value: int, least: int, most: int = _LARGEST) -> int:
    """An integer argument: refused by name unless an int in `least ..=
    most` (the library checks the upper bounds it knows and names them the
    same way)."""
    if isinstance(value, bool) or not isinstance(value, int) and not hasattr(value, "__index__"):
        raise SceneError(
            f"invalid argument: `{name}` = {value!r}: must be an integer ≥ {least}",
            field=name,
            value=repr(value),
            allowed=f"an integer ≥ {least}",
        )
    n = int(value)
    if n < least or n > most:
        shown = _short(str(n))
        raise SceneError(
            f"invalid argument: `{name}` = {shown}: must be an integer in {least} ..= {most}",
            field=name,
            value=shown,
            allowed=f"an integer in {least} ..= {most}",
        )
    return n


def _short(text: str) -> str:
    """Text for a message: at most 200 characters (the library clips so too)."""
    return text if len(text) <= 200 else f"{text[:200]}… ({len(text)} characters in all)"


def _real(name: str, value: float) -> float:
    """A real argument: refused by name unless a number a float can hold."""
    try:
        return float(value)
    except OverflowError:
        shown = _short(str(value))
        raise SceneError(
            f"invalid argument: `{name}` = {shown}: must be a number a float can hold (|x| < 1.8e308)",
            field=name,
            value=shown,
            allowed="a number a float can hold (|x| < 1.8e308)",
        ) from None
    except (TypeError, ValueError):
        raise SceneError(
            f"invalid argument: `{name}` = {value!r}: must be a number",
            field=name,
            value=repr(value),
            allowed="a number",
        ) from None


def _toml_quoted(value: Any) -> str:
    """Inside a table or list a string must be quoted."""
    if isinstance(value, str):
        return json.dumps(value)
    return _toml(value)


def _overrides(set: Union[None, Mapping[str, Any], Iterable[str]]) -> List[str]:
    """`set` as the CLI's `--set key=value` list, in order."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        out = []
        for k, v in set.items():
            try:
                out.append(f"{k}={_toml(v)}")
            except SceneError as e:
                # name the key the value was given for
                raise SceneError(
                    f"set: `{k}`: {e}", field=str(k), value=e.value, allowed=e.allowed
                ) from None
        return out
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]


def _list(value: Union[str, Sequence[str]]) -> str:
    """A list of names as the CLI's comma list."""
    if isinstance(value, str):
        return value
    return ",".join(str(v) for v in value)


def _names(value: Union[None, str, Sequence[str]]) -> Optional[str]:
    """An optional list of names (None: the scene's own)."""
    return None if value is None else _list(value)


def _axes(vary: Union[str, Mapping[str, Any], Iterable[str]]) -> List[str]:
    """`vary` as the CLI's `--vary key=start:stop:count` list."""
    if isinstance(vary, str):
        return [vary]
    if isinstance(vary, Mapping):
        out = []
        for key, axis in vary.items():
            if isinstance(axis, str):
                out.append(f"{key}={axis}")
                continue
            try:
                start, stop, count = axis
            except (TypeError, ValueError):
                raise SceneError(
                    f"vary: `{key}` = {axis!r}: must be (start, stop, count)",
                    field=f"vary.{key}",
                    value=repr(axis),
                    allowed="(start, stop, count)",
                ) from None
            out.append(f"{key}={_toml(start)}:{_toml(stop)}:{_toml(count)}")
        return out
    return [str(v) for v in vary]


class _Sink:
    """Where progress goes: the caller's callable, a tqdm bar, or nowhere."""

    def __init__(self, progress: Progress, unit: str) -> None:
        self.bar: Any = None
        self.unit = unit
        self.call: Optional[Callable[[int, int], Any]] = None
        if callable(progress):
            self.call = progress
        elif progress is None or progress is True:
            try:
                from tqdm.auto import tqdm
            except ImportError:
                return
            self.tqdm = tqdm
            self.call = self._tqdm

    def _tqdm(self, done: int, total: int) -> None:
        # made at the first report: a call that fails at once shows no bar
        if self.bar is None:
            self.bar = self.tqdm(total=total, unit=self.unit, leave=False)
        if self.bar.total != total:
            self.bar.total = total
        self.bar.n = done
        self.bar.refresh()

    def __enter__(self) -> Optional[Callable[[int, int], Any]]:
        return self.call

    def __exit__(self, *exc: Any) -> None:
        if self.bar is not None:
            self.bar.close()


def _out(out: Union[None, str, "os.PathLike[str]"]) -> Optional[str]:
    return None if out is None else os.fspath(out)


def run(
    scene: Scene,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    *,
    tolerance: Optional[float] = None,
    quantity: Optional[str] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
) -> Run:
    """Run one scene (`taut run`), or choose its mesh and Δt for an accuracy
    target first (`taut run --tolerance`, docs/accuracy.md).

    Args:
        scene: a path to a scene file, or its TOML text.
        set: overrides, {"beam.tension": 2.01e4, "mesh.elements": 400}
            (the CLI's `--set`; a list of "key=value" strings works too).
        tolerance: the largest error allowed in `quantity` (relative;
            absolute for loss fractions): pilot runs measure convergence,
            the run is made at the resolution they call for, and every
            result gets an estimated error (`Run.accuracy`,
            summary["accuracy"]).
        quantity: what the tolerance is on: "force" (0–20 Hz contact force,
            the default), "force_raw", "loss_fraction", "loss_fraction_span"
            or "displacement".
        out: a folder to write the CLI's files into as well (history.csv,
            summary.json, force.svg; accuracy.csv with a tolerance).
        progress: see the module doc (steps done, steps; pilot runs done,
            runs with a tolerance).

    Returns:
        Run with `.summary` (dict of summary.json), `.history` (Table of
        history.csv's columns), `.warnings`, and with a tolerance
        `.accuracy` (Table of accuracy.csv's columns).

    Raises:
        SceneError, DivergedError, ContactError, ToleranceError, OutputError;
        KeyboardInterrupt.
    """
    path, text = _scene(scene)
    tol = None if tolerance is None else _toml(_real("tolerance", tolerance))
    with _Sink(progress, "steps" if tol is None else "runs") as p:
        summary, history, warnings, accuracy = _taut.run(
            path, text, _overrides(set), _out(out), tol, quantity, p
        )
    return Run(
        json.loads(summary),
        table(history),
        list(warnings),
        None if accuracy is None else table(accuracy),
    )


def sweep(
    scene: Scene,
    vary: Union[str, Mapping[str, Any], Iterable[str]],
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    threads: Optional[int] = None,
    *,
    log: bool = False,
    check_refinement: bool = False,
    batch: Optional[int] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """Sweep one or two scene values or dimensionless axes (`taut sweep`).

    Args:
        scene: a path to a scene file, or its TOML text.
        vary: {"carrier.speed.cruise": (50, 230, 41)} (start, stop, count;
            one or two axes, the last varying fastest), or the CLI's
            "key=start:stop:count" strings. Axes may be `speed_ratio`,
            `tension_ratio`, `mass_ratio`, `stiffness_ratio`.
        set: fixed overrides, as for run().
        threads: worker threads (default: one per core).
        log: logarithmic spacing on every axis.
        check_refinement: run each point again with 2N elements and Δt/2 and
            add the refined P_l and its change as columns.
        batch: runs stepped together when they share their matrix (1 ..= 8;
            default 4); the table is the same whatever it is.
        out: a folder for the CLI's files (sweep.csv, maps, runs/). The sweep
            is resumable there: an interrupted sweep keeps the points it
            finished, and the same call resumes from them. Without `out`
            the work happens in a temporary folder, removed afterwards.
        progress: see the module doc (points done, points).
        yes: start even when the estimated cost is above 1e11 DOF-steps
            (unknowns × steps over the runs); without it such a study raises
            SceneError with the estimate, before any run.

    Returns:
        Table of sweep.csv's columns: the swept values, speed_ratio,
        loss_fraction, loss_fraction_span, ..., error (the message of a
        point whose run stopped: its results are NaN; the sweep goes on).
    """
    path, text = _scene(scene)
    args = (_axes(vary), log, _overrides(set))
    n_threads, n_batch = _opt_ranged("threads", threads), _opt_ranged("batch", batch)
    with _Sink(progress, "runs") as p:
        if out is not None:
            cols = _taut.sweep(
                path, text, *args, os.fspath(out), True, n_threads, n_batch, check_refinement, p, yes
            )
        else:
            with tempfile.TemporaryDirectory(prefix="taut-sweep-") as tmp:
                cols = _taut.sweep(
                    path, text, *args, tmp, False, n_threads, n_batch, check_refinement, p, yes
                )
    return table(cols)


def compare(
    scene: Scene,
    formulations: Union[str, Sequence[str]] = ALL_FORMULATIONS,
    *,
    methods: Union[None, str, Sequence[str]] = None,
    discretizations: Union[None, str, Sequence[str]] = None,
    reference: str = "lagrange",
    reference_method: Optional[str] = None,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    batch: Optional[int] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """Compare contact formulations, time integrators and space
    discretizations on one scene (`taut compare`).

    Args:
        formulations: lagrange, penalty, complementarity, impact.
        methods: generalized_alpha, newmark, hht, wbz, bathe,
            central_difference, moreau_jean, modal_exact (the last on a
            galerkin or modal discretization only) (default: the scene's own).
        discretizations: hermite, "galerkin:J", "modal:J" (default: the scene's own).
        reference: the formulation differences are measured against.
        reference_method: the method they are measured against (one of methods).
        set, batch, out, progress, yes: as for sweep().

    Returns:
        Table of compare.csv's columns, one row per run; `.failed` lists
        the runs that stopped and `.skipped` the combinations that could not
        run (a method outside its stability limit), with their reasons.
    """
    path, text = _scene(scene)
    with _Sink(progress, "runs") as p:
        cols, failed, skipped = _taut.compare(
            path,
            text,
            _overrides(set),
            _list(formulations),
            _names(methods),
            _names(discretizations),
            reference,
            reference_method,
            _opt_ranged("batch", batch),
            _out(out),
            p,
            yes,
        )
    t = table(cols)
    t.failed = _not_run(failed)
    t.skipped = _not_run(skipped)
    return t


def converge(
    scene: Scene,
    refine: str = "both",
    levels: int = 4,
    ratio: float = 2.0,
    *,
    methods: Union[None, str, Sequence[str]] = None,
    discretizations: Union[None, str, Sequence[str]] = None,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """Refine mesh, step or both and measure errors, observed orders and GCI
    (`taut converge`).

    Args:
        refine: "mesh", "step" or "both".
        levels: refinement levels (≥ 3 for observed orders).
        ratio: refinement ratio between levels.
        methods, discretizations: study each side by side (default: the
            scene's own); a modal discretization refines its J.
        set, out, progress, yes: as for sweep().

    Returns:
        Table of converge.csv's columns (method, discretization, level, h,
        modes, dt, quantity, value, error, observed_order, gci, reference,
        error_order, ratio_change, formal_order, regime, omega_max_dt;
        docs/output.md); `.skipped` lists the variants that could not run
        the ladder.
    """
    path, text = _scene(scene)
    with _Sink(progress, "runs") as p:
        cols, skipped = _taut.converge(
            path,
            text,
            _overrides(set),
            refine,
            _count("levels", levels, 0),
            _real("ratio", ratio),
            _names(methods),
            _names(discretizations),
            _out(out),
            p,
            yes,
        )
    t = table(cols)
    t.skipped = _not_run(skipped)
    return t


def precision(
    scene: Scene,
    formulations: Union[str, Sequence[str]] = ALL_FORMULATIONS,
    *,
    methods: Union[None, str, Sequence[str]] = None,
    discretizations: Union[None, str, Sequence[str]] = None,
    levels: int = 3,
    ratio: int = 2,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    batch: Optional[int] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """Work against precision over a (mesh, Δt) grid, per formulation,
    method and discretization (`taut precision`). Arguments as for
    compare(); levels and ratio as the CLI's --levels and --ratio.

    Returns:
        Table of precision.csv's columns, with the Pareto flag; `.skipped`
        lists the combinations that could not run.
    """
    path, text = _scene(scene)
    with _Sink(progress, "runs") as p:
        cols, skipped = _taut.precision(
            path,
            text,
            _overrides(set),
            _list(formulations),
            _names(methods),
            _names(discretizations),
            _count("levels", levels, 0),
            _count("ratio", ratio, 0),
            _opt_ranged("batch", batch),
            _out(out),
            p,
            yes,
        )
    t = table(cols)
    t.skipped = _not_run(skipped)
    return t
