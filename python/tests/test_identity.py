"""The module's numbers are the CLI's: the same scene through `taut.run`,
`taut.sweep`, `taut.compare` and `taut.converge` and through the `taut`
binary gives the same values, compared exactly (the CSVs are written in
shortest round-trip form, so a float read back is the same float)."""

from __future__ import annotations

import json

import numpy as np
import pytest

import taut
from conftest import REFERENCE, ROOT, read_csv, run_cli, same_column

# short runs of the reference case: coarse mesh and step, first 0.3 s
SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.3}
SHORT_CLI = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]

# columns that are wall-clock times: machine-dependent by nature
WALL = {"wall_seconds"}


def assert_same_table(csv_path, table, skip=()):
    cols = read_csv(csv_path)
    assert list(cols) == list(table), "same columns in the same order"
    for name in cols:
        if name in skip:
            continue
        assert same_column(cols[name], table[name]), name


def test_run_is_the_cli_run(cli, tmp_path):
    run_cli(cli, "run", REFERENCE, *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    assert r.history.rows > 1000
    assert_same_table(tmp_path / "cli" / "history.csv", r.history)
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    for s in (summary, r.summary):
        s.pop("wall_seconds")
    assert summary == r.summary
    assert r.warnings == r.summary["warnings"]
    assert r.history["in_contact"].dtype == bool
    assert r.history["force"].dtype == np.float64


def without_wall(doc):
    """A JSON document without its measured times (any key naming a wall
    time, and each run's CPU seconds)."""
    if isinstance(doc, dict):
        return {
            k: without_wall(v)
            for k, v in doc.items()
            if "wall_seconds" not in k and k != "cpu_seconds"
        }
    if isinstance(doc, list):
        return [without_wall(v) for v in doc]
    return doc


def test_a_tolerance_run_is_the_cli_tolerance_run(cli, tmp_path):
    # the reference case on a small modal basis: a few hundredths of a second
    scene = ROOT / "scenes" / "reference.toml"
    sets = [
        "mesh.kind=galerkin",
        "mesh.modes=100",
        "time.step=2e-4",
        'integrator={ method = "modal_exact" }',
        "carrier.speed.cruise=120",
    ]
    flags = [w for k in sets for w in ("--set", k)]
    run_cli(cli, "run", scene, *flags, "--tolerance", "0.5", "--quantity", "force_mean", "--out", tmp_path / "cli", "--quiet")
    r = taut.run(scene, set=sets, tolerance=0.5, quantity="force_mean", progress=False)
    assert r.accuracy is not None and "reported" in list(r.accuracy["role"])
    assert_same_table(tmp_path / "cli" / "accuracy.csv", r.accuracy, skip=WALL)
    assert_same_table(tmp_path / "cli" / "history.csv", r.history)
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert without_wall(summary) == without_wall(r.summary)
    assert "accuracy" in r.summary
    assert taut.run(scene, set=sets, progress=False).accuracy is None


def test_run_writes_the_cli_files_with_out(tmp_path):
    r = taut.run(REFERENCE, set=SHORT, out=tmp_path / "py", progress=False)
    for f in ("history.csv", "summary.json", "force.svg"):
        assert (tmp_path / "py" / f).exists(), f
    assert_same_table(tmp_path / "py" / "history.csv", r.history)


def test_scene_text_and_path_give_the_same_run():
    text = REFERENCE.read_text()
    a = taut.run(REFERENCE, set=SHORT, progress=False)
    b = taut.run(text, set=SHORT, progress=False)
    c = taut.run(str(REFERENCE), set=[f"{k}={v}" for k, v in SHORT.items()], progress=False)
    for other in (b, c):
        for k in a.history:
            assert np.array_equal(a.history[k], other.history[k]), k


def test_sweep_is_the_cli_sweep(cli, tmp_path):
    vary = "speed_ratio=0.5:1.1:4"
    run_cli(cli, "sweep", REFERENCE, "--vary", vary, *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    t = taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.1, 4)}, SHORT, progress=False)
    assert t.rows == 4
    assert_same_table(tmp_path / "cli" / "sweep.csv", t)
    # a list of the CLI's axis strings is the same sweep; so is another batch width
    u = taut.sweep(REFERENCE, [vary], SHORT, threads=1, batch=1, progress=False)
    for k in t:
        if k != "error":
            assert np.array_equal(t[k], u[k], equal_nan=True), k


