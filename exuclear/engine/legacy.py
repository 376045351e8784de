"""The body-point builder of exuclear's first form, deprecated: ``add_clearance_joint``.

It placed a planar joint by a point in each body's frame (journal body first) and is kept
so that old scripts run, with a ``DeprecationWarning`` that writes out the call to use
instead (:func:`~exuclear.engine.connector.CreateClearanceJoint` with the bearing body
first, or :func:`~exuclear.engine.connector.AddClearanceJoint` with rigid markers).  It
builds those markers and calls ``AddClearanceJoint``; nothing else depends on it.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import exudyn as exu
from exudyn.itemInterface import MarkerBodyRigid, MarkerKinematicTreeRigid

from ..checks import check_positive
from ..joint import ClearanceJoint
from .arguments import check_system, object_type
from .connector import AddClearanceJoint
from .handle import ClearanceJointHandle
from .placement import PLACED_BY_POINTS


def add_clearance_joint(
    mbs: exu.MainSystem,
    journal_body: Any,
    bearing_body: Any,
    *,
    journal_point: Sequence[float] = (0.0, 0.0),
    bearing_point: Sequence[float] = (0.0, 0.0),
    journal_link: int | None = None,
    bearing_link: int | None = None,
    joint: ClearanceJoint | None = None,
    record: bool = True,
    name: str = "",
    max_penetration: float | None = None,
    backend: str | None = None,
    bearing_rotates: bool | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle:
    """A planar clearance joint from body-frame points, the journal body first.

    .. deprecated:: 0.1.0
        Use :func:`~exuclear.engine.connector.CreateClearanceJoint` (bearing body first,
        ``maxPenetration``), or :func:`~exuclear.engine.connector.AddClearanceJoint` with
        rigid markers; the warning names the call to write.

    The journal's centre is ``journal_point`` (x, y) in ``journal_body``'s frame, the
    bearing's ``bearing_point`` in ``bearing_body``'s; an ``ObjectKinematicTree`` body
    needs the link index (``journal_link`` / ``bearing_link``).  The axis is z.  Builds
    the rigid markers and calls :func:`AddClearanceJoint`.
    """
    warnings.warn(_replacement(journal_body, bearing_body, journal_point, bearing_point, journal_link, bearing_link,
                               max_penetration, bearing_rotates), DeprecationWarning, stacklevel=2)
    check_system(mbs)
    if max_penetration is not None:
        check_positive("max_penetration", max_penetration)
    markers = [_point_marker(mbs, bearing_body, bearing_point, bearing_link, "bearing"),
               _point_marker(mbs, journal_body, journal_point, journal_link, "journal")]
    if object_type(mbs, journal_body, "journal") == "Ground" and object_type(mbs, bearing_body, "bearing") == "Ground":
        raise ValueError("`journal_body` and `bearing_body` are both the ground: one must be a moving body")
    if journal_body == bearing_body and journal_link == bearing_link:
        raise ValueError("`journal_body` and `bearing_body` are the same body")
    handle = AddClearanceJoint(mbs, markers, name=name, joint=joint, backend=backend, maxPenetration=max_penetration,
                               bearingRotates=bearing_rotates, record=record, **joint_parameters)
    handle.placed_by = PLACED_BY_POINTS
    return handle


def _replacement(journal_body: Any, bearing_body: Any, journal_point: Any, bearing_point: Any, journal_link: Any,
                 bearing_link: Any, max_penetration: Any, bearing_rotates: Any) -> str:
    """The deprecation message of :func:`add_clearance_joint`: the call to write instead."""
    options = "".join(f", {k}={v!r}" for k, v in (("maxPenetration", max_penetration),
                                                    ("bearingRotates", bearing_rotates)) if v is not None)
    markers = (f"exuclear.AddClearanceJoint(mbs, markerNumbers=[bearing_marker, journal_marker]{options}, ...) with "
               f"rigid markers at bearing_point {tuple(bearing_point)!r} and journal_point {tuple(journal_point)!r} "
               "(MarkerBodyRigid, or MarkerKinematicTreeRigid on a kinematic-tree link)")
    if journal_link is not None or bearing_link is not None:
        return f"exuclear.engine.add_clearance_joint is deprecated; write {markers}"
    position = [*(float(v) for v in bearing_point), 0.0]
    return ("exuclear.engine.add_clearance_joint(mbs, journal_body, bearing_body, ...) is deprecated; write "
            f"exuclear.CreateClearanceJoint(mbs, itemNumbers=[{bearing_body!r}, {journal_body!r}], "
            f"position={position!r}, useGlobalFrame=False{options}, ...the same joint parameters) (the bearing "
            "body first; journal and bearing centred at `position`, in the bearing body's frame), or, where the "
            f"two points differ in the reference configuration, {markers}")


def _point_marker(mbs: exu.MainSystem, body: Any, point: Sequence[float], link: int | None, role: str) -> Any:
    """A rigid marker at ``point`` (local x, y) of ``body`` (its link ``link`` on a kinematic
    tree); ``ValueError`` naming the ``role``'s argument for a bad point, body or link."""
    try:
        x, y = (float(v) for v in point)
    except (TypeError, ValueError):
        raise ValueError(f"`{role}_point` must be two finite numbers (local x, y), got {point!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"`{role}_point` must be two finite numbers (local x, y), got {point!r}")
    try:
        item = mbs.GetObject(body)
    except Exception:  # Exudyn raises its own error types for a bad index
        raise ValueError(f"`{role}_body` {body!r} is not an object of this MainSystem") from None
    kind = item["objectType"]
    if kind == "KinematicTree":
        n_links = len(item["linkParents"])
        if isinstance(link, bool) or not isinstance(link, int) or not 0 <= link < n_links:
            raise ValueError(f"`{role}_link` must be a link index 0..{n_links - 1} of the kinematic tree, got {link!r}")
        return mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=body, linkNumber=link, localPosition=[x, y, 0.0]))
    if link is not None:
        raise ValueError(f"`{role}_link` applies to an ObjectKinematicTree only, but `{role}_body` is a {kind}")
    try:
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[x, y, 0.0]))
    except Exception:  # Exudyn refuses a rigid marker on a body that has none
        raise ValueError(f"`{role}_body` is an object of type {kind!r}, which has no rigid body marker") from None
