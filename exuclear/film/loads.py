"""The film's kinematics and loads, and the blend to metal contact: what every film model shares.

The eccentricity and its rate in the frame of the line of centres (:func:`film_kinematics`,
physics.md eqs. (55)-(56)), the loads a film returns (:class:`FilmLoad`, eqs. (68)-(69)),
the helper quantities of the bearing literature (Sommerfeld number, attitude angle) and
the eccentricity at which the film is evaluated near the wall (:func:`blend_eccentricity`,
eq. (70)).  Pure physics: no exudyn, no state.
"""
from __future__ import annotations

import math
from typing import NamedTuple

from ..checks import check_nonnegative
from ..geometry import BearingGeometry

#: Eccentricity ratio below which the film acts alone (physics.md eq. (70)): the threshold
#: of Flores et al. (2009), h_min = 0.1 c.
EPS_FILM_DEFAULT = 0.9
#: Eccentricity ratio the film's argument approaches at and beyond the wall (eq. (70)):
#: h_min = 0.03 c, a few micrometres for c ~ 0.1 mm, the order of a ground surface's
#: roughness, below which a smooth film means little; the short model's rotation load there
#: is 11 times that at 0.9, finite.
EPS_CAP_DEFAULT = 0.97


# -- helper quantities ---------------------------------------------------------------------
def eccentricity_ratio(ex: float, ey: float, clearance: float) -> float:
    """``eps = |e| / c`` (physics.md eq. (55)); dimensionless."""
    return math.hypot(ex, ey) / clearance


def minimum_film_thickness(eps: float, clearance: float) -> float:
    """``h_min = c (1 - eps)`` [m] (physics.md eq. (55))."""
    return clearance * (1.0 - eps)


def relative_clearance(geometry: BearingGeometry) -> float:
    """``psi = c / R`` with ``R`` the journal radius (physics.md eq. (57))."""
    return geometry.clearance / geometry.journal_radius


def sommerfeld_number(force: float, geometry: BearingGeometry, viscosity: float, omega: float) -> float:
    """``So = F psi^2 / (B D eta |omega|)`` (physics.md eq. (57)); ``D = 2 R``, ``B = L``.

    ``omega`` is the angular velocity the load is carried at (``omega_eff`` of eq. (56)).
    """
    psi = relative_clearance(geometry)
    return force * psi * psi / (geometry.length * 2.0 * geometry.journal_radius * viscosity * abs(omega))


def attitude_angle(ex: float, ey: float, fx: float, fy: float) -> float:
    """Angle ``beta`` [rad] between the load and the line of centres, in ``[0, pi]``.

    The load is what the film carries, ``-F`` with ``F`` the film force on the journal;
    ``beta`` is the angle between ``-F`` and ``e`` (physics.md eq. (57)).
    """
    return math.atan2(abs(ex * fy - ey * fx), -(ex * fx + ey * fy))


# -- the loads a film puts on journal and bearing -----------------------------------------------
class FilmLoad(NamedTuple):
    """What a film law returns (physics.md eqs. (68)-(69)).

    Attributes
    ----------
    fx, fy : float
        Film force on the journal [N], bearing frame; the bearing receives ``-F``.
    torque_journal, torque_bearing : float
        Viscous moments about ``+z`` on journal and bearing [N m], eq. (69).
    f_n, f_t : float
        The force along ``n`` and along the tangent ``t = (n_y, -n_x)`` of physics.md eq. (3)
        [N]; ``f_n < 0`` pushes the journal back towards the centre.
    eps : float
        The journal's eccentricity ratio (:meth:`FilmLaw.blended_load` evaluates the film at
        the blended one of eq. (70)).
    omega_eff : float
        Effective angular velocity of the wedge, eq. (56) [rad/s].
    """

    fx: float
    fy: float
    torque_journal: float
    torque_bearing: float
    f_n: float
    f_t: float
    eps: float
    omega_eff: float


