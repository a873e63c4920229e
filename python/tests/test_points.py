"""Any set of points on the sweep's engine: listed
values, lists of points, a grid's shape, and each point's force along the
span and warnings, bit for bit the CLI's."""

from __future__ import annotations

import numpy as np
import pytest

import taut
from conftest import REFERENCE, read_csv, run_cli, same_column

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}
SHORT_CLI = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]


def assert_same_table(csv_path, table):
    cols = read_csv(csv_path)
    assert list(cols) == list(table)
    for name in cols:
        assert same_column(cols[name], table[name]), name


def test_a_list_or_array_is_values_and_a_tuple_a_range(cli, tmp_path):
    values = np.array([60.0, 50.0, 55.0])
    t = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": values}, set=SHORT, progress=False)
    assert list(t["carrier.speed.cruise"]) == [60.0, 50.0, 55.0]
    run_cli(cli, "sweep", REFERENCE, "--vary", "carrier.speed.cruise=60,50,55", *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    assert_same_table(tmp_path / "cli" / "sweep.csv", t)
    as_list = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": [60, 50, 55]}, set=SHORT, progress=False)
    assert np.array_equal(as_list["force_std"], t["force_std"])
    # a tuple is (start, stop, count): 50, 55, 60
    r = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": (50, 60, 3)}, set=SHORT, progress=False)
    assert list(r["carrier.speed.cruise"]) == [50.0, 55.0, 60.0]
    assert np.array_equal(r["force_std"], t["force_std"][[1, 2, 0]])


def test_a_list_of_points_is_the_cli_points_file_and_each_run(cli, tmp_path):
    pts = [
        {"carrier.speed.cruise": 60.0, "beam.tension": 2.5e4},
        {"carrier.speed.cruise": 50.0, "beam.tension": 3.0e4},
        {"carrier.speed.cruise": 55.0, "beam.tension": 2.75e4},
    ]
    t = taut.sweep(REFERENCE, points=pts, set=SHORT, progress=False)
    assert t.rows == 3 and t.paired and t.axes == []
    csv = tmp_path / "points.csv"
    csv.write_text("carrier.speed.cruise,beam.tension\n" + "".join(f"{p['carrier.speed.cruise']!r},{p['beam.tension']!r}\n" for p in pts))
    run_cli(cli, "sweep", REFERENCE, "--points", csv, *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    assert_same_table(tmp_path / "cli" / "sweep.csv", t)
    # each point is the run of its values, bit for bit
    for i, p in enumerate(pts):
        r = taut.run(REFERENCE, set={**SHORT, **p}, progress=False)
        for col in ("loss_fraction", "force_mean", "force_std", "force_max"):
            assert t[col][i] == getattr(r, col), (i, col)
    # a dict of columns (a DataFrame's shape) is the same list
    cols = {k: [p[k] for p in pts] for k in pts[0]}
    u = taut.sweep(REFERENCE, points=cols, set=SHORT, progress=False)
    assert np.array_equal(u["force_std"], t["force_std"])


def test_bad_points_are_named():
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, points=[{"beam.tension": 3e4}, {"carrier.mass": 1.0}], progress=False)
    assert e.value.field == "points[0]" and "carrier.mass" in str(e.value)
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, points=[{"beam.tension": "3e4"}], progress=False)
    assert "number" in str(e.value)
    with pytest.raises(taut.SceneError):
        taut.sweep(REFERENCE, progress=False)
    with pytest.raises(taut.SceneError):
        taut.sweep(REFERENCE, vary={"beam.tension": [3e4]}, points=[{"beam.tension": 3e4}], progress=False)
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, vary={"beam.tension": [3e4, float("nan")]}, progress=False)
    assert "finite" in str(e.value)


def test_a_2d_sweep_has_its_grid_shape_span_maps_and_warnings(cli, tmp_path):
    vary = {"carrier.speed.cruise": [50.0, 60.0, 70.0], "beam.tension": (2.5e4, 3e4, 2)}
    t = taut.sweep(REFERENCE, vary=vary, set=SHORT, progress=False)
    (k0, v0), (k1, v1) = t.axes
    assert (k0, list(v0)) == ("carrier.speed.cruise", [50.0, 60.0, 70.0])
    assert (k1, list(v1)) == ("beam.tension", [2.5e4, 3e4])
    g = t.grid("loss_fraction_span")
    assert g.shape == (3, 2)
    # the last axis varies fastest: row 3 is (60, 3e4)
    assert g[1, 1] == t["loss_fraction_span"][3] or np.isnan(g[1, 1])
    assert t.grid("force_std")[2, 0] == t["force_std"][4]
    # the force along the span of each point: the CLI's sweep_force.csv
    run_cli(cli, "sweep", REFERENCE, "--vary", "carrier.speed.cruise=50,60,70", "--vary", "beam.tension=2.5e4:3e4:2", *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    force = read_csv(tmp_path / "cli" / "sweep_force.csv")
    bins = [k for k in force if k.startswith("x")]
    assert t.span_force.shape == (6, len(bins)) and t.span_loss.shape == (6, len(bins))
    assert np.array_equal(t.span_x, [float(b[1:]) for b in bins])
    for j, b in enumerate(bins):
        assert same_column(force[b], t.span_force[:, j]), b
    assert len(t.warnings) == 6 and all(isinstance(w, list) for w in t.warnings)
    assert list(t["warnings"]) == [len(w) for w in t.warnings]
    with pytest.raises(ValueError):
        taut.sweep(REFERENCE, points=[{"beam.tension": 3e4}], set=SHORT, progress=False).grid("force_std")


def test_to_xarray_when_installed():
    xr = pytest.importorskip("xarray")
    t = taut.sweep(REFERENCE, vary={"carrier.speed.cruise": [50.0, 60.0]}, set=SHORT, progress=False)
    ds = t.to_xarray()
    assert isinstance(ds, xr.Dataset)
    assert list(ds["force_std"].values) == list(t["force_std"])
