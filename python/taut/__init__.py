"""taut from Python: the runs and studies of the `taut` command line, as numpy
arrays, computed by the same Rust library.

    >>> import taut
    >>> r = taut.run("scenes/reference.toml", set={"mesh.elements": 200})
    >>> r.summary["carriers"][0]["loss_fraction"]
    >>> t = taut.sweep("scenes/reference.toml", vary={"carrier.speed.cruise": (50, 230, 10)})
    >>> t["loss_fraction_span"]

Every function takes a scene as a path (str or os.PathLike), a bundled
scene's name (taut.scenes()), TOML text or a dict (taut.load_scene), and
`set`, a dict of dotted keys to values: the CLI's `--set` (None removes a
key: `--unset`). The numbers are the CLI's for the same scene, bit for bit
(the module calls the same library functions and reads the same tables the
CLI writes as CSV).

While runs execute the GIL is released. Progress goes to `progress`: a
callable `progress(done, total)`, False for none, or by default a tqdm bar
when tqdm is installed (taut.set_progress(False) turns the bars off). Ctrl-C stops the work at the next step of every run
and raises KeyboardInterrupt; nothing half-written is left behind (a sweep
into `out` keeps the points it finished, and resumes from them).

Errors are exceptions with the fields of the error as attributes:
SceneError (field, value, allowed), DivergedError (step, time, quantity,
value, cause), ContactError, ToleranceError, OutputError; all derive from
TautError; a missing scene raises SceneNotFound, a FileNotFoundError too.
The API is documented in docs/python.md.
"""

from __future__ import annotations

import functools
import json
import operator
import os
import tempfile
from typing import (
    Any,
    Callable,
    Dict,
    Iterable,
    Iterator,
    List,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    TypeVar,
    Union,
    cast,
)

import numpy as np

import numpy as np

from . import _scene as _scenes
from . import _show
from . import _sweep as _sweeps
from . import _taut
from ._errors import (
    ContactError,
    DivergedError,
    OutputError,
    SceneError,
    SceneNotFound,
    TautError,
    ToleranceError,
    speak_python,
)
from ._progress import Progress, Sink, progress_enabled, set_progress
from ._scene import load_scene, scene_text, scenes
from ._simulation import CarrierState, ProbeState, Simulation, SimulationState
from ._table import Table, _not_run, table

__all__ = [
    "run",
    "sweep",
    "compare",
    "converge",
    "precision",
    "uncertainty",
    "study",
    "studies",
    "load_scene",
    "scenes",
    "scene_text",
    "set_progress",
    "progress_enabled",
    "modes",
    "mesh",
    "report",
    "Report",
    "quantities",
    "Run",
    "CarrierStats",
    "Modes",
    "WireSeries",
    "Simulation",
    "SimulationState",
    "CarrierState",
    "ProbeState",
    "Table",
    "TautError",
    "SceneError",
    "SceneNotFound",
    "DivergedError",
    "ContactError",
    "ToleranceError",
    "OutputError",
    "__version__",
]

__version__: str = _taut.__version__


def quantities() -> List[Dict[str, Any]]:
    """Every quantity taut reports, one dict each: `name` (its column in
    every table and its key in `summary["quantities"]`), `label`, `unit`,
    `definition`, `window` (what it is measured over), `smooth`, `error`
    (how its discretization error behaves) and `count`. The library's
    registry, read as it is: a quantity registered there is here too."""
    found: List[Dict[str, Any]] = json.loads(_taut.quantities())
    return found


_show.QUANTITY_LABELS.update(
    {
        q["name"]: f'{q["label"]} ({"–" if q["unit"] == "-" else q["unit"]})'
        for q in quantities()
    }
)


