"""Each command's options are declared once, in the library
(`taut::app::args`, the CLI's flags): every Python function of a command
takes exactly those options as keywords, with the same defaults, besides
what only a front end has (the scene, `set`, `out`, `progress`)."""

import inspect

import pytest

import taut

# what only a front end has: where the scene comes from, its overrides, the
# output folder and where progress goes
FRONT_END = {"scene", "set", "out", "progress"}

SCHEMA = dict(taut._taut.schema())


def _same_default(python: object, library: object) -> bool:
    """A Python default against the library's (text, or None for no default
    or a switch that is off)."""
    if library is None:
        return python is None or python is False
    if isinstance(python, (tuple, list)):
        python = ",".join(python)
    if isinstance(python, (int, float)) and not isinstance(python, bool):
        return float(python) == float(library)
    return python == library


STUDIES = {name for name, _ in taut.studies()}


def test_every_command_of_the_library_has_its_python_function():
    assert set(SCHEMA) == {"run", "sweep", "modes"} | STUDIES
    assert {"compare", "converge", "precision", "uncertainty"} <= STUDIES


def test_every_study_of_the_library_is_offered_by_taut_study():
    # the library's list of studies is what taut.study() takes: a study
    # added there needs no function here
    e = pytest.raises(taut.SceneError, taut.study, "bogus", "reference").value
    for name in STUDIES:
        assert name in str(e), str(e)


def test_the_stub_names_what_the_native_module_has():
    # the typing stub (_taut.pyi) is written by hand: it is held to the
    # module, so that a function added or removed fails here until it is
    import ast
    import pathlib

    stub = ast.parse((pathlib.Path(taut.__file__).parent / "_taut.pyi").read_text())
    listed = next(
        ast.literal_eval(n.value)
        for n in stub.body
        if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "__all__"
    )
    defined = {n.name for n in stub.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    native = {n for n in dir(taut._taut) if not n.startswith("_")} | {"__version__"}
    assert set(listed) == native
    assert {n for n in native if callable(getattr(taut._taut, n))} == defined


@pytest.mark.parametrize("command", sorted(set(SCHEMA) - (STUDIES - {"compare", "converge", "precision", "uncertainty"})))
def test_a_python_function_takes_its_command_s_options(command):
    params = inspect.signature(getattr(taut, command)).parameters
    options = {name: default for name, default, _ in SCHEMA[command]}
    assert set(params) - FRONT_END == set(options), command
    for name, default in options.items():
        p = params[name].default
        p = None if p is inspect.Parameter.empty else p
        assert _same_default(p, default), f"{command}({name}=...): Python {p!r}, library {default!r}"


def test_the_check_sees_a_python_option_the_library_does_not_declare():
    # the guard itself: a keyword too many, or a default apart, is caught
    options = {name: default for name, default, _ in SCHEMA["converge"]}
    assert "levels" in options and _same_default(4, options["levels"])
    assert not _same_default(5, options["levels"])
    assert "bogus" not in options


def test_compare_s_help_lists_the_library_s_names():
    # the lists in compare()'s docstring are made from the library's enums
    doc = taut.compare.__doc__
    assert "{" not in doc
    for name in [*taut.ALL_FORMULATIONS, *taut._taut.methods, *taut._taut.mesh_kinds]:
        assert name in doc, name
    assert "modal_exact" in taut._taut.methods and "hermite" in taut._taut.mesh_kinds


def test_a_study_by_name_is_the_named_function_s(tmp_path):
    # taut.study runs the study of the library's list as taut.compare does:
    # the same table, and the CLI's files in `out`
    import numpy as np

    from conftest import ROOT

    scene = ROOT / "scenes" / "oscillator_one_dof.toml"
    named = taut.compare(scene, ["lagrange", "penalty"])
    found = taut.study("compare", scene, formulations=["lagrange", "penalty"], out=tmp_path)
    assert set(found) == {"compare.csv"}
    by_name = found["compare.csv"]
    assert by_name.columns == named.columns
    same = [c for c in named.columns if "wall" not in c and by_name[c].dtype.kind == "f"]
    assert same
    for c in same:
        assert np.array_equal(by_name[c], named[c], equal_nan=True), c
    assert (tmp_path / "compare.csv").exists()
    with pytest.raises(taut.SceneError, match="levels"):
        taut.study("converge", scene, levels=1)
