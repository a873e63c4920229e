"""Errors in Python's terms: a missing scene is a
FileNotFoundError, parse errors fill value and allowed, messages name
keyword arguments, sane bounds, keyword-only `threads`."""

from __future__ import annotations

import errno
import inspect
import pickle

import pytest

import taut
from conftest import REFERENCE

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}


def test_a_missing_scene_is_a_file_not_found_error(tmp_path):
    missing = tmp_path / "no_such_scene.toml"
    for scene in (missing, str(missing)):
        try:
            taut.run(scene, progress=False)
        except FileNotFoundError as e:
            assert isinstance(e, taut.SceneNotFound) and isinstance(e, taut.SceneError)
            assert e.errno == errno.ENOENT and e.filename == str(missing)
            assert str(missing) in str(e)
        else:
            pytest.fail("no FileNotFoundError")
    with pytest.raises(FileNotFoundError):
        taut.sweep(missing, vary={"beam.tension": [3e4]}, progress=False)
    e2 = pickle.loads(pickle.dumps(taut.SceneNotFound("no such scene", "x.toml")))
    assert (e2.filename, e2.errno, str(e2)) == ("x.toml", errno.ENOENT, "no such scene")


def test_a_parse_error_names_the_value_and_the_choices():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"contact.formulation": "lagrnge"}, progress=False)
    assert e.value.field == "contact.formulation"
    assert e.value.value == "lagrnge"
    assert "lagrange" in e.value.allowed and "penalty" in e.value.allowed
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.lenght": 50.0}, progress=False)
    assert e.value.value == "lenght" and "length" in e.value.allowed


def test_messages_name_keyword_arguments_not_flags():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set=SHORT, quantity="force")
    assert "--" not in str(e.value) and "tolerance" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set=SHORT, tolerance=1e-3, quantity="forse")
    assert "--quantity" not in str(e.value) and "quantity" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.compare(REFERENCE, ["lagrange"], reference_method="newmark", set=SHORT, progress=False)
    assert "--" not in str(e.value) and "methods=" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, vary={"beam.tension": (3e4, 3e4, 2)}, set=SHORT, progress=False)
    assert "--vary" not in str(e.value) and "vary" in str(e.value)


@pytest.mark.parametrize("levels", [-1, 2**70, 13])
def test_converge_levels_name_the_library_range(levels):
    with pytest.raises(taut.SceneError) as e:
        taut.converge(REFERENCE, levels=levels, progress=False)
    assert e.value.field == "levels" and "2 ..= 12" in str(e.value), str(e.value)
    assert "9223372036854775807" not in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.precision(REFERENCE, levels=-1, progress=False)
    assert "1 ..= 5" in str(e.value)


def test_threads_is_keyword_only_everywhere():
    for f in (taut.run, taut.sweep, taut.compare, taut.converge, taut.precision):
        p = inspect.signature(f).parameters.get("threads")
        assert p is None or p.kind is inspect.Parameter.KEYWORD_ONLY, f.__name__
    with pytest.raises(TypeError):
        taut.sweep(REFERENCE, {"beam.tension": [3e4]}, None, 2)  # type: ignore[misc]
