"""Scenes as Python objects: a scene given as a path, a bundled scene's
name, TOML text or a dict; `load_scene` (a scene as a dict); the dict
written back as TOML text; `set` values as the overrides the library reads.

Which a `str` is (docs/python.md, "Scenes"):

1. an existing file: that file;
2. a bundled scene's name (`taut.scenes()`, e.g. "reference"): its text;
3. text with a line break, an `=` or a `[` (a scene's TOML text always
   has one, `[beam]` or `beam = {...}`; a path rarely): the scene's text,
   whose syntax errors are reported by line and column;
4. anything else: a path that does not exist, `SceneNotFound` (a
   `FileNotFoundError`).

A dict is written as TOML text (below) and given as text: the numbers are
the same as from the file it was loaded from, bit for bit (integers stay
integers, floats are written in their shortest round-trip form).
"""

from __future__ import annotations

import json
import math
import os
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple, Union

from . import _taut
from ._errors import SceneError, SceneNotFound

Scene = Union[str, "os.PathLike[str]", Mapping[str, Any]]
"""A path to a scene file, a bundled scene's name, the scene's TOML text,
or the scene as a dict (taut.load_scene)."""

_BUNDLED: Dict[str, str] = dict(_taut.bundled_scenes())


def scenes() -> List[str]:
    """The names of the scenes bundled with taut (the repository's
    `scenes/*.toml`), usable wherever a scene is: taut.run("reference")."""
    return sorted(_BUNDLED)


def scene_text(name: str) -> str:
    """The TOML text of the bundled scene `name` (see scenes())."""
    try:
        return _BUNDLED[name]
    except KeyError:
        raise SceneError(
            f"no bundled scene is called {name!r}",
            field="name",
            value=repr(name),
            allowed="one of " + ", ".join(scenes()),
        ) from None


def looks_like_toml(text: str) -> bool:
    """Whether a str that names no file is TOML text: it has a line
    break, an `=` or a `[` (every scene's text has one; a path rarely)."""
    return any(c in text for c in "\n=[")


def source(scene: Scene) -> Tuple[Optional[str], Optional[str]]:
    """(path, text) of a scene given as the module's functions take it
    (rules in the module doc)."""
    if isinstance(scene, os.PathLike):
        path = os.fspath(scene)
        if not os.path.exists(path):
            raise _not_found(path)
        return path, None
    if isinstance(scene, Mapping):
        return None, dumps(scene)
    if isinstance(scene, str):
        if os.path.exists(scene):
            return scene, None
        if scene in _BUNDLED:
            return None, _BUNDLED[scene]
        if looks_like_toml(scene):
            return None, scene
        raise _not_found(scene)
    raise TypeError(
        "scene: expected a path (str or os.PathLike), a bundled scene's name, "
        f"TOML text or a dict, got {type(scene).__name__}"
    )


def _not_found(path: str) -> SceneNotFound:
    shown = path if len(path) <= 200 else path[:200] + "…"
    return SceneNotFound(
        f"no such scene: {shown!r} is not a file, not a bundled scene's name "
        "(taut.scenes()) and not a scene's TOML text",
        path,
    )


def load_scene(
    scene: Scene, set: Union[None, Mapping[str, Any], Iterable[str]] = None
) -> Dict[str, Any]:
    """A scene as a dict of its TOML tables (`{"beam": {"tension": 30000.0,
    ...}, "carrier": [{...}], ...}`), with `set` applied (as for run()).

    Edit it and give it back to any function: taut.run(d). Integers stay
    int and floats float, so an unchanged dict runs the same numbers as
    the file, bit for bit.
    """
    path, text = source(scene)
    tree: Dict[str, Any] = json.loads(_taut.scene_json(path, text, overrides(set)))
    return tree


# --- a dict as TOML text ------------------------------------------------


def dumps(scene: Mapping[str, Any]) -> str:
    """A scene dict as TOML text: one `key = value` line a top-level key,
    tables and arrays of tables written inline. A None value leaves its key
    out (as absent: the default applies)."""
    lines = []
    for k, v in scene.items():
        if v is None:
            continue
        lines.append(f"{key(str(k))} = {value(v, str(k))}")
    return "\n".join(lines) + "\n"


def key(k: str) -> str:
    """A TOML key: bare when it may be, else quoted."""
    return k if k and all(c.isascii() and (c.isalnum() or c in "_-") for c in k) else _string(k)


def _string(s: str) -> str:
    """A TOML basic string (JSON's escapes are TOML's; DEL must be escaped too)."""
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def value(v: Any, where: str) -> str:
    """A Python value as a TOML value; `where` names it in an error."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(int(v))
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        # repr is the shortest text that reads back as the same float
        return repr(float(v))
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, Mapping):
        inner = ", ".join(
            f"{key(str(k))} = {value(x, f'{where}.{k}')}" for k, x in v.items() if x is not None
        )
        return "{ " + inner + " }" if inner else "{}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x, f"{where}.{i}") for i, x in enumerate(v)) + "]"
    if hasattr(v, "tolist"):  # a numpy scalar (a number) or array (a list)
        try:
            plain = v.tolist()
        except Exception as e:  # an array numpy cannot turn into a list
            raise _bad(where, v, f" ({e})") from None
        if plain is v:
            raise _bad(where, v, "")
        return value(plain, where)
    raise _bad(where, v, "")


def _bad(where: str, v: Any, why: str) -> SceneError:
    shown = repr(v)
    shown = shown if len(shown) <= 200 else shown[:200] + "…"
    return SceneError(
        f"`{where}`: a value of type {type(v).__name__} cannot be a scene value{why}",
        field=where,
        value=shown,
        allowed="a bool, number, str, list or dict (numpy scalars and arrays become numbers and lists)",
    )


# --- set= ---------------------------------------------------------------

UNSET = "unset "
"""The library's spelling of a removal in an override list (`--unset`)."""


def overrides(set: Union[None, Mapping[str, Any], Iterable[str]]) -> List[str]:
    """`set` as the library's override list, in order: `{key: value}` is
    `key=<value as TOML>` (a str is a TOML string, quoted, never parsed as
    TOML; numbers and bools are themselves; lists arrays; dicts inline
    tables), `{key: None}` removes the key (`--unset key`); a list of
    "key=value" strings is the CLI's `--set` text as it is."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        out = []
        for k, v in set.items():
            if v is None:
                out.append(f"{UNSET}{k}")
            else:
                out.append(f"{k}={value(v, str(k))}")
        return out
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]
