"""What :func:`exuclear.simulate` checks before a run and reads after it.

Before: a model that cannot run names its likely cause (issue 15): a body of a
clearance joint without mass, a journal that starts outside its bearing, a non-finite
initial coordinate or velocity.  After: contact chatter that is a numerical artefact.

Chatter.  An implicit method without error control (Exudyn's generalized-alpha) that
takes steps of more than a tenth of a joint's contact period
(:func:`exuclear.timescales.contact_period`) while a contact opens does not resolve the
opening: the contact mode rings and the journal leaves the wall without a physical
cause.  A resting pendulum at steps of 1e-3 s leaves the wall 68 times in 2 s where
DOPRI5 and physics give one contact.  Separations taken at such steps are counted per
joint from the contact records and the accepted step times, and the run says so.
"""
from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np

from ..timescales import STEPS_PER_CONTACT_PERIOD, contact_period, reduced_mass
from .connector import ClearanceJointHandle

#: Gravitational acceleration assumed for the contact load where a model has no
#: mass-proportional load [m/s^2]: a joint is then pressed by its effective mass times g.
STANDARD_GRAVITY = 9.81


def _body_of(mbs: exu.MainSystem, marker: Any) -> tuple[Any, dict | None, int | None]:
    """The object a marker sits on, its dictionary and its kinematic-tree link; ``(None,
    None, None)`` for a node marker (``MarkerNodeRigid``), which sits on no object."""
    m = mbs.GetMarker(marker)
    body = m.get("bodyNumber", m.get("objectNumber"))
    if body is None:
        return None, None, None
    link = m.get("linkNumber")
    return body, mbs.GetObject(body), (int(link) if link is not None else None)


def _where(mbs: exu.MainSystem, marker: Any) -> str:
    """The body a marker sits on, for messages: "object 3", "link 1 of object 0", "node 2"."""
    body, _, link = _body_of(mbs, marker)
    if body is None:
        return f"node {mbs.GetMarker(marker)['nodeNumber']}"
    return f"link {link} of object {body}" if link is not None else f"object {body}"


def _element_mass(item: dict) -> float:
    """Mass [kg] of an object, nan where its type does not say: a rigid body's or mass
    point's ``physicsMass`` / ``mass``; a beam or cable element's mass per length times its
    length (``ObjectANCFCable2D``, ``ObjectBeamGeometricallyExact2D``: ``massPerLength``
    and ``length``; the 3D elements: ``physicsMassPerLength`` or their ``sectionData``,
    and ``physicsLength``)."""
    for key in ("physicsMass", "mass"):  # ObjectRigidBody and mass points; ObjectRigidBody2D
        if key in item:
            return float(item[key])
    per_length = item.get("massPerLength", item.get("physicsMassPerLength"))
    if per_length is None and "sectionData" in item:
        per_length = getattr(item["sectionData"], "massPerLength", None)
    length = item.get("length", item.get("physicsLength"))
    if per_length is None or length is None:
        return math.nan
    return float(per_length) * float(length)


def _node_mass(mbs: exu.MainSystem, node: int) -> float:
    """Mass [kg] that moves with a node: the whole mass of the objects whose only node it is
    (a rigid body), and a share ``1 / (number of the element's nodes)`` of every element
    that has it among several nodes (the lumped mass of a beam or cable node); nan where
    an attached object's mass is not read (:func:`_element_mass`) or nothing is attached."""
    mass, attached = 0.0, False
    for i in range(mbs.systemData.NumberOfObjects()):
        item = mbs.GetObject(i)
        nodes = [int(n) for n in item.get("nodeNumbers", [])]
        if "nodeNumber" in item and item["nodeNumber"] is not None and int(item["nodeNumber"]) >= 0:
            nodes.append(int(item["nodeNumber"]))
        if node not in nodes or item["objectType"].startswith(("Connector", "Joint", "Contact")):
            continue
        attached = True
        mass += _element_mass(item) / len(nodes)
    return mass if attached else math.nan


def body_mass(mbs: exu.MainSystem, marker: Any) -> float:
    """Mass [kg] of the body (or kinematic-tree link) a marker sits on; inf for the
    ground; for a node marker the mass that moves with the node (:func:`_node_mass`); nan
    where the object type does not say."""
    body, item, link = _body_of(mbs, marker)
    if item is None:
        return _node_mass(mbs, int(mbs.GetMarker(marker)["nodeNumber"]))
    kind = item["objectType"]
    if kind == "Ground":
        return math.inf
    if kind == "KinematicTree":
        return float(item["linkMasses"][link])
    return _element_mass(item)