def _chain_sigint() -> None:
    """Make Ctrl-C stop taut calls made from any thread.

    Python runs signal handlers on the main thread only; a call made from
    a thread pool's worker (docs/python.md, "Studies that are not a grid")
    never sees a Ctrl-C, and the pool's shutdown waited for its runs to
    end. So SIGINT's handler, when the package is imported on the main
    thread, first asks every taut call at work to stop at its next step,
    then does what the handler it replaces did (raise KeyboardInterrupt,
    by default). A handler installed later replaces this one.
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return
    try:
        previous = signal.getsignal(signal.SIGINT)
    except (ValueError, AttributeError):
        return

    def handler(signum: int, frame: Any) -> Any:
        _taut.stop_running_calls()
        if callable(previous):
            return previous(signum, frame)
        if previous == signal.SIG_IGN:
            return None
        # SIG_DFL (or None: set outside Python): end as the default would
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGINT)
        return None

    try:
        signal.signal(signal.SIGINT, handler)
    except (ValueError, OSError):
        pass


_chain_sigint()

Scene = _scenes.Scene
"""A path to a scene file, a bundled scene's name, the scene's TOML text,
or the scene as a dict (docs/python.md, "Scenes")."""

# every contact formulation, in the library's order (`Formulation::ALL`)
ALL_FORMULATIONS = tuple(_taut.formulations)


def _with_lists(doc: Optional[str]) -> Optional[str]:
    """A docstring with its lists of names made from the library's enums
    (`Formulation::ALL`, `Method::ALL`, `MeshKind::ALL`), so that a new
    contact law, method or mesh kind needs no edit here."""
    if doc is None:
        return None
    kinds = [k if k == "hermite" else f'"{k}:J"' for k in _taut.mesh_kinds]
    return (
        doc.replace("{FORMULATIONS}", ", ".join(ALL_FORMULATIONS))
        .replace("{METHODS}", ", ".join(_taut.methods))
        .replace("{DISCRETIZATIONS}", ", ".join(kinds))
    )


class Run:
    """One run's results.

    Attributes:
        snapshots: v(x) at the times `[output] snapshots` asks for
            (WireSeries: `.t_requested`, `.t`, `.x`, `.v[time, point]`;
            the CLI's snapshots.csv), None when the scene asks for none.
        field: the space–time field v(x, t) of `[output] field`
            (WireSeries), None when the scene asks for none.
        spans: the contact force's statistics per carrier and span between
            `[output] supports` (Table of spans.csv's columns: carrier,
            span, x_start, x_end, samples, force_mean, force_std, force_max,
            force_min, filtered_mean, filtered_std, loss_fraction), None
            without supports.
        supports: the wire's uplift at each support (Table of
            supports.csv's columns: x, v_max, v_min, t_max, v_static,
            uplift), None without.
        standard: the standards' statistics over the analysis section
            (`[analysis]`), a row per carrier (Table of standard.csv's
            columns: carrier, x_start, x_end, band_hz, speed, speed_kmh,
            samples, mean, std, statistical_max, statistical_min, max, min,
            loss_percent, uplift_max_mm, uplift_x; docs/output.md).
        envelope: the range of v over time at every mesh node with
            `[output] envelope = true` (Table of envelope.csv's columns: x,
            v_min, v_max), None otherwise.
        x: the mesh nodes, m (a property: `taut.mesh` of the run's scene).
        summary: the dict of the CLI's `summary.json` (scene, derived
            quantities, per-carrier statistics, warnings, wall time).
        history: the columns of `history.csv` as a Table of arrays (`t`,
            `x_m`, `beam_w`, `mass_q`, `gap`, `force`, `in_contact`,
            `force_filtered` (when every step is recorded), probes;
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
        self.snapshots: Optional[WireSeries] = None
        self.field: Optional[WireSeries] = None
        self.spans: Optional[Table] = None
        self.supports: Optional[Table] = None
        self.envelope: Optional[Table] = None
        self.standard: Table = Table()
        self._scene: Optional[Tuple[Optional[str], Optional[str], List[str]]] = None
        self._x: Optional[np.ndarray] = None

    def _line(
        self,
        line: Tuple[
            Optional[List[Tuple[str, str, Any]]],
            Optional[List[Tuple[str, str, Any]]],
            Optional[List[Tuple[str, str, Any]]],
            List[Tuple[str, str, Any]],
        ],
    ) -> None:
        spans, supports, envelope, standard = line
        self.spans = None if spans is None else table(spans)
        self.supports = None if supports is None else table(supports)
        self.envelope = None if envelope is None else table(envelope)
        self.standard = table(standard)

    @property
    def x(self) -> np.ndarray:
        """The mesh nodes of the run's scene, m (`taut.mesh`; computed on
        first use)."""
        if self._x is None:
            if self._scene is None:
                raise ValueError("Run.x: this Run was not made by taut.run")
            self._x = _f8(_taut.mesh(*self._scene))
        return self._x

    def __repr__(self) -> str:
        carriers = self.summary.get("carriers", [])
        loss = ", ".join(_round(c.get("loss_fraction")) for c in carriers)
        if len(carriers) != 1:
            loss = f"[{loss}]"
        f = (carriers[0].get("force_filtered") or {}) if carriers else {}
        force = (
            f", 0–{_round(f.get('cutoff_hz'))} Hz force {_round(f.get('mean'))} ± {_round(f.get('std'))} N"
            if f
            else ""
        )
        return (
            f"taut.Run({self.history.rows} rows, P_l = {loss}{force}, "
            f"{len(self.warnings)} warning{'' if len(self.warnings) == 1 else 's'})"
        )

    @property
    def scalars(self) -> Dict[str, Any]:
        """The summary's numbers as flat names, those of sweep.csv's
        columns: carrier 0's statistics (`loss_fraction`, `force_std` for
        summary["carriers"][0]["force"]["std"], ...) and the derived
        figures (`speed_ratio`, `wave_speed`, `dofs`, ...). Each is an
        attribute too: `run.force_std`."""
        carriers = self.summary.get("carriers") or [{}]
        values = self.summary.get("quantities") or [{}]
        flat = _study_names(_flat(carriers[0]), values[0])
        for k, v in _flat(self.summary.get("derived", {})).items():
            flat.setdefault(k, v)
        flat.setdefault("wall_seconds", self.summary.get("wall_seconds"))
        return flat

    @property
    def carriers(self) -> List["CarrierStats"]:
        """Each carrier's statistics with the same flat names:
        run.carriers[1].force_std."""
        values = self.summary.get("quantities") or []
        return [
            CarrierStats(_study_names(_flat(c), values[i] if i < len(values) else {}))
            for i, c in enumerate(self.summary.get("carriers", []))
        ]

    def __getattr__(self, name: str) -> Any:
        # only for names that are not attributes: the summary's scalars
        if name.startswith("_") or name in ("summary", "history", "warnings", "accuracy"):
            raise AttributeError(name)
        flat = self.scalars
        if name in flat:
            return flat[name]
        raise AttributeError(
            f"taut.Run has no attribute {name!r}; its summary figures are {', '.join(flat)}"
        )

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.scalars))

    def _repr_html_(self) -> str:
        return _show.run_html(
            self.scalars, len(self.summary.get("carriers", [])), self.history.rows, self.warnings
        )

    def plot(self, ax: Any = None) -> Any:
        """Draw what the CLI's force.svg draws (matplotlib, `taut[plot]`):
        each carrier's contact force along x_m/L (along t when no carrier
        moves), lost contact shaded. Returns the matplotlib Axes."""
        length = float(self.summary["scene"]["beam"]["length"])
        band = ((self.summary.get("carriers") or [{}])[0].get("force_filtered") or {}).get("cutoff_hz", 20.0)
        return _show.plot_run(self.history, len(self.summary.get("carriers", [])), length, ax, band)


