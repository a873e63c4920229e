"""`taut.Simulation`: one run stepped on request, for co-simulation (an
active pantograph's controller, a force law of one's own); docs/python.md.

    >>> sim = taut.Simulation("scenes/reference.toml", set={"mesh.elements": 200})
    >>> while not sim.done:
    ...     s = sim.state
    ...     sim.apply_force(0, 0.5 * (60.0 - s.carriers[0].force))
    ...     sim.step()
    >>> r = sim.result()   # a taut.Run, as taut.run gives it

With nothing applied the steps are `taut.run`'s: `result()` is the same Run,
bit for bit, however the steps were grouped.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Dict, Iterable, Mapping, Optional, Tuple, Union

from . import _taut
from ._scene import Scene
from ._table import table

if TYPE_CHECKING:
    from . import Run


@dataclass(frozen=True)
class CarrierState:
    """One carrier between steps (MODEL §2 names and signs).

    Attributes:
        x: position x_m, m.
        w: beam displacement under it, w = s·v(x_m), m (positive into the beam).
        q: mass displacement q = s·ξ, m (positive into the beam; = w for a
            moving force).
        q_dot: mass velocity, m/s (None for a moving force: no mass).
        gap: g = w − q, m.
        force: contact force λ, N, as history.csv records it.
        in_contact: the contact is closed.
        applied: the force held on the mass by apply_force, N (+ up,
            whatever `into_wire` it was given with).
    """

    x: float
    w: float
    q: float
    q_dot: Optional[float]
    gap: float
    force: float
    in_contact: bool
    applied: float


@dataclass(frozen=True)
class ProbeState:
    """One probe between steps: v(x) and its rate (+ up, as history.csv's
    probe columns; central difference keeps the half-step velocity)."""

    name: str
    x: float
    v: float
    v_dot: float


@dataclass(frozen=True)
class SimulationState:
    """The state between steps: time t (s), steps taken, each carrier's
    state and each probe's (by name)."""

    t: float
    step: int
    carriers: Tuple[CarrierState, ...]
    probes: Dict[str, ProbeState]

    def _repr_html_(self) -> str:
        from ._show import state_html

        return state_html(self)


class Simulation:
    """One run of a scene, stepped on request.

    Args:
        scene: a path to a scene file, or its TOML text.
        set: overrides, as taut.run takes them.
        out: a folder for taut.run's files (history.csv, summary.json,
            force.svg), written by result().

    Raises:
        SceneError and the other errors of taut.run.
    """

    def __init__(
        self,
        scene: Scene,
        set: Union[None, Mapping[str, Any], Iterable[str]] = None,
        *,
        out: Union[None, str, "os.PathLike[str]"] = None,
    ) -> None:
        from . import _out, _overrides, _scene

        path, text = _scene(scene)
        sets = _overrides(set)
        self._sim = _taut.Simulation(path, text, sets, _out(out))
        self._scene = (path, text, sets)
        steps, dt = self._sim.steps_dt()
        # each carrier's side (MODEL §2): +1 below the wire, −1 above
        from ._scene import load_scene

        self._toward: Tuple[float, ...] = tuple(
            1.0 if c.get("side") == "below" else -1.0
            for c in load_scene(scene, set).get("carrier", [])
        )
        self.steps: int = steps
        """The run's number of steps."""
        self.dt: float = dt
        """The time step Δt, s."""

    def step(self, k: int = 1) -> int:
        """Advance k steps (fewer at the run's end); returns how many were
        taken. Ctrl-C stops a long call between steps (KeyboardInterrupt)
        and leaves the simulation usable."""
        from . import _count

        return int(self._sim.step(_count("k", k, 0)))

    @property
    def done(self) -> bool:
        """True once the run has ended (every step taken)."""
        return bool(self._sim.done())

    @property
    def t(self) -> float:
        """The current time, s."""
        return self.state.t

    @property
    def state(self) -> SimulationState:
        """The state at the current time (a new object each read)."""
        t, step, carriers, probes = self._sim.state()
        return SimulationState(
            t=t,
            step=step,
            carriers=tuple(CarrierState(*c) for c in carriers),
            probes={p[0]: ProbeState(*p) for p in probes},
        )

    def apply_force(self, carrier: int, newtons: float, *, into_wire: bool = False) -> None:
        """Hold `newtons` on carrier `carrier`'s mass from the next step on
        until changed, on top of the scene's `external_force` series if
        any; constant over each step.

        The sign: with `into_wire=True`, positive newtons push the mass
        toward the wire (up for a carrier below it, down for one above:
        what a controller raising the contact force wants, whatever the
        side); with the default `into_wire=False`, positive is up (+v,
        MODEL §2). `toward_wire(carrier)` is the factor between the two.
        Refused (SceneError) for a moving force or an index out of range."""
        from . import _count, _real

        i = _count("carrier", carrier, 0)
        f = _real("newtons", newtons)
        if into_wire:
            f *= self.toward_wire(i)
        self._sim.apply_force(i, f)

    def toward_wire(self, carrier: int) -> float:
        """+1.0 when up is toward the wire for carrier `carrier` (a carrier
        below the wire, side = "below"), −1.0 when down is (side = "above"):
        `apply_force(c, toward_wire(c) * F)` pushes F newtons into the wire."""
        from . import _count

        i = _count("carrier", carrier, 0)
        if i >= len(self._toward):
            raise IndexError(f"carrier {i}: the scene has {len(self._toward)} carrier(s)")
        return self._toward[i]

    def w_at(self, x: float) -> float:
        """The beam displacement v(x), m (+ up, as the probes), at any x on
        the beam, at the current time."""
        from . import _real

        return float(self._sim.w_at(_real("x", x)))

    def result(self) -> "Run":
        """The run's result once every step is taken: a taut.Run, as
        taut.run gives it (and `out`'s files). Ends the simulation; refused
        (SceneError) before the end."""
        from . import Run, _wire

        summary, history, warnings, _, (snap, field), line = self._sim.finish()
        r = Run(json.loads(summary), table(history), list(warnings), None)
        r.snapshots = _wire(snap)
        r.field = _wire(field)
        r._line(line)
        r._scene = self._scene
        return r

    def __repr__(self) -> str:
        s = self.state
        return f"taut.Simulation(step {s.step} of {self.steps}, t = {s.t:.6g} s)"

    def _repr_html_(self) -> str:
        from ._show import state_html

        return state_html(self.state, self.steps)
