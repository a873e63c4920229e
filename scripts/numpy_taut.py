#!/usr/bin/env python3
"""taut's method in plain numpy/scipy, and a timed, step-by-step comparison.

What this is
------------
A straightforward numpy/scipy implementation of the discrete method taut uses
(the project's physics contract MODEL.md, "MODEL" below), run on the same
scene and mesh as the taut binary, in one run of this script on one machine.
It

1. runs ``taut run <scene> --set mesh.elements=N --out DIR --quiet`` R times
   (best wall time; the in-process ``wall_seconds`` of its summary.json and the
   process wall time around the subprocess) and reads its ``history.csv``;
2. runs the numpy/scipy version R times (best wall time, split into
   assembly + factorization + initial state, and the step loop);
3. compares the two histories step by step (contact force λ, beam
   displacement under the carrier w, contact state, P_l) and prints a table
   of sizes, wall times, DOF-steps/s, the speed ratio and the agreement.

Both sides time the same work: model assembly, factorization of A, the
initial accelerations and the time loop with recording of the carrier
samples (taut's ``wall_seconds`` covers exactly that; its process wall time
adds start-up and writing history.csv/summary.json/force.svg).

How it maps onto taut
---------------------
- ``load_scene``: the subset of src/scene (mod.rs, validate.rs) the
  comparison needs: beam props (ρA, EI, T), supports, one mass–spring
  carrier (f0 = k δ0 − s m g, MODEL §2), unilateral or bilateral contact,
  Δt, the number of steps (floor(t_end/Δt·(1 + 4ε)), t_end the time the
  carrier leaves, as validate.rs), ρ∞, gravity. Other formulations, the
  `alpha` placement, moving forces and several carriers are refused, not
  ignored; probes (extra history columns only) are ignored.
- ``Motion``: src/model/motion.rs, the smooth ramp of MODEL §3
  (x_m(t) = ∫V, t0 = 2L/(5V0)) or constant speed.
- ``gen_alpha``: ``GenAlpha::from_rho_inf`` in src/integrate.rs (MODEL §5).
- ``element_matrices`` / ``Beam``: src/model/element.rs and
  src/model/beam.rs: Hermite elements with consistent mass, bending and
  tension (geometric) stiffness (MODEL §4), C0 string elements when EI = 0
  (MODEL §6); supported dofs removed; vectorised assembly into
  scipy.sparse (CSR, used for the per-step products M a and K u) and the
  symmetric band of A for LAPACK; ``Beam.point_vector`` is r_b(x) (the four
  shape functions of the element holding x, ``BeamModel::point_vector``).
- ``BandedCholesky``: the role of ``BandedLdlt`` in src/model/banded.rs:
  A = (1 − α_m)M + (1 − α_f)βΔt²K factored ONCE per run with
  ``scipy.linalg.cholesky_banded`` (LAPACK dpbtrf), each step solved with
  ``scipy.linalg.cho_solve_banded`` (dpbtrs) for the two right-hand sides
  [F, s r_f] at once, as taut's fused ``solve_many`` sweep does.
  ``--solver splu`` uses ``scipy.sparse.linalg.splu`` (SuperLU, factored
  once) instead, which is the faster of the two scipy solvers here.
- ``simulate``: ``Integrator::new``, ``initial_accelerations`` and
  ``Integrator::step`` of src/integrate.rs with the default ``end``
  placement, one step being MODEL §5 "One step, spelled out":
  predictors d̃, ṽ; F = f(t_f) − α_m M a_n − K[(1 − α_f)d̃ + α_f d_n];
  a★ = A⁻¹F and z = A⁻¹(s r_f) in one solve; the mass dof's free
  acceleration (it is not coupled to the beam except by the contact);
  g_free = r_gᵀ(d̃ + βΔt²a★) − (q̃ + βΔt²a_q★), W = βΔt²(s r_gᵀz + 1/A_q);
  the Lagrange law (src/contact/lagrange.rs, one contact: closed iff
  g_free < 0, then λ = −g_free/W; bilateral: always λ = −g_free/W);
  a = a★ + λz and the Newmark updates. Initial state (MODEL §5): beam
  straight and at rest, mass touching, M a₀ = f + λ r with the gap
  acceleration zero when the contact is closed.
- The recorded samples are those of ``Integrator::sample`` (x_m, w = s r_gᵀd,
  q, gap, λ, contact state) and P_l is src/record.rs's loss fraction (steps
  with the contact open over all steps); the columns of taut's history.csv
  are src/report/csv.rs's.

Agreement: both sides implement the same discrete method in double
precision, so the histories differ by round-off (different factorization,
summation order) only, and a contact state can only differ where |g_free|
is at round-off level.

How to run
----------
From the repository root::

    pip install -r scripts/requirements.txt && cargo build --release \\
        && python3 scripts/numpy_taut.py

    python3 scripts/numpy_taut.py --elements 400 800 1600 --repeat 3 \\
        --json out/numpy_comparison.json

Options: ``--scene`` (default scenes/reference.toml), ``--elements`` (one or
more N, repeatable, default 800), ``--repeat`` R (default 3), ``--taut``
(binary, default target/release/taut), ``--solver`` (cholesky_banded,
default, and/or splu), ``--json FILE``. Timings are only meaningful on an
otherwise idle machine; the load average is printed and stored with them.
"""

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

