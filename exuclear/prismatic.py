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

The spatial joint (``slider_width`` given) is a box ``L`` x ``H`` x ``B`` in a rectangular
channel: the planar walls and two more at ``z = -+(B/2 + c_z)``.  Its eight corners
``c_k = (+-L/2, +-H/2, +-B/2)`` against the four walls make 32 pairs, each as a planar pair
in 3D: ``r = A c_k`` with ``A`` the slider's rotation relative to the guide (Exudyn's
Tait-Bryan angles), ``q = p + r``, ``delta = s q_a - w_a`` across the wall's axis ``a`` (y or
z) at ``w_a`` from the centre line, the normal ``s e_a``, and friction against the corner's
slip over the wall, the vector ``v_s`` of its velocity along the wall's plane (as the
spherical joint's ball).  All 32 are kept: which corner can reach which wall depends on the
clearances and on how far the slider turns, and a pair that never touches costs one
evaluation and nothing else.

A finite guide (``guide_length``): a corner whose position along the axis is beyond
``guide_length / 2`` of the guide's centre point has no wall under it (:func:`leave_guide`):
its penetration is ``-inf``, the history's mark of no state, so that its contact ends there
and, where it comes back into the guide, its onset velocity is taken afresh.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from .checks import check_positive, warn_unit
from .contact.pair import ContactGeometry
from .geometry import SIZE_WARN_ABOVE
from .vectors import V3, cross

#: The slider's corners in its own frame as signs of (L/2, H/2), counter-clockwise from the
#: rear-lower corner: rear-lower, front-lower, front-upper, rear-upper.
CORNER_SIGNS = ((-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0))
#: The guide's walls, lower and upper, as the sign ``s`` of their normal along y.
WALL_SIDES = (-1.0, 1.0)
CORNER_NAMES = ("rear-lower", "front-lower", "front-upper", "rear-upper")
WALL_NAMES = ("lower", "upper")
#: The corner-wall pairs in the kernels' order (every corner with the lower wall, then with the upper one).
PAIRS = tuple((k, w) for w in range(len(WALL_SIDES)) for k in range(len(CORNER_SIGNS)))
#: The spatial joint's corners as signs of (L/2, H/2, B/2), the planar four at z = -B/2, then at z = +B/2.
BOX_CORNER_SIGNS = tuple((sx, sy, sz) for sz in (-1.0, 1.0) for sx, sy in CORNER_SIGNS)
BOX_CORNER_NAMES = tuple(f"{name}-{side}" for side in ("far", "near") for name in CORNER_NAMES)
#: The spatial joint's walls as (the axis across them, 1 for y and 2 for z; the sign ``s`` of their normal).
BOX_WALLS = ((1, -1.0), (1, 1.0), (2, -1.0), (2, 1.0))
BOX_WALL_NAMES = ("lower", "upper", "far", "near")
#: The spatial joint's pairs in the kernels' order, every corner with the lower wall, then the upper, far, near one.
BOX_PAIRS = tuple((k, w) for w in range(len(BOX_WALLS)) for k in range(len(BOX_CORNER_SIGNS)))
#: Clearances above this fraction of the slider height are legal but unusual for a guide:
#: a warning asks whether a unit slipped (as the revolute joint's ``CLEARANCE_WARN_FRACTION``).
GUIDE_CLEARANCE_WARN_FRACTION = 0.5


def pair_name(pair: int, spatial: bool = False) -> str:
    """``"corner front-lower / lower wall"`` for the pair number ``pair`` (:data:`PAIRS`; ``spatial``:
    :data:`BOX_PAIRS`, ``"corner front-lower-near / far wall"``)."""
    if spatial:
        k, w = BOX_PAIRS[pair]
        return f"corner {BOX_CORNER_NAMES[k]} / {BOX_WALL_NAMES[w]} wall"
    k, w = PAIRS[pair]
    return f"corner {CORNER_NAMES[k]} / {WALL_NAMES[w]} wall"


