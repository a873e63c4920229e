#!/usr/bin/env python3
"""The hostile pass: scripted bad input against the `taut` binary.

Every case runs under a time limit and an address-space limit (`ulimit -v`)
and is judged by what came out:

* hang: killed at the time limit;
* abort: ended by a signal (a panic that aborts, SIGABRT, SIGSEGV, the
  kernel's OOM kill under the limit);
* bad exit: a status other than 0 (done), 1 (refused or stopped, with an
  `error: ` line) or 2 (the argument parser's refusal);
* panic: `panicked` anywhere in the output;
* unbounded message: an error longer than 20 000 characters;
* thread dependence: a sweep whose `sweep.csv` differs between --threads 1
  and 2 (modal and Hermite).

Families (the failure classes of the second round and a fuzz):
  kinds      every bundled scene x every mesh kind x every method;
  set-fuzz   every scalar key of every bundled scene set to hostile values
             (0, -1, 1e-300, -1e-300, 1e300, 1.7e308, nan, inf, a 100 kB
             string, a wrong type, ...);
  text-fuzz  bundled scenes mutated (lines dropped, duplicated, truncated,
             bytes flipped, NUL and invalid UTF-8 inserted), seeded;
  inputs     /dev/zero, /dev/urandom and oversized files as scene, gate case,
             replay file; a run record outside the grid;
  axes       sweeps over axes a plot cannot draw;
  studies    costly converge/precision/compare/sweep (refused at once);
  options    every integer option of every subcommand given text that is
             not in its range (-1, 0, x, 1.5, "", 2^32, 10^23, ...);
  threads    sweeps on 1 and 2 threads compared byte for byte, and a modal
             run pinned to one CPU (`taskset -c 0`) against the same run
             unpinned (skipped, saying so, without taskset).

Families of the third round, each case judged as above and, where
its name is in `must`, by the key its error must name:
  budget     every key that sizes a run's memory or files (lines, droppers,
             attachments, probes, fields, snapshots, clarabel's solvers):
             refused naming the key, or run to the end under the address
             limit; a finished run's folder holds no INCOMPLETE marker;
  points     --points files whose columns set one value twice (refused,
             naming both), wider than the cap (a short error), with a byte
             order mark (read), and a FIFO (refused);
  paths      errors of a [line] scene's explicit droppers and attachments:
             the key the error names is taken by --set;
  tables     every table given as a positional array (refused);
  folders    a shard into a folder holding the whole sweep (refused, the
             folder's tables kept), a run whose writing fails (its
             folder marked INCOMPLETE, no summary.json), a good folder
             of run, compare, modes, converge and uncertainty kept byte
             for byte by a typo, a missing scene, a bad value and a
             diverging run, two runs on one folder (one refused naming
             the holder, never a mixed folder), a folder that cannot be
             written (refused before the work), an uncertainty whose
             family diverged (exit 1), a compare some of whose runs
             stopped (exit 1, the good folder kept), a report into a
             folder a command is writing (refused);
  plausible  lumped stiffnesses, masses and dashpots at 5e-324, 1e-300 and
             1e300 (refused naming the key); every key of a line, a
             dropper's design height and a cruise speed at 0, -1, 5e-324,
             1e308, NaN and inf (run, or refused naming the key written,
             no NaN in the message); the messenger's supports and
             clamps, a pantograph's uplift at 1e308 and 3e152, and a saved
             contact problem with nulls (replay says why);
  fifo       a FIFO as scene, points file, run record, gate case, table file
             and replay file (refused or run again, never waited on);
  messages   the flag of --check-refinement, half_waves = 0, reference.modes'
             range, the messenger under central_difference;
  python     (when `import taut` works) the Python classes: `set` removals'
             field, `progress`, strings for numbers, wide and aliased
             points, Ctrl-C of runs in a thread pool.

Usage: python3 scripts/hostile_pass.py [--taut target/release/taut]
       [--jobs 2] [--limit-s 120] [--seed 25] [--quick | --sample N]
       [--count] [--only FAMILY,...]
Prints one line per finding and a summary `N passed, M failed`; exits 1 on
any finding.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted((ROOT / "scenes").glob("*.toml"))
KINDS = [[], ["--set", "mesh.kind=modal", "--set", "mesh.modes=20"],
         ["--set", "mesh.kind=galerkin", "--set", "mesh.modes=20"]]
METHODS = ["generalized_alpha", "newmark", "hht", "wbz", "bathe",
           "central_difference", "moreau_jean"]
HOSTILE = ["0", "-1", "1e-300", "-1e-300", "1e300", "1.7e308", "-1.7e308",
           "nan", "inf", "-inf", "1e-320", "4294967297", "18446744073709551617",
           '""', "true", "[]", "{}", '"x"', '"' + "y" * 100_000 + '"']
# a short run: the fuzz is about input, not long runs
SHORT = ["--set", "time.end=0.02"]
MAX_MESSAGE = 20_000
ADDRESS_KIB = 4 << 20  # 4 GiB of address space: a run plans at most 2 GiB


class Runner:
    def __init__(self, taut: str, limit_s: int, work: Path):
        self.taut, self.limit_s, self.work = taut, limit_s, work
        self.count = 0

    def run(self, name: str, args, cwd: Path | None = None,
            must: str | None = None) -> list[str]:
        """Run one case; return its findings (empty: passed). With `must`,
        the case must exit 1 with `must` in its error. A case that is a
        callable runs itself (given this runner) and returns its findings."""
        if callable(args):
            return args(self)
        p = self.proc(args, cwd)
        if p is None:
            return [f"{name}: hang (killed after {self.limit_s} s)"]
        return self.verdict(name, p, must)

    def proc(self, args: list[str], cwd: Path | None = None):
        """Run taut under the limits; None when killed at the time limit."""
        cmd = ["bash", "-c", f"ulimit -v {ADDRESS_KIB}; exec \"$0\" \"$@\"", self.taut, *args]
        try:
            return subprocess.run(cmd, capture_output=True, timeout=self.limit_s,
                                  cwd=cwd or self.work)
        except subprocess.TimeoutExpired:
            return None

    def judged(self, name: str, args: list[str], must: str | None = None) -> tuple:
        """(findings, the process or None) for a case that checks more."""
        p = self.proc(args)
        if p is None:
            return [f"{name}: hang (killed after {self.limit_s} s)"], None
        return self.verdict(name, p, must), p

    def verdict(self, name: str, p, must: str | None) -> list[str]:
        """The findings of a finished process (module doc)."""
        out = (p.stdout + p.stderr).decode("utf-8", "replace")
        found = []
        if p.returncode < 0:
            found.append(f"{name}: abort (signal {-p.returncode})")
        elif p.returncode not in (0, 1, 2):
            found.append(f"{name}: exit {p.returncode}")
        if "panicked" in out:
            found.append(f"{name}: panic: {out[out.find('panicked'):][:300]}")
        err = p.stderr.decode("utf-8", "replace")
        if p.returncode == 1 and "error: " not in err and "stopped with an error" not in err \
                and "stopped" not in out and "FAIL" not in out and "ERROR" not in out:
            found.append(f"{name}: exit 1 without an error line: {err[:200]!r}")
        if len(err) > MAX_MESSAGE:
            found.append(f"{name}: unbounded message ({len(err)} characters)")
        if must is not None and (p.returncode != 1 or must not in err):
            found.append(f"{name}: exit {p.returncode} without {must!r}: {err[:200]!r}")
        return found


def scalar_keys(text: str) -> list[str]:
    """Dotted keys of the scalar values of a scene (tables and carriers)."""
    keys, table = [], ""
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        m = re.match(r"^\[\[?([\w.]+)\]\]?$", line)
        if m:
            table = m.group(1)
            continue
        m = re.match(r"^([\w]+)\s*=\s*[^{\[]", line)
        if m and table:
            keys.append(f"{table}.{m.group(1)}")
    return sorted(set(keys))


def mutate(text: str, rng: random.Random) -> bytes:
    lines = text.splitlines(keepends=True)
    op = rng.randrange(7)
    if op == 0 and lines:
        del lines[rng.randrange(len(lines))]
    elif op == 1 and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
    elif op == 2:
        return text.encode()[: rng.randrange(len(text) + 1)]
    elif op == 3:
        b = bytearray(text.encode())
        for _ in range(rng.randrange(1, 8)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b)
    elif op == 4 and lines:
        i = rng.randrange(len(lines))
        lines[i] = re.sub(r"=\s*[-\d.e+]+", "= " + rng.choice(HOSTILE[:12]), lines[i])
    elif op == 5:
        return text.encode() + b"\x00\xff\xfe"
    elif op == 6 and lines:
        i = rng.randrange(len(lines))
        lines[i] = lines[i].replace("=", "= [", 1)
    return "".join(lines).encode()


def fifo(path: Path) -> bool:
    """Make a FIFO at `path`; False where the system cannot."""
    try:
        os.mkfifo(path)
        return True
    except (AttributeError, OSError):
        return False


def dropper_tables(n: int, length: float) -> str:
    """`n` taut [[dropper]] tables along a span of `length` m."""
    return "".join(
        f"\n[[dropper]]\nx = {length * (i + 0.5) / n}\nstiffness = 1.0e5\n"
        "anchor_height = 1.2\nlength = 1.199\n" for i in range(n))


def round_three(work: Path, must: dict, out) -> list:
    """The cases of the third round's classes (module doc)."""
    cases: list = []
    ref = str(ROOT / "scenes" / "reference.toml")
    line = str(ROOT / "scenes" / "line_10_spans.toml")
    drops = str(ROOT / "scenes" / "span_droppers.toml")
    panto = str(ROOT / "scenes" / "pantograph_3mass.toml")
    short = ["--set", "time.end=0.002"]
    files = work / "r3"
    files.mkdir()

    def add(name: str, args, key: str | None = None) -> None:
        cases.append((name, args))
        if key is not None:
            must[name] = key

    # budget: the commands that once failed, then grids over the size-driving keys
    many = files / "droppers_30000.toml"
    many.write_text((ROOT / "scenes" / "reference.toml").read_text() + dropper_tables(30000, 50.0))
    attach = files / "attachments_100000.toml"
    attach.write_text((ROOT / "scenes" / "reference.toml").read_text() + "".join(
        f"\n[[attachment]]\nx = {50.0 * (i + 0.5) / 100000}\nstiffness = 1.0\n" for i in range(100000)))
    add("budget line.spans=1000", ["run", line, "--set", "line.spans=1000", *short, *out("b")],
        "`line.droppers`")
    add("budget 30000 droppers", ["run", str(many), *short, *out("b")], "`dropper`")
    add("budget line.droppers.count=100 element_length=0.01",
        ["run", line, "--set", "line.droppers.count=100", "--set", "line.element_length=0.01",
         *out("b")], "`line.droppers`")
    add("budget field 1e6 points", ["run", ref, "--set", "time.end=0.01", "--set",
                                    "output.field={every=1, points=1000000}", *out("b")],
        "`output.field`")
    snaps = ", ".join(str(0.6 * k / 200) for k in range(200))
    add("budget 200 snapshots x 1e6 points",
        ["run", ref, "--set", f"output.snapshots=[{snaps}]", "--set",
         "output.snapshot_points=1000000", *out("b")], "`output.snapshots`")
    add("budget 100000 attachments", ["run", str(attach), *short, *out("b")])
    for spans in [1, 30, 1000]:
        for count in [1, 30, 100]:
            for h in [0.5, 0.05, 0.01]:
                add(f"budget line spans={spans} droppers={count} h={h}",
                    ["run", line, "--set", f"line.spans={spans}", "--set",
                     f"line.droppers.count={count}", "--set", f"line.element_length={h}",
                     *short, *out(f"bl{spans}_{count}_{h}")])
    for every in [1, 10]:
        for pts in [1000, 100000, 1000000]:
            for end in ["0.01", "0.1"]:
                add(f"budget field every={every} points={pts} end={end}",
                    ["run", ref, "--set", f"time.end={end}", "--set",
                     f"output.field={{every={every}, points={pts}}}", *out(f"bf{every}_{pts}_{end}")])
    for k in [1, 50, 200]:
        for pts in [10000, 1000000]:
            ts = ", ".join(str(0.01 * i / k) for i in range(k))
            add(f"budget snapshots={k} points={pts}",
                ["run", ref, "--set", "time.end=0.01", "--set", f"output.snapshots=[{ts}]",
                 "--set", f"output.snapshot_points={pts}", *out(f"bs{k}_{pts}")])
    add("budget clarabel line", ["run", line, "--set", "line.spans=3", "--set",
                                 "line.droppers.count=30", "--set", "contact.formulation=complementarity",
                                 "--set", "contact.complementarity.solver=clarabel", *short, *out("bc")])

    # a finished run's folder holds no INCOMPLETE marker
    def finished_whole(r) -> list[str]:
        d = work / "whole"
        found, p = r.judged("budget finished folder whole", ["run", ref, *short, "--out", str(d), "--quiet"])
        if p is not None and p.returncode == 0 and (d / "INCOMPLETE").exists():
            found.append("budget finished folder whole: INCOMPLETE left in a finished run's folder")
        return found
    add("budget finished folder whole", finished_whole)

    # points: one value per key, bounded width, a BOM, a FIFO
    for pair in [("carrier.mass", "carrier.0.mass"), ("carrier.speed.cruise", "speed_ratio"),
                 ("carrier.0.speed", "carrier.speed.cruise"), ("beam.tension", "tension_ratio"),
                 ("mass_ratio", "carrier.0.mass"), ("stiffness_ratio", "carrier.stiffness")]:
        f = files / f"points_{pair[0]}_{pair[1]}.csv"
        value = "{ profile = \"constant\", value = 10 }" if pair[0] == "carrier.0.speed" else "1.0"
        f.write_text(f"{pair[0]},{pair[1]}\n{'1.0' if value == '1.0' else '1.0'},0.5\n")
        add(f"points alias {pair[0]},{pair[1]}", ["sweep", ref, "--points", str(f), *short,
                                                   *out(f"pa{len(cases)}")], "both set")
    wide = files / "points_wide.csv"
    wide.write_text(",".join(f"beam.k{i}" for i in range(40000)) + "\n"
                    + ",".join("1" for _ in range(40000)) + "\n")
    add("points 40000 columns", ["sweep", ref, "--points", str(wide), *out("pw")], "40000 columns")

    def short_message(r) -> list[str]:
        found, p = r.judged("points wide message", ["sweep", ref, "--points", str(wide), *out("pw2")])
        if p is not None and len(p.stderr) > 1000:
            found.append(f"points wide message: {len(p.stderr)} characters for a wide file")
        return found
    add("points wide message", short_message)
    bom = files / "points_bom.csv"
    bom.write_text("\ufeffcarrier.mass\n1.0\n1.2\n", encoding="utf-8")
    add("points bom", ["sweep", ref, "--points", str(bom), "--set", "time.end=0.01",
                       "--set", "mesh.elements=50", *out("pb")])

    def bom_read(r) -> list[str]:
        found, p = r.judged("points bom read", ["sweep", ref, "--points", str(bom), "--set",
                                                "time.end=0.01", "--set", "mesh.elements=50",
                                                "--out", str(work / "pbom"), "--quiet"])
        if p is not None and p.returncode != 0:
            found.append(f"points bom read: exit {p.returncode}: {p.stderr[:200]!r}")
        return found
    add("points bom read", bom_read)
    fifo_points = files / "points.fifo"
    if fifo(fifo_points):
        add("points fifo", ["sweep", ref, "--points", str(fifo_points), *out("pf")], "FIFO")

    # paths: the key an error names is one --set takes
    line_text = (ROOT / "scenes" / "line_10_spans.toml").read_text()
    bad_dropper = files / "line_bad_dropper.toml"
    bad_dropper.write_text(line_text + "\n[[dropper]]\nname = \"extra\"\nx = 12.0\n"
                           "stiffness = -1.0\nanchor_height = 1.2\nlength = 1.199\n")
    typo_dropper = files / "line_typo_dropper.toml"
    typo_dropper.write_text(line_text + "\n[[dropper]]\nname = \"extra\"\nx = 12.0\n"
                            "stifness = 1.0e5\nanchor_height = 1.2\nlength = 1.199\n")
    bad_attach = files / "line_bad_attachment.toml"
    bad_attach.write_text(line_text + "\n[[attachment]]\nx = 12.0\nmass = -1.0\n")
    for name, scene, sets in [
        ("explicit dropper", bad_dropper, []),
        ("explicit dropper typo", typo_dropper, []),
        ("explicit attachment", bad_attach, []),
        ("generated dropper stiffness", Path(line), ["--set", "line.dropper_stiffness=5e-324"]),
        ("generated steady arm", Path(line), ["--set", "line.steady_arm.mass=1e300"]),
    ]:
        def paste_back(r, name=name, scene=scene, sets=sets) -> list[str]:
            case = f"paths {name}"
            found, p = r.judged(case, ["run", str(scene), *sets, *short, *out("pp")])
            err = p.stderr.decode("utf-8", "replace") if p is not None else ""
            m = re.search(r"(?:invalid scene: |at )`([^`]+)`", err)
            if p is None or p.returncode != 1 or m is None:
                return found + [f"{case}: no key named: {err[:200]!r}"]
            key = m.group(1)
            again = r.proc(["run", str(scene), *sets, "--set", f"{key}=1", *short, *out("pq")])
            text = again.stderr.decode("utf-8", "replace") if again is not None else ""
            if "invalid override" in text:
                found.append(f"{case}: the error names `{key}`, which --set refuses: {text[:200]!r}")
            return found
        add(f"paths {name}", paste_back)

    # tables: positional arrays refused
    for scene, key, value in [
        (ref, "beam.damping", "[1.0, 2.0]"), (ref, "attachment", "[[10.0, 1e4]]"),
        (ref, "dropper", "[[10.0, 1e5, 1.2, 1.199]]"), (ref, "messenger", "[1.6e4, 1.07, 100.0, 1.6]"),
        (ref, "time", "[1e-4, 0.1]"), (ref, "integrator", "[\"newmark\"]"),
        (ref, "contact", "[\"unilateral\"]"), (ref, "contact.penalty", "[1e5]"),
        (ref, "gravity", "[9.81]"), (ref, "output", "[1]"), (ref, "output.field", "[1, 10]"),
        (ref, "carrier.0.speed", "[\"constant\", 10.0]"), (ref, "carrier", "[[1.0, 987.0]]"),
        (ref, "probe", "[[\"p\", 1.0]]"), (ref, "mesh", "[400]"), (ref, "reference", "[\"richardson\"]"),
        (ref, "beam", "[50.0]"), (line, "line", "[10, 55.0]"), (line, "line.messenger", "[1.6e4, 1.07]"),
        (line, "line.steady_arm", "[1.0, 2.0]"), (ref, "carrier.0.speed.profile", "[\"constant\"]"),
        (ref, "carrier.0.external_force", "[[0.0, 1.0], [0.0, 1.0]]"),
    ]:
        add(f"tables {Path(scene).stem} {key}", ["run", scene, "--set", f"{key}={value}",
                                                  *out("ta")], "not an array" if key != "carrier.0.speed.profile" else "carrier.0.speed")

    # folders: a shard into a whole sweep's folder; a run whose writing fails
    def shard_into_whole(r) -> list[str]:
        case = "folders shard into a whole sweep"
        d = work / "whole_sweep"
        sweep = ["sweep", ref, "--vary", "carrier.speed.cruise=90:110:3", "--set", "time.end=0.01",
                 "--set", "mesh.elements=50", "--out", str(d), "--quiet"]
        found, p = r.judged(case, sweep)
        if p is None or p.returncode != 0:
            return found + [f"{case}: the whole sweep did not run"]
        before = (d / "sweep.csv").read_bytes()
        found2, p2 = r.judged(case, [*sweep, "--shard", "0/2"], "`--shard`")
        found += found2
        if not (d / "sweep.csv").exists() or (d / "sweep.csv").read_bytes() != before:
            found.append(f"{case}: the whole sweep's sweep.csv was changed")
        return found
    add("folders shard into a whole sweep", shard_into_whole)

    def failed_writing(r) -> list[str]:
        case = "folders failed writing"
        d = work / "failed_write"
        (d / "force.svg").mkdir(parents=True)
        found, p = r.judged(case, ["run", ref, *short, "--out", str(d), "--quiet"])
        if p is None or p.returncode != 1:
            found.append(f"{case}: exit {None if p is None else p.returncode}, not 1")
        if not (d / "INCOMPLETE").exists() or (d / "summary.json").exists():
            found.append(f"{case}: the folder looks complete (no INCOMPLETE, or a summary.json)")
        return found
    add("folders failed writing", failed_writing)

    # folders: a good result survives every command that stops
    good = ["--set", "mesh.elements=20", "--set", "time.end=0.02"]
    diverges = ["--set", "contact.placement=alpha", "--set", "contact.kind=bilateral",
                "--set", "carrier.speed.cruise=120", "--set", "time.end=0.1",
                "--set", "mesh.elements=400"]

    def snapshot(d: Path) -> dict:
        return {f.name: f.read_bytes() for f in d.iterdir() if f.is_file()} if d.is_dir() else {}

    for command, own in [("run", []), ("compare", []), ("modes", ["--count", "3"]),
                         ("converge", ["--levels", "3", "--refine", "step"]),
                         ("uncertainty", ["--levels", "3"])]:
        def survives(r, command=command, own=own) -> list[str]:
            case = f"folders {command} survives"
            d = work / f"survive_{command}"
            quiet = [] if command == "modes" else ["--quiet"]
            found, p = r.judged(case, [command, ref, *good, *own, "--out", str(d), *quiet])
            if p is None or p.returncode != 0:
                return found + [f"{case}: the good {command} did not run"]
            before = snapshot(d)
            stops = [("typo", ref, ["--set", "mesh.elemnts=5"]),
                     ("missing scene", str(files / "no_such.toml"), []),
                     ("bad value", ref, ["--set", "mesh.elements=-1"])]
            if command != "modes":
                stops.append(("diverging", ref, diverges))
            for what, scene, extra in stops:
                f2, p2 = r.judged(case, [command, scene, *good, *own, *extra, "--out", str(d), *quiet])
                found += f2
                if p2 is None or p2.returncode != 1:
                    found.append(f"{case}: {what}: exit {None if p2 is None else p2.returncode}, not 1")
                if snapshot(d) != before:
                    found.append(f"{case}: {what}: the good folder changed")
            return found
        add(f"folders {command} survives", survives)

    def compare_partial(r) -> list[str]:
        case = "folders compare with stopped runs"
        d = work / "compare_partial"
        found, p = r.judged(case, ["compare", ref, *good, "--out", str(d), "--quiet"])
        if p is None or p.returncode != 0:
            return found + [f"{case}: the good compare did not run"]
        before = snapshot(d)
        f2, p2 = r.judged(case, ["compare", ref, "--reference", "impact", *diverges,
                                 "--out", str(d), "--quiet"])
        found += f2
        if p2 is None or p2.returncode != 1:
            found.append(f"{case}: exit {None if p2 is None else p2.returncode}, not 1")
        if snapshot(d) != before:
            found.append(f"{case}: the good folder changed")
        return found
    add("folders compare with stopped runs", compare_partial)

    def report_claims(r) -> list[str]:
        case = "folders report beside a writer"
        d = work / "report_claims"
        found, p = r.judged(case, ["run", ref, *good, "--out", str(d), "--quiet"])
        if p is None or p.returncode != 0:
            return found + [f"{case}: the good run did not run"]
        # a run of seconds holds the folder while the report tries it
        w = subprocess.Popen([r.taut, "run", ref, "--set", "mesh.elements=3000", "--set",
                              "time.step=1e-5", "--set", "output.record_every=100",
                              "--out", str(d), "--quiet"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        import time
        deadline = time.monotonic() + 30
        while not (d / "sweep.lock").exists() and time.monotonic() < deadline:
            time.sleep(0.02)
        f2, p2 = r.judged(case, ["report", str(d)])
        w.kill()
        w.wait()
        found += f2
        if p2 is None or p2.returncode != 1 or "in use by another command" not in \
                p2.stderr.decode("utf-8", "replace"):
            found.append(f"{case}: a report wrote beside a running command")
        return found
    add("folders report beside a writer", report_claims)

    def two_writers(r) -> list[str]:
        case = "folders two writers"
        found = []
        for trial in range(5):
            d = work / f"two_{trial}"
            procs = [subprocess.Popen([r.taut, "run", ref, "--set", "mesh.elements=40", "--set",
                                       f"time.end={end}", "--out", str(d), "--quiet"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                     for end in ["0.2", "0.25"]]
            outs = [(q.wait(timeout=r.limit_s), q.stderr.read().decode("utf-8", "replace"))
                    for q in procs]
            codes = [c for c, _ in outs]
            if 0 not in codes:
                found.append(f"{case}: neither run finished: {outs}")
                continue
            for c, err in outs:
                if c != 0 and "in use by another command" not in err:
                    found.append(f"{case}: a refused writer does not name the holder: {err[:200]!r}")
            rows = len((d / "history.csv").read_text().splitlines()) - 1
            steps = __import__("json").loads((d / "summary.json").read_text())["derived"]["steps"]
            if rows != steps + 1 or (d / "INCOMPLETE").exists():
                found.append(f"{case}: a mixed folder ({rows} rows for {steps} steps)")
        return found
    add("folders two writers", two_writers)

    def unwritable(r) -> list[str]:
        case = "folders unwritable"
        blocker = files / "a_file"
        blocker.write_text("x")
        import time
        t = time.perf_counter()
        found, p = r.judged(case, ["modes", line, "--count", "50", "--out", str(blocker / "o")])
        took = time.perf_counter() - t
        if p is None or p.returncode != 1:
            found.append(f"{case}: exit {None if p is None else p.returncode}, not 1")
        if took > 10:
            found.append(f"{case}: refused after {took:.1f} s: it computed first")
        return found
    add("folders unwritable", unwritable)
    add("folders uncertainty nothing estimated",
        ["uncertainty", ref, "--levels", "3", *diverges, *out("un")], "diverged")
    for v in ["1e308", "3e152"]:
        add(f"plausible pantograph uplift_coefficient={v}",
            ["run", panto, "--set", f"carrier.0.uplift_coefficient={v}", *short, *out("pu")],
            "`carrier.0.uplift_coefficient`")
    for k in ["stiffness", "mass", "damping"]:
        for v in ["5e-324", "1e308"]:
            t = {"stiffness": "1e5", "mass": "0", "damping": "0", k: v}
            if k == "stiffness" and v == "5e-324":
                continue  # the messenger's sag check comes first
            add(f"plausible messenger support {k}={v}",
                ["run", line, "--set",
                 "line.messenger.support={" + ", ".join(f"{a}={b}" for a, b in t.items()) + "}",
                 *short, *out("ps")], f"`line.messenger.support.{k}`")

    # plausible: every physical key of a line, a dropper's design height
    # and a cruise speed at 0, negative, 5e-324, 1e308, NaN and inf: run,
    # or refused naming the key written (its table for a table's keys),
    # never a NaN in the message nor another key blamed
    hostile = ["0", "-1", "5e-324", "1e308", "nan", "inf"]
    grid = []
    for key in ["line.dropper_stiffness", "line.dropper_damping", "line.dropper_mass",
                "line.clamp_mass.contact", "line.clamp_mass.messenger",
                "line.steady_arm.stiffness", "line.steady_arm.mass", "line.steady_arm.damping"]:
        for v in hostile:
            grid.append((line, key, [f"{key}={v}"], v))
    for k in ["arm_length", "inertia", "pivot_stiffness"]:
        for v in hostile:
            t = {"arm_length": "1.2", "inertia": "2.0", "pivot_stiffness": "720.0", k: v}
            grid.append((line, f"line.steady_arm.{k}", [
                "line.steady_arm={" + ", ".join(f"{a} = {b}" for a, b in t.items()) + "}"], v))
    for k in ["stiffness", "mass", "damping"]:
        for v in hostile:
            t = {"stiffness": "1e5", k: v}
            grid.append((line, f"line.messenger.support.{k}", [
                "line.messenger.support={" + ", ".join(f"{a} = {b}" for a, b in t.items()) + "}"], v))
    for v in hostile + ["-1e308"]:
        grid.append((drops, "dropper.0.design_height", [f"dropper.0.design_height={v}"], v))
    for v in hostile + ["1e-320", '"1e-320 km/h"']:
        grid.append((ref, "carrier.0.speed.cruise", [f"carrier.speed.cruise={v}"], v))
    for scene, key, sets, v in grid:
        name = f"plausible {Path(scene).stem} {key}={v}"
        # a table's keys may be named by their table (`line.steady_arm` = { … });
        # a cruise so fast the carrier leaves the beam at once is named by
        # the end time it must not pass, with the carrier
        named = "`" + (key.rsplit(".", 1)[0] if key.startswith("line.steady_arm.") else key)
        also = "carrier 0 leaves the beam at t = 0" if key.endswith("cruise") else None

        def keyed(r, name=name, scene=scene, sets=sets, named=named, v=v, also=also) -> list[str]:
            args = ["run", scene, *[a for s2 in sets for a in ("--set", s2)], *short, *out("pg")]
            found, p = r.judged(name, args)
            if p is None or p.returncode == 0:
                return found
            err = p.stderr.decode("utf-8", "replace")
            last = err.strip().splitlines()[-1] if err.strip() else ""
            if named not in last and not (also and also in last):
                found.append(f"{name}: refused without naming {named}`: {last[:300]!r}")
            # NaN only as the value written
            if "NaN" in last.replace("` = NaN:", "", 1 if v == "nan" else 0):
                found.append(f"{name}: NaN in the message: {last[:300]!r}")
            return found
        add(name, keyed)

    # plausible: lumped elements a model cannot compute
    for scene, key in [(drops, "dropper.0.stiffness"), (drops, "dropper.0.damping"),
                       (ref, "carrier.0.mass"), (ref, "carrier.0.stiffness"), (ref, "carrier.0.damping"),
                       (ref, "contact.penalty.stiffness"), (ref, "beam.damping.mass"),
                       (ref, "beam.damping.stiffness"), (panto, "carrier.0.masses.1"),
                       (panto, "carrier.0.stiffnesses.0"), (line, "line.dropper_damping"),
                       (line, "line.steady_arm.mass"), (line, "line.clamp_mass.contact"),
                       (line, "line.clamp_mass.messenger")]:
        for v in ["5e-324", "1e-300", "1e300"]:
            add(f"plausible {Path(scene).stem} {key}={v}",
                ["run", scene, "--set", f"{key}={v}", *short, *out("pl")], f"`{key}`")
    nulls = files / "failed_contact_step_1.json"
    nulls.write_text('{"not_replayable": "a test", "level": "position", "rows": 1, '
                     '"contact": {"kind": "unilateral", "formulation": "lagrange"}}')
    add("plausible replay of a record that cannot be replayed", ["replay", str(nulls)], "not replayable")
    raw_nulls = files / "nulls.json"
    raw_nulls.write_text('{"level": "position", "g_free": [null], "w": [null], '
                         '"contact": {"kind": "unilateral", "formulation": "lagrange"}}')
    add("plausible replay of nulls", ["replay", str(raw_nulls)])

    # fifo: never waited on
    pipe = files / "scene.fifo"
    if fifo(pipe):
        add("fifo scene", ["run", str(pipe), *out("ff")], "FIFO")
        add("fifo converge", ["converge", str(pipe), *out("ff")], "FIFO")
        add("fifo replay", ["replay", str(pipe)], "FIFO")
        suite = files / "fifo_suite"
        suite.mkdir()
        fifo(suite / "case.json")
        add("fifo gate case", ["gate", str(suite), *out("fg")])
        table_scene = files / "table_scene.toml"
        table_scene.write_text((ROOT / "scenes" / "reference.toml").read_text().replace(
            'speed = { profile = "smooth_ramp", cruise = 100.0 }', 'speed = { file = "scene.fifo" }'))
        add("fifo table file", ["run", str(table_scene), *out("ft")], "FIFO")

        def run_record(r) -> list[str]:
            case = "fifo run record"
            d = work / "fifo_sweep"
            sweep = ["sweep", ref, "--vary", "carrier.speed.cruise=90:110:2", "--set", "time.end=0.01",
                     "--set", "mesh.elements=50", "--out", str(d), "--quiet"]
            found, p = r.judged(case, sweep)
            (d / "runs" / "000000.json").unlink(missing_ok=True)
            fifo(d / "runs" / "000000.json")
            found2, _ = r.judged(case, sweep)
            return found + found2
        add("fifo run record", run_record)

    # messages
    add("messages check-refinement", ["sweep", ref, "--vary", "carrier.speed.cruise=90:110:2",
                                      "--set", "mesh.elements=1000000", "--set", "time.end=0.0002",
                                      "--check-refinement", *out("mr")], "`--check-refinement`")
    mms = str(ROOT / "scenes" / "verify" / "mms_beam_space.toml")
    add("messages half_waves=0", ["run", mms, "--set", "manufactured.term.0.x.0.half_waves=0",
                                  *out("mh")], "half_waves")
    riding = str(ROOT / "scenes" / "riding_mass_pinned.toml")
    add("messages reference.modes=16001", ["run", riding, "--set", "reference.modes=16001", *out("mm")],
        "1 ..= 16000")
    messenger = str(ROOT / "scenes" / "span_messenger.toml")
    add("messages messenger central_difference",
        ["run", messenger, "--set", "dropper.0.linear=true", "--unset", "integrator",
         "--set", "integrator.method=central_difference", "--set", "time.step=1e-5",
         "--set", "time.end=0.002", *out("mc")])
    return cases


PYTHON_CASES = {
    "unset field": """
try:
    taut.run("reference", set={"beam.tensoin": None}, progress=False)
except taut.SceneError as e:
    assert e.field == "beam.tensoin", e.field
    print("OK")
""",
    "progress=5": """
try:
    taut.run("reference", set={"time.end": 0.001}, progress=5)
except taut.SceneError as e:
    assert e.field == "progress", e.field
    print("OK")
""",
    "apply_force string": """
s = taut.Simulation("reference", set={"time.end": 0.001})
try:
    s.apply_force(0, "1.0")
except taut.SceneError as e:
    assert e.field == "newtons", e.field
    print("OK")
""",
    "w_at string": """
s = taut.Simulation("reference", set={"time.end": 0.001})
try:
    s.w_at("5")
except taut.SceneError as e:
    assert e.field == "x", e.field
    print("OK")
""",
    "points aliases": """
try:
    taut.sweep("reference", points=[{"carrier.mass": 1.0, "carrier.0.mass": 2.0}], progress=False)
except taut.SceneError as e:
    assert "both set" in str(e), e
    print("OK")
""",
    "points 1e6 keys": """
try:
    taut.sweep("reference", points=[{f"k{i}": 1.0 for i in range(1000000)}], progress=False)
except taut.SceneError as e:
    assert "keys" in str(e) and len(str(e)) < 1000, str(e)[:300]
    print("OK")
""",
    "ctrl-c in a thread pool": """
import os, signal, threading, time
from concurrent.futures import ThreadPoolExecutor
sets = [{"mesh.elements": 3200, "time.step": 1.25e-5} for _ in range(4)]
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t0 = time.time()
try:
    with ThreadPoolExecutor(max_workers=2) as pool:
        list(pool.map(lambda s: taut.run("reference", set=s, progress=False), sets))
except KeyboardInterrupt:
    pass
assert time.time() - t0 < 5.0, time.time() - t0
print("OK")
""",
}


def python_cases() -> list:
    """The Python classes, when the package imports (else none, said so)."""
    if subprocess.run([sys.executable, "-c", "import taut"], capture_output=True).returncode != 0:
        print("python: SKIPPED (`import taut` fails: pip install ./python)")
        return []

    def case(name: str, code: str):
        def go(r) -> list[str]:
            try:
                p = subprocess.run([sys.executable, "-c", "import taut\n" + code],
                                   capture_output=True, timeout=r.limit_s, cwd=ROOT)
            except subprocess.TimeoutExpired:
                return [f"python {name}: hang (killed after {r.limit_s} s)"]
            if p.returncode != 0 or b"OK" not in p.stdout:
                return [f"python {name}: {p.stderr.decode('utf-8', 'replace')[-300:]!r}"]
            return []
        return (f"python {name}", go)
    return [case(n, c) for n, c in PYTHON_CASES.items()]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--taut", default=str(ROOT / "target" / "release" / "taut"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--limit-s", type=int, default=120)
    ap.add_argument("--seed", type=int, default=25)
    ap.add_argument("--quick", action="store_true", help="a sample of 200 cases")
    ap.add_argument("--sample", type=int, default=0,
                    help="a seeded sample of N cases (the byte comparisons always run)")
    ap.add_argument("--count", action="store_true",
                    help="print the number of cases of each family and exit")
    ap.add_argument("--only", default="",
                    help="comma-separated families to run (default: all)")
    a = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="taut-hostile-"))
    r = Runner(os.path.abspath(a.taut), a.limit_s, work)
    rng = random.Random(a.seed)
    cases: list[tuple[str, list[str]]] = []
    # what a case's error must say (by case name), where more than any
    # error will not do
    must: dict[str, str] = {}
    out = lambda tag: ["--out", str(work / tag), "--quiet"]  # noqa: E731

    # kinds: every bundled scene x kind x method
    for s in SCENES:
        for k, kind in enumerate(KINDS):
            for m in METHODS:
                cases.append((f"kinds {s.name} kind{k} {m}",
                              ["run", str(s), *SHORT, *kind,
                               "--set", f"integrator={{ method = \"{m}\" }}", *out("k")]))
    # set-fuzz: every scalar key x hostile value
    for s in SCENES:
        for key in scalar_keys(s.read_text()):
            for v in HOSTILE:
                cases.append((f"set {s.name} {key}={v[:20]}",
                              ["run", str(s), *SHORT, "--set", f"{key}={v}", *out("s")]))
    # text-fuzz
    fuzz_dir = work / "fuzz"
    fuzz_dir.mkdir()
    for s in SCENES:
        for i in range(40):
            p = fuzz_dir / f"{s.stem}_{i}.toml"
            p.write_bytes(mutate(s.read_text(), rng))
            cases.append((f"text {p.name}", ["run", str(p), *SHORT, *out("t")]))
    # inputs
    ref = str(ROOT / "scenes" / "reference.toml")
    for dev in ["/dev/zero", "/dev/urandom"]:
        cases += [
            (f"input run {dev}", ["run", dev, *out("i")]),
            (f"input replay {dev}", ["replay", dev]),
            (f"input sweep {dev}", ["sweep", dev, "--vary", "speed_ratio=0.5:1:2", *out("i")]),
            (f"input converge {dev}", ["converge", dev, *out("i")]),
            (f"input merge {dev}", ["merge", dev, *out("i")]),
        ]
    # axes a plot cannot draw
    for vary, log in [("carrier.stiffness=1e100:1e300:2", True), ("carrier.damping=0:1.7e308:2", False),
                      ("carrier.mass=1e-300:1e300:8", True), ("beam.tension=1e300:1.7e308:2", False),
                      ("carrier.mass=1e-320:1e-310:3", True), ("speed_ratio=1e-300:1e-299:2", False)]:
        cases.append((f"axes {vary}", ["sweep", ref, "--vary", vary, *(["--log"] if log else []),
                                       "--set", "mesh.elements=40", *SHORT, *out(f"a{len(cases)}")]))
    # costly studies
    cases += [
        ("study converge", ["converge", ref, "--set", "mesh.elements=50", "--set", "time.end=0.05",
                            "--ratio", "20", "--levels", "4", *out("c")]),
        ("study precision", ["precision", ref, "--ratio", "100", "--levels", "2", *out("c")]),
        ("study compare", ["compare", ref, "--set", "time.step=2e-8", "--set", "mesh.elements=1000", *out("c")]),
        ("study sweep", ["sweep", ref, "--vary", "speed_ratio=0.5:1:3", "--set", "time.step=2e-8", "--set", "output.record_every=10",
                         "--set", "mesh.elements=1000", *out("c2")]),
        ("study uncertainty", ["uncertainty", ref, "--set", "time.step=2e-8", "--set", "mesh.elements=1000", *out("c3")]),
    ]
    # options: every integer option of every subcommand, out of range
    integer_options = [
        (["sweep", ref, "--vary", "speed_ratio=0.5:1:2"], "--threads"),
        (["sweep", ref, "--vary", "speed_ratio=0.5:1:2"], "--batch"),
        (["gate", str(ROOT / "golden")], "--batch"),
        (["compare", ref], "--batch"),
        (["precision", ref], "--batch"),
        (["precision", ref], "--levels"),
        (["precision", ref], "--ratio"),
        (["converge", ref], "--levels"),
        (["converge", ref], "--ratio"),
        (["uncertainty", ref], "--levels"),
        (["verify", "--quick"], "--threads"),
        (["replay", str(work / "none.json")], "--max-iter"),
    ]
    for command, flag in integer_options:
        for v in ["-1", "0", "x", "1.5", "", "-1e300", "4294967296",
                  "99999999999", "99999999999999999999999", "-99999999999999999999999"]:
            tail = [] if command[0] == "replay" else out(f"o{len(cases)}")
            name = f"option {command[0]} {flag}={v}"
            cases.append((name, [*command, flag, v, *tail]))
            # taut's own message naming the flag (or, for a ratio that is a
            # number > 1, the study's cost), never the parser's
            must[name] = f"`{flag}` = " if not (command[0] == "converge" and flag == "--ratio"
                                              and v in ["4294967296", "99999999999",
                                                        "99999999999999999999999"]) else "`--yes`"

    cases += round_three(work, must, out)
    cases += python_cases()
    if a.only:
        keep = set(a.only.split(","))
        cases = [c for c in cases if c[0].split()[0] in keep]

    def per_family(cases: list) -> dict[str, int]:
        n: dict[str, int] = {}
        for name, _ in cases:
            n[name.split()[0]] = n.get(name.split()[0], 0) + 1
        return n

    families = per_family(cases)
    if a.count:
        for fam, n in families.items():
            print(f"{fam}: {n}")
        print(f"threads: 3 comparisons; total {len(cases) + 3}")
        print("(python: the Python classes, counted when `import taut` works)")
        shutil.rmtree(work, ignore_errors=True)
        return 0
    if a.quick:
        cases = rng.sample(cases, min(len(cases), 200))
    elif a.sample:
        cases = rng.sample(cases, min(len(cases), a.sample))
    families = per_family(cases)

    findings: list[str] = []
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for f in ex.map(lambda c: r.run(*c, must=must.get(c[0])), cases):
            findings += f
    passed = len(cases) - len({f.split(":")[0] for f in findings})

    # threads: the same bytes on 1 and 2 threads (Hermite and modal)
    with_threads = not a.only or "threads" in a.only.split(",")
    thread_cases = [[], ["--set", "mesh.kind=modal", "--set", "mesh.modes=60"]] if with_threads else []
    for k, extra in enumerate(thread_cases):
        csvs = []
        for t in ["1", "2"]:
            d = work / f"thr{k}_{t}"
            f = r.run(f"threads {k} t{t}", ["sweep", ref, "--vary", "carrier.speed.cruise=100:140:3",
                                            "--set", "mesh.elements=200", *extra, *SHORT,
                                            "--threads", t, "--out", str(d), "--quiet"])
            findings += f
            csvs.append((d / "sweep.csv").read_bytes() if (d / "sweep.csv").exists() else b"")
        if csvs[0] != csvs[1] or not csvs[0]:
            findings.append(f"threads {k}: sweep.csv differs between 1 and 2 threads")
        else:
            passed += 1
    # a modal run pinned to one CPU (a pool of one thread) and unpinned
    total = len(cases) + len(thread_cases) + 1
    if not with_threads:
        total -= 1
    elif shutil.which("taskset") and subprocess.run(["taskset", "-c", "0", "true"]).returncode == 0:
        modal = ["run", ref, "--set", "mesh.kind=modal", "--set", "mesh.modes=60",
                 "--set", "mesh.elements=200", "--set", "time.end=0.05", "--quiet"]
        hist = []
        for pinned in [False, True]:
            d = work / f"pinned_{pinned}"
            taut = ["taskset", "-c", "0", r.taut] if pinned else [r.taut]
            p = subprocess.run([*taut, *modal, "--out", str(d)], capture_output=True,
                               timeout=a.limit_s)
            h = d / "history.csv"
            hist.append(h.read_bytes() if p.returncode == 0 and h.exists() else b"")
        if hist[0] != hist[1] or not hist[0]:
            findings.append("threads taskset: a modal run's history.csv differs under taskset -c 0")
        else:
            passed += 1
    else:
        total -= 1
        print("threads taskset: SKIPPED (taskset missing or cannot pin to CPU 0)")

    for f in findings:
        print(f)
    shutil.rmtree(work, ignore_errors=True)
    print("cases per family: " + ", ".join(f"{k} {v}" for k, v in families.items())
          + f", threads {total - len(cases)}")
    print(f"hostile pass: {total} cases; {len(findings)} findings")
    print(f"{passed} passed, {total - passed} failed")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
