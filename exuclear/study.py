"""Parameter studies: one function of a parameter set, run over many sets, into one table.

A *study function* takes one parameter set (a ``dict``) and returns a summary (a
``dict`` of scalars, and of arrays where asked).  :func:`run_study` runs it over a list
of parameter sets (:func:`grid`, :func:`sample`, or any list of dicts) and returns a tidy
:class:`pandas.DataFrame`, one row per run: the parameters, the summary, ``success``,
``message``, ``wall_time`` [s] and ``run_id``.

Execution goes through a :class:`concurrent.futures.Executor`:

- local worker processes by default, one per core (``workers=1``: in this process);
- a Dask cluster when ``scheduler`` is an address (``"tcp://host:8786"``, passed to
  ``dask.distributed.Client``) or ``"local"`` (a ``LocalCluster`` of ``workers``
  processes); needs the ``cluster`` extra (``pip install exuclear[cluster]``);
- any executor the caller passes (``executor=``; the caller keeps it).

Runs are sent in batches sized so that one task lasts about :data:`TASK_SECONDS`.

Nothing is lost: with ``out="study.csv"`` every finished run is appended to the CSV at
once; a run that raises is a row with ``success`` False and the error as ``message``,
and a run that kills its worker process is retried alone and then recorded the same
way; Ctrl-C (or a ``KeyboardInterrupt`` from a run) stops the study, keeps the finished
rows and raises ``KeyboardInterrupt``; running the same study again skips the runs whose
``run_id`` (a hash of the parameter set) is already in the table.  Runs must be
deterministic (the same parameter set gives the same summary), and then a row does not
depend on the executor that ran it, except for ``wall_time``.

A *scene* is a module with a ``study`` function, its parameter defaults
``STUDY_PARAMETERS`` and (optionally) its check ``check_study`` and ``STUDY_COLUMNS``
(:class:`Column` of its parameters and metrics: help, units, the option names of the
scene's own command line); :func:`scene` makes it a
:class:`Study`, from a dotted module path or from a short name.  The library never imports
its scenes: short names come from the entry-point group :data:`SCENE_ENTRY_POINTS`, which
installed distributions fill (exuclear's own scenes declare ``slider-crank`` and
``journal-bearing`` in its ``pyproject.toml``; a user's package can add its own).  The
command line::

    python -m exuclear.study slider-crank --cr 0.3:0.9:0.2 --clearance 5e-5,1e-4,2e-4 \\
        --rpm 200:5000:50 --workers 2 --out study.csv
    python -m exuclear.study plot study.csv --metric peak_force --x rpm --by cr --out study.png

Plots come from the opt-in :mod:`exuclear.study_plot` (matplotlib).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import contextlib
import csv
import hashlib
import importlib
import io
import itertools
import json
import math
import multiprocessing
import os
import pickle
import re
import sys
import time
import warnings
from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from numbers import Integral
from pathlib import Path
from typing import Any

import numpy as np

#: Target duration of one task [s]: a batch holds about this much work, so that the
#: per-task cost (some milliseconds with Dask, less with local processes) stays below
#: 1 % of it, while a finished batch still reaches the table within a second or so.
TASK_SECONDS = 1.0
#: Tasks kept in flight per worker: one running, one waiting, so no worker idles while
#: the next batch travels to it.
IN_FLIGHT_PER_WORKER = 2
#: At least this many tasks per worker over what is left of a study, so that the last
#: batches finish together instead of one worker carrying a long tail.
TASKS_PER_WORKER = 4
#: Hex digits of the run identifier (64 bits: a collision among 1e6 runs has odds 3e-8).
RUN_ID_DIGITS = 16
#: Significant digits of the values :func:`parse_values` makes from a range: enough for
#: any step, and 0.3 + 0.2 comes out as 0.5, not 0.5000000000000001.
RANGE_DIGITS = 12

#: Columns every row has, after the parameters and the summary.
STATUS_COLUMNS = ("success", "message", "wall_time", "run_id")

#: Entry-point group of the scenes known by short name (``name = "package.module"``).
SCENE_ENTRY_POINTS = "exuclear.scenes"

Params = dict[str, Any]


@dataclass(frozen=True)
class Column:
    """What a column of a study table holds: a parameter's option help and other
    spellings, and the axis label of a plot (:mod:`exuclear.study_plot`).

    Parameters
    ----------
    label : str
        What the value is, without its unit (``"radial clearance"``).
    unit : str
        Its unit (``"m"``, ``"N"``, ``"rpm"``); empty for a number without one.
    aliases : tuple of str
        Other names of a parameter, as the scene's command line spells them too
        (``("length",)`` for ``bearing_length``): accepted by :meth:`Study.complete`
        and as options (``--length``).
    """

    label: str
    unit: str = ""
    aliases: tuple[str, ...] = ()

    @property
    def axis_label(self) -> str:
        """``"label [unit]"``, or the label alone."""
        return f"{self.label} [{self.unit}]" if self.unit else self.label


#: The status columns that carry a unit, as :class:`Column`.
STATUS_LABELS = {"wall_time": Column("wall time of the run", "s")}


# =======================================================================================
# studies and parameter sets
# =======================================================================================


@dataclass(frozen=True)
class Study:
    """A study function with its parameter names and its input check.

    Parameters
    ----------
    function : callable
        ``function(params: dict) -> dict``: one run.  Must be importable by name (a
        module-level function) to run in worker processes and on Dask workers.  A
        returned ``success`` (bool) and ``message`` (str) become the row's status (a
        run that finished but failed its own criterion); every other key is a metric.
    parameters : mapping, optional
        Parameter names and their default values.  Given: every parameter set is
        completed with the defaults, and an unknown name is a ``ValueError``.
    check : callable, optional
        ``check(params)`` raises ``ValueError`` for a (completed) parameter set the study
        would refuse; called for every set before any run starts.
    name : str
        For messages.
    columns : mapping, optional
        :class:`Column` of parameters and metrics by name: option help, other spellings
        of a parameter, axis labels with units.
    """

    function: Callable[[Params], Mapping[str, Any]]
    parameters: Mapping[str, Any] | None = None
    check: Callable[[Params], None] | None = None
    name: str = ""
    columns: Mapping[str, Column] | None = None

    def aliases(self) -> dict[str, str]:
        """Other spellings of the parameters: alias -> parameter name."""
        return {alias: name for name, column in (self.columns or {}).items() for alias in column.aliases
                if self.parameters is None or name in self.parameters}

    def complete(self, params: Mapping[str, Any]) -> Params:
        """The parameter set with the defaults filled in and other spellings
        (:meth:`aliases`) under the parameter's name; ``ValueError`` for unknown names."""
        if not isinstance(params, Mapping):
            raise ValueError(f"a parameter set must be a dict, got {params!r}")
        aliases = self.aliases()
        named: dict[str, Any] = {}
        for key, value in params.items():
            name = aliases.get(key, key)
            if name in named:
                raise ValueError(f"`{name}` is given twice (as {name!r} and as its other name {key!r})")
            named[name] = value
        params = named
        if self.parameters is None:
            return dict(params)
        unknown = sorted(set(params) - set(self.parameters))
        if unknown:
            raise ValueError(f"unknown parameter {', '.join(map(repr, unknown))} of study {self.name or self.function.__name__!r}; "
                             f"known: {', '.join(self.parameters)}")
        return {**self.parameters, **params}


