"""Scenes as Python objects: load_scene, a dict / a
bundled name / one-line TOML as the scene, `set` values (None removes a
key, a str is a string), the scenes bundled in the extension."""

from __future__ import annotations

import json

import numpy as np
import pytest

import taut
from conftest import REFERENCE, ROOT, run_cli
from taut._scene import dumps

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}
SHORT_CLI = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]


def same_run(a: taut.Run, b: taut.Run) -> bool:
    """Bit for bit: every history column and the summary (wall time aside)."""
    if list(a.history) != list(b.history):
        return False
    if not all(np.array_equal(a.history[k], b.history[k]) for k in a.history):
        return False
    sa, sb = dict(a.summary), dict(b.summary)
    sa.pop("wall_seconds"), sb.pop("wall_seconds")
    return sa == sb


def same_history(a: taut.Run, b: taut.Run) -> bool:
    return list(a.history) == list(b.history) and all(
        np.array_equal(a.history[k], b.history[k]) for k in a.history
    )


def test_the_bundled_scenes_are_the_repository_scenes_text_for_text():
    files = {p.stem: p.read_text() for p in (ROOT / "scenes").glob("*.toml")}
    assert taut.scenes() == sorted(files)
    for name, text in files.items():
        assert taut.scene_text(name) == text, name
    with pytest.raises(taut.SceneError) as e:
        taut.scene_text("refrence")
    assert "reference" in e.value.allowed


def test_a_bundled_name_a_dict_and_the_file_run_the_same_numbers():
    by_file = taut.run(REFERENCE, set=SHORT, progress=False)
    by_name = taut.run("reference", set=SHORT, progress=False)
    d = taut.load_scene("reference")
    by_dict = taut.run(d, set=SHORT, progress=False)
    assert same_run(by_file, by_name) and same_run(by_file, by_dict)
    # the dict keeps integers and floats apart, and tables as dicts
    assert d["mesh"]["elements"] == 400 and isinstance(d["mesh"]["elements"], int)
    assert d["beam"]["tension"] == 3.0e4 and isinstance(d["beam"]["tension"], float)
    assert d["carrier"][0]["speed"] == {"profile": "smooth_ramp", "cruise": 100.0}


def test_an_edited_dict_is_the_scene_with_set():
    d = taut.load_scene(REFERENCE)
    d["beam"]["tension"] = np.float64(2.5e4)  # numpy scalars are numbers
    d["mesh"]["elements"] = np.int64(SHORT["mesh.elements"])
    d["time"]["step"], d["time"]["end"] = SHORT["time.step"], SHORT["time.end"]
    edited = taut.run(d, progress=False)
    with_set = taut.run(REFERENCE, set={**SHORT, "beam.tension": 2.5e4}, progress=False)
    assert same_run(edited, with_set)
    # load_scene applies set, the same way
    assert taut.load_scene(REFERENCE, set={"beam.tension": 2.5e4})["beam"]["tension"] == 2.5e4


def test_every_bundled_scene_round_trips_through_a_dict():
    for name in taut.scenes():
        d = taut.load_scene(name)
        assert taut.load_scene(dumps(d)) == d, name


def test_none_in_set_removes_the_key_as_the_cli_unset(cli, tmp_path):
    removed = taut.run(REFERENCE, set={**SHORT, "carrier.0.preload": None}, progress=False)
    zero = taut.run(REFERENCE, set={**SHORT, "carrier.0.preload": 0}, progress=False)
    preloaded = taut.run(REFERENCE, set=SHORT, progress=False)
    # the same numbers (the summary's scene echoes the key only when given)
    assert same_history(removed, zero) and removed.summary["carriers"] == zero.summary["carriers"]
    assert "preload" not in removed.summary["scene"]["carrier"][0]
    assert not same_history(removed, preloaded)
    run_cli(cli, "run", REFERENCE, *SHORT_CLI, "--unset", "carrier.0.preload", "--out", tmp_path / "cli", "--quiet")
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    summary.pop("wall_seconds")
    mine = dict(removed.summary)
    mine.pop("wall_seconds")
    assert summary == mine
    # a key that is not there is refused by name (a misspelt key removes nothing)
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"integrator.rho_infinity": None}, progress=False)
    assert "integrator.rho_infinity" in str(e.value) and "not in the scene" in str(e.value)


def test_a_str_in_set_is_a_toml_string_never_parsed():
    # "123" is the string "123", refused as a formulation by its choices
    # (not "invalid type: integer")
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"contact.formulation": "123"}, progress=False)
    assert "unknown variant `123`" in str(e.value) and "integer" not in str(e.value)
    # a str that would be TOML is a string too
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"mesh.elements": "400"}, progress=False)
    assert "string" in str(e.value)
    r = taut.run(REFERENCE, set={**SHORT, "contact.formulation": "penalty"}, progress=False)
    assert r.summary["scene"]["contact"]["formulation"] == "penalty"


def test_one_line_toml_is_text_and_a_missing_path_is_not_found(tmp_path):
    assert taut.load_scene("beam = { length = 50.0 }") == {"beam": {"length": 50.0}}
    with pytest.raises(FileNotFoundError):
        taut.load_scene(str(tmp_path / "nothing.toml"))
    with pytest.raises(taut.SceneError) as e:
        taut.load_scene("[beam]\nlength = = 3\n")
    assert "line 2" in str(e.value)


def test_every_study_takes_a_dict_and_a_name():
    d = taut.load_scene("reference")
    t = taut.sweep(d, vary={"carrier.speed.cruise": [50.0, 60.0]}, set=SHORT, progress=False)
    u = taut.sweep("reference", vary={"carrier.speed.cruise": [50.0, 60.0]}, set=SHORT, progress=False)
    assert np.array_equal(t["force_std"], u["force_std"])
    c = taut.compare(d, ["lagrange", "penalty"], set=SHORT, progress=False)
    assert c.rows == 2
    with pytest.raises(TypeError):
        taut.run(42, progress=False)  # type: ignore[arg-type]