class CarrierStats:
    """One carrier's statistics as attributes with sweep.csv's names
    (`loss_fraction`, `force_std`, ...); `.scalars` is the dict."""

    def __init__(self, scalars: Dict[str, Any]) -> None:
        self.scalars: Dict[str, Any] = scalars

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name == "scalars":
            raise AttributeError(name)
        try:
            return self.scalars[name]
        except KeyError:
            raise AttributeError(
                f"no carrier figure {name!r}; there are {', '.join(self.scalars)}"
            ) from None

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.scalars))

    def __repr__(self) -> str:
        return f"taut.CarrierStats(loss_fraction={_round(self.scalars.get('loss_fraction'))})"


def _round(v: Any) -> str:
    """A figure as a person reads it: 4 significant digits (a repr, not the
    value: the attributes hold every digit)."""
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _study_names(flat: Dict[str, Any], values: Mapping[str, Any]) -> Dict[str, Any]:
    """The carrier's quantities under the names every table gives them
    (summary["quantities"], the library's registry: `filtered_force_mean`,
    `displacement_max`, ...), then the rest of its statistics under their
    flat summary names."""
    out: Dict[str, Any] = dict(values)
    for k, v in flat.items():
        out.setdefault(k, v)
    return out


def _flat(d: Mapping[str, Any], prefix: str = "") -> Dict[str, Any]:
    """The scalars of a nested dict under `_`-joined names (lists left out)."""
    out: Dict[str, Any] = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, Mapping):
            out.update(_flat(v, name + "_"))
        elif v is None or isinstance(v, (bool, int, float, str)):
            out[name] = v
    return out


