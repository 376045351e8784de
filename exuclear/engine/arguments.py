"""Checks of the clearance-joint builders' arguments (:mod:`exuclear.engine.connector`):
each raises ``ValueError`` naming the argument and the rule it broke, before any item is
added to the system."""
from __future__ import annotations

import warnings
from typing import Any

import exudyn as exu
import numpy as np

from ..checks import check_positive
from ..joint import ClearanceJoint, make_joint
from ..spatial import ShoulderGeometry
from .modes import resolve_contact_mode

#: Recommended number of slices of a spatial joint (docs/physics.md section 9.3): total
#: force within 0.22 % and restoring moment within 0.47 % while the contact zone spans at
#: least 8 slices; raise it for shorter edge contacts (L / N <= contact length / 8).
DEFAULT_SLICES = 20
#: An axis whose length differs from 1 by more than this is normalised with a warning.
AXIS_UNIT_TOLERANCE = 1e-9

#: Default penetration bound, the larger of these fractions of the clearance and of the
#: journal radius: it catches blow-ups (a journal sinking through its bearing), not hard
#: impacts (a 1.3 m/s crank-pin impact exceeds 10 % of its 0.1 mm clearance; a 1 um
#: clearance sees 0.4 um of static penetration).
PENETRATION_LIMIT_CLEARANCE = 0.5
PENETRATION_LIMIT_RADIUS = 1e-3

#: Exudyn marker types that carry a position and an orientation.
RIGID_MARKERS = ("BodyRigid", "NodeRigid", "KinematicTreeRigid", "SuperElementRigid")

#: Object types on which Exudyn 1.13 builds a ``MarkerBodyRigid`` that cannot run: the
#: solver stops at the first step with "illegal call to CObjectBody::GetAngularVelocityLocal"
#: (the element gives a connector no angular velocity).  Their nodes are rigid-body nodes,
#: which a ``MarkerNodeRigid`` carries.
NO_RIGID_BODY_MARKER = ("BeamGeometricallyExact2D",)
#: Object types without an orientation: Exudyn refuses a ``MarkerBodyRigid`` on them when the
#: system is assembled ("requires an object with orientation (rotation) information").
NO_ORIENTATION = ("MassPoint", "MassPoint2D")


def default_penetration_limit(geometry: Any) -> float:
    """The default penetration bound [m] of a joint (:data:`PENETRATION_LIMIT_CLEARANCE`)."""
    return max(PENETRATION_LIMIT_CLEARANCE * geometry.clearance, PENETRATION_LIMIT_RADIUS * geometry.inner_radius)


def check_system(mbs: Any) -> None:
    if not isinstance(mbs, exu.MainSystem):
        raise ValueError(f"`mbs` must be an exudyn MainSystem (exudyn.SystemContainer().AddSystem()), "
                         f"got {type(mbs).__name__}")


def vector3(name: str, value: Any) -> np.ndarray:
    try:
        v = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be 3 finite numbers, got {value!r}") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"`{name}` must be 3 finite numbers, got {value!r}")
    return v


def check_contact_mode(contact_mode: Any) -> str:
    """The mode ``contact_mode`` asks for (None: the environment's, else ``"compliant"``),
    checked (:func:`exuclear.engine.modes.resolve_contact_mode`)."""
    return resolve_contact_mode(contact_mode)


def check_axis(axis: Any) -> np.ndarray:
    """The bearing axis as given (non-zero); warns where it is not a unit vector."""
    axis_local = vector3("axis", axis)
    if not np.linalg.norm(axis_local) > 0.0:
        raise ValueError(f"`axis` must not be zero, got {axis!r}")
    length = float(np.linalg.norm(axis_local))
    if abs(length - 1.0) > AXIS_UNIT_TOLERANCE:
        warnings.warn(f"`axis` {axis!r} is not a unit vector (length {length:.6g}); it is normalised", UserWarning,
                      stacklevel=3)
    return axis_local


def object_type(mbs: exu.MainSystem, item: Any, role: str) -> str:
    try:
        return mbs.GetObject(item)["objectType"]
    except Exception:  # Exudyn raises its own error types for a bad index
        raise ValueError(f"`itemNumbers` {role} {item!r} is not an object of this MainSystem") from None


def check_markers(mbs: exu.MainSystem, markerNumbers: Any) -> None:  # noqa: N803 - Exudyn's argument name
    if isinstance(markerNumbers, (str, bytes)) or len(markerNumbers) != 2:
        raise ValueError(f"`markerNumbers` must be [bearing marker, journal marker], got {markerNumbers!r}")
    for k, marker in enumerate(markerNumbers):
        check_marker(mbs, marker, f"`markerNumbers[{k}]`")
    if int(markerNumbers[0]) == int(markerNumbers[1]):
        raise ValueError("`markerNumbers` names the same marker twice")


def check_marker(mbs: exu.MainSystem, marker: Any, where: str) -> None:
    """``ValueError`` unless ``marker`` is a rigid marker of ``mbs`` that can carry a joint."""
    try:
        kind = mbs.GetMarker(marker)["markerType"]
    except Exception:  # Exudyn raises its own error types for a bad index
        raise ValueError(f"{where} {marker!r} is not a marker of this MainSystem") from None
    if kind not in RIGID_MARKERS:
        raise ValueError(f"{where} is a {kind} marker; a clearance joint needs rigid markers (position and "
                         f"orientation): {', '.join(RIGID_MARKERS)}")
    if kind == "BodyRigid":
        check_rigid_body_marker(mbs, mbs.GetMarker(marker)["bodyNumber"], f"{where} (a MarkerBodyRigid)")


