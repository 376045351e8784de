"""A study's table on disk: a CSV appended row by row and rewritten atomically when its
columns change, read back by :func:`load_table` as the runner returns it.  Beside it, a
JSON sidecar (:func:`identity_path`) holds the identity of the study that wrote it
(:func:`exuclear.study.spec.identity`): a table is resumed only by that study."""
from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..columns import Column

#: Columns every row has, after the parameters and the summary.
STATUS_COLUMNS = ("success", "message", "wall_time", "run_id")


#: Suffix of the sidecar beside a table's CSV that holds its study's identity.
IDENTITY_SUFFIX = ".study.json"


def identity_path(path: Path) -> Path:
    """The sidecar of the table at ``path`` (``x.csv`` -> ``x.csv.study.json``)."""
    return path.with_name(path.name + IDENTITY_SUFFIX)


def _check_identity(path: Path, identity: Mapping[str, Any]) -> None:
    """``ValueError`` if the table at ``path`` was written by a study other than ``identity``,
    naming what differs and how to start afresh or keep both; a table without a sidecar
    (written before tables had one) is taken as the study's."""
    sidecar = identity_path(path)
    if not sidecar.exists():
        return
    stored = json.loads(sidecar.read_text())
    what = {"function": "its function", "source": "its function's code", "parameters": "its parameters or their "
            "defaults", "columns": "its columns"}
    differs = [text for key, text in what.items() if stored.get(key) != identity.get(key)]
    if differs:
        raise ValueError(f"{path} was written by another study ({stored.get('function')}): {', '.join(differs)} "
                         f"differ from those of {identity.get('function')}, so its rows are not this study's. To "
                         f"start afresh, delete {path} and {sidecar.name} (or move them away); to keep both, give "
                         "another `out`")


#: The status columns that carry a unit, as :class:`Column`.
STATUS_LABELS = {"wall_time": Column("wall time of the run", "s")}


def _encode(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, list):
        return json.dumps(value)
    return str(value)  # str(float) is the shortest text that reads back to the same float


