#!/usr/bin/env python3
"""Sibling runs at the finest level of every coverage pair: can a noise
estimate made at the finest level move the coverage–sharpness frontier?
(docs/verification.md, "Can both targets be met at once on this
grid?").

For each of the 129 stored pairs (golden/uncertainty_pairs.jsonl) the
finest run of its family is made again with its level parameter (N, or J
on a modal basis) changed by +1, +2 and −1 at the same Δt and support
zone. Those changes are immaterial to the discretization's order, but they
move the element (or mode) boundaries against the load's path, so the
spread A = max |φ_sibling − φ_finest| measures the part of the finest
level's error that scatters with such details (the load's position within
an element at a maximum, a short loss interval). A is then combined with
the family's own numbers (taut's u_num and estimated error from `cargo
xtask uncertainty replay FILE --pairs OUT`, and the finest step's mesh and
Δt parts |Δ_h| + |Δ_Δt|) and every combination's coverage and sharpness
over the pairs are printed.

    cargo build --release
    cargo xtask uncertainty replay golden/uncertainty_pairs.jsonl --pairs pairs.jsonl
    python3 scripts/sibling_spread.py pairs.jsonl [--runs DIR] [--fit]

316 runs (237 siblings, and the 79 distinct finest runs made again and
checked against the family's values), ≈ 3.5 min on an AMD EPYC, 2 vCPUs. The runs are
kept in DIR (default out/siblings), one folder per run, so a second call
only reads (≈ 50 s).
"""

import argparse
import concurrent.futures as cf
import csv
import json
import math
import os
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
TAUT = os.path.join(ROOT, "target", "release", "taut")
STORED = os.path.join(ROOT, "golden", "uncertainty_pairs.jsonl")

# each case's scene and fixed overrides (xtask/src/uncertainty/cases.rs)
MF = "scenes/moving_force_beam.toml"
RM = "scenes/riding_mass_pinned.toml"
REF = "scenes/reference.toml"
MODAL = ["mesh.kind=galerkin", 'integrator={ method = "modal_exact" }']
CASES = {
    "moving force, pinned–pinned": (MF, []),
    "moving force, clamped–pinned": (MF, ['beam.left="clamped"', 'reference.kind="richardson"']),
    "riding mass, pinned–pinned": (RM, []),
    "reference case V0/c = 0.9, Hermite": (REF, ["carrier.speed.cruise=134.92"]),
    "reference case V0/c = 0.9, modal_exact": (REF, ["carrier.speed.cruise=134.92"] + MODAL),
    "reference case V0/c = 0.8, modal_exact": (REF, ["carrier.speed.cruise=119.93"] + MODAL),
}

# the level parameter's changes of the siblings
SIBLINGS = (1, 2, -1)

# the coverage target (xtask's COVERAGE_TARGET)
COVERAGE = 0.95


def peak(w):
    """The largest sample refined by the parabola through it and its
    neighbours (taut's `quantity::peak`)."""
    k = max(range(len(w)), key=lambda i: w[i])
    if k == 0 or k == len(w) - 1:
        return w[k]
    a, b, c = w[k - 1], w[k], w[k + 1]
    cur = a - 2 * b + c
    if cur >= 0:
        return b
    x = 0.5 * (a - c) / cur
    return b - 0.25 * (a - c) * x


def folder(runs, case, level, dt, zone):
    """One folder per run: the case, level parameter, Δt and zone."""
    tag = "".join(ch if ch.isalnum() else "_" for ch in case)
    return os.path.join(runs, f"{tag}_{level}_{dt:.6e}_{zone:.6e}")


def make(runs, case, level, dt, zone):
    """Run once into its folder (kept: a second call reads it)."""
    d = folder(runs, case, level, dt, zone)
    if os.path.exists(os.path.join(d, "summary.json")):
        return d
    scene, sets = CASES[case]
    key = "mesh.modes" if any("galerkin" in s for s in sets) else "mesh.elements"
    args = [TAUT, "run", os.path.join(ROOT, scene), "--out", d, "--quiet"]
    for s in sets + [f"{key}={level}", f"time.step={dt:e}", f"analysis.support_zone={zone:e}"]:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(args)}: {p.stderr.strip()}")
    return d


