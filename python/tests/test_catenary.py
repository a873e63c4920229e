"""The form-found catenary from Python (docs/lines.md "Form-finding"): the
bundled scene runs through the same TOML, its line at rest meets the design
heights within the tolerance, and the lengths in the summary's scene are
the found ones, as `taut line expand` writes them."""

from __future__ import annotations

import taut
from conftest import run_cli

CUT = {"line.spans": 2, "time.end": 0.05}


def test_the_bundled_catenary_is_form_found(cli):
    assert "catenary_designed" in taut.scenes()
    r = taut.run("catenary_designed", set=CUT, progress=False)
    f = r.summary["form_finding"]
    assert f["steps"] == 1 and f["error"] <= f["tolerance"] == 1e-6
    assert f["start_error"] > 1e-3  # the string design's lengths were mm off
    droppers = r.summary["scene"]["dropper"]
    assert len(droppers) == 18 and all("design_height" in d for d in droppers)
    sets = [a for k, v in CUT.items() for a in ("--set", f"{k}={v}")]
    text = run_cli(cli, "line", "expand", "scenes/catenary_designed.toml", *sets).stdout
    for d in droppers:
        assert f"length = {d['length']!r}" in text, d["name"]
