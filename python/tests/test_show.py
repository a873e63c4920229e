"""Results that show themselves: flat attributes with
sweep.csv's names, HTML for notebooks, plots, and the progress switch."""

from __future__ import annotations

import re
import sys

import numpy as np
import pytest

import taut
from taut import _progress
from conftest import REFERENCE, ROOT

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}
# sweep.csv's result columns that are a run's statistics
SWEEP_STATS = (
    "speed_ratio",
    "loss_fraction",
    "loss_fraction_span",
    "loss_fraction_support",
    "force_mean",
    "force_std",
    "force_min",
    "force_max",
    "first_loss_position",
    "contact_switches",
)


def test_flat_attributes_have_the_sweep_columns_names_and_values():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    c = r.summary["carriers"][0]
    assert r.force_std == c["force"]["std"] and r.loss_fraction == c["loss_fraction"]
    assert r.speed_ratio == r.summary["derived"]["speed_ratio"]
    t = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": [100.0]}, set=SHORT, progress=False)
    for name in SWEEP_STATS:
        assert name in t, name
        mine, theirs = getattr(r, name), t[name][0]
        assert mine == theirs or (mine is None and np.isnan(theirs)), name
    assert "force_std" in dir(r)
    with pytest.raises(AttributeError) as e:
        r.force_sdt
    assert "force_std" in str(e.value)


def test_each_carrier_has_its_figures():
    r = taut.run(ROOT / "scenes" / "two_pantographs.toml", set={"time.end": 0.05}, progress=False)
    assert len(r.carriers) == 2
    for i, c in enumerate(r.carriers):
        assert c.force_std == r.summary["carriers"][i]["force"]["std"]
    assert r.force_std == r.carriers[0].force_std


def test_run_and_table_show_html():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    h = r._repr_html_()
    assert "<table" in h and "force_std" in h and "taut.Run" in h
    t = r.history
    h = t._repr_html_()
    assert h.count("<tr>") == 1 + 2 * 5 + 1, "the head, five rows, an ellipsis and five"
    assert f"{t.rows} rows" in h and "in_contact" in h


def test_run_html_has_units_each_figure_once_and_warnings_first():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    h = r._repr_html_()
    names = re.findall(r"<tr><td>([^<]*)</td>", h)
    words = [frozenset(n.split("_")) for n in names]
    assert len(words) == len(set(words)), "a figure under two names"
    assert "force_filtered_mean" not in names or "filtered_force_mean" not in names
    assert "<th>unit</th>" in h and "<td>N</td>" in h
    w = taut._show.run_html({"force_mean": 1.0}, 1, 3, ["soft"])
    assert w.index("soft") < w.index("<table"), "warnings above the figures"


def test_plots_draw_what_the_cli_svgs_draw(monkeypatch):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    r = taut.run(REFERENCE, set={**SHORT, "time.end": 0.3}, progress=False)
    ax = r.plot()
    # the force light and its filtered force bold, as force.svg
    assert ax.get_xlabel() == "carrier position x_m / L (–)" and len(ax.lines) == 2
    t = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": [50.0, 60.0]}, set=SHORT, progress=False)
    ax = t.plot("force_std")
    assert ax.get_xlabel() == "cruise speed V0 (m/s)   [carrier.speed.cruise]"
    assert list(ax.lines[0].get_ydata()) == list(t["force_std"])
    g = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": [50.0, 60.0], "beam.tension": [2.5e4, 3e4]}, set=SHORT, progress=False)
    ax = g.plot("force_std")
    assert ax.get_ylabel().endswith("[carrier.speed.cruise]") and ax.get_xlabel() == "tension T (N)   [beam.tension]"
    # without matplotlib: an ImportError naming the extra
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    with pytest.raises(ImportError) as e:
        r.plot()
    assert "taut[plot]" in str(e.value)


class FakeBar:
    made: list = []

    def __init__(self, total, initial, unit, leave):
        self.total, self.n = total, initial
        FakeBar.made.append(self)

    def update(self, k):
        self.n += k

    def close(self):
        pass


def test_the_progress_switch_and_the_first_tick(monkeypatch):
    monkeypatch.setattr(_progress, "_tqdm_class", lambda: FakeBar)
    FakeBar.made = []
    taut.set_progress(False)
    try:
        assert not taut.progress_enabled()
        taut.run(REFERENCE, set=SHORT, progress=None)
        assert FakeBar.made == [], "no bar with progress off"
        # a call's own progress= still wins
        taut.run(REFERENCE, set=SHORT, progress=True)
        assert len(FakeBar.made) == 1
    finally:
        taut.set_progress(True)
    FakeBar.made = []
    taut.run(REFERENCE, set=SHORT)
    assert len(FakeBar.made) == 1
    # the bar starts at the first report's count: no absurd first rate
    s = _progress.Sink(None, "steps")
    with s as call:
        call(5000, 10000)
        assert s.bar.n == 5000 and FakeBar.made[-1].n == 5000
        call(7000, 10000)
        assert s.bar.n == 7000
    with pytest.raises(TypeError):
        taut.set_progress("no")  # type: ignore[arg-type]


def test_without_ipywidgets_the_text_bar_is_used(monkeypatch):
    pytest.importorskip("tqdm")
    monkeypatch.setitem(sys.modules, "ipywidgets", None)
    from tqdm.std import tqdm

    assert _progress._tqdm_class() is tqdm
