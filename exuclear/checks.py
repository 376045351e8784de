"""Input checks shared by the public constructors and the scenes (exuclear.models).

Every check raises ``ValueError`` naming the argument and the rule it broke, so a
bad parameter fails before any simulation starts.  Nothing is clamped.
"""
from __future__ import annotations

import math
import warnings
from numbers import Real

from .exceptions import UnitWarning


def warn_unit(message: str) -> None:
    """Warn about a likely unit mistake, pointing at the caller of the public API."""
    warnings.warn(message, UnitWarning, stacklevel=4)


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


def check_choice(name: str, value: object, table: dict) -> str:
    """Check that ``value`` is a key of ``table``; list the known keys if not."""
    if not isinstance(value, str) or value not in table:
        known = ", ".join(sorted(table))
        raise ValueError(f"unknown `{name}` {value!r}; known: {known}")
    return value