def _as_study(study: Study | Callable[[Params], Mapping[str, Any]]) -> Study:
    if isinstance(study, Study):
        return study
    if not callable(study):
        raise ValueError(f"`study` must be a Study or a function of one parameter set, got {study!r}")
    return Study(study, name=getattr(study, "__name__", ""))


def grid(**axes: Iterable[Any]) -> list[Params]:
    """Every combination of the values of each axis (the last axis varies fastest).

    ``grid(cr=[0.3, 0.9], rpm=[500, 1000])`` is four parameter sets.  ``ValueError``
    for an empty axis.
    """
    names, values = list(axes), []
    for name in names:
        axis = axes[name]
        if isinstance(axis, (str, bytes)) or not isinstance(axis, Iterable):
            axis = [axis]  # a single value
        axis = list(axis)
        if not axis:
            raise ValueError(f"the values of `{name}` are empty")
        values.append(axis)
    return [dict(zip(names, combo)) for combo in itertools.product(*values)]


def sample(bounds: Mapping[str, tuple[float, float]], n: int, *, seed: int, method: str = "lhs",
           log: Sequence[str] = (), fixed: Mapping[str, Any] | None = None) -> list[Params]:
    """``n`` parameter sets drawn in the box ``bounds`` ({name: (low, high)}).

    ``method``: ``"lhs"`` (Latin hypercube: one point in each of ``n`` strata per axis) or
    ``"random"`` (independent uniform draws).  Names in ``log`` are drawn uniformly in
    their logarithm (both bounds positive).  ``fixed`` values are added to every set.
    The same ``seed`` gives the same sets.
    """
    if isinstance(n, bool) or not isinstance(n, Integral) or n < 1:
        raise ValueError(f"`n` must be a positive integer, got {n!r}")
    if not bounds:
        raise ValueError("`bounds` is empty: give at least one parameter to sample")
    unknown_log = sorted(set(log) - set(bounds))
    if unknown_log:
        raise ValueError(f"`log` names {unknown_log} that are not in `bounds`")
    low, high = [], []
    for name, pair in bounds.items():
        try:
            lo, hi = (float(v) for v in pair)
        except (TypeError, ValueError):
            raise ValueError(f"the bounds of `{name}` must be two numbers (low, high), got {pair!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi)) or not lo < hi:
            raise ValueError(f"the bounds of `{name}` must be finite with low < high, got ({lo}, {hi})")
        if name in log:
            if lo <= 0.0:
                raise ValueError(f"`{name}` is sampled in its logarithm: its bounds must be positive, got ({lo}, {hi})")
            lo, hi = math.log(lo), math.log(hi)
        low.append(lo)
        high.append(hi)
    rng = np.random.default_rng(seed)
    if method == "lhs":
        # Latin hypercube: in each dimension one point in each of the n equal strata, the
        # strata shuffled independently per dimension, the point uniform within its stratum
        strata = rng.permuted(np.tile(np.arange(n), (len(bounds), 1)), axis=1).T
        unit = (strata + rng.random((n, len(bounds)))) / n
    elif method == "random":
        unit = rng.random((n, len(bounds)))
    else:
        raise ValueError(f"unknown sampling `method` {method!r}; known: lhs, random")
    points = np.asarray(low) + unit * (np.asarray(high) - np.asarray(low))
    runs = []
    for row in points:
        params = {name: float(math.exp(v) if name in log else v) for name, v in zip(bounds, row)}
        runs.append({**(fixed or {}), **params})
    return runs


def parse_values(text: str) -> list[Any]:
    """Values of a command-line option: ``"0.3:0.9:0.2"`` (start:stop:step, stop included
    when it lies on the grid), ``"5e-5,1e-4,2e-4"`` (a list), or one value.  Numbers
    become int or float, anything else stays a string (``"steel,aluminium"``,
    ``"none,coulomb:0.1"``)."""
    text = text.strip()
    if not text:
        raise ValueError("empty value")
    parts = text.split(":")
    if len(parts) > 1 and _is_number_list(parts):  # numbers only: a range ("coulomb:0.1" is a value)
        if len(parts) != 3:
            raise ValueError(f"a range is start:stop:step (three numbers), got {text!r}")
        start, stop, step = (float(v) for v in parts)
        if not step > 0.0 or not math.isfinite(step):
            raise ValueError(f"the step of range {text!r} must be positive")
        if stop < start:
            raise ValueError(f"range {text!r} is empty (stop below start)")
        count = int(math.floor((stop - start) / step * (1.0 + 1e-12))) + 1  # stop counts when it is on the grid
        values = [float(f"{start + k * step:.{RANGE_DIGITS}g}") for k in range(count)]
        integral = all(float(v).is_integer() for v in (start, step))
        return [int(v) for v in values] if integral else values
    items = [item.strip() for item in text.split(",")]
    if any(not item for item in items):
        raise ValueError(f"empty item in list {text!r}")
    return [_number(item) for item in items]


def parse_bounds(text: str) -> tuple[float, float]:
    """``"low:high"`` of a sampled option."""
    parts = text.split(":")
    if len(parts) != 2 or not _is_number_list(parts):
        raise ValueError(f"a sampled parameter needs bounds low:high, got {text!r}")
    return float(parts[0]), float(parts[1])


def _is_number_list(items: Sequence[str]) -> bool:
    try:
        [float(v) for v in items]
    except ValueError:
        return False
    return True


def _number(text: str) -> Any:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return {"true": True, "false": False}.get(text.lower(), text)


def _plain(value: Any) -> Any:
    """A value as a plain Python scalar or list (numpy scalars and arrays converted)."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (np.ndarray, list, tuple)):
        return np.asarray(value).tolist()
    return value


def run_id(params: Mapping[str, Any]) -> str:
    """Identifier of a parameter set: a hash of its canonical JSON (names sorted, floats
    exact); equal for equal sets, whichever process computes it."""
    canonical = json.dumps({k: _plain(v) for k, v in params.items()}, sort_keys=True, allow_nan=True, default=repr)
    return hashlib.sha256(canonical.encode()).hexdigest()[:RUN_ID_DIGITS]


# =======================================================================================
# one batch of runs (in a worker)
# =======================================================================================


def _error_text(err: BaseException) -> str:
    return f"{type(err).__name__}: {' '.join(str(err).split())}"


def _carried_categories() -> tuple[type[Warning], ...]:
    """The warnings a row carries in its message: exuclear's own, which say that a result
    may not mean what it seems (a unit slip, a law outside its validity, an unconverged path)."""
    from .checks import UnitWarning
    from .contact import ValidityWarning
    from .engine import AccuracyWarning

    return UnitWarning, ValidityWarning, AccuracyWarning


#: Names of the warning categories a row's message carries (:func:`_carried_categories`),
#: each written ``Name: text`` there; :func:`warned` finds them.
CARRIED_WARNINGS = ("UnitWarning", "ValidityWarning", "AccuracyWarning")


def warned(table) -> Any:
    """Which rows of a study table carry a warning of the run in their ``message``
    (a boolean Series)."""
    pattern = r"\b(?:" + "|".join(CARRIED_WARNINGS) + r"): "
    return table["message"].fillna("").astype(str).str.contains(pattern, regex=True)


def _message(own: str, caught: Sequence[warnings.WarningMessage]) -> str:
    """The row's message: the run's own, then each distinct warning of :data:`CARRIED_WARNINGS`
    as ``Name: text``, separated by ``"; "``.  Other warnings are shown as usual."""
    carried = _carried_categories()
    parts = [own] if own else []
    for w in caught:
        if issubclass(w.category, carried):
            text = f"{w.category.__name__}: {' '.join(str(w.message).split())}"
            if text not in parts:
                parts.append(text)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
    return "; ".join(parts)


def _run_one(function: Callable[[Params], Mapping[str, Any]], params: Params, key: str) -> dict[str, Any]:
    start = time.perf_counter()
    row: dict[str, Any] = dict(params)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")  # every run says its own warnings, not only the first run of a process
        _run_into(row, function, params)
    row["message"] = _message(row["message"], caught)
    row["wall_time"] = time.perf_counter() - start
    row["run_id"] = key
    return row


def _run_into(row: dict[str, Any], function: Callable[[Params], Mapping[str, Any]], params: Params) -> None:
    """One run: its metrics, ``success`` and ``message`` into ``row``."""
    try:
        summary = function(dict(params))
        if not isinstance(summary, Mapping):
            raise TypeError(f"the study function must return a dict, got {type(summary).__name__}")
        clash = sorted((set(summary) & set(params)) | (set(summary) & {"wall_time", "run_id"}))
        if clash:
            raise ValueError(f"the summary repeats the names {clash} (parameters or status columns)")
        # arrays travel back whole (pickled); the table turns them into lists
        metrics = {k: v if isinstance(v, np.ndarray) else _plain(v) for k, v in summary.items()
                   if k not in ("success", "message")}
        row.update(metrics)
        row["success"] = bool(summary.get("success", True))
        row["message"] = str(summary.get("message", ""))
    except Exception as err:  # a failed run is a row; KeyboardInterrupt is not caught
        row["success"], row["message"] = False, _error_text(err)


def _run_batch(function: Any, batch: Sequence[tuple[str, Params]]) -> list[dict[str, Any]]:
    """Run a batch in a worker; ``function`` may come cloudpickled (bytes)."""
    if isinstance(function, bytes):
        function = pickle.loads(function)
    return [_run_one(function, params, key) for key, params in batch]


def _shippable(function: Callable) -> Any:
    """The function as local worker processes receive it: by name if importable, else
    (a function of ``__main__`` or a closure) by value through cloudpickle if present."""
    try:
        pickle.dumps(function)
        if getattr(function, "__module__", None) != "__main__":
            return function
    except Exception:  # not picklable by name; cloudpickle may still manage
        pass
    try:
        import cloudpickle
    except ImportError:
        return function  # the executor will report it
    return cloudpickle.dumps(function)


def _ignore_sigint() -> None:
    """Worker initializer: Ctrl-C goes to the main process, which stops the study."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


class _CtrlC:
    """Ctrl-C during a study run in this process (``workers=1``).

    A ``KeyboardInterrupt`` raised inside a solver's Python callback would come back from
    Exudyn as a failed run, and the study would carry on.  So the first Ctrl-C only sets
    :attr:`pressed`: the current run finishes, its row is kept, and the runner then
    stops.  A second Ctrl-C raises at once (a row that then comes back failed is not
    recorded).  Installed only in the main thread, over Python's default handler.
    """

    def __init__(self) -> None:
        self.pressed = 0
        self.previous: Any = None

    def _handle(self, signum: int, frame: Any) -> None:  # noqa: ARG002 - signal handler signature
        self.pressed += 1
        if self.pressed > 1:
            raise KeyboardInterrupt

    def __enter__(self) -> _CtrlC:
        import signal
        import threading

        if threading.current_thread() is threading.main_thread() and \
                signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            self.previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc: object) -> None:
        if self.previous is not None:
            import signal

            signal.signal(signal.SIGINT, self.previous)


