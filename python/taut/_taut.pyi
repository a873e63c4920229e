"""Type stubs of the native module `taut._taut` (python/src/lib.rs).

Not for direct use: `taut.run`, `taut.sweep`, `taut.compare`,
`taut.converge`, `taut.precision` and `taut.uncertainty`
(python/taut/__init__.py) call these
with the CLI's words and turn their `(name, kind, data)` columns into
numpy arrays (python/taut/_table.py).
"""

from typing import Callable, List, Optional, Tuple, Union, final

__version__: str
taut_version: str

__all__ = [
    "Simulation",
    "__version__",
    "bundled_scenes",
    "compare",
    "converge",
    "level_ranges",
    "limits",
    "mesh",
    "modes",
    "precision",
    "run",
    "scene_json",
    "sweep",
    "taut_version",
    "uncertainty",
]

_Column = Tuple[str, str, Union[bytes, List[Optional[str]]]]
_NotRun = Tuple[str, str, str, str]
_Progress = Optional[Callable[[int, int], object]]
_Wire = Optional[Tuple[bytes, bytes, bytes, bytes]]
_Line = Tuple[Optional[List[_Column]], Optional[List[_Column]], Optional[List[_Column]]]

def run(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    out: Optional[str],
    tolerance: Optional[str],
    quantity: Optional[str],
    progress: _Progress,
) -> Tuple[
    str, List[_Column], List[str], Optional[List[_Column]], Tuple[_Wire, _Wire], _Line
]: ...
def limits() -> Tuple[int, int]: ...
def sweep(
    path: Optional[str],
    text: Optional[str],
    vary: List[str],
    log: bool,
    set: List[str],
    out: str,
    files: bool,
    threads: Optional[int],
    batch: Optional[int],
    check_refinement: bool,
    progress: _Progress,
    yes: bool,
    points: bool = False,
    tolerance: Optional[str] = None,
    quantity: Optional[str] = None,
    max_cost: Optional[str] = None,
) -> List[_Column]: ...
def compare(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    formulations: str,
    methods: Optional[str],
    discretizations: Optional[str],
    reference: str,
    reference_method: Optional[str],
    batch: Optional[int],
    out: Optional[str],
    progress: _Progress,
    yes: bool,
) -> Tuple[List[_Column], List[_NotRun], List[_NotRun]]: ...
def converge(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    refine: str,
    levels: int,
    ratio: float,
    methods: Optional[str],
    discretizations: Optional[str],
    out: Optional[str],
    progress: _Progress,
    yes: bool,
) -> Tuple[List[_Column], List[_NotRun]]: ...
def precision(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    formulations: str,
    methods: Optional[str],
    discretizations: Optional[str],
    levels: int,
    ratio: int,
    batch: Optional[int],
    out: Optional[str],
    progress: _Progress,
    yes: bool,
) -> Tuple[List[_Column], List[_NotRun]]: ...
def uncertainty(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    levels: int,
    out: Optional[str],
    progress: _Progress,
    yes: bool,
) -> Tuple[List[_Column], List[_Column]]: ...
def scene_json(path: Optional[str], text: Optional[str], set: List[str]) -> str: ...
def level_ranges() -> Tuple[Tuple[int, int], Tuple[int, int], Tuple[int, int]]: ...
def bundled_scenes() -> List[Tuple[str, str]]: ...
def modes(
    path: Optional[str],
    text: Optional[str],
    set: List[str],
    count: Optional[int],
    out: Optional[str],
) -> Tuple[List[_Column], List[_Column]]: ...
def mesh(path: Optional[str], text: Optional[str], set: List[str]) -> bytes: ...

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
