"""Clearance-joint geometry and loads of the reference solver, written independently.

docs/physics.md sections 1 and 4 again, in the reference's own words.  From exuclear only the
laws are taken: :func:`exuclear.make_joint` builds them, and the reference calls
:meth:`ContactLaw.normal_force` and :meth:`FrictionLaw.coefficient`, nothing else.

Plain float arithmetic throughout: these functions run inside the right-hand sides,
where NumPy's per-call overhead on 2-vectors would dominate.

Planar conventions used below: the cross product of two in-plane vectors is the
scalar ``a x b = a_x b_y - a_y b_x``; an angular velocity ``w`` (about +Z) turns a
vector ``p`` into the velocity ``w x p = w (-p_y, p_x)``.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import exuclear


class Laws(NamedTuple):
    """The two laws of a clearance joint, as built by :func:`exuclear.make_joint`.

    Attributes
    ----------
    normal_force : callable
        ``F_N(delta, delta_dot, v0) -> float`` [N], docs/physics.md section 2.
    friction_coefficient : callable
        ``mu(v_T) -> float``, odd in ``v_T``, docs/physics.md section 3.
    frictional : bool
        False when ``mu`` is identically zero (the friction work is then skipped).
    """

    normal_force: Callable[[float, float, float], float]
    friction_coefficient: Callable[[float], float]
    frictional: bool


def build_laws(*, journal_radius: float, bearing_radius: float, length: float, law: str, cr: float,
               journal_material: str, bearing_material: str, friction: str, v_min: float) -> Laws:
    """Normal and friction laws of a joint, from the names of a params dataclass."""
    joint = exuclear.make_joint(journal_radius=journal_radius, bearing_radius=bearing_radius, length=length,
                                law=law, cr=cr, journal_material=journal_material,
                                bearing_material=bearing_material, friction=friction, v_min=v_min)
    friction_law = joint.friction
    return Laws(joint.law.normal_force, friction_law.coefficient, friction_law.coefficient(1.0) != 0.0)


def gap(ex: float, ey: float, vex: float, vey: float, clearance: float) -> tuple[float, float]:
    """Penetration and its rate from the eccentricity and its time derivative.

    ``delta = |e| - c`` and ``delta_dot = d|e|/dt = (e . e_dot) / |e|`` (docs/physics.md section 1).  At
    ``|e| = 0`` the one-sided derivative ``|e_dot|`` is returned (only the centred
    initial state of the slider-crank lands there, far from any contact).

    Returns
    -------
    delta, delta_dot : float
        [m], [m/s]; ``delta > 0`` is penetration, ``delta_dot > 0`` approach.
    """
    ecc = math.hypot(ex, ey)
    if ecc == 0.0:
        return -clearance, math.hypot(vex, vey)
    return ecc - clearance, (ex * vex + ey * vey) / ecc


def contact_kinematics(ex: float, ey: float, vex: float, vey: float, omega_i: float, omega_j: float,
                       journal_radius: float, bearing_radius: float,
                       clearance: float) -> tuple[float, float, float, float, float]:
    """Contact quantities of docs/physics.md section 1 for ``|e| > 0``.

    Parameters
    ----------
    ex, ey : float
        Eccentricity ``e = r(P_J) - r(P_B)`` [m].
    vex, vey : float
        Its time derivative ``v(P_J) - v(P_B)`` [m/s].
    omega_i, omega_j : float
        Angular velocities of the journal's body i and the bearing's body j [rad/s].
    journal_radius, bearing_radius, clearance : float
        ``R_J``, ``R_B`` and ``c = R_B - R_J`` [m].

    Returns
    -------
    delta, delta_dot, v_t, nx, ny : float
        Penetration ``|e| - c``; ``delta_dot = v . n``; slip ``v_T = v . t``; the unit
        normal ``n = e / |e|``.  With the tangent ``t = (n_y, -n_x)`` one has
        ``w x (R n) = -w R t``, so the relative contact-point velocity is
        ``v = e_dot - (omega_i R_J - omega_j R_B) t``: the rotations only add slip.
    """
    ecc = math.hypot(ex, ey)
    nx, ny = ex / ecc, ey / ecc
    delta_dot = vex * nx + vey * ny
    v_t = vex * ny - vey * nx - omega_i * journal_radius + omega_j * bearing_radius
    return ecc - clearance, delta_dot, v_t, nx, ny


def journal_loads(nx: float, ny: float, f_n: float, f_t: float, journal_radius: float,
                  bearing_radius: float) -> tuple[float, float, float, float]:
    """Loads of docs/physics.md section 4 from the force magnitudes.

    ``F_i = -F_N n - F_T t`` on the journal at ``P_J``; ``M_i = (R_J n) x (-F_T t)``;
    ``F_j = -F_i`` on the bearing at ``P_B``; ``M_j = (R_B n) x (F_T t)``.  With
    ``n x t = -1``: ``M_i = F_T R_J`` and ``M_j = -F_T R_B``.

    Returns
    -------
    fx_i, fy_i, m_i, m_j : float
        Force on the journal [N] and the two moments [N m].
    """
    return -f_n * nx - f_t * ny, -f_n * ny + f_t * nx, f_t * journal_radius, -f_t * bearing_radius