REPO = Path(__file__).resolve().parent.parent


# --------------------------------------------------------------------------
# Scene (src/scene)
# --------------------------------------------------------------------------


@dataclass
class Scene:
    length: float
    rho_a: float
    ei: float
    tension: float
    left: str
    right: str
    distributed_load: float
    elements: int
    mass: float
    stiffness: float
    damping: float
    f0: float  # k δ0 − s m g
    side: float  # s: +1 below, −1 above
    motion: "Motion"
    bilateral: bool
    dt: float
    steps: int
    rho_inf: float


def load_scene(path, elements):
    """Read a scene file and resolve it as src/scene/validate.rs does.

    Only the features the comparison needs are accepted: one mass–spring
    carrier, the Lagrange formulation and the `end` placement (probes only
    add history columns and are ignored).
    """
    with open(path, "rb") as fh:
        sc = tomllib.load(fh)
    b = sc["beam"]
    (car,) = sc["carrier"]  # exactly one carrier
    contact = sc.get("contact", {})
    unsupported = {
        "contact.formulation": contact.get("formulation", "lagrange") != "lagrange",
        "contact.placement": contact.get("placement", "end") != "end",
        "carrier.force": "force" in car,
    }
    bad = [k for k, v in unsupported.items() if v]
    if bad:
        raise SystemExit(f"{path}: not supported by this script: {', '.join(bad)}")
    gravity = sc.get("gravity", {})
    g = gravity.get("g", 9.81)
    rho_a = b["mass_per_length"] if "mass_per_length" in b else b["density"] * b["area"]
    ei = (b["bending_stiffness"] if "bending_stiffness" in b
          else b["youngs_modulus"] * b["second_moment"])
    length = b["length"]
    side = {"above": -1.0, "below": 1.0}[car["side"]]
    mass, k = car["mass"], car.get("stiffness", 0.0)
    motion = Motion(car["start"], car["speed"], length)
    end = sc["time"]["end"]
    t_end = motion.time_to_leave(length) if end == "carrier_leaves" else float(end)
    dt = sc["time"]["step"]
    return Scene(
        length=length,
        rho_a=rho_a,
        ei=ei,
        tension=b["tension"],
        left=b["left"],
        right=b["right"],
        distributed_load=-rho_a * g if gravity.get("beam_self_weight", False) else 0.0,
        elements=elements,
        mass=mass,
        stiffness=k,
        damping=car.get("damping", 0.0),
        f0=k * car.get("preload", 0.0) - side * mass * g,
        side=side,
        motion=motion,
        bilateral=contact.get("kind", "unilateral") == "bilateral",
        dt=dt,
        steps=int(math.floor(t_end / dt * (1.0 + 4.0 * sys.float_info.epsilon))),
        rho_inf=sc.get("integrator", {}).get("rho_inf", 1.0),
    )


