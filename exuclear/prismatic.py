"""A slider in a guide: the planar translational clearance joint's contact pairs (Flores,
Ambrosio, Claro, Lankarani, J. Comput. Nonlinear Dyn. 3 (2008) 011007, section 3; Flores,
Leine, Glocker, Multibody Syst. Dyn. 23 (2010) 165-190, section 2).

Pure Python, no exudyn, plain float arithmetic (it runs inside the force callback; the
compiled kernel ``exuclear/_kernel/kinematics.hpp`` and ``contacts.hpp`` write the same
formulas in the same order, with the same names).  Everything is in the guide's joint frame
J0: ``x`` along the guide (the sliding axis), ``y`` across it, ``z`` normal to the plane of
motion.  ``p`` is the slider's centre relative to the guide's centre-line point, ``theta``
the slider's turn relative to the guide, ``dv``, ``dw`` Exudyn's relative velocity and
angular velocity, ``w_j`` the guide's own spin.

The slider (length ``L``, height ``H``) has four corners ``c_k = (+-L/2, +-H/2)`` in its
own frame; the guide has two walls at ``y = -+(H/2 + c)``.  Every corner is paired with
both walls (eight pairs, each with its own law and onset history): free flight, one corner,
two corners on one wall and two opposite corners on opposite walls come by themselves.  A
pair's penetration is ``delta = s q_y - (H/2 + c)`` with ``q = p + R(theta) c_k`` the
corner and ``s = -1`` for the lower wall, ``+1`` for the upper one; its normal is
``(0, s)``; friction acts along the wall against the corner's slip over it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from .checks import check_positive, warn_unit
from .contact.pair import ContactGeometry
from .geometry import SIZE_WARN_ABOVE

#: The slider's corners in its own frame, as signs of (L/2, H/2): rear-lower, front-lower,
#: front-upper, rear-upper (counter-clockwise from the rear-lower corner).
CORNER_SIGNS = ((-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0))
#: The guide's walls as the sign ``s`` of their normal along y: lower, upper.
WALL_SIDES = (-1.0, 1.0)
CORNER_NAMES = ("rear-lower", "front-lower", "front-upper", "rear-upper")
WALL_NAMES = ("lower", "upper")
#: The pairs in the kernels' order: every corner with the lower wall, then with the upper one.
PAIRS = tuple((k, w) for w in range(len(WALL_SIDES)) for k in range(len(CORNER_SIGNS)))
#: Clearances above this fraction of the slider height are legal but unusual for a guide:
#: a warning asks whether a unit slipped (as the revolute joint's ``CLEARANCE_WARN_FRACTION``).
GUIDE_CLEARANCE_WARN_FRACTION = 0.5


def pair_name(pair: int) -> str:
    """``"corner front-lower / lower wall"`` for the pair number ``pair`` (:data:`PAIRS`)."""
    k, w = PAIRS[pair]
    return f"corner {CORNER_NAMES[k]} / {WALL_NAMES[w]} wall"


@dataclass(frozen=True)
class GuideGeometry(ContactGeometry):
    """A slider of length ``slider_length`` and height ``slider_height`` [m] in a guide
    ``slider_height + 2 clearance`` wide: ``clearance`` [m] is the play per side.

    As a :class:`ContactGeometry` the corner is a point contact (``length`` None) between
    the slider's half-height (``inner_radius``) and the guide's half-width
    (``outer_radius``), so that ``clearance`` is their difference; a sharp corner has no
    radius of curvature, so its stiffness is given (:class:`exuclear.contact.stiffness.GivenStiffness`).
    A corner edge rounded to ``corner_radius`` [m] along ``corner_length`` [m] (the slider's
    depth across the plane) is a cylinder on a flat wall, a line contact: its
    :attr:`relative_curvature` is ``1 / corner_radius`` and its ``length`` ``corner_length``.
    """

    slider_length: float
    slider_height: float
    guide_clearance: float
    corner_radius: float | None = None
    corner_length: float | None = None
    joint_type: ClassVar[str] = "prismatic"

    def __post_init__(self) -> None:
        check_positive("slider_length", self.slider_length)
        h = check_positive("slider_height", self.slider_height)
        c = check_positive("clearance", self.guide_clearance)
        if c > GUIDE_CLEARANCE_WARN_FRACTION * h:
            warn_unit(f"the clearance {c:.3g} m is more than {GUIDE_CLEARANCE_WARN_FRACTION:g} of the slider height "
                      f"{h:.3g} m; lengths are in metres: was a value given in mm?")
        elif max(self.slider_length, h) > SIZE_WARN_ABOVE:
            warn_unit(f"the slider ({self.slider_length:.3g} m x {h:.3g} m) is above {SIZE_WARN_ABOVE:g} m; lengths "
                      "are in metres: was it given in mm?")
        for name in ("corner_radius", "corner_length"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))

    @property
    def inner_radius(self) -> float:
        """The slider's half-height H/2 [m]."""
        return 0.5 * self.slider_height

    @property
    def outer_radius(self) -> float:
        """The guide's half-width H/2 + c [m]."""
        return 0.5 * self.slider_height + self.guide_clearance

    @property
    def length(self) -> float | None:
        """``corner_length``, the length of a rounded corner edge's line contact; None: a
        corner touches a wall at a point."""
        return self.corner_length

    @property
    def relative_curvature(self) -> float:
        """``1 / corner_radius`` [1/m]: a rounded corner on a flat wall."""
        if self.corner_radius is None:
            raise ValueError("a sharp corner (corner_radius None) has no finite curvature: give `corner_radius`")
        return 1.0 / self.corner_radius


