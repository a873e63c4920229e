#!/usr/bin/env python3
"""Check an accuracy-targeted sweep against a refined one (docs/performance.md,
"The Fig. 12 map with --tolerance"): is every point's value within EPS of
the refined solution, and does its u_num cover the difference?

TOL_DIR holds `taut sweep ... --tolerance EPS --quantity Q`; REF_DIR a sweep
over the same points at one refined resolution (`--set mesh.modes=...
--set time.step=...`, no --tolerance). Points are matched by their axis
values; a reference over part of the points (a `--points` sweep, e.g. the
supersonic corner) checks that part. Prints a markdown table of the counts below and above V0/c = 1,
then every point whose u_num does not cover its difference.

Usage: python3 scripts/tolerance_check.py TOL_DIR REF_DIR [--eps 0.002]
           [--quantity loss_fraction_span]
"""

import argparse
import csv
import math
import os


def rows(folder):
    with open(os.path.join(folder, "sweep.csv"), newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tol_dir")
    ap.add_argument("ref_dir")
    ap.add_argument("--eps", type=float, default=0.002)
    ap.add_argument("--quantity", default="loss_fraction_span")
    a = ap.parse_args()
    tol = rows(a.tol_dir)
    if not tol or "u_num" not in tol[0]:
        raise SystemExit(f"{a.tol_dir}/sweep.csv has no u_num column: not a --tolerance sweep")
    # the axes: the columns before speed_ratio
    header = list(tol[0].keys())
    axes = header[: header.index("speed_ratio")]
    ref = {tuple(r[k] for k in axes): r for r in rows(a.ref_dir)}
    q = a.quantity
    # a reference over part of the map (e.g. the supersonic corner, a
    # `--points` sweep) checks that part
    every = len(tol)
    tol = [r for r in tol if tuple(r[k] for k in axes) in ref]
    if not tol:
        raise SystemExit(f"no point of {a.tol_dir} is in {a.ref_dir}")
    if len(tol) < every:
        print(f"{len(tol)} of the {every} points have a reference in {a.ref_dir}: those are checked\n")

    def diff(r):
        f = ref.get(tuple(r[k] for k in axes))
        if f is None:
            raise SystemExit(f"point {[r[k] for k in axes]} is not in {a.ref_dir}")
        return abs(float(r[q]) - float(f[q])), float(f[q])

    def u(r):
        return float(r["u_num"]) if r["u_num"] else math.inf

    print(f"| points | n | u_num ≤ {a.eps} (met) | within {a.eps} of the reference "
          "| u_num ≥ the difference (covered) | largest difference |")
    print("|---|---|---|---|---|---|")
    for name, sub in [
        ("V0/c < 1", [r for r in tol if float(r["speed_ratio"]) < 1]),
        ("V0/c ≥ 1", [r for r in tol if float(r["speed_ratio"]) >= 1]),
        ("all", tol),
    ]:
        if not sub:
            continue
        met = [r for r in sub if r["tolerance_met"] == "yes"]
        within = lambda s: sum(diff(r)[0] <= a.eps for r in s)  # noqa: E731
        covered = lambda s: sum(u(r) >= diff(r)[0] for r in s)  # noqa: E731
        print(f"| {name} | {len(sub)} | {len(met)} | {within(sub)} ({within(met)} of the met) "
              f"| {covered(sub)} ({covered(met)} of the met) "
              f"| {max(diff(r)[0] for r in sub):.4f} |")
    print()
    print("| " + " | ".join(axes) + " | V0/c | value | u_num | met | J or N, Δt used "
          "| reference | difference |")
    print("|" + "---|" * (len(axes) + 7))
    for r in tol:
        d, t = diff(r)
        if u(r) < d:
            res = r["modes_used"] or r["elements_used"]
            print("| " + " | ".join(r[k] for k in axes)
                  + f" | {float(r['speed_ratio']):.2f} | {float(r[q]):.5f} | {u(r):.5f} "
                  f"| {r['tolerance_met']} | {res}, {r['dt_used']} | {t:.5f} | {d:.5f} |")


if __name__ == "__main__":
    main()