class Motion:
    """Carrier kinematics x_m(t) (src/model/motion.rs, MODEL §3)."""

    def __init__(self, start, speed, length):
        self.start = start
        self.profile = speed["profile"]
        if self.profile == "smooth_ramp":
            self.v0 = speed["cruise"]
            self.t0 = 2.0 * length / (5.0 * self.v0)
        elif self.profile == "constant":
            self.v0 = speed["value"]
            self.t0 = 0.0
        else:
            raise SystemExit(f"unknown speed profile {self.profile!r}")

    def position(self, t):
        if self.profile == "constant":
            return self.start + self.v0 * t
        t0 = self.t0
        if t <= t0:
            travelled = self.v0 * (
                t * t / (2.0 * t0)
                + t0 / (4.0 * math.pi * math.pi) * (math.cos(2.0 * math.pi * t / t0) - 1.0)
            )
        else:
            travelled = self.v0 * (0.5 * t0 + (t - t0))
        return self.start + travelled

    def time_to_leave(self, length):
        dist = length - self.start
        if self.v0 == 0.0:
            raise SystemExit("time.end = \"carrier_leaves\" needs a moving carrier")
        if dist <= 0.0:
            return 0.0
        if self.profile == "constant":
            return dist / self.v0
        ramp_dist = 0.5 * self.v0 * self.t0
        if dist >= ramp_dist:
            return self.t0 + (dist - ramp_dist) / self.v0
        lo, hi = 0.0, self.t0  # position() is increasing on the ramp
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.position(mid) - self.start < dist else (lo, mid)
        return hi


def gen_alpha(rho):
    """(α_m, α_f, β, γ) from ρ∞ (Chung & Hulbert 1993, MODEL §5)."""
    am = (2.0 * rho - 1.0) / (rho + 1.0)
    af = rho / (rho + 1.0)
    gamma = 0.5 - am + af
    beta = 0.25 * (1.0 - am + af) ** 2
    return am, af, beta, gamma


# --------------------------------------------------------------------------
# Beam model (src/model/element.rs, src/model/beam.rs)
# --------------------------------------------------------------------------


def element_matrices(sc, h):
    """Element mass, stiffness and uniform-load vector (MODEL §4, §6)."""
    if sc.ei > 0.0:
        h2 = h * h
        me = sc.rho_a * h / 420.0 * np.array([
            [156.0, 22.0 * h, 54.0, -13.0 * h],
            [22.0 * h, 4.0 * h2, 13.0 * h, -3.0 * h2],
            [54.0, 13.0 * h, 156.0, -22.0 * h],
            [-13.0 * h, -3.0 * h2, -22.0 * h, 4.0 * h2]])
        kb = sc.ei / (h2 * h) * np.array([
            [12.0, 6.0 * h, -12.0, 6.0 * h],
            [6.0 * h, 4.0 * h2, -6.0 * h, 2.0 * h2],
            [-12.0, -6.0 * h, 12.0, -6.0 * h],
            [6.0 * h, 2.0 * h2, -6.0 * h, 4.0 * h2]])
        kt = sc.tension / (30.0 * h) * np.array([
            [36.0, 3.0 * h, -36.0, 3.0 * h],
            [3.0 * h, 4.0 * h2, -3.0 * h, -h2],
            [-36.0, -3.0 * h, 36.0, -3.0 * h],
            [3.0 * h, -h2, -3.0 * h, 4.0 * h2]])
        fe = sc.distributed_load * np.array([h / 2.0, h2 / 12.0, h / 2.0, -h2 / 12.0])
        return me, kb + kt, fe
    me = sc.rho_a * h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    ke = sc.tension / h * np.array([[1.0, -1.0], [-1.0, 1.0]])
    fe = sc.distributed_load * np.array([h / 2.0, h / 2.0])
    return me, ke, fe


