"""What the model says about a clearance joint's bodies: their masses, the joint's
effective mass and its contact period under its weight.

The masses are read from the Exudyn objects the joint's markers sit on (rigid bodies, mass
points, kinematic-tree links, beam and cable elements); where an object's type does not say,
the mass is nan and the callers say so (:func:`unread_masses`).  The contact period is the
time scale of :mod:`exuclear.timescales` that the joint's step control
(:mod:`~exuclear.engine.steering`), ``step="auto"`` (:func:`exuclear.engine.solver.automatic_step`)
and the joint's notes (:mod:`~exuclear.engine.diagnostics`) measure steps against.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import exudyn as exu
import numpy as np

from ..timescales import contact_period, reduced_mass

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

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


def body_label(mbs: exu.MainSystem, marker: Any) -> str:
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
            unread.append(f"its {role} body ({body_label(mbs, marker)}{kind})")
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


def joint_mass(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> float:
    """The effective mass [kg] of a joint's relative motion: its two bodies' reduced mass
    (nan where a body's mass is not read).  A crude estimate: a body held by other joints
    moves the journal with more or less than its own mass."""
    return reduced_mass(*(body_mass(mbs, m) for m in handle.markerNumbers))


def joint_contact_period(mbs: exu.MainSystem, handle: ClearanceJointHandle, force: float | None = None) -> float:
    """Contact period [s] of a joint: its two bodies' reduced mass (:func:`joint_mass`),
    pressed by ``force`` [N] (default: that mass times the model's gravity, or
    :data:`STANDARD_GRAVITY`)."""
    mass = joint_mass(mbs, handle)
    if not mass > 0.0 or not math.isfinite(mass):
        return math.nan
    if force is None:
        force = mass * (_gravity(mbs) or STANDARD_GRAVITY)
    return contact_period(handle.joint.law, mass, force)


def coordinate_owner(mbs: Any, marker: Any) -> tuple[str, int]:
    """The body (object) or node whose coordinates move the marker."""
    info = mbs.GetMarker(marker)
    for key, kind in (("bodyNumber", "object"), ("objectNumber", "object"), ("nodeNumber", "node")):
        if key in info:
            return kind, int(info[key])
    raise ValueError(f"contact_mode='impulse': marker {int(marker)} ({info.get('markerType')}) is on no body or node")


def object_nodes(mbs: Any, number: int) -> list[int]:
    """The nodes of object ``number``."""
    info = mbs.GetObject(number)
    if "nodeNumbers" in info:
        return [int(n) for n in info["nodeNumbers"]]
    return [int(info["nodeNumber"])] if "nodeNumber" in info else []


def node_ode2_size(mbs: Any, number: int) -> int:
    """The number of second-order coordinates of node ``number`` (0 for a ground node)."""
    info = mbs.GetNode(number)
    if "Ground" in info["nodeType"]:
        return 0
    if "numberOfODE2Coordinates" in info:
        return int(info["numberOfODE2Coordinates"])
    return len(info["referenceCoordinates"])
