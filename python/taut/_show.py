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
from typing import Any, Dict, List, Optional, Protocol, Sequence, Tuple

import numpy as np


class Table(Protocol):
    """What the drawings read of a `taut.Table` (`_table.py`), named here
    so that this file imports nothing of the package: columns by name,
    the row count, a sweep's axes and its columns on the grid."""

    axes: List[Tuple[str, np.ndarray]]
    paired: bool

    @property
    def rows(self) -> int: ...

    def keys(self) -> Any: ...

    def get(self, key: str) -> Optional[np.ndarray]: ...

    def __getitem__(self, key: Any) -> Any: ...

    def grid(self, column: str) -> np.ndarray: ...

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


def table_html(t: Table) -> str:
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


def _unit(name: str) -> str:
    """The unit of a summary figure: the registry's, or one read off the
    name's last word (a force is in N, a time in s, a position in m);
    "" when the name does not say."""
    found = QUANTITY_LABELS.get(name) or _LABELS.get(name)
    if found and found.endswith(")") and "(" in found:
        return found[found.rindex("(") + 1 : -1]
    words = name.split("_")
    last = words[-1]
    if last in ("seconds", "time", "hz") or name.endswith("_time"):
        return "Hz" if last == "hz" else "s"
    if last in ("fraction", "ratio", "count", "switches", "steps", "order"):
        return "–"
    if "force" in words and last in ("mean", "std", "min", "max", "rms"):
        return "N"
    if last in ("length", "gap", "penetration"):
        return "m"
    return ""


def _distinct(scalars: Dict[str, Any]) -> List[Tuple[str, Any]]:
    """The figures once each: a flat summary name that is a registry name's
    words in another order (`force_filtered_mean` beside
    `filtered_force_mean`) is the same figure and left out; the first name
    (the registry's, which every table uses) is kept."""
    seen = set()
    out = []
    for k, v in scalars.items():
        words = frozenset(k.split("_"))
        if words in seen:
            continue
        seen.add(words)
        out.append((k, v))
    return out


def run_html(scalars: Dict[str, Any], carriers: int, rows: int, warnings: Sequence[str]) -> str:
    """A run's summary figures (carrier 0's statistics and the derived
    figures) as an HTML table of name, value and unit, each figure once,
    with its warnings first."""
    cells = "".join(
        f"<tr><td>{html.escape(k)}</td><td>{_cell(v)}</td><td>{html.escape(_unit(k))}</td></tr>"
        for k, v in _distinct(scalars)
    )
    warn = "".join(f"<li>{html.escape(w)}</li>" for w in warnings)
    return (
        f"<div><b>taut.Run</b>: {rows} history rows, {carriers} carrier(s)"
        f"{'' if carriers == 1 else ' (figures of carrier 0; run.carriers[i] for each)'}"
        f"{'<p><b>warnings</b></p><ul>' + warn + '</ul>' if warnings else ''}"
        f"<table><thead><tr><th>figure</th><th>value</th><th>unit</th></tr></thead>"
        f"<tbody>{cells}</tbody></table></div>"
    )


# units of the other columns and of a sweep's axes, for axis labels (the CLI's maps label them the same way:
# src/report/sweep_maps/axes.rs)
# labels of the library's quantities ("contact loss P_l (-)"), filled from
# its registry by the package (taut/__init__.py) so that no list of them is
# kept here
QUANTITY_LABELS: Dict[str, str] = {}

_LABELS = {
    "speed_ratio": "speed ratio V0/c (–)",
    "tension_ratio": "tension ratio T/EA (–)",
    "mass_ratio": "mass ratio m/M (–)",
    "stiffness_ratio": "stiffness ratio k/(T/L) (–)",
    "tension": "tension T (N)",
    "cruise": "cruise speed V0 (m/s)",
    "value": "speed V (m/s)",
    "mass": "mass m (kg)",
    "stiffness": "stiffness k (N/m)",
    "preload": "preload δ0 (m)",
    "damping": "damping c_s (N·s/m)",
    "length": "length L (m)",
    "elements": "elements N (–)",
    "step": "time step Δt (s)",
    "wall_seconds": "wall time (s)",
    "force_error": "relative RMS force error (–)",
    "dt": "time step Δt (s)",
}


