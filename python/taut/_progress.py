"""Progress bars: where a call's progress goes, and the module-wide
switch (`taut.set_progress`).

A tqdm bar is shown only when tqdm is installed (`taut[progress]`) and
progress is on. In Jupyter the widget bar (`tqdm.auto`) is used when
ipywidgets can be imported; a kernel without it gets a bar of its own, an
HTML `<progress>` in one display that is emptied when the call ends, so a
saved notebook keeps no progress text (tqdm's text bar would leave its
lines in the cell's output). A bar is made at the call's first report with that report's
count as its start (`initial`): work an earlier start finished (a resumed
sweep) or done before the first report does not count into the rate.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable, Optional, Union

Progress = Union[None, bool, Callable[[int, int], Any]]
"""None: the module-wide setting (taut.set_progress; on by default: a
tqdm bar if tqdm is installed); False: none; True: tqdm (if installed); a
callable: called as progress(done, total) on the calling thread."""

_ON = True


def set_progress(on: bool) -> None:
    """Switch the default progress bars of every call on or off (a call's
    own `progress=` argument still wins). Off: no bar in a loop of calls."""
    global _ON
    if not isinstance(on, bool):
        raise TypeError(f"set_progress: expected True or False, got {on!r}")
    _ON = on


def progress_enabled() -> bool:
    """Whether calls show a bar by default (see set_progress)."""
    return _ON


def _in_notebook() -> bool:
    """True inside a Jupyter kernel (IPython's ZMQ shell)."""
    try:
        ipython: Any = importlib.import_module("IPython")
    except ImportError:
        return False
    shell = ipython.get_ipython()
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell"


class NotebookBar:
    """A progress bar for a Jupyter kernel without ipywidgets: an HTML
    `<progress>` element in one display, updated in place and emptied on
    close, so nothing of it is saved with the notebook. The calls of a
    tqdm bar that `Sink` makes (total, n, update, close)."""

    def __init__(self, total: int, initial: int = 0, unit: str = "it", leave: bool = False) -> None:
        display_mod: Any = importlib.import_module("IPython.display")
        HTML, display = display_mod.HTML, display_mod.display
        self._html: Any = HTML
        self.total = total
        self.n = initial
        self.unit = unit
        self._handle: Any = display(HTML(self._text()), display_id=True)

    def _text(self) -> str:
        return (
            f'<progress value="{self.n}" max="{max(self.total, 1)}" style="width:40em"></progress>'
            f" {self.n}/{self.total} {self.unit}"
        )

    def update(self, k: int) -> None:
        self.n += k
        if self._handle is not None:
            self._handle.update(self._html(self._text()))

    def close(self) -> None:
        if self._handle is not None:
            self._handle.update(self._html(""))


def _tqdm_class() -> Any:
    """tqdm's bar for this front end (NotebookBar in a notebook without
    ipywidgets), or None when tqdm is not installed."""
    try:
        import ipywidgets  # noqa: F401  (the widget bar needs it)
    except ImportError:
        try:
            from tqdm.std import tqdm
        except ImportError:
            return None
        return NotebookBar if _in_notebook() else tqdm
    try:
        from tqdm.auto import tqdm as auto
    except ImportError:
        return None
    return auto


class Sink:
    """Where one call's progress goes: the caller's callable, a tqdm bar,
    or nowhere."""

    def __init__(self, progress: Progress, unit: str) -> None:
        if not (progress is None or isinstance(progress, bool) or callable(progress)):
            from ._errors import SceneError

            shown = repr(progress)
            shown = shown if len(shown) <= 200 else shown[:200] + "…"
            raise SceneError(
                f"invalid argument: `progress` = {shown}: must be None, True, False "
                "or a callable progress(done, total)",
                field="progress",
                value=shown,
                allowed="None, True, False or a callable progress(done, total)",
            )
        self.bar: Any = None
        self.unit = unit
        self.tqdm: Any = None
        self.call: Optional[Callable[[int, int], Any]] = None
        if callable(progress):
            self.call = progress
        elif progress is True or (progress is None and _ON):
            self.tqdm = _tqdm_class()
            if self.tqdm is not None:
                self.call = self._tqdm

    def _tqdm(self, done: int, total: int) -> None:
        # made at the first report, counting from it: a call that fails at
        # once shows no bar, and the rate is the work seen while it shows
        if self.bar is None:
            self.bar = self.tqdm(total=total, initial=done, unit=self.unit, leave=False)
            return
        if self.bar.total != total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)

    def __enter__(self) -> Optional[Callable[[int, int], Any]]:
        return self.call

    def __exit__(self, *exc: Any) -> None:
        if self.bar is not None:
            self.bar.close()
