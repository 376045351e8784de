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
outputs (:mod:`~exuclear.engine.outputs`), its drawing (:mod:`~exuclear.engine.drawing`),
the builders' argument checks (:mod:`~exuclear.engine.arguments`) and the deprecated
body-point builder (:mod:`~exuclear.engine.legacy`).
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any, NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    ObjectJointGeneric,
    VObjectJointGeneric,
)
from exudyn.rigidBodyUtilities import ComputeOrthonormalBasis

from ..checks import check_choice, check_positive
from ..joint import ClearanceJoint
from ..spatial import FACE_SIDES
from . import kernel
from .arguments import (
    AXIS_UNIT_TOLERANCE,
    DEFAULT_SLICES,
    PENETRATION_LIMIT_CLEARANCE,
    PENETRATION_LIMIT_RADIUS,
    check_axis,
    check_contact_mode,
    check_flags,
    check_marker,
    check_markers,
    check_rigid_body_marker,
    check_shoulders,
    check_slices,
    check_system,
    check_wear,
    default_penetration_limit,
    object_type,
    physics,
    vector3,
)
from .drawing import drawing_function, drawing_sizes
from .handle import ClearanceJointHandle, JointHistory
from .impulse import ImpulseJointHandle, add_impulse_joint
from .impulse_group import ImpulsePairsHandle, add_impulse_slices
from .items import add_connectors, finish_items
from .layout import MAIN, data_columns, parameters, spatial_data_columns
from .modes import IMPULSE, choose_mode
from .outputs import FACE_OUTPUT_PREFIX, OUTPUT_COLUMNS, SPATIAL_OUTPUT_COLUMNS
from .placement import PLACED_BY_POSITION
from .registry import REGISTRY_KEY, joints_of

#: Names kept here for the code that imports them from this module.
__all__ = ["AXIS_UNIT_TOLERANCE", "BACKENDS", "DEFAULT_BACKEND", "DEFAULT_SLICES", "FACE_OUTPUT_PREFIX",
           "OUTPUT_COLUMNS", "PENETRATION_LIMIT_CLEARANCE", "PENETRATION_LIMIT_RADIUS", "REGISTRY_KEY",
           "SPATIAL_OUTPUT_COLUMNS", "AddClearanceJoint", "ClearanceJointHandle", "CreateClearanceJoint",
           "JointHistory", "default_penetration_limit", "drawing_function", "joint_frame",
           "joints_of", "revolute_frame"]

#: How the joint's user functions are evaluated.
BACKENDS = {"compiled": "C++ kernel called by Exudyn without Python (the default where it passed its self-test)",
            "python": "Python kernel: the readable statement, and the path for laws written in Python"}

#: The backend used where none is given: ``"compiled"`` where its self-test passed.
DEFAULT_BACKEND = kernel.default_backend()


#: Largest entry of ``R - I`` below which two markers' reference frames are taken as one:
#: the round-off of composing and reading back rotation matrices (1e-16 per product),
#: far below any frame a user sets on purpose.
SAME_FRAME_ROUNDOFF = 1e-12


