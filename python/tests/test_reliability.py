"""Python's messages under hostile input: every bad argument raises SceneError naming
the argument or key and the real range, never a bare Python or numpy error,
and an empty `out` is refused (it would write into the current folder);
and the third hostile round's Python findings (below): droppers past the memory budget,
a removal's field, `progress`, strings for numbers, points, two sweeps
into one folder, Ctrl-C of runs in a thread pool."""

import os
import threading
import time

import numpy as np
import re

import pytest
from conftest import REFERENCE, ctrl_c

import taut

SHORT = {"mesh.elements": 20, "time.end": 0.01}


def test_tolerance_too_large_for_a_float_is_a_scene_error():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set=SHORT, tolerance=10**400)
    assert e.value.field == "tolerance"
    assert len(str(e.value)) < 400


def test_a_numpy_array_as_a_set_value_names_its_key():
    # an array is a list value: the scene check names the key
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={**SHORT, "beam.tension": np.array([1.0, 2.0])})
    assert "beam.tension" in str(e.value)
    # a numpy scalar is its number
    r = taut.run(REFERENCE, set={**SHORT, "beam.tension": np.float64(3e4)})
    assert r.summary["scene"]["beam"]["tension"] == 3e4


@pytest.mark.parametrize("name", ["threads", "batch"])
def test_counts_out_of_range_name_the_real_range(name):
    # the library checks the count (taut::app::args) and names its range
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, vary={"speed_ratio": (0.5, 1.0, 2)}, set=SHORT, **{name: -1})
    assert e.value.field == name and e.value.value == "-1"
    assert re.search(r"1 \.\.= [1-9][0-9]*", e.value.allowed), e.value.allowed


def test_an_empty_out_is_refused(tmp_path, monkeypatch):
    scene = str(REFERENCE)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(taut.SceneError) as e:
        taut.run(scene, set=SHORT, out="")
    assert e.value.field == "out"
    assert not (tmp_path / "summary.json").exists()


def test_a_sweep_over_an_axis_a_plot_cannot_draw_returns_its_table(tmp_path):
    # this once hung in the plotting library's tick code after the tables
    # (a carrier's stiffness is held to the wire's scales:
    # its preload takes any size)
    t = taut.sweep(
        REFERENCE,
        vary={"carrier.preload": (1e100, 1e300, 2)},
        log=True,
        set={"mesh.elements": 40, "time.end": 0.02},
        out=tmp_path / "s",
        progress=False,
    )
    assert len(t["carrier.preload"]) == 2
    note = (tmp_path / "s" / "force_map.svg").read_text()
    assert "This plot is not drawn" in note


# --- the third hostile round: the Python findings ---------------------


def test_droppers_past_the_budget_are_refused_not_fatal():
    # 1e5 droppers from a dict scene killed the interpreter (a dense
    # response each and their square matrices): refused before allocating
    scene = taut.load_scene(REFERENCE)
    scene["dropper"] = [
        {"x": 50.0 * (i + 0.5) / 100000, "stiffness": 1.0e5, "anchor_height": 1.2, "length": 1.199}
        for i in range(100000)
    ]
    with pytest.raises(taut.SceneError) as e:
        taut.run(scene, set={"time.end": 0.002}, progress=False)
    assert e.value.field == "dropper" and "memory budget" in str(e.value)


def test_a_removal_names_the_key_as_its_field():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.tensoin": None}, progress=False)
    assert e.value.field == "beam.tensoin"


@pytest.mark.parametrize("bad", [5, "yes", 1.5])
def test_progress_is_none_a_bool_or_a_callable(bad):
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set=SHORT, progress=bad)
    assert e.value.field == "progress"


def test_a_simulation_takes_numbers_not_strings():
    s = taut.Simulation(REFERENCE, set=SHORT)
    with pytest.raises(taut.SceneError) as e:
        s.apply_force(0, "1.0")
    assert e.value.field == "newtons"
    with pytest.raises(taut.SceneError) as e:
        s.w_at("5")
    assert e.value.field == "x"
    with pytest.raises(taut.SceneError):
        s.apply_force(0, True)
    s.apply_force(0, np.float64(1.0))  # a numpy number is a number
    assert s.w_at(np.float64(5.0)) == s.w_at(5.0)


def test_points_that_set_one_value_twice_are_refused_naming_both():
    for a, b in [("carrier.mass", "carrier.0.mass"), ("carrier.speed.cruise", "speed_ratio")]:
        with pytest.raises(taut.SceneError) as e:
            taut.sweep(REFERENCE, points=[{a: 1.0, b: 0.5}], set=SHORT, progress=False)
        assert "both set" in str(e.value) and a in str(e.value) and b in str(e.value)


def test_a_point_with_a_million_keys_is_refused_at_once():
    start = time.perf_counter()
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, points=[{f"k{i}": 1.0 for i in range(1_000_000)}], progress=False)
    # it ran past 300 s before (a list scanned for every key)
    assert time.perf_counter() - start < 20.0
    assert e.value.field == "points" and len(str(e.value)) < 400


def test_two_sweeps_into_one_out_in_one_process_are_refused(tmp_path):
    out = tmp_path / "s"
    slow = {"mesh.elements": 1600, "time.step": 2.5e-5}
    first: dict = {}

    def sweep() -> None:
        try:
            first["table"] = taut.sweep(
                REFERENCE, vary={"speed_ratio": (0.5, 0.9, 8)}, set=slow, out=out, progress=False
            )
        except BaseException as e:  # noqa: BLE001
            first["error"] = e

    t = threading.Thread(target=sweep)
    t.start()
    # wait until the first sweep holds the folder
    deadline = time.perf_counter() + 60
    while not (out / "sweep.lock").exists() and time.perf_counter() < deadline:
        time.sleep(0.05)
    time.sleep(0.2)
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, vary={"speed_ratio": (0.5, 0.9, 8)}, set=slow, out=out, progress=False)
    assert "in use by another command" in str(e.value)
    t.join()
    assert "table" in first, first


THREAD_POOL = """
import taut
from concurrent.futures import ThreadPoolExecutor
# four runs of about 5 s each (N = 3200, 48 000 steps) on two workers
sets = [{"mesh.elements": 3200, "time.step": 1.25e-5} for _ in range(4)]
print("started", flush=True)
with ThreadPoolExecutor(max_workers=2) as pool:
    list(pool.map(lambda s: taut.run("reference", set=s, progress=False), sets))
print("finished", flush=True)
"""


@pytest.mark.skipif(os.name != "posix", reason="SIGINT by os.kill")
def test_ctrl_c_stops_runs_in_a_thread_pool():
    # the pattern docs/python.md recommends for runs that are not a grid:
    # the workers never see the signal; the pool waited ~20 s for them
    stopped_in, stdout, stderr = ctrl_c(THREAD_POOL, [], 1.0)
    assert "KeyboardInterrupt" in stderr, stderr
    assert "finished" not in stdout
    # four runs of about 5 s each were pending (the two queued ones ran to
    # their end before): a step per running run, the queued ones stopping
    # at their start, and the interpreter's exit on a loaded machine
    assert stopped_in < 5.0, stopped_in
