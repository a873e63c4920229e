#!/usr/bin/env python3
"""The hostile pass of issue 25: scripted bad input against the `taut` binary.

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

Families (the classes of issue 25 and a fuzz):
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

Usage: python3 scripts/hostile_pass.py [--taut target/release/taut]
       [--jobs 2] [--limit-s 120] [--seed 25] [--quick | --sample N]
       [--count]
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

    def run(self, name: str, args: list[str], cwd: Path | None = None,
            must: str | None = None) -> list[str]:
        """Run one case; return its findings (empty: passed). With `must`,
        the case must exit 1 with `must` in its error."""
        cmd = ["bash", "-c", f"ulimit -v {ADDRESS_KIB}; exec \"$0\" \"$@\"", self.taut, *args]
        try:
            p = subprocess.run(cmd, capture_output=True, timeout=self.limit_s,
                               cwd=cwd or self.work)
        except subprocess.TimeoutExpired:
            return [f"{name}: hang (killed after {self.limit_s} s)"]
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

    def per_family(cases: list[tuple[str, list[str]]]) -> dict[str, int]:
        n: dict[str, int] = {}
        for name, _ in cases:
            n[name.split()[0]] = n.get(name.split()[0], 0) + 1
        return n

    families = per_family(cases)
    if a.count:
        for fam, n in families.items():
            print(f"{fam}: {n}")
        print(f"threads: 3 comparisons; total {len(cases) + 3}")
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
    thread_cases = [[], ["--set", "mesh.kind=modal", "--set", "mesh.modes=60"]]
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
    if shutil.which("taskset") and subprocess.run(["taskset", "-c", "0", "true"]).returncode == 0:
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
