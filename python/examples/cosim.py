"""Co-simulation from Python: an active pantograph under a PI controller.

The reference wire with its 1 kg mass–spring as a pantograph below the wire
(the bundled scene scenes/reference_below.toml: the spring's preload presses
it up, gravity pulls it down, k δ0 − m g = 39.5 N on a rigid wire).
A PI controller on the contact force drives an actuator force on the mass
through `taut.Simulation.apply_force`, step by step, to hold the force at
F_REF. The notebook-style cells (`# %%`) run in Jupyter/VS Code as they do
from the shell:

    python python/examples/cosim.py                # figures, out/cosim.png with matplotlib
    python python/examples/cosim.py --check        # exit 1 unless the checks hold (CI, < 20 s)

The checks: (1) with no force applied, a Simulation stepped in mixed groups
is taut.run bit for bit; (2) the controlled contact force's mean over the
cruise holds F_REF within FORCE_BAND while the passive one is far from it. The
steps out of contact over the cruise are printed (a few, where the raw
force's ripple dips: the controller acts on the force, not on the wire).
"""

# %% setup
from __future__ import annotations

import argparse
import pathlib
import sys
from typing import List, Optional

import numpy as np

import taut

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = "reference_below"  # a bundled scene: the carrier below the wire
# at a cut-down resolution (a few seconds of CPU)
SET = ["mesh.elements=200", "carrier.0.speed.cruise=80.0"]

F_REF = 70.0  # N: the contact force the controller holds
KP = 0.3  # N/N: proportional gain on the force error
KI = 60.0  # 1/s: integral gain (N of actuator per N·s of error)
U_MAX = 200.0  # N: the actuator's limit (the integral stops growing there)

# The controlled mean over the cruise is F_REF to within this, N: the integral
# action removes the mean error; what is left is the force's own ripple
# averaged over the cruise (measured: 0.4 N on this scene, 69.60 N).
FORCE_BAND = 1.5


# %% the passive pantograph, and the check that stepping is run
def passive_identity() -> bool:
    """A Simulation with nothing applied, stepped in mixed groups, gives
    taut.run's history bit for bit."""
    r = taut.run(SCENE, set=SET, progress=False)
    sim = taut.Simulation(SCENE, set=SET)
    groups = [1, 5, 2, 100]
    i = 0
    while not sim.done:
        sim.step(groups[i % len(groups)])
        i += 1
    s = sim.result()
    same = all(np.array_equal(r.history[c], s.history[c]) for c in r.history)
    print(f"passive: Simulation == taut.run bit for bit: {same}")
    return same


# %% the controlled pantograph
def controlled() -> taut.Run:
    """Step the run one step at a time; before each step, read the contact
    force and set the actuator force by a PI law (anti-windup at U_MAX)."""
    sim = taut.Simulation(SCENE, set=SET)
    integral = 0.0
    while not sim.done:
        c = sim.state.carriers[0]
        error = F_REF - c.force
        u = KP * error + KI * integral
        if abs(u) < U_MAX:
            integral += error * sim.dt
        # into the wire, whatever the side the carrier is on (here: up)
        sim.apply_force(0, float(np.clip(u, -U_MAX, U_MAX)), into_wire=True)
        sim.step()
    return sim.result()


# %% figures over the cruise (after the smooth start, before the far support)
def cruise(r: taut.Run) -> "np.ndarray":
    """The contact force over the cruise: after the ramp (x > L/5) and
    before the last tenth of the span."""
    x, f = r.history["x_m"], r.history["force"]
    return np.asarray(f[(x > 10.0) & (x < 45.0)])


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--check", action="store_true", help="exit 1 unless the checks hold")
    ap.add_argument("--plot", default=str(ROOT / "out" / "cosim.png"), help="figure file (needs matplotlib)")
    args = ap.parse_args(argv)

    same = passive_identity()
    passive = taut.run(SCENE, set=SET, progress=False)
    active = controlled()
    fp, fa = cruise(passive), cruise(active)
    print(f"passive: mean force {fp.mean():.2f} N, std {fp.std():.2f} N")
    print(f"PI ({F_REF} N): mean force {fa.mean():.2f} N, std {fa.std():.2f} N")
    x = np.asarray(active.history["x_m"])
    cruising = (x > 10.0) & (x < 45.0)
    lost = int(np.count_nonzero(~np.asarray(active.history["in_contact"], dtype=bool)[cruising]))
    print(f"PI: steps out of contact over the cruise: {lost}")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 3.5))
        ax.plot(passive.history["t"], passive.history["force"], lw=0.6, label="passive")
        ax.plot(active.history["t"], active.history["force"], lw=0.6, label=f"PI to {F_REF} N")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("contact force (N)")
        ax.legend()
        fig.tight_layout()
        pathlib.Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    except ImportError:
        pass

    if not args.check:
        return 0
    ok = True
    if not same:
        print("FAIL: a Simulation with nothing applied is not taut.run")
        ok = False
    if abs(fa.mean() - F_REF) > FORCE_BAND:
        print(f"FAIL: the controlled mean {fa.mean():.2f} N is not {F_REF} ± {FORCE_BAND} N")
        ok = False
    if abs(fp.mean() - F_REF) <= FORCE_BAND:
        print("FAIL: the passive mean already holds F_REF: the check would not see a controller")
        ok = False
    print("checks: " + ("ok" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
