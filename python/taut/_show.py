"""Results that show themselves: the HTML a notebook shows for a Run or a
Table, and their plots (matplotlib, optional: `pip install taut[plot]`)
drawing what the CLI's SVGs draw: a run's contact force against the
carrier's position with the lost-contact steps shaded (force.svg), and a
sweep's column against its axis (a 1-D sweep) or as a map over its two
axes (a 2-D one).
"""

from __future__ import annotations

import html
import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ._table import Table

# rows of a table a notebook shows: the head and the tail
HTML_ROWS = 5


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            "plot() needs matplotlib, taut's `plot` extra: pip install 'taut[plot]'"
        ) from e
    return plt


def _cell(v: Any) -> str:
    if isinstance(v, (float, np.floating)):
        f = float(v)
        return "" if math.isnan(f) else f"{f:.6g}"
    if v is None:
        return ""
    return html.escape(str(v))


def table_html(t: "Table") -> str:
    """A table's head and tail as an HTML table, with its size."""
    names = list(t.keys())
    n = t.rows
    shown: List[Optional[int]] = list(range(n))
    if n > 2 * HTML_ROWS:
        shown = list(range(HTML_ROWS)) + [None] + list(range(n - HTML_ROWS, n))
    head = "".join(f"<th>{html.escape(k)}</th>" for k in names)
    body = []
    for i in shown:
        if i is None:
            body.append("<tr>" + "<td>…</td>" * len(names) + "</tr>")
        else:
            body.append("<tr>" + "".join(f"<td>{_cell(t[k][i])}</td>" for k in names) + "</tr>")
    extra = ""
    if t.axes:
        extra = " · grid " + " × ".join(f"{html.escape(k)} ({len(v)})" for k, v in t.axes)
    elif t.paired:
        extra = " · a list of points"
    return (
        f"<div><b>taut.Table</b>: {n} rows × {len(names)} columns{extra}"
        f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table></div>"
    )


def run_html(scalars: Dict[str, Any], carriers: int, rows: int, warnings: Sequence[str]) -> str:
    """A run's summary figures (carrier 0's statistics and the derived
    figures) as an HTML table, with its warnings."""
    cells = "".join(
        f"<tr><td>{html.escape(k)}</td><td>{_cell(v)}</td></tr>" for k, v in scalars.items()
    )
    warn = "".join(f"<li>{html.escape(w)}</li>" for w in warnings)
    return (
        f"<div><b>taut.Run</b>: {rows} history rows, {carriers} carrier(s)"
        f"{'' if carriers == 1 else ' (figures of carrier 0; run.carriers[i] for each)'}"
        f"<table><tbody>{cells}</tbody></table>"
        f"{'<b>warnings</b><ul>' + warn + '</ul>' if warnings else ''}</div>"
    )


def plot_run(history: "Table", carriers: int, length: float, ax: Any = None) -> Any:
    """force.svg: every carrier's contact force against its position
    x_m/L (against t when no carrier moves), the steps with contact lost
    shaded."""
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 3.5))
    suffixes = [""] if carriers == 1 else [f"_{i}" for i in range(carriers)]
    moving = any(np.ptp(history["x_m" + s]) > 0 for s in suffixes)
    for i, s in enumerate(suffixes):
        x = history["x_m" + s] / length if moving else history["t"]
        force = history["force" + s]
        lost = ~history["in_contact" + s].astype(bool)
        name = "contact force" if carriers == 1 else f"carrier {i}"
        ax.plot(x, force, lw=0.8, color=f"C{i}", label=name)
        if lost.any():
            lo, hi = float(np.nanmin(force)), float(np.nanmax(force))
            ax.fill_between(
                x,
                lo,
                hi,
                where=lost,
                color=f"C{i}",
                alpha=0.2,
                step="mid",
                label="contact lost (shaded)" if i == 0 else None,
            )
    ax.set_xlabel("x_m / L" if moving else "t (s)")
    ax.set_ylabel("contact force λ (N)")
    ax.legend(loc="upper right")
    return ax


def plot_table(t: "Table", column: str, ax: Any = None) -> Any:
    """A sweep's `column` against its axis (1-D), as a map over its two
    axes (2-D), or against the row (anything else)."""
    plt = _pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4))
    if len(t.axes) == 2:
        g, (kx, x), (ky, y) = t.grid(column), t.axes[0], t.axes[1]
        # first axis on the vertical, as the CLI's loss_fraction_map.svg
        m = ax.pcolormesh(y, x, g, shading="nearest")
        ax.figure.colorbar(m, ax=ax, label=column)
        ax.set_xlabel(ky)
        ax.set_ylabel(kx)
        return ax
    if len(t.axes) == 1:
        key, x = t.axes[0]
        ax.plot(x, t.grid(column), marker="o", ms=3)
        ax.set_xlabel(key)
    else:
        ax.plot(np.arange(t.rows), t[column], marker="o", ms=3, ls="none")
        ax.set_xlabel("point")
    ax.set_ylabel(column)
    return ax
