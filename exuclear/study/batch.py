"""One batch of runs, as a worker runs it: each run's row (parameters, metrics, status,
wall time, run id) with the warnings it carries in its message."""
from __future__ import annotations

import pickle
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .spec import Params, _plain


def _error_text(err: BaseException) -> str:
    return f"{type(err).__name__}: {' '.join(str(err).split())}"


def _carried_categories() -> tuple[type[Warning], ...]:
    """The warnings a row carries in its message: exuclear's own, which say that a result
    may not mean what it seems (a unit slip, a law outside its validity, an unconverged path)."""
    from ..exceptions import AccuracyWarning, UnitWarning, ValidityWarning

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
