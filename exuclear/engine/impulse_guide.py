"""The translational joints in the impulse contact mode (:mod:`~exuclear.engine.impulse`): a
slider's corners against its guide's walls, each a one-contact pair of the mode.

A corner against the two opposite walls across one axis ``a`` of the guide's joint frame
(the planar slider: y; the spatial box: y and z, separately) is a contact pair as the mode
sees it (:mod:`~exuclear.engine.impulse_pairs`): its eccentricity is ``e = d_a a``, with
``d`` the corner's offset from the guide's centre point in the guide's frame, so that
``|e|`` is the corner's distance from the guide's mid-plane across ``a``; it touches a wall
at ``|e| = w`` (``w = H/2 + c`` across y, ``B/2 + c_z`` across z: the wall's distance from
the mid-plane, docs/physics.md section 14), its normal ``sign(d_a) a`` points into the wall
it approaches, and its gap's rate is the corner's velocity (a point of the slider's body,
``v + omega x r``) against that of the guide's material point ``S`` at the corner's foot on
the mid-plane.  The gap ``|e| - w`` is the compliant joint's penetration of that corner on
that wall (:func:`exuclear.prismatic.corner_kinematics`).

A finite guide (``guide_length``): a corner beyond the guide's end along its axis has no wall
under it, as in the compliant joint (:func:`exuclear.prismatic.leave_guide`): its pair is
open (its gap ``-inf``), the step in which a held corner passes the end is computed again
without its condition, and a corner that comes back inside and meets a wall is an impact (or
a resting contact's onset) again.

The corners are held together as a joint's several contacts
(:mod:`~exuclear.engine.impulse_group`): two corners of a slider thrown flat at a wall hit
in one step, a slider resting flat holds two corners, a box four.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import exudyn as exu
import numpy as np

from ..joint import ClearanceJoint
from ..prismatic import (
    BOX_CORNER_NAMES,
    BOX_CORNER_SIGNS,
    BOX_WALL_NAMES,
    BOX_WALLS,
    CORNER_NAMES,
    CORNER_SIGNS,
    WALL_NAMES,
    WALL_SIDES,
    GuideGeometry,
)
from .condition import Poses
from .impulse_group import ImpulsePairsHandle
from .impulse_pairs import Eccentricity

#: The guide's axes a pair acts across, as the joint frame's columns.
Y, Z = 1, 2


@dataclass(frozen=True)
class CornerPair:
    """A slider's corner against the guide's two walls across the joint frame's axis
    ``axis`` (:data:`Y` or :data:`Z`): ``corner`` [m] the corner in the slider's joint frame
    (marker 1's), ``reach`` [m] the walls' distance from the guide's mid-plane, ``clearance``
    [m] the play across ``axis`` (module docstring); ``name`` the corner's, ``walls`` the
    names of the walls at ``-reach`` and ``+reach``; ``plane`` the guide's plane normal
    (marker 0's frame) of a planar slider, whose corners slide along ``n x plane`` (the
    guide's axis), None for the box, whose corners slide in the wall's plane; ``half_guide``
    [m] half the guide's length (inf: walls without ends), beyond which along the guide's
    axis the corner has no wall under it."""

    corner: np.ndarray
    axis: int
    reach: float
    clearance: float
    name: str
    walls: tuple[str, str]
    plane: np.ndarray | None
    half_guide: float = math.inf
    #: the corner's share of the law: its own (each corner carries the whole law) ...
    share: ClassVar[float] = 1.0
    #: ... which is the joint's
    law: ClassVar[None] = None
    #: a corner is a point: its contact point is itself, with no spin term in its slip
    radius: ClassVar[float] = 0.0
    rotations: ClassVar[tuple[bool, bool]] = (True, True)

    @property
    def body(self) -> str:
        return f"corner {self.name}"

    def _across(self, poses: Poses) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
        """The corner's offset ``d_a`` across the axis from the guide's centre point, the
        axis (global), the corner's position from the guide's centre point and its arm from
        marker 1's point (global)."""
        (p0, p1), (r0, r1) = poses
        arm = r1 @ self.corner
        relative = p1 + arm - p0
        axis = r0[:, self.axis]
        return float(axis @ relative), axis, relative, arm

    def eccentricity(self, poses: Poses) -> Eccentricity:
        offset, axis, relative, arm = self._across(poses)
        e = offset * axis
        # S: the corner's foot on the mid-plane, a point of the guide's body; beyond the
        # guide's end no wall (exuclear.prismatic.leave_guide)
        along = float(poses.rotations[0][:, 0] @ relative)
        return Eccentricity(e, relative - e, arm, abs(along) <= self.half_guide)

    def contact_name(self, poses: Poses) -> str:
        """The corner and the wall it is nearest (by the sign of its offset across the axis),
        ``"corner front-lower / lower wall"``."""
        return f"corner {self.name} / {self.walls[bool(self._across(poses)[0] >= 0.0)]} wall"


def corner_pairs(geometry: GuideGeometry) -> list[tuple[str, CornerPair]]:
    """The pairs of a slider in its guide, with their names: the planar slider's four
    corners across y, the box's eight across y, then across z."""
    half = np.array([0.5 * geometry.slider_length, geometry.inner_radius, geometry.half_width])
    plane = None if geometry.spatial else np.array([0.0, 0.0, 1.0])  # the joint frame's z
    if not geometry.spatial:
        corners = [(name, np.array([sx, sy, 0.0]) * half) for name, (sx, sy) in zip(CORNER_NAMES, CORNER_SIGNS)]
        axes = [(Y, geometry.outer_radius, geometry.guide_clearance)]
    else:
        corners = [(name, np.array(signs) * half) for name, signs in zip(BOX_CORNER_NAMES, BOX_CORNER_SIGNS)]
        axes = [(Y, geometry.outer_radius, geometry.guide_clearance),
                (Z, geometry.channel_half_width, float(geometry.clearance_width))]
    return [(f"corner {name} / {' and '.join(_walls(geometry, axis))} walls",
             CornerPair(corner, axis, reach, play, name, _walls(geometry, axis), plane, geometry.half_guide))
            for axis, reach, play in axes for name, corner in corners]


def _walls(geometry: GuideGeometry, axis: int) -> tuple[str, str]:
    """The names of the walls across ``axis``, the one at -w, then the one at +w."""
    if not geometry.spatial:
        return WALL_NAMES[WALL_SIDES.index(-1.0)], WALL_NAMES[WALL_SIDES.index(1.0)]
    return tuple(BOX_WALL_NAMES[BOX_WALLS.index((axis, s))] for s in (-1.0, 1.0))  # type: ignore[return-value]


class ImpulseGuideHandle(ImpulsePairsHandle):
    """A translational clearance joint in the impulse mode; returned by
    :func:`exuclear.CreatePrismaticClearanceJoint` with ``contact_mode="impulse"``: an
    :class:`~exuclear.engine.impulse_group.ImpulsePairsHandle` whose pairs are the corners
    across each guide axis (:func:`corner_pairs`; ``"corner front-lower / lower and upper
    walls"``), whose impacts name corner and wall (``"corner front-lower / lower wall"``),
    and whose outputs' ``ecc_x``, ``ecc_y``, ``ecc_z`` are a corner's eccentricity ``d_a a``
    and ``penetration`` its penetration of the wall it is nearest (``-inf`` beyond a finite
    guide's end, where there is no wall)."""

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any]) -> None:
        super().__init__(mbs, joint, name, markers, corner_pairs(joint.geometry))


def add_impulse_guide(mbs: exu.MainSystem, joint: ClearanceJoint, name: str,
                      markers: Sequence[Any]) -> ImpulseGuideHandle:
    """The impulse mode's items for a slider in its guide between ``markers`` [guide, slider],
    both carrying the joint frame: a condition and a carrier per corner-axis pair."""
    return ImpulseGuideHandle(mbs, joint, name, markers)