class _SerialExecutor(cf.Executor):
    """Runs each task at submission, in this process (``workers=1``).  A
    ``KeyboardInterrupt`` propagates from :meth:`submit` at once."""

    def submit(self, fn, /, *args, **kwargs):  # noqa: D102 - Executor's interface
        future: cf.Future = cf.Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as err:
            future.set_exception(err)
        return future


# =======================================================================================
# the table on disk
# =======================================================================================


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

    def __init__(self, path: Path | None, parameter_names: Sequence[str], keep_arrays: bool = False) -> None:
        self.path = path
        self.columns: list[str] = []
        self.rows: dict[str, dict[str, str]] = {}  # run_id -> row as text
        self.parameter_names = list(parameter_names)
        self.keep_arrays = keep_arrays
        self.arrays: dict[str, dict[str, np.ndarray]] = {}  # run_id -> arrays kept in memory

    @classmethod
    def open(cls, path: Path | None, parameter_names: Sequence[str], keep_arrays: bool = False) -> _Table:
        """The table at ``path``, resumed if it exists (``ValueError`` if it holds another
        study), or a new one."""
        table = cls(path, parameter_names, keep_arrays)
        if path is None or not path.exists() or path.stat().st_size == 0:
            return table
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

    def _rewrite(self) -> None:
        if self.path is None:
            return
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