class Beam:
    """Global M, K (CSR), load f and point vectors r_b(x), supports removed."""

    def __init__(self, sc):
        ne = sc.elements
        self.hermite = sc.ei > 0.0
        self.per_node = 2 if self.hermite else 1
        self.elements, self.h = ne, sc.length / ne
        self.bandwidth = 3 if self.hermite else 1
        pn = self.per_node
        removed = np.zeros((ne + 1) * pn, dtype=bool)
        for node, support in ((0, sc.left), (ne, sc.right)):
            if support in ("clamped", "pinned"):
                removed[node * pn] = True
            if support == "clamped" and pn == 2:
                removed[node * pn + 1] = True
        self.dof_of = np.where(removed, -1, np.cumsum(~removed) - 1)
        self.n = n = int((~removed).sum())

        me, ke, fe = element_matrices(sc, self.h)
        nd = 2 * pn
        conn = self.dof_of[pn * np.arange(ne)[:, None] + np.arange(nd)[None, :]]
        rows = np.broadcast_to(conn[:, :, None], (ne, nd, nd))
        cols = np.broadcast_to(conn[:, None, :], (ne, nd, nd))
        keep = (rows >= 0) & (cols >= 0)
        ij = (rows[keep], cols[keep])
        self.M = sp.coo_array((np.broadcast_to(me, rows.shape)[keep], ij), shape=(n, n)).tocsr()
        self.K = sp.coo_array((np.broadcast_to(ke, rows.shape)[keep], ij), shape=(n, n)).tocsr()
        self.load = np.zeros(n)
        free = conn >= 0
        np.add.at(self.load, conn[free], np.broadcast_to(fe, conn.shape)[free])

    def upper_band(self, a):
        """`a` in LAPACK's upper symmetric band storage: ab[p + i − j, j] = a[i, j]."""
        p = self.bandwidth
        ab = np.zeros((p + 1, self.n))
        for k in range(p + 1):
            ab[p - k, k:] = a.diagonal(k)
        return ab

    def point_vector(self, x):
        """r_b(x) as (free dof indices, shape-function values) (MODEL §4)."""
        ne, h = self.elements, self.h
        xi = min(max(x / h, 0.0), float(ne))
        e = min(int(math.floor(xi)), ne - 1)
        s = min(max(xi - e, 0.0), 1.0)
        if self.hermite:
            s2 = s * s
            s3 = s2 * s
            shape = (1.0 - 3.0 * s2 + 2.0 * s3, h * (s - 2.0 * s2 + s3),
                     3.0 * s2 - 2.0 * s3, h * (s3 - s2))
        else:
            shape = (1.0 - s, s)
        dofs = self.dof_of[self.per_node * e: self.per_node * (e + 2)]
        free = dofs >= 0
        return dofs[free], np.array(shape)[free]


class BandedCholesky:
    """A = UᵀU by LAPACK dpbtrf once; solves by dpbtrs (taut: BandedLdlt)."""

    def __init__(self, beam, a):
        self.cb = sla.cholesky_banded(beam.upper_band(a), lower=False, check_finite=False)

    def solve(self, b):
        return sla.cho_solve_banded((self.cb, False), b, check_finite=False)


class SparseLU:
    """A = LU by SuperLU once (scipy.sparse.linalg.splu); solves per step."""

    def __init__(self, beam, a):
        self.lu = spla.splu(sp.csc_array(a))

    def solve(self, b):
        return self.lu.solve(b)


SOLVERS = {"cholesky_banded": BandedCholesky, "splu": SparseLU}


# --------------------------------------------------------------------------
# Time integration (src/integrate.rs)
# --------------------------------------------------------------------------


