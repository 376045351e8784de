"""Geometry and kinematics of a planar revolute clearance joint.

Notation and equations: docs/physics.md section 1, eqs. (1)-(8) (the paper's eqs. 1-6), and section 4,
eqs. (24)-(26).
Everything here is plain float arithmetic on scalars: it runs inside the per-step
force callback, where NumPy's per-call overhead on 2-vectors would dominate.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from .checks import check_positive, warn_unit
from .contact.pair import ContactGeometry

#: Clearances above this fraction of the journal radius are legal but unusual for a
#: revolute joint (the paper's is 1 %): a warning asks whether a unit slipped.
CLEARANCE_WARN_FRACTION = 0.1
#: Bearing radii or lengths above this [m] are legal but far beyond the pins of machines
#: (the paper's are 10 and 15 mm): a warning asks whether millimetres were given, which
#: the clearance check cannot see when every length is in mm (9.9, 10, 15).
SIZE_WARN_ABOVE = 1.0


@dataclass(frozen=True)
class BearingGeometry(ContactGeometry):
    """Journal and bearing dimensions: the revolute joint's contact pair, a line contact.

    Parameters
    ----------
    journal_radius : float
        ``R_J`` [m], > 0.
    bearing_radius : float
        ``R_B`` [m], > ``R_J``.
    length : float
        Axial length ``L`` of the bearing [m], > 0.
    """

    journal_radius: float
    bearing_radius: float
    length: float
    joint_type: ClassVar[str] = "revolute"

    def __post_init__(self) -> None:
        r_j = check_positive("journal_radius", self.journal_radius)
        r_b = check_positive("bearing_radius", self.bearing_radius)
        check_positive("length", self.length)
        if r_j >= r_b:
            raise ValueError(
                f"`journal_radius` must be smaller than `bearing_radius` "
                f"(radial clearance R_B - R_J > 0), got R_J = {r_j}, R_B = {r_b}"
            )
        if r_b - r_j > CLEARANCE_WARN_FRACTION * r_j:
            warn_unit(f"the radial clearance {r_b - r_j:.3g} m is more than {CLEARANCE_WARN_FRACTION:g} of the "
                      f"journal radius {r_j:.3g} m; lengths are in metres: was a value given in mm?")
        else:
            large = [f"the {what} {value:.3g} m" for what, value in (("bearing radius", r_b), ("length", self.length))
                     if value > SIZE_WARN_ABOVE]
            if large:
                warn_unit(f"{' and '.join(large)} {'is' if len(large) == 1 else 'are'} above {SIZE_WARN_ABOVE:g} m; "
                          f"lengths are in metres: {'was it' if len(large) == 1 else 'were they'} given in mm?")

    @property
    def inner_radius(self) -> float:
        return self.journal_radius

    @property
    def outer_radius(self) -> float:
        return self.bearing_radius

    @property
    def clearance(self) -> float:
        """Radial clearance ``c = R_B - R_J`` [m]."""
        return self.bearing_radius - self.journal_radius

    @classmethod
    def from_clearance(cls, bearing_radius: float, clearance: float, length: float) -> BearingGeometry:
        """Geometry from the bearing radius and the radial clearance ``c``."""
        check_positive("clearance", clearance)
        return cls(bearing_radius - clearance, bearing_radius, length)


class ContactKinematics(NamedTuple):
    """Contact quantities of docs/physics.md section 1, eqs. (1)-(8), at one instant (all SI).

    ``ecc`` is ``|e|``; ``(nx, ny)`` the unit normal from bearing centre to journal
    centre; the tangent is ``t = (ny, -nx)``; ``delta = |e| - c`` (> 0: contact);
    ``delta_dot = v . n`` and ``v_t = v . t`` with ``v`` the relative velocity of the
    contact points ``Q_J`` and ``Q_B``.
    """

    ex: float
    ey: float
    ecc: float
    nx: float
    ny: float
    delta: float
    delta_dot: float
    v_t: float


def contact_kinematics(
    geometry: BearingGeometry,
    xj: float, yj: float, vxj: float, vyj: float, omega_i: float,
    xb: float, yb: float, vxb: float, vyb: float, omega_j: float,
) -> ContactKinematics:
    """Evaluate eqs. 1-6 from journal centre ``P_J`` (body i) and bearing centre ``P_B`` (body j).

    At ``|e| = 0`` the normal is undefined; the joint is then far from contact
    (``delta = -c``) and ``n = (1, 0)`` is used so the returned values stay finite.
    """
    ex, ey = xj - xb, yj - yb
    ecc = math.sqrt(ex * ex + ey * ey)  # not hypot: the compiled kernel computes exactly this
    if ecc > 0.0:
        nx, ny = ex / ecc, ey / ecc
    else:
        nx, ny = 1.0, 0.0
    return kinematics_along(geometry, ex, ey, ecc, nx, ny, vxj - vxb, vyj - vyb, omega_i, omega_j)


def kinematics_along(
    geometry: BearingGeometry, ex: float, ey: float, ecc: float, nx: float, ny: float,
    dvx: float, dvy: float, omega_i: float, omega_j: float,
) -> ContactKinematics:
    """The rest of :func:`contact_kinematics` once ``|e|`` and ``n`` are known.
    ``(dvx, dvy) = v(P_J) - v(P_B)``."""
    # omega x (R n) = R omega (-ny, nx) = -R omega t, so only the tangential component changes
    r_j, r_b = geometry.journal_radius, geometry.bearing_radius
    delta_dot = dvx * nx + dvy * ny
    v_t = dvx * ny - dvy * nx - omega_i * r_j + omega_j * r_b
    return ContactKinematics(ex, ey, ecc, nx, ny, ecc - (r_b - r_j), delta_dot, v_t)


class JointLoads(NamedTuple):
    """Forces and moments of docs/physics.md section 4, eqs. (24)-(26).

    ``(fx, fy)`` acts on the journal body i at ``P_J`` with moment ``m_i``; the
    bearing body j gets ``(-fx, -fy)`` at ``P_B`` and moment ``m_j``.
    """

    fx: float
    fy: float
    m_i: float
    m_j: float


def joint_loads(geometry: BearingGeometry, kin: ContactKinematics, f_n: float, f_t: float) -> JointLoads:
    """Loads from the normal force ``f_n`` (>= 0) and tangential force ``f_t = mu F_N``.

    ``F_i = -F_N n - F_T t``; ``M_i = (R_J n) x (-F_T t) = R_J F_T`` and
    ``M_j = (R_B n) x (F_T t) = -R_B F_T``, since ``n x t = -e_z``.
    """
    nx, ny = kin.nx, kin.ny
    fx = -f_n * nx - f_t * ny
    fy = -f_n * ny + f_t * nx
    return JointLoads(fx, fy, geometry.journal_radius * f_t, -geometry.bearing_radius * f_t)
