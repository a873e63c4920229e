#!/usr/bin/env python3
"""P_l counted in steps against P_l as a located time: their Δt ladders.

Runs `taut run` on a scene over a ladder of time steps (the space
discretization fixed and fine) and prints, for each step, P_l counted in
lost steps (`loss_fraction_steps`, the source study's count), P_l as the
time in loss with each loss and re-contact located within its step
(`loss_fraction`), and the in-span part (`loss_fraction_span`); then each
one's successive differences, observed orders log2(d_k / d_k+1) and the
scatter of those orders (their standard deviation): a quantity that
converges regularly has differences that fall by a steady factor.

    python3 scripts/pl_located.py target/release/taut scenes/reference.toml \
        --set carrier.speed.cruise=134.92 --set mesh.kind=galerkin \
        --set mesh.modes=800 --set 'integrator={ method = "modal_exact" }'
"""

import argparse
import json
import math
import statistics
import subprocess
import tempfile

QUANTITIES = ["loss_fraction_steps", "loss_fraction", "loss_fraction_span"]


def run(taut, scene, sets, dt, out):
    args = [taut, "run", scene, "--out", out, "--quiet", "--set", f"time.step={dt}"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    with open(f"{out}/summary.json") as f:
        return json.load(f)["quantities"][0]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("taut")
    p.add_argument("scene")
    p.add_argument("--set", action="append", default=[])
    p.add_argument("--dt0", type=float, default=1e-4)
    p.add_argument("--levels", type=int, default=6)
    a = p.parse_args()
    steps = [a.dt0 / 2**k for k in range(a.levels)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, dt in enumerate(steps):
            rows.append(run(a.taut, a.scene, a.set, dt, f"{tmp}/l{k}"))
    print("dt_s," + ",".join(QUANTITIES))
    for dt, r in zip(steps, rows):
        print(f"{dt:.6e}," + ",".join(f"{r[q]:.6f}" for q in QUANTITIES))
    print()
    for q in QUANTITIES:
        v = [r[q] for r in rows]
        d = [abs(v[k] - v[k + 1]) for k in range(len(v) - 1)]
        orders = [
            math.log2(d[k] / d[k + 1])
            for k in range(len(d) - 1)
            if d[k] > 0 and d[k + 1] > 0
        ]
        spread = statistics.pstdev(orders) if len(orders) > 1 else float("nan")
        print(
            f"{q}: differences {', '.join(f'{x:.2e}' for x in d)}; "
            f"orders {', '.join(f'{o:.2f}' for o in orders)}; "
            f"median order {statistics.median(orders) if orders else float('nan'):.2f}, "
            f"scatter (std of orders) {spread:.2f}"
        )


if __name__ == "__main__":
    main()