def label(name: str) -> str:
    """An axis label with its unit for a column or a scene key (the key's
    last part decides: `carrier.speed.cruise` is a speed in m/s); the name
    itself when taut does not know its unit."""
    last = name.rsplit(".", 1)[-1]
    found = (
        QUANTITY_LABELS.get(name)
        or _LABELS.get(name)
        or QUANTITY_LABELS.get(last)
        or _LABELS.get(last)
    )
    if found is None:
        return name
    return found if name == last else f"{found}   [{name}]"


def _figure(ax: Any, size: Any) -> Any:
    plt = _pyplot()
    if ax is None:
        # constrained layout keeps the axis labels inside a saved figure
        _, ax = plt.subplots(figsize=size, layout="constrained")
    return ax


# loss intervals narrower than this share of the x range are widened to it
# when drawn (the CLI's force.svg does the same: a single lost step shows)
MIN_MARK_WIDTH = 0.003


def _loss_spans(x: np.ndarray, lost: np.ndarray) -> List[Any]:
    """[x_start, x_end] of each run of lost steps, widened to be seen."""
    spans = []
    i, n = 0, len(lost)
    width = MIN_MARK_WIDTH * float(np.nanmax(x) - np.nanmin(x)) if n else 0.0
    while i < n:
        if lost[i]:
            j = i
            while j + 1 < n and lost[j + 1]:
                j += 1
            a, b = float(x[max(i - 1, 0)]), float(x[j])
            c, w = 0.5 * (a + b), max(b - a, width)
            spans.append((c - 0.5 * w, c + 0.5 * w))
            i = j + 1
        else:
            i += 1
    return spans


def plot_run(history: Table, carriers: int, length: float, ax: Any = None, band_hz: float = 20.0) -> Any:
    """force.svg: every carrier's contact force against its position
    x_m/L (against t when no carrier moves), light, its filtered force
    (`force_filtered`) bold over it, the steps with contact lost shaded
    and marked under the lines."""
    ax = _figure(ax, (9, 4))
    suffixes = [""] if carriers == 1 else [f"_{i}" for i in range(carriers)]
    moving = any(np.ptp(history["x_m" + s]) > 0 for s in suffixes)
    lost_label = "contact lost (shaded, marked below)"
    peaks: List[np.ndarray] = []
    for i, s in enumerate(suffixes):
        # rows 1 …: row 0 is the initial state, as the CLI's plot
        x = (history["x_m" + s] / length if moving else history["t"])[1:]
        force = history["force" + s][1:]
        filtered = history.get("force_filtered" + s)
        name = "λ" if carriers == 1 else f"carrier {i}"
        ax.plot(x, force, lw=0.7, color=f"C{i}", alpha=0.45 if filtered is not None else 1.0, label=name)
        if filtered is not None:
            dark = _darker(f"C{i}")
            ax.plot(x, filtered[1:], lw=2.0, color=dark, label=f"{name}, 0–{band_hz:g} Hz filtered")
        peaks.append(force)
        lost = ~history["in_contact" + s][1:].astype(bool)
        for k, (a, b) in enumerate(_loss_spans(x, lost)):
            ax.axvspan(a, b, color=f"C{i}", alpha=0.22, lw=0, label=lost_label if (i == 0 and k == 0) else None)
            ax.axvspan(a, b, ymin=0.0, ymax=0.035, color="C3", lw=0)
    ax.set_xlabel("carrier position x_m / L (–)" if moving else "time t (s)")
    ax.set_ylabel("contact force λ (N)")
    # the CLI's rule: clip the axis above re-contact spikes (over twice the
    # 99.5th percentile), and say so with the peak
    f = np.concatenate(peaks) if peaks else np.zeros(1)
    f = f[np.isfinite(f)]
    if f.size:
        p995, top, low = float(np.percentile(f, 99.5)), float(f.max()), float(f.min())
        if p995 > 0 and top > CLIP_FACTOR * p995:
            clip = CLIP_FACTOR * p995
            span = clip - low
            ax.set_ylim(low - 0.05 * span, clip + 0.28 * span)
            ax.set_title(f"(axis clipped; peak {top:.0f} N)", fontsize="small", loc="right")
    ax.legend(loc="upper left", fontsize="small", framealpha=0.85)
    return ax