class FilmKinematics(NamedTuple):
    """The journal's motion in the frame of the line of centres (physics.md eq. (56))."""

    eps: float          # eccentricity ratio
    eps_dot: float      # its rate [1/s], > 0 towards the wall
    omega_eff: float    # omega_J + omega_B - 2 dphi/dt [rad/s]
    nx: float           # unit normal n (bearing -> journal)
    ny: float


def film_kinematics(ex: float, ey: float, vx: float, vy: float, omega_journal: float, omega_bearing: float,
                    clearance: float) -> FilmKinematics:
    """``eps``, ``eps_dot``, ``omega_eff`` and ``n`` from ``e`` and ``de/dt`` (eqs. (55)-(56)).

    At ``e = 0`` the normal is taken along ``de/dt`` (the direction the journal leaves
    the centre in, so ``eps_dot = |de/dt| / c``), or ``(1, 0)`` at rest; ``dphi/dt = 0``.
    """
    ecc = math.hypot(ex, ey)
    if ecc > 0.0:
        nx, ny = ex / ecc, ey / ecc
        phi_dot = (ex * vy - ey * vx) / (ecc * ecc)
    else:
        speed = math.hypot(vx, vy)
        nx, ny = (vx / speed, vy / speed) if speed > 0.0 else (1.0, 0.0)
        phi_dot = 0.0
    eps_dot = (nx * vx + ny * vy) / clearance
    return FilmKinematics(ecc / clearance, eps_dot, omega_journal + omega_bearing - 2.0 * phi_dot, nx, ny)



# -- the transition to metal contact ----------------------------------------------------------------
def blend_eccentricity(eps: float, eps_dot: float, eps_film: float = EPS_FILM_DEFAULT,
                       eps_cap: float = EPS_CAP_DEFAULT) -> tuple[float, float]:
    """The eccentricity ratio (and its rate) the film is evaluated at, physics.md eq. (70).

    ``eps_b = eps`` for ``eps <= eps_film``; beyond,

        eps_b = eps_film + (eps_cap - eps_film) tanh((eps - eps_film) / (eps_cap - eps_film)),
        eps_dot_b = eps_dot / cosh^2((eps - eps_film) / (eps_cap - eps_film)),

    below ``eps_cap < 1`` for every ``eps``: the film force grows monotonically and stays
    finite at and beyond the wall, where the dry contact law (which the joint adds unchanged)
    takes over; the squeeze damping fades as ``eps_dot_b -> 0`` while the contact law's own
    damping acts.  ``eps_dot_b`` is the exact rate of ``eps_b``.

    Smoothness at ``eps_film``: ``eps_b`` keeps its value and first two derivatives (its
    third jumps, by ``-2 / (eps_cap - eps_film)^2``); ``eps_dot_b`` keeps value and slope in
    ``eps``, its second derivative jumps by ``-2 eps_dot / (eps_cap - eps_film)^2``.  So the
    film force and its first derivatives, the entries of Newton's Jacobian, are continuous
    across ``eps_film``; only the force's second derivative in ``eps`` jumps, and only for a
    moving journal (the jump is proportional to ``eps_dot``, zero at rest).  Newton converges
    quadratically wherever its Jacobian is Lipschitz continuous, which that jump does not
    break; a difference quotient straddling ``eps_film`` errs by its increment times the
    jump.  What stalled Newton for a journal resting near ``eps = 0.9`` was a jump of the
    first derivative, at ``eps_dot = 0``: the finite model's squeeze switch, which eq. (66a)
    turns smoothly (:meth:`FiniteBearing.turning_squeeze`).
    """
    check_nonnegative("eps", eps)
    if eps <= eps_film:
        return eps, eps_dot
    width = eps_cap - eps_film
    x = (eps - eps_film) / width
    # tanh(x) = (1 - q) / (1 + q) and 1 / cosh^2(x) = 4 q / (1 + q)^2 with q = exp(-2 x): one
    # exponential, as the compiled kernel, and no overflow far beyond the wall (cosh(x)^2
    # overflowed above x = 355, where a long explicit step had carried the journal)
    q = math.exp(-2.0 * x)
    return eps_film + width * ((1.0 - q) / (1.0 + q)), eps_dot * (4.0 * q / ((1.0 + q) * (1.0 + q)))
