"""Sliced line contact of a spatial revolute clearance joint (docs/physics.md section 9).

Pure Python, no exudyn, plain float arithmetic on 3-tuples (it runs inside the force
callback; the compiled kernel ``exuclear/_kernel/kinematics.hpp`` writes the same
formulas in the same order, with the same names).  The planar joint is the case of one
slice with the motion projected on the plane normal to the axis (``u = e_z``, ``p_z = 0``).

Everything is expressed in the bearing's joint frame J0: origin at the bearing centre
``P_B`` (mid-length), z along the bearing axis.  The journal is given by its centre
``p`` (the journal marker's point, relative to ``P_B``) and its unit axis ``u``; its
motion relative to the bearing by ``dv = v(P_J) - v(P_B)`` and ``dw = omega_i - omega_j``
(both in J0, Exudyn's connector arguments) and the bearing's own angular velocity
``w_j`` (in J0).  The bearing length ``L`` is cut into ``N`` slices of width ``L / N``;
slice ``k`` is the plane ``z = z_k`` through its centre, eq. (33).

Sign conventions follow the planar joint (section 1): ``n`` from the bearing axis to the
journal axis, ``t = (n_y, -n_x, 0)``, penetration ``delta = e - c`` (> 0: contact).

With an axial clearance (section 9.6, eqs. (48)-(54)) the journal's
shoulders meet the bearing's end faces: each face is one more contact, after the slices.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from .contact import damped_normal_force
from .vectors import V3, cross, dot


def slice_centres(length: float, slices: int) -> tuple[float, ...]:
    """Axial positions ``z_k`` [m] of the slice planes (eq. (33)): the centres of ``slices``
    equal parts of ``[-L/2, L/2]``."""
    width = length / slices
    return tuple(-0.5 * length + (k + 0.5) * width for k in range(slices))


def rotation_xyz(angles: V3) -> tuple[V3, V3, V3]:
    """Rows of ``R = Rx(a) Ry(b) Rz(c)``, Exudyn's Tait-Bryan xyz angles (its
    ``RotXYZ2RotationMatrix``; the connector's ``rotation`` argument)."""
    ca, sa = math.cos(angles[0]), math.sin(angles[0])
    cb, sb = math.cos(angles[1]), math.sin(angles[1])
    cc, sc = math.cos(angles[2]), math.sin(angles[2])
    return ((cb * cc, -cb * sc, sb),
            (ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb),
            (sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb))


def journal_axis(angles: V3, axis_journal: V3) -> V3:
    """The journal axis ``u`` in J0 (eq. (34)): ``R(angles) a_J``, with ``a_J`` the journal
    axis in the journal marker's frame and ``R`` the marker's rotation relative to J0."""
    r = rotation_xyz(angles)
    return (dot(r[0], axis_journal), dot(r[1], axis_journal), dot(r[2], axis_journal))


class SliceKinematics(NamedTuple):
    """Contact quantities of one slice, eqs. (35)-(40), in J0 (SI units).

    ``s`` the journal-axis parameter of the crossing point ``c = p + s u``; ``(ex, ey)``
    its eccentricity, ``ecc = |e|``, ``(nx, ny)`` the in-plane normal; ``a = (n . u) /
    u_z``, so that ``m = (nx, ny, -a)`` is the normal of eq. (37); ``delta``,
    ``delta_dot`` the penetration and its exact rate; ``v_t``, ``v_a`` the
    circumferential and axial slip of the contact points and ``speed`` their length.
    """

    s: float
    ex: float
    ey: float
    ecc: float
    nx: float
    ny: float
    a: float
    delta: float
    delta_dot: float
    v_t: float
    v_a: float
    speed: float


def slice_kinematics(r_j: float, r_b: float, z: float, p: V3, u: V3, dv: V3, dw: V3, w_j: V3) -> SliceKinematics:
    """The kinematics of the slice at ``z`` (docs/physics.md eqs. (35)-(40))."""
    s, ex, ey = slice_eccentricity(z, p, u)
    ecc = math.sqrt(ex * ex + ey * ey)
    if ecc > 0.0:
        nx, ny = ex / ecc, ey / ecc
    else:  # journal axis on the bearing axis: no contact, any normal keeps the values finite
        nx, ny = 1.0, 0.0
    return slice_kinematics_along(r_j, r_b, s, ex, ey, ecc, nx, ny, p, u, dv, dw, w_j)


def slice_eccentricity(z: float, p: V3, u: V3) -> tuple[float, float, float]:
    """The journal-axis parameter ``s`` of the slice plane ``z`` and the eccentricity
    ``(ex, ey)`` of the crossing point ``c = p + s u`` (eq. (35))."""
    s = (z - p[2]) / u[2]                                      # eq. (35)
    return s, p[0] + s * u[0], p[1] + s * u[1]