def simulate(sc, solver="cholesky_banded"):
    """Run the scene; return the recorded history and the wall times."""
    t_start = time.perf_counter()
    am, af, beta, gamma = gen_alpha(sc.rho_inf)
    dt, s, motion = sc.dt, sc.side, sc.motion
    bdt2 = beta * dt * dt
    c_pred = (0.5 - beta) * dt * dt
    beam = Beam(sc)
    n, M, K, f = beam.n, beam.M, beam.K, beam.load
    # the effective matrix, factored once (MODEL §5)
    A_fac = SOLVERS[solver](beam, (1.0 - am) * M + (1.0 - af) * bdt2 * K)
    m, k, c, f0 = sc.mass, sc.stiffness, sc.damping, sc.f0
    a_eff = (1.0 - am) * m + (1.0 - af) * gamma * dt * c + (1.0 - af) * bdt2 * k

    steps = sc.steps
    hist = {
        "t": np.arange(steps + 1) * dt,
        "x_m": np.empty(steps + 1),
        "beam_w": np.empty(steps + 1),
        "mass_q": np.empty(steps + 1),
        "gap": np.empty(steps + 1),
        "force": np.empty(steps + 1),
        "in_contact": np.empty(steps + 1, dtype=bool),
    }

    # initial state: beam straight and at rest, mass touching (q = 0); loads on
    d, v = np.zeros(n), np.zeros(n)
    q = vq = 0.0
    x0 = motion.position(0.0)
    idx, val = beam.point_vector(x0)
    rhs = np.zeros((n, 2), order="F")
    rhs[:, 0] = f
    rhs[idx, 1] = s * val
    sol = SOLVERS[solver](beam, M).solve(rhs)  # M⁻¹[f, s r]
    g_free = s * (val @ sol[idx, 0]) - f0 / m  # free gap acceleration
    w_acc = s * (val @ sol[idx, 1]) + 1.0 / m
    lam, closed = contact_law(g_free, w_acc, sc.bilateral)
    a = sol[:, 0] + lam * sol[:, 1]
    aq = (f0 - lam) / m
    record(hist, 0, x0, s * (val @ d[idx]), q, lam, closed)
    t_setup = time.perf_counter()

    for step in range(1, steps + 1):
        t1 = step * dt
        tf = t1 - af * dt
        idx_f, val_f = beam.point_vector(motion.position(tf))
        x1 = motion.position(t1)
        idx_g, val_g = beam.point_vector(x1)
        # predictors and the free right-hand side F, with s r_f beside it
        d_pred = d + dt * v + c_pred * a
        u = (1.0 - af) * d_pred + af * d
        rhs[:, 0] = f - am * (M @ a) - K @ u
        rhs[:, 1] = 0.0
        rhs[idx_f, 1] = s * val_f
        sol = A_fac.solve(rhs)  # [a★, z] = A⁻¹[F, s r_f]
        a_star, z = sol[:, 0], sol[:, 1]
        # the mass dof, free step
        q_pred = q + dt * vq + c_pred * aq
        vq_pred = vq + (1.0 - gamma) * dt * aq
        fq = (f0 - am * m * aq - c * ((1.0 - af) * vq_pred + af * vq)
              - k * ((1.0 - af) * q_pred + af * q))
        aq_free = fq / a_eff
        # free gap, Delassus W, contact law (MODEL §5, §6)
        g_free = (s * (val_g @ d_pred[idx_g] + bdt2 * (val_g @ a_star[idx_g]))
                  - (q_pred + bdt2 * aq_free))
        w = bdt2 * (s * (val_g @ z[idx_g]) + 1.0 / a_eff)
        lam, closed = contact_law(g_free, w, sc.bilateral)
        # update
        a_new = a_star + lam * z
        v = v + dt * ((1.0 - gamma) * a + gamma * a_new)
        d = d_pred + bdt2 * a_new
        a = a_new
        aq_new = aq_free - lam / a_eff
        q += dt * vq + c_pred * aq + bdt2 * aq_new
        vq += dt * ((1.0 - gamma) * aq + gamma * aq_new)
        aq = aq_new
        record(hist, step, x1, s * (val_g @ d[idx_g]), q, lam, closed)
    t_end = time.perf_counter()
    return {
        "history": hist,
        "dofs": n + 1,
        "steps": steps,
        "setup_seconds": t_setup - t_start,
        "loop_seconds": t_end - t_setup,
        "wall_seconds": t_end - t_start,
    }


