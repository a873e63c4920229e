"""The exceptions taut raises: each carries the fields of the library's error
(`taut::Error`, src/error.rs) as attributes, besides the CLI's message.

The parameters after the message have defaults so that an exception
survives pickling (multiprocessing): unpickling calls the class with the
message only and then restores the attributes.

Every class derives from `TautError`, and from the built-in exception a
Python user would expect (`ValueError` for bad input, `OSError` for files),
so `except ValueError` keeps working in code that does not know taut.
A run stopped by Ctrl-C raises the built-in `KeyboardInterrupt`.
"""

from __future__ import annotations

import errno
import json
import os
import re
from typing import Any, Optional


class TautError(Exception):
    """Base of every error taut raises."""


class SceneError(TautError, ValueError):
    """Bad input: a scene value out of range, an unknown key, a bad `set`,
    or a study argument out of range.

    Attributes:
        field: dotted path of the key (`beam.length`, `carrier.0.speed`),
            or the argument's name (`batch`, `levels`); None for a TOML
            syntax error or a file that is not a scene.
        value: the value as given (text), or None when the fault is a key.
        allowed: what is allowed (`must be > 0 (m)`), or None.
    """

    def __init__(
        self,
        message: str,
        field: Optional[str] = None,
        value: Optional[str] = None,
        allowed: Optional[str] = None,
    ) -> None:
        super().__init__(message)
        self.field = field
        self.value = value
        self.allowed = allowed
        if value is None and allowed is None:
            # a parse error lists the choices in its message only
            self.value, self.allowed = _choices(message)


# serde's "unknown variant `x`, expected one of `a`, `b`" and "unknown
# field `x`, expected `a` or `b`", as the library's parse errors quote them
_CHOICES = re.compile(r"unknown (?:variant|field) `([^`]*)`, expected (?:one of )?(.+?)\s*$")


def _choices(message: str) -> "tuple[Optional[str], Optional[str]]":
    """(value, allowed) of a parse error whose message names the value and
    lists the choices; (None, None) otherwise."""
    m = _CHOICES.search(message)
    if m is None:
        return None, None
    return m.group(1), m.group(2)


class SceneNotFound(SceneError, FileNotFoundError):
    """The scene file does not exist (and the text is not a scene's TOML,
    nor a bundled scene's name). `except FileNotFoundError` catches it.

    Attributes:
        filename: the path as given; errno: errno.ENOENT; field: "scene".
    """

    def __init__(self, message: str, filename: Optional[str] = None) -> None:
        SceneError.__init__(self, message, "scene", filename, "an existing scene file, a bundled scene's name (taut.scenes()) or a scene's TOML text")
        self.errno = errno.ENOENT
        self.strerror = os.strerror(errno.ENOENT)
        self.filename = filename

    def __str__(self) -> str:
        return str(self.args[0])

    def __reduce__(self) -> Any:
        return (type(self), (self.args[0], self.filename))


# a CLI flag in a message (`--quantity`, `--reference-method`)
_FLAG = re.compile(r"(`?)--([a-z][a-z0-9-]*)(`?)( (?=[^\s`]))?")


def _keyword(m: "re.Match[str]") -> str:
    name = m.group(2).replace("-", "_")
    if m.group(1) and m.group(3):
        return f"`{name}`{m.group(4) or ''}"
    # `--quantity force` -> `quantity=force`; a bare `--methods` -> `methods=`
    return f"{m.group(1)}{name}={m.group(3)}"


def pythonic(text: str) -> str:
    """A library message in the terms of the Python call: keyword
    arguments (`quantity=`, `set=`) for the CLI's flags (`--quantity`,
    `--set`)."""
    return _FLAG.sub(_keyword, text)


def speak_python(e: BaseException) -> None:
    """Reword a taut exception raised from a Python call, in place: its
    message and its `field`/`allowed` name keyword arguments, not flags."""
    if not isinstance(e, TautError) or not e.args or not isinstance(e.args[0], str):
        return
    e.args = (pythonic(e.args[0]),) + tuple(e.args[1:])
    for attr in ("field", "allowed", "quantity", "reason"):
        v = getattr(e, attr, None)
        if isinstance(v, str):
            setattr(e, attr, pythonic(v))


class DivergedError(TautError, ArithmeticError):
    """A run went unstable and stopped with a diagnosis.

    Attributes:
        step: the step (1-based) at which it was seen.
        time: the time at the end of that step, s.
        quantity: what left its sane range (`carrier 0: contact force λ (N)`).
        value: its value.
        cause: the likely cause.
    """

    def __init__(
        self,
        message: str,
        step: int = 0,
        time: float = 0.0,
        quantity: str = "",
        value: float = 0.0,
        cause: str = "",
    ) -> None:
        super().__init__(message)
        self.step = step
        self.time = time
        self.quantity = quantity
        self.value = value
        self.cause = cause


class ContactError(TautError):
    """The contact law could not find forces at a step.

    Attributes:
        step: the step.
        time: the time at the end of that step, s.
        run: which run of a study it was (`formulation penalty`), or "".
        reason: why the law failed (`the active set did not settle …`).
        problem: the contact problem the law was given, as the dict the CLI
            saves to `failed_contact_step_N.json` (`taut replay` solves it).
        saved: where it was saved (a call with `out`), or None.
    """

    def __init__(
        self,
        message: str,
        step: int = 0,
        time: float = 0.0,
        run: str = "",
        reason: str = "",
        problem: str = "",
        saved: Optional[str] = None,
    ) -> None:
        super().__init__(message)
        self.step = step
        self.time = time
        self.run = run
        self.reason = reason
        self.problem: Any = json.loads(problem) if problem else None
        self.saved = saved


class ToleranceError(TautError, ValueError):
    """An accuracy target that cannot be met honestly.

    Attributes: quantity, tolerance, reason.
    """

    def __init__(
        self, message: str, quantity: str = "", tolerance: float = 0.0, reason: str = ""
    ) -> None:
        super().__init__(message)
        self.quantity = quantity
        self.tolerance = tolerance
        self.reason = reason


class OutputError(TautError, OSError):
    """A file could not be read or written.

    Attributes:
        path: the file or folder.
    """

    def __init__(self, message: str, path: str = "") -> None:
        super().__init__(message)
        self.path = path

    def __str__(self) -> str:
        return str(self.args[0])
