"""What :func:`exuclear.simulate` checks before a run and reads after it.

Before: a model that cannot run names its likely cause (issue 15): a body of a
clearance joint without mass, a journal that starts outside its bearing, a non-finite
initial coordinate or velocity.  After: the tilt of a spatial joint that started aligned
(below).  Contact chatter that is a numerical artefact is counted by the joint's kernel in
any implicit run, ``mbs.SolveDynamic`` as well (:func:`exuclear.engine.handle._separation_step`).

Tilt of an aligned journal (issue 21, docs/physics.md section 9.8).  A spatial joint's
journal that starts exactly aligned stays in its plane only as long as round-off does:
under a varying in-plane load (a swinging double pendulum) the tilt is an unstable mode of
the rigid bodies on the slices, and it grows from round-off (1e-17 to 1e-14 rad) at some 30
to 60 per second.  A run
in which such a journal tilted beyond a fraction of ``c / L`` says so.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np

from ..exceptions import OutOfPlaneWarning
from ..timescales import contact_period, reduced_mass
from .connector import ClearanceJointHandle

#: Largest number of ODE2 coordinates for which :func:`unheld_motion` runs: it takes the
#: dense constraint Jacobian's SVD and one marker read per admissible direction (0.1 s
#: at a few hundred coordinates); a larger model is not checked.
UNHELD_MAX_COORDINATES = 1000
#: Step [coordinate units] along an admissible direction (a unit vector of ODE2
#: coordinates) at which the journal's axial and tilt motion are read: far below any
#: model's size, far above round-off of the positions.
_UNHELD_STEP = 1e-6
#: Axial displacement [m] or tilt [rad] per unit step below which a direction does not move
#: the journal out of the plane (round-off of a position of 10 m over the step: 1e-9).
_UNHELD_TOLERANCE = 1e-6
#: Singular values of the constraint Jacobian below this fraction of the largest count as
#: zero (Exudyn's ComputeSystemDegreeOfFreedom uses 1e-12).
_RANK_RTOL = 1e-10
#: Initial tilt [rad] up to which a spatial joint's journal counts as started aligned:
#: round-off of a rotation matrix (1e-16) with a wide margin, far below any misalignment
#: a model would set on purpose.
ALIGNED_TILT = 1e-12
#: Fraction of ``c / L`` (the tilt at which an edge of the journal crosses the clearance,
#: from centred) beyond which a journal that started aligned is named after the run: far
#: above round-off, far below the edge contact (issue 21's model: 0.16 of it in 1 s).
TILT_NOTE_FRACTION = 0.01
#: Relative angular velocity across the axis [rad/s] up to which a journal counts as
#: started without tilting: a journal set tumbling on purpose has far more.
ALIGNED_TILT_RATE = 1e-12


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


def _constraint_jacobian(mbs: exu.MainSystem) -> np.ndarray:
    """The constraint Jacobian C_q (constraints x ODE2 coordinates) at the initial state,
    as Exudyn's ``ComputeSystemDegreeOfFreedom`` reads it (no joint force is evaluated)."""
    settings = exu.SimulationSettings()
    settings.staticSolver.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.active = False  # no sensor records from this evaluation
    solver = exu.MainSolverStatic()
    solver.InitializeSolver(mbs, settings)
    try:
        n2, n1, n_ae = solver.GetODE2size(), solver.GetODE1size(), solver.GetAEsize()
        if n_ae == 0:
            return np.zeros((0, n2))
        size = n2 + n1 + n_ae  # the matrix is not zeroed by InitializeSolver, and ComputeJacobianAE fills its part
        solver.SetSystemJacobian(np.zeros((size, size)))
        solver.ComputeJacobianAE(mbs, scalarFactor_ODE2=1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=1.0,
                                 velocityLevel=False)
        jacobian = np.asarray(solver.GetSystemJacobian())
        return jacobian[:n2, n2 + n1:].T
    finally:
        solver.FinalizeSolver(mbs, settings)


