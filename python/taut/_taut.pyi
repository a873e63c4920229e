"""Type stubs of the native module `taut._taut` (python/src/lib.rs).

Not for direct use: `taut.run`, `taut.sweep`, `taut.compare`,
`taut.converge`, `taut.precision` and `taut.uncertainty`
(python/taut/__init__.py) call these
with their options as JSON (the library's `taut::app::args`, the CLI's
flags) and turn their `(name, kind, data)` columns into
numpy arrays (python/taut/_table.py).
"""

from typing import Callable, List, Optional, Tuple, Union, final

__version__: str
taut_version: str
formulations: List[str]
methods: List[str]
mesh_kinds: List[str]

__all__ = [
    "Simulation",
    "__version__",
    "bundled_scenes",
    "compare",
    "converge",
    "formulations",
    "mesh",
    "mesh_kinds",
    "methods",
    "modes",
    "most_point_keys",
    "quantities",
    "precision",
    "report",
    "run",
    "scene_json",
    "schema",
    "studies",
    "study_tables",
    "stop_running_calls",
    "sweep",
    "taut_version",
    "uncertainty",
]

_Column = Tuple[str, str, Union[bytes, List[Optional[str]]]]
_NotRun = Tuple[str, str, str, str]
_Progress = Optional[Callable[[int, int], object]]
_Wire = Optional[Tuple[bytes, bytes, bytes, bytes]]
_Line = Tuple[
    Optional[List[_Column]], Optional[List[_Column]], Optional[List[_Column]], List[_Column]
]

# (path, text, set): a scene file or its TOML text, and the overrides
_SceneArg = Tuple[Optional[str], Optional[str], List[str]]

# `args` of each command: its options as JSON (the library's
# taut::app::args structs, the CLI's flags)
def run(
    on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> Tuple[
    str, List[_Column], List[str], Optional[List[_Column]], Tuple[_Wire, _Wire], _Line
]: ...
def sweep(
    on: _SceneArg, out: str, files: bool, progress: _Progress, args: str
) -> List[_Column]: ...
def compare(
    on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> Tuple[List[_Column], List[_NotRun], List[_NotRun]]: ...
def converge(
    on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> Tuple[List[_Column], List[_NotRun]]: ...
def precision(
    on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> Tuple[List[_Column], List[_NotRun]]: ...
def study_tables(
    name: str, on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> List[Tuple[str, List[_Column]]]: ...
def studies() -> List[Tuple[str, str]]: ...
def schema() -> List[Tuple[str, List[Tuple[str, Optional[str], str]]]]: ...
def uncertainty(
    on: _SceneArg, out: Optional[str], progress: _Progress, args: str
) -> Tuple[List[_Column], List[_Column]]: ...
def scene_json(path: Optional[str], text: Optional[str], set: List[str]) -> str: ...
def bundled_scenes() -> List[Tuple[str, str]]: ...
def modes(
    on: _SceneArg, out: Optional[str], args: str
) -> Tuple[List[_Column], List[_Column]]: ...
def mesh(path: Optional[str], text: Optional[str], set: List[str]) -> bytes: ...
def report(
    dirs: List[str], out: Optional[str]
) -> Tuple[str, int, int, List[str], List[str], List[str]]: ...
def stop_running_calls() -> bool: ...
def most_point_keys() -> int: ...
def quantities() -> str: ...

_CarrierTuple = Tuple[float, float, float, Optional[float], float, float, bool, float]
_ProbeTuple = Tuple[str, float, float, float]

@final
class Simulation:
    def __new__(
        cls, path: Optional[str], text: Optional[str], set: List[str], out: Optional[str]
    ) -> "Simulation": ...
    def step(self, k: int) -> int: ...
    def done(self) -> bool: ...
    def steps_dt(self) -> Tuple[int, float]: ...
    def apply_force(self, carrier: int, newtons: float) -> None: ...
    def state(self) -> Tuple[float, int, List[_CarrierTuple], List[_ProbeTuple]]: ...
    def w_at(self, x: float) -> float: ...
    def finish(
        self,
    ) -> Tuple[
        str,
        List[_Column],
        List[str],
        Optional[List[_Column]],
        Tuple[_Wire, _Wire],
        _Line,
    ]: ...
