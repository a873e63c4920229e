"""`taut.Simulation`, the step-by-step API, and the
`external_force` scene key from Python: stepping gives taut.run's
numbers bit for bit, forces applied between steps act, the state reads
what the history records, bad input is refused naming the field."""

from __future__ import annotations

import json

import numpy as np
import pytest

import taut
from conftest import REFERENCE, ROOT

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.1}
T2 = ROOT / "scenes" / "t2_stationary_mass.toml"
T2_SHORT = {"mesh.elements": 60, "time.end": 0.05}


def step_to_end(sim: taut.Simulation, groups=(1, 3, 17, 2)) -> None:
    i = 0
    while not sim.done:
        sim.step(groups[i % len(groups)])
        i += 1


def test_stepping_is_run_bit_for_bit(tmp_path):
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    sim = taut.Simulation(REFERENCE, set=SHORT, out=tmp_path / "sim")
    assert sim.steps == 500 and sim.dt == 2e-4
    step_to_end(sim)
    assert sim.step(10) == 0
    s = sim.result()
    assert list(s.history) == list(r.history)
    for c in r.history:
        assert np.array_equal(r.history[c], s.history[c]), c
    for d in (r.summary, s.summary):
        d.pop("wall_seconds")
    assert r.summary == s.summary
    written = json.loads((tmp_path / "sim" / "summary.json").read_text())
    written.pop("wall_seconds")
    assert written == r.summary


def test_a_held_force_is_a_preload_change():
    """A force F held from the first step on, against the same force as a
    constant series from t = 0: the same run but for the first step, whose
    initial state the series sees and the held force does not."""
    f = -9.87  # N, + up: presses the carrier above the beam down into it
    sim = taut.Simulation(T2, set=T2_SHORT)
    sim.apply_force(0, f)
    assert sim.state.carriers[0].applied == f
    step_to_end(sim)
    held = sim.result().history["force"]
    series = {"carrier.0.external_force": {"time": [0.0, 1.0], "force": [f, f]}}
    preload = taut.run(T2, set={**T2_SHORT, "carrier.0.preload": 0.06}, progress=False)
    constant = taut.run(T2, set={**T2_SHORT, **series}, progress=False)
    plain = taut.run(T2, set=T2_SHORT, progress=False)
    # a constant series is the preload change to round-off (tests/simulation.rs)
    assert np.allclose(constant.history["force"], preload.history["force"], rtol=0, atol=1e-9)
    # the held force acts: its run ends near the preload change's force
    # and far from the run without it (9.87 N apart)
    assert abs(held[-1] - preload.history["force"][-1]) < 1.0
    assert abs(held[-1] - plain.history["force"][-1]) > 5.0


def test_state_and_w_at():
    sim = taut.Simulation(T2, set={**T2_SHORT, "probe": [{"name": "p", "x": 1.0}]})
    assert sim.step(20) == 20
    s = sim.state
    assert s.step == 20 and s.t == 20 * sim.dt
    c = s.carriers[0]
    assert c.x == 1.0 and c.in_contact and c.q_dot is not None and c.force > 0.0
    assert s.probes["p"].v == -c.w  # a carrier above: v = s·w = −w
    assert sim.w_at(1.0) == s.probes["p"].v
    step_to_end(sim)
    assert sim.done
    assert sim.result().history["force"][20] == c.force


def test_bad_input_is_refused_naming_the_field():
    sim = taut.Simulation(T2, set=T2_SHORT)
    with pytest.raises(taut.SceneError) as e:
        sim.apply_force(1, 1.0)
    assert e.value.field == "carrier" and "0 ..= 0" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        sim.apply_force(0, float("inf"))
    assert e.value.field == "newtons"
    with pytest.raises(taut.SceneError) as e:
        sim.w_at(-1.0)
    assert e.value.field == "x"
    with pytest.raises(taut.SceneError) as e:
        sim.step(-1)
    assert e.value.field == "k"
    with pytest.raises(taut.SceneError) as e:
        sim.result()
    assert "before its end" in str(e.value)
    # refused before the end, the simulation goes on
    step_to_end(sim)
    assert sim.result().history.rows > 1
    with pytest.raises(RuntimeError):
        sim.step()
    with pytest.raises(taut.SceneError) as e:
        taut.run(
            ROOT / "scenes" / "moving_force_beam.toml",
            set={"carrier.0.external_force": {"time": [0.0, 9.0], "force": [1.0, 1.0]}},
            progress=False,
        )
    assert e.value.field == "carrier.0.external_force"
    with pytest.raises(taut.SceneError) as e:
        taut.run(T2, set={**T2_SHORT, "carrier.0.external_force": {"time": [0.0, 0.01], "force": [1.0, 1.0]}}, progress=False)
    assert e.value.field == "carrier.0.external_force.time.1"


def test_a_numpy_series_reaches_the_scene():
    """An uplift series from numpy arrays through `set`."""
    t = np.linspace(0.0, 0.05, 11)
    force = -20.0 * t / 0.05
    r = taut.run(T2, set={**T2_SHORT, "carrier.0.external_force": {"time": t, "force": force}}, progress=False)
    plain = taut.run(T2, set=T2_SHORT, progress=False)
    # a carrier above: −20 N (down) presses it into the beam, ~20 N more force at the end
    assert r.history["force"][-1] - plain.history["force"][-1] > 10.0