_F = TypeVar("_F", bound=Callable[..., Any])


def _speaks_python(f: _F) -> _F:
    """A public function whose errors speak in its terms (`quantity=`,
    `set=`, not the CLI's `--quantity`, `--set`: `_errors.speak_python`)."""

    @functools.wraps(f)
    def wrapped(*args: Any, **kwargs: Any) -> Any:
        try:
            return f(*args, **kwargs)
        except TautError as e:
            speak_python(e)
            raise

    return cast(_F, wrapped)


def _f8(data: bytes) -> np.ndarray:
    """Little-endian f64 bytes of the native module as a writable array."""
    return np.frombuffer(data, dtype="<f8").astype(np.float64, copy=True)


class WireSeries:
    """The wire's displacement v along the span at a series of times
    (docs/output.md#snapshots): v is the beam displacement, positive up, m,
    as the probes record it, evaluated with the discretization's own
    interpolation.

    Attributes:
        t_requested: the times asked for, s (for the field, equal to `t`).
        t: the time of the step recorded, s (the step nearest the time
            asked for).
        x: the points, m.
        v: v[k, i] = v(x[i]) at t[k], m.
    """

    def __init__(self, t_requested: np.ndarray, t: np.ndarray, x: np.ndarray, v: np.ndarray) -> None:
        self.t_requested: np.ndarray = t_requested
        self.t: np.ndarray = t
        self.x: np.ndarray = x
        self.v: np.ndarray = v

    def __iter__(self) -> Iterator[np.ndarray]:
        """(t, x, v): `t, x, v = run.snapshots`."""
        return iter((self.t, self.x, self.v))

    def __repr__(self) -> str:
        return f"taut.WireSeries({len(self.t)} times × {len(self.x)} points)"


def _wire(data: Optional[Tuple[bytes, bytes, bytes, bytes]]) -> Optional[WireSeries]:
    if data is None:
        return None
    req, t, x, v = (_f8(b) for b in data)
    return WireSeries(req, t, x, v.reshape(len(t), len(x)))


class Modes:
    """A scene's natural frequencies and mode shapes (`taut modes`,
    docs/output.md#modes).

    Attributes:
        frequency_hz: f_j, Hz, ascending.
        source: "fe_eigen" (the FE eigenproblem of the scene's mesh,
            attachments included) or "exact" (the continuous beam's modes,
            for mesh.kind = "galerkin").
        string_hz: the taut string's j c / (2L), Hz, NaN where it does not
            apply (T = 0, a free end, or attachments).
        x: the points the shapes are sampled at (the mesh nodes), m.
        shapes: shapes[j, i] = φ_j(x[i]), mass-normalized (kg^-1/2), the
            largest sample of each shape positive.
        table: the columns of modes.csv; shapes_table: those of
            mode_shapes.csv.
    """

    def __init__(self, table: Table, shapes_table: Table) -> None:
        self.table: Table = table
        self.shapes_table: Table = shapes_table
        self.frequency_hz: np.ndarray = table["frequency_hz"]
        self.string_hz: np.ndarray = table["string_hz"]
        sources = table["source"]
        self.source: str = str(sources[0]) if len(sources) else ""
        self.x: np.ndarray = shapes_table["x"]
        names = [k for k in shapes_table.keys() if k != "x"]
        self.shapes: np.ndarray = (
            np.stack([shapes_table[k] for k in names])
            if names
            else np.empty((0, len(self.x)))
        )

    def __repr__(self) -> str:
        return f"taut.Modes({len(self.frequency_hz)} modes, {self.source}, {len(self.x)} points)"

    def _repr_html_(self) -> str:
        return _show.modes_html(self.frequency_hz, self.string_hz, self.source, len(self.x))


def _scene(scene: Scene) -> Tuple[Optional[str], Optional[str]]:
    """(path, text) of a scene: a file, a bundled scene's name, TOML text
    or a dict (the rules of `taut._scene`); a missing file raises
    SceneNotFound."""
    return _scenes.source(scene)


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


