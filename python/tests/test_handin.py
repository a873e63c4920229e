"""Results an engineer can hand in: the filtered force and the
standards' statistics from Python, tables by row, HTML and rounded reprs,
progress that leaves no text in a saved notebook, a sign-safe force into
the wire, speeds in km/h, and report.html."""

from __future__ import annotations

import pathlib
import re
import sys
import types

import numpy as np
import pytest

import taut
from taut import _progress
from conftest import REFERENCE, ROOT, read_csv, run_cli

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}


def test_the_history_has_the_filtered_force_and_the_summary_its_statistics() -> None:
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    f = r.history["force_filtered"]
    assert f.shape == r.history["force"].shape
    s = r.summary["carriers"][0]["force_filtered"]
    # the summary's mean is the column's time average over the window
    # [0, T] (the trapezoid rule between rows; here T is a whole number of
    # steps, so no step is carried past the last row)
    t = r.history["t"]
    trapezoid = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))
    assert s["mean"] == pytest.approx(trapezoid / t[-1], rel=1e-12)
    assert s["statistical_max"] == s["mean"] + 3 * s["std"]
    assert r.filtered_force_mean == s["mean"]


def test_the_standards_table_is_the_clis(cli: pathlib.Path, tmp_path: pathlib.Path) -> None:
    sets = {**SHORT, "analysis.x": [0.0, 4.0]}
    r = taut.run(REFERENCE, set=sets, out=tmp_path / "py", progress=False)
    args = [f"--set={k}={taut._toml(v)}" for k, v in sets.items()]
    run_cli(cli, "run", REFERENCE, *args, "--out", tmp_path / "cli", "--quiet")
    csv = read_csv(tmp_path / "cli" / "standard.csv")
    assert list(r.standard.keys()) == list(csv.keys())
    assert float(csv["mean"][0]) == r.standard["mean"][0]
    assert r.standard["x_end"][0] == 4.0
    assert r.standard[0]["loss_percent"] == r.summary["standard"][0]["loss_percent"]


def test_tables_count_and_give_rows() -> None:
    t = taut.run(REFERENCE, set=SHORT, progress=False).history
    assert len(t) == t.rows == len(t["t"]) > 2
    assert t.columns == list(t.keys())
    first, last = t[0], t[-1]
    assert first["t"] == 0.0 and isinstance(first["t"], float)
    assert last["t"] == pytest.approx(0.05)
    assert t.row(1) == t[1] and [r["t"] for r in t.iterrows()][:2] == [t[0]["t"], t[1]["t"]]
    with pytest.raises(IndexError):
        t[len(t)]
    assert bool(t) and not bool(taut.Table())


def test_reprs_are_rounded_and_html_is_shown() -> None:
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    text = repr(r)
    assert "P_l = " in text, text
    # figures to 4 significant digits, not every digit of a float
    assert not re.search(r"\d{6,}", text), text
    m = taut.modes(REFERENCE, 3, set={"mesh.elements": 40})
    assert "<table" in m._repr_html_() and "f (Hz)" in m._repr_html_()
    sim = taut.Simulation(REFERENCE, set=SHORT)
    assert "<table" in sim._repr_html_() and "carrier" in sim._repr_html_()
    assert "<table" in sim.state._repr_html_()


def test_into_the_wire_is_up_below_and_down_above() -> None:
    def pushed(scene: str, f: float, into: bool) -> np.ndarray:
        sim = taut.Simulation(scene, set=SHORT)
        sim.apply_force(0, f, into_wire=into)
        while not sim.done:
            sim.step(50)
        return sim.result().history["force"]

    below = taut.Simulation("reference_below", set=SHORT)
    above = taut.Simulation("reference", set=SHORT)
    assert below.toward_wire(0) == 1.0 and above.toward_wire(0) == -1.0
    # into the wire is the plain force times the side's factor, bit for bit
    assert np.array_equal(pushed("reference", 5.0, True), pushed("reference", -5.0, False))
    assert np.array_equal(pushed("reference_below", 5.0, True), pushed("reference_below", 5.0, False))
    # and it raises the contact force on either side
    for scene in ("reference", "reference_below"):
        base = pushed(scene, 0.0, True)[1:].mean()
        assert pushed(scene, 5.0, True)[1:].mean() > base + 1.0
    with pytest.raises(IndexError):
        below.toward_wire(1)


