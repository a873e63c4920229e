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


def test_every_command_of_the_library_has_its_python_function():
    assert set(SCHEMA) == {"run", "compare", "converge", "precision", "sweep", "modes", "uncertainty"}


@pytest.mark.parametrize("command", sorted(SCHEMA))
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