def _word(value: Any) -> Any:
    """A command option's value as the library reads it (`taut._taut`
    `args`, JSON): numbers as their text, so that every int Python has and
    every float reach the library's range check exactly (its errors name
    the keyword, the value and the range); None, strings and switches as
    they are, lists item by item."""
    if value is None or isinstance(value, (str, bool)):
        return value
    if isinstance(value, (list, tuple)):
        return [_word(v) for v in value]
    if isinstance(value, float):
        return repr(value)
    if hasattr(value, "__index__"):
        return str(operator.index(value))
    return repr(value)


def _options(**words: Any) -> str:
    """A command's options as JSON for `taut._taut` (its `args`): the
    library's struct of the same command, the CLI's flags (`taut.app.args`),
    declared once there; the keys given are the Python keywords."""
    return json.dumps({k: _word(v) for k, v in words.items()})


def _short(text: str) -> str:
    """Text for a message: at most 200 characters (the library clips so too)."""
    return text if len(text) <= 200 else f"{text[:200]}… ({len(text)} characters in all)"


def _real(name: str, value: float) -> float:
    """A real argument: refused by name unless a number a float can hold
    (a str is not a number, though float() reads one; nor is a bool)."""
    if isinstance(value, (str, bytes, bytearray, bool)):
        raise SceneError(
            f"invalid argument: `{name}` = {_short(repr(value))}: must be a number, not {type(value).__name__}",
            field=name,
            value=_short(repr(value)),
            allowed="a number",
        )
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
    """`set` as the library's override list, in order: a str value is a
    TOML string, None removes the key (`taut._scene.overrides`)."""
    try:
        return _scenes.overrides(set)
    except SceneError as e:
        raise SceneError(f"set: {e}", field=e.field, value=e.value, allowed=e.allowed) from None


def _list(value: Union[str, Sequence[str]]) -> str:
    """A list of names as the CLI's comma list."""
    if isinstance(value, str):
        return value
    return ",".join(str(v) for v in value)


def _names(value: Union[None, str, Sequence[str]]) -> Optional[str]:
    """An optional list of names (None: the scene's own)."""
    return None if value is None else _list(value)


def _grid_axes(t: Table, vary: List[str]) -> None:
    """Give a grid sweep's table its axes (key, values): the axis columns,
    in grid order (the last axis fastest), reshaped."""
    keys, counts = [], []
    for v in vary:
        key, _, rng = v.partition("=")
        keys.append(key.strip())
        counts.append(int(rng.rsplit(":", 1)[1]) if ":" in rng else len(rng.split(",")))
    if t.rows != int(np.prod(counts)) or any(k not in t for k in keys):
        return
    axes = []
    for i, k in enumerate(keys):
        g = t[k].reshape(counts)
        axes.append((k, g[tuple(slice(None) if j == i else 0 for j in range(len(keys)))].copy()))
    t.axes = axes


_Sink = Sink
"""Where a call's progress goes (`taut._progress.Sink`)."""


def _out(out: Union[None, str, "os.PathLike[str]"]) -> Optional[str]:
    return None if out is None else os.fspath(out)


@_speaks_python
def run(
    scene: Scene,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    *,
    tolerance: Optional[float] = None,
    quantity: Optional[str] = None,
    max_cost: Optional[float] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
) -> Run:
    """Run one scene (`taut run`), or choose its mesh and Δt for an accuracy
    target first (`taut run --tolerance`, docs/accuracy.md).

    Args:
        scene: a path to a scene file, or its TOML text.
        set: overrides, {"beam.tension": 2.01e4, "mesh.elements": 400}
            (the CLI's `--set`; a list of "key=value" strings works too).
        tolerance: the largest u_num allowed in `quantity` (absolute, in
            its unit): the scene is refined as the one point of
            `sweep(..., tolerance=...)`, with the same resolution, value and
            u_num, and every result gets a u_num (`Run.accuracy`,
            summary["accuracy"]); a tolerance not reached raises
            ToleranceError.
        quantity: what the tolerance is on: a quantity `sweep` takes
            ("loss_fraction_span", the default; "force_mean", …).
        max_cost: with `tolerance`, the most the run may cost, pilots
            included, as a multiple of its run at the scene's resolution
            (default 64).
        out: a folder to write the CLI's files into as well (history.csv,
            summary.json, force.svg; accuracy.csv with a tolerance).
        progress: see the module doc (steps done, steps; with a tolerance,
            0 of 1 run at the start and 1 of 1 at the end).

    Returns:
        Run with `.summary` (dict of summary.json), `.history` (Table of
        history.csv's columns), `.warnings`, and with a tolerance
        `.accuracy` (Table of accuracy.csv's columns).

    Raises:
        SceneError, DivergedError, ContactError, ToleranceError, OutputError;
        KeyboardInterrupt.
    """
    path, text = _scene(scene)
    sets = _overrides(set)
    args = _options(tolerance=tolerance, quantity=quantity, max_cost=max_cost)
    with _Sink(progress, "steps" if tolerance is None else "runs") as p:
        summary, history, warnings, accuracy, (snap, field), line = _taut.run(
            (path, text, sets), _out(out), p, args
        )
    r = Run(
        json.loads(summary),
        table(history),
        list(warnings),
        None if accuracy is None else table(accuracy),
    )
    r.snapshots = _wire(snap)
    r.field = _wire(field)
    r._line(line)
    r._scene = (path, text, sets)
    return r


