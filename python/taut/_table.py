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

from typing import Any, Dict, Iterator, List, Optional, Tuple

import numpy as np

_KINDS = {"f8": "<f8", "i8": "<i8"}


class Table(Dict[str, np.ndarray]):
    """Columns by name, in the CLI's column order; rows by number.

    `t["force"]` is a column (a numpy array), `t[0]` (or `t.row(0)`) a row
    as a dict from column name to value, `t[-1]` the last row, and
    `len(t)` the number of rows (as a DataFrame's); iterating gives the
    column names, as a dict does (`t.columns` lists them).

    Attributes:
        failed: runs of a study that stopped (each a dict with `method`,
            `discretization`, `formulation`, `reason`); empty when all ran.
        skipped: variants of a convergence study that could not run the
            ladder, likewise.
        axes: of a grid sweep, [(key, values)] (the last axis fastest);
            empty otherwise. grid(column) reshapes a column to them.
        paired: a sweep over a list of points (no grid).
        span_force, span_loss: of a sweep, each point's mean contact force
            (N) and fraction of steps with contact lost along the span,
            points × bins at x/L = span_x (sweep_force.csv,
            sweep_loss.csv); NaN where no step fell. None otherwise.
        warnings: of a sweep, each point's warning texts.
        family: of an uncertainty study, its runs (a Table).
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.failed: List[Dict[str, str]] = []
        self.skipped: List[Dict[str, str]] = []
        self.axes: List[Tuple[str, np.ndarray]] = []
        self.paired: bool = False
        self.span_force: Optional[np.ndarray] = None
        self.span_loss: Optional[np.ndarray] = None
        self.span_x: Optional[np.ndarray] = None
        self.warnings: List[List[str]] = []
        self.family: Optional["Table"] = None

    @property
    def rows(self) -> int:
        """Number of rows."""
        return len(next(iter(self.values()))) if dict.__len__(self) else 0

    @property
    def columns(self) -> List[str]:
        """The column names, in order."""
        return list(self.keys())

    def __len__(self) -> int:
        """The number of rows (a dict's len would count the columns)."""
        return self.rows

    def __bool__(self) -> bool:
        return dict.__len__(self) > 0

    def __getitem__(self, key: Any) -> Any:
        """A column by name, or a row by number (a dict of its values;
        negative numbers count from the end)."""
        if isinstance(key, (int, np.integer)) and not isinstance(key, bool):
            return self.row(int(key))
        return dict.__getitem__(self, key)

    def row(self, i: int) -> Dict[str, Any]:
        """Row `i` as a dict from column name to value (numbers as Python
        floats, ints and bools; negative i counts from the end)."""
        n = self.rows
        if not -n <= i < n:
            raise IndexError(f"row {i} of a table of {n} rows")
        i %= max(n, 1)
        return {k: _scalar(v[i]) for k, v in self.items()}

    def iterrows(self) -> Iterator[Dict[str, Any]]:
        """Each row as a dict, in order."""
        return (self.row(i) for i in range(self.rows))

    def to_pandas(self) -> Any:
        """The table as a `pandas.DataFrame` (pandas is not a dependency of
        taut: this needs it installed)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("Table.to_pandas needs pandas, taut's `pandas` extra: pip install 'taut[pandas]'") from e
        return pd.DataFrame({k: v for k, v in self.items()})

    def __repr__(self) -> str:
        return f"taut.Table({self.rows} rows: {', '.join(self.keys())})"

    def grid(self, column: str) -> np.ndarray:
        """A grid sweep's `column` shaped by its axes (`.axes`): g[i, j]
        is the point at the first axis's i-th and the second's j-th value."""
        if not self.axes:
            raise ValueError(
                "grid(): this table is not a grid sweep's (a list of points or another study has no grid)"
            )
        col: np.ndarray = dict.__getitem__(self, column)
        return col.reshape([len(v) for _, v in self.axes])

    def to_xarray(self) -> Any:
        """A grid sweep as an `xarray.Dataset` over its axes, one variable
        a numeric column (xarray is not a dependency: this needs it)."""
        try:
            import xarray as xr
        except ImportError as e:
            raise ImportError("Table.to_xarray needs xarray, in taut's `all` extra: pip install 'taut[all]' (or xarray)") from e
        if not self.axes:
            raise ValueError("to_xarray(): this table is not a grid sweep's")
        dims = [k for k, _ in self.axes]
        data = {
            k: (dims, self.grid(k))
            for k, v in self.items()
            if k not in dims and v.dtype != object
        }
        return xr.Dataset(data, coords={k: v for k, v in self.axes})

    def _repr_html_(self) -> str:
        from ._show import table_html

        return table_html(self)

    def plot(self, column: str = "loss_fraction_span", ax: Any = None) -> Any:
        """Draw `column` (matplotlib, `taut[plot]`): against a 1-D sweep's
        axis, as a map over a 2-D sweep's axes (the CLI's maps), else
        against the row. Returns the matplotlib Axes."""
        from ._show import plot_table

        return plot_table(self, column, ax)


def _scalar(v: Any) -> Any:
    """A numpy scalar as the Python number it holds."""
    return v.item() if isinstance(v, np.generic) else v


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