def joint_frame(axis: np.ndarray) -> np.ndarray:
    """Rotation matrix whose z column is ``axis`` (unit); for ``axis = z`` the identity, so
    that a planar model's eccentricity is in global x, y."""
    z = axis / np.linalg.norm(axis)
    e = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = e - (e @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def revolute_frame(axis: np.ndarray) -> np.ndarray:
    """The joint frame of Exudyn's ``mbs.CreateRevoluteJoint`` for a global ``axis``: z along
    the axis, x and y from Exudyn's ``ComputeOrthonormalBasis`` (its columns b0 = axis, b1,
    b2: x = -b2, y = b1).  Its revolute joint reports ``ForceLocal`` and ``TorqueLocal`` in
    this frame (the markers' rotation); for ``axis = z`` it is x = -y_global, y = x_global."""
    b = ComputeOrthonormalBasis(np.asarray(axis, dtype=float))
    return np.column_stack([-b[:, 2], b[:, 1], b[:, 0]])


def _reference_pose(mbs: exu.MainSystem, item: Any, where: str) -> tuple[np.ndarray, np.ndarray]:
    """Position and rotation matrix, in the reference configuration, of a rigid marker or
    of a body's reference point (where the body has no rotation matrix output, as
    ``ObjectANCFCable2D``: its planar rotation angle)."""
    ref, ov = exu.ConfigurationType.Reference, exu.OutputVariableType
    if isinstance(item, exu.MarkerIndex):
        return (np.asarray(mbs.GetMarkerOutput(item, ov.Position, configuration=ref), dtype=float),
                _marker_rotation(mbs, item))
    p = np.asarray(mbs.GetObjectOutputBody(item, ov.Position, localPosition=[0, 0, 0], configuration=ref), dtype=float)
    try:
        a = np.asarray(mbs.GetObjectOutputBody(item, ov.RotationMatrix, localPosition=[0, 0, 0], configuration=ref),
                       dtype=float).reshape(3, 3)
    except Exception:  # Exudyn raises its own error types for an output a body does not have
        try:
            phi = float(mbs.GetObjectOutputBody(item, ov.Rotation, localPosition=[0, 0, 0], configuration=ref))
        except Exception:  # no planar angle either (a 3D flexible element)
            raise ValueError(f"{where} (object {int(item)}, an Object{mbs.GetObject(item)['objectType']}) gives no "
                             "reference orientation from which to place the joint's marker: give a rigid marker on it "
                             "(e.g. MarkerBodyRigid or MarkerNodeRigid) in `itemNumbers`") from None
        c, s = math.cos(phi), math.sin(phi)
        a = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
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
    contact_mode: str | None = None,
    _frame: np.ndarray | None = None,
    _drawing: dict | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle | ImpulseJointHandle | ImpulsePairsHandle:
    """Add a clearance joint between two rigid markers: the bearing hole's centre on
    ``markerNumbers[0]``, the journal's centre on ``markerNumbers[1]``.

    ``axis`` is the bearing axis in marker 0's frame (default its z axis); the contact acts
    in the plane normal to it (planar joint), or slice by slice along it (``slices``; the
    journal's axis is taken parallel to it in the reference configuration).  The other
    arguments are those of :func:`CreateClearanceJoint`.  Call before ``mbs.Assemble()``.
    Where the joint frame is not marker 0's own, the joint sits on copies of the two markers
    turned into it (``handle.markerNumbers``), as ``mbs.CreateRevoluteJoint`` makes them.
    """
    check_system(mbs)
    check_contact_mode(contact_mode)
    check_markers(mbs, markerNumbers)
    axial_clearance = joint_parameters.pop("axial_clearance", None)
    shoulder_radius = joint_parameters.pop("shoulder_radius", None)
    joint = physics(joint, joint_parameters)
    axis_local = check_axis(axis) if _frame is None else None
    slices = check_slices(slices)
    shoulders = check_shoulders(axial_clearance, shoulder_radius, slices, constrainAxial, joint)
    check_flags(name, bearingRotates, constrainAxial=constrainAxial, record=record, show=show)
    backend, maxPenetration = kernel_settings(joint, backend, maxPenetration)
    check_wear(joint, slices, backend)
    mode = choose_mode(contact_mode, joint, slices, backend, name, joint_type=joint.geometry.joint_type)
    m_bearing, m_journal = markerNumbers
    a_bearing = _marker_rotation(mbs, m_bearing)
    a_journal = _marker_rotation(mbs, m_journal)
    # the joint frame in marker 0's frame: from `axis`, or the global frame CreateClearanceJoint gives
    frame = joint_frame(axis_local) if _frame is None else a_bearing.T @ np.asarray(_frame, dtype=float)
    if not np.array_equal(frame, np.eye(3)) and all("localHT" in mbs.GetMarker(m) for m in (m_bearing, m_journal)):
        # copies of the markers turned into the joint frame, as Exudyn's CreateRevoluteJoint
        # makes them: its connectors' rotationMarker0/1 are deprecated
        m_bearing, m_journal = (_turned_marker(mbs, m_bearing, frame),
                                _turned_marker(mbs, m_journal, a_journal.T @ a_bearing @ frame))
        a_bearing, a_journal, frame = _marker_rotation(mbs, m_bearing), _marker_rotation(mbs, m_journal), np.eye(3)
    rotation0 = frame.tolist()
    relative = a_journal.T @ a_bearing @ frame  # the same joint frame, seen from marker 1
    if np.abs(relative - np.eye(3)).max() <= SAME_FRAME_ROUNDOFF:
        relative = np.eye(3)  # markers turned into one frame: no deprecated rotationMarker1 for round-off
    rotation1 = relative.tolist()
    # the journal axis in marker 1's frame: the bearing axis in the reference configuration (eq. (34))
    axis_journal = tuple(float(v) for v in relative[:, 2])
    if mode == IMPULSE:  # the mode's own items (exuclear.engine.modes); the spatial joint's a pair per slice
        impulse = add_impulse_slices(mbs, joint, name, [m_bearing, m_journal], frame, relative[:, 2], slices,
                                     shoulders, axial=not constrainAxial) if slices else \
            add_impulse_joint(mbs, joint, name, [m_bearing, m_journal], frame)
        if constrainAxial:
            impulse.constraintNumber = _axial_constraint(mbs, name, [m_bearing, m_journal], slices, rotation0,
                                                         rotation1)
        return impulse

    handle = ClearanceJointHandle(mbs, joint, name, backend, float(maxPenetration), slices, axis_journal, shoulders)
    handle.markerNumbers = [m_bearing, m_journal]
    handle._axis_local = frame[:, 2].copy()
    handle._drawing = _drawing or {}
    if bearingRotates is None:
        bearingRotates = not _orientation_is_fixed(mbs, m_bearing)
    n_faces = len(FACE_SIDES) if shoulders is not None else 0
    lubricated = joint.film is not None
    n_data = len(spatial_data_columns(slices, n_faces, lubricated)) if slices else len(data_columns(lubricated))
    add_connectors(mbs, handle, [m_bearing, m_journal], rotation0, bearingRotates, n_data, show,
                   2.0 * joint.geometry.bearing_radius)
    if constrainAxial:
        handle.constraintNumber = _axial_constraint(mbs, name, [m_bearing, m_journal], slices, rotation0, rotation1)
    finish_items(mbs, handle, drawing_function if show else None, record, load_sensors=bool(slices))
    return handle


def _axial_constraint(mbs: exu.MainSystem, name: str, markers: list, slices: int, rotation0: list,
                      rotation1: list) -> int:
    """The ``ObjectJointGeneric`` of ``constrainAxial=True``: the axial translation held (and,
    for the planar joint, the two tilts)."""
    return mbs.AddObject(ObjectJointGeneric(
        name=f"{name}:axial" if name else "", markerNumbers=markers,
        constrainedAxes=[0, 0, 1, 0, 0, 0] if slices else [0, 0, 1, 1, 1, 0], rotationMarker0=rotation0,
        rotationMarker1=rotation1, visualization=VObjectJointGeneric(show=False)))


def CreateClearanceJoint(  # noqa: N802 - Exudyn's naming of item factories
    mbs: exu.MainSystem,
    name: str = "",
    itemNumbers: Sequence[Any] = (None, None),
    position: Sequence[float] | None = None,
    axis: Sequence[float] = (0.0, 0.0, 1.0),
    useGlobalFrame: bool = True,
    show: bool = True,
    axisRadius: float | None = None,
    axisLength: float | None = None,
    color: Sequence[float] | None = None,
    bodyNumbers: Sequence[Any] | None = None,
    *,
    joint: ClearanceJoint | None = None,
    backend: str | None = None,
    maxPenetration: float | None = None,
    constrainAxial: bool = False,
    bearingRotates: bool | None = None,
    record: bool = True,
    slices: int | None = None,
    contact_mode: str | None = None,
    **joint_parameters: Any,
) -> ClearanceJointHandle | ImpulseJointHandle | ImpulsePairsHandle:
    """Create a revolute clearance joint between two bodies, as ``mbs.CreateRevoluteJoint`` does
    for an ideal one: the bearing (hole) on ``itemNumbers[0]``, the journal (pin) on
    ``itemNumbers[1]``, both centred at ``position`` in the reference configuration.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system; call before ``mbs.Assemble()``.
    name : str
        The joint's name (its connector's).
    itemNumbers : [bearing item, journal item]
        Each a body (``ObjectIndex``) or a rigid marker (``MarkerIndex``), as in
        ``mbs.CreateRevoluteJoint``: the ground, ``ObjectRigidBody2D``, the bodies of
        ``mbs.CreateRigidBody`` with any rotation node, ``ObjectRigidBody``, flexible
        elements that give a ``MarkerBodyRigid`` (``ObjectANCFCable2D``: the joint's
        marker sits at ``position`` on the element's axis).  Where a body cannot carry the
        joint, give a marker: a ``MarkerNodeRigid`` on a node of an
        ``ObjectBeamGeometricallyExact2D`` (on which a ``MarkerBodyRigid`` fails at the
        first step, so it is refused here), and a ``MarkerKinematicTreeRigid`` on a
        kinematic-tree link (``ObjectKinematicTree`` is refused: a joint needs a link, and
        the tree must give the journal's link its in-plane play, e.g. ``PrismaticX`` and
        ``PrismaticY`` links before its revolute joint, which its own joint holds otherwise).
    position : 3 floats, optional
        The joint's centre [m]: global (``useGlobalFrame=True``) or in item 0's frame;
        default the global origin.  Where an item is a marker, the marker sets the centre
        and ``position`` must be omitted (or ``[]``), as in ``mbs.CreateRevoluteJoint``.
    axis : 3 floats
        Bearing axis (global, or item 0's frame); the contact acts in the plane normal to it.
        The joint frame is that of ``mbs.CreateRevoluteJoint`` (:func:`revolute_frame`):
        ``ForceLocal``/``TorqueLocal`` of ``objectNumber``, the eccentricity and the tilt
        outputs are in the frame the replaced revolute joint reports in.
    useGlobalFrame : bool
        Whether ``position`` and ``axis`` are global (True) or in item 0's frame.
    show : bool
        Draw the joint (Exudyn draws its connector; nothing is drawn without a renderer).
    axisRadius, axisLength : float, optional
        ``mbs.CreateRevoluteJoint``'s drawing sizes [m]: the drawn journal radius (the
        bearing drawn to the same scale, so the play stays in proportion) and the drawn
        length; default the joint's own ``journal_radius`` and ``length``.
    color : 4 floats, optional
        RGBA colour of the drawn journal.
    bodyNumbers : deprecated
        Exudyn's former name of ``itemNumbers`` (a ``DeprecationWarning``, as Exudyn gives).
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
        (``slices``) the axial translation only, since the slices carry the tilt.  A spatial
        journal started aligned under varying in-plane loads tilts from round-off (an
        unstable mode of the slices, docs/physics.md section 9.8): for a model meant to stay
        planar, leave out ``slices``.
        Where nothing in the model holds what the replaced revolute joint held (a 3D
        journal whose only link to the bearing is this joint), :func:`exuclear.simulate`
        warns before the run (``OutOfPlaneWarning``, naming the joint, the motion and
        this fix); :func:`exuclear.engine.unheld_motion` is the same check for a plain
        ``mbs.SolveDynamic``.
    bearingRotates : bool, optional
        Whether the bearing body can turn about the axis.  Where it can, two helper
        connectors supply the bearing's own spin to the slip and its own moment
        (docs/physics.md section 4.1).  None (default): True unless the bearing is the
        ground or a kinematic-tree link behind prismatic joints only.  Give False where
        the model's constraints hold the bearing's rotation (a slider in a prismatic
        guide): it saves two connector evaluations per force evaluation.  Where the
        joint's loads do not use the bearing's spin (a planar joint without friction and
        without a film), both connectors are switched off by the joint itself
        (docs/physics.md section 4.1); a new physics (``joint.joint = ...``) switches
        them on again where it needs them.
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
    contact_mode : str, optional
        ``"compliant"`` (the default; None: ``EXUCLEAR_CONTACT_MODE`` where set) or
        ``"impulse"`` (docs/guide/contact_modes.md: velocity jumps, resting contact as a
        condition; returns an :class:`~exuclear.engine.impulse.ImpulseJointHandle`, with
        ``slices`` an :class:`~exuclear.engine.impulse_group.ImpulsePairsHandle`, a contact
        per slice and per end face of ``axial_clearance``).

    Returns
    -------
    ClearanceJointHandle
        ``objectNumber`` is the connector (for ``SensorObject`` with ``ForceLocal``).
    """
    check_system(mbs)
    check_contact_mode(contact_mode)
    draw = drawing_sizes(axisRadius, axisLength, color)
    a = check_axis(axis)
    items = joint_items(mbs, itemNumbers, bodyNumbers, ("bearing", "journal"), position, useGlobalFrame,
                        "CreateRevoluteJoint", tree_advice=REVOLUTE_TREE_ADVICE)
    (b0, b1), kinds, p = items.items, items.kinds, items.centre
    (p0, a0), (p1, a1) = items.poses
    if not useGlobalFrame:
        a = a0 @ a
    # the joint frame of mbs.CreateRevoluteJoint, carried by the markers' localHT as Exudyn
    # carries it (its rotationMarker0 is deprecated): joint frame z = the axis in both markers
    frame = revolute_frame(a)
    markers, frame0 = [], None
    for item, kind, pos, rot in ((b0, kinds[0], p0, a0), (b1, kinds[1], p1, a1)):
        turn = rot.T @ frame
        if kind != "marker":
            markers.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localHT=exu.HT(
                rotation=turn, translation=rot.T @ (p - pos)))))
            continue
        marker = _turned_marker(mbs, item, turn)
        if marker is None:  # a marker without localHT: the connector's rotationMarker0 takes the frame
            marker, frame0 = item, (frame if not markers else frame0)
        markers.append(marker)
    handle = AddClearanceJoint(mbs, markers, name=name, joint=joint, backend=backend, maxPenetration=maxPenetration,
                               constrainAxial=constrainAxial, bearingRotates=bearingRotates, record=record, show=show,
                               slices=slices, contact_mode=contact_mode, _frame=frame0, _drawing=draw,
                               **joint_parameters)
    if "marker" not in kinds:
        handle.placed_by = PLACED_BY_POSITION
    return handle


