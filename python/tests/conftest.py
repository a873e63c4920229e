"""Shared pieces of the Python module's tests: the repository, the CLI
binary the module's numbers are compared with, and CSV reading."""

from __future__ import annotations

import csv
import math
import os
import pathlib
import select
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
REFERENCE = ROOT / "scenes" / "reference.toml"


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The `taut` CLI built from the same sources (`cargo build --release`;
    TAUT_CLI names another)."""
    path = pathlib.Path(os.environ.get("TAUT_CLI", ROOT / "target" / "release" / "taut"))
    if not path.exists():
        subprocess.run(
            ["cargo", "build", "--release", "--locked", "--bin", "taut"], cwd=ROOT, check=True
        )
    return path


def run_cli(cli: pathlib.Path, *args: str) -> subprocess.CompletedProcess:
    p = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    return p


def read_csv(path: pathlib.Path) -> dict:
    """A CLI CSV as {column: list of cells (str)}."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [r[i] for r in body] for i, name in enumerate(header)}


def same_column(cells: list, array: np.ndarray) -> bool:
    """Whether a CSV column and a module column hold the same values: the
    CSV writes floats in shortest round-trip form, so equality is exact;
    an empty cell is NaN (numbers) or None (text)."""
    if array.dtype == object:
        # text: absent is an empty cell; the CSV turns " into ' (quoted cells)
        return cells == ["" if v is None else v.replace('"', "'") for v in array]
    if array.dtype == bool:
        return [c in ("1", "true") for c in cells] == list(array)
    parsed = np.array([float(c) if c != "" else math.nan for c in cells])
    return bool(np.array_equal(parsed, array.astype(np.float64), equal_nan=True))


def ctrl_c(script: str, args: list, after: float) -> tuple:
    """Run `script` in a new interpreter, send it SIGINT `after` s past the
    line "started" it prints once its work has begun, and return (seconds
    from the signal to its exit, stdout, stderr)."""
    p = subprocess.Popen(
        [sys.executable, "-c", script, *map(str, args)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
    )
    assert p.stdout is not None
    ready, _, _ = select.select([p.stdout], [], [], 60)
    if not ready:
        p.kill()
        pytest.fail("the work did not start within 60 s")
    assert p.stdout.readline().strip() == "started"
    time.sleep(after)
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    try:
        stdout, stderr = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        pytest.fail("the work did not stop on Ctrl-C")
    return time.perf_counter() - t0, stdout, stderr
