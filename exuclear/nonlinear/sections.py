"""Poincare sections of recorded signals (no exudyn): once per forcing period
(:func:`stroboscopic`, a speed-driven crank) and where an angle crosses a value
(:func:`crossings`, a torque-driven crank).

A run records its outputs at the solver's accepted steps, which do not fall on the
section times; the samples are interpolated between them.  The default interpolant is
the modified Akima spline (:class:`scipy.interpolate.Akima1DInterpolator`, ``makima``):
cubic and local, so a kink of the signal (an impact) does not ring into its neighbours,
as a global cubic spline would.
"""
from __future__ import annotations

import math

import numpy as np

from ..checks import check_positive, check_real

#: How the samples between recorded instants are found: ``"makima"`` (cubic, local) or
#: ``"linear"``.
INTERPOLATIONS = ("makima", "linear")


def _signal(t: object, x: object) -> tuple[np.ndarray, np.ndarray]:
    """``t`` as increasing times and ``x`` as an array of shape (n, ...) on them; a time
    recorded twice (Exudyn writes the last step again at the end) keeps its last value."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise ValueError(f"`t` must be a 1-d array of at least 2 times, got shape {t.shape}")
    if x.shape[:1] != t.shape:
        raise ValueError(f"`x` must have one row per time: shape ({t.size}, ...), got {x.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x))):
        raise ValueError("`t` and `x` must be finite")
    if np.any(np.diff(t) < 0.0):
        raise ValueError("`t` must not decrease")
    keep = np.append(np.diff(t) > 0.0, True)  # the last of equal times
    return t[keep], x[keep]


def _interpolant(t: np.ndarray, x: np.ndarray, interpolation: str):
    if interpolation not in INTERPOLATIONS:
        raise ValueError(f"`interpolation` must be one of {', '.join(INTERPOLATIONS)}, got {interpolation!r}")
    if interpolation == "linear" or t.size < 3:
        from scipy.interpolate import interp1d

        return interp1d(t, x, axis=0, assume_sorted=True)
    from scipy.interpolate import Akima1DInterpolator

    return Akima1DInterpolator(t, x, axis=0, method="makima")


def stroboscopic(t: object, x: object, period: float, phase: float = 0.0, *,
                 interpolation: str = "makima") -> tuple[np.ndarray, np.ndarray]:
    """Sample a recorded signal once per period: at ``t_k = phase + k period`` within
    ``[t[0], t[-1]]``.

    The Poincare map of a system driven with the period ``period`` (a crank at constant
    speed: ``2 pi / omega``): a period-N response repeats every N samples.

    Parameters
    ----------
    t : array, shape (n,)
        Recorded times [s], not decreasing (a repeated time keeps its last value).
    x : array, shape (n,) or (n, m)
        Recorded values, one row per time.
    period : float
        Forcing period [s], > 0.
    phase : float
        Time of one section [s] (its phase in the period).
    interpolation : str
        ``"makima"`` (default; module docstring) or ``"linear"``.

    Returns
    -------
    t_k : array, shape (k,)
        The section times [s].
    x_k : array, shape (k,) or (k, m)
        The signal there.
    """
    t, x = _signal(t, x)
    period = check_positive("period", period)
    phase = check_real("phase", phase)
    first = math.ceil((t[0] - phase) / period - 1e-9)  # a section on the first instant counts
    last = math.floor((t[-1] - phase) / period + 1e-9)
    t_k = phase + period * np.arange(first, last + 1)
    t_k = np.clip(t_k, t[0], t[-1])  # the 1e-9 of a period above: round-off at the ends
    if t_k.size == 0:
        return t_k, x[:0]
    return t_k, np.asarray(_interpolant(t, x, interpolation)(t_k))


def crossings(t: object, angle: object, x: object, at: float = 0.0, *, direction: int = 1,
              interpolation: str = "makima") -> tuple[np.ndarray, np.ndarray]:
    """Sample a recorded signal where an angle crosses ``at`` (modulo 2 pi).

    The section of a system whose period is not known in advance (a crank under a
    torque): each time the angle passes ``at + 2 pi k``, the instant is found by a root
    search (Brent's method) on the interpolated angle, and ``x`` is interpolated there.

    Parameters
    ----------
    t : array, shape (n,)
        Recorded times [s], not decreasing.
    angle : array, shape (n,)
        The angle [rad], continuous or wrapped to any 2 pi interval (it is unwrapped).
    x : array, shape (n,) or (n, m)
        Recorded values.
    at : float
        The section's angle [rad].
    direction : int
        +1: crossings with the angle increasing (default); -1: decreasing; 0: both.

    Returns
    -------
    t_k, x_k : arrays
        Crossing times [s] and the signal there.
    """
    from scipy.optimize import brentq

    if direction not in (-1, 0, 1):
        raise ValueError(f"`direction` must be -1, 0 or +1, got {direction!r}")
    at = check_real("at", at)
    t_raw = np.asarray(t, dtype=float)
    angle = np.asarray(angle, dtype=float)
    if angle.shape != t_raw.shape:
        raise ValueError(f"`angle` must have the shape of `t` {t_raw.shape}, got {angle.shape}")
    t, both = _signal(t_raw, np.column_stack([np.unwrap(angle), np.asarray(x, dtype=float).reshape(t_raw.size, -1)]))
    phi = both[:, 0]
    turns = np.floor((phi - at) / (2.0 * math.pi))
    interp = _interpolant(t, both, interpolation)
    times = []
    for i in np.flatnonzero(np.diff(turns) != 0.0):
        up = turns[i + 1] > turns[i]
        if direction and up != (direction > 0):
            continue
        target = at + 2.0 * math.pi * (turns[i + 1] if up else turns[i])

        def offset(s: float, target: float = target) -> float:
            return float(interp(s)[0]) - target

        lo, hi = offset(t[i]), offset(t[i + 1])
        times.append(t[i + 1] if hi == 0.0 else t[i] if lo == 0.0 else
                     brentq(offset, t[i], t[i + 1], xtol=1e-14 * max(1.0, abs(t[i + 1])))
                     if lo * hi < 0.0 else t[i] + (t[i + 1] - t[i]) * lo / (lo - hi))
    t_k = np.asarray(times)
    values = np.asarray(interp(t_k))[:, 1:] if t_k.size else np.zeros((0, both.shape[1] - 1))
    return t_k, values if np.ndim(x) > 1 else values[:, 0]