def check_rigid_body_marker(mbs: exu.MainSystem, body: Any, where: str) -> None:
    """``ValueError`` where ``body`` cannot carry a running ``MarkerBodyRigid``
    (:data:`NO_RIGID_BODY_MARKER`), naming the marker to give instead."""
    item = mbs.GetObject(body)
    kind = item["objectType"]
    if kind in NO_ORIENTATION:
        raise ValueError(f"{where} is object {int(body)}, an Object{kind}, a point mass without orientation: a "
                         "clearance joint needs a body with a rigid marker (position and orientation), e.g. "
                         "mbs.CreateRigidBody")
    if kind in NO_RIGID_BODY_MARKER:
        nodes = [int(n) for n in item.get("nodeNumbers", [])]
        raise ValueError(f"{where} is on object {int(body)}, an Object{kind}, on which Exudyn's MarkerBodyRigid fails at "
                         "the first step ('illegal call to CObjectBody::GetAngularVelocityLocal'): put the joint on "
                         f"one of the element's nodes {nodes} with a MarkerNodeRigid (nodeNumber=...), and give that "
                         "marker in `itemNumbers` of exuclear.CreateClearanceJoint or in `markerNumbers` of "
                         "exuclear.AddClearanceJoint")


def check_flags(name: Any, bearingRotates: Any, **flags: Any) -> None:  # noqa: N803 - Exudyn's argument name
    if not isinstance(name, str):
        raise ValueError(f"`name` must be a string, got {name!r}")
    if bearingRotates is not None and not isinstance(bearingRotates, bool):
        raise ValueError(f"`bearingRotates` must be True, False or None (decide from the marker), got {bearingRotates!r}")
    for flag, value in flags.items():
        if not isinstance(value, bool):
            raise ValueError(f"`{flag}` must be True or False, got {value!r}")


def physics(joint: ClearanceJoint | None, joint_parameters: dict) -> ClearanceJoint:
    """The joint's physics: ``joint`` as given, or built by :func:`exuclear.make_joint`."""
    if joint is None:
        return make_joint(**joint_parameters)
    if joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    if not isinstance(joint, ClearanceJoint):
        raise ValueError(f"`joint` must be a ClearanceJoint, got {type(joint).__name__}")
    return joint


def check_wear(joint: ClearanceJoint, slices: int, backend: str) -> None:
    """``ValueError`` where the joint's wear cannot be modelled as asked: a starting profile
    of slices x nodes (:class:`exuclear.Wear`) whose rows are not the spatial joint's slices,
    or one given to the planar joint (docs/physics.md section 11.7)."""
    wear = joint.wear
    if wear is None:
        return
    for name in ("bearing", "journal"):
        rows = wear.profile_rows(name)
        if rows and not slices:
            raise ValueError(f"the wear's `{name}` profile has {rows} rows (slices x nodes, a spatial joint's); the "
                             f"planar joint (slices=None) takes one profile of {wear.nodes} depths")
        if rows and rows != slices:
            raise ValueError(f"the wear's `{name}` profile has {rows} rows but the joint has {slices} slices: give "
                             f"one row per slice, or one profile of {wear.nodes} depths for every slice")
    if backend == "compiled" and not kernel_has_wear(slices):
        raise ValueError("`wear` needs backend='python': this build's compiled kernel has no wear"
                         + (" per slice" if slices else ""))


def kernel_has_wear(slices: int = 0) -> bool:
    """Whether the compiled kernel wears the joint (a spatial joint's slices: ``slices`` > 0)."""
    from . import kernel

    if kernel.COMPILED is None or not hasattr(kernel.COMPILED, "wear_profiles"):
        return False
    return not slices or getattr(kernel.COMPILED, "SLICE_WEAR", False)


def check_slices(slices: Any) -> int:
    """0 for the planar joint (None or 0), else the number of slices (an int >= 1)."""
    if slices is None:
        return 0
    if isinstance(slices, bool) or not isinstance(slices, (int, np.integer)):
        raise ValueError(f"`slices` must be None (planar joint) or an integer >= 1, got {slices!r}")
    if slices < 0:
        raise ValueError(f"`slices` must be None (planar joint) or an integer >= 1, got {slices!r}")
    return int(slices)


def check_shoulders(axial_clearance: Any, shoulder_radius: Any, slices: int, constrain_axial: Any,
                    joint: ClearanceJoint) -> ShoulderGeometry | None:
    """The axial clearance of docs/physics.md section 9.6, or None where none is given."""
    if axial_clearance is None:
        if shoulder_radius is not None:
            raise ValueError(f"`shoulder_radius` ({shoulder_radius!r}) is given without `axial_clearance`; give both "
                             "for shoulder contact, or neither")
        return None
    play = check_positive("axial_clearance", axial_clearance)
    if not slices:
        raise ValueError("`axial_clearance` needs the spatial joint: give `slices` (e.g. "
                         f"{DEFAULT_SLICES}); the planar joint has no axial direction")
    if shoulder_radius is None:
        raise ValueError("`axial_clearance` needs the shoulder geometry: give `shoulder_radius`, the outer radius [m] "
                         "of the annulus where a shoulder meets a bearing end face (> `bearing_radius`)")
    r_s = check_positive("shoulder_radius", shoulder_radius)
    r_b = joint.geometry.bearing_radius
    if not r_s > r_b:
        raise ValueError(f"`shoulder_radius` must exceed `bearing_radius` {r_b} (the end face's annulus starts at the "
                         f"bearing radius), got {r_s}")
    if constrain_axial is True:
        raise ValueError("`constrainAxial=True` holds the journal axially, which leaves `axial_clearance` nothing to "
                         "do: give one or the other")
    return ShoulderGeometry(play, r_s, r_b)
