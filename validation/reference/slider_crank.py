"""SciPy reference for the slider-crank with a clearance joint (docs/physics.md section 6.2, the paper's example 2).

::

        Y
        ^          A = r (cos theta, sin theta)
        |         o.
        |  crank /   '.  rod (length l, absolute angle phi)
        |    r  /      '.
        |      / theta   '.   B_J = A + l (cos phi, sin phi): journal centre
        O-----o-----------'(o)__    bearing centre (x, 0) in the slider
      ground pivot          [slider]=====> X   (frictionless guide, y = 0)

Minimal coordinates: the crank angle is prescribed, ``theta = omega t``; the free
coordinates are the rod's absolute angle ``phi`` and the slider position ``x``.  The
clearance joint B (journal on the rod, bearing in the slider) decouples rod and slider,
so the mass matrix of ``(phi, x)`` is diagonal:

``T = J_O omega^2 / 2 + m_r |v_G|^2 / 2 + I_r phi_t^2 / 2 + m_s x_t^2 / 2`` with the crank
inertia about O ``J_O = I_c + m_c r^2 / 4``, the rod centre of mass
``G = A + (l/2)(cos phi, sin phi)`` and
``|v_G|^2 = r^2 omega^2 + (l^2/4) phi_t^2 + r l omega phi_t cos(theta - phi)``;
``V = m_c g (r/2) sin theta + m_r g G_y``.  Lagrange's equations (``theta_tt = 0``):

``J_A phi_tt - m_r (l/2) r omega^2 sin(theta - phi) = -m_r g (l/2) cos phi + Q_phi``,
``J_A = I_r + m_r l^2 / 4`` (the rod about A);

``m_s x_tt = Q_x``.

Contact (docs/physics.md sections 1-4, :mod:`validation.reference._contact`): eccentricity
``e = B_J - (x, 0)``, journal body the rod (angular velocity ``phi_t``), bearing body
the slider (no rotation).  The force ``F_i`` on the journal and the moment ``M_i`` on the
rod give, by virtual work with ``dB_J/dphi = l (-sin phi, cos phi)`` and
``dP_B/dx = (1, 0)``,

``Q_phi = F_i . l (-sin phi, cos phi) + M_i``,   ``Q_x = -F_i,x``.

The slider's moment ``M_j`` is taken by its guide and does no work.  The contact power
on the bodies is then ``-(F_N delta_dot + F_T v_T)``, the energy absorbed by the contact.

Integration is piecewise: free flight until ``delta`` crosses 0 upward (terminal
event), then a contact phase with ``v0`` the exact ``delta_dot`` of the onset state,
until the release event.  Two quadrature states ride along: the crank work
``int M omega dt`` and the contact work ``int (F_N delta_dot + F_T v_T) dt`` (for the
energy audit of :attr:`Result.energy`).
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from exuclear.models.slider_crank import SliderCrankParams

from ._contact import Laws, build_laws, contact_kinematics, gap, journal_loads

#: The exact column names of :attr:`Result.columns` (SI units, angles in degrees).
COLUMNS = ("time", "crank_angle", "slider_x", "slider_v", "slider_a", "contact_force", "crank_moment",
           "ecc_x", "ecc_y", "penetration", "in_contact")
#: Columns of :attr:`Result.energy` [J], cumulative from t = 0.
ENERGY_COLUMNS = ("time", "kinetic", "potential", "crank_work", "contact_work")
#: solve_ivp methods accepted; DOP853 and RK45 (explicit) and Radau (implicit, stiff) are tested.
METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")
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

#: Methods that need a Jacobian; they get the one of :func:`_make_jacobian`.
IMPLICIT_METHODS = ("Radau", "BDF", "LSODA")
#: Relative finite-difference step of that Jacobian: sqrt(machine epsilon), the usual
#: balance of truncation and round-off for forward differences.
FD_STEP = float(np.sqrt(np.finfo(float).eps))

# state vector: phi, x, phi_t, x_t, crank work, contact work; the first four are the
# mechanical states, the last two quadratures that the right-hand side never reads
_N_MECHANICAL, _N_STATE = 4, 6


class _Mechanism(NamedTuple):
    """Constants of the mechanism (SI), read once from the params."""

    r: float
    l: float
    omega: float
    m_c: float
    m_r: float
    m_s: float
    i_r: float
    j_a: float      # rod inertia about A, I_r + m_r l^2 / 4
    j_o: float      # crank inertia about O, I_c + m_c r^2 / 4
    g: float
    r_j: float
    r_b: float
    c: float


def _mechanism(p: SliderCrankParams) -> _Mechanism:
    r, l = p.crank_length, p.rod_length
    return _Mechanism(r=r, l=l, omega=p.crank_speed, m_c=p.crank_mass, m_r=p.rod_mass, m_s=p.slider_mass,
                      i_r=p.rod_inertia, j_a=p.rod_inertia + p.rod_mass * l * l / 4.0,
                      j_o=p.crank_inertia + p.crank_mass * r * r / 4.0, g=p.gravity,
                      r_j=p.bearing_radius - p.clearance, r_b=p.bearing_radius, c=p.clearance)


def _laws(p: SliderCrankParams) -> Laws:
    if p.viscosity is not None:  # the reference has the dry joint's laws only: never treat oil as dry
        raise ValueError(f"the SciPy reference models the dry joint; got `viscosity` {p.viscosity} (an oil film)")
    return build_laws(journal_radius=p.bearing_radius - p.clearance, bearing_radius=p.bearing_radius,
                      length=p.bearing_length, law=p.law, cr=p.cr, journal_material=p.journal_material,
                      bearing_material=p.bearing_material, friction=p.friction, v_min=p.v_min)


@dataclass
class Result:
    """Output of :func:`simulate`.

    Attributes
    ----------
    columns : dict of str to ndarray, shape (n,)
        Exactly the keys of :data:`COLUMNS`: ``time`` [s], ``crank_angle`` [deg],
        ``slider_x`` [m], ``slider_v`` [m/s], ``slider_a`` [m/s^2], ``contact_force``
        ``sqrt(F_N^2 + F_T^2)`` [N], ``crank_moment`` [N m], ``ecc_x``, ``ecc_y`` (journal
        centre minus bearing centre) [m], ``penetration`` ``|e| - c`` [m], ``in_contact``
        (1 inside a contact phase, from onset to release event, else 0).
    onsets : ndarray
        Times of the contact onsets [s].
    n_impacts : int
        Number of contact onsets.
    wall_time : float
        Integration time [s] (output evaluation excluded).
    n_rhs : int
        Right-hand-side evaluations, finite-difference Jacobians of implicit methods included.
    success : bool
    message : str
    energy : dict of str to ndarray, shape (n,)
        Keys of :data:`ENERGY_COLUMNS` on the output grid: kinetic and potential energy,
        the crank work ``int M omega dt`` and the contact work
        ``int (F_N delta_dot + F_T v_T) dt`` (absorbed by the contact; stored elastic
        energy included).  Energy balance: ``crank_work = Delta(kinetic + potential) +
        contact_work``.  Empty for the ideal mechanism.
    """

    columns: dict[str, np.ndarray]
    onsets: np.ndarray
    n_impacts: int
    wall_time: float
    n_rhs: int
    success: bool
    message: str
    energy: dict[str, np.ndarray] = field(default_factory=dict)


# --------------------------------------------------------------------------------------
# dynamics
# --------------------------------------------------------------------------------------
def _eccentricity(m: _Mechanism, t: float, y) -> tuple[float, float, float, float]:
    """``e = B_J - (x, 0)`` and ``e_t`` from the state ``y = (phi, x, phi_t, x_t, ...)``."""
    theta = m.omega * t
    ct, st = math.cos(theta), math.sin(theta)
    cp, sp = math.cos(y[0]), math.sin(y[0])
    return (m.r * ct + m.l * cp - y[1], m.r * st + m.l * sp,
            -m.r * m.omega * st - m.l * y[2] * sp - y[3], m.r * m.omega * ct + m.l * y[2] * cp)


def _crank_moment(m: _Mechanism, theta: float, phi: float, phi_t: float, phi_tt: float,
                 fx_i: float, fy_i: float) -> float:
    """Crank driving moment that keeps ``theta_tt = 0`` [N m].

    Lagrange's equation of the crank angle, with the whole kinetic energy ``T`` of the
    module docstring (``theta`` now free, ``M`` its generalized force):

    ``d/dt dT/dtheta_t - dT/dtheta + dV/dtheta = M + Q_theta``, where
    ``dT/dtheta_t = (J_O + m_r r^2) theta_t + m_r (r l / 2) phi_t cos(theta - phi)``,
    ``dT/dtheta = -m_r (r l / 2) theta_t phi_t sin(theta - phi)`` and
    ``dV/dtheta = (m_c / 2 + m_r) g r cos theta``.  With ``theta_tt = 0``:

    ``M = m_r (r l / 2) (phi_tt cos(theta - phi) + phi_t^2 sin(theta - phi))
    + (m_c / 2 + m_r) g r cos theta - Q_theta``,

    ``Q_theta = F_i . dB_J/dtheta = r (-F_i,x sin theta + F_i,y cos theta)``: the joint
    force on the rod end, which moves with A.  The rod's coupling enters through
    ``phi_tt``, ``phi_t`` and ``F_i``.

    Parameters
    ----------
    m : _Mechanism
    theta, phi, phi_t, phi_tt : float
        Crank angle [rad], rod angle [rad], its rate [rad/s] and acceleration [rad/s^2].
    fx_i, fy_i : float
        Force on the rod end B_J (the journal) [N].
    """
    s, c = math.sin(theta - phi), math.cos(theta - phi)
    coupling = m.m_r * m.r * m.l / 2.0 * (phi_tt * c + phi_t * phi_t * s)
    gravity = (m.m_c / 2.0 + m.m_r) * m.g * m.r * math.cos(theta)
    q_theta = m.r * (-fx_i * math.sin(theta) + fy_i * math.cos(theta))
    return coupling + gravity - q_theta


def _make_dynamics(m: _Mechanism, laws: Laws, v0: float | None) -> Callable:
    """``dyn(t, y) -> (phi_tt, x_tt, M, f_n, f_t, power, e_x, e_y, delta)`` of one phase.

    ``v0 is None``: free flight, no contact force.  Otherwise contact with onset rate v0;
    ``power = F_N delta_dot + F_T v_T`` is the power absorbed by the contact.
    """
    r, l, w, m_r, m_s, j_a, g = m.r, m.l, m.omega, m.m_r, m.m_s, m.j_a, m.g
    r_j, r_b, c = m.r_j, m.r_b, m.c
    normal_force, mu, frictional = laws.normal_force, laws.friction_coefficient, laws.frictional
    in_contact = v0 is not None

    def dyn(t: float, y) -> tuple:
        theta = w * t
        ct, st = math.cos(theta), math.sin(theta)
        phi, phi_t = y[0], y[2]
        cp, sp = math.cos(phi), math.sin(phi)
        ex, ey = r * ct + l * cp - y[1], r * st + l * sp
        f_n = f_t = power = fx = fy = m_i = 0.0
        delta = math.hypot(ex, ey) - c
        if in_contact and delta > 0.0:
            vex, vey = -r * w * st - l * phi_t * sp - y[3], r * w * ct + l * phi_t * cp
            delta, delta_dot, v_t, nx, ny = contact_kinematics(ex, ey, vex, vey, phi_t, 0.0, r_j, r_b, c)
            f_n = normal_force(delta, delta_dot, v0)
            f_t = mu(v_t) * f_n if frictional else 0.0
            fx, fy, m_i, _ = journal_loads(nx, ny, f_n, f_t, r_j, r_b)  # M_j goes to the guide
            power = f_n * delta_dot + f_t * v_t
        q_phi = -m_r * g * l / 2.0 * cp + l * (-sp * fx + cp * fy) + m_i
        phi_tt = (q_phi + m_r * l / 2.0 * r * w * w * math.sin(theta - phi)) / j_a
        x_tt = -fx / m_s
        moment = _crank_moment(m, theta, phi, phi_t, phi_tt, fx, fy)
        return phi_tt, x_tt, moment, f_n, f_t, power, ex, ey, delta

    return dyn


class _Counter:
    """Counts right-hand-side calls of all phases."""

    def __init__(self) -> None:
        self.calls = 0


def _make_rhs(m: _Mechanism, dyn: Callable, counter: _Counter) -> Callable:
    w = m.omega

    def rhs(t: float, y) -> list[float]:
        counter.calls += 1
        phi_tt, x_tt, moment, _, _, power, _, _, _ = dyn(t, y)
        return [y[2], y[3], phi_tt, x_tt, moment * w, power]

    return rhs


def _make_jacobian(m: _Mechanism, rhs: Callable) -> Callable:
    """Forward-difference Jacobian for the implicit methods.

    Only the four mechanical columns are differenced, with steps ``FD_STEP *
    max(|y_j|, scale_j)`` on the scales (1 rad, l, omega, r omega); the quadrature
    columns are exactly zero.  (SciPy's own ``num_jac`` keeps enlarging its step on
    those columns, whose differences stay zero, until it overflows.)
    """
    scales = (1.0, m.l, m.omega, m.r * m.omega)

    def jac(t: float, y) -> np.ndarray:
        f0 = np.asarray(rhs(t, y))
        out = np.zeros((_N_STATE, _N_STATE))
        for j in range(_N_MECHANICAL):
            h = FD_STEP * max(abs(y[j]), scales[j])
            yh = np.array(y, dtype=float)
            yh[j] += h
            out[:, j] = (np.asarray(rhs(t, yh)) - f0) / h
        return out

    return jac


# --------------------------------------------------------------------------------------
# events and phases
# --------------------------------------------------------------------------------------
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


# --------------------------------------------------------------------------------------
# output
# --------------------------------------------------------------------------------------
def _output_times(t_end: float, output_step: float) -> np.ndarray:
    n = int(math.floor(t_end / output_step * (1.0 + GRID_SLACK)))
    return np.minimum(np.arange(n + 1) * output_step, t_end)


def _energies(m: _Mechanism, t: float, y) -> tuple[float, float]:
    """Kinetic and potential energy of the three bodies [J]."""
    theta, phi, phi_t, x_t = m.omega * t, y[0], y[2], y[3]
    v_g2 = (m.r * m.omega) ** 2 + (m.l * phi_t / 2.0) ** 2 + m.r * m.l * m.omega * phi_t * math.cos(theta - phi)
    kinetic = 0.5 * (m.j_o * m.omega**2 + m.m_r * v_g2 + m.i_r * phi_t**2 + m.m_s * x_t**2)
    g_y = m.r * math.sin(theta) + m.l / 2.0 * math.sin(phi)
    potential = m.g * (m.m_c * m.r / 2.0 * math.sin(theta) + m.m_r * g_y)
    return kinetic, potential


def _sample(m: _Mechanism, laws: Laws, phases: list[_Phase], times: np.ndarray) -> tuple[dict, dict]:
    """Columns and energies on ``times``, each point from the dense output of its own phase."""
    starts = np.array([ph.t_start for ph in phases])
    owner = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(phases) - 1)
    rows, energy_rows = [], []
    for k, phase in enumerate(phases):
        ts = times[owner == k]
        if len(ts) == 0:
            continue
        dyn = _make_dynamics(m, laws, phase.v0)
        ys = phase.sol(ts)
        for j, t in enumerate(ts):
            y = ys[:, j]
            phi_tt, x_tt, moment, f_n, f_t, _, ex, ey, delta = dyn(float(t), y)
            rows.append((t, y[1], y[3], x_tt, math.hypot(f_n, f_t), moment, ex, ey, delta,
                         0.0 if phase.v0 is None else 1.0))
            energy_rows.append((t, *_energies(m, float(t), y), y[4], y[5]))
    table = np.array(rows).reshape(-1, 10)
    columns = {"time": table[:, 0], "crank_angle": np.degrees(m.omega * table[:, 0])}
    columns.update(zip(COLUMNS[2:], table[:, 1:].T))
    energy = dict(zip(ENERGY_COLUMNS, np.array(energy_rows).reshape(-1, 5).T))
    return columns, energy


# --------------------------------------------------------------------------------------
# ideal mechanism
# --------------------------------------------------------------------------------------
def ideal_kinematics(params: SliderCrankParams, t) -> dict[str, np.ndarray]:
    """Closed-form ideal slider-crank (ideal revolute joint at B, clearance 0).

    ``sin phi = -(r/l) sin theta``, ``x = r cos theta + l cos phi =
    r cos theta + sqrt(l^2 - r^2 sin^2 theta)``; differentiating
    ``l sin phi = -r sin theta`` twice (``theta_t = omega``, ``theta_tt = 0``):
    ``phi_t = -r omega cos theta / (l cos phi)``,
    ``phi_tt = (r omega^2 sin theta + l phi_t^2 sin phi) / (l cos phi)``,
    ``x_t = -r omega sin theta - l phi_t sin phi``,
    ``x_tt = -r omega^2 cos theta - l (phi_tt sin phi + phi_t^2 cos phi)``.

    Crank moment by the energy balance ``M omega = d(T + V)/dt`` with
    ``dT/dt = m_r v_G . a_G + I_r phi_t phi_tt + m_s x_t x_tt`` (the crank's own kinetic
    energy is constant) and ``dV/dt = m_r g v_G,y + m_c g (r/2) omega cos theta``.

    ``contact_force`` is the magnitude of the ideal joint's force ``R`` on the rod end:
    ``R_x = -m_s x_tt`` (the slider's equation) and ``R_y`` from the rod's moment balance
    about A, ``l (cos phi R_y - sin phi R_x) = I_r phi_tt + m_r (G - A) x a_G +
    m_r g (G - A)_x``.  ``ecc_x``, ``ecc_y`` and ``penetration`` are 0; ``in_contact`` is
    1 (the ideal joint always carries its force).

    Parameters
    ----------
    params : SliderCrankParams
    t : array_like, shape (n,)
        Times [s].

    Returns
    -------
    dict of str to ndarray, shape (n,)
        The columns of :data:`COLUMNS`.
    """
    m = _mechanism(params)
    t = np.asarray(t, dtype=float)
    theta = m.omega * t
    st, ct = np.sin(theta), np.cos(theta)
    sp = -m.r / m.l * st
    cp = np.sqrt(1.0 - sp * sp)
    phi_t = -m.r * m.omega * ct / (m.l * cp)
    phi_tt = (m.r * m.omega**2 * st + m.l * phi_t**2 * sp) / (m.l * cp)
    x = m.r * ct + m.l * cp
    x_t = -m.r * m.omega * st - m.l * phi_t * sp
    x_tt = -m.r * m.omega**2 * ct - m.l * (phi_tt * sp + phi_t**2 * cp)
    # rod centre of mass: G - A = (l/2)(cos phi, sin phi)
    h = m.l / 2.0
    vg_x, vg_y = -m.r * m.omega * st - h * phi_t * sp, m.r * m.omega * ct + h * phi_t * cp
    ag_x = -m.r * m.omega**2 * ct - h * (phi_tt * sp + phi_t**2 * cp)
    ag_y = -m.r * m.omega**2 * st + h * (phi_tt * cp - phi_t**2 * sp)
    power = (m.m_r * (vg_x * ag_x + vg_y * ag_y) + m.i_r * phi_t * phi_tt + m.m_s * x_t * x_tt
             + m.g * (m.m_r * vg_y + m.m_c * m.r / 2.0 * m.omega * ct))
    r_x = -m.m_s * x_tt
    moment_a = m.i_r * phi_tt + m.m_r * h * (cp * ag_y - sp * ag_x) + m.m_r * m.g * h * cp
    r_y = (moment_a / m.l + sp * r_x) / cp
    zeros = np.zeros_like(t)
    return {"time": t, "crank_angle": np.degrees(theta), "slider_x": x, "slider_v": x_t, "slider_a": x_tt,
            "contact_force": np.hypot(r_x, r_y), "crank_moment": power / m.omega, "ecc_x": zeros,
            "ecc_y": zeros.copy(), "penetration": zeros.copy(), "in_contact": np.ones_like(t)}


# --------------------------------------------------------------------------------------
# public driver
# --------------------------------------------------------------------------------------
def _check(method: str, t_end: float, rtol: float, atol: float, max_step: float | None, output_step: float) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown `method` {method!r}; known: {', '.join(METHODS)}")
    for name, value in (("t_end", t_end), ("rtol", rtol), ("atol", atol), ("output_step", output_step)):
        if not value > 0.0:
            raise ValueError(f"`{name}` must be positive, got {value}")
    if max_step is not None and not max_step > 0.0:
        raise ValueError(f"`max_step` must be positive or None, got {max_step}")


def simulate(params: SliderCrankParams, t_end: float | None = None, method: str = "DOP853", rtol: float = 1e-10,
             atol: float = 1e-13, max_step: float | None = None, output_step: float = 1e-5) -> Result:
    """Simulate the slider-crank with its clearance joint (or the ideal one) by SciPy.

    Parameters
    ----------
    params : SliderCrankParams
        Mechanism and joint (attribute access only); ``params.ideal`` selects the closed
        form of :func:`ideal_kinematics`.
    t_end : float, optional
        End time [s]; default ``params.end_time`` (its revolutions at its crank speed).
    method : str
        A :func:`scipy.integrate.solve_ivp` method of :data:`METHODS`.
    rtol, atol : float
        Tolerances; ``atol`` meets angles [rad], positions [m] (penetrations of order
        1e-6 m), velocities and the energy integrals [J].
    max_step : float, optional
        Largest step [s]; default unbounded.
    output_step : float
        Interval of the output grid [s]; values come from each phase's dense output.

    Returns
    -------
    Result
    """
    t_end = params.end_time if t_end is None else t_end
    _check(method, t_end, rtol, atol, max_step, output_step)
    times = _output_times(t_end, output_step)
    if params.ideal:
        start = time.perf_counter()
        columns = ideal_kinematics(params, times)
        return Result(columns, np.array([]), 0, time.perf_counter() - start, 0, True, "closed form (ideal joint)")
    m, laws = _mechanism(params), _laws(params)
    options = {"method": method, "rtol": rtol, "atol": atol, "max_step": np.inf if max_step is None else max_step}
    start = time.perf_counter()
    phases, onsets, n_rhs, success, message = _integrate(m, laws, t_end, options)
    wall_time = time.perf_counter() - start
    if not success:
        times = times[times <= phases[-1].t_stop]
    columns, energy = _sample(m, laws, phases, times)
    return Result(columns, np.array(onsets), len(onsets), wall_time, n_rhs, success, message, energy)


# --------------------------------------------------------------------------------------
# command line
# --------------------------------------------------------------------------------------
def _parser() -> argparse.ArgumentParser:
    p = SliderCrankParams.paper()
    ap = argparse.ArgumentParser(prog="python -m validation.reference.slider_crank",
                                 description="SciPy reference run of the paper's slider-crank (docs/physics.md section 6.2).")
    ap.add_argument("--law", default=p.law, help="contact law (default %(default)s)")
    ap.add_argument("--cr", type=float, default=p.cr, help="coefficient of restitution (default %(default)s)")
    ap.add_argument("--friction", default=p.friction, help="none, coulomb:MU or paper (default %(default)s)")
    ap.add_argument("--journal", default=p.journal_material, help="journal material (default %(default)s)")
    ap.add_argument("--clearance", type=float, default=p.clearance, help="radial clearance [m] (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=p.revolutions, help="crank revolutions (default %(default)s)")
    ap.add_argument("--ideal", action="store_true", help="ideal joint at B (closed form)")
    ap.add_argument("--method", default="DOP853", choices=METHODS, help="solve_ivp method (default %(default)s)")
    ap.add_argument("--rtol", type=float, default=1e-10, help="relative tolerance (default %(default)s)")
    ap.add_argument("--atol", type=float, default=1e-13, help="absolute tolerance (default %(default)s)")
    ap.add_argument("--max-step", type=float, default=None, help="largest step [s] (default unbounded)")
    ap.add_argument("--output-step", type=float, default=1e-5, help="output interval [s] (default %(default)s)")
    ap.add_argument("--csv", metavar="FILE", help="write the columns to FILE")
    return ap


def _write_csv(path: str, columns: dict[str, np.ndarray]) -> None:
    """:data:`COLUMNS` as CSV (every value a float, written as Python writes it; CRLF line ends)."""
    import pandas as pd

    table = pd.DataFrame({k: np.asarray(columns[k], dtype=float) for k in COLUMNS})
    table.to_csv(path, index=False, na_rep="nan", lineterminator="\r\n")


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        params = replace(SliderCrankParams.paper(), law=args.law, cr=args.cr, friction=args.friction,
                         journal_material=args.journal, clearance=args.clearance, revolutions=args.revolutions,
                         ideal=args.ideal)
        result = simulate(params, method=args.method, rtol=args.rtol, atol=args.atol, max_step=args.max_step,
                          output_step=args.output_step)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    cols = result.columns
    print(f"slider-crank reference: {params.law}, cr = {params.cr}, friction {params.friction}, "
          f"c = {params.clearance:g} m, {params.revolutions:g} revolutions, {args.method} rtol {args.rtol:g}")
    print(f"  peak contact force  {cols['contact_force'].max():.1f} N")
    print(f"  peak |crank moment| {np.abs(cols['crank_moment']).max():.2f} N m")
    print(f"  impacts             {result.n_impacts}")
    print(f"  rhs evaluations     {result.n_rhs}")
    print(f"  wall time           {result.wall_time:.2f} s")
    if args.csv:
        _write_csv(args.csv, cols)
        print(f"wrote {args.csv}")
    if not result.success:
        print(f"error: {result.message}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
