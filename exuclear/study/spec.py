"""What a study is: a function of one parameter set with its defaults and checks, and the
parameter sets to run it over (:func:`grid`, :func:`sample`, the command line's value
grammar :func:`parse_values`) with their identifiers (:func:`run_id`)."""
from __future__ import annotations

import hashlib
import inspect
import itertools
import json
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from numbers import Integral
from typing import Any

import numpy as np

from ..columns import Column

#: Hex digits of the run identifier (64 bits: a collision among 1e6 runs has odds 3e-8).
RUN_ID_DIGITS = 16
#: Significant digits of the values :func:`parse_values` makes from a range: enough for
#: any step, and 0.3 + 0.2 comes out as 0.5, not 0.5000000000000001.
RANGE_DIGITS = 12


Params = dict[str, Any]


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


def identity(study: Study) -> dict[str, Any]:
    """What identifies a study's table: the function (module and qualified name, and a hash
    of its source, which changes with its code: a new metric, another formula), the
    parameters with their defaults and the columns with their units.  Stored beside the
    table (:mod:`exuclear.study.table`), so that a table is resumed only by the study that
    wrote it.  A function whose source cannot be read (built in, typed at a prompt) is
    known by its name alone."""
    function = study.function
    try:
        source = inspect.getsource(function)
    except (OSError, TypeError):  # no source file: the name alone
        source = ""
    name = f"{getattr(function, '__module__', '?')}.{getattr(function, '__qualname__', repr(function))}"
    parameters = None if study.parameters is None else {k: _plain(v) for k, v in study.parameters.items()}
    columns = {k: [c.label, c.unit] for k, c in (study.columns or {}).items()}
    return {"function": name, "source": hashlib.sha256(source.encode()).hexdigest()[:RUN_ID_DIGITS] if source else "",
            "parameters": json.loads(json.dumps(parameters, default=repr)), "columns": columns}


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

