"""The translational clearance joint as Exudyn items: ``CreatePrismaticClearanceJoint``.

A slider (on the second body) in a guide (on the first), the clearance form of
``mbs.CreatePrismaticJoint``.  The joint is the revolute joint's connector with the
slider's corner-wall pairs (:mod:`exuclear.prismatic`): the same items
(:mod:`~exuclear.engine.items`), kernels, history, step control, notes and outputs; its
type (``joint.geometry.joint_type``) tells the kernels which contacts to build, and its
geometry whether it is planar (eight pairs) or spatial (``slider_width`` given: a box in a
channel, 32 pairs).  The joint frame has ``x`` along ``axis``; the planar joint's ``z`` is
the global z axis (the plane's normal), the spatial joint's ``y`` is ``height_axis`` (default
``z x axis``, the planar joint's ``y``).  Both markers carry it in the reference configuration.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid

from ..joint import ClearanceJoint, make_prismatic_joint
from ..prismatic import GuideGeometry
from .arguments import check_axis, check_flags, check_system, vector3
from .connector import _orientation_is_fixed, joint_items, kernel_settings
from .drawing import slider_drawing_function
from .handle import ClearanceJointHandle
from .items import add_connectors, finish_items
from .layout import pair_data_columns
from .impulse_guide import ImpulseGuideHandle, add_impulse_guide
from .modes import IMPULSE, choose_mode
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
    height_axis: Sequence[float] | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle | ImpulseGuideHandle:
    """Create a translational clearance joint, as ``mbs.CreatePrismaticJoint`` creates an
    ideal one: the guide on ``itemNumbers[0]``, the slider on ``itemNumbers[1]``, the
    slider's centre at ``position`` (a point of the guide's centre line) in the reference
    configuration, sliding along ``axis``.  Without ``slider_width`` the joint is planar (a
    rectangle between two walls, motion in the global x-y plane); with it, spatial (a box in
    a rectangular channel, 3D bodies).

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
        The sliding direction: global, or in item 0's frame; default x.  The planar joint's
        lies in the global x-y plane (its plane of motion).
    height_axis : 3 floats, optional
        The spatial joint's direction of ``slider_height`` (the joint frame's y; the width
        is along ``axis x height_axis``), in the frame of ``axis``; its part along ``axis``
        is dropped.  Default ``z x axis`` (the planar joint's y); required where ``axis``
        is along z.
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
        ``"lankarani-nikravesh"``) with ``cr``, ``friction``, ``v_min``; ``slider_width``
        [m] makes it the spatial joint (a box in a channel ``slider_width + 2 clearance_width``
        deep, ``clearance_width`` default ``clearance``; 3D bodies); ``guide_length`` [m]
        ends the walls ``guide_length / 2`` either side of ``position`` (default: they do not
        end).
    backend, maxPenetration, bearingRotates, record, contact_mode
        As in :func:`exuclear.CreateClearanceJoint` (``bearingRotates``: whether the guide
        can turn; its spin moves the walls under the corners; ``contact_mode="impulse"``:
        each corner against the two walls across y, and the box's across z too, a contact
        of its own, :mod:`~exuclear.engine.impulse_guide`, with its friction along the
        guide's axis, the box's in its wall's plane; a corner beyond a finite guide's end
        has no wall).

    Returns
    -------
    ClearanceJointHandle or ImpulseGuideHandle
        (The latter in the impulse mode: :class:`~exuclear.engine.impulse_guide.ImpulseGuideHandle`.)
        ``objectNumber`` is the connector; ``outputs()`` has :data:`OUTPUT_COLUMNS` per
        corner-wall pair (shape (times, 8), :data:`exuclear.prismatic.PAIRS`' order) and
        ``force``, ``moment`` (the load on the guide); the spatial joint has 32 pairs
        (:data:`exuclear.prismatic.BOX_PAIRS`); ``impacts()`` names each contact's corner
        and wall (:class:`exuclear.history.PairImpact`); ``notes`` and ``counts`` as for the
        revolute joint.
    """
    check_system(mbs)
    check_flags(name, bearingRotates, record=record, show=show)
    joint = _physics(joint, joint_parameters)
    backend, maxPenetration = kernel_settings(joint, backend, maxPenetration)
    mode = choose_mode(contact_mode, joint, None, backend, name, joint_type=joint.geometry.joint_type)
    markers = plane_markers(mbs, itemNumbers, bodyNumbers, ("guide", "slider"), position, axis, useGlobalFrame,
                            "CreatePrismaticJoint", spatial=joint.geometry.spatial, height_axis=height_axis)
    if mode == IMPULSE:  # the mode's own items, a pair per corner and axis (exuclear.engine.impulse_guide)
        return add_impulse_guide(mbs, joint, name, markers)

    handle = ClearanceJointHandle(mbs, joint, name, backend, maxPenetration)
    handle.placed_by = PLACED_BY_POSITION
    handle.markerNumbers = markers
    handle._axis_local = np.array([0.0, 0.0, 1.0])
    if bearingRotates is None:
        bearingRotates = not _orientation_is_fixed(mbs, markers[0])
    add_connectors(mbs, handle, markers, np.eye(3).tolist(), bearingRotates,
                   len(pair_data_columns(len(joint.geometry.pairs))), show,
                   joint.geometry.slider_height)
    finish_items(mbs, handle, slider_drawing_function if show else None, record, load_sensors=True)
    return handle


def plane_markers(mbs: exu.MainSystem, itemNumbers: Any, bodyNumbers: Any, roles: tuple[str, str],  # noqa: N803
                  position: Any, axis: Any, useGlobalFrame: Any, exudyn_name: str,  # noqa: N803
                  spatial: bool = False, height_axis: Any = None) -> list:
    """The two markers of a planar joint on the bodies ``itemNumbers`` (checked as
    :func:`~exuclear.engine.connector.joint_items` checks them, ``roles`` naming them), both
    at ``position`` with the joint frame: ``x`` along ``axis`` (in the global x-y plane),
    ``z`` the global z axis (the plane's normal).  ``spatial``: the spatial translational
    joint's frame instead, ``x`` along ``axis`` (anywhere), ``y`` along ``height_axis``
    (:func:`CreatePrismaticClearanceJoint`)."""
    axis_given = check_axis(axis)
    items = joint_items(mbs, itemNumbers, bodyNumbers, roles, position, useGlobalFrame, exudyn_name)
    if "marker" in items.kinds:
        raise ValueError(f"`itemNumbers` must be [{roles[0]} body, {roles[1]} body]: the joint places its own markers "
                         "at `position`")
    p, a0 = items.centre, items.poses[0][1]
    in_global = (lambda v: v) if useGlobalFrame else (lambda v: a0 @ v)
    x = in_global(axis_given) / np.linalg.norm(axis_given)
    if spatial:
        frame = _channel_frame(x, None if height_axis is None else in_global(vector3("height_axis", height_axis)))
        flat = [f"`itemNumbers[{k}]` ({kind})" for k, kind in enumerate(items.kinds) if kind.endswith("2D")]
        if flat:
            raise ValueError(f"`slider_width` makes the translational joint spatial, for 3D bodies; {flat[0]} is a 2D "
                             "body: leave `slider_width` out for the planar joint")
    else:
        if height_axis is not None:
            raise ValueError("`height_axis` orients the spatial joint's box: give `slider_width` too, or leave it out "
                             "(the planar joint's height lies in the x-y plane)")
        if abs(x[2]) > PLANE_TOLERANCE:
            raise ValueError(f"`axis` must lie in the global x-y plane (the planar joint's plane of motion), got "
                             f"{axis!r}; give `slider_width` for the spatial joint")
        z = np.array([0.0, 0.0, 1.0])
        frame = np.column_stack((x, np.cross(z, x), z))  # the joint frame's axes in the global frame
    return [mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localHT=exu.HT(
        rotation=rot.T @ frame, translation=rot.T @ (p - pos)))) for item, (pos, rot) in zip(items.items, items.poses)]


def _channel_frame(x: np.ndarray, height: np.ndarray | None) -> np.ndarray:
    """The spatial joint's frame (columns x, y, z in the global frame): ``x`` the unit axis,
    ``y`` the ``height`` direction without its part along ``x`` (default ``e_z x x``), ``z = x x y``."""
    if height is None:
        height = np.cross([0.0, 0.0, 1.0], x)
        if not np.linalg.norm(height) > PLANE_TOLERANCE:
            raise ValueError("`axis` is along z: give `height_axis`, the direction of the slider's height")
    y = height - (height @ x) * x
    if not np.linalg.norm(y) > PLANE_TOLERANCE * np.linalg.norm(height):
        raise ValueError(f"`height_axis` must not be parallel to `axis`, got {height.tolist()!r}")
    y = y / np.linalg.norm(y)
    return np.column_stack((x, y, np.cross(x, y)))


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