@_speaks_python
def sweep(
    scene: Scene,
    vary: Optional[_sweeps.Vary] = None,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    *,
    points: Optional[_sweeps.Points] = None,
    shard: Optional[str] = None,
    threads: Optional[int] = None,
    log: bool = False,
    check_refinement: bool = False,
    batch: Optional[int] = None,
    tolerance: Optional[float] = None,
    quantity: Optional[str] = None,
    max_cost: Optional[float] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """Sweep one or two scene values or dimensionless axes over their grid,
    or run a list of points (`taut sweep`, `--vary` / `--points`), on the
    sweep's engine (batched, parallel, resumable into `out`).

    Args:
        scene: a path, a bundled scene's name, TOML text or a dict.
        vary: {"carrier.speed.cruise": (50, 230, 41)} (a tuple is start,
            stop, count), {"beam.tension": [2e4, 2.5e4, 3e4]} (a list or a
            numpy array is the values, in order); one or two axes, the last
            varying fastest; or the CLI's "key=start:stop:count" /
            "key=v1,v2" strings. Axes may be `speed_ratio`,
            `tension_ratio`, `mass_ratio`, `stiffness_ratio`.
        set: fixed overrides, as for run().
        points: instead of `vary`, a list of points [{key: value, ...},
            ...] (a Latin hypercube, an optimizer's proposals; a dict of
            columns or a pandas DataFrame too): each is one run, in order.
        shard: "i/n": run only the points with index ≡ i (mod n), into
            `out` (the CLI's `--shard`; join the folders with `taut merge`).
        threads: worker threads (default: one per core).
        log: logarithmic spacing on every axis.
        check_refinement: run each point again with 2N elements and Δt/2 and
            add the refined P_l and its change as columns.
        batch: runs stepped together when they share their matrix (1 ..= 8;
            default 4); the table is the same whatever it is.
        tolerance: refine each point until the numerical uncertainty of
            `quantity` is at most this (absolute, in its unit), only as far
            as it must (`taut sweep --tolerance`); adds the columns u_num,
            tolerance_met, elements_used, modes_used, dt_used, runs_used,
            dof_steps_used and estimator.
        quantity: what `tolerance` is on: a column of the table
            ("loss_fraction_span", the default;
            "loss_fraction_span_sustained", "loss_fraction",
            "loss_fraction_support", "force_mean", "force_std", "force_max",
            "force_min", "first_loss_position").
        max_cost: with `tolerance`, the most a point may cost, pilots
            included, as a multiple of its run at the scene's resolution
            (default 64).
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
        Besides: `.axes` (a grid's [(key, values)]; `.grid(column)` is a
        column in the grid's shape), `.span_force` and `.span_loss`
        (points × bins along x/L at `.span_x`: the CLI's sweep_force.csv
        and sweep_loss.csv), `.warnings` (each point's warning texts).
    """
    if (vary is None) == (points is None):
        raise SceneError(
            "sweep: give `vary` (a grid) or `points` (a list of points), one of the two",
            field="vary",
            value=None if vary is None else repr(vary)[:200],
            allowed="vary= or points=",
        )
    path, text = _scene(scene)
    axes = _sweeps.axes(vary) if vary is not None else _sweeps.points(points)
    paired = points is not None
    on = (path, text, _overrides(set))
    args = _options(
        vary=axes,
        paired=paired,
        log=log,
        shard=shard,
        check_refinement=check_refinement,
        tolerance=tolerance,
        quantity=quantity,
        max_cost=max_cost,
        threads=threads,
        batch=batch,
        yes=yes,
    )

    def call(folder: str, files: bool) -> Table:
        cols = _taut.sweep(on, folder, files, p, args)
        t = table(cols)
        t.paired = paired
        for k, v in _sweeps.span_profiles(folder, t.rows).items():
            setattr(t, k, v)
        return t

    with _Sink(progress, "runs") as p:
        if out is not None:
            t = call(os.fspath(out), True)
        else:
            with tempfile.TemporaryDirectory(prefix="taut-sweep-") as tmp:
                t = call(tmp, False)
    if not paired:
        _grid_axes(t, axes)
    return t


@_speaks_python
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
        formulations: {FORMULATIONS}.
        methods: {METHODS} (modal_exact on a galerkin or modal
            discretization only) (default: the scene's own).
        discretizations: {DISCRETIZATIONS} (default: the scene's own).
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
            (path, text, _overrides(set)),
            _out(out),
            p,
            _options(
                formulations=_list(formulations),
                methods=_names(methods),
                discretizations=_names(discretizations),
                reference=reference,
                reference_method=reference_method,
                batch=batch,
                yes=yes,
            ),
        )
    t = table(cols)
    t.failed = _not_run(failed)
    t.skipped = _not_run(skipped)
    return t


compare.__doc__ = _with_lists(compare.__doc__)


@_speaks_python
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
            (path, text, _overrides(set)),
            _out(out),
            p,
            _options(
                refine=refine,
                levels=levels,
                ratio=ratio,
                methods=_names(methods),
                discretizations=_names(discretizations),
                yes=yes,
            ),
        )
    t = table(cols)
    t.skipped = _not_run(skipped)
    return t


@_speaks_python
def uncertainty(
    scene: Scene,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    *,
    levels: int = 4,
    max_cost: Optional[float] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    yes: bool = False,
) -> Table:
    """The numerical uncertainty of every reported quantity of a scene
    (`taut uncertainty`, docs/verification.md "Solution verification"): a
    family of runs refined in space (h, or J) and time (Δt) together and
    apart, and for each quantity its value, u_num, the estimator (Roache's
    GCI, or Eça & Hoekstra's least squares for scattered data), the
    observed orders the data support and the share of the error from space.

    Args:
        levels: diagonal levels K (3 ..= 6; 2K − 1 runs, the finest 4^(K−1)
            times the scene's run).
        max_cost: the most the family may cost, in runs of the scene, when
            a pre-asymptotic level 0 calls for one finer level (default 128).
        set, out, progress, yes: as for sweep().

    Returns:
        Table of uncertainty.csv's columns (quantity, unit, smooth, value,
        u_num, u_relative, error, extrapolated, safety_factor, estimator,
        fit, behaviour, observed_order, formal_order, order_space,
        order_time, space_share, asymptotic, sigma, data_range, value_scene,
        u_scene, note; docs/output.md); `.family` is a Table of its runs
        (role, level, elements, modes, h, dt, steps, dofs).
    """
    path, text = _scene(scene)
    with _Sink(progress, "runs") as p:
        cols, family = _taut.uncertainty(
            (path, text, _overrides(set)),
            _out(out),
            p,
            _options(levels=levels, max_cost=max_cost, yes=yes),
        )
    t = table(cols)
    t.family = table(family)
    return t


def studies() -> List[Tuple[str, str]]:
    """Every study of one scene the library offers as a command, as
    `(name, help)`: the names `study()` takes (`taut <name>` on the
    command line)."""
    return list(_taut.studies())


@_speaks_python
def study(
    name: str,
    scene: Scene,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    *,
    out: Union[None, str, "os.PathLike[str]"] = None,
    progress: Progress = None,
    **options: Any,
) -> Dict[str, Table]:
    """Any study of one scene the library offers as a command (`taut
    <name>`; `studies()` lists them), its options as keywords with the
    CLI's names (`taut <name> --help`: `--reference-method` is
    `reference_method`; a list may be a sequence of names). A study added
    to the library is offered here with no edit of this package;
    `compare()`, `converge()`, `precision()` and `uncertainty()` are the
    same studies with their own signatures and docs.

    Args:
        name: the study's command (`"converge"`).
        set, out, progress: as for sweep().
        options: the study's options.

    Returns:
        Its tables by the file each is written as (`"converge.csv"`).
    """
    path, text = _scene(scene)
    words = {k: _list(v) if isinstance(v, (list, tuple)) else v for k, v in options.items()}
    with _Sink(progress, "runs") as p:
        found = _taut.study_tables(
            name, (path, text, _overrides(set)), _out(out), p, _options(**words)
        )
    return {file: table(cols) for file, cols in found}


@_speaks_python
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
            (path, text, _overrides(set)),
            _out(out),
            p,
            _options(
                formulations=_list(formulations),
                methods=_names(methods),
                discretizations=_names(discretizations),
                levels=levels,
                ratio=ratio,
                batch=batch,
                yes=yes,
            ),
        )
    t = table(cols)
    t.skipped = _not_run(skipped)
    return t


