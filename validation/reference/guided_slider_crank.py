"""The slider-crank with a slider of play in its guide (Flores, Leine, Glocker 2010), by SciPy.

The benchmark of P. Flores, R. Leine, C. Glocker, "Modeling and analysis of planar rigid
multibody systems with translational clearance joints based on the non-smooth dynamics
approach", Multibody Syst. Dyn. 23 (2010) 165-190, section 4, with compliant corners in
place of its rigid impacts: the slider is a rectangle ``2a x 2b`` whose four corners meet
the guide's two walls at ``y = +-(b + c)``.  Each corner is a contact pair with each wall
(eight pairs; the paper keeps the four that can touch at small slider angles, the others
never close here), each with the normal law ``F_N = F_e(delta) (1 + D delta_dot / v0)``
and Coulomb friction along the wall.

What it shares with exuclear is the laws only (:func:`exuclear.contact.damped_normal_force`,
:func:`exuclear.contact.damping_model`, :func:`exuclear.friction.friction_law`); the
kinematics, the equations of motion (Lagrange, the three angles as coordinates) and the
integration (:func:`scipy.integrate.solve_ivp`, one phase per change of the set of closed
pairs, each pair's ``v0`` the exact penetration rate at its onset) are its own.

Coordinates: ``q = (theta1, theta2, theta3)``, the crank's, rod's and slider's angles from
+X; the crank turns about the origin, the slider's centre is the rod's end ``B`` and the
guide's centre line is the X axis.  Gravity acts along -Y.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from exuclear.contact import damped_normal_force, damping_model
from exuclear.friction import friction_law

#: The pairs: corner signs ``(s_x, s_y)`` of the slider's body-fixed corner ``(s_x a, s_y b)``
#: and the wall ``w`` (+1 the upper wall at ``y = b + c``, -1 the lower one), corner by corner.
CORNERS = ((-1, 1), (1, 1), (1, -1), (-1, -1))
PAIRS = tuple((k, wall) for k in range(len(CORNERS)) for wall in (1, -1))
#: Safety limit on the number of phases; a run needing more (a pair chattering at its
#: release) stops with a message instead of looping.
MAX_PHASES = 200_000
#: Samples of a pair's penetration that bracket an onset hidden inside one step.
GRAZE_SAMPLES = 32
#: First step [s] of a phase that begins with an onset: far below any corner's contact
#: period (the slider's rocking on a corner is the fastest mode, some 1e-5 s at the
#: benchmark's stiffness); DOP853 grows it up to tenfold a step.  A longer first step
#: overflows in its trial stages and is rejected only after that.
ONSET_FIRST_STEP = 1e-9
#: Brent tolerance for a hidden onset: round-off in time, as solve_ivp's events.
ROOT_TOL = 4 * np.finfo(float).eps


@dataclass(frozen=True)
class GuidedSliderCrank:
    """Parameters of the benchmark (SI units); :meth:`benchmark` gives the paper's values.

    Parameters
    ----------
    crank_length, rod_length : float
        ``l1``, ``l2`` [m]; centres of mass at the link midpoints.
    slider_length, slider_height : float
        ``2a``, ``2b`` [m]; the slider's centre of mass at its centre, the rod's end.
    clearance : float
        ``c`` per side [m]: the guide is ``slider_height + 2 c`` wide.
    crank_mass, rod_mass, slider_mass : float
        [kg].
    crank_inertia, rod_inertia, slider_inertia : float
        About the centres of mass [kg m^2].
    gravity : float
        Along -Y [m/s^2].
    crank_speed, rod_speed : float
        Initial angular speeds [rad/s]; all angles start at 0 (crank and rod along +X, the
        slider centred and aligned); the crank is not driven.
    stiffness, exponent : float
        A corner's elastic force ``K delta^n`` [N/m^n].
    damping, cr : str, float
        A damping model of :data:`exuclear.contact.DAMPING_MODELS` and its restitution.
    friction : str
        As :func:`exuclear.friction.friction_law` takes it.
    v_min : float
        Floor of the onset velocity in the damping term [m/s].
    """

    crank_length: float
    rod_length: float
    slider_length: float
    slider_height: float
    clearance: float
    crank_mass: float
    rod_mass: float
    slider_mass: float
    crank_inertia: float
    rod_inertia: float
    slider_inertia: float
    gravity: float
    crank_speed: float
    rod_speed: float
    stiffness: float
    exponent: float
    damping: str
    cr: float
    friction: str
    v_min: float

    @classmethod
    def benchmark(cls, **changes: object) -> GuidedSliderCrank:
        """Flores, Leine, Glocker (2010) section 4: crank 0.153 m, rod 0.306 m, slider
        0.10 x 0.05 m in a guide with 1 mm clearance per side, masses 0.038, 0.038, 0.076 kg,
        inertias 7.4e-5, 5.9e-4, 2.7e-6 kg m^2, gravity, restitution 0.4, friction 0.01,
        the crank at 150 rad/s and the rod at -75 rad/s (the ideal mechanism's at theta = 0).

        The paper's impacts are rigid; the corners' compliance is this model's own:
        ``K = 1e10 N/m^1.5`` (a steel corner's order of magnitude: some 40 um of penetration
        at 1 m/s against the slider's mass) with the Carvalho-Martins damping, whose
        restitution is exactly ``cr`` for a free mass.
        """
        base = cls(crank_length=0.153, rod_length=0.306, slider_length=0.10, slider_height=0.05, clearance=1e-3,
                   crank_mass=0.038, rod_mass=0.038, slider_mass=0.076, crank_inertia=7.4e-5, rod_inertia=5.9e-4,
                   slider_inertia=2.7e-6, gravity=9.81, crank_speed=150.0, rod_speed=-75.0, stiffness=1e10,
                   exponent=1.5, damping="carvalho-martins", cr=0.4, friction="coulomb:0.01", v_min=1e-4)
        return replace(base, **changes)


class Result(NamedTuple):
    """Output of :func:`simulate`.

    Attributes
    ----------
    time : ndarray, shape (n,)
        The output grid [s].
    q, u : ndarray, shape (n, 3)
        The angles [rad] and angular speeds [rad/s] of crank, rod and slider.
    slider : ndarray, shape (n, 2)
        The slider centre's position ``(x, y)`` [m]; ``y / c`` is its place in the guide.
    penetration, normal_force : ndarray, shape (n, 8)
        Each pair's penetration [m] (negative: its gap) and normal force [N], pairs in
        :data:`PAIRS` order.
    energy : ndarray, shape (n,)
        Kinetic plus gravitational plus the corners' elastic energy [J]; conserved with
        ``damping="none"`` and no friction.
    impacts : list of (float, int, float)
        ``(onset time [s], pair index, v0 [m/s])`` per onset.
    success : bool
    message : str
    wall_time : float
        Integration time [s].
    """

    time: np.ndarray
    q: np.ndarray
    u: np.ndarray
    slider: np.ndarray
    penetration: np.ndarray
    normal_force: np.ndarray
    energy: np.ndarray
    impacts: list
    success: bool
    message: str
    wall_time: float


class _Model(NamedTuple):
    """The numbers the right-hand side reads, as plain floats."""

    l1: float
    l2: float
    a: float
    b: float
    wall: float       # b + c: the walls' distance from the centre line
    m1: float
    m2: float
    m3: float
    J1: float
    J2: float
    J3: float
    g: float
    K: float
    n: float
    D: float
    v_min: float
    mu: Callable[[float], float]


def _model(p: GuidedSliderCrank) -> _Model:
    for name in ("crank_length", "rod_length", "slider_length", "slider_height", "clearance", "crank_mass",
                 "rod_mass", "slider_mass", "crank_inertia", "rod_inertia", "slider_inertia", "stiffness",
                 "exponent", "v_min"):
        if not getattr(p, name) > 0.0:
            raise ValueError(f"`{name}` must be positive, got {getattr(p, name)}")
    a, b = p.slider_length / 2.0, p.slider_height / 2.0
    return _Model(p.crank_length, p.rod_length, a, b, b + p.clearance, p.crank_mass, p.rod_mass, p.slider_mass,
                  p.crank_inertia, p.rod_inertia, p.slider_inertia, p.gravity, p.stiffness, p.exponent,
                  damping_model(p.damping, p.cr).factor, p.v_min, friction_law(p.friction).coefficient)


# ======================================================================================
# kinematics: the points and their Jacobians in q
# ======================================================================================
def _corner(m: _Model, q, u, k: int) -> tuple[float, float, float, float, float, float]:
    """Corner ``k``'s position ``(x, y)``, velocity ``(vx, vy)`` and the lever ``(-r_y, r_x)``
    of the slider's rotation on it (``r = R(theta3) (s_x a, s_y b)``): its Jacobian's third
    column."""
    th1, th2, th3 = q
    sx, sy = CORNERS[k]
    c3, s3 = math.cos(th3), math.sin(th3)
    rx, ry = sx * m.a * c3 - sy * m.b * s3, sx * m.a * s3 + sy * m.b * c3
    xB = m.l1 * math.cos(th1) + m.l2 * math.cos(th2)
    yB = m.l1 * math.sin(th1) + m.l2 * math.sin(th2)
    vxB = -m.l1 * math.sin(th1) * u[0] - m.l2 * math.sin(th2) * u[1]
    vyB = m.l1 * math.cos(th1) * u[0] + m.l2 * math.cos(th2) * u[1]
    return xB + rx, yB + ry, vxB - ry * u[2], vyB + rx * u[2], -ry, rx


def _pair_gap(m: _Model, q, u, pair: int) -> tuple[float, float]:
    """Penetration ``delta = w y_k - (b + c)`` and its rate ``w vy_k`` of a pair (corner
    ``k``, wall ``w``)."""
    k, wall = PAIRS[pair]
    _, y, _, vy, _, _ = _corner(m, q, u, k)
    return wall * y - m.wall, wall * vy


#: The centres of mass as ``w1 l1 e1 + w2 l2 e2`` (``e_i`` the unit vector at ``theta_i``):
#: (mass field, w1, w2) of the crank, the rod and the slider (the rod's end B).
_CENTRES = (("m1", 0.5, 0.0), ("m2", 1.0, 0.5), ("m3", 1.0, 1.0))


def mass_matrix(m: _Model, q) -> np.ndarray:
    """``M = sum_i m_i J_i^T J_i + diag(J1, J2, J3)`` from the centres of mass' Jacobians.

    A centre ``w1 l1 e1 + w2 l2 e2`` has the Jacobian ``[w1 d1, w2 d2, 0]`` with
    ``d_i = l_i e_i'``, so ``M11 = sum m w1^2 l1^2``, ``M12 = sum m w1 w2 d1 . d2`` and
    ``M22 = sum m w2^2 l2^2``; the slider turns alone (``M33 = J3``).  The test compares it
    with the closed form of Flores, Leine, Glocker (2010) eqs. (90)-(94).
    """
    th1, th2, _ = q
    d12 = m.l1 * m.l2 * (math.sin(th1) * math.sin(th2) + math.cos(th1) * math.cos(th2))
    M11 = m.J1 + sum(getattr(m, mass) * w1 * w1 for mass, w1, _ in _CENTRES) * m.l1 ** 2
    M12 = sum(getattr(m, mass) * w1 * w2 for mass, w1, w2 in _CENTRES) * d12
    M22 = m.J2 + sum(getattr(m, mass) * w2 * w2 for mass, _, w2 in _CENTRES) * m.l2 ** 2
    return np.array([[M11, M12, 0.0], [M12, M22, 0.0], [0.0, 0.0, m.J3]])


def _bias(m: _Model, q, u) -> np.ndarray:
    """``-sum_i m_i J_i^T (dJ_i/dt u) + Q_gravity``: the centripetal terms and gravity."""
    th1, th2, _ = q
    c1, s1, c2, s2 = math.cos(th1), math.sin(th1), math.cos(th2), math.sin(th2)
    d1, d2 = (-s1 * m.l1, c1 * m.l1), (-s2 * m.l2, c2 * m.l2)
    a1 = (-c1 * m.l1 * u[0] ** 2, -s1 * m.l1 * u[0] ** 2)   # dJ/dt u of l1 e1
    a2 = (-c2 * m.l2 * u[1] ** 2, -s2 * m.l2 * u[1] ** 2)   # of l2 e2
    # acceleration bias and gravity of each centre of mass: (mass, weights of l1 e1, l2 e2)
    f = np.zeros(3)
    for name, w1, w2 in _CENTRES:
        mass = getattr(m, name)
        fx = -mass * (w1 * a1[0] + w2 * a2[0])
        fy = -mass * (w1 * a1[1] + w2 * a2[1]) - mass * m.g
        f[0] += w1 * (d1[0] * fx + d1[1] * fy)
        f[1] += w2 * (d2[0] * fx + d2[1] * fy)
    return f


# ======================================================================================
# the corners' loads and the right-hand side
# ======================================================================================
def _pair_loads(m: _Model, q, u, pair: int, v0: float | None) -> tuple[np.ndarray, float]:
    """Generalized force of one pair and its normal force [N]; zero while the pair is open
    (``v0`` None).  The wall pushes the corner along ``-w Y`` by ``F_N`` and along X by
    ``-mu(vx) F_N`` (friction against the corner's slip on the fixed wall)."""
    if v0 is None:
        return np.zeros(3), 0.0
    k, wall = PAIRS[pair]
    _, y, vx, vy, lx, ly = _corner(m, q, u, k)
    delta = wall * y - m.wall
    f_n = damped_normal_force(m.K * max(delta, 0.0) ** m.n, m.D, m.v_min, wall * vy, v0)
    fx, fy = -m.mu(vx) * f_n, -wall * f_n
    th1, th2, _ = q
    return np.array([m.l1 * (-math.sin(th1) * fx + math.cos(th1) * fy),
                     m.l2 * (-math.sin(th2) * fx + math.cos(th2) * fy),
                     lx * fx + ly * fy]), f_n


def _rhs(m: _Model, v0s: tuple) -> Callable:
    def rhs(t: float, y) -> np.ndarray:
        q, u = y[:3], y[3:]
        f = _bias(m, q, u)
        for pair, v0 in enumerate(v0s):
            if v0 is not None:
                f += _pair_loads(m, q, u, pair, v0)[0]
        M = mass_matrix(m, q)
        det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]  # the crank-rod block by Cramer's rule
        return np.array([u[0], u[1], u[2], (M[1, 1] * f[0] - M[0, 1] * f[1]) / det,
                         (M[0, 0] * f[1] - M[1, 0] * f[0]) / det, f[2] / M[2, 2]])

    return rhs


def energy(m: _Model, y) -> float:
    """Kinetic + gravitational + the closed pairs' elastic energy ``K delta^(n+1)/(n+1)`` [J]."""
    q, u = y[:3], y[3:]
    th1, th2, _ = q
    kinetic = 0.5 * u @ mass_matrix(m, q) @ u
    potential = m.g * (m.m1 * 0.5 * m.l1 * math.sin(th1) + m.m2 * (m.l1 * math.sin(th1) + 0.5 * m.l2 * math.sin(th2))
                       + m.m3 * (m.l1 * math.sin(th1) + m.l2 * math.sin(th2)))
    elastic = sum(m.K * max(_pair_gap(m, q, u, p)[0], 0.0) ** (m.n + 1) / (m.n + 1) for p in range(len(PAIRS)))
    return float(kinetic + potential + elastic)


# ======================================================================================
# phases: one per set of closed pairs
# ======================================================================================
def _events(m: _Model, v0s: tuple) -> list[Callable]:
    """A terminal event per pair: an open pair's onset ``min(delta, delta_dot)`` up through
    0, a closed pair's release ``max(delta, delta_dot)`` down through 0 (these equal
    ``delta`` at the crossing and keep a return within the first step from being lost);
    then a recorded apex ``delta_dot`` down through 0 per open pair, to find a graze that
    opens and closes inside one step."""
    events = []
    for pair, v0 in enumerate(v0s):
        def switch(t, y, pair=pair, closed=v0 is not None):
            delta, rate = _pair_gap(m, y[:3], y[3:], pair)
            return max(delta, rate) if closed else min(delta, rate)

        switch.terminal, switch.direction = True, (-1.0 if v0 is not None else 1.0)
        events.append(switch)
    for pair in range(len(PAIRS)):
        def apex(t, y, pair=pair):
            return _pair_gap(m, y[:3], y[3:], pair)[1]

        apex.terminal, apex.direction = False, -1.0
        events.append(apex)
    return events


def _hidden_onset(m: _Model, sol, v0s: tuple, t_stop: float) -> tuple[float, int] | None:
    """The earliest onset of an open pair hidden inside one step before ``t_stop``: an apex
    with ``delta > 0``, its upward crossing bracketed on the dense output and refined."""
    found = None
    for pair in range(len(PAIRS)):
        if v0s[pair] is not None:
            continue
        for t_apex in sol.t_events[len(PAIRS) + pair]:
            if t_apex >= t_stop:
                break
            y = sol.sol(t_apex)
            if _pair_gap(m, y[:3], y[3:], pair)[0] <= 0.0:
                continue

            def delta_at(t: float, pair=pair) -> float:
                y = sol.sol(t)
                return _pair_gap(m, y[:3], y[3:], pair)[0]

            k = max(int(np.searchsorted(sol.t, t_apex)) - 1, 0)
            ts = np.linspace(float(sol.t[k]), float(t_apex), GRAZE_SAMPLES)
            below = np.flatnonzero(np.array([delta_at(t) for t in ts]) <= 0.0)
            t_on = float(ts[0]) if len(below) == 0 else brentq(delta_at, ts[below[-1]], ts[below[-1] + 1],
                                                               xtol=ROOT_TOL, rtol=ROOT_TOL)
            if found is None or t_on < found[0]:
                found = (t_on, pair)
            break
    return found


def _switch_at(m: _Model, y, v0s: tuple) -> tuple[tuple, list[int]]:
    """Close every open pair that already penetrates and approaches at a phase's start, and
    open every closed pair that is out and leaving: pairs that reach the switch in the same
    instant as the event that ended the phase (the two upper corners of an aligned slider)
    sit on the switch at round-off, where no sign change is left for an event to see.
    Returns the new ``v0`` per pair and the pairs closed here."""
    new, closed = list(v0s), []
    for pair, v0 in enumerate(v0s):
        delta, rate = _pair_gap(m, y[:3], y[3:], pair)
        if v0 is None and delta >= 0.0 and rate > 0.0:
            new[pair] = rate
            closed.append(pair)
        elif v0 is not None and delta <= 0.0 and rate < 0.0:
            new[pair] = None
    return tuple(new), closed


def initial_state(p: GuidedSliderCrank) -> np.ndarray:
    """All angles 0, the given crank and rod speeds, the slider not turning."""
    return np.array([0.0, 0.0, 0.0, p.crank_speed, p.rod_speed, 0.0])


def simulate(p: GuidedSliderCrank, t_end: float, *, rtol: float = 1e-10, atol: float = 1e-12,
             output_step: float = 1e-5, y0: np.ndarray | None = None) -> Result:
    """Integrate the benchmark from :func:`initial_state` (or ``y0``) to ``t_end`` [s].

    DOP853 at ``rtol``/``atol`` (angles, speeds and penetrations of some 1e-5 m), one phase
    per set of closed pairs; the outputs are sampled every ``output_step`` [s] from each
    phase's dense output.
    """
    for name, value in (("t_end", t_end), ("rtol", rtol), ("atol", atol), ("output_step", output_step)):
        if not value > 0.0:
            raise ValueError(f"`{name}` must be positive, got {value}")
    m = _model(p)
    y = initial_state(p) if y0 is None else np.asarray(y0, dtype=float)
    grid = np.arange(0.0, t_end * (1.0 + 1e-12), output_step)
    v0s: tuple = (None,) * len(PAIRS)
    t, impacts, phases, message, success = 0.0, [], [], "success", True
    first_step = None  # each phase starts with the last step of the one before: solve_ivp's own first
    start = time.perf_counter()  # guess ignores the contact's time scale and overflows in trial steps
    while t < t_end:
        v0s, closed = _switch_at(m, y, v0s)
        impacts += [(t, pair, v0s[pair]) for pair in closed]
        if closed:
            first_step = ONSET_FIRST_STEP
        if len(phases) >= MAX_PHASES:
            success, message = False, f"more than {MAX_PHASES} phases before t = {t:.6g} s (a pair chattering)"
            break
        sol = solve_ivp(_rhs(m, v0s), (t, t_end), y, method="DOP853", rtol=rtol, atol=atol,
                        events=_events(m, v0s), dense_output=True,
                        first_step=None if first_step is None else min(first_step, t_end - t))
        if sol.status == -1:
            success, message = False, f"solver failed at t = {sol.t[-1]:.6g} s: {sol.message}"
            phases.append((t, float(sol.t[-1]), sol.sol, v0s))
            break
        hits = [(float(sol.t_events[i][0]), i) for i in range(len(PAIRS)) if len(sol.t_events[i])]
        t_stop, switched = min(hits) if hits else (float(sol.t[-1]), None)
        hidden = _hidden_onset(m, sol, v0s, t_stop)
        if hidden is not None:
            t_stop, switched = hidden
        phases.append((t, t_stop, sol.sol, v0s))
        if len(sol.t) > 1 and sol.t[-1] > sol.t[-2]:
            first_step = float(sol.t[-1] - sol.t[-2])
        t, y = t_stop, sol.sol(t_stop)
        if switched is not None and t < t_end:
            rate = _pair_gap(m, y[:3], y[3:], switched)[1]
            closing = v0s[switched] is None
            v0s = tuple((rate if closing else None) if i == switched else v for i, v in enumerate(v0s))
            if closing:
                impacts.append((t, switched, rate))
                first_step = ONSET_FIRST_STEP
    wall_time = time.perf_counter() - start
    grid = grid[grid <= phases[-1][1] * (1.0 + 1e-12)]
    return _sample(m, p, phases, grid, impacts, success, message, wall_time)


def _sample(m: _Model, p: GuidedSliderCrank, phases: list, grid: np.ndarray, impacts: list, success: bool,
            message: str, wall_time: float) -> Result:
    n = len(grid)
    q, u = np.zeros((n, 3)), np.zeros((n, 3))
    slider, pen, force, e = np.zeros((n, 2)), np.zeros((n, len(PAIRS))), np.zeros((n, len(PAIRS))), np.zeros(n)
    j = 0
    for i, t in enumerate(grid):
        while j < len(phases) - 1 and t > phases[j][1]:
            j += 1
        y = phases[j][2](t)
        q[i], u[i] = y[:3], y[3:]
        slider[i] = (m.l1 * math.cos(y[0]) + m.l2 * math.cos(y[1]), m.l1 * math.sin(y[0]) + m.l2 * math.sin(y[1]))
        for pair in range(len(PAIRS)):
            pen[i, pair] = _pair_gap(m, y[:3], y[3:], pair)[0]
            force[i, pair] = _pair_loads(m, y[:3], y[3:], pair, phases[j][3][pair])[1]
        e[i] = energy(m, y)
    return Result(grid, q, u, slider, pen, force, e, impacts, success, message, wall_time)


# ======================================================================================
# command line: the benchmark's figures and the table over the corners' stiffness
# ======================================================================================
#: The benchmark's span [s]: two crank turns and a little (the crank, not driven, slows
#: from 150 rad/s to some 70 rad/s and back within a turn).
BENCHMARK_END_TIME = 0.15


def _summary(p: GuidedSliderCrank, r: Result) -> dict[str, float]:
    """What the papers read off a run: the slider's excursions in the guide, its tilt, the
    crank's speed at the end, the impacts and the largest corner force."""
    return {"K [N/m^n]": p.stiffness, "impacts": len(r.impacts), "y/c min": r.slider[:, 1].min() / p.clearance,
            "y/c max": r.slider[:, 1].max() / p.clearance, "|theta3| max [deg]": math.degrees(np.abs(r.q[:, 2]).max()),
            "crank speed at end [rad/s]": r.u[-1, 0], "peak corner force [N]": r.normal_force.max(),
            "largest penetration [um]": 1e6 * r.penetration.max(), "wall time [s]": r.wall_time}


def _figure(p: GuidedSliderCrank, r: Result, path) -> None:
    """The slider's path in the guide (x/l1 against y/c), the crank's speed, the corners'
    gaps and forces: the panels of Flores, Leine, Glocker (2010) figs. 9-12."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    ax[0, 0].plot(r.slider[:, 0] / p.crank_length, r.slider[:, 1] / p.clearance, lw=0.8)
    ax[0, 0].set(xlabel="x / l1", ylabel="y / c", title="slider centre in the guide")
    ax[0, 1].plot(r.time, r.u[:, 0], lw=0.8)
    ax[0, 1].set(xlabel="t [s]", ylabel="crank speed [rad/s]")
    for j, (k, wall) in enumerate(PAIRS):
        if r.normal_force[:, j].max() > 0.0:
            label = f"corner {k + 1}, {'upper' if wall > 0 else 'lower'} wall"
            ax[1, 0].plot(r.time, -1e3 * r.penetration[:, j], lw=0.8, label=label)
            ax[1, 1].plot(r.time, r.normal_force[:, j], lw=0.8, label=label)
    ax[1, 0].set(xlabel="t [s]", ylabel="gap [mm]", ylim=(-0.1, 2.2 * 1e3 * p.clearance))
    ax[1, 1].set(xlabel="t [s]", ylabel="normal force [N]")
    ax[1, 1].legend(fontsize=7)
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    import argparse
    import pathlib
    import sys

    import pandas as pd

    ap = argparse.ArgumentParser(prog="python -m validation.reference.guided_slider_crank",
                                 description="SciPy reference of the Flores-Leine-Glocker slider-crank with "
                                             "compliant corners: the benchmark's figure and a table over K.")
    ap.add_argument("--end-time", type=float, default=BENCHMARK_END_TIME, help="[s] (default %(default)s)")
    ap.add_argument("--stiffness", type=float, nargs="+", default=[1e8, 1e9, 1e10, 1e11],
                    help="corner stiffnesses K [N/m^1.5] of the table; the figure is drawn for the last")
    ap.add_argument("--out", default="results/guided_slider_crank_reference", help="folder (default %(default)s)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for K in args.stiffness:
        p = GuidedSliderCrank.benchmark(stiffness=K)
        try:
            r = simulate(p, args.end_time, output_step=1e-5)
        except ValueError as err:
            print(f"error: {err}", file=sys.stderr)
            return 2
        rows.append(_summary(p, r))
        print(f"K = {K:.3g}: {len(r.impacts)} impacts, {r.message}, {r.wall_time:.1f} s", flush=True)
        if not r.success:
            print(f"error: {r.message}", file=sys.stderr)
            return 1
    table = pd.DataFrame(rows)
    table.to_csv(out / "stiffness.csv", index=False)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    try:
        _figure(p, r, out / "benchmark.png")
        print(f"wrote {out / 'benchmark.png'}")
    except ImportError:
        print("matplotlib is not installed: no figure (pip install exuclear[plot])")
    print(f"wrote {out / 'stiffness.csv'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
