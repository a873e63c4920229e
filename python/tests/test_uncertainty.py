"""Every number with its error bar: taut.uncertainty and the
accuracy-targeted sweep, bit for bit the CLI's."""

from __future__ import annotations

import pytest

import taut
from conftest import ROOT, REFERENCE, read_csv, run_cli, same_column

MOVING_FORCE = ROOT / "scenes" / "moving_force_beam.toml"
COARSE = {"mesh.elements": 20, "time.step": 4e-4}
COARSE_CLI = [a for k, v in COARSE.items() for a in ("--set", f"{k}={v}")]

# a small modal map: at 140 m/s the contact is lost in the span and the
# point refined, at 100 m/s its in-span P_l is 0 at every pilot
MAP = {
    "mesh.kind": "galerkin",
    "mesh.modes": 100,
    "time.step": 2e-4,
    "integrator": {"method": "modal_exact"},
}
MAP_CLI = [
    "--set", "mesh.kind=galerkin", "--set", "mesh.modes=100", "--set", "time.step=2e-4",
    "--set", "integrator={ method = \"modal_exact\" }",
]


def assert_same_table(csv_path, table):
    cols = read_csv(csv_path)
    assert list(cols) == list(table)
    for name in cols:
        assert same_column(cols[name], table[name]), name


def test_uncertainty_is_the_cli_table(cli, tmp_path):
    t = taut.uncertainty(MOVING_FORCE, set=COARSE, levels=3, progress=False)
    run_cli(cli, "uncertainty", MOVING_FORCE, "--levels", "3", *COARSE_CLI, "--out", tmp_path / "cli", "--quiet")
    assert_same_table(tmp_path / "cli" / "uncertainty.csv", t)
    assert t.family is not None and t.family.rows == 5
    i = list(t["quantity"]).index("displacement_rms")
    assert t["u_num"][i] > 0 and t["estimator"][i] in ("gci", "least_squares")


def test_uncertainty_levels_are_checked():
    with pytest.raises(taut.SceneError) as e:
        taut.uncertainty(MOVING_FORCE, set=COARSE, levels=2, progress=False)
    assert e.value.field == "levels" and "3 ..= 6" in str(e.value)


def test_an_accuracy_targeted_sweep_is_the_cli_table(cli, tmp_path):
    vary = {"carrier.speed.cruise": [100.0, 140.0]}
    t = taut.sweep(REFERENCE, vary=vary, set=MAP, tolerance=0.01, progress=False)
    run_cli(
        cli, "sweep", REFERENCE, "--vary", "carrier.speed.cruise=100,140", *MAP_CLI,
        "--tolerance", "0.01", "--out", tmp_path / "cli", "--quiet",
    )
    assert_same_table(tmp_path / "cli" / "sweep.csv", t)
    assert set(t["tolerance_met"]) <= {"yes", "no"}
    for met, u in zip(t["tolerance_met"], t["u_num"]):
        assert (met == "yes") == (u <= 0.01)
    with pytest.raises(taut.SceneError) as e:
        taut.sweep(REFERENCE, vary=vary, set=MAP, tolerance=0.01, quantity="speed", progress=False)
    assert e.value.field == "quantity"
