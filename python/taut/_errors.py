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

import json
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
