#!/usr/bin/env python3
"""The figures of docs/discretizations.md, from taut's own CLI.

1. Modal truncation on the reference case: `mesh.kind = "modal"` with
   J = 25 … 799 (all FE unknowns of N = 400) against the Hermite run it is
   taken from: in-span errors (RMS of the difference over the steps with
   x_m/L < 0.98, relative to the reference's RMS there) of w under the
   carrier, of the raw contact force and of the 0–20 Hz contact force (the
   band railway practice evaluates; scipy's butter/filtfilt, the same
   design as taut's study::tolerance::filter), the observed rate of the
   last in J, P_l and its in-span part, wall time.
2. The same for `galerkin` against a fine Hermite run (N = 1600, the
   continuous answer's stand-in).
3. Graded meshes at equal unknowns (N = 400) on the reference case at a
   step that resolves the arrival (Δt = 2.5e-5 s): uniform against graded
   toward the supports, each against a uniform N = 1600 run: the in-span
   force error, and the support-zone part of P_l and the largest force
   in the zone (the arrival, docs/contact_loss.md).

Usage: python3 scripts/discretization_study.py [--taut target/release/taut]
Prints markdown tables. Deterministic except the wall times.
"""

import argparse
import csv
import json
import math
import os
import subprocess
import tempfile

SPAN = 0.98  # x_m/L below which a step is "in the span" (docs/contact_loss.md)


def run(taut, sets, out):
    cmd = [taut, "run", "scenes/reference.toml", "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return rows, summary


def span_error(rows, ref, col="force", length=50.0):
    """RMS of a − b over the in-span steps, relative to the RMS of b there."""
    a = [float(r[col]) for r in rows]
    b = [float(r[col]) for r in ref]
    return span_error_of(a, b, ref, length)


def span_error_of(a, b, ref, length=50.0):
    d2 = r2 = 0.0
    for x, y, r in zip(a, b, ref):
        if float(r["x_m"]) / length < SPAN:
            d2 += (x - y) ** 2
            r2 += y**2
    return math.sqrt(d2 / r2)


def force_0_20(rows):
    """The 0–20 Hz contact force: a zero-phase 2nd-order Butterworth pair,
    the design cut-off raised so the pair is −3 dB at 20 Hz (as taut's
    study::tolerance::filter)."""
    from scipy.signal import butter, filtfilt

    t = [float(r["t"]) for r in rows]
    fs = 1.0 / (t[1] - t[0])
    fd = 20.0 / (math.sqrt(2.0) - 1.0) ** 0.25
    b, a = butter(2, fd, fs=fs)
    return list(filtfilt(b, a, [float(r["force"]) for r in rows]))


def filtered_error(rows, ref):
    return span_error_of(force_0_20(rows), force_0_20(ref), ref)


def span_force_error(rows, ref):
    return span_error(rows, ref)


def zone_max_force(rows, zone, length=50.0):
    return max(
        (float(r["force"]) for r in rows if float(r["x_m"]) > length - zone),
        default=0.0,
    )


def truncation(taut, tmp, kind, js, ref_sets, extra):
    ref, rs = run(taut, ref_sets + extra, os.path.join(tmp, f"{kind}-ref"))
    c = rs["carriers"][0]
    print(
        f"\nreference: {rs['derived']['elements']} N = {rs['scene']['mesh']['elements']}, "
        f"P_l = {c['loss_fraction']:.5f} (in span {c['loss_fraction_span']:.5f}), "
        f"{rs['wall_seconds']:.3f} s wall\n"
    )
    print("| J | w error | force error (raw) | force error (0–20 Hz) | rate (0–20 Hz) | P_l | P_l in span | wall s |")
    print("|---|---|---|---|---|---|---|---|")
    prev = None
    for j in js:
        rows, s = run(
            taut,
            [f"mesh.kind={kind}", f"mesh.modes={j}"] + extra,
            os.path.join(tmp, f"{kind}-{j}"),
        )
        e = filtered_error(rows, ref)
        rate = "—" if prev is None or e == 0 else f"{math.log(prev[1] / e) / math.log(j / prev[0]):.2f}"
        c = s["carriers"][0]
        print(
            f"| {j} | {span_error(rows, ref, 'beam_w'):.3e} | {span_force_error(rows, ref):.3e} | {e:.3e} | {rate} | {c['loss_fraction']:.5f} | "
            f"{c['loss_fraction_span']:.5f} | {s['wall_seconds']:.3f} |"
        )
        prev = (j, e)


def grading(taut, tmp):
    dt = "time.step=2.5e-5"
    ref, rs = run(taut, ["mesh.elements=1600", dt], os.path.join(tmp, "g-ref"))
    zone = rs["carriers"][0]["support_zone"]
    c = rs["carriers"][0]
    print(
        f"\nreference: uniform N = 1600, Δt = 2.5e-5 s: P_l in span {c['loss_fraction_span']:.5f}, "
        f"at supports {c['loss_fraction_support']:.5f}, largest force within {zone:.3f} m of "
        f"x = L {zone_max_force(ref, zone):.1f} N\n"
    )
    print("| mesh (N = 400) | h_min m | force error (raw) | force error (0–20 Hz) | P_l in span | P_l at supports | largest force near x = L, N | wall s |")
    print("|---|---|---|---|---|---|---|---|")
    for label, sets in [
        ("uniform", []),
        ("supports, R = 4", ["mesh.grading=supports", "mesh.grading_ratio=4"]),
        ("supports, R = 8", ["mesh.grading=supports", "mesh.grading_ratio=8"]),
        ("supports, R = 16", ["mesh.grading=supports", "mesh.grading_ratio=16"]),
    ]:
        rows, s = run(taut, ["mesh.elements=400", dt] + sets, os.path.join(tmp, f"g-{label[:10]}"))
        c = s["carriers"][0]
        r = float(sets[1].split("=")[1]) if sets else 1.0
        # h_min of a supports grading: geometric sizes over a half span of 200 elements
        q = r ** (1 / 199) if r > 1 else 1.0
        h_min = 25.0 * (q - 1) / (q**200 - 1) if r > 1 else 50.0 / 400
        print(
            f"| {label} | {h_min:.4f} | {span_force_error(rows, ref):.3e} | {filtered_error(rows, ref):.3e} | "
            f"{c['loss_fraction_span']:.5f} | {c['loss_fraction_support']:.5f} | "
            f"{zone_max_force(rows, zone):.1f} | {s['wall_seconds']:.3f} |"
        )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--taut", default="target/release/taut")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print("## Modal truncation (reference case, N = 400, Δt = 1e-4 s)")
        truncation(a.taut, tmp, "modal", [25, 50, 100, 200, 400, 799], [], [])
        print("\n## Galerkin against a fine Hermite run (reference case, Δt = 1e-4 s)")
        truncation(a.taut, tmp, "galerkin", [25, 50, 100, 200, 400, 800], ["mesh.elements=1600"], [])
        print("\n## Graded meshes at equal unknowns (reference case, Δt = 2.5e-5 s)")
        grading(a.taut, tmp)


if __name__ == "__main__":
    main()
