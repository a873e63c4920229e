"""The library's one registry of quantities, as Python sees it: the names of
`taut.quantities()` are the keys of a run summary's `quantities`, each with
a unit and a definition, and the plots label them from it."""

import taut
from taut import _show
from conftest import REFERENCE

SHORT = {"mesh.elements": 60, "time.step": 2e-4, "time.end": 0.05}


def test_the_registry_names_every_quantity_of_a_summary() -> None:
    qs = taut.quantities()
    names = [q["name"] for q in qs]
    assert len(names) == len(set(names)), "one name, one definition"
    assert {"loss_fraction", "loss_fraction_steps", "displacement_rms"} <= set(names)
    for q in qs:
        assert q["unit"] and q["definition"] and q["label"], q
    r = taut.run(REFERENCE, set=SHORT, progress=False)
    assert list(r.summary["quantities"][0].keys()) == sorted(names)
    # the flat names read the registry's values
    assert r.scalars["loss_fraction_steps"] == r.summary["quantities"][0]["loss_fraction_steps"]
    assert r.force_mean == r.summary["quantities"][0]["force_mean"]


def test_plots_label_a_quantity_from_the_registry() -> None:
    q = next(q for q in taut.quantities() if q["name"] == "force_mean")
    assert _show.label("force_mean") == f"{q['label']} (N)"
    assert _show.label("loss_fraction").endswith("(–)")