def contact_law(g_free, w, bilateral):
    """Lagrange multiplier, one contact (src/contact/lagrange.rs): (λ, closed)."""
    if bilateral or g_free < 0.0:
        return -g_free / w, True
    return 0.0, False


def record(hist, i, x, w, q, lam, closed):
    hist["x_m"][i] = x
    hist["beam_w"][i] = w
    hist["mass_q"][i] = q
    hist["gap"][i] = w - q
    hist["force"][i] = lam
    hist["in_contact"][i] = closed


# --------------------------------------------------------------------------
# taut, comparison, timing
# --------------------------------------------------------------------------


def run_taut(taut, scene, elements, out_dir):
    """One taut run; returns (process wall s, summary.json, history columns)."""
    cmd = [str(taut), "run", str(scene), "--set", f"mesh.elements={elements}",
           "--out", str(out_dir), "--quiet"]
    t0 = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{done.stderr}")
    summary = json.loads((out_dir / "summary.json").read_text())
    with open(out_dir / "history.csv") as fh:
        names = fh.readline().strip().split(",")
    data = np.loadtxt(out_dir / "history.csv", delimiter=",", skiprows=1, ndmin=2)
    hist = {name: data[:, j] for j, name in enumerate(names)}
    hist["in_contact"] = hist["in_contact"] != 0.0
    return wall, summary, hist


def loss_fraction(in_contact):
    """P_l: steps with the contact open over all steps (src/record.rs)."""
    return float(np.mean(~in_contact[1:]))


def switches(in_contact):
    return int(np.count_nonzero(in_contact[1:] != in_contact[:-1]))


def agreement(ref, other):
    """Step-by-step differences of λ and w, relative to their largest size."""
    if len(ref["t"]) != len(other["t"]):
        raise SystemExit(f"histories differ in length: {len(ref['t'])} vs {len(other['t'])}")
    dl = np.abs(ref["force"] - other["force"])
    dw = np.abs(ref["beam_w"] - other["beam_w"])
    lam_scale = max(np.abs(ref["force"]).max(), np.abs(other["force"]).max())
    w_scale = max(np.abs(ref["beam_w"]).max(), np.abs(other["beam_w"]).max())
    differ = np.flatnonzero(ref["in_contact"] != other["in_contact"])
    # before the first contact switch of either run: the pure round-off level
    sw = np.flatnonzero((ref["in_contact"][1:] != ref["in_contact"][:-1])
                        | (other["in_contact"][1:] != other["in_contact"][:-1]))
    pre = sw[0] + 1 if len(sw) else len(dl)
    return {
        "max_abs_dlambda": float(dl.max()),
        "max_rel_dlambda": float(dl.max() / lam_scale),
        "step_of_max_dlambda": int(dl.argmax()),
        "max_abs_lambda": float(lam_scale),
        "max_abs_dw": float(dw.max()),
        "max_rel_dw": float(dw.max() / w_scale),
        "max_abs_w": float(w_scale),
        "max_rel_dlambda_before_first_switch": float(dl[:pre].max() / lam_scale),
        "first_switch_step": int(pre) if len(sw) else None,
        "max_abs_dx_m": float(np.abs(ref["x_m"] - other["x_m"]).max()),
        "contact_state_differs_at_steps": differ.tolist(),
        "P_l_taut": loss_fraction(ref["in_contact"]),
        "P_l_numpy": loss_fraction(other["in_contact"]),
        "switches_taut": switches(ref["in_contact"]),
        "switches_numpy": switches(other["in_contact"]),
    }