def test_sweep_with_stopped_points_and_refinement_is_the_cli_sweep(cli, tmp_path):
    # the bilateral α-level contact diverges at the two faster speeds
    # (tests/sweep_faults.rs): their rows carry the error
    cfg = ["--set", "contact.placement=alpha", "--set", "contact.kind=bilateral", "--set", "time.end=0.1"]
    run_cli_args = ["sweep", REFERENCE, "--vary", "speed_ratio=0.4:1.2:3", *cfg]
    import subprocess

    p = subprocess.run(
        [str(cli), *map(str, run_cli_args), "--check-refinement", "--out", str(tmp_path / "cli"), "--quiet"],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 1, "a sweep with stopped points exits 1"
    t = taut.sweep(
        REFERENCE,
        {"speed_ratio": (0.4, 1.2, 3)},
        {"contact.placement": "alpha", "contact.kind": "bilateral", "time.end": 0.1},
        check_refinement=True,
        progress=False,
    )
    assert_same_table(tmp_path / "cli" / "sweep.csv", t)
    assert t["error"][0] is None and "diverged" in t["error"][1]
    assert np.isnan(t["loss_fraction"][1])
    assert t["refined_elements"].dtype == np.float64


def test_compare_is_the_cli_compare(cli, tmp_path):
    run_cli(cli, "compare", REFERENCE, *SHORT_CLI, "--methods", "generalized_alpha,bathe", "--out", tmp_path / "cli", "--quiet")
    t = taut.compare(REFERENCE, set=SHORT, methods=["generalized_alpha", "bathe"], progress=False)
    assert t.rows == 8 and t.failed == []
    assert_same_table(tmp_path / "cli" / "compare.csv", t, skip=WALL)


def test_converge_is_the_cli_converge(cli, tmp_path):
    scene = ROOT / "scenes" / "moving_force_beam.toml"
    run_cli(cli, "converge", scene, "--refine", "step", "--levels", "3", "--out", tmp_path / "cli", "--quiet")
    t = taut.converge(scene, refine="step", levels=3, progress=False)
    assert_same_table(tmp_path / "cli" / "converge.csv", t)
    run_cli(
        cli, "converge", scene, "--refine", "step", "--levels", "3",
        "--methods", "newmark,bathe", "--out", tmp_path / "cli2", "--quiet",
    )
    t = taut.converge(scene, "step", 3, methods="newmark,bathe", progress=False)
    assert_same_table(tmp_path / "cli2" / "converge.csv", t)
    assert set(t["method"]) == {"newmark", "bathe"}


def test_precision_is_the_cli_precision(cli, tmp_path):
    small = ["--set", "mesh.elements=20", "--set", "time.step=8e-4", "--set", "time.end=0.3"]
    run_cli(cli, "precision", REFERENCE, *small, "--levels", "2", "--out", tmp_path / "cli", "--quiet")
    t = taut.precision(
        REFERENCE, set={"mesh.elements": 20, "time.step": 8e-4, "time.end": 0.3}, levels=2, progress=False
    )
    # the Pareto flag is on wall time: machine-dependent like it
    assert_same_table(tmp_path / "cli" / "precision.csv", t, skip=WALL | {"pareto"})


def test_to_pandas_gives_the_same_columns():
    pd = pytest.importorskip("pandas")
    t = taut.sweep(REFERENCE, {"speed_ratio": (0.5, 1.1, 3)}, SHORT, progress=False)
    df = t.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(t)
    assert np.array_equal(df["loss_fraction"].to_numpy(), t["loss_fraction"])


def test_compare_lists_the_runs_it_skipped_as_the_cli_does(cli, tmp_path):
    # central difference at Δt = 2e-4 s is above its stability limit on 400 elements
    run_cli(
        cli, "compare", REFERENCE, *SHORT_CLI, "--set", "mesh.elements=400",
        "--methods", "generalized_alpha,central_difference", "--out", tmp_path / "cli", "--quiet",
    )
    t = taut.compare(
        REFERENCE, set={**SHORT, "mesh.elements": 400},
        methods=["generalized_alpha", "central_difference"], progress=False,
    )
    doc = json.loads((tmp_path / "cli" / "compare.json").read_text())
    assert len(t.skipped) == 4 and t.failed == []
    # compare.json leaves out an empty discretization
    assert [{k: v for k, v in s.items() if v} for s in t.skipped] == doc["skipped"]
    assert_same_table(tmp_path / "cli" / "compare.csv", t, skip=WALL)
