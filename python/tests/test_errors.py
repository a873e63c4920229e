"""Bad input and failing runs raise exceptions that carry the error's
fields as attributes, never a panic or a silent NaN."""

from __future__ import annotations

import json

import pytest

import taut
from conftest import REFERENCE

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.3}


def test_a_value_out_of_range_names_field_value_and_range():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.tension": -1.0}, progress=False)
    assert e.value.field == "beam.tension"
    assert e.value.value == "-1"
    assert "≥ 0" in e.value.allowed
    assert "`beam.tension` = -1" in str(e.value)
    # the built-in class a user would catch
    assert isinstance(e.value, ValueError) and isinstance(e.value, taut.TautError)


def test_an_unknown_key_names_its_path():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.lenght": 50.0}, progress=False)
    assert e.value.field == "beam.lenght"
    assert "unknown field `lenght`" in str(e.value)
    assert str(REFERENCE) in str(e.value), "a scene file's error names the file"


def test_a_toml_syntax_error_is_a_scene_error_without_field():
    with pytest.raises(taut.SceneError) as e:
        taut.run("[beam]\nlength = = 3\n", progress=False)
    assert e.value.field is None
    assert "line 2" in str(e.value)


def test_a_bad_override_names_key_and_value():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set=["beam.length.x=3"], progress=False)
    assert (e.value.field, e.value.value) == ("beam.length.x", "3")
    assert e.value.allowed == "`beam.length` is a value, not a table"


def test_study_arguments_are_named_as_python_arguments():
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.0, 2)}, batch=9, progress=False)
    assert (e.value.field, e.value.value) == ("batch", "9")
    assert "1 ..= 8" in e.value.allowed
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.0, 2)}, threads=0, progress=False)
    assert e.value.field == "threads"
    with pytest.raises(taut.SceneError) as e:
        taut.converge(REFERENCE, refine="space", progress=False)
    assert (e.value.field, e.value.value) == ("refine", "space")
    with pytest.raises(taut.SceneError) as e:
        taut.compare(REFERENCE, formulations=["lagrange", "magic"], progress=False)
    assert e.value.value == "magic"
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.0)}, progress=False)
    assert e.value.field == "vary.speed_ratio"
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.tension": object()}, progress=False)
    # the key the value was given for (the field once said "set")
    assert e.value.field == "beam.tension"


def test_tolerance_arguments_are_checked_by_name():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, tolerance=-1.0, progress=False)
    assert e.value.field == "tolerance"
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, tolerance=1e-3, quantity="speed", progress=False)
    assert (e.value.field, e.value.value) == ("quantity", "speed")
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, quantity="force", progress=False)
    assert e.value.field == "quantity" and "tolerance" in e.value.allowed
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, tolerance=object(), progress=False)  # type: ignore[arg-type]
    assert e.value.field == "tolerance"


def test_a_non_finite_value_is_refused_by_name():
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={"beam.tension": float("nan")}, progress=False)
    assert e.value.field == "beam.tension"


def test_a_missing_file_is_a_scene_not_found_naming_it(tmp_path):
    # an input, not an output: SceneNotFound, a SceneError and a
    # FileNotFoundError (test_python_terms.py has the rest)
    missing = tmp_path / "no_such_scene.toml"
    with pytest.raises(taut.SceneNotFound) as e:
        taut.run(missing, progress=False)
    assert e.value.filename == str(missing)
    assert isinstance(e.value, OSError)


def test_a_diverging_run_raises_with_step_time_and_cause():
    # the bilateral α-level contact on a moving carrier (MODEL §5)
    bad = {"contact.placement": "alpha", "contact.kind": "bilateral", "time.end": 0.1, "carrier.speed.cruise": 150.0}
    with pytest.raises(taut.DivergedError) as e:
        taut.run(REFERENCE, set=bad, progress=False)
    err = e.value
    assert err.step > 1 and 0 < err.time <= 0.1
    assert "contact force" in err.quantity
    assert "alpha" in err.cause
    assert isinstance(err, ArithmeticError)


def test_a_scene_that_is_not_a_scene_does_not_echo_its_content():
    with pytest.raises(taut.SceneError) as e:
        taut.run("[secret]\npassword = 'hunter2'\n", progress=False)
    assert "hunter2" not in str(e.value) and "not a scene" in str(e.value)


def test_a_failed_contact_solve_raises_with_its_problem_and_saves_it_with_out(tmp_path):
    # an iteration limit of 1 for the QP solver (tests/cli.rs does the same)
    bad = {
        "contact.formulation": "complementarity",
        "contact.complementarity.solver": "clarabel",
        "contact.complementarity.max_iter": 1,
    }
    with pytest.raises(taut.ContactError) as e:
        taut.run(REFERENCE, set=bad, out=tmp_path, progress=False)
    err = e.value
    assert err.step == 0 and err.time == 0.0
    assert "MaxIterations" in err.reason and err.run == ""
    assert set(err.problem) >= {"level", "g_free", "w", "contact"}
    assert err.saved == str(tmp_path / "failed_contact_step_0.json")
    assert json.loads((tmp_path / "failed_contact_step_0.json").read_text()) == err.problem
    with pytest.raises(taut.ContactError) as e:
        taut.run(REFERENCE, set=bad, progress=False)
    assert e.value.saved is None, "nothing is written without out"


def test_integer_arguments_are_checked_by_name():
    for kwargs, field in (
        ({"levels": -1}, "levels"),
        ({"levels": 2.5}, "levels"),
        ({"ratio": "two"}, "ratio"),
    ):
        with pytest.raises(taut.SceneError) as e:
            taut.converge(REFERENCE, **kwargs, progress=False)
        assert e.value.field == field, kwargs
    with pytest.raises(taut.SceneError) as e:
        taut.precision(REFERENCE, ratio=2.0, progress=False)
    assert e.value.field == "ratio"
    with pytest.raises(taut.SceneError) as e:
        taut.precision(REFERENCE, ratio=10**6, levels=5, progress=False)
    assert e.value.field == "ratio" and "overflows" in e.value.allowed
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.0, 2)}, threads=-2, progress=False)
    assert e.value.field == "threads"
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.0, 2)}, batch=2**70, progress=False)
    assert e.value.field == "batch"


def test_exceptions_survive_pickling_with_their_attributes():
    """multiprocessing sends exceptions between processes by pickle."""
    import pickle

    made = [
        taut.SceneError("m", field="beam.length", value="-1", allowed="must be > 0 (m)"),
        taut.DivergedError("m", 3, 0.5, "λ", 1e9, "too large a step"),
        taut.ContactError("m", 1, 0.1, "formulation penalty", "cycling", '{"level": "position"}', "/tmp/x.json"),
        taut.ToleranceError("m", "force", 1e-3, "does not converge"),
        taut.OutputError("m", "/tmp/out"),
    ]
    for e in made:
        back = pickle.loads(pickle.dumps(e))
        assert type(back) is type(e) and str(back) == str(e)
        assert vars(back) == vars(e), type(e).__name__
