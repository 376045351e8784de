"""A ball in a spherical socket: the spherical clearance joint's contact (docs/physics.md
section 13, eqs. (93)-(98)).

Pure Python, no exudyn, plain float arithmetic on 3-tuples (it runs inside the force
callback; the compiled kernel ``exuclear/_kernel/kinematics.hpp`` and ``contacts.hpp`` write
the same formulas in the same order, with the same names).  Everything is in the socket's
joint frame J0, as for :mod:`exuclear.spatial`: the ball's centre ``p`` relative to the
socket's centre, ``dv = v(P_ball) - v(P_socket)`` and ``dw = omega_ball - omega_socket``
(Exudyn's connector arguments), and the socket's own angular velocity ``w_j``.

The joint has one contact, a point: ``n = p / |p|`` from the socket's centre to the ball's,
penetration ``delta = |p| - (R_S - R_B)`` (> 0: contact), contact points ``P_ball + R_B n``
on the ball and ``P_socket + R_S n`` on the socket.  Its loads go to the same
``[force (3), torque (3), correction (3)]`` as a slice's (:func:`exuclear.spatial.finish_loads`
adds ``p x F``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from .checks import check_positive, warn_unit
from .contact.pair import ContactGeometry
from .geometry import SIZE_WARN_ABOVE
from .vectors import V3, cross

#: Clearances above this fraction of the ball radius are legal but unusual for a ball joint:
#: a warning asks whether a unit slipped (as the revolute joint's ``CLEARANCE_WARN_FRACTION``).
BALL_CLEARANCE_WARN_FRACTION = 0.1


@dataclass(frozen=True)
class SphereGeometry(ContactGeometry):
    """A ball of radius ``ball_radius`` [m] in a spherical socket of radius ``socket_radius``
    [m] > ``ball_radius``: the spherical joint's contact pair, a point contact."""

    ball_radius: float
    socket_radius: float
    joint_type: ClassVar[str] = "spherical"

    def __post_init__(self) -> None:
        r_b = check_positive("ball_radius", self.ball_radius)
        r_s = check_positive("socket_radius", self.socket_radius)
        if r_b >= r_s:
            raise ValueError(f"`ball_radius` must be smaller than `socket_radius` (radial clearance R_S - R_B > 0), "
                             f"got R_B = {r_b}, R_S = {r_s}")
        if r_s - r_b > BALL_CLEARANCE_WARN_FRACTION * r_b:
            warn_unit(f"the radial clearance {r_s - r_b:.3g} m is more than {BALL_CLEARANCE_WARN_FRACTION:g} of the "
                      f"ball radius {r_b:.3g} m; lengths are in metres: was a value given in mm?")
        elif r_s > SIZE_WARN_ABOVE:
            warn_unit(f"the socket radius {r_s:.3g} m is above {SIZE_WARN_ABOVE:g} m; lengths are in metres: was it "
                      "given in mm?")

    @property
    def inner_radius(self) -> float:
        return self.ball_radius

    @property
    def outer_radius(self) -> float:
        return self.socket_radius

    @property
    def length(self) -> None:
        """None, as the ball touches its socket at a point."""
        return None


class BallKinematics(NamedTuple):
    """The ball's contact quantities, eqs. (93)-(96), in J0 (SI units).

    ``(ex, ey, ez)`` the eccentricity ``p``, ``ecc = |p|``, ``(nx, ny, nz)`` the normal;
    ``delta``, ``delta_dot`` the penetration and its rate; ``(vx, vy, vz)`` the slip of the
    ball's contact point over the socket's, across the normal, and ``v_t`` its length (the
    speed friction acts against).
    """

    ex: float
    ey: float
    ez: float
    ecc: float
    nx: float
    ny: float
    nz: float
    delta: float
    delta_dot: float
    vx: float
    vy: float
    vz: float
    v_t: float


def ball_kinematics(r_b: float, r_s: float, p: V3, dv: V3, dw: V3, w_j: V3) -> BallKinematics:
    """The kinematics of the ball of radius ``r_b`` in the socket of radius ``r_s``
    (docs/physics.md eqs. (93)-(96))."""
    ecc = math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
    if ecc > 0.0:
        n = (p[0] / ecc, p[1] / ecc, p[2] / ecc)                # eq. (93)
    else:  # the ball at the socket's centre: no contact, any normal keeps the values finite
        n = (1.0, 0.0, 0.0)
    delta = ecc - (r_s - r_b)                                   # eq. (94)
    delta_dot = n[0] * dv[0] + n[1] * dv[1] + n[2] * dv[2]      # eq. (95): the spins do not enter
    r = (r_b * n[0], r_b * n[1], r_b * n[2])                    # Q_ball - P_ball
    lever = (delta * n[0] - p[0], delta * n[1] - p[1], delta * n[2] - p[2])  # Q_ball - Q_socket - p
    wr = cross(dw, r)
    wl = cross(w_j, lever)
    v = (dv[0] + wr[0] + wl[0], dv[1] + wr[1] + wl[1], dv[2] + wr[2] + wl[2])
    vn = n[0] * v[0] + n[1] * v[1] + n[2] * v[2]
    vs = (v[0] - vn * n[0], v[1] - vn * n[1], v[2] - vn * n[2])  # eq. (96)
    v_t = math.sqrt(vs[0] * vs[0] + vs[1] * vs[1] + vs[2] * vs[2])
    return BallKinematics(p[0], p[1], p[2], ecc, n[0], n[1], n[2], delta, delta_dot, vs[0], vs[1], vs[2], v_t)


def add_ball_loads(loads: list[float], r_b: float, kin: BallKinematics, f_n: float, f_t: float) -> None:
    """Add the ball's loads to ``loads`` = [force (3), torque (3), correction (3)] (eqs.
    (97), (98)): ``F_N n`` and the friction ``F_T`` along the slip on the socket, the
    friction's moment ``R_B n x F_T`` about the ball's centre; the correction (the socket's
    moment beyond ``T``) gets ``-delta n x F_T`` here and ``p x F`` at the end
    (:func:`exuclear.spatial.finish_loads`), which make ``R_S n x F_T``."""
    if kin.v_t > 0.0:
        scale = f_t / kin.v_t
        t_force = (scale * kin.vx, scale * kin.vy, scale * kin.vz)  # friction on the socket, eq. (97)
    else:
        t_force = (0.0, 0.0, 0.0)
    total = (f_n * kin.nx + t_force[0], f_n * kin.ny + t_force[1], f_n * kin.nz + t_force[2])
    rim = cross((r_b * kin.nx, r_b * kin.ny, r_b * kin.nz), t_force)
    couple = cross((kin.delta * kin.nx, kin.delta * kin.ny, kin.delta * kin.nz), t_force)
    for i in range(3):
        loads[i] += total[i]                                    # eq. (97)
        loads[3 + i] += rim[i]                                  # eq. (98)
        loads[6 + i] -= couple[i]                               # eq. (98), p x F added at the end
