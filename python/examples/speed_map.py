"""Speed map from Python: P_l against V0/c on the reference scene.

The study's Fig. 8 (TARGETS T3): `taut.sweep` over speed_ratio = 0.4 … 1.3
(46 points) at the study-like resolution of docs/reproduction.md (N = 400,
Δt = 1e-4 s, the reference scene's own). It prints P_l (the time in loss),
its in-span part and the first loss per speed, checks P_l as the study
counts it (`loss_fraction_steps`, lost steps over all steps) and the first
loss position against the study-like column of docs/reproduction.md's
"Every run of T3" table (each printed there to 3 significant digits), and
plots P_l against V0/c when matplotlib is installed.

    python python/examples/speed_map.py                 # table, check, out/speed_map.png
    python python/examples/speed_map.py --check         # exit 1 unless every row agrees
"""

from __future__ import annotations

import argparse
import math
import pathlib
import re
import sys

import taut

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "reference.toml"
DOC = ROOT / "docs" / "reproduction.md"

# docs/reproduction.md prints P_l and x_m/L to 3 significant digits
# (examples/reproduction_report.rs, `sig3`): agreement is equality at that
# precision, nothing looser
DIGITS = 3


def documented() -> "dict[float, tuple[float, float]]":
    """{V0/c: (P_l, first loss x_m/L)} of the study-like runs in the T3
    "Every run" table: rows `| V0/c | V0/c | P_l study / refined | … | x study / refined | …`."""
    text = DOC.read_text(encoding="utf-8")
    block = text.split("Every run of T3", 1)[1].split("</details>", 1)[0]
    rows = {}
    for line in block.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 5 or not re.fullmatch(r"[0-9.]+", cells[0]):
            continue
        p_l = cells[2].split("/")[0].strip()
        first = cells[4].split("/")[0].strip()
        rows[round(float(cells[0]), 6)] = (
            float(p_l),
            float(first) if first not in ("", "—", "-") else math.nan,
        )
    return rows


def sig(v: float) -> float:
    """v to DIGITS significant digits."""
    return float(f"{v:.{DIGITS}g}") if math.isfinite(v) else v


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=46, help="speeds from 0.4 to 1.3 (46: the doc's grid)")
    ap.add_argument("--plot", default=str(pathlib.Path(__file__).resolve().parents[2] / "out" / "speed_map.png"), help="where to save the plot (matplotlib)")
    ap.add_argument("--check", action="store_true", help="exit 1 unless every documented row agrees")
    args = ap.parse_args()

    t = taut.sweep(SCENE, vary={"speed_ratio": (0.4, 1.3, args.points)})
    doc = documented() if args.points == 46 else {}
    agree = 0
    print(f"{'V0/c':>6} {'P_l':>10} {'P_l span':>10} {'first loss':>10}  docs/reproduction.md (study-like, P_l in steps)")
    for r, pt, p, ps, x, err in zip(
        t["speed_ratio"],
        t["loss_fraction"],
        t["loss_fraction_steps"],
        t["loss_fraction_span"],
        t["first_loss_position"],
        t["error"],
    ):
        key = round(float(r), 6)
        note = ""
        if err is not None:
            note = f"stopped: {err}"
        elif key in doc:
            dp, dx = doc[key]
            same = sig(p) == dp and (sig(x) == dx or (math.isnan(x) and math.isnan(dx)))
            agree += same
            note = f"P_l {dp:g}, first loss {dx:g}: {'same' if same else 'DIFFERS'}"
        print(f"{r:6.3g} {pt:10.4g} {ps:10.4g} {x:10.4g}  {note}")
    if doc:
        print(f"{agree} of {len(doc)} documented rows reproduced to {DIGITS} significant digits")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot (pip install matplotlib)")
    else:
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(t["speed_ratio"], t["loss_fraction"], "o-", label="P_l")
        ax.plot(t["speed_ratio"], t["loss_fraction_span"], "s-", label="P_l in span")
        ax.set_xlabel("V0/c")
        ax.set_ylabel("contact loss fraction")
        ax.set_title("reference scene, N = 400, Δt = 1e-4 s (study Fig. 8)")
        ax.legend()
        fig.tight_layout()
        pathlib.Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.plot, dpi=120)
        print(f"plot: {args.plot}")

    if args.check and (not doc or agree != len(doc)):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
