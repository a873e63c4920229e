"""Issue 25's Python messages: every bad argument raises SceneError naming
the argument or key and the real range, never a bare Python or numpy error,
and an empty `out` is refused (it would write into the current folder)."""

import numpy as np
import re

import pytest
from conftest import REFERENCE

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
    # issue 25: this hung in the plotting library's tick code after the tables
    t = taut.sweep(
        REFERENCE,
        vary={"carrier.stiffness": (1e100, 1e300, 2)},
        log=True,
        set={"mesh.elements": 40, "time.end": 0.02},
        out=tmp_path / "s",
        progress=False,
    )
    assert len(t["carrier.stiffness"]) == 2
    note = (tmp_path / "s" / "force_map.svg").read_text()
    assert "This plot is not drawn" in note
