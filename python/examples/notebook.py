"""A notebook session with taut: any set of points, the wire, its modes, and a controller.

The cells (`# %%`) run in Jupyter or VS Code as they do from the shell; each
uses only what `pip install "./python[all]"` brings. On the bundled reference
scene (a 1 kg mass–spring under a 50 m wire at 100 m/s), cut to a few
seconds of CPU:

    python python/examples/notebook.py                    # prints, and out/notebook.png with matplotlib
    python python/examples/notebook.py --check            # exit 1 unless the checks hold (CI)

1. A non-grid study on the sweep's engine: a Latin hypercube in (tension,
   speed), batched and resumable like any sweep; each point is `taut.run`
   of its values bit for bit (checked on two points).
2. Snapshots of the wire, v(x) at chosen times: the supports stay at zero
   and the largest deflection is under the carrier (checked).
3. The mode shapes and natural frequencies (`taut.modes`): the first
   frequencies are the taut string's j·c/(2L) raised by the small bending
   stiffness (checked: within STRING_BAND above it).
4. A co-simulated controller (`taut.Simulation`): a proportional actuator
   on the carrier pulls the mean contact force toward a set point (checked:
   closer than the passive run's).
"""

# %% setup
from __future__ import annotations

import argparse
import pathlib
import sys
from typing import Any, Dict, List, Optional

import numpy as np

import taut

# the bundled reference scene, by name (works outside the repository)
SCENE = "reference"
# cut down for a notebook cell: a coarser mesh and half the run
SHORT: Dict[str, Any] = {"mesh.elements": 200, "time.end": 0.3}

# The first modes of the reference wire are the taut string's j·c/(2L)
# raised by bending (EI/(T L²) ≈ 1.7e-6) and by the clamped end's boundary
# layer: measured 1.40e-3 above the string for mode 1 on 200 elements
# (`taut modes scenes/reference.toml --set mesh.elements=200`); modes 1–4
# (1.42e-3, 1.47e-3, 1.53e-3) stay inside this band.
STRING_BAND = 5e-3


# %% 1. a Latin hypercube in (tension, speed) on the sweep's engine
def latin_hypercube(n: int, seed: int = 7) -> List[Dict[str, float]]:
    """n points in tension 2.01e4…4.02e4 N × speed 60…140 m/s, one per row
    and column of an n × n grid (a Latin hypercube), from a fixed seed."""
    rng = np.random.default_rng(seed)
    u = (np.stack([rng.permutation(n), rng.permutation(n)], axis=1) + rng.random((n, 2))) / n
    tension = 2.01e4 + u[:, 0] * (4.02e4 - 2.01e4)
    speed = 60.0 + u[:, 1] * (140.0 - 60.0)
    return [{"beam.tension": float(t), "carrier.speed.cruise": float(v)} for t, v in zip(tension, speed)]


def study() -> bool:
    points = latin_hypercube(8)
    t = taut.sweep(SCENE, points=points, set=SHORT, progress=False)
    print("point  tension N   speed m/s   P_l      force std N")
    for i, p in enumerate(points):
        print(
            f"{i:5d}  {p['beam.tension']:9.0f}   {p['carrier.speed.cruise']:9.2f}"
            f"   {t['loss_fraction'][i]:.4f}   {t['force_std'][i]:.3f}"
        )
    same = True
    for i in (0, 5):
        r = taut.run(SCENE, set={**SHORT, **points[i]}, progress=False)
        same &= bool(t["force_std"][i] == r.force_std and t["loss_fraction"][i] == r.loss_fraction)
    print(f"points 0 and 5 are taut.run of their values bit for bit: {same}")
    return same