def value(d, quantity):
    """The quantity of `taut uncertainty` read from a run's folder."""
    c = json.load(open(os.path.join(d, "summary.json")))["carriers"][0]
    if quantity == "loss_fraction_span":
        return c["loss_fraction_span"]
    if quantity == "force_mean":
        return c["force"]["mean"]
    w = [float(r["beam_w"]) for r in csv.DictReader(open(os.path.join(d, "history.csv"))) if r["beam_w"]]
    if quantity == "displacement_max":
        return peak(w)
    if quantity == "displacement_rms":
        return math.sqrt(sum(x * x for x in w[1:]) / len(w[1:]))
    raise ValueError(quantity)


def score(rows, u):
    """(covered share, sharp share) of u_num list `u` over `rows`."""
    cov = sharp = 0
    for r, x in zip(rows, u):
        e = abs(r["diagonal"][-1] - r["truth"])
        cov += x >= e
        sharp += (x / e <= 10) if e > 0 else x == 0
    return cov / len(rows), sharp / len(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pairs", help="the replay's --pairs output (taut's u_num and estimated error)")
    ap.add_argument("--runs", default=os.path.join(ROOT, "out", "siblings"))
    ap.add_argument("--fit", action="store_true", help="also the best factors for these pairs")
    a = ap.parse_args()
    rows = [json.loads(l) for l in open(STORED) if l.strip()]
    taut = [json.loads(l) for l in open(a.pairs) if l.strip()]
    if len(taut) != len(rows):
        sys.exit(f"{a.pairs}: {len(taut)} pairs, the stored file has {len(rows)}")
    os.makedirs(a.runs, exist_ok=True)
    jobs = sorted(
        {
            (r["case"], r["finest"][0] + s, r["finest"][1], r["support_zone"])
            for r in rows
            for s in (0,) + SIBLINGS
        },
        key=lambda j: -j[1] / j[2],  # costliest first
    )
    with cf.ThreadPoolExecutor(os.cpu_count() or 2) as ex:
        done = dict(zip(jobs, ex.map(lambda j: make(a.runs, *j), jobs)))
    spread, dparts = [], []
    for r in rows:
        lev, dt = r["finest"]
        at = lambda s: value(done[(r["case"], lev + s, dt, r["support_zone"])], r["quantity"])
        fine = at(0)
        if abs(fine - r["diagonal"][-1]) > 1e-9 * max(1.0, abs(fine)):
            sys.exit(f"{r['case']} {r['start']}: the finest run reads {fine}, its family {r['diagonal'][-1]}")
        spread.append(max(abs(at(s) - fine) for s in SIBLINGS))
        d, sp = r["diagonal"], r["space"]
        dparts.append(abs(d[-2] - sp[-1]) + abs(sp[-1] - d[-1]))
    u = [t["u_num"] for t in taut]
    eps = [abs(t["error_estimated"]) if t["error_estimated"] is not None else 0.0 for t in taut]
    table = [("taut's u_num", u)]
    for c in (1, 2, 3):
        table.append((f"{c} A", [c * x for x in spread]))
    for c in (1, 2, 3):
        for k in (0.5, 1, 1.25, 1.5):
            table.append((f"max({c} A, {k} (|Δ_h| + |Δ_Δt|))", [max(c * x, k * y) for x, y in zip(spread, dparts)]))
    for c in (1, 2, 3):
        table.append(
            (f"max(|ε|, {c} A, |Δ_h| + |Δ_Δt|)", [max(e, c * x, y) for e, x, y in zip(eps, spread, dparts)])
        )
    if a.fit:
        # the best factors for these very pairs (an upper bound, not an
        # estimator: they are fitted to the data they are scored on)
        best = []
        for c in [x / 4 for x in range(2, 21)]:
            for k in [x / 20 for x in range(5, 41)]:
                for form, f in (("max", lambda x, y: max(c * x, k * y)), ("sum", lambda x, y: c * x + k * y)):
                    cov, sh = score(rows, [f(x, y) for x, y in zip(spread, dparts)])
                    if cov >= COVERAGE:
                        best.append((sh, cov, form, c, k))
        sh, cov, form, c, k = max(best)
        print(f"fitted: {form}({c} A, {k} (|Δ_h| + |Δ_Δt|)) covers {100 * cov:.1f} %, sharp at {100 * sh:.1f} %")
    print("| estimator (seven runs and three siblings a pair) | covered | u_num ≤ 10× error |")
    print("|---|---|---|")
    for name, x in table:
        c, s = score(rows, x)
        print(f"| {name.replace('|', chr(92) + '|')} | {100 * c:.1f} % | {100 * s:.1f} % |")


if __name__ == "__main__":
    main()
