"""The pin-in-slot clearance joint as Exudyn items: ``CreatePinSlotClearanceJoint``.

A pin (on the second body) in a slot (on the first), planar: the revolute joint's items and
connector (:func:`~exuclear.engine.connector.AddClearanceJoint`) with the pin's contact
against the slot's centre segment (:mod:`exuclear.slot`).  The joint frame has ``x`` along
the slot's ``axis`` and ``z`` the global z axis (the plane's normal), carried by both markers
in the reference configuration.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import exudyn as exu

from ..joint import ClearanceJoint, make_pin_slot_joint
from ..slot import SlotGeometry
from .arguments import check_system
from .connector import AddClearanceJoint
from .handle import ClearanceJointHandle
from .impulse import ImpulseJointHandle
from .placement import PLACED_BY_POSITION
from .prismatic import plane_markers


def CreatePinSlotClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
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
) -> ClearanceJointHandle | ImpulseJointHandle:
    """Create a planar pin-in-slot clearance joint: the slot on ``itemNumbers[0]``, centred at
    ``position`` and running along ``axis``; the pin on ``itemNumbers[1]``, its centre at
    ``position`` in the reference configuration.

    Parameters
    ----------
    mbs, name, itemNumbers, position, useGlobalFrame, show, bodyNumbers
        As in :func:`exuclear.CreatePrismaticClearanceJoint` (bodies, not markers).
    axis : 3 floats
        The slot's direction, in the global x-y plane: global, or in item 0's frame.
    joint : ClearanceJoint, optional
        The physics, ready built (:func:`exuclear.joint.make_pin_slot_joint`); else built from
        the keyword arguments ``pin_radius``, ``slot_width`` (> 2 ``pin_radius``),
        ``slot_length`` (the end centres' distance, >= 0), ``length`` (the pin's length in
        contact, for the line-contact laws) and the law's arguments of
        :func:`exuclear.CreateClearanceJoint` (``law``, ``cr``, ``stiffness``/``damping``,
        ``friction``, ``v_min``, ``E_star``, ``pin_material``, ``slot_material``).
    backend, maxPenetration, bearingRotates, record, contact_mode
        As in :func:`exuclear.CreateClearanceJoint` (``bearingRotates``: whether the slot can turn;
        ``contact_mode="impulse"``: the pin against the slot's centre segment, its normal
        turning around the end caps, its friction along the slot's wall).

    Returns
    -------
    ClearanceJointHandle or ImpulseJointHandle
        The planar revolute joint's outputs; ``ecc_x``, ``ecc_y`` are the pin's centre
        relative to the slot's nearest centre-segment point, in the slot's frame (global
        in the impulse mode, with ``ecc_z``).  At
        ``slot_length = 0`` the joint is :func:`exuclear.CreateClearanceJoint` with
        ``journal_radius = pin_radius`` and ``bearing_radius = slot_width / 2``.
    """
    check_system(mbs)
    joint = _physics(joint, joint_parameters)
    markers = plane_markers(mbs, itemNumbers, bodyNumbers, ("slot", "pin"), position, axis, useGlobalFrame,
                            "CreateRevoluteJoint")
    handle = AddClearanceJoint(mbs, markers, name=name, joint=joint, backend=backend, maxPenetration=maxPenetration,
                               bearingRotates=bearingRotates, record=record, show=show,
                               contact_mode=contact_mode)
    handle.placed_by = PLACED_BY_POSITION
    return handle


def _physics(joint: ClearanceJoint | None, joint_parameters: dict) -> ClearanceJoint:
    """The joint's physics: ``joint`` as given (a pin in a slot), or built by
    :func:`exuclear.joint.make_pin_slot_joint`."""
    if joint is None:
        for required in ("pin_radius", "slot_width", "slot_length", "length"):
            if required not in joint_parameters:
                raise ValueError(f"`{required}` is required: the pin-in-slot clearance joint is a pin (`pin_radius`, "
                                 "`length`) in a slot (`slot_width`, `slot_length` between its end centres), in metres")
        return make_pin_slot_joint(**joint_parameters)
    if joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    if not isinstance(joint, ClearanceJoint) or not isinstance(joint.geometry, SlotGeometry):
        raise ValueError(f"`joint` must be a pin-in-slot ClearanceJoint (exuclear.joint.make_pin_slot_joint), got {joint!r}")
    return joint
