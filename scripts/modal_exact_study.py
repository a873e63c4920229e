#!/usr/bin/env python3
"""Which route is faster to a given accuracy: `modal_exact` on `galerkin`
or generalized-α on Hermite elements (docs/performance.md, "Picking the
right tool"; docs/discretizations.md).

The reference case at V0/c = 0.9 (`scenes/reference.toml`, cruise
134.9157 m/s, the case `modal_exact` was built for) under each route at several
resolutions, each against a fine Hermite run (N = 3200, Δt = 1.25e-5 s,
generalized-α ρ∞ = 1, the study's method) on the run's own time grid (every
Δt below divides into 1.25e-5 s):

- P_l in the span (`loss_fraction_span`, as each run reports it) and its
  absolute difference;
- the mean contact force, relative difference;
- the 0–20 Hz contact force (the band railway practice evaluates; scipy's
  4th-order Butterworth, zero phase, as taut's study::tolerance::filter),
  RMS of the difference over the in-span steps (x_m/L < 0.98) relative to
  the reference's RMS there;
- w under the carrier, the same measure;
- CPU seconds of the whole `taut run` process (user + system, the median of
  `--repeat` runs, history writing included; the machine's other load
  shows in wall time, much less in CPU time).

Usage: python3 scripts/modal_exact_study.py [--taut target/release/taut] [--repeat 3]
Prints a markdown table. Deterministic except the CPU times.
"""

import argparse
import csv
import json
import math
import os
import resource
import statistics
import subprocess
import tempfile

import numpy as np
from scipy.signal import butter, filtfilt

SPEED = "134.91570401925506"  # 0.9 c on the reference wire
SPAN = 0.98  # x_m/L below which a step is "in the span"
REF_DT = 1.25e-5
EXACT = 'integrator={ method = "modal_exact" }'

ROUTES = [
    ("reference: Hermite N = 3200, generalized-α", ["mesh.elements=3200"], REF_DT),
    ("Hermite N = 400, generalized-α", ["mesh.elements=400"], 1e-4),
    ("Hermite N = 800, generalized-α", ["mesh.elements=800"], 5e-5),
    ("Hermite N = 1600, generalized-α", ["mesh.elements=1600"], 6.25e-5),
    ("Hermite N = 1600, generalized-α", ["mesh.elements=1600"], 2.5e-5),
    ("galerkin J = 800, generalized-α", ["mesh.kind=galerkin", "mesh.modes=800"], 6.25e-5),
    ("galerkin J = 200, modal_exact", ["mesh.kind=galerkin", "mesh.modes=200", EXACT], 1e-4),
    ("galerkin J = 400, modal_exact", ["mesh.kind=galerkin", "mesh.modes=400", EXACT], 1e-4),
    ("galerkin J = 800, modal_exact", ["mesh.kind=galerkin", "mesh.modes=800", EXACT], 1e-4),
    ("galerkin J = 800, modal_exact", ["mesh.kind=galerkin", "mesh.modes=800", EXACT], 6.25e-5),
    ("galerkin J = 800, modal_exact", ["mesh.kind=galerkin", "mesh.modes=800", EXACT], 2.5e-5),
    ("galerkin J = 1600, modal_exact", ["mesh.kind=galerkin", "mesh.modes=1600", EXACT], 2.5e-5),
]


def run(taut, sets, dt, out, repeat):
    cmd = [taut, "run", "scenes/reference.toml", "--out", out, "--quiet",
           "--set", f"carrier.speed.cruise={SPEED}", "--set", f"time.step={dt!r}"]
    for s in sets:
        cmd += ["--set", s]
    cpu = []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    cols = {k: np.array([float(r[k]) for r in rows]) for k in ("t", "x_m", "beam_w", "force")}
    return cols, summary, statistics.median(cpu)


def lowpass(x, dt, hz=20.0):
    b, a = butter(4, hz * 2.0 * dt)
    return filtfilt(b, a, x)


def span_rms(a, b, x, length=50.0):
    m = x / length < SPAN
    return math.sqrt(np.sum((a[m] - b[m]) ** 2) / np.sum(b[m] ** 2))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--taut", default="target/release/taut")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, (label, sets, dt) in enumerate(ROUTES):
            cols, summary, cpu = run(args.taut, sets, dt, os.path.join(tmp, str(k)), args.repeat)
            results.append((label, dt, cols, summary, cpu))
    _, _, ref, ref_summary, _ = results[0]
    ref_f = lowpass(ref["force"], REF_DT)
    ref_c = ref_summary["carriers"][0]
    print("| route | Δt, s | P_l in span | ΔP_l | mean λ, N | Δ mean | 0–20 Hz λ error | w error | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, dt, cols, summary, cpu in results:
        c = summary["carriers"][0]
        stride = round(dt / REF_DT)
        n = len(cols["t"])
        rf, rw = ref_f[::stride][:n], ref["beam_w"][::stride][:n]
        f = lowpass(cols["force"], dt)
        e_f = span_rms(f, rf, cols["x_m"])
        e_w = span_rms(cols["beam_w"], rw, cols["x_m"])
        mean, ref_mean = c["force"]["mean"], ref_c["force"]["mean"]
        print(f"| {label} | {dt:g} | {c['loss_fraction_span']:.4f} | "
              f"{abs(c['loss_fraction_span'] - ref_c['loss_fraction_span']):.4f} | "
              f"{mean:.2f} | {abs(mean - ref_mean) / ref_mean:.1e} | {e_f:.1e} | {e_w:.1e} | "
              f"{cpu:.3f} |")


if __name__ == "__main__":
    main()