# =======================================================================================
# executors
# =======================================================================================


@dataclass
class _Pool:
    """The executor of a study, with what it takes to close (and to restart) it."""

    executor: cf.Executor
    workers: int
    owned: bool
    restart: Callable[[], cf.Executor] | None = None
    closers: list[Callable[[], None]] = field(default_factory=list)

    def close(self, cancel: bool = False) -> None:
        if self.owned:
            self.executor.shutdown(wait=not cancel, cancel_futures=True)
        for close in self.closers:
            close()


def _local_processes(workers: int) -> cf.Executor:
    # spawn: the workers start clean (no copy of this process's threads: progress bar,
    # Dask client), as Dask's workers do
    return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                                  initializer=_ignore_sigint)


def _dask_pool(scheduler: str, workers: int | None) -> _Pool:
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError("`scheduler` needs Dask: pip install 'exuclear[cluster]'") from None
    closers = []
    if scheduler == "local":
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
        closers = [client.close, cluster.close]
    else:
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as err:
            raise ValueError(f"cannot reach the Dask scheduler at {scheduler!r}: {err}") from None
        closers = [client.close]
    threads = sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values()) or 1
    # pure=False: a batch resubmitted after a worker was lost is run again, not served
    # from the result of its first submission
    executor = client.get_executor(pure=False)
    return _Pool(executor, threads, owned=False, closers=closers)