def _relative_pose(mbs: exu.MainSystem, handle: ClearanceJointHandle, frame: np.ndarray) -> np.ndarray:
    """Journal centre along the bearing axis [m] and the journal axis's x, y in the bearing's
    joint frame, in the current configuration."""
    cur, ov = exu.ConfigurationType.Current, exu.OutputVariableType
    b, j = handle.markerNumbers
    a_b = np.asarray(mbs.GetMarkerOutput(b, ov.RotationMatrix, configuration=cur), dtype=float).reshape(3, 3) @ frame
    a_j = np.asarray(mbs.GetMarkerOutput(j, ov.RotationMatrix, configuration=cur), dtype=float).reshape(3, 3)
    d = np.asarray(mbs.GetMarkerOutput(j, ov.Position, configuration=cur), dtype=float) - np.asarray(
        mbs.GetMarkerOutput(b, ov.Position, configuration=cur), dtype=float)
    axis = a_b.T @ a_j @ np.asarray(handle.axis_journal, dtype=float)
    return np.array([a_b[:, 2] @ d, axis[0], axis[1]])


def unheld_motion(mbs: exu.MainSystem, joints: Sequence[ClearanceJointHandle] | None = None) -> dict[Any, list[str]]:
    """The motions a clearance joint leaves free that nothing in the model holds: for each
    joint (by name, or connector number where unnamed) the list of ``"axial translation"``
    and ``"tilt"`` its journal can make relative to its bearing without violating any of
    the model's constraints (a planar joint: both, unless ``constrainAxial``; a spatial
    one: the axial translation, unless ``constrainAxial`` or ``axial_clearance``).  Only
    3D bodies can; the replaced revolute joint held both.  Call after ``mbs.Assemble()``.

    Method: the admissible velocities are the null space of the constraint Jacobian at the
    initial state; the journal is moved a small step (:data:`_UNHELD_STEP`) along each
    and its axial displacement and tilt are read from the markers.  Models with more than
    :data:`UNHELD_MAX_COORDINATES` coordinates are not checked (an empty result).
    """
    from .handle import joints_of  # noqa: PLC0415 - the handle module imports this one's users

    joints = list(joints_of(mbs) if joints is None else joints)
    checked = [h for h in joints if h.constraintNumber is None and not (h.slices and h.shoulders is not None)]
    if not checked:
        return {}
    init, cur = exu.ConfigurationType.Initial, exu.ConfigurationType.Current
    q0 = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=init), dtype=float)
    if not 0 < q0.size <= UNHELD_MAX_COORDINATES:
        return {}
    saved = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=cur), dtype=float)
    jacobian = _constraint_jacobian(mbs)
    if not np.all(np.isfinite(jacobian)):  # a constraint without a finite Jacobian: nothing to say
        return {}
    if jacobian.shape[0]:
        _, sv, vt = np.linalg.svd(jacobian)
        rank = int(np.sum(sv > _RANK_RTOL * sv[0])) if sv.size and sv[0] > 0.0 else 0
        directions = vt[rank:]
    else:
        directions = np.eye(q0.size)
    frames = {h: np.asarray(mbs.GetObject(h.objectNumber)["rotationMarker0"], dtype=float) for h in checked}
    found: dict[Any, list[str]] = {}
    try:
        mbs.systemData.SetODE2Coordinates(q0.tolist(), configuration=cur)
        base = {h: _relative_pose(mbs, h, frames[h]) for h in checked}
        moved = {h: np.zeros(3) for h in checked}
        for n in directions:
            mbs.systemData.SetODE2Coordinates((q0 + _UNHELD_STEP * n).tolist(), configuration=cur)
            for h in checked:
                moved[h] = np.maximum(moved[h], np.abs(_relative_pose(mbs, h, frames[h]) - base[h]) / _UNHELD_STEP)
    finally:
        mbs.systemData.SetODE2Coordinates(saved.tolist(), configuration=cur)
    for h in checked:
        free = []
        if moved[h][0] > _UNHELD_TOLERANCE:
            free.append("axial translation")
        if not h.slices and max(moved[h][1:]) > _UNHELD_TOLERANCE:
            free.append("tilt")
        if free:
            found[h.name or h.objectNumber] = free
    return found


