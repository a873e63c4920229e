"""The wire itself from Python: snapshots and the
space-time field of a run, the modes and the mesh of a scene, the filtered
force statistics of every summary, a tabulated speed profile; each compared
exactly with the CLI's files for the same scene."""

from __future__ import annotations

import numpy as np
import pytest

import taut
from conftest import REFERENCE, read_csv, run_cli, same_column

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.3}
SHORT_CLI = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]
WIRE = "\n[output]\nsnapshots = [0.1, 0.25]\nsnapshot_points = 21\nfield = { every = 100 }\n"


def test_snapshots_and_field_are_the_clis(cli, tmp_path):
    scene = tmp_path / "wire.toml"
    scene.write_text(REFERENCE.read_text() + WIRE)
    run_cli(cli, "run", scene, *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    r = taut.run(scene, set=SHORT, progress=False)
    s = r.snapshots
    assert s is not None and r.field is not None
    assert s.v.shape == (2, 21)
    cols = read_csv(tmp_path / "cli" / "snapshots.csv")
    assert list(cols) == ["t_requested", "t", "x", "v"]
    assert same_column(cols["v"], s.v.ravel())
    assert same_column(cols["x"], np.tile(s.x, 2))
    assert same_column(cols["t"], np.repeat(s.t, 21))
    assert list(s.t_requested) == [0.1, 0.25]
    f = read_csv(tmp_path / "cli" / "field.csv")
    assert same_column(f["v"], r.field.v.ravel())
    assert r.field.v.shape == (len(r.field.t), 61)
    # the field's t = 0 row is the history's first
    assert r.field.t[0] == r.history["t"][0]
    t, x, v = s
    assert v is s.v and x is s.x
    np.testing.assert_array_equal(r.x, taut.mesh(scene, set=SHORT))
    assert len(r.x) == 61


def test_no_snapshots_unless_asked():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    assert r.snapshots is None and r.field is None


def test_modes_are_the_clis(cli, tmp_path):
    run_cli(cli, "modes", REFERENCE, "--count", "5", "--set", "mesh.elements=100",
            "--out", tmp_path / "cli")
    m = taut.modes(REFERENCE, 5, set={"mesh.elements": 100})
    cols = read_csv(tmp_path / "cli" / "modes.csv")
    assert same_column(cols["frequency_hz"], m.frequency_hz)
    assert m.source == "fe_eigen"
    assert m.shapes.shape == (5, 101)
    shapes = read_csv(tmp_path / "cli" / "mode_shapes.csv")
    for j in range(5):
        assert same_column(shapes[f"mode_{j + 1}"], m.shapes[j])
    np.testing.assert_array_equal(m.x, taut.mesh(REFERENCE, set={"mesh.elements": 100}))
    # the first mode of the 50 m reference beam: near the string's c/2L
    c = np.sqrt(3.0e4 / (8900.0 * 1.5e-4))
    assert m.string_hz[0] == pytest.approx(c / 100.0, rel=1e-15)
    assert m.frequency_hz[0] == pytest.approx(m.string_hz[0], rel=1e-2)
    g = taut.modes(REFERENCE, 3, set={"mesh.kind": "galerkin", "mesh.modes": 10})
    assert g.source == "exact"
    # 100 elements (h = 0.5 m) do not resolve the clamped end's boundary
    # layer sqrt(EI/T) = 0.066 m: measured 3.9e-4 above the exact modes
    np.testing.assert_allclose(g.frequency_hz, m.frequency_hz[:3], rtol=1e-3)


def test_bad_counts_name_the_argument():
    with pytest.raises(taut.SceneError) as e:
        taut.modes(REFERENCE, 0)
    assert e.value.field == "count"
    with pytest.raises(taut.SceneError) as e:
        taut.modes(REFERENCE, 10_000, set={"mesh.elements": 10})
    assert e.value.field == "count" and "1 ..= 19" in str(e.value)


def test_every_summary_has_the_filtered_force():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    f = r.summary["carriers"][0]["force_filtered"]
    assert f["cutoff_hz"] == 20.0
    raw = r.summary["carriers"][0]["force"]
    assert f["std"] < raw["std"]
    assert f["min"] <= f["mean"] <= f["max"]


def test_a_speed_table_from_a_numpy_array_in_toml():
    times = np.array([0.0, 0.1, 1.0])
    speeds = np.array([0.0, 50.0, 50.0])
    table = (
        "speed = { profile = \"table\", "
        f"time = [{', '.join(map(repr, times.tolist()))}], "
        f"speed = [{', '.join(map(repr, speeds.tolist()))}] }}"
    )
    text = REFERENCE.read_text().replace(
        'speed = { profile = "smooth_ramp", cruise = 100.0 }', table
    )
    r = taut.run(text, set=SHORT, progress=False)
    x = r.history["x_m"]
    t = r.history["t"]
    ramp = t <= 0.1
    np.testing.assert_allclose(x[ramp], 250.0 * t[ramp] ** 2, rtol=1e-13, atol=1e-15)
