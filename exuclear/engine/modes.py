"""A joint's contact mode: how its contact acts at the user's step.

- ``"compliant"`` (the default): the contact law at every step; the force pulse of each
  impact is integrated, which needs steps of a fraction of the contact's duration.
- ``"impulse"``: Moreau-Jean time stepping (Acary and Brogliato, *Numerical Methods for
  Nonsmooth Dynamical Systems*, 2008, chapter 10): an impact is a velocity jump within one
  step, with the restitution the joint's own law gives at the impact velocity, and resting
  contact a unilateral condition; no force pulse is integrated
  (:mod:`~exuclear.engine.impulse`).

The builders call :func:`resolve_contact_mode` once; the compliant mode is the builders'
own path, the impulse mode its builder :func:`~exuclear.engine.impulse.add_impulse_joint`
(:func:`mode_builder`).  :data:`ENVIRONMENT_VARIABLE` sets the mode of every joint that
names none.
"""
from __future__ import annotations

import os
import warnings
from typing import Any

from ..joint import ClearanceJoint
from .impulse_pairs import PAIRS

COMPLIANT = "compliant"
IMPULSE = "impulse"

#: The modes, by name.
CONTACT_MODES = {COMPLIANT: "the contact law at every step (the default)",
                 IMPULSE: "impacts as velocity jumps and resting contact as a unilateral condition"}

#: The environment variable that sets the mode of every joint whose builder names none.
ENVIRONMENT_VARIABLE = "EXUCLEAR_CONTACT_MODE"


def resolve_contact_mode(contact_mode: Any) -> str:
    """The mode a builder's ``contact_mode`` asks for: as given, else
    :data:`ENVIRONMENT_VARIABLE` where set (and not empty), else ``"compliant"``."""
    source = "`contact_mode`"
    if contact_mode is None:
        contact_mode = os.environ.get(ENVIRONMENT_VARIABLE, "").strip() or COMPLIANT
        source = f"the environment variable {ENVIRONMENT_VARIABLE}"
    if contact_mode == "follow":
        raise ValueError(f"{source} 'follow' was removed (its study: docs/design/contact_following.md); "
                         "leave `contact_mode` out for the compliant contact, the default, or give 'impulse'")
    if contact_mode not in CONTACT_MODES:
        raise ValueError(f"{source} must be one of {sorted(CONTACT_MODES)}, got {contact_mode!r}")
    return str(contact_mode)


def impulse_refusal(joint: ClearanceJoint, slices: int | None, backend: str, joint_type: str) -> str:
    """Why the impulse mode cannot take a joint ('' where it can): it covers the dry joints
    without wear whose contacts are each one point against its clearance
    (:data:`~exuclear.engine.impulse_pairs.PAIRS`: the planar revolute, the spherical and the
    pin-in-slot joint; the translational joints' corners and the spatial revolute joint's
    slices and end faces, each a pair of its own, :mod:`~exuclear.engine.impulse_group`; a
    finite guide's), with their friction (:mod:`~exuclear.engine.impulse_friction`)."""
    if joint_type != "prismatic" and joint_type not in PAIRS:
        return (f"it covers the planar revolute, spherical, pin-in-slot and translational joints, not the {joint_type} "
                "joint")
    if joint.film is not None:
        return "a lubricated joint's film acts over the whole approach, not in one step"
    if joint.wear is not None:
        return "wear integrates the contact's force and slip over each impact, which the mode does not compute"
    return ""


def choose_mode(contact_mode: Any, joint: ClearanceJoint, slices: int | None, backend: str, name: str,
                joint_type: str = "revolute") -> str:
    """The mode a joint gets: :func:`resolve_contact_mode`'s.  Where the impulse mode cannot
    take the joint (:func:`impulse_refusal`), a ``contact_mode="impulse"`` the builder was
    given raises ``ValueError`` naming the joint, the cause and what to use; one that
    :data:`ENVIRONMENT_VARIABLE` asked for falls back to the compliant contact and warns so."""
    mode = resolve_contact_mode(contact_mode)
    reason = impulse_refusal(joint, slices, backend, joint_type) if mode == IMPULSE else ""
    if not reason:
        return mode
    where = f"joint {name or '(unnamed)'}: contact_mode='impulse' cannot take this joint: {reason}"
    if contact_mode is None:
        warnings.warn(f"{where}; it has the compliant contact ({ENVIRONMENT_VARIABLE}=impulse applies to the joints "
                      "the mode covers)", UserWarning, stacklevel=3)
        return COMPLIANT
    raise ValueError(f"{where}; use contact_mode='compliant'")
