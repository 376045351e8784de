"""The clearance joint as Exudyn items: ``CreateClearanceJoint``, ``AddClearanceJoint`` and the helper connectors.

A clearance joint is an ``ObjectConnectorRigidBodySpringDamper`` between a rigid marker
on the bearing body (marker 0) and one on the journal body (marker 1), whose user
functions (compiled or Python, :mod:`exuclear.engine.kernel`) compute the contact and
friction loads of docs/physics.md eqs. (24)-(26) and, once per accepted step, the contact
history (a ``NodeGenericData``, see :mod:`exuclear.engine.layout`).  Exudyn computes the
markers' kinematics and Jacobians, so any body with a rigid marker works.

The connector sees the journal's motion relative to the bearing, expressed in the
bearing's joint frame (z along the axis), and applies equal and opposite torques.  Two
things of the physics need the bearing's own motion: its spin enters the slip (eq. (8),
``omega_j (R_B - R_J)`` beyond the relative spin), and its moment is ``-R_B F_T``, not
``-R_J F_T``.  Where the bearing body can rotate (it is not the ground), two more
connectors between the bearing marker and a ground marker close that gap: a probe,
before the joint, that records the bearing's spin, and a torque connector, after it,
that adds ``(R_J - R_B) F_T`` to the bearing.  Exudyn evaluates connectors in the order
of their indices within one evaluation (with one thread, its default), which is what
this relies on.

The other roles live next to this file: the handle a builder returns
(:mod:`~exuclear.engine.handle`, with its backends :mod:`~exuclear.engine.backends`), its
outputs (:mod:`~exuclear.engine.outputs`), its drawing (:mod:`~exuclear.engine.drawing`)
and the builders' argument checks (:mod:`~exuclear.engine.checks`).
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    MarkerKinematicTreeRigid,
    NodeGenericData,
    ObjectConnectorRigidBodySpringDamper,
    ObjectGround,
    ObjectJointGeneric,
    SensorNode,
    VObjectConnectorRigidBodySpringDamper,
    VObjectGround,
    VObjectJointGeneric,
)

from .._checks import check_choice, check_positive
from ..joint import ClearanceJoint
from ..spatial import FACE_SIDES
from . import kernel
from .checks import (
    AXIS_UNIT_TOLERANCE,
    DEFAULT_SLICES,
    PENETRATION_LIMIT_CLEARANCE,
    PENETRATION_LIMIT_RADIUS,
    check_axis,
    check_flags,
    check_markers,
    check_shoulders,
    check_slices,
    check_system,
    default_penetration_limit,
    object_type,
    physics,
    vector3,
)
from .drawing import drawing_function
from .handle import REGISTRY_KEY, ClearanceJointHandle, JointHistory, joints_of, register
from .layout import MAIN, data_columns, parameters, spatial_data_columns
from .outputs import FACE_OUTPUT_PREFIX, OUTPUT_COLUMNS, SPATIAL_OUTPUT_COLUMNS

#: Names kept here for the code that imports them from this module.
__all__ = ["AXIS_UNIT_TOLERANCE", "BACKENDS", "DEFAULT_BACKEND", "DEFAULT_SLICES", "FACE_OUTPUT_PREFIX",
           "OUTPUT_COLUMNS", "PENETRATION_LIMIT_CLEARANCE", "PENETRATION_LIMIT_RADIUS", "REGISTRY_KEY",
           "SPATIAL_OUTPUT_COLUMNS", "AddClearanceJoint", "ClearanceJointHandle", "CreateClearanceJoint",
           "JointHistory", "add_clearance_joint", "default_penetration_limit", "drawing_function", "joint_frame",
           "joints_of"]

#: How the joint's user functions are evaluated.
BACKENDS = {"compiled": "C++ kernel called by Exudyn without Python (the default where it passed its self-test)",
            "python": "Python kernel: the readable statement, and the path for laws written in Python"}

#: The backend used where none is given: ``"compiled"`` where its self-test passed.
DEFAULT_BACKEND = kernel.default_backend()


def joint_frame(axis: np.ndarray) -> np.ndarray:
    """Rotation matrix whose z column is ``axis`` (unit); for ``axis = z`` the identity, so
    that a planar model's eccentricity is in global x, y."""
    z = axis / np.linalg.norm(axis)
    e = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = e - (e @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])