def test_speeds_in_km_per_hour() -> None:
    kmh = taut.run(REFERENCE, set={**SHORT, "carrier.0.speed.cruise": "360 km/h"}, progress=False)
    ms = taut.run(REFERENCE, set={**SHORT, "carrier.0.speed.cruise": 100.0}, progress=False)
    assert kmh.summary["scene"]["carrier"][0]["speed"]["cruise"] == pytest.approx(100.0, rel=1e-15)
    assert np.allclose(kmh.history["force"], ms.history["force"], rtol=1e-12, atol=1e-9)
    with pytest.raises(taut.SceneError) as e:
        taut.run(REFERENCE, set={**SHORT, "carrier.0.speed.cruise": "360"}, progress=False)
    assert "km/h" in str(e.value) and "cruise" in str(e.value)


def test_a_report_of_run_and_sweep_folders(tmp_path: pathlib.Path) -> None:
    taut.run(REFERENCE, set=SHORT, out=tmp_path / "run", progress=False)
    taut.sweep(REFERENCE, vary={"speed_ratio": (0.5, 0.9, 3)}, set=SHORT, out=tmp_path / "sweep", progress=False)
    page = taut.report([tmp_path / "run", tmp_path / "sweep"], out=tmp_path / "report.html")
    html = pathlib.Path(page).read_text(encoding="utf-8")
    # every plot embedded as an image, none as markup
    assert html.count('<img src="data:image/svg+xml;base64,') == len(list(tmp_path.glob("*/*.svg")))
    assert "<svg" not in html
    assert "standard.csv" in html and "sweep.csv" in html
    # nothing fetched, no script, and a policy that forbids both
    assert not re.search(r'(src|href)="(https?:)?//', html) and "<script" not in html
    assert "Content-Security-Policy\" content=\"default-src 'none'" in html
    # a finished sweep leaves no lock file behind
    assert not (tmp_path / "sweep" / "sweep.lock").exists()
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(taut.SceneError) as e:
        taut.report(empty)
    assert "no taut outputs" in str(e.value) and "empty" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.report(tmp_path / "missing")
    assert "not a folder" in str(e.value)


def test_a_report_says_what_it_left_out(tmp_path: pathlib.Path) -> None:
    taut.run(REFERENCE, set=SHORT, out=tmp_path / "run", progress=False)
    (tmp_path / "run" / "extra.csv").write_text("a\n1\n")
    (tmp_path / "run" / "standard.csv").write_bytes(b"\xff\xfe")
    page = taut.report(tmp_path / "run")
    assert isinstance(page, taut.Report) and isinstance(page, str)
    assert pathlib.Path(page).is_file() and page.plots >= 1
    # a file that could not be shown, and files not shown by design, each
    # named with the reason
    assert any("standard.csv" in w for w in page.left_out), page.left_out
    assert any("history.csv: " in n for n in page.not_shown), page.not_shown
    assert any("extra.csv: not a file taut writes" in n for n in page.not_shown)
    assert page.incomplete == []


def test_plots_label_units_and_draw_the_filtered_force(tmp_path: pathlib.Path) -> None:
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    ax = r.plot()
    assert "(–)" in ax.get_xlabel() and "(N)" in ax.get_ylabel()
    labels = [l.get_label() for l in ax.get_lines()]
    assert any("filtered" in l for l in labels), labels
    t = taut.sweep(REFERENCE, vary={"speed_ratio": (0.5, 0.9, 3)}, set=SHORT, progress=False)
    ax = t.plot("filtered_force_std")
    assert ax.get_xlabel().startswith("speed ratio V0/c") and ax.get_ylabel().endswith("(N)")
    path = tmp_path / "force.png"
    ax.figure.savefig(path)
    assert path.stat().st_size > 0


def test_a_notebook_without_widgets_gets_a_bar_it_clears(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("tqdm")
    shown = []

    class Handle:
        def update(self, obj: object) -> None:
            shown.append(obj.data)  # type: ignore[attr-defined]

    class HTML:
        def __init__(self, data: str) -> None:
            self.data = data

    display_mod = types.ModuleType("IPython.display")
    display_mod.HTML = HTML  # type: ignore[attr-defined]
    display_mod.display = lambda obj, display_id=False: (shown.append(obj.data), Handle())[1]  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "IPython.display", display_mod)
    monkeypatch.setitem(sys.modules, "ipywidgets", None)  # not installed
    monkeypatch.setattr(_progress, "_in_notebook", lambda: True)
    assert _progress._tqdm_class() is _progress.NotebookBar
    with _progress.Sink(None, "steps") as p:
        assert p is not None
        p(1, 4)
        p(4, 4)
    assert "<progress" in shown[0] and shown[-1] == ""


def test_to_xarray_comes_with_the_all_extra() -> None:
    # pyproject's [all] (and [test]) bring xarray
    tomllib = pytest.importorskip("tomllib")
    meta = tomllib.loads((ROOT / "python" / "pyproject.toml").read_text(encoding="utf-8"))
    extras = meta["project"]["optional-dependencies"]
    assert "xarray" in extras["all"] and "xarray" in extras["test"]