def slice_kinematics_along(r_j: float, r_b: float, s: float, ex: float, ey: float, ecc: float, nx: float, ny: float,
                           p: V3, u: V3, dv: V3, dw: V3, w_j: V3) -> SliceKinematics:
    """The rest of :func:`slice_kinematics` once ``|e|`` (``ecc``) and the in-plane normal
    ``n`` are known (eqs. (36)-(40)); a worn slice gives its own (the worn contact's normal,
    eq. (75), and ``ecc = delta + c`` from its penetration, eq. (76)), as
    :func:`exuclear.geometry.kinematics_along` for the planar joint."""
    delta = ecc - (r_b - r_j)                                   # eq. (36)
    a = (nx * u[0] + ny * u[1]) / u[2]                          # eq. (37)
    su = (s * u[0], s * u[1], s * u[2])
    wp = cross(w_j, p)
    ws = cross(dw, su)
    w = (dv[0] - wp[0] + ws[0], dv[1] - wp[1] + ws[1], dv[2] - wp[2] + ws[2])
    delta_dot = nx * w[0] + ny * w[1] - a * w[2]                # eq. (38)
    r = (su[0] + r_j * nx, su[1] + r_j * ny, su[2])             # Q_J - P_J, eq. (39)
    lever = (delta * nx - p[0], delta * ny - p[1], -p[2])       # Q_J - Q_B - p
    wr = cross(dw, r)
    wl = cross(w_j, lever)
    v = (dv[0] + wr[0] + wl[0], dv[1] + wr[1] + wl[1], dv[2] + wr[2] + wl[2])
    v_t = v[0] * ny - v[1] * nx                                 # eq. (40)
    v_a = v[2]
    speed = math.sqrt(v_t * v_t + v_a * v_a)
    return SliceKinematics(s, ex, ey, ecc, nx, ny, a, delta, delta_dot, v_t, v_a, speed)


def slice_friction(mu: float, f_n: float, kin: SliceKinematics) -> tuple[float, float]:
    """Circumferential and axial friction forces ``(F_T, F_A)`` [N] on the bearing at its
    contact point (eq. (42)): ``mu(|v_s|) F_N`` along the slip ``(v_t, v_a)``."""
    return friction_components(mu * f_n, kin)


def friction_components(f_t: float, kin: SliceKinematics) -> tuple[float, float]:
    """The friction force of magnitude ``f_t = mu(|v_s|) F_N`` [N] split along the slip
    ``(v_t, v_a)`` of the contact points (eq. (42)): ``(F_T, F_A)``."""
    if not kin.speed > 0.0:
        return 0.0, 0.0
    return f_t * (kin.v_t / kin.speed), f_t * (kin.v_a / kin.speed)


class SpatialLoads(NamedTuple):
    """Loads of eqs. (43)-(45) in J0: ``force`` on the bearing (the journal gets its
    negative), ``torque`` = minus the journal's moment about ``P_J`` (Exudyn's connector
    torque), ``correction`` = the bearing's moment about ``P_B`` minus ``torque`` (the
    torque connector's)."""

    force: V3
    torque: V3
    correction: V3


def add_slice_loads(loads: list[float], r_j: float, u: V3, kin: SliceKinematics, f_n: float, f_t: float,
                    f_a: float) -> None:
    """Add one slice's share to ``loads`` = [force (3), torque (3), correction (3)] (eqs. (43)-(45))."""
    n_force = (f_n * kin.nx, f_n * kin.ny, -f_n * kin.a)        # F_N m, on the bearing at c, eq. (41)
    t_force = (f_t * kin.ny, -f_t * kin.nx, f_a)                 # friction on the bearing at Q_B, eq. (42)
    total = (n_force[0] + t_force[0], n_force[1] + t_force[1], n_force[2] + t_force[2])
    su = (kin.s * u[0], kin.s * u[1], kin.s * u[2])
    arm = cross(su, total)
    rim = cross((r_j * kin.nx, r_j * kin.ny, 0.0), t_force)
    couple = cross((kin.delta * kin.nx, kin.delta * kin.ny, 0.0), t_force)
    for i in range(3):
        loads[i] += total[i]                                    # eq. (43)
        loads[3 + i] += arm[i] + rim[i]                         # eq. (44)
        loads[6 + i] -= couple[i]                               # eq. (45), the p x F part added at the end


