"""Piecewise integration of the slider-crank: free flight until ``delta`` crosses 0
upward (a terminal event, or an onset hidden inside one step, found by sampling and
Brent's method), then a contact phase with ``v0`` the exact ``delta_dot`` of the onset
state, until the release event; the phases alternate up to the end time."""
from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from validation.reference._contact import Laws, gap
from validation.reference.slider_crank.mechanism import (
    _N_STATE,
    IMPLICIT_METHODS,
    _Counter,
    _eccentricity,
    _make_dynamics,
    _make_jacobian,
    _make_rhs,
    _Mechanism,
)

#: Safety limit on the number of phases (free flight / contact); a run needing more
#: (chattering at the release) stops with a message instead of looping.
MAX_PHASES = 200_000
#: Relative slack when the output grid is laid on [0, t_end]: keeps a grid point that
#: lands on t_end up to round-off.
GRID_SLACK = 1e-9
#: Samples of ``delta`` that bracket an onset hidden inside one free-flight step.
GRAZE_SAMPLES = 64
#: Brent tolerances for a hidden onset: machine precision in time, as solve_ivp's events.
ROOT_XTOL, ROOT_RTOL = 4 * np.finfo(float).eps, 4 * np.finfo(float).eps

def _gap(m: _Mechanism, t: float, y) -> tuple[float, float]:
    return gap(*_eccentricity(m, t, y), m.c)


def _free_events(m: _Mechanism) -> list[Callable]:
    """Onset: ``min(delta, delta_dot)`` up through 0 (terminal); apex of ``delta`` (recorded).

    The onset function equals ``delta`` at an onset (``delta_dot > 0`` there), but starts
    at ``delta_dot(release) < 0`` although ``delta(release) = 0`` up to round-off, so a
    return to the wall within the first step is not lost.  The apex event guards against
    a graze that enters and leaves the wall inside one step: its step ends have
    ``delta < 0``, but the apex inside shows ``delta > 0`` (see :func:`_missed_onset`).
    """
    def onset(t: float, y) -> float:
        delta, delta_dot = _gap(m, t, y)
        return min(delta, delta_dot)

    def apex(t: float, y) -> float:
        return _gap(m, t, y)[1]

    onset.terminal, onset.direction = True, 1.0
    apex.terminal, apex.direction = False, -1.0
    return [onset, apex]


def _contact_events(m: _Mechanism) -> list[Callable]:
    """Release: ``max(delta, delta_dot)`` down through 0 (terminal).

    The mirror image of the onset function of :func:`_free_events`: it equals ``delta``
    at a release (``delta_dot < 0`` there), starts at ``delta_dot(onset) > 0`` although
    ``delta(onset) = 0`` up to round-off, and catches a contact whose penetration never
    shows at a step end.
    """
    def release(t: float, y) -> float:
        delta, delta_dot = _gap(m, t, y)
        return max(delta, delta_dot)

    release.terminal, release.direction = True, -1.0
    return [release]


def _missed_onset(m: _Mechanism, sol, t_stop: float) -> float | None:
    """Earliest onset hidden inside one free-flight step, or None.

    An apex with ``delta > 0`` before ``t_stop`` means ``delta`` crossed 0 upward between
    the step point before the apex and the apex.  The last upward crossing there is
    bracketed on :data:`GRAZE_SAMPLES` points of the dense output and refined by Brent's
    method.
    """
    def delta_at(t: float) -> float:
        return _gap(m, t, sol.sol(t))[0]

    for t_apex, y_apex in zip(sol.t_events[1], sol.y_events[1]):
        if t_apex >= t_stop or _gap(m, t_apex, y_apex)[0] <= 0.0:
            continue
        k = max(int(np.searchsorted(sol.t, t_apex)) - 1, 0)
        ts = np.linspace(float(sol.t[k]), float(t_apex), GRAZE_SAMPLES)
        below = np.flatnonzero(np.array([delta_at(t) for t in ts]) <= 0.0)
        if len(below) == 0:
            return float(ts[0])
        j = int(below[-1])
        return brentq(delta_at, ts[j], ts[j + 1], xtol=ROOT_XTOL, rtol=ROOT_RTOL)
    return None


class _Phase(NamedTuple):
    """One integrated phase: [t_start, t_stop], its dense output and its v0 (None: free)."""

    t_start: float
    t_stop: float
    sol: object
    v0: float | None


def _solve_phase(m: _Mechanism, laws: Laws, counter: _Counter, t0: float, y0: np.ndarray, t_end: float,
                 v0: float | None, options: dict) -> tuple[_Phase, object]:
    """Integrate one phase until its event or ``t_end``; returns the phase and the solution."""
    events = _free_events(m) if v0 is None else _contact_events(m)
    rhs = _make_rhs(m, _make_dynamics(m, laws, v0), counter)
    if options["method"] in IMPLICIT_METHODS:
        options = {**options, "jac": _make_jacobian(m, rhs)}
    sol = solve_ivp(rhs, (t0, t_end), y0, events=events, dense_output=True, **options)
    t_stop = float(sol.t_events[0][0]) if sol.status == 1 else float(sol.t[-1])
    if v0 is None:
        hidden = _missed_onset(m, sol, t_stop)
        t_stop = t_stop if hidden is None else hidden
    return _Phase(t0, t_stop, sol.sol, v0), sol


def _initial_state(m: _Mechanism) -> np.ndarray:
    """Crank angle 0, rod along +X (``phi = 0``), journal centred (``x = r + l``), the
    velocities of the ideal mechanism at ``theta = 0`` (``phi_t = -omega r / l``,
    ``x_t = 0``), no work done yet."""
    y = np.zeros(_N_STATE)
    y[1], y[2] = m.r + m.l, -m.omega * m.r / m.l
    return y


def _integrate(m: _Mechanism, laws: Laws, t_end: float, options: dict) -> tuple[list[_Phase], list[float], int, bool, str]:
    """Alternate free and contact phases from the initial state up to ``t_end``."""
    counter = _Counter()
    y = _initial_state(m)
    t, v0 = 0.0, None
    phases: list[_Phase] = []
    onsets: list[float] = []
    while t < t_end:
        if len(phases) >= MAX_PHASES:
            return phases, onsets, counter.calls, False, (
                f"more than {MAX_PHASES} phases before t = {t:.6g} s (chattering); "
                "try a larger v_min or a different law")
        phase, sol = _solve_phase(m, laws, counter, t, y, t_end, v0, options)
        phases.append(phase)
        if not sol.success:
            return phases, onsets, counter.calls, False, f"solver failed at t = {sol.t[-1]:.6g} s: {sol.message}"
        t = phase.t_stop
        y = phase.sol(t)
        if t < t_end:  # an event ended the phase: switch free <-> contact
            if v0 is None:
                v0 = _gap(m, t, y)[1]  # the exact penetration rate at the onset
                onsets.append(t)
            else:
                v0 = None
    return phases, onsets, counter.calls, True, "success"
