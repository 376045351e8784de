"""The spherical clearance joint as Exudyn items: ``CreateSphericalClearanceJoint``.

A ball (on the second body) in a spherical socket (on the first), the clearance form of
``mbs.CreateSphericalJoint``.  The joint is the revolute joint's connector with the ball's
contact (:mod:`exuclear.spherical`, docs/physics.md section 13): the same items
(:mod:`~exuclear.engine.items`), kernels, history, step control, notes and outputs; its type
(``joint.geometry.joint_type``) tells the kernels which contact to build.  The joint frame is
the global frame in the reference configuration, carried by the socket's marker.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid

from ..joint import ClearanceJoint, make_spherical_joint
from ..spherical import SphereGeometry
from .arguments import check_flags, check_system
from .connector import _orientation_is_fixed, _turned_marker, joint_items, kernel_settings
from .drawing import ball_drawing_function, drawing_sizes
from .handle import ClearanceJointHandle
from .items import add_connectors, finish_items
from .layout import BALL_DATA_COLUMNS
from .impulse import ImpulseJointHandle, add_impulse_joint
from .modes import IMPULSE, choose_mode
from .placement import PLACED_BY_POSITION


def CreateSphericalClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
    mbs: exu.MainSystem,
    name: str = "",
    itemNumbers: Sequence[Any] = (None, None),  # noqa: N803 - Exudyn's argument names
    position: Sequence[float] | None = None,
    useGlobalFrame: bool = True,  # noqa: N803
    show: bool = True,
    jointRadius: float | None = None,  # noqa: N803
    color: Sequence[float] | None = None,
    bodyNumbers: Sequence[Any] | None = None,  # noqa: N803
    *,
    joint: ClearanceJoint | None = None,
    backend: str | None = None,
    maxPenetration: float | None = None,  # noqa: N803
    bearingRotates: bool | None = None,  # noqa: N803
    record: bool = True,
    contact_mode: str | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle | ImpulseJointHandle:
    """Create a spherical clearance joint, as ``mbs.CreateSphericalJoint`` creates an ideal
    one: the socket on ``itemNumbers[0]``, the ball on ``itemNumbers[1]``, both centred at
    ``position`` in the reference configuration.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system; call before ``mbs.Assemble()``.
    name : str
        The joint's name (its connector's).
    itemNumbers : [socket item, ball item]
        Each a body (``ObjectIndex``) with a rigid marker (the ground, ``ObjectRigidBody``,
        the bodies of ``mbs.CreateRigidBody`` with any rotation node) or a rigid marker
        (``MarkerIndex``: ``MarkerNodeRigid`` on a beam's node, ``MarkerBodyRigid``, ...).
    position : 3 floats, optional
        The joint's centre [m]: global (``useGlobalFrame=True``) or in item 0's frame;
        default the global origin.  Where an item is a marker, the marker sets the centre
        and ``position`` must be omitted (or ``[]``).
    useGlobalFrame : bool
        Whether ``position`` is global (True) or in item 0's frame.
    show : bool
        Draw the ball in its socket (only a renderer draws).
    jointRadius : float, optional
        ``mbs.CreateSphericalJoint``'s drawing size [m]: the drawn ball's radius (the socket
        to the same scale); default the ball's own radius.
    color : 4 floats, optional
        RGBA colour of the drawn ball.
    bodyNumbers : deprecated
        Exudyn's former name of ``itemNumbers`` (a ``DeprecationWarning``, as Exudyn gives).
    joint : ClearanceJoint, optional
        The physics, ready built (:func:`exuclear.joint.make_spherical_joint`); else built
        from the keyword arguments ``ball_radius``, ``socket_radius`` (both required, the
        ball smaller), ``law`` (default ``"hertz+lankarani-nikravesh"``; the stiffness
        ``"hertz"`` is the ball in a socket, ``K = 4/3 E* sqrt(R_S R_B / (R_S - R_B))``),
        ``cr``, ``stiffness``/``damping`` (the law as a pair), ``friction``, ``v_min``,
        ``E_star``, ``ball_material``, ``socket_material``, as
        :func:`exuclear.CreateClearanceJoint` names them.
    backend, maxPenetration, bearingRotates, record
        As in :func:`exuclear.CreateClearanceJoint` (``bearingRotates``: whether the socket
        body can turn; its spin enters the slip).
    contact_mode : str, optional
        ``"compliant"`` (the default) or ``"impulse"`` (docs/guide/contact_modes.md: velocity
        jumps with the point-contact law's restitution, resting contact as a condition;
        returns an :class:`~exuclear.engine.impulse.ImpulseJointHandle`, whose ``outputs()``
        has ``ecc_x``, ``ecc_y``, ``ecc_z``, global), as in
        :func:`exuclear.CreateClearanceJoint`; the mode's friction acts in the ball's tangent plane.

    Returns
    -------
    ClearanceJointHandle or ImpulseJointHandle
        ``objectNumber`` is the connector; ``outputs()`` has ``ecc_x``, ``ecc_y``, ``ecc_z``
        (the ball's centre relative to the socket's, in the global frame of the reference
        configuration), ``penetration``, ``normal_force``, ``tangential_force``,
        ``slip_velocity`` (the slip speed), ``force`` and ``moment`` (the connector's load on
        the socket); ``impacts()``, ``notes`` and ``counts`` as for the revolute joint.
    """
    check_system(mbs)
    check_flags(name, bearingRotates, record=record, show=show)
    joint = _physics(joint, joint_parameters)
    draw = drawing_sizes(jointRadius, None, color, radius_name="jointRadius")
    backend, maxPenetration = kernel_settings(joint, backend, maxPenetration)
    mode = choose_mode(contact_mode, joint, None, backend, name, joint_type=joint.geometry.joint_type)

    items = joint_items(mbs, itemNumbers, bodyNumbers, ("socket", "ball"), position, useGlobalFrame,
                        "CreateSphericalJoint")
    kinds, p = items.kinds, items.centre
    # both markers in the global frame of the reference configuration, as the joint frame
    markers = []
    for item, kind, (pos, rot) in zip(items.items, kinds, items.poses):
        if kind != "marker":
            markers.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localHT=exu.HT(
                rotation=rot.T, translation=rot.T @ (p - pos)))))
            continue
        marker = _turned_marker(mbs, item, rot.T)
        if marker is None:
            raise ValueError(f"the marker in `itemNumbers` ({int(item)}) has no localHT to turn into the joint frame: "
                             "give a MarkerBodyRigid or MarkerNodeRigid with localHT, or the body")
        markers.append(marker)
    if mode == IMPULSE:  # the mode's own items (exuclear.engine.modes)
        return add_impulse_joint(mbs, joint, name, markers, np.eye(3))

    handle = ClearanceJointHandle(mbs, joint, name, backend, maxPenetration)
    if "marker" not in kinds:
        handle.placed_by = PLACED_BY_POSITION
    handle.markerNumbers = markers
    handle._axis_local = np.array([0.0, 0.0, 1.0])
    handle._drawing = draw
    if bearingRotates is None:
        bearingRotates = not _orientation_is_fixed(mbs, markers[0])
    add_connectors(mbs, handle, markers, np.eye(3).tolist(), bearingRotates, len(BALL_DATA_COLUMNS), show,
                   2.0 * joint.geometry.socket_radius)
    finish_items(mbs, handle, ball_drawing_function if show else None, record, load_sensors=True)
    return handle


def _physics(joint: ClearanceJoint | None, joint_parameters: dict) -> ClearanceJoint:
    """The joint's physics: ``joint`` as given (a ball in a socket), or built by
    :func:`exuclear.joint.make_spherical_joint`."""
    if joint is None:
        for radius in ("ball_radius", "socket_radius"):
            if radius not in joint_parameters:
                raise ValueError(f"`{radius}` is required: the spherical clearance joint is a ball (`ball_radius`) "
                                 "in a socket (`socket_radius` > `ball_radius`), in metres")
        return make_spherical_joint(**joint_parameters)
    if joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    if not isinstance(joint, ClearanceJoint) or not isinstance(joint.geometry, SphereGeometry):
        raise ValueError("`joint` must be a spherical ClearanceJoint (exuclear.joint.make_spherical_joint), got "
                         f"{joint!r}")
    return joint
