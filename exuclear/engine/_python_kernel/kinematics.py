"""The contact kinematics the kernel evaluates: those of :mod:`exuclear.geometry` (the planar
joint, eqs. (1)-(8)), :mod:`exuclear.spatial` (a slice and an end face, eqs. (33)-(40),
(48)-(51)) and :mod:`exuclear.spherical` (the ball, eqs. (93)-(96)) and :mod:`exuclear.prismatic` (a slider's
corner against a guide's wall, a box's against a channel's) and :mod:`exuclear.slot` (a pin in a slot).  The compiled kernel's ``kinematics.hpp``."""
from __future__ import annotations

import math

from ...geometry import ContactKinematics, contact_kinematics, joint_loads
from ...spatial import (
    FACE_SIDES,
    V3,
    FaceKinematics,
    SliceKinematics,
    add_face_loads,
    add_slice_loads,
    face_kinematics,
    finish_loads,
    friction_components,
    journal_axis,
    rotation_xyz,
    slice_centres,
    slice_kinematics,
)
from ...prismatic import (
    BoxCornerKinematics,
    CornerKinematics,
    add_box_corner_loads,
    add_corner_loads,
    box_corner_kinematics,
    corner_kinematics,
    leave_guide,
)
from ...slot import SlotKinematics, slot_kinematics
from ...spherical import BallKinematics, add_ball_loads, ball_kinematics

__all__ = ["FACE_SIDES", "V3", "BallKinematics", "BoxCornerKinematics", "ContactKinematics", "CornerKinematics",
           "FaceKinematics", "Kinematics", "SliceKinematics", "SlotKinematics", "add_ball_loads", "add_box_corner_loads",
           "add_corner_loads", "add_face_loads", "add_slice_loads", "ball_kinematics", "box_corner_kinematics",
           "contact_kinematics", "corner_kinematics", "face_kinematics", "finish_loads", "finite",
           "friction_components", "joint_loads", "journal_axis", "leave_guide", "rotation_xyz", "slice_centres",
           "slice_kinematics", "slot_kinematics"]

Kinematics = (ContactKinematics | SliceKinematics | FaceKinematics | BallKinematics | CornerKinematics
              | BoxCornerKinematics | SlotKinematics)


def finite(kin: Kinematics) -> bool:
    return all(math.isfinite(v) for v in (kin.ex, kin.ey, kin.delta_dot, kin.v_t))