def finish_loads(loads: list[float], p: V3) -> SpatialLoads:
    """The loads after the last slice: adds ``p x F`` to the correction (eq. (45))."""
    force = (loads[0], loads[1], loads[2])
    pf = cross(p, force)
    return SpatialLoads(force, (loads[3], loads[4], loads[5]),
                        (pf[0] + loads[6], pf[1] + loads[7], pf[2] + loads[8]))


# -- axial clearance: the journal's shoulders against the bearing's end faces (section 9.6) ----
FACE_SIDES = (-1, 1)  # face 0 at z = -L/2, face 1 at z = +L/2 (the order of the slices)


@dataclass(frozen=True)
class ShoulderGeometry:
    """The axial clearance of a spatial joint (docs/physics.md section 9.6), SI units.

    ``axial_clearance`` g [m]: the total axial play, the sum of both gaps between the
    journal's shoulders and the bearing's end faces with the journal centred; the shoulders'
    faces are ``L + g`` apart.  ``shoulder_radius`` R_S [m]: outer radius of the annulus in
    which a shoulder meets an end face (the smaller of the collar's and the end face's
    outer radius); its inner radius is the bearing radius R_B.  Checked at the public
    boundary (``exuclear.engine.connector``): ``g > 0``, ``R_S > R_B``.
    """

    axial_clearance: float
    shoulder_radius: float
    bearing_radius: float

    @property
    def friction_radius(self) -> float:
        """R_e [m] of eq. (51): the friction radius of the annulus under uniform pressure."""
        r_o, r_i = self.shoulder_radius, self.bearing_radius
        return 2.0 / 3.0 * (r_o**3 - r_i**3) / (r_o**2 - r_i**2)

    def face_stiffness(self, e_star: float) -> float:
        """K_f [N/m] of eq. (52): a flat circular punch of radius R_S (Sneddon 1965), an
        upper bound for the annulus."""
        return 2.0 * e_star * self.shoulder_radius


class FaceKinematics(NamedTuple):
    """Contact quantities of one end face, eqs. (48)-(51), in J0 (SI units).

    ``side`` f = -1 (face at z = -L/2) or +1; ``s`` the journal-axis parameter of the
    shoulder's centre ``c_f = p + s u``; ``(ex, ey)`` that centre's offset from the bearing
    axis; ``delta``, ``delta_dot`` the axial penetration and its exact rate; ``v_t`` the
    circumferential slip at the friction radius (positive: the journal spins faster about
    its axis than the bearing).
    """

    side: int
    s: float
    ex: float
    ey: float
    delta: float
    delta_dot: float
    v_t: float


def face_kinematics(length: float, play: float, r_e: float, side: int, p: V3, u: V3, dv: V3, dw: V3,
                    w_j: V3) -> FaceKinematics:
    """The kinematics of the end face ``side`` (docs/physics.md eqs. (48)-(51))."""
    s = side * 0.5 * (length + play)                            # eq. (48)
    cz = p[2] + s * u[2]
    delta = 0.5 * length - side * cz                            # eq. (49)
    su = (s * u[0], s * u[1], s * u[2])
    wp = cross(w_j, p)
    ws = cross(dw, su)
    delta_dot = -side * (dv[2] - wp[2] + ws[2])                  # eq. (50)
    v_t = r_e * dot(dw, u)                                      # eq. (51)
    return FaceKinematics(side, s, p[0] + su[0], p[1] + su[1], delta, delta_dot, v_t)


def face_normal_force(k_face: float, damping_factor: float, v_min: float, delta: float, delta_dot: float,
                      v0: float) -> float:
    """F_N,f [N] of eq. (53): eq. (9) with ``F_e = K_f delta`` and the joint law's ``D`` and
    ``v_min``; 0 without penetration, no adhesion."""
    if delta <= 0.0:
        return 0.0
    return damped_normal_force(k_face * delta, damping_factor, v_min, delta_dot, v0)


def add_face_loads(loads: list[float], r_e: float, u: V3, kin: FaceKinematics, f_n: float, f_t: float) -> None:
    """Add one end face's loads to ``loads`` = [force (3), torque (3), correction (3)] (eq. (54)):
    ``-f F_N e_z`` on the bearing along the axis through the shoulder's centre, and the
    friction couple ``R_e F_T u`` on the bearing (its negative on the journal)."""
    total = (0.0, 0.0, -kin.side * f_n)                          # on the bearing, at c_f
    su = (kin.s * u[0], kin.s * u[1], kin.s * u[2])
    arm = cross(su, total)
    couple = (r_e * f_t * u[0], r_e * f_t * u[1], r_e * f_t * u[2])
    for i in range(3):
        loads[i] += total[i]                                    # eq. (54)
        loads[3 + i] += arm[i] + couple[i]                      # eq. (54); the correction is p x F (eq. (45))