@dataclass(frozen=True)
class GuideGeometry(ContactGeometry):
    """A slider of length ``slider_length`` and height ``slider_height`` [m] in a guide
    ``slider_height + 2 clearance`` wide: ``clearance`` [m] is the play per side.

    ``slider_width`` [m] makes it the spatial joint, a box in a channel
    ``slider_width + 2 clearance_width`` deep (``clearance_width`` [m], the play per side
    across the width; default ``clearance``); None: the planar joint.  ``guide_length`` [m]:
    the guide's walls end ``guide_length / 2`` either side of its centre point; None: they
    do not end.

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
    guide_length: float | None = None
    slider_width: float | None = None
    clearance_width: float | None = None
    joint_type: ClassVar[str] = "prismatic"

    def __post_init__(self) -> None:
        check_positive("slider_length", self.slider_length)
        h = check_positive("slider_height", self.slider_height)
        c = check_positive("clearance", self.guide_clearance)
        for name in ("corner_radius", "corner_length"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))
        if self.guide_length is not None:
            check_positive("guide_length", self.guide_length)
        if self.slider_width is None:
            if self.clearance_width is not None:
                raise ValueError("`clearance_width` is the spatial joint's play across the slider's width: give "
                                 "`slider_width` too, or leave it out for the planar joint")
        else:
            check_positive("slider_width", self.slider_width)
            if self.corner_length is not None:
                raise ValueError("`corner_length` is the planar slider's corner edge rounded along its depth (a line "
                                 "contact); the box's corners are points: leave it out with `slider_width`")
            if self.clearance_width is None:
                object.__setattr__(self, "clearance_width", c)
            check_positive("clearance_width", self.clearance_width)
        sizes = (h,) if self.slider_width is None else (h, self.slider_width)
        plays = (("clearance", c, "height", h),) if self.slider_width is None else (
            ("clearance", c, "height", h), ("clearance_width", self.clearance_width, "width", self.slider_width))
        for name, play, side, size in plays:
            if play > GUIDE_CLEARANCE_WARN_FRACTION * size:
                warn_unit(f"the {name} {play:.3g} m is more than {GUIDE_CLEARANCE_WARN_FRACTION:g} of the slider {side} "
                          f"{size:.3g} m; lengths are in metres: was a value given in mm?")
                return
        if max(self.slider_length, *sizes) > SIZE_WARN_ABOVE:
            warn_unit(f"the slider ({' m x '.join(f'{v:.3g}' for v in (self.slider_length, *sizes))} m) is above "
                      f"{SIZE_WARN_ABOVE:g} m; lengths are in metres: was it given in mm?")

    @property
    def spatial(self) -> bool:
        """Whether the joint is the spatial one (a box in a channel, :data:`BOX_PAIRS`)."""
        return self.slider_width is not None

    @property
    def pairs(self) -> tuple[tuple[int, int], ...]:
        """The corner-wall pairs in the kernels' order, :data:`PAIRS` (planar) or :data:`BOX_PAIRS` (spatial)."""
        return BOX_PAIRS if self.spatial else PAIRS

    @property
    def half_guide(self) -> float:
        """Half the guide's length [m], ``inf`` for a guide without ends."""
        return math.inf if self.guide_length is None else 0.5 * self.guide_length

    @property
    def inner_radius(self) -> float:
        """The slider's half-height H/2 [m]."""
        return 0.5 * self.slider_height

    @property
    def outer_radius(self) -> float:
        """The guide's half-width H/2 + c [m]."""
        return 0.5 * self.slider_height + self.guide_clearance

    @property
    def half_width(self) -> float:
        """The spatial slider's half-width B/2 [m] (0 for the planar joint)."""
        return 0.5 * self.slider_width if self.spatial else 0.0

    @property
    def channel_half_width(self) -> float:
        """The spatial channel's half-depth B/2 + c_z [m], its far and near walls' distance
        from the centre line (0 for the planar joint)."""
        return 0.5 * self.slider_width + self.clearance_width if self.spatial else 0.0

    @property
    def length(self) -> float | None:
        """The length of a rounded corner edge's line contact, ``corner_length`` [m]; None for
        a sharp or ball-rounded corner, which touches a wall at a point."""
        return self.corner_length

    @property
    def relative_curvature(self) -> float:
        """``1 / corner_radius`` [1/m], a rounded corner on a flat wall; ``ValueError`` for a
        sharp corner, which has no radius."""
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


def leave_guide(kin: CornerKinematics | BoxCornerKinematics, half_guide: float) -> CornerKinematics | BoxCornerKinematics:
    """``kin`` of a corner beyond the end of a guide ``2 half_guide`` long: no wall under it,
    its penetration ``-inf`` (module docstring); else ``kin`` as it is."""
    if abs(kin.ex) > half_guide:
        return kin._replace(delta=-math.inf)
    return kin