class _Table:
    """The study's CSV: rows appended one by one; when a row brings a new column or
    replaces a row, the file is rewritten (to a temporary file, then renamed, so that a
    crash never leaves half a table).

    With ``keep_arrays`` (a table in memory only), array values stay as the run returned
    them, out of the text."""

    def __init__(self, path: Path | None, parameter_names: Sequence[str], keep_arrays: bool = False,
                 identity: Mapping[str, Any] | None = None) -> None:
        self.path = path
        self.identity = identity
        self.columns: list[str] = []
        self.rows: dict[str, dict[str, str]] = {}  # run_id -> row as text
        self.parameter_names = list(parameter_names)
        self.keep_arrays = keep_arrays
        self.arrays: dict[str, dict[str, np.ndarray]] = {}  # run_id -> arrays kept in memory

    @classmethod
    def open(cls, path: Path | None, parameter_names: Sequence[str], keep_arrays: bool = False,
             identity: Mapping[str, Any] | None = None) -> _Table:
        """The table at ``path``, resumed if it exists (``ValueError`` if it holds another
        study: other parameters, or another ``identity`` in its sidecar), or a new one."""
        table = cls(path, parameter_names, keep_arrays, identity)
        if path is None or not path.exists() or path.stat().st_size == 0:
            return table
        if identity is not None:
            _check_identity(path, identity)
        table._read()
        if "run_id" not in table.columns:
            raise ValueError(f"{path} is not a study table (no `run_id` column); give another `out`")
        missing = [name for name in parameter_names if name not in table.columns]
        if missing:
            raise ValueError(f"{path} holds another study: it has no column for the parameters {missing}; "
                             f"give another `out`")
        table._rewrite()  # drops a row cut short by a crash
        return table

    def _read(self) -> None:
        with open(self.path, newline="") as f:
            text = f.read()
        if not text.endswith("\n"):
            text = text[: text.rfind("\n") + 1]  # a row cut short by a crash: dropped, its run is redone
        reader = csv.reader(io.StringIO(text, newline=""))  # a quoted message may hold line breaks
        self.columns = next(reader, [])
        for fields in reader:
            if len(fields) == len(self.columns):
                row = dict(zip(self.columns, fields))
                self.rows[row["run_id"]] = row

    def _write(self, target: Any, rows: Iterable[Mapping[str, str]], *, header: bool, mode: str = "w") -> None:
        """``rows`` (text) as CSV lines in the order of :attr:`columns`, through pandas
        (strings as they are, quoted where they hold a comma, quote or line break; CRLF
        line ends, the CSV standard's)."""
        import pandas as pd

        lines = pd.DataFrame([[row.get(c, "") for c in self.columns] for row in rows], columns=self.columns,
                             dtype=object)
        lines.to_csv(target, mode=mode, header=header, index=False, lineterminator="\r\n")

    def _write_identity(self) -> None:
        """The study's identity beside the table, before its first row (atomically, as the table)."""
        if self.path is None or self.identity is None:
            return
        sidecar = identity_path(self.path)
        tmp = sidecar.with_name(sidecar.name + ".tmp")
        tmp.write_text(json.dumps(self.identity, indent=1, sort_keys=True) + "\n")
        os.replace(tmp, sidecar)

    def _rewrite(self) -> None:
        if self.path is None:
            return
        if not identity_path(self.path).exists():
            self._write_identity()
        tmp = self.path.with_name(self.path.name + ".tmp")
        self._write(tmp, self.rows.values(), header=True)
        os.replace(tmp, self.path)

    def add(self, row: Mapping[str, Any]) -> None:
        if self.keep_arrays:
            self.arrays[row["run_id"]] = {k: v for k, v in row.items() if isinstance(v, np.ndarray)}
        text = {k: "" if k in self.arrays.get(row["run_id"], ()) else _encode(v) for k, v in row.items()}
        new = [k for k in row if k not in self.columns]
        replaces = text["run_id"] in self.rows  # a failed run done again (retry_failed)
        self.rows[text["run_id"]] = text
        if replaces and not new:
            self._rewrite()
        elif new:
            if not self.columns:  # parameters, metrics, status
                metrics = [k for k in row if k not in self.parameter_names and k not in STATUS_COLUMNS]
                self.columns = [k for k in self.parameter_names if k in row] + metrics + list(STATUS_COLUMNS)
            else:  # new metrics go before the status columns
                status = [c for c in self.columns if c in STATUS_COLUMNS]
                self.columns = [c for c in self.columns if c not in STATUS_COLUMNS] + new + status
            self._rewrite()
        elif self.path is not None:
            self._write(self.path, [text], header=False, mode="a")

    def frame(self, order: Sequence[str] | None = None):
        """The rows as a DataFrame (all, or those of ``order``'s run ids in that order)."""
        import pandas as pd

        keys = list(self.rows) if order is None else [k for k in order if k in self.rows]
        if not self.columns:
            return pd.DataFrame(columns=[*self.parameter_names, *STATUS_COLUMNS])
        # the rows go through CSV text even in memory, so that the returned table and the
        # table read back from disk are parsed by the same code and equal value by value
        buffer = io.StringIO(newline="")
        self._write(buffer, [self.rows[k] for k in keys], header=True)
        buffer.seek(0)
        # floats must read back exactly: pandas 3 does by default, pandas 2 when asked
        exact = {"float_precision": "round_trip"} if int(pd.__version__.split(".")[0]) < 3 else {}
        df = _decode(pd.read_csv(buffer, keep_default_na=False, na_values=["", "nan", "NaN"],
                                 dtype={"run_id": str, "message": str}, **exact))
        kept = list(dict.fromkeys(name for k in keys for name in self.arrays.get(k, ())))
        for name in kept:
            df[name] = pd.Series([self.arrays.get(k, {}).get(name) for k in keys], index=df.index, dtype=object)
        return df


def _decode(df):
    """JSON lists back to lists; empty messages to ''."""
    if "message" in df:
        df["message"] = df["message"].fillna("").astype(str)
    for column in df.columns:
        if df[column].dtype == object or str(df[column].dtype).startswith("str"):
            values = df[column].dropna()
            if len(values) and all(isinstance(v, str) and v.startswith("[") for v in values):
                df[column] = [json.loads(v) if isinstance(v, str) else v for v in df[column]]
    return df


def load_table(path: str | os.PathLike):
    """A study's table (CSV) as a DataFrame, parsed as :func:`run_study` returns it."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"no study table at {str(path)!r}")
    table = _Table(path, [])
    table._read()
    if "run_id" not in table.columns:
        raise ValueError(f"{path} is not a study table (no `run_id` column)")
    return table.frame()


def _write_parquet(df, csv_path: Path) -> Path | None:
    """Write the table as Parquet next to the CSV when pyarrow is present."""
    try:
        import pyarrow  # noqa: F401 - only whether it is there
    except ImportError:
        return None
    path = csv_path.with_suffix(".parquet")
    df.to_parquet(path, index=False)
    return path

