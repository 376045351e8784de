"""Where a clearance joint's journal starts: its initial penetration, and the refusal of a
journal that starts outside its bearing, which both paths give (:func:`exuclear.simulate`
before its run, a plain ``mbs.SolveDynamic`` through the joint's run-start record, whose
kernel then stops the run at its first evaluation)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import exudyn as exu
import numpy as np

from ..prismatic import box_corner_kinematics, corner_kinematics, leave_guide

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

#: What the builders' own arguments place (:attr:`ClearanceJointHandle.placed_by`): named in
#: the refusal of a journal outside its bearing, so that it points at the user's call.
PLACED_BY_POSITION = "the joint's `position` and the initial coordinates of the bodies in `itemNumbers`"
PLACED_BY_MARKERS = "the positions of `markerNumbers` on their bodies and the bodies' initial coordinates"
PLACED_BY_POINTS = "`journal_point` / `bearing_point` and the bodies' initial coordinates"
#: Joint type -> (outer, inner) part, as messages name them.
PARTS = {"revolute": ("bearing", "journal"), "spherical": ("socket", "ball"), "prismatic": ("guide", "slider"),
         "pin-slot": ("slot", "pin")}


def initial_penetration(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> float:
    """Penetration ``e - c`` [m] of a joint in the initial configuration: a revolute joint's in the
    plane of its joint frame, a spherical joint's in space, a translational joint's deepest corner, a pin's from its slot's centre segment."""
    ref = exu.ConfigurationType.Initial
    b, j = handle.markerNumbers
    p_b = np.asarray(mbs.GetMarkerOutput(b, exu.OutputVariableType.Position, configuration=ref), dtype=float)
    p_j = np.asarray(mbs.GetMarkerOutput(j, exu.OutputVariableType.Position, configuration=ref), dtype=float)
    a_b = np.asarray(mbs.GetMarkerOutput(b, exu.OutputVariableType.RotationMatrix, configuration=ref),
                     dtype=float).reshape(3, 3)
    frame = a_b @ np.asarray(mbs.GetObject(handle.objectNumber)["rotationMarker0"], dtype=float)
    local = frame.T @ (p_j - p_b)
    if handle.joint_type == "prismatic":
        a_j = np.asarray(mbs.GetMarkerOutput(j, exu.OutputVariableType.RotationMatrix, configuration=ref),
                         dtype=float).reshape(3, 3)
        turn = frame.T @ a_j  # the slider marker's frame is the joint frame in the reference configuration
        g = handle.joint.geometry
        if g.spatial:  # the box turned by the slider marker's frame in the joint frame
            p, zero = (local[0], local[1], local[2]), (0.0, 0.0, 0.0)
            rows = tuple(tuple(float(v) for v in row) for row in turn)
            kins = [box_corner_kinematics(0.5 * g.slider_length, g.inner_radius, g.half_width, g.outer_radius,
                                          g.channel_half_width, corner, wall, p, rows, zero, zero, zero)
                    for corner, wall in g.pairs]
        else:
            kins = [corner_kinematics(0.5 * g.slider_length, g.inner_radius, g.outer_radius, corner, wall, local[0],
                                      local[1], math.atan2(turn[1, 0], turn[0, 0]), 0.0, 0.0, 0.0, 0.0)
                    for corner, wall in g.pairs]
        return max(leave_guide(k, g.half_guide).delta for k in kins)
    if handle.joint_type == "pin-slot":  # from the slot's centre segment (exuclear/slot.py)
        half = 0.5 * handle.joint.geometry.slot_length
        local[0] -= min(max(local[0], -half), half)
    ecc = np.linalg.norm(local) if handle.joint_type == "spherical" else math.hypot(local[0], local[1])
    return float(ecc - handle.joint.geometry.clearance)


def outside_bearing(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> str:
    """Why a run of ``mbs`` cannot start where the joint's journal starts outside its bearing
    (a penetration beyond the joint's ``maxPenetration``), naming the arguments that placed
    it; ``""`` where it starts within (or its markers cannot be read yet)."""
    try:
        delta = initial_penetration(mbs, handle)
    except Exception:  # not assembled yet, or a marker Exudyn cannot evaluate: the run's own checks speak
        return ""
    if not delta > handle.max_penetration:
        return ""
    c = handle.joint.geometry.clearance
    outer, inner = PARTS[handle.joint_type]
    return (f"the {inner} starts outside its {outer} (penetration {delta:.4g} m, {delta / c:.3g} clearances, beyond "
            f"the limit {handle.max_penetration:.3g} m); place the {inner} centre within the clearance "
            f"({c:.3g} m) of the {outer} centre: check {handle.placed_by} (in metres)")