class CornerKinematics(NamedTuple):
    """One corner-wall pair's contact quantities in J0 (SI units).

    ``(ex, ey)`` the corner ``q``, ``(nx, ny)`` the wall's normal ``(0, s)``; ``delta``,
    ``delta_dot`` the penetration and its rate; ``v_t`` the corner's slip along the wall
    (signed, along x), which friction acts against; ``(rx, ry)`` the corner relative to the
    slider's centre, ``R(theta) c_k`` (the lever of its loads).
    """

    ex: float
    ey: float
    nx: float
    ny: float
    delta: float
    delta_dot: float
    v_t: float
    rx: float
    ry: float


def corner_kinematics(half_length: float, half_height: float, half_width: float, corner: int, wall: int,
                      px: float, py: float, theta: float, dvx: float, dvy: float, dw: float, w_j: float
                      ) -> CornerKinematics:
    """The kinematics of ``corner`` (:data:`CORNER_SIGNS`) against ``wall`` (:data:`WALL_SIDES`)
    of a slider ``2 half_length`` by ``2 half_height`` in a guide ``2 half_width`` wide, the
    slider at ``(px, py)`` turned by ``theta`` relative to the guide (module docstring)."""
    sx, sy = CORNER_SIGNS[corner]
    s = WALL_SIDES[wall]
    cos_t, sin_t = math.cos(theta), math.sin(theta)
    rx = cos_t * sx * half_length - sin_t * sy * half_height   # R(theta) c_k
    ry = sin_t * sx * half_length + cos_t * sy * half_height
    qx, qy = px + rx, py + ry                                  # the corner in J0
    delta = s * qy - half_width
    # the corner's velocity over the guide's point under it: dv + dw x r - w_j x p
    vx = dvx - dw * ry + w_j * py
    vy = dvy + dw * rx - w_j * px
    return CornerKinematics(qx, qy, 0.0, s, delta, s * vy, vx, rx, ry)


def add_corner_loads(loads: list[float], kin: CornerKinematics, f_n: float, f_t: float) -> None:
    """Add one pair's loads to ``loads`` = [force (3), torque (3), correction (3)]: on the
    guide, ``F = F_N n + F_T x`` (the wall pushed along its normal, dragged along the slip;
    ``f_t`` has the slip's sign); the slider's moment about its centre ``r x (-F)``, minus
    it as the torque; the guide's moment beyond it, ``p x F``, is added at the end
    (:func:`exuclear.spatial.finish_loads`)."""
    fx = f_t + f_n * kin.nx
    fy = f_n * kin.ny
    loads[0] += fx
    loads[1] += fy
    loads[5] += kin.rx * fy - kin.ry * fx                      # T = -(r x (-F)) = r x F
