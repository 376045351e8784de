"""SciPy reference for the journal-bearing impact (docs/physics.md section 6.1, the paper's example 1).

::

        bearing hole, radius R_B, fixed
           .-------.
          /  .---.  \\
         |  ( J   )->|   journal: mass m, no rotation, no gravity, no friction;
          \\  '---'  /    at t = 0 it touches the wall (|e| = c) and moves along n
           '-------'     into it at v_impact

The journal's centre ``(x, y)`` relative to the bearing centre is integrated in the
plane, ``m (x, y)'' = -F_N n``, with the contact geometry of
:mod:`validation.reference._contact`; the start is ``e = (c, 0)``, ``e_dot =
(v_impact, 0)``.  The contact begins at t = 0, so ``v0 = delta_dot(0) = v_impact``
exactly.  Events locate the deepest penetration (``delta_dot`` crossing 0 downward)
and the release (``delta`` back to 0, terminal).  Nothing of exuclear but the law is
used (see :mod:`validation.reference`).
"""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from exuclear.models.journal_bearing import JournalBearingParams

from ._contact import build_laws, gap

#: Samples of the output time series over the contact (release time included).
N_OUTPUT = 2001
#: Relative tolerance in time when the force peak is refined on the dense output:
#: far below the sampling interval (contact duration / 2000), near machine precision.
PEAK_XTOL = 1e-13


def _gap_of(clearance: float):
    """``(delta, delta_dot)`` of a state ``y = (x, y, vx, vy)``."""
    def gap_of(y) -> tuple[float, float]:
        return gap(y[0], y[1], y[2], y[3], clearance)
    return gap_of


def _make_rhs(normal_force, mass: float, clearance: float, v0: float):
    """``y' = (vx, vy, ax, ay)`` with ``m a = -F_N n`` (no friction, no rotation)."""
    def rhs(t: float, y) -> list[float]:
        x, yy, vx, vy = y
        ecc = math.hypot(x, yy)
        delta = ecc - clearance
        if delta <= 0.0:
            return [vx, vy, 0.0, 0.0]
        nx, ny = x / ecc, yy / ecc
        f_n = normal_force(delta, vx * nx + vy * ny, v0)
        return [vx, vy, -f_n * nx / mass, -f_n * ny / mass]
    return rhs


def _events(gap_of):
    """Release (terminal) and deepest penetration (recorded)."""
    def release(t: float, y) -> float:
        # max(delta, delta_dot) falls through 0 only once delta < 0 while separating;
        # it starts at delta_dot(0) = v_impact > 0 although delta(0) = 0
        delta, delta_dot = gap_of(y)
        return max(delta, delta_dot)

    def deepest(t: float, y) -> float:
        return gap_of(y)[1]

    release.terminal, release.direction = True, -1.0
    deepest.terminal, deepest.direction = False, -1.0
    return [release, deepest]


def _peak_force(force_at, times: np.ndarray, forces: np.ndarray) -> float:
    """Largest force: the sampled maximum refined by a bounded search on the dense output."""
    k = int(np.argmax(forces))
    lo, hi = times[max(k - 1, 0)], times[min(k + 1, len(times) - 1)]
    if hi <= lo:
        return float(forces[k])
    best = minimize_scalar(lambda t: -force_at(t), bounds=(lo, hi), method="bounded",
                           options={"xatol": PEAK_XTOL * hi})
    return max(float(forces[k]), -float(best.fun))


def _check(params: JournalBearingParams, rtol: float, atol: float) -> None:
    for name, value in (("mass", params.mass), ("impact_velocity", params.impact_velocity),
                        ("end_time", params.end_time), ("rtol", rtol), ("atol", atol)):
        if not value > 0.0:
            raise ValueError(f"`{name}` must be positive, got {value}")


def simulate(params: JournalBearingParams, method: str = "DOP853", rtol: float = 1e-11,
             atol: float = 1e-16) -> dict:
    """One impact of the journal on the bearing wall, integrated until the release.

    Parameters
    ----------
    params : JournalBearingParams
        Law, cr, materials, radii, length, mass, impact velocity, ``v_min`` and the
        latest release time ``end_time`` (attribute access only).
    method : str
        A :func:`scipy.integrate.solve_ivp` method.
    rtol, atol : float
        Its tolerances; ``atol`` applies to positions of order ``c = 1e-4`` m and to
        velocities of order ``v_impact``.

    Returns
    -------
    dict
        ``departure_velocity`` [m/s] (the speed at the release, where ``delta`` is back
        to 0), ``max_force`` [N], ``max_penetration`` [m], ``contact_duration`` [s]; the
        series ``time``, ``penetration``, ``penetration_rate``, ``normal_force`` with
        :data:`N_OUTPUT` samples from 0 to the release; ``n_rhs`` (solve_ivp's ``nfev``), ``wall_time``,
        ``success`` and ``message``.  When the journal has not left the wall by
        ``params.end_time`` the scalars are NaN and ``success`` is False.
    """
    _check(params, rtol, atol)
    clearance = params.bearing_radius - params.journal_radius
    laws = build_laws(journal_radius=params.journal_radius, bearing_radius=params.bearing_radius,
                      length=params.length, law=params.law, cr=params.cr, journal_material=params.journal_material,
                      bearing_material=params.bearing_material, friction="none", v_min=params.v_min)
    gap_of = _gap_of(clearance)
    y0 = np.array([clearance, 0.0, params.impact_velocity, 0.0])
    v0 = gap_of(y0)[1]  # the contact starts now: v0 is the exact penetration rate of the start
    rhs = _make_rhs(laws.normal_force, params.mass, clearance, v0)
    start = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, params.end_time), y0, method=method, rtol=rtol, atol=atol,
                    events=_events(gap_of), dense_output=True)
    wall_time = time.perf_counter() - start
    released = sol.status == 1
    t_end = float(sol.t_events[0][0]) if released else float(sol.t[-1])
    times = np.linspace(0.0, t_end, N_OUTPUT)
    states = sol.sol(times)
    gaps = [gap_of(states[:, k]) for k in range(N_OUTPUT)]
    delta = np.array([g[0] for g in gaps])
    delta_dot = np.array([g[1] for g in gaps])
    force = np.array([laws.normal_force(d, dd, v0) for d, dd in gaps])

    def force_at(t: float) -> float:
        return laws.normal_force(*gap_of(sol.sol(t)), v0)

    deepest = sol.y_events[1]
    out = {
        "departure_velocity": math.hypot(*sol.y_events[0][0][2:]) if released else math.nan,
        "max_force": _peak_force(force_at, times, force),
        "max_penetration": max(gap_of(y)[0] for y in deepest) if len(deepest) else float(delta.max()),
        "contact_duration": t_end if released else math.nan,
        "time": times, "penetration": delta, "penetration_rate": delta_dot, "normal_force": force,
        "n_rhs": int(sol.nfev), "wall_time": wall_time, "success": bool(sol.success and released),
        "message": sol.message,
    }
    if sol.success and not released:
        out["message"] = f"the journal had not left the wall by end_time = {params.end_time} s; raise end_time"
    return out