@_speaks_python
def modes(
    scene: Scene,
    count: Optional[int] = None,
    *,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
) -> Modes:
    """The natural frequencies and mode shapes of the scene's beam (`taut
    modes`): the FE eigenproblem of its mesh with the attachments, or the
    exact continuous modes for mesh.kind = "galerkin".

    Args:
        scene: a path to a scene file, or its TOML text.
        count: how many modes (default 10, or the mesh's unknowns if fewer).
        set: overrides, as for `run`.
        out: a folder to write modes.csv and mode_shapes.csv into as well.

    Returns:
        Modes with `.frequency_hz`, `.source`, `.string_hz`, `.x`,
        `.shapes[mode, point]`.

    Raises:
        SceneError (a bad scene or count), OutputError.
    """
    path, text = _scene(scene)
    freq, shapes = _taut.modes((path, text, _overrides(set)), _out(out), _options(count=count))
    return Modes(table(freq), table(shapes))


@_speaks_python
def mesh(
    scene: Scene,
    *,
    set: Union[None, Mapping[str, Any], Iterable[str]] = None,
) -> np.ndarray:
    """The mesh nodes of the scene, m (for mesh.kind = "galerkin", which has
    no mesh, those of the uniform mesh of mesh.elements elements): where
    snapshots, the field and mode shapes are sampled by default."""
    path, text = _scene(scene)
    return _f8(_taut.mesh(path, text, _overrides(set)))