def kernel_settings(joint: ClearanceJoint, backend: str | None, max_penetration: float | None) -> tuple[str, float]:
    """A builder's ``backend`` (None: the default) and ``maxPenetration`` (None:
    :func:`default_penetration_limit`), checked, after a trial of the parameters the kernel
    will take, which refuses a law or friction it has no compiled form of."""
    backend = kernel.default_backend() if backend is None else check_choice("backend", backend, BACKENDS)
    if backend == "compiled" and kernel.COMPILED is None:
        raise ValueError(f"backend 'compiled' is not available: {kernel.REASON}")
    if max_penetration is None:
        max_penetration = default_penetration_limit(joint.geometry)
    check_positive("maxPenetration", max_penetration)
    parameters(joint, 0, MAIN, max_penetration, compiled=backend == "compiled")  # refuses what the kernel cannot do
    return backend, float(max_penetration)


#: What a revolute joint on a kinematic tree needs beyond a link's marker (``joint_items``).
REVOLUTE_TREE_ADVICE = ("give the journal's link its in-plane play in the tree (PrismaticX and PrismaticY links before "
                        "its revolute joint), and ")


class JointItems(NamedTuple):
    """The two items of a ``Create*ClearanceJoint`` as :func:`joint_items` checks them: the
    items, their kinds (an object type, or ``"marker"``), the joint's centre (global, in the
    reference configuration) and each item's reference pose (position, rotation matrix)."""

    items: tuple[Any, Any]
    kinds: list[str]
    centre: np.ndarray
    poses: tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def joint_items(mbs: exu.MainSystem, itemNumbers: Any, bodyNumbers: Any, roles: tuple[str, str],  # noqa: N803
                position: Any, useGlobalFrame: Any, exudyn_name: str, tree_advice: str = "") -> JointItems:  # noqa: N803
    """The items of a joint builder with Exudyn's keywords (``itemNumbers``, its deprecated
    ``bodyNumbers``, ``position``, ``useGlobalFrame``; the rules of Exudyn's ``exudyn_name``):
    each a body with a rigid marker or a rigid marker, ``roles`` naming them in messages; a
    marker sets the centre, else ``position`` (global, or in item 0's frame)."""
    if bodyNumbers is not None:
        if tuple(itemNumbers) != (None, None):
            raise ValueError("give `itemNumbers` only: `bodyNumbers` is its deprecated name, and both were given")
        warnings.warn(f"`bodyNumbers` is deprecated (as in Exudyn's {exudyn_name}): use `itemNumbers`",
                      DeprecationWarning, stacklevel=3)
        itemNumbers = bodyNumbers
    if isinstance(itemNumbers, (str, bytes)) or len(itemNumbers) != 2:
        raise ValueError(f"`itemNumbers` must be [{roles[0]} item, {roles[1]} item] (bodies or rigid markers), "
                         f"got {itemNumbers!r}")
    if not isinstance(useGlobalFrame, bool):
        raise ValueError(f"`useGlobalFrame` must be True or False, got {useGlobalFrame!r}")
    kinds = []
    for k, (role, item) in enumerate(zip(roles, itemNumbers)):
        if item is None:
            raise ValueError(f"`itemNumbers` needs the {role} item (a body or a rigid marker)")
        where = f"`itemNumbers[{k}]`"
        if isinstance(item, exu.MarkerIndex):
            check_marker(mbs, item, where)
            kinds.append("marker")
            continue
        kind = object_type(mbs, item, f"{role} body")
        if kind == "KinematicTree":
            raise ValueError(f"{where} is an ObjectKinematicTree: a joint on a tree sits on one of its links, whose "
                             f"motion the tree's own joints hold: {tree_advice}give MarkerKinematicTreeRigid "
                             "markers (objectNumber, linkNumber, localPosition) in `itemNumbers` "
                             "(validation/exudyn_examples/kinematic_tree_chain.py)")
        check_rigid_body_marker(mbs, item, where)
        kinds.append(kind)
    b0, b1 = itemNumbers
    if "marker" not in kinds:
        if int(b0) == int(b1):
            raise ValueError(f"`itemNumbers` names the same body twice; the {roles[0]} and the {roles[1]} are on "
                             "different bodies")
        if kinds == ["Ground", "Ground"]:
            raise ValueError("`itemNumbers` are both ground objects: one must be a moving body")
    p0, a0 = _reference_pose(mbs, b0, "`itemNumbers[0]`")
    p1, a1 = _reference_pose(mbs, b1, "`itemNumbers[1]`")
    if "marker" in kinds:  # the marker sets the joint's centre (Exudyn's rule)
        if position is not None and len(position) != 0:
            raise ValueError(f"`position` must be omitted (or []) where `itemNumbers` gives a marker: the marker sets "
                             f"the joint's centre, got {position!r}")
        p = p0 if kinds[0] == "marker" else p1
    else:
        p = vector3("position", (0.0, 0.0, 0.0) if position is None else position)
        if not useGlobalFrame:
            p = a0 @ p + p0
    return JointItems((b0, b1), kinds, p, ((p0, a0), (p1, a1)))


def _turned_marker(mbs: exu.MainSystem, marker: Any, rotation: np.ndarray) -> Any:
    """A rigid marker whose frame is ``marker``'s turned by ``rotation`` (in its own frame):
    the marker itself for the unit rotation, else a copy with the composed ``localHT``;
    None for a marker without ``localHT``."""
    if np.array_equal(rotation, np.eye(3)):
        return marker
    data = mbs.GetMarker(marker)
    if "localHT" not in data:
        return None
    copy = {key: value for key, value in data.items() if key not in ("name", "localPosition") and key[0] != "V"}
    copy["localHT"] = exu.HT(data["localHT"]) @ exu.HT(rotation=rotation)
    return mbs.AddMarker(copy)
