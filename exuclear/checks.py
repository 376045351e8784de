"""Input checks shared by the public constructors and the scenes (exuclear.models).

Every check raises ``ValueError`` naming the argument and the rule it broke, so a
bad parameter fails before any simulation starts.  Nothing is clamped.
"""
from __future__ import annotations

import math
import os
import sys
import warnings
from numbers import Real

from .exceptions import UnitWarning


def _library_prefixes() -> tuple[str, ...]:
    """The folders of exuclear's own code: the library and, where imported, its scenes
    (``exuclear.models``, installed from another folder)."""
    folders = [os.path.dirname(os.path.abspath(__file__))]
    models = sys.modules.get("exuclear.models")
    folders += [os.path.abspath(p) for p in getattr(models, "__path__", ())]
    return tuple(folder + os.sep for folder in folders)


def warn_at_caller(message: str, category: type[Warning]) -> None:
    """Warn with the location of the first frame outside exuclear: the user's line that
    made the value, however deep in the library the check sits (the ``__init__`` that
    ``dataclasses`` generates, file ``<string>``, counts as the library's)."""
    prefixes = _library_prefixes()
    frame, level = sys._getframe(1), 2
    while frame.f_back is not None and (frame.f_code.co_filename.startswith(prefixes) or (
            frame.f_code.co_filename == "<string>" and frame.f_code.co_name == "__init__")):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


def warn_unit(message: str) -> None:
    """Warn about a likely unit mistake, pointing at the caller of the public API."""
    warn_at_caller(message, UnitWarning)


def check_real(name: str, value: object) -> float:
    """Return ``value`` as float; reject non-numbers, bools, NaN and infinity."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ValueError(f"`{name}` must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"`{name}` must be finite, got {value}")
    return value


def check_positive(name: str, value: object) -> float:
    value = check_real(name, value)
    if value <= 0.0:
        raise ValueError(f"`{name}` must be positive, got {value}")
    return value


def check_nonnegative(name: str, value: object) -> float:
    value = check_real(name, value)
    if value < 0.0:
        raise ValueError(f"`{name}` must be non-negative, got {value}")
    return value


def check_open_closed(name: str, value: object, low: float, high: float) -> float:
    """Check ``low < value <= high``."""
    value = check_real(name, value)
    if not low < value <= high:
        raise ValueError(f"`{name}` must lie in ({low}, {high}], got {value}")
    return value


def check_open(name: str, value: object, low: float, high: float) -> float:
    """Check ``low < value < high``."""
    value = check_real(name, value)
    if not low < value < high:
        raise ValueError(f"`{name}` must lie in ({low}, {high}), got {value}")
    return value


def check_choice(name: str, value: object, table: dict, ignore_case: bool = False) -> str:
    """Check that ``value`` is a key of ``table`` and return the key; list the known keys if
    not.  ``ignore_case``: ``"Wang-Liu"`` finds the key ``"wang-liu"`` (names of laws and
    models, which papers and users spell with capitals)."""
    if isinstance(value, str) and ignore_case and value not in table:
        value = {key.lower(): key for key in table}.get(value.lower(), value)
    if not isinstance(value, str) or value not in table:
        known = ", ".join(sorted(table))
        raise ValueError(f"unknown `{name}` {value!r}; known: {known}")
    return value
