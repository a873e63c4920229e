"""What a sweep gives besides sweep.csv's columns: its axes and their
grid shape, the per-point force and loss along the span (the CLI's
sweep_force.csv and sweep_loss.csv) and each point's warning texts, read
from the sweep's records (`runs/NNNNNN.json`) before a temporary folder
is removed; and `vary` / `points` in the library's words.
"""

from __future__ import annotations

import json
import math
import os
from typing import Any, Dict, Iterable, List, Mapping, Sequence, Union

import numpy as np

from . import _taut
from ._errors import SceneError
from ._scene import value as toml_value

Vary = Union[str, Mapping[str, Any], Iterable[str]]
Points = Union[Sequence[Mapping[str, Any]], Mapping[str, Sequence[Any]], Any]


def _number(v: Any, where: str) -> float:
    """A listed value: a real number (bools are not numbers here)."""
    if hasattr(v, "tolist") and not isinstance(v, (list, tuple)):
        v = v.tolist()
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise SceneError(
            f"`{where}` = {v!r}: a listed value must be a number",
            field=where,
            value=repr(v),
            allowed="a finite number",
        )
    if not math.isfinite(v):
        raise SceneError(
            f"`{where}` = {v!r}: a listed value must be finite",
            field=where,
            value=repr(v),
            allowed="a finite number",
        )
    return float(v) if isinstance(v, float) else v


def _listed(key: str, values: Iterable[Any], where: str) -> str:
    """`key=v1,v2,...` (each number in the text that reads back exactly)."""
    cells = [toml_value(_number(v, f"{where}[{i}]"), where) for i, v in enumerate(values)]
    if not cells:
        raise SceneError(
            f"`{where}`: an empty list of values",
            field=where,
            value="[]",
            allowed="at least one value",
        )
    return f"{key}={','.join(cells)}"


def axes(vary: Vary) -> List[str]:
    """`vary` as the library's axis texts. A tuple is (start, stop, count);
    a list or a numpy array is the values themselves."""
    if isinstance(vary, str):
        return [vary]
    if not isinstance(vary, Mapping):
        return [str(v) for v in vary]
    out = []
    for key, axis in vary.items():
        where = f"vary.{key}"
        if isinstance(axis, str):
            out.append(f"{key}={axis}")
        elif isinstance(axis, tuple):
            try:
                start, stop, count = axis
            except ValueError:
                raise SceneError(
                    f"{where} = {axis!r}: a tuple is (start, stop, count); give a list for values",
                    field=where,
                    value=repr(axis),
                    allowed="(start, stop, count), or a list of values",
                ) from None
            out.append(
                f"{key}={toml_value(start, where)}:{toml_value(stop, where)}:{toml_value(count, where)}"
            )
        elif isinstance(axis, list) or hasattr(axis, "tolist"):
            values = axis.tolist() if hasattr(axis, "tolist") else axis
            if not isinstance(values, list):
                values = [values]
            out.append(_listed(str(key), values, where))
        else:
            raise SceneError(
                f"{where} = {axis!r}: must be (start, stop, count) or a list of values",
                field=where,
                value=repr(axis),
                allowed="(start, stop, count), a list or a numpy array of values",
            )
    return out


def points(pts: Points) -> List[str]:
    """A list of points ([{key: value, ...}, ...]; a dict of columns or a
    pandas DataFrame too) as the library's listed axes, one a key."""
    if hasattr(pts, "to_dict") and not isinstance(pts, Mapping):
        pts = pts.to_dict("records")
    most = _taut.most_point_keys()
    if isinstance(pts, Mapping):
        _at_most(len(pts), most)
        cols = {str(k): list(v.tolist() if hasattr(v, "tolist") else v) for k, v in pts.items()}
        n = {len(v) for v in cols.values()}
        if len(n) > 1:
            raise SceneError(
                "points: the columns differ in length",
                field="points",
                value=repr({k: len(v) for k, v in cols.items()}),
                allowed="one value a point in every column",
            )
        return [_listed(k, v, f"points[{k!r}]") for k, v in cols.items()]
    rows = list(pts)
    if not rows:
        raise SceneError(
            "points: an empty list", field="points", value="[]", allowed="at least one point"
        )
    # the keys in order of first appearance (a dict: a million keys in one
    # point took minutes as a list)
    seen: Dict[str, None] = {}
    for r in rows:
        if not isinstance(r, Mapping):
            raise SceneError(
                f"points: a point must be a dict of key to value, got {type(r).__name__}",
                field="points",
                value=repr(r)[:200],
                allowed="a list of dicts {key: value}",
            )
        _at_most(len(r), most)
        for k in r:
            seen.setdefault(str(k), None)
        _at_most(len(seen), most)
    keys = list(seen)
    for i, r in enumerate(rows):
        missing = [k for k in keys if k not in r]
        if missing:
            raise SceneError(
                f"points[{i}] has no value for {', '.join(missing)}: every point gives every key",
                field=f"points[{i}]",
                value=repr(dict(r))[:200],
                allowed="a value for each of " + ", ".join(keys),
            )
    return [_listed(k, [r[k] for r in rows], f"points[*][{k!r}]") for k in keys]


def _at_most(keys: int, most: int) -> None:
    """Refuse a list of points setting more than `most` keys (the library's
    MAX_POINT_KEYS), before its axes are built."""
    if keys > most:
        raise SceneError(
            f"points: {keys} keys: a list of points sets at most {most} keys: vary fewer scene values",
            field="points",
            value=f"{keys} keys",
            allowed=f"at most {most} keys",
        )


def span_profiles(dir: str, n: int) -> Dict[str, Any]:
    """The per-point records of a sweep folder: force and loss along the
    span (points × bins, NaN where no step fell), bin centres x/L, and the
    warning texts of each point."""
    force: List[List[float]] = []
    loss: List[List[float]] = []
    warnings: List[List[str]] = []
    for i in range(n):
        with open(os.path.join(dir, "runs", f"{i:06d}.json"), encoding="utf-8") as f:
            r = json.load(f)
        force.append([math.nan if v is None else v for v in r["force_profile"]])
        loss.append([math.nan if v is None else v for v in r["loss_profile"]])
        warnings.append(list(r["warnings"]))
    # a stopped point's record has no profile: NaN in every bin
    bins = max((len(f) for f in force), default=0)
    force = [f + [math.nan] * (bins - len(f)) for f in force]
    loss = [f + [math.nan] * (bins - len(f)) for f in loss]
    return {
        "span_force": np.array(force, dtype=np.float64).reshape(n, bins),
        "span_loss": np.array(loss, dtype=np.float64).reshape(n, bins),
        "span_x": (np.arange(bins, dtype=np.float64) + 0.5) / max(bins, 1),
        "warnings": warnings,
    }