# --check: the largest λ difference before the first contact switch, relative
# to max |λ|. Both sides solve the same discrete equations; they differ only in
# round-off (factorization and summation order), which the division of the
# free gap (a small difference of millimetre terms) by W magnifies to ~1e-11
# (measured: 9e-12 to 4e-11 for N = 400 to 1600). 1e-8 leaves three orders of
# margin and still catches any difference of method, which shows at 1e-3 or more.
CHECK_LAMBDA_BEFORE_SWITCH = 1e-8
# --check: the largest w difference over the whole run, relative to max |w|,
# for meshes whose contact sequences agree (measured 1e-13 to 2e-12).
CHECK_W = 1e-9


def check(rows):
    """Fail unless every numpy run agrees with taut to round-off: λ before the
    first contact switch, and, when both runs switch at the same steps, w and
    λ over the whole run. Meshes coarse enough to chatter (N ≤ 200 on the
    reference scene) part after a switch in both directions; that is the
    sensitivity of grazing contact to round-off, not a difference of method,
    so only the part before the first switch is checked there."""
    failures = []
    for r in rows:
        ag = r.get("agreement")
        if not ag:
            continue
        tag = f"N = {r['elements']} {r['implementation']}"
        if ag["max_rel_dlambda_before_first_switch"] > CHECK_LAMBDA_BEFORE_SWITCH:
            failures.append(f"{tag}: λ differs by {ag['max_rel_dlambda_before_first_switch']:.1e} "
                            f"of max |λ| before the first switch (allowed "
                            f"{CHECK_LAMBDA_BEFORE_SWITCH:.0e})")
        if not ag["contact_state_differs_at_steps"] and ag["max_rel_dw"] > CHECK_W:
            failures.append(f"{tag}: w differs by {ag['max_rel_dw']:.1e} of max |w| "
                            f"(allowed {CHECK_W:.0e})")
    for f in failures:
        print(f"CHECK FAILED: {f}")
    if failures:
        raise SystemExit(1)
    print("check: numpy/scipy and taut agree to round-off")


def compare(args, elements):
    scene = load_scene(args.scene, elements)
    rows = []
    with tempfile.TemporaryDirectory(prefix="numpy_taut_") as tmp:
        best_proc, best_inproc = math.inf, math.inf
        for r in range(args.repeat):
            out = Path(tmp) / f"taut_{elements}_{r}"
            proc, summary, taut_hist = run_taut(args.taut, args.scene, elements, out)
            best_proc = min(best_proc, proc)
            best_inproc = min(best_inproc, summary["wall_seconds"])
    dofs, steps = summary["derived"]["dofs"], summary["derived"]["steps"]
    taut_row = {
        "implementation": "taut",
        "elements": elements,
        "dofs": dofs,
        "steps": steps,
        "wall_seconds": best_inproc,
        "process_wall_seconds": best_proc,
        "taut_version": summary.get("taut_version"),
    }
    rows.append(taut_row)
    for solver in args.solver:
        best = None
        for _ in range(args.repeat):
            res = simulate(scene, solver)
            if best is None or res["wall_seconds"] < best["wall_seconds"]:
                best = res
        if (best["dofs"], best["steps"]) != (dofs, steps):
            raise SystemExit(f"size mismatch: numpy {best['dofs']} dofs, {best['steps']} "
                             f"steps; taut {dofs} dofs, {steps} steps")
        rows.append({
            "implementation": f"numpy/scipy ({solver})",
            "elements": elements,
            "dofs": best["dofs"],
            "steps": best["steps"],
            "wall_seconds": best["wall_seconds"],
            "setup_seconds": best["setup_seconds"],
            "loop_seconds": best["loop_seconds"],
            "speed_ratio": best["wall_seconds"] / best_inproc,
            "speed_ratio_vs_taut_process": best["wall_seconds"] / best_proc,
            "agreement": agreement(taut_hist, best["history"]),
        })
    for row in rows:
        row["dof_steps_per_second"] = row["dofs"] * row["steps"] / row["wall_seconds"]
    return rows