class Report(str):
    """The path of a page `report` wrote (a `str`, usable wherever the path
    is), with what the page holds and what it does not.

    Attributes:
        plots: plots embedded.
        tables: tables shown.
        left_out: each file that could not be shown, as "path: reason"
            (a symbolic link, not a regular file, too large, not UTF-8, not
            an SVG, a JSON that does not parse).
        not_shown: each file the page names but does not show by design,
            as "path: reason" (a time series drawn in a plot, a table's
            JSON twin, a file taut does not write).
        incomplete: the folders marked INCOMPLETE, shown as partial.
    """

    plots: int
    tables: int
    left_out: List[str]
    not_shown: List[str]
    incomplete: List[str]


@_speaks_python
def report(
    dirs: Union[str, "os.PathLike[str]", Iterable[Union[str, "os.PathLike[str]"]]],
    out: Union[None, str, "os.PathLike[str]"] = None,
) -> Report:
    """One self-contained report.html (plots as embedded images, inline
    CSS, no script, nothing fetched) from the outputs taut wrote into one
    or more folders (`taut report`): a first section of every folder's
    verdicts, then per folder each command's summary, tables (verdicts
    coloured, a compared run's warnings under its row) and plots; a file
    not shown is named with the reason (docs/output.md).

    Args:
        dirs: a folder, or a list of folders, given as `out=` to taut.run,
            compare, converge, precision, uncertainty, modes or sweep (or
            the CLI's --out).
        out: the page (default: report.html in the folder when there is
            one, out/report.html for several).

    Returns:
        The page's path, a `Report` (a `str`) whose `left_out`,
        `not_shown` and `incomplete` list what the page leaves out.

    Raises:
        SceneError naming a folder that holds no taut outputs; OutputError.
    """
    if isinstance(dirs, (str, os.PathLike)):
        dirs = [dirs]
    path, plots, tables, left_out, not_shown, incomplete = _taut.report(
        [os.fspath(d) for d in dirs], _out(out)
    )
    page = Report(path)
    page.plots, page.tables = plots, tables
    page.left_out, page.not_shown, page.incomplete = list(left_out), list(not_shown), list(incomplete)
    return page