def _pool(workers: int | None, scheduler: str | None, executor: cf.Executor | None) -> _Pool:
    if executor is not None:
        if scheduler is not None:
            raise ValueError("give either `executor` or `scheduler`, not both")
        count = workers or getattr(executor, "_max_workers", None) or os.cpu_count() or 1
        return _Pool(executor, count, owned=False)
    if scheduler is not None:
        if not isinstance(scheduler, str) or not scheduler:
            raise ValueError(f"`scheduler` must be an address such as 'tcp://host:8786' or 'local', got {scheduler!r}")
        return _dask_pool(scheduler, workers)
    count = workers if workers is not None else (os.cpu_count() or 1)
    if count == 1:
        return _Pool(_SerialExecutor(), 1, owned=False)
    return _Pool(_local_processes(count), count, owned=True, restart=lambda: _local_processes(count))


def _check_workers(workers: int | None) -> None:
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, Integral) or workers < 1):
        raise ValueError(f"`workers` must be a positive integer, got {workers!r}")


# =======================================================================================
# the runner
# =======================================================================================


def prepare(study: Study | Callable, runs: Iterable[Mapping[str, Any]]) -> list[tuple[str, Params]]:
    """Complete and check every parameter set before any run: ``ValueError`` naming the
    first bad set.  Returns ``(run_id, params)`` pairs, duplicates dropped."""
    study = _as_study(study)
    prepared, seen = [], set()
    for index, params in enumerate(runs):
        full = study.complete(params)
        if study.check is not None:
            try:
                study.check(dict(full))
            except ValueError as err:
                raise ValueError(f"run {index} {params}: {err}") from None
        key = run_id(full)
        if key not in seen:
            seen.add(key)
            prepared.append((key, full))
    if not prepared:
        raise ValueError("the study has no runs")
    return prepared


def run_study(study: Study | Callable[[Params], Mapping[str, Any]], runs: Iterable[Mapping[str, Any]],
              out: str | os.PathLike | None = None, *, workers: int | None = None, scheduler: str | None = None,
              executor: cf.Executor | None = None, batch_size: int | None = None, retry_failed: bool = False,
              progress: bool = True, keep_arrays: bool = False):
    """Run ``study`` over ``runs``; returns the table (a DataFrame, rows in the order of
    ``runs``).

    Parameters
    ----------
    study : Study or callable
        The study (a bare function: no parameter names or checks).
    runs : iterable of dict
        Parameter sets (:func:`grid`, :func:`sample`, or a list); all are completed and
        checked before the first run.
    out : path, optional
        The study's CSV, appended row by row; an existing table of the same study is
        resumed (its runs are skipped).  Parquet is written next to it at the end when
        pyarrow is present.
    workers : int, optional
        Local worker processes (default: all cores; 1: in this process), or the workers
        of a local Dask cluster.
    scheduler : str, optional
        A Dask scheduler address, or ``"local"`` for a ``LocalCluster``.
    executor : concurrent.futures.Executor, optional
        Run through this executor instead (not shut down here).
    batch_size : int, optional
        Runs per task; default: adaptive, about :data:`TASK_SECONDS` of work per task.
    retry_failed : bool
        Also redo the runs that failed in the existing table.
    progress : bool
        Show a tqdm progress bar (done, failed, rate, ETA) on stderr.
    keep_arrays : bool
        Only with ``out=None``: array metrics come back as the numpy arrays the runs
        returned, not through the table's text as lists; for time series a table on
        disk would not carry.

    Returns
    -------
    DataFrame
        One row per parameter set of ``runs``.  ``table.attrs["ran"]``: the runs made
        by this call; ``table.attrs["resumed"]``: the rows taken from the table at ``out``
        (a resumed study).  A row's ``message`` carries the run's own message and its
        warnings of :data:`CARRIED_WARNINGS` (``UnitWarning: ...``; :func:`warned`).

    Raises
    ------
    ValueError
        Before any run: unknown parameter names, values the study refuses, no runs,
        a table at ``out`` that belongs to another study.
    KeyboardInterrupt
        On Ctrl-C or a ``KeyboardInterrupt`` from a run, after the finished rows are on
        disk.
    """
    study = _as_study(study)
    _check_workers(workers)
    if batch_size is not None and (isinstance(batch_size, bool) or not isinstance(batch_size, Integral)
                                   or batch_size < 1):
        raise ValueError(f"`batch_size` must be a positive integer, got {batch_size!r}")
    prepared = prepare(study, runs)
    path = None if out is None else Path(out)
    if keep_arrays and path is not None:
        raise ValueError("`keep_arrays` keeps arrays in memory: give it with `out=None`")
    if path is not None and path.suffix.lower() != ".csv":
        raise ValueError(f"`out` must name a .csv file (Parquet is written next to it), got {str(out)!r}")
    if path is not None and not path.parent.exists():
        path.parent.mkdir(parents=True)
    names = list(study.parameters) if study.parameters is not None else list(dict.fromkeys(
        k for _, p in prepared for k in p))
    table = _Table.open(path, names, keep_arrays)
    done = {k for k, row in table.rows.items() if not (retry_failed and row.get("success") == "False")}
    todo = deque((k, p) for k, p in prepared if k not in done)
    order = [k for k, _ in prepared]
    ran = len(todo)
    if todo:
        _execute(study, todo, table, len(prepared), workers, scheduler, executor, batch_size, progress)
    df = table.frame(order)
    if path is not None:
        _write_parquet(df, path)
    df.attrs.update(ran=ran, resumed=len(prepared) - ran)  # after the Parquet file, which would keep them
    return df


