"""Elastic messenger supports, clamp masses and per-dropper keys from Python
(docs/lines.md "Elastic supports and clamp masses"): the same TOML
runs to the CLI's numbers, and a bad value is refused naming its field."""

from __future__ import annotations

import pytest

import taut
from conftest import ROOT, read_csv, run_cli, same_column

SPAN = ROOT / "scenes" / "span_messenger.toml"
ELASTIC = {
    "messenger.support": {"stiffness": 5.0e5, "damping": 200.0, "mass": 10.0},
    "time.end": 0.1,
}
ELASTIC_CLI = [
    "messenger.support={ stiffness = 5.0e5, damping = 200.0, mass = 10.0 }",
    "time.end=0.1",
]


def test_an_elastic_messenger_support_runs_as_the_cli(cli, tmp_path):
    cli_set = [a for s in ELASTIC_CLI for a in ("--set", s)]
    run_cli(cli, "run", SPAN, *cli_set, "--out", tmp_path / "cli", "--quiet")
    r = taut.run(SPAN, set=ELASTIC, progress=False)
    cols = read_csv(tmp_path / "cli" / "history.csv")
    for c in cols:
        assert same_column(cols[c], r.history[c]), c
    # the support moves the run (the check can fail)
    rigid = taut.run(SPAN, set={"time.end": 0.1}, progress=False)
    assert any(a != b for a, b in zip(r.history["force"], rigid.history["force"]))


def test_a_support_without_a_spring_names_its_field():
    with pytest.raises(taut.SceneError) as e:
        taut.run(SPAN, set={"messenger.support": {"mass": 10.0}}, progress=False)
    assert e.value.field == "messenger.support.stiffness"
    assert "singular" in str(e.value)