class BoxCornerKinematics(NamedTuple):
    """One corner-wall pair of the spatial joint in J0 (SI units).

    ``(ex, ey)`` the corner's coordinate along the axis and across its wall (``q_x`` and
    ``q_y`` or ``q_z``), ``ez`` its third coordinate; ``(nx, ny, nz)`` the wall's normal
    ``s e_a``; ``delta``, ``delta_dot`` the penetration and its rate; ``v_s`` the corner's
    slip over the wall (its velocity along the wall's plane), ``v_t`` its length; ``r`` the
    corner relative to the slider's centre, ``A c_k`` (the lever of its loads).
    """

    ex: float
    ey: float
    ez: float
    nx: float
    ny: float
    nz: float
    delta: float
    delta_dot: float
    v_s: V3
    v_t: float
    r: V3


def box_corner_kinematics(half_length: float, half_height: float, half_width: float, wall_y: float, wall_z: float,
                          corner: int, wall: int, p: V3, a: tuple[V3, V3, V3], dv: V3, dw: V3, w_j: V3
                          ) -> BoxCornerKinematics:
    """The kinematics of ``corner`` (:data:`BOX_CORNER_SIGNS`) against ``wall``
    (:data:`BOX_WALLS`) of a box ``2 half_length`` x ``2 half_height`` x ``2 half_width`` in a
    channel whose walls lie ``wall_y`` and ``wall_z`` from its centre line, the box at ``p``
    turned by the rotation ``a`` (rows; :func:`exuclear.spatial.rotation_xyz` of the
    connector's angles) relative to the guide (module docstring)."""
    sx, sy, sz = BOX_CORNER_SIGNS[corner]
    axis, s = BOX_WALLS[wall]
    c = (sx * half_length, sy * half_height, sz * half_width)
    r = (a[0][0] * c[0] + a[0][1] * c[1] + a[0][2] * c[2],        # A c_k
         a[1][0] * c[0] + a[1][1] * c[1] + a[1][2] * c[2],
         a[2][0] * c[0] + a[2][1] * c[1] + a[2][2] * c[2])
    q = (p[0] + r[0], p[1] + r[1], p[2] + r[2])                  # the corner in J0
    delta = s * q[axis] - (wall_y if axis == 1 else wall_z)
    # the corner's velocity over the guide's point under it: dv + dw x r - w_j x p
    wr, wp = cross(dw, r), cross(w_j, p)
    v = (dv[0] + wr[0] - wp[0], dv[1] + wr[1] - wp[1], dv[2] + wr[2] - wp[2])
    v_s = (v[0], 0.0 if axis == 1 else v[1], 0.0 if axis == 2 else v[2])  # along the wall's plane
    v_t = math.sqrt(v_s[0] * v_s[0] + v_s[1] * v_s[1] + v_s[2] * v_s[2])
    n = (0.0, s if axis == 1 else 0.0, s if axis == 2 else 0.0)
    return BoxCornerKinematics(q[0], q[axis], q[3 - axis], n[0], n[1], n[2], delta, s * v[axis], v_s, v_t, r)


def add_box_corner_loads(loads: list[float], kin: BoxCornerKinematics, f_n: float, f_t: float) -> None:
    """Add one spatial pair's loads to ``loads`` = [force (3), torque (3), correction (3)]: on
    the guide ``F = F_N n + F_T v_s / |v_s|`` (the wall pushed along its normal, dragged along
    the slip), the torque ``r x F``; the guide's moment beyond it, ``p x F``, is added at the
    end (:func:`exuclear.spatial.finish_loads`), as :func:`add_corner_loads` in the plane."""
    t_force = (0.0, 0.0, 0.0)
    if kin.v_t > 0.0:
        scale = f_t / kin.v_t
        t_force = (scale * kin.v_s[0], scale * kin.v_s[1], scale * kin.v_s[2])
    force = (f_n * kin.nx + t_force[0], f_n * kin.ny + t_force[1], f_n * kin.nz + t_force[2])
    moment = cross(kin.r, force)
    for i in range(3):
        loads[i] += force[i]
        loads[3 + i] += moment[i]
