"""The planar translational clearance joint as Exudyn items: ``CreatePrismaticClearanceJoint``.

A slider (on the second body) in a guide (on the first), the clearance form of
``mbs.CreatePrismaticJoint`` for motion in a plane.  The joint is the revolute joint's
connector with the slider's eight corner-wall pairs (:mod:`exuclear.prismatic`): the same
items (:mod:`~exuclear.engine.items`), kernels, history, step control, notes and outputs;
its type (``joint.geometry.joint_type``) tells the kernels which contacts to build.  The
joint frame has ``x`` along ``axis``, ``z`` the global z axis (the plane's normal), and is
carried by both markers in the reference configuration.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid

from ..joint import ClearanceJoint, make_prismatic_joint
from ..prismatic import PAIRS, GuideGeometry
from .arguments import check_axis, check_flags, check_system
from .connector import _orientation_is_fixed, joint_items, kernel_settings
from .drawing import slider_drawing_function
from .handle import ClearanceJointHandle
from .items import add_connectors, finish_items
from .layout import pair_data_columns
from .modes import choose_mode
from .placement import PLACED_BY_POSITION

#: Largest z component of a unit ``axis``: the planar joint slides in the global x-y plane.
PLANE_TOLERANCE = 1e-12


def CreatePrismaticClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
    mbs: exu.MainSystem,
    name: str = "",
    itemNumbers: Sequence[Any] = (None, None),  # noqa: N803 - Exudyn's argument names
    position: Sequence[float] | None = None,
    axis: Sequence[float] = (1.0, 0.0, 0.0),
    useGlobalFrame: bool = True,  # noqa: N803
    show: bool = True,
    bodyNumbers: Sequence[Any] | None = None,  # noqa: N803
    *,
    joint: ClearanceJoint | None = None,
    backend: str | None = None,
    maxPenetration: float | None = None,  # noqa: N803
    bearingRotates: bool | None = None,  # noqa: N803
    record: bool = True,
    contact_mode: str | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle:
    """Create a planar translational clearance joint, as ``mbs.CreatePrismaticJoint``
    creates an ideal one: the guide on ``itemNumbers[0]``, the slider on ``itemNumbers[1]``,
    the slider's centre at ``position`` (a point of the guide's centre line) in the
    reference configuration, sliding along ``axis``.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system; call before ``mbs.Assemble()``.
    name : str
        The joint's name (its connector's).
    itemNumbers : [guide body, slider body]
        Each a body with a rigid marker (the ground, ``ObjectRigidBody2D``,
        ``ObjectRigidBody``, the bodies of ``mbs.CreateRigidBody``); the slider's body
        reference point is anywhere, its centre is ``position``.
    position : 3 floats, optional
        The slider's centre [m] in the reference configuration: global
        (``useGlobalFrame=True``) or in item 0's frame; default the global origin.
    axis : 3 floats
        The sliding direction, in the global x-y plane (the joint's plane of motion):
        global, or in item 0's frame; default x.
    useGlobalFrame, show, bodyNumbers
        As in ``mbs.CreatePrismaticJoint`` (``show``: draw the slider and the guide's walls;
        only a renderer draws).
    joint : ClearanceJoint, optional
        The physics, ready built (:func:`exuclear.joint.make_prismatic_joint`); else built
        from the keyword arguments ``slider_length``, ``slider_height``, ``clearance`` (per
        side: the guide is ``slider_height + 2 clearance`` wide), ``stiffness`` (a corner's
        ``K`` [N/m^n], or ``"hertz"`` with ``corner_radius``, or ``"dubowsky-freudenstein"``
        with ``corner_radius`` and ``corner_length``, and ``slider_material``,
        ``guide_material``, ``E_star``), ``exponent`` (default 1.5), ``damping`` (default
        ``"lankarani-nikravesh"``) with ``cr``, ``friction``, ``v_min``.
    backend, maxPenetration, bearingRotates, record, contact_mode
        As in :func:`exuclear.CreateClearanceJoint` (``bearingRotates``: whether the guide
        can turn; its spin moves the walls under the corners; ``contact_mode="impulse"``
        is refused: it covers the revolute joint).

    Returns
    -------
    ClearanceJointHandle
        ``objectNumber`` is the connector; ``outputs()`` has :data:`OUTPUT_COLUMNS` per
        corner-wall pair (shape (times, 8), :data:`exuclear.prismatic.PAIRS`' order) and
        ``force``, ``moment`` (the load on the guide); ``impacts()`` names each
        contact's corner and wall (:class:`exuclear.history.PairImpact`); ``notes`` and
        ``counts`` as for the revolute joint.
    """
    check_system(mbs)
    check_flags(name, bearingRotates, record=record, show=show)
    joint = _physics(joint, joint_parameters)
    backend, maxPenetration = kernel_settings(joint, backend, maxPenetration)
    choose_mode(contact_mode, joint, None, backend, name, joint_type=joint.geometry.joint_type)
    markers = plane_markers(mbs, itemNumbers, bodyNumbers, ("guide", "slider"), position, axis, useGlobalFrame,
                            "CreatePrismaticJoint")

    handle = ClearanceJointHandle(mbs, joint, name, backend, maxPenetration)
    handle.placed_by = PLACED_BY_POSITION
    handle.markerNumbers = markers
    handle._axis_local = np.array([0.0, 0.0, 1.0])
    if bearingRotates is None:
        bearingRotates = not _orientation_is_fixed(mbs, markers[0])
    add_connectors(mbs, handle, markers, np.eye(3).tolist(), bearingRotates, len(pair_data_columns(len(PAIRS))), show,
                   joint.geometry.slider_height)
    finish_items(mbs, handle, slider_drawing_function if show else None, record, load_sensors=True)
    return handle


def plane_markers(mbs: exu.MainSystem, itemNumbers: Any, bodyNumbers: Any, roles: tuple[str, str],  # noqa: N803
                  position: Any, axis: Any, useGlobalFrame: Any, exudyn_name: str) -> list:  # noqa: N803
    """The two markers of a planar joint on the bodies ``itemNumbers`` (checked as
    :func:`~exuclear.engine.connector.joint_items` checks them, ``roles`` naming them), both
    at ``position`` with the joint frame: ``x`` along ``axis`` (in the global x-y plane),
    ``z`` the global z axis (the plane's normal)."""
    axis_given = check_axis(axis)
    items = joint_items(mbs, itemNumbers, bodyNumbers, roles, position, useGlobalFrame, exudyn_name)
    if "marker" in items.kinds:
        raise ValueError(f"`itemNumbers` must be [{roles[0]} body, {roles[1]} body]: the joint places its own markers "
                         "at `position`")
    p, a0 = items.centre, items.poses[0][1]
    x = (axis_given if useGlobalFrame else a0 @ axis_given) / np.linalg.norm(axis_given)
    if abs(x[2]) > PLANE_TOLERANCE:
        raise ValueError(f"`axis` must lie in the global x-y plane (the planar joint's plane of motion), got {axis!r}")
    z = np.array([0.0, 0.0, 1.0])
    frame = np.column_stack((x, np.cross(z, x), z))  # the joint frame's axes in the global frame
    return [mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localHT=exu.HT(
        rotation=rot.T @ frame, translation=rot.T @ (p - pos)))) for item, (pos, rot) in zip(items.items, items.poses)]


def _physics(joint: ClearanceJoint | None, joint_parameters: dict) -> ClearanceJoint:
    """The joint's physics: ``joint`` as given (a slider in a guide), or built by
    :func:`exuclear.joint.make_prismatic_joint`."""
    if joint is None:
        for required in ("slider_length", "slider_height", "clearance", "stiffness"):
            if required not in joint_parameters:
                raise ValueError(f"`{required}` is required: the translational clearance joint is a slider "
                                 "(`slider_length` x `slider_height`, m) in a guide with `clearance` per side (m), "
                                 "its corners' law K delta^n with `stiffness` K (N/m^n)")
        return make_prismatic_joint(**joint_parameters)
    if joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    if not isinstance(joint, ClearanceJoint) or not isinstance(joint.geometry, GuideGeometry):
        raise ValueError("`joint` must be a translational ClearanceJoint (exuclear.joint.make_prismatic_joint), got "
                         f"{joint!r}")
    return joint