def unheld_note(found: dict[Any, list[str]]) -> str:
    """The warning of :func:`check_model` for the result of :func:`unheld_motion`, or ``""``."""
    if not found:
        return ""
    joints = "; ".join(f"joint {name!r}: {' and '.join(free)}" for name, free in found.items())
    return (f"nothing in the model holds the journal's out-of-plane motion that the replaced revolute joint held "
            f"({joints}): the clearance joint acts in the plane normal to its axis only, so the journal may drift "
            "along the axis or tilt until the contact gives way. Give constrainAxial=True to the clearance joint (or "
            "hold the motion by other joints, or use the spatial joint with axial_clearance)")


def check_model(mbs: exu.MainSystem, joints: Sequence[ClearanceJointHandle]) -> None:
    """``ValueError`` naming the likely cause for a model that cannot run (module docstring);
    an :class:`OutOfPlaneWarning` where a journal's out-of-plane motion is held by nothing."""
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
    note = unheld_note(unheld_motion(mbs, joints))
    if note:
        warnings.warn(note, OutOfPlaneWarning, stacklevel=3)


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


def started_aligned(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> bool:
    """Whether a spatial joint's journal starts aligned and not tilting: its axis within
    :data:`ALIGNED_TILT` of the bearing axis, and the relative angular velocity across the
    axis within :data:`ALIGNED_TILT_RATE`, in the initial configuration."""
    if not handle.slices:
        return False
    ref, ov = exu.ConfigurationType.Initial, exu.OutputVariableType
    b, j = handle.markerNumbers
    frame = np.asarray(mbs.GetObject(handle.objectNumber)["rotationMarker0"], dtype=float)
    a_b = np.asarray(mbs.GetMarkerOutput(b, ov.RotationMatrix, configuration=ref), dtype=float).reshape(3, 3) @ frame
    a_j = np.asarray(mbs.GetMarkerOutput(j, ov.RotationMatrix, configuration=ref), dtype=float).reshape(3, 3)
    axis = a_b.T @ a_j @ np.asarray(handle.axis_journal, dtype=float)
    rate = a_b.T @ (np.asarray(mbs.GetMarkerOutput(j, ov.AngularVelocity, configuration=ref), dtype=float)
                    - np.asarray(mbs.GetMarkerOutput(b, ov.AngularVelocity, configuration=ref), dtype=float))
    return bool(math.hypot(axis[0], axis[1]) <= ALIGNED_TILT and math.hypot(rate[0], rate[1]) <= ALIGNED_TILT_RATE)


def tilt_note(handle: ClearanceJointHandle, aligned: bool) -> str:
    """A sentence if a spatial joint whose journal started aligned (``aligned``, from
    :func:`started_aligned`) tilted beyond :data:`TILT_NOTE_FRACTION` of ``c / L`` (module
    docstring), else ``""``.  Reads the recorded outputs: nothing without ``record``."""
    if not aligned or handle.sensorNumber is None:
        return ""
    out = handle.outputs()
    if len(out["time"]) == 0:
        return ""
    tilt = np.hypot(out["tilt_x"], out["tilt_y"])
    k = int(np.argmax(tilt))
    geometry = handle.joint.geometry
    scale = geometry.clearance / geometry.length
    if not tilt[k] > TILT_NOTE_FRACTION * scale:
        return ""
    return (f"joint {handle.name or handle.objectNumber!r}: the journal started aligned and tilted to {tilt[k]:.2g} rad "
            f"({tilt[k] / scale:.2g} c/L) at t = {out['time'][k]:.4g} s. If nothing in the model loads it out of its "
            "plane, this is the unstable tilt mode of the sliced joint under a varying in-plane load, grown from "
            "round-off (docs/physics.md section 9.8): its growth rate is the model's, its size at a given time is set "
            "by round-off. "
            "For a model meant to stay planar, use the planar joint (no `slices`) with constrainAxial=True, which "
            "holds the tilt")