class _Progress:
    """tqdm bar of done runs, with the failed ones in its postfix; or nothing."""

    def __init__(self, total: int, initial: int, label: str, show: bool) -> None:
        self.failed = 0
        self.bar = None
        if show:
            from tqdm.auto import tqdm

            self.bar = tqdm(total=total, initial=initial, desc=label or "study", unit="run", dynamic_ncols=True,
                            smoothing=0.1)
            self.bar.set_postfix(failed=0)

    def update(self, rows: Sequence[Mapping[str, Any]]) -> None:
        self.failed += sum(not r["success"] for r in rows)
        if self.bar is not None:
            self.bar.update(len(rows))
            self.bar.set_postfix(failed=self.failed)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _execute(study: Study, todo: deque, table: _Table, total: int, workers: int | None, scheduler: str | None,
             executor: cf.Executor | None, batch_size: int | None, show: bool) -> None:
    pool = _pool(workers, scheduler, executor)
    serial = isinstance(pool.executor, _SerialExecutor)
    function = study.function if serial else _shippable(study.function)
    bar = _Progress(total, total - len(todo), study.name, show)
    in_flight: dict[cf.Future, list] = {}
    window = 1 if serial else pool.workers * IN_FLIGHT_PER_WORKER
    ctrl_c = _CtrlC() if serial else contextlib.nullcontext(None)
    interrupted = False
    try:
        with ctrl_c as pressed:
            _loop(pool, function, todo, table, bar, batch_size, window, in_flight, pressed)
    except KeyboardInterrupt:
        interrupted = True
        for future in list(in_flight):  # tasks finished meanwhile are kept too
            if future.done() and not future.cancelled() and future.exception() is None:
                for row in future.result():
                    table.add(row)
                del in_flight[future]
    finally:
        bar.close()
        for future in in_flight:
            future.cancel()
        pool.close(cancel=interrupted or bool(in_flight))
    if interrupted:
        where = f"; {len(table.rows)} rows kept in {table.path}, run again to resume" if table.path else ""
        raise KeyboardInterrupt(f"study interrupted{where}")


def _loop(pool: _Pool, function: Any, todo: deque, table: _Table, bar: _Progress, batch_size: int | None,
          window: int, in_flight: dict, ctrl_c: _CtrlC | None) -> None:
    """Submit batches, keep ``window`` tasks in flight, record the rows as tasks finish."""
    # runs of a task that died as a whole (its worker crashed or was lost): each is rerun
    # alone, so that a second death names the run that causes it
    suspects: deque = deque()
    alone: set[cf.Future] = set()
    timing = [0.0, 0]  # wall time and number of finished runs, for the batch size

    def restart() -> None:
        """A broken local pool loses every task in it: they become suspects."""
        for other in list(in_flight):
            suspects.extend(in_flight.pop(other))
        alone.clear()
        pool.executor.shutdown(wait=True, cancel_futures=True)
        pool.executor = pool.restart()

    def submit(batch: list) -> cf.Future:
        try:
            future = pool.executor.submit(_run_batch, function, batch)
        except BrokenProcessPool:  # a worker died before its task came back: noticed here first
            if pool.restart is None:
                raise
            restart()
            future = pool.executor.submit(_run_batch, function, batch)
        in_flight[future] = batch
        return future

    while todo or suspects or in_flight:
        while (todo or suspects) and len(in_flight) < window:
            if suspects:
                if in_flight:
                    break  # a suspect waits until it can run alone
                future = submit([suspects.popleft()])
                if len(in_flight) == 1:
                    alone.add(future)
                break
            size = batch_size or _batch_size(timing, len(todo), pool.workers)
            submit([todo.popleft() for _ in range(min(size, len(todo)))])
        finished, _ = cf.wait(in_flight, return_when=cf.FIRST_COMPLETED)
        for future in [f for f in in_flight if f in finished]:  # in the order of submission
            batch = in_flight.pop(future, None)
            if batch is None:
                continue  # lost with its broken pool (below) and queued again
            try:
                rows = future.result()
            except (KeyboardInterrupt, cf.CancelledError):
                raise KeyboardInterrupt from None
            except Exception as err:  # the task died as a whole: worker killed or lost, unpicklable result
                rows = [_crashed_row(batch[0], err)] if future in alone else []
                if not rows:
                    suspects.extend(batch)
                if isinstance(err, BrokenProcessPool) and pool.restart is not None:
                    restart()
            alone.discard(future)
            if ctrl_c is not None and ctrl_c.pressed > 1:
                rows = [row for row in rows if row["success"]]  # a failure may be the second Ctrl-C
            for row in rows:
                table.add(row)
                timing[0] += row["wall_time"] if math.isfinite(row["wall_time"]) else 0.0
                timing[1] += 1
            bar.update(rows)
        if ctrl_c is not None and ctrl_c.pressed:
            raise KeyboardInterrupt