def print_table(rows):
    head = (f"{'implementation':<28} {'N':>5} {'dofs':>5} {'steps':>5} {'wall s':>8} "
            f"{'setup s':>8} {'loop s':>8} {'DOF-steps/s':>11} {'ratio':>6} "
            f"{'|Δλ|/|λ|':>9} {'|Δw|/|w|':>9} {'P_l':>13}")
    print(head)
    print("-" * len(head))
    for r in rows:
        ag = r.get("agreement")
        if r["implementation"] == "taut":
            extra = (f"{'':>8} {'':>8} {r['dof_steps_per_second']:11.3e} {'1':>6}"
                     f"  (process {r['process_wall_seconds']:.3f} s)")
        else:
            extra = (f"{r['setup_seconds']:8.3f} {r['loop_seconds']:8.3f} "
                     f"{r['dof_steps_per_second']:11.3e} {r['speed_ratio']:6.1f} "
                     f"{ag['max_rel_dlambda']:9.1e} {ag['max_rel_dw']:9.1e} "
                     f"{ag['P_l_numpy']:.4f}/{ag['P_l_taut']:.4f}")
        print(f"{r['implementation']:<28} {r['elements']:5d} {r['dofs']:5d} {r['steps']:5d} "
              f"{r['wall_seconds']:8.3f} {extra}")


def environment(args):
    env = {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "machine": platform.machine(),
        "processor": platform.processor(),
        "cpus": os.cpu_count(),
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "scene": str(args.scene),
        "taut": str(args.taut),
        "repeat": args.repeat,
    }
    try:
        head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "HEAD"],
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(REPO), "status", "--porcelain", "--",
                                "src", "Cargo.toml", "Cargo.lock"],
                               capture_output=True, text=True).stdout.strip()
        env["git_commit"] = head + ("+dirty" if dirty else "")
    except OSError:
        pass
    return env


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", type=Path, default=REPO / "scenes" / "reference.toml")
    ap.add_argument("--elements", type=int, nargs="+", action="extend", metavar="N",
                    help="mesh size(s) N (repeatable; default 800)")
    ap.add_argument("--repeat", type=int, default=3, help="best of R runs (default 3)")
    ap.add_argument("--taut", type=Path, default=REPO / "target" / "release" / "taut",
                    help="taut binary (default target/release/taut)")
    ap.add_argument("--solver", choices=sorted(SOLVERS), nargs="+", action="extend",
                    help="numpy-side solver(s) (default cholesky_banded)")
    ap.add_argument("--json", type=Path, help="write the figures to this file")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless the histories agree to round-off (CI)")
    args = ap.parse_args()
    args.elements = args.elements or [800]
    args.solver = args.solver or ["cholesky_banded"]
    if not args.taut.exists():
        raise SystemExit(f"no taut binary at {args.taut}: run `cargo build --release` "
                         "or pass --taut")
    env = environment(args)
    print(f"numpy {env['numpy']}, scipy {env['scipy']}, python {env['python']}, "
          f"{env['cpus']} cpus, load average {env['load_average']}")
    rows = []
    for elements in args.elements:
        rows += compare(args, elements)
    print_table(rows)
    for r in rows:
        ag = r.get("agreement")
        if ag:
            first = ag["first_switch_step"]
            before = (f"before the first contact switch (step {first})" if first is not None
                      else "no contact switch;")
            print(f"N = {r['elements']} {r['implementation']}: max |Δλ| = "
                  f"{ag['max_abs_dlambda']:.2e} N at step {ag['step_of_max_dlambda']} "
                  f"(max |λ| {ag['max_abs_lambda']:.1f} N); {before} "
                  f"{ag['max_rel_dlambda_before_first_switch']:.1e} relative; "
                  f"max |Δw| = {ag['max_abs_dw']:.2e} m; contact state differs at "
                  f"{len(ag['contact_state_differs_at_steps'])} steps; switches "
                  f"{ag['switches_numpy']} (numpy) / {ag['switches_taut']} (taut)")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"environment": env, "rows": rows}, indent=2) + "\n")
        print(f"wrote {args.json}")
    if args.check:
        check(rows)


if __name__ == "__main__":
    main()
