"""The line's outputs from Python: the contact force
per span, the uplift at the supports and the envelope of a run, each the
CLI's spans.csv, supports.csv and envelope.csv for the same scene, exactly."""

from __future__ import annotations

import numpy as np

import taut
from conftest import REFERENCE, read_csv, run_cli, same_column

SHORT = {"mesh.elements": 60, "time.step": 2e-4}
SHORT_CLI = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]
LINE = "\n[output]\nsupports = [5.0, 20.0, 35.0, 50.0]\nenvelope = true\n"


def test_spans_supports_and_envelope_are_the_clis(cli, tmp_path):
    scene = tmp_path / "line.toml"
    scene.write_text(REFERENCE.read_text() + LINE)
    run_cli(cli, "run", scene, *SHORT_CLI, "--out", tmp_path / "cli", "--quiet")
    r = taut.run(scene, set=SHORT, progress=False)
    assert r.spans is not None and r.supports is not None and r.envelope is not None
    for name, t in [("spans", r.spans), ("supports", r.supports), ("envelope", r.envelope)]:
        cols = read_csv(tmp_path / "cli" / f"{name}.csv")
        assert list(cols) == list(t), name
        for c in cols:
            assert same_column(cols[c], t[c]), f"{name}.csv {c}"
    assert r.spans.rows == 3
    assert list(r.supports["x"]) == [5.0, 20.0, 35.0, 50.0]
    assert r.envelope.rows == 61
    # the summary's lists hold the same numbers
    assert [s["samples"] for s in r.summary["spans"]] == list(r.spans["samples"])
    assert [s["v_max"] for s in r.summary["supports"]] == list(r.supports["v_max"])
    # every step whose contact point lies in [5, 50] m counts in one span
    x = r.history["x_m"][1:]
    assert r.spans["samples"].sum() == np.count_nonzero((x >= 5.0) & (x <= 50.0))


def test_the_simulation_gives_the_same_tables(tmp_path):
    scene = REFERENCE.read_text() + LINE
    r = taut.run(scene, set=SHORT, progress=False)
    sim = taut.Simulation(scene, set=SHORT)
    sim.step(sim.steps)
    s = sim.result()
    assert s.spans is not None and s.supports is not None and s.envelope is not None
    for a, b in [(r.spans, s.spans), (r.supports, s.supports), (r.envelope, s.envelope)]:
        for c in a:
            np.testing.assert_array_equal(a[c], b[c])


def test_no_line_tables_unless_asked():
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    assert r.spans is None and r.supports is None and r.envelope is None
    assert "spans" not in r.summary and "supports" not in r.summary