def _reference_pose(mbs: exu.MainSystem, body: Any) -> tuple[np.ndarray, np.ndarray]:
    """Position and rotation matrix of a body's reference point in the reference configuration."""
    ref = exu.ConfigurationType.Reference
    p = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.Position, localPosition=[0, 0, 0],
                                           configuration=ref), dtype=float)
    a = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.RotationMatrix, localPosition=[0, 0, 0],
                                           configuration=ref), dtype=float).reshape(3, 3)
    return p, a


def _marker_rotation(mbs: exu.MainSystem, marker: Any) -> np.ndarray:
    """A marker's rotation matrix in the reference configuration."""
    return np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.RotationMatrix,
                                          configuration=exu.ConfigurationType.Reference), dtype=float).reshape(3, 3)


def _orientation_is_fixed(mbs: exu.MainSystem, marker: Any) -> bool:
    """Whether a marker can never rotate: on the ground, or on a kinematic-tree link whose
    chain to the base has prismatic joints only (the slider of a minimal slider-crank)."""
    m = mbs.GetMarker(marker)
    body = m.get("bodyNumber", m.get("objectNumber"))
    if body is None:
        return False
    item = mbs.GetObject(body)
    if item["objectType"] == "Ground":
        return True
    if m["markerType"] != "KinematicTreeRigid":
        return False
    parents, types = list(item["linkParents"]), [t.name for t in item["jointTypes"]]
    link = int(m["linkNumber"])
    while link >= 0:
        if not types[link].startswith("Prismatic"):
            return False
        link = parents[link]
    return True



def AddClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
    mbs: exu.MainSystem,
    markerNumbers: Sequence[Any],
    *,
    axis: Sequence[float] = (0.0, 0.0, 1.0),
    name: str = "",
    joint: ClearanceJoint | None = None,
    backend: str | None = None,
    maxPenetration: float | None = None,
    constrainAxial: bool = False,
    bearingRotates: bool | None = None,
    record: bool = True,
    show: bool = True,
    slices: int | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle:
    """Add a clearance joint between two rigid markers: the bearing hole's centre on
    ``markerNumbers[0]``, the journal's centre on ``markerNumbers[1]``.

    ``axis`` is the bearing axis in marker 0's frame (default its z axis); the contact acts
    in the plane normal to it (planar joint), or slice by slice along it (``slices``; the
    journal's axis is taken parallel to it in the reference configuration).  The other
    arguments are those of :func:`CreateClearanceJoint`.  Call before ``mbs.Assemble()``.
    """
    check_system(mbs)
    check_markers(mbs, markerNumbers)
    axial_clearance = joint_parameters.pop("axial_clearance", None)
    shoulder_radius = joint_parameters.pop("shoulder_radius", None)
    joint = physics(joint, joint_parameters)
    axis_local = check_axis(axis)
    slices = check_slices(slices)
    shoulders = check_shoulders(axial_clearance, shoulder_radius, slices, constrainAxial, joint)
    check_flags(name, bearingRotates, constrainAxial=constrainAxial, record=record, show=show)
    backend = kernel.default_backend() if backend is None else check_choice("backend", backend, BACKENDS)
    if backend == "compiled" and kernel.COMPILED is None:
        raise ValueError(f"backend 'compiled' is not available: {kernel.REASON}")
    if maxPenetration is None:
        maxPenetration = default_penetration_limit(joint.geometry)
    check_positive("maxPenetration", maxPenetration)

    parameters(joint, 0, MAIN, maxPenetration, compiled=backend == "compiled")  # refuses what the kernel cannot do
    m_bearing, m_journal = markerNumbers
    a_bearing = _marker_rotation(mbs, m_bearing)
    a_journal = _marker_rotation(mbs, m_journal)
    frame = joint_frame(axis_local)  # in marker 0's frame
    rotation0 = frame.tolist()
    rotation1 = (a_journal.T @ a_bearing @ frame).tolist()  # the same joint frame, seen from marker 1
    # the journal axis in marker 1's frame: the bearing axis in the reference configuration (eq. (34))
    axis_journal = tuple(float(v) for v in a_journal.T @ a_bearing @ frame[:, 2])

    handle = ClearanceJointHandle(mbs, joint, name, backend, float(maxPenetration), slices, axis_journal, shoulders)
    handle.markerNumbers = [m_bearing, m_journal]
    handle._axis_local = axis_local / np.linalg.norm(axis_local)
    fns = handle.user_functions()
    hidden = VObjectConnectorRigidBodySpringDamper(show=False)
    if bearingRotates is None:
        bearingRotates = not _orientation_is_fixed(mbs, m_bearing)
    if bearingRotates:
        # the bearing can rotate: probe before the joint, torque connector after it (module docstring)
        ground = mbs.AddObject(ObjectGround(visualization=VObjectGround(show=False)))
        m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
        probe_node = mbs.AddNode(NodeGenericData(initialCoordinates=[0.0], numberOfDataCoordinates=1))
        handle.probeNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
            name=f"{name}:probe" if name else "", markerNumbers=[m_bearing, m_ground], nodeNumber=probe_node,
            rotationMarker0=rotation0, springForceTorqueUserFunction=fns["probe"],
            postNewtonStepUserFunction=fns["probe_post_newton"], visualization=hidden))
    n_faces = len(FACE_SIDES) if shoulders is not None else 0
    lubricated = joint.film is not None
    n_data = len(spatial_data_columns(slices, n_faces, lubricated)) if slices else len(data_columns(lubricated))
    handle.nodeNumber = mbs.AddNode(NodeGenericData(initialCoordinates=[0.0] * n_data, numberOfDataCoordinates=n_data))
    handle.objectNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
        name=name, markerNumbers=[m_bearing, m_journal], nodeNumber=handle.nodeNumber,
        rotationMarker0=rotation0,  # marker 1's rotation enters only Exudyn's relative angles, unused here
        springForceTorqueUserFunction=fns["force_torque"], postNewtonStepUserFunction=fns["post_newton"],
        visualization=VObjectConnectorRigidBodySpringDamper(show=show, drawSize=2.0 * joint.geometry.bearing_radius)))
    if handle.probeNumber is not None:
        handle.torqueNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
            name=f"{name}:torque" if name else "", markerNumbers=[m_bearing, m_ground], rotationMarker0=rotation0,
            springForceTorqueUserFunction=fns["torque"], visualization=hidden))
    if constrainAxial:
        handle.constraintNumber = mbs.AddObject(ObjectJointGeneric(
            name=f"{name}:axial" if name else "", markerNumbers=[m_bearing, m_journal],
            constrainedAxes=[0, 0, 1, 0, 0, 0] if slices else [0, 0, 1, 1, 1, 0], rotationMarker0=rotation0, rotationMarker1=rotation1,
            visualization=VObjectJointGeneric(show=False)))
    if show:  # journal and bearing drawn by a graphics function, which only a renderer calls
        handle.drawingNumber = mbs.AddObject(ObjectGround(visualization=VObjectGround(
            show=True, graphicsDataUserFunction=drawing_function(handle))))
    handle._write_parameters()
    register(mbs, handle)
    if record:
        handle.sensorNumber = mbs.AddSensor(SensorNode(nodeNumber=handle.nodeNumber, storeInternal=True,
                                                       writeToFile=False,
                                                       outputVariableType=exu.OutputVariableType.Coordinates))
    return handle



def CreateClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
    mbs: exu.MainSystem,
    name: str = "",
    itemNumbers: Sequence[Any] = (None, None),
    position: Sequence[float] = (0.0, 0.0, 0.0),
    axis: Sequence[float] = (0.0, 0.0, 1.0),
    useGlobalFrame: bool = True,
    show: bool = True,
    *,
    joint: ClearanceJoint | None = None,
    backend: str | None = None,
    maxPenetration: float | None = None,
    constrainAxial: bool = False,
    bearingRotates: bool | None = None,
    record: bool = True,
    slices: int | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle:
    """Create a revolute clearance joint between two bodies, as ``mbs.CreateRevoluteJoint`` does
    for an ideal one: the bearing (hole) on ``itemNumbers[0]``, the journal (pin) on
    ``itemNumbers[1]``, both centred at ``position`` in the reference configuration.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system; call before ``mbs.Assemble()``.
    name : str
        The joint's name (its connector's).
    itemNumbers : [ObjectIndex, ObjectIndex]
        Bearing body and journal body: any object with rigid body markers (ground,
        ``ObjectRigidBody2D``, the bodies of ``mbs.CreateRigidBody`` with any rotation
        node, ``ObjectRigidBody``, flexible bodies that give a ``MarkerBodyRigid``).  For
        kinematic-tree links use :func:`AddClearanceJoint` with ``MarkerKinematicTreeRigid``.
    position : 3 floats
        The joint's centre [m]: global (``useGlobalFrame=True``) or in body 0's frame.
    axis : 3 floats
        Bearing axis (global, or body 0's frame); the contact acts in the plane normal to it.
    show : bool
        Draw the joint (Exudyn draws its connector; nothing is drawn without a renderer).
    joint : ClearanceJoint, optional
        The physics, ready built; else built by :func:`exuclear.make_joint` from the
        keyword arguments ``journal_radius``, ``bearing_radius``, ``length``, ``law``,
        ``cr``, ``journal_material``, ``bearing_material``, ``E_star``, ``friction``,
        ``v_min``.
    backend : str, optional
        ``"compiled"`` (default where the compiled kernel passed its self-test) or
        ``"python"``; both give the same results to round-off.
    maxPenetration : float, optional
        Penetration [m] beyond which a run stops with an error naming the joint; default
        :func:`default_penetration_limit`.
    constrainAxial : bool
        False (default): the joint adds no constraint, so a model whose other joints hold
        the out-of-plane motion stays free of redundant constraints.  True: an
        ``ObjectJointGeneric`` also holds axial translation and tilt, as the replaced
        revolute joint did (3D bodies; needs an implicit solver); for a spatial joint
        (``slices``) the axial translation only, since the slices carry the tilt.
    bearingRotates : bool, optional
        Whether the bearing body can turn about the axis.  Where it can, two helper
        connectors supply the bearing's own spin to the slip and its own moment
        (docs/physics.md section 4.1).  None (default): True unless the bearing is the
        ground or a kinematic-tree link behind prismatic joints only.  Give False where
        the model's constraints hold the bearing's rotation (a slider in a prismatic
        guide): it saves two connector evaluations per force evaluation.
    record : bool
        Record the joint's outputs (:meth:`ClearanceJointHandle.outputs`).
    slices : int, optional
        None or 0 (default): the planar joint.  N >= 1: the spatial joint of
        docs/physics.md section 9, for 3D bodies: the bearing length is cut into N slices,
        each a share ``L / N`` of the contact law at its own penetration, so that a tilted
        journal loads the bearing's edges and feels the restoring moment; the journal may
        also move along the axis (without ``axial_clearance`` there is no axial contact:
        hold it by the model, e.g. ``constrainAxial`` or other joints; the journal is taken
        longer than the bearing).  :data:`DEFAULT_SLICES` is the converged choice.  The
        bearing's own rotation (all three components) enters as in the planar joint,
        through the probe and torque connectors.
    axial_clearance, shoulder_radius : float, optional (keyword, spatial joint only)
        Shoulder contact (docs/physics.md section 9.6): ``axial_clearance`` is the total
        axial play [m] (the journal's shoulders are ``length + axial_clearance`` apart),
        ``shoulder_radius`` the outer radius [m] of the annulus where a shoulder meets a
        bearing end face (inner radius ``bearing_radius``).  Each end face is a contact
        with its own history: a linear flat-punch stiffness ``2 E* shoulder_radius`` with
        the joint law's damping, and the joint's friction law against the relative spin
        at the annulus's friction radius.  Not with ``constrainAxial=True``.

    Returns
    -------
    ClearanceJointHandle
        ``objectNumber`` is the connector (for ``SensorObject`` with ``ForceLocal``).
    """
    check_system(mbs)
    if isinstance(itemNumbers, (str, bytes)) or len(itemNumbers) != 2:
        raise ValueError(f"`itemNumbers` must be [bearing body, journal body], got {itemNumbers!r}")
    if not isinstance(useGlobalFrame, bool):
        raise ValueError(f"`useGlobalFrame` must be True or False, got {useGlobalFrame!r}")
    b0, b1 = itemNumbers
    for role, body in (("bearing body", b0), ("journal body", b1)):
        if body is None:
            raise ValueError(f"`itemNumbers` needs the {role}")
        object_type(mbs, body, role)
    if int(b0) == int(b1):
        raise ValueError("`itemNumbers` names the same body twice; the bearing and the journal are on different bodies")
    if (object_type(mbs, b0, "bearing body") == "Ground") and (object_type(mbs, b1, "journal body") == "Ground"):
        raise ValueError("`itemNumbers` are both ground objects: one must be a moving body")
    p = vector3("position", position)
    a = vector3("axis", axis)
    if not np.linalg.norm(a) > 0.0:
        raise ValueError(f"`axis` must not be zero, got {axis!r}")
    p0, a0 = _reference_pose(mbs, b0)
    p1, a1 = _reference_pose(mbs, b1)
    if not useGlobalFrame:
        p, a = a0 @ p + p0, a0 @ a
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=b0, localPosition=(a0.T @ (p - p0)).tolist())),
               mbs.AddMarker(MarkerBodyRigid(bodyNumber=b1, localPosition=(a1.T @ (p - p1)).tolist()))]
    return AddClearanceJoint(mbs, markers, axis=(a0.T @ a).tolist(), name=name, joint=joint, backend=backend,
                             maxPenetration=maxPenetration, constrainAxial=constrainAxial,
                             bearingRotates=bearingRotates, record=record, show=show, slices=slices,
                             **joint_parameters)


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
    """A planar clearance joint from body-frame points (the form of exuclear 0.1).

    .. deprecated::
        Use :func:`CreateClearanceJoint` (bearing body first, ``maxPenetration``), or
        :func:`AddClearanceJoint` with rigid markers; the warning names the call to write.

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
    return AddClearanceJoint(mbs, markers, name=name, joint=joint, backend=backend, maxPenetration=max_penetration,
                             bearingRotates=bearing_rotates, record=record, **joint_parameters)


def _replacement(journal_body: Any, bearing_body: Any, journal_point: Any, bearing_point: Any, journal_link: Any,
                 bearing_link: Any, max_penetration: Any, bearing_rotates: Any) -> str:
    """The deprecation message of :func:`add_clearance_joint`: the call to write instead."""
    options = "".join(f", {k}={v!r}" for k, v in (("maxPenetration", max_penetration),
                                                    ("bearingRotates", bearing_rotates)) if v is not None)
    markers = (f"exuclear.AddClearanceJoint(mbs, markerNumbers=[bearing_marker, journal_marker]{options}, ...) with "
               f"rigid markers at bearing_point {tuple(bearing_point)!r} and journal_point {tuple(journal_point)!r} "
               "(MarkerBodyRigid, or MarkerKinematicTreeRigid on a kinematic-tree link)")
    if journal_link is not None or bearing_link is not None:
        return f"exuclear.add_clearance_joint is deprecated; write {markers}"
    position = [*(float(v) for v in bearing_point), 0.0]
    return ("exuclear.add_clearance_joint(mbs, journal_body, bearing_body, ...) is deprecated; write "
            f"exuclear.CreateClearanceJoint(mbs, itemNumbers=[{bearing_body!r}, {journal_body!r}], "
            f"position={position!r}, useGlobalFrame=False{options}, ...the same joint parameters) (the bearing "
            "body first; journal and bearing centred at `position`, in the bearing body's frame), or, where the "
            f"two points differ in the reference configuration, {markers}")


def _point_marker(mbs: exu.MainSystem, body: Any, point: Sequence[float], link: int | None, role: str) -> Any:
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