def _crashed_row(item: tuple[str, Params], err: BaseException) -> dict[str, Any]:
    key, params = item
    return {**params, "success": False, "message": f"the run killed its worker ({_error_text(err)})",
            "wall_time": math.nan, "run_id": key}


def _batch_size(timing: list, left: int, workers: int) -> int:
    """Runs per task: about :data:`TASK_SECONDS` of work at the mean run time so far
    (one run until a first one has finished), and no more than leaves
    :data:`TASKS_PER_WORKER` tasks per worker over the runs left."""
    seconds, count = timing
    if count == 0:
        return 1
    mean = max(seconds / count, 1e-6)
    balanced = max(1, left // (workers * TASKS_PER_WORKER))
    return max(1, min(int(TASK_SECONDS / mean), balanced))


# =======================================================================================
# scenes
# =======================================================================================


def scene_names() -> dict[str, str]:
    """The scenes known by short name: name -> module path, from the installed
    distributions' entry points in the group :data:`SCENE_ENTRY_POINTS` (the first of a
    name wins, as on ``sys.path``)."""
    from importlib.metadata import entry_points

    found: dict[str, str] = {}
    for point in entry_points(group=SCENE_ENTRY_POINTS):
        found.setdefault(point.name, point.value)
    return found


def scene(name: str) -> Study:
    """The study of a scene: a short name of :func:`scene_names` (``"slider-crank"``), or
    a dotted path of any module with a ``study`` function, ``STUDY_PARAMETERS`` (defaults)
    and ``check_study``."""
    if "." in name:
        module_name = name
    else:
        known = scene_names()
        if name not in known:
            raise ValueError(f"unknown scene {name!r}; known: {', '.join(sorted(known)) or 'none installed'}, "
                             "or a module path (package.module)")
        module_name = known[name]
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as err:
        raise ValueError(f"unknown scene {name!r} (no module {module_name}: {err})") from None
    missing = [n for n in ("study", "STUDY_PARAMETERS") if not hasattr(module, n)]
    if missing:
        raise ValueError(f"module {module_name} is not a scene: it has no {', '.join(missing)}")
    return Study(module.study, dict(module.STUDY_PARAMETERS), getattr(module, "check_study", None), name,
                 dict(getattr(module, "STUDY_COLUMNS", {})))


# =======================================================================================
# command line
# =======================================================================================


def _option(name: str) -> str:
    return "--" + name.replace("_", "-")


#: What the study's parsers take for a negative value, not an option: "-" and a digit
#: (``-1e-4``, ``-.5``, ``-2:0:1``, ``-1,0,1``), ``-inf``, ``-nan``.  argparse's own pattern
#: (Python < 3.13) misses the exponent and list forms, and ``--clearance -1e-4`` was
#: "expected one argument" instead of the rule the value breaks.
_NEGATIVE_VALUE = re.compile(r"^-(\.?\d|inf|nan)", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` that reads negative numbers (:data:`_NEGATIVE_VALUE`) as values."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_VALUE  # argparse's hook for what a negative number is


def _scene_parser(study: Study, prog: str) -> argparse.ArgumentParser:
    ap = _Parser(
        prog=prog, description=f"Sweep the {study.name} scene: each parameter option takes one value, a list "
        "a,b,c or a range start:stop:step (stop included); with --sample N, low:high bounds to draw from.")
    columns = study.columns or {}
    for name, default in (study.parameters or {}).items():
        column = columns.get(name)
        flags = [_option(name)] + [_option(alias) for alias in (column.aliases if column else ())]
        what = f"{column.axis_label}; " if column else ""
        ap.add_argument(*flags, dest=name, metavar="VALUES", help=f"{what}default {default!r}".replace("%", "%%"))
    ap.add_argument("--sample", type=int, metavar="N", help="draw N parameter sets in the low:high bounds "
                    "instead of the grid")
    # not --method, which on the scenes' command lines is the solver
    ap.add_argument("--sampling", choices=("lhs", "random"), default="lhs",
                    help="how --sample draws: Latin hypercube or independent uniform (default %(default)s)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the sample (default %(default)s)")
    ap.add_argument("--workers", type=int, help="local worker processes (default: all cores; 1: serial), or the "
                    "workers of --scheduler local")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address (tcp://host:8786), or 'local' "
                    "for a Dask LocalCluster")
    ap.add_argument("--batch-size", type=int, help="runs per task (default: about 1 s of work)")
    ap.add_argument("--retry-failed", action="store_true", help="redo the runs that failed in an existing table")
    ap.add_argument("--out", required=True, metavar="FILE.csv", help="the study's table; an existing one is resumed")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    return ap


def _runs_from_args(study: Study, args: argparse.Namespace) -> list[Params]:
    given = {name: getattr(args, name) for name in (study.parameters or {}) if getattr(args, name) is not None}
    if args.sample is None:
        axes = {}
        for name, text in given.items():
            try:
                axes[name] = parse_values(text)
            except ValueError as err:
                raise ValueError(f"`{_option(name)}`: {err}") from None
        return grid(**axes)
    bounds, fixed = {}, {}
    for name, text in given.items():
        if ":" in text:
            try:
                bounds[name] = parse_bounds(text)
            except ValueError as err:
                raise ValueError(f"`{_option(name)}`: {err}") from None
        else:
            values = parse_values(text)
            if len(values) != 1:
                raise ValueError(f"`{_option(name)}`: with --sample, give low:high bounds or one value, got {text!r}")
            fixed[name] = values[0]
    return sample(bounds, args.sample, seed=args.seed, method=args.sampling, fixed=fixed)


def _plot_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="python -m exuclear.study plot",
                                 description="Plot a metric of a study table over one parameter (lines, one per "
                                 "value of --by) or two (heat map, --y).")
    ap.add_argument("table", help="the study's CSV")
    ap.add_argument("--metric", required=True, help="column to plot")
    ap.add_argument("--x", required=True, help="parameter on the horizontal axis")
    ap.add_argument("--y", help="second parameter: a heat map")
    ap.add_argument("--by", help="one line (or point set) per value of this parameter")
    ap.add_argument("--points", action="store_true", help="markers only (a bifurcation-style diagram)")
    ap.add_argument("--where", action="append", default=[], metavar="NAME=VALUE",
                    help="keep the rows with this parameter value (repeatable)")
    ap.add_argument("--scene", help="the scene whose study made the table, for axis labels with units (default: the "
                    "installed scene whose parameters are all columns of the table)")
    ap.add_argument("--logx", action="store_true")
    ap.add_argument("--logy", action="store_true")
    ap.add_argument("--out", required=True, metavar="FILE", help="figure file (png, pdf, svg)")
    return ap


def _scene_of(table) -> Study | None:
    """The installed scene (:func:`scene_names`) whose parameters are all columns of
    ``table``, if exactly one is; None otherwise."""
    found = []
    for name in scene_names():
        try:
            study = scene(name)
        except ValueError:  # a broken entry point does not stop a plot
            continue
        if study.parameters and set(study.parameters) <= set(table.columns):
            found.append(study)
    return found[0] if len(found) == 1 else None


def _plot_main(argv: list[str]) -> int:
    args = _plot_parser().parse_args(argv)
    try:
        from exuclear.study_plot import plot_metric

        table = load_table(args.table)
        where = {}
        for item in args.where:
            name, sep, value = item.partition("=")
            if not sep:
                raise ValueError(f"`--where` is NAME=VALUE, got {item!r}")
            where[name] = _number(value)
        study = scene(args.scene) if args.scene else _scene_of(table)
        path = plot_metric(table, args.metric, args.x, y=args.y, by=args.by, where=where, points=args.points,
                           logx=args.logx, logy=args.logy, path=args.out, columns=study.columns if study else None)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print(f"wrote {path}")
    return 0


def _one_line_warnings() -> None:
    """Show warnings of the parameter checks (a unit slip, before any run) as one line
    ``warning: ...`` on stderr, as the scenes' command lines do; the runs' own warnings go
    into their rows."""

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001 - warnings' signature
        print(f"warning: {category.__name__}: {message}", file=sys.stderr)

    warnings.showwarning = show


def main(argv: list[str] | None = None) -> int:
    """``python -m exuclear.study SCENE [options]`` or ``python -m exuclear.study plot TABLE ...``."""
    argv = list(sys.argv[1:] if argv is None else argv)
    prog = "python -m exuclear.study"
    if not argv or argv[0] in ("-h", "--help"):
        names = ", ".join(sorted(scene_names())) or "none installed"
        print(f"usage: {prog} SCENE [--PARAMETER VALUES ...] --out FILE.csv   (SCENE: {names}, "
              f"or a module path)\n       {prog} SCENE --help\n       {prog} plot TABLE --metric M "
              f"--x P [--by P | --y P] --out FIG")
        return 0 if argv else 2
    if argv[0] == "plot":
        return _plot_main(argv[1:])
    with warnings.catch_warnings():  # the caller's way of showing warnings comes back after it
        _one_line_warnings()
        return _scene_main(argv, prog)


def _scene_main(argv: list[str], prog: str) -> int:
    """``python -m exuclear.study SCENE [options]``."""
    try:
        study = scene(argv[0])
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    args = _scene_parser(study, f"{prog} {argv[0]}").parse_args(argv[1:])
    try:
        runs = _runs_from_args(study, args)
        table = run_study(study, runs, args.out, workers=args.workers, scheduler=args.scheduler,
                          batch_size=args.batch_size, retry_failed=args.retry_failed, progress=not args.no_progress)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as err:
        print(f"{err or 'interrupted'}", file=sys.stderr)
        return 130
    print(_summary_line(table, args.out))
    return 0


def _summary_line(table, out: str | os.PathLike) -> str:
    """The command line's last line: runs made now and taken from the file, failed runs,
    and runs with warnings (:func:`warned`)."""
    failed = int((~table["success"].astype(bool)).sum())
    with_warnings = int(warned(table).sum()) if len(table) else 0
    ran, resumed = table.attrs.get("ran", len(table)), table.attrs.get("resumed", 0)
    runs = f"{len(table)} runs ({ran} ran now, {resumed} taken from {out})" if resumed else f"{len(table)} runs"
    warns = f", {with_warnings} with warnings (see their message)" if with_warnings else ""
    return f"{runs}, {failed} failed{warns}; table {out}"


if __name__ == "__main__":
    # the importable module's main, so that what travels to worker processes (functions,
    # classes) is exuclear.study's own and not this __main__ copy's
    from exuclear.study import main as _main

    sys.exit(_main())