def unread_masses(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> str:
    """The bodies of a joint whose mass :func:`body_mass` does not read, for messages
    ("its journal body (object 3, an ObjectFFRF)"), or ``""``."""
    unread = []
    for role, marker in zip(("bearing", "journal"), handle.markerNumbers):
        if math.isnan(body_mass(mbs, marker)):
            _, item, _ = _body_of(mbs, marker)
            kind = f", an Object{item['objectType']}" if item is not None else ""
            unread.append(f"its {role} body ({_where(mbs, marker)}{kind})")
    return " and ".join(unread)


def _gravity(mbs: exu.MainSystem) -> float:
    g = 0.0
    for i in range(mbs.systemData.NumberOfLoads()):
        load = mbs.GetLoad(i)
        if load["loadType"] == "MassProportional":
            g = max(g, float(np.linalg.norm(load["loadVector"])))
    for i in range(mbs.systemData.NumberOfObjects()):
        item = mbs.GetObject(i)
        if item["objectType"] == "KinematicTree":
            g = max(g, float(np.linalg.norm(item["gravity"])))
    return g


def joint_contact_period(mbs: exu.MainSystem, handle: ClearanceJointHandle, force: float | None = None) -> float:
    """Contact period [s] of a joint: its two bodies' reduced mass, pressed by ``force``
    [N] (default: that mass times the model's gravity, or :data:`STANDARD_GRAVITY`)."""
    masses = [body_mass(mbs, m) for m in handle.markerNumbers]
    mass = reduced_mass(*masses)
    if not mass > 0.0 or not math.isfinite(mass):
        return math.nan
    if force is None:
        force = mass * (_gravity(mbs) or STANDARD_GRAVITY)
    return contact_period(handle.joint.law, mass, force)


def check_model(mbs: exu.MainSystem, joints: Sequence[ClearanceJointHandle]) -> None:
    """``ValueError`` naming the likely cause for a model that cannot run (module docstring)."""
    for handle in joints:
        name = handle.name or handle.objectNumber
        for role, marker in zip(("bearing", "journal"), handle.markerNumbers):
            mass = body_mass(mbs, marker)
            if mass <= 0.0:  # NaN (a body type whose mass is not read here) passes
                raise ValueError(f"clearance joint {name!r}: its {role} body ({_where(mbs, marker)}) has mass {mass}; every body "
                                 "of a clearance joint needs a positive mass (the contact force would accelerate "
                                 "it without bound)")
        delta = initial_penetration(mbs, handle)
        if delta > handle.max_penetration:
            c = handle.joint.geometry.clearance
            raise ValueError(f"clearance joint {name!r}: the journal starts outside its bearing (penetration "
                             f"{delta:.4g} m, {delta / c:.3g} clearances, beyond the limit {handle.max_penetration:.3g} "
                             "m); place the journal centre within the clearance of the bearing centre (check "
                             "journal_point / bearing_point and the bodies' initial positions, in metres)")
    ref = exu.ConfigurationType.Initial
    for label, values in (("coordinate", mbs.systemData.GetODE2Coordinates(configuration=ref)),
                          ("velocity", mbs.systemData.GetODE2Coordinates_t(configuration=ref))):
        bad = [k for k, v in enumerate(np.asarray(values, dtype=float)) if not math.isfinite(v)]
        if bad:
            raise ValueError(f"initial {label} {bad[0]} (ODE2 index; node {_node_of(mbs, bad[0])}) is {values[bad[0]]}: "
                             f"every initial {label} must be finite")


def _node_of(mbs: exu.MainSystem, index: int) -> Any:
    for n in range(mbs.systemData.NumberOfNodes()):
        try:
            start = mbs.GetNodeODE2Index(n)
        except Exception:  # nodes without ODE2 coordinates (ground, data nodes)
            continue
        size = len(np.atleast_1d(mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates,
                                                   configuration=exu.ConfigurationType.Initial)))
        if start <= index < start + size:
            return n
    return "?"


def initial_penetration(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> float:
    """Penetration ``e - c`` [m] of a joint in the initial configuration, in the plane of its joint frame."""
    ref = exu.ConfigurationType.Initial
    b, j = handle.markerNumbers
    p_b = np.asarray(mbs.GetMarkerOutput(b, exu.OutputVariableType.Position, configuration=ref), dtype=float)
    p_j = np.asarray(mbs.GetMarkerOutput(j, exu.OutputVariableType.Position, configuration=ref), dtype=float)
    a_b = np.asarray(mbs.GetMarkerOutput(b, exu.OutputVariableType.RotationMatrix, configuration=ref),
                     dtype=float).reshape(3, 3)
    frame = a_b @ np.asarray(mbs.GetObject(handle.objectNumber)["rotationMarker0"], dtype=float)
    local = frame.T @ (p_j - p_b)
    return float(math.hypot(local[0], local[1]) - handle.joint.geometry.clearance)


def chatter_note(mbs: exu.MainSystem, handle: ClearanceJointHandle, step_times: Sequence[float]) -> str:
    """A sentence if the joint's contacts opened at steps longer than a tenth of its
    contact period (module docstring), else ``""``."""
    period = joint_contact_period(mbs, handle)
    if not period > 0.0 or len(step_times) < 2:
        return ""
    limit = period / STEPS_PER_CONTACT_PERIOD
    unresolved = 0
    records = handle.impacts()
    for record in records:
        end = record.onset_time + record.duration
        k = bisect.bisect_left(step_times, end * (1.0 - 1e-12))  # the accepted step that ends at or after it
        if 0 < k < len(step_times) and step_times[k] - step_times[k - 1] > limit * (1.0 + 1e-9):
            unresolved += 1
    if unresolved == 0:
        return ""
    onsets = handle.history.onsets
    return (f"joint {handle.name or handle.objectNumber!r}: {unresolved} of its {len(records)} contacts ended at a step "
            f"longer than a tenth of its contact period ({period:.2g} s, estimated); such separations are not "
            f"resolved, and the {onsets} contact onsets may be numerical chatter, not physics. Rerun with "
            f"`step` <= {limit:.2g} s (or an explicit adaptive method where the model allows)")
