"""Results tables: a dict of numpy arrays, one per column of the CLI's CSV.

The columns are made by the library's `report::Table` (src/report/table.rs),
the same object the CLI writes as CSV; this file only turns each column's
bytes into an array:

* real numbers -> float64 (a CSV's empty cell is NaN);
* counts -> int64; counts that may be absent (`modes`) -> float64 with NaN;
* yes/no (`in_contact`, `pareto`) -> bool;
* names and messages -> object arrays of str (None where the CSV is empty
  for a message).
"""

from __future__ import annotations

from typing import Any, Dict, List, Tuple

import numpy as np

_KINDS = {"f8": "<f8", "i8": "<i8"}


class Table(Dict[str, np.ndarray]):
    """Columns by name, in the CLI's column order.

    Attributes:
        failed: runs of a study that stopped (each a dict with `method`,
            `discretization`, `formulation`, `reason`); empty when all ran.
        skipped: variants of a convergence study that could not run the
            ladder, likewise.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.failed: List[Dict[str, str]] = []
        self.skipped: List[Dict[str, str]] = []

    @property
    def rows(self) -> int:
        """Number of rows."""
        return len(next(iter(self.values()))) if self else 0

    def to_pandas(self) -> Any:
        """The table as a `pandas.DataFrame` (pandas is not a dependency of
        taut: this needs it installed)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("Table.to_pandas needs pandas: pip install pandas") from e
        return pd.DataFrame({k: v for k, v in self.items()})

    def __repr__(self) -> str:
        return f"taut.Table({self.rows} rows: {', '.join(self.keys())})"


def _array(kind: str, data: Any) -> np.ndarray:
    if kind in _KINDS:
        a = np.frombuffer(data, dtype=_KINDS[kind])
        # a writable array in the machine's byte order
        return a.astype(a.dtype.newbyteorder("="), copy=True)
    if kind == "b1":
        return np.frombuffer(data, dtype=np.uint8).astype(bool)
    return np.array(data, dtype=object)


def _not_run(rows: List[Tuple[str, str, str, str]]) -> List[Dict[str, str]]:
    return [
        {"method": m, "discretization": d, "formulation": f, "reason": r}
        for (m, d, f, r) in rows
    ]


def table(columns: List[Tuple[str, str, Any]]) -> Table:
    """A Table from the native module's `(name, kind, data)` columns."""
    t = Table()
    for name, kind, data in columns:
        t[name] = _array(kind, data)
    return t