# %% 2. snapshots of the wire v(x)
def snapshots() -> "tuple[taut.Run, bool]":
    wire = {**SHORT, "output.snapshots": [0.1, 0.2, 0.29], "output.snapshot_points": 201}
    r = taut.run(SCENE, set=wire, progress=False)
    s = r.snapshots
    assert s is not None
    ok = True
    for k, t in enumerate(s.t):
        # the carrier's position at that step, from the history
        i = int(np.argmin(np.abs(np.asarray(r.history["t"]) - t)))
        x_m = float(r.history["x_m"][i])
        v = s.v[k]
        x_peak = float(s.x[int(np.argmax(np.abs(v)))])
        print(f"t = {t:.4f} s: carrier at {x_m:6.2f} m, largest |v| {np.abs(v).max():.3e} m at {x_peak:6.2f} m")
        # supports at rest; the deflection's peak near the carrier (within
        # 2 m: the wave ahead of and behind it is smaller at these speeds)
        ok &= bool(v[0] == 0.0 and v[-1] == 0.0 and abs(x_peak - x_m) < 2.0)
    print(f"supports at zero and the peak under the carrier: {ok}")
    return r, ok


# %% 3. mode shapes and natural frequencies
def modes() -> "tuple[taut.Modes, bool]":
    m = taut.modes(SCENE, 4, set={"mesh.elements": 200})
    ok = True
    for j, (f, fs) in enumerate(zip(m.frequency_hz, m.string_hz), start=1):
        rel = (f - fs) / fs
        print(f"mode {j}: {f:.5f} Hz, string {fs:.5f} Hz, {rel:+.2e}")
        ok &= bool(0.0 <= rel < STRING_BAND)
    print(f"modes within {STRING_BAND} above the string: {ok}")
    return m, ok


# %% 4. a co-simulated controller
def controller(f_ref: float = 60.0, gain: float = 0.5) -> "tuple[float, float, bool]":
    """A proportional actuator of gain·(f_ref − λ) pressing the mass into the
    wire, set before every step through `apply_force`. Forces are + up
    (MODEL's v); the reference carrier rides above the wire, so pressing in
    is − up."""
    passive = taut.run(SCENE, set=SHORT, progress=False)
    sim = taut.Simulation(SCENE, set=SHORT)
    while not sim.done:
        lam = sim.state.carriers[0].force
        sim.apply_force(0, -gain * (f_ref - lam))
        sim.step()
    active = sim.result()
    fp = float(np.mean(passive.history["force"]))
    fa = float(np.mean(active.history["force"]))
    print(f"mean contact force: passive {fp:.2f} N, controlled {fa:.2f} N (set point {f_ref} N)")
    return fp, fa, abs(fa - f_ref) < abs(fp - f_ref)


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--check", action="store_true", help="exit 1 unless the checks hold")
    ap.add_argument("--plot", default=str(pathlib.Path(__file__).resolve().parents[2] / "out" / "notebook.png"), help="figure file (needs matplotlib)")
    args = ap.parse_args(argv)

    ok_study = study()
    r, ok_snap = snapshots()
    m, ok_modes = modes()
    _, _, ok_ctrl = controller()

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.5))
        s = r.snapshots
        assert s is not None
        for k, t in enumerate(s.t):
            a1.plot(s.x, s.v[k] * 1e3, label=f"t = {t:.2f} s")
        a1.set_xlabel("x (m)")
        a1.set_ylabel("v (mm)")
        a1.legend()
        for j in range(m.shapes.shape[0]):
            a2.plot(m.x, m.shapes[j], label=f"{m.frequency_hz[j]:.3f} Hz")
        a2.set_xlabel("x (m)")
        a2.set_ylabel("mode shape (mass-normalized)")
        a2.legend()
        fig.tight_layout()
        pathlib.Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    except ImportError:
        pass

    if not args.check:
        return 0
    checks = {
        "points are runs": ok_study,
        "snapshots": ok_snap,
        "modes near the string": ok_modes,
        "controller": ok_ctrl,
    }
    for name, ok in checks.items():
        if not ok:
            print(f"FAIL: {name}")
    print("checks: " + ("ok" if all(checks.values()) else "FAILED"))
    return 0 if all(checks.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