# the force axis is clipped at this multiple of the 99.5th percentile, as
# the CLI's force.svg does (src/report/plot.rs CLIP_FACTOR)
CLIP_FACTOR = 2.0


def _darker(colour: str) -> Any:
    """A darker shade of a matplotlib colour (the filtered line over its
    raw line, as force.svg draws it)."""
    from matplotlib.colors import to_rgb

    r, g, b = to_rgb(colour)
    return (0.55 * r, 0.55 * g, 0.55 * b)


def plot_table(t: Table, column: str, ax: Any = None) -> Any:
    """A sweep's `column` against its axis (1-D, with error bars from a
    `<column>_u_num` column when the table has one), as a map over its two
    axes (2-D), or against the row (anything else); axes labelled with
    their units."""
    ax = _figure(ax, (7, 4))
    if len(t.axes) == 2:
        g, (kx, x), (ky, y) = t.grid(column), t.axes[0], t.axes[1]
        # first axis on the vertical, as the CLI's loss_fraction_map.svg
        m = ax.pcolormesh(y, x, g, shading="nearest")
        ax.figure.colorbar(m, ax=ax, label=label(column))
        ax.set_xlabel(label(ky))
        ax.set_ylabel(label(kx))
        return ax
    if len(t.axes) == 1:
        key, x = t.axes[0]
        err = t.get(column + "_u_num")
        if err is not None:
            ax.errorbar(x, t.grid(column), yerr=err, marker="o", ms=3, capsize=3)
        else:
            ax.plot(x, t.grid(column), marker="o", ms=3)
        ax.set_xlabel(label(key))
    else:
        ax.plot(np.arange(t.rows), t[column], marker="o", ms=3, ls="none")
        ax.set_xlabel("point (–)")
    ax.set_ylabel(label(column))
    return ax


def modes_html(frequency_hz: np.ndarray, string_hz: np.ndarray, source: str, points: int) -> str:
    """A scene's modes as an HTML table: frequency and the taut string's."""
    rows = "".join(
        f"<tr><td>{j + 1}</td><td>{_cell(f)}</td><td>{_cell(s)}</td></tr>"
        for j, (f, s) in enumerate(zip(frequency_hz, string_hz))
    )
    return (
        f"<div><b>taut.Modes</b>: {len(frequency_hz)} modes ({html.escape(source)}), "
        f"shapes on {points} points"
        "<table><thead><tr><th>mode</th><th>f (Hz)</th><th>string j·c/(2L) (Hz)</th></tr></thead>"
        f"<tbody>{rows}</tbody></table></div>"
    )


def state_html(state: Any, steps: Optional[int] = None) -> str:
    """A simulation's state between steps as an HTML table, a row a
    carrier (and a row a probe)."""
    names = ("x", "w", "q", "q_dot", "gap", "force", "in_contact", "applied")
    units = ("m", "m", "m", "m/s", "m", "N", "", "N")
    head = "".join(
        f"<th>{n}{f' ({u})' if u else ''}</th>" for n, u in zip(names, units)
    )
    rows = "".join(
        f"<tr><td>{i}</td>" + "".join(f"<td>{_cell(getattr(c, n))}</td>" for n in names) + "</tr>"
        for i, c in enumerate(state.carriers)
    )
    probes = "".join(
        f"<tr><td>{html.escape(p.name)}</td><td>{_cell(p.x)}</td><td>{_cell(p.v)}</td><td>{_cell(p.v_dot)}</td></tr>"
        for p in state.probes.values()
    )
    of = f" of {steps}" if steps is not None else ""
    return (
        f"<div><b>taut.Simulation</b> at t = {state.t:.6g} s, step {state.step}{of}"
        f"<table><thead><tr><th>carrier</th>{head}</tr></thead><tbody>{rows}</tbody></table>"
        + (
            "<table><thead><tr><th>probe</th><th>x (m)</th><th>v (m)</th><th>v_dot (m/s)</th></tr></thead>"
            f"<tbody>{probes}</tbody></table>"
            if probes
            else ""
        )
        + "</div>"
    )
