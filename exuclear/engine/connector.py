"""The clearance joint as Exudyn items: ``CreateClearanceJoint`` and its handle.

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
"""
from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
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
from ..history import ContactState, ImpactRecord
from ..joint import ClearanceJoint, make_joint
from ..spatial import FACE_SIDES, ShoulderGeometry, slice_centres
from . import kernel
from ._python_kernel import PythonJointKernel, SpatialJointKernel, data_values, spatial_data_values
from .layout import (
    DATA_COLUMNS,
    MAIN,
    PROBE,
    SLICE_COLUMNS,
    SPATIAL_JOINT_COLUMNS,
    TORQUE,
    parameters,
    spatial_data_columns,
)

#: How the joint's user functions are evaluated.
BACKENDS = {"compiled": "C++ kernel called by Exudyn without Python (the default where it passed its self-test)",
            "python": "Python kernel: the readable statement, and the path for laws written in Python"}

#: The backend used where none is given: ``"compiled"`` where its self-test passed.
DEFAULT_BACKEND = kernel.default_backend()

#: Columns of :meth:`ClearanceJointHandle.outputs` after ``time`` (SI units).
OUTPUT_COLUMNS = ("penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "tangential_force",
                  "slip_velocity", "v0", "in_contact")
#: A spatial joint's outputs: the journal's tilt (axis components x, y in the bearing's
#: joint frame) and axial displacement [m], then :data:`OUTPUT_COLUMNS` per slice
#: (arrays of shape (times, slices); ``slip_velocity`` is the slip speed, ``tangential_force``
#: the friction force's magnitude).
SPATIAL_OUTPUT_COLUMNS = ("tilt_x", "tilt_y", "axial_displacement")
#: With an axial clearance (docs/physics.md section 9.6), the end faces' outputs: ``"face_"``
#: and each of :data:`OUTPUT_COLUMNS`, arrays of shape (times, 2), face 0 at z = -L/2
#: (``slip_velocity`` the signed circumferential slip at the friction radius,
#: ``tangential_force`` the signed friction force there).
FACE_OUTPUT_PREFIX = "face_"

#: Recommended number of slices of a spatial joint (docs/physics.md section 9.3): total
#: force within 0.22 % and restoring moment within 0.47 % while the contact zone spans at
#: least 8 slices; raise it for shorter edge contacts (L / N <= contact length / 8).
DEFAULT_SLICES = 20
#: An axis whose length differs from 1 by more than this is normalised with a warning.
AXIS_UNIT_TOLERANCE = 1e-9

#: Default penetration bound, the larger of these fractions of the clearance and of the
#: journal radius: it catches blow-ups (a journal sinking through its bearing), not hard
#: impacts (a 1.3 m/s crank-pin impact exceeds 10 % of its 0.1 mm clearance; a 1 um
#: clearance sees 0.4 um of static penetration).
PENETRATION_LIMIT_CLEARANCE = 0.5
PENETRATION_LIMIT_RADIUS = 1e-3

_TOKENS = itertools.count(1)
#: ``mbs.variables`` key of the joints created in a system (for exuclear.simulate).
REGISTRY_KEY = "exuclear.joints"

_RIGID_MARKERS = ("BodyRigid", "NodeRigid", "KinematicTreeRigid", "SuperElementRigid")


def default_penetration_limit(geometry: Any) -> float:
    """The default penetration bound [m] of a joint (:data:`PENETRATION_LIMIT_CLEARANCE`)."""
    return max(PENETRATION_LIMIT_CLEARANCE * geometry.clearance, PENETRATION_LIMIT_RADIUS * geometry.journal_radius)


def _vector3(name: str, value: Any) -> np.ndarray:
    try:
        v = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be 3 finite numbers, got {value!r}") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"`{name}` must be 3 finite numbers, got {value!r}")
    return v


def joint_frame(axis: np.ndarray) -> np.ndarray:
    """Rotation matrix whose z column is ``axis`` (unit); for ``axis = z`` the identity, so
    that a planar model's eccentricity is in global x, y."""
    z = axis / np.linalg.norm(axis)
    e = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = e - (e @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def _object_type(mbs: exu.MainSystem, item: Any, role: str) -> str:
    try:
        return mbs.GetObject(item)["objectType"]
    except Exception:  # Exudyn raises its own error types for a bad index
        raise ValueError(f"`itemNumbers` {role} {item!r} is not an object of this MainSystem") from None


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


class ClearanceJointHandle:
    """A clearance joint in an Exudyn system; returned by :func:`CreateClearanceJoint`.

    Attributes (Exudyn indices)
    ---------------------------
    objectNumber : the joint's connector; ``SensorObject`` on it with ``ForceLocal`` /
        ``TorqueLocal`` records ``-F_i`` and ``-M_i`` (the loads on the bearing from the
        journal, in the bearing's joint frame).
    nodeNumber : the ``NodeGenericData`` with :data:`exuclear.engine.layout.DATA_COLUMNS`
        after every accepted step.
    markerNumbers : [bearing marker, journal marker].
    sensorNumber : the sensor that records the data node (None with ``record=False``).
    probeNumber, torqueNumber : the bearing-spin probe and torque connectors (None where
        the bearing is the ground).
    constraintNumber : the ``ObjectJointGeneric`` of ``constrainAxial=True``, else None.
    drawingNumber : the ground object whose graphics function draws journal and bearing
        (``show=True``), else None.
    """

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, backend: str,
                 max_penetration: float, slices: int = 0,
                 axis_journal: tuple[float, float, float] = (0.0, 0.0, 1.0),
                 shoulders: ShoulderGeometry | None = None) -> None:
        self.mbs, self.name, self.backend, self.max_penetration = mbs, name, backend, max_penetration
        self._joint = joint
        self.slices, self.axis_journal, self.shoulders = slices, axis_journal, shoulders
        if backend != "python":
            self.python_kernel = None
        elif slices:
            self.python_kernel = SpatialJointKernel(joint, slices, axis_journal, shoulders)
        else:
            self.python_kernel = PythonJointKernel(joint)
        self.joint_id = kernel.COMPILED.new_joint() if backend == "compiled" else -1
        self.objectNumber: Any = None
        self.nodeNumber: Any = None
        self.markerNumbers: list = []
        self.sensorNumber: Any = None
        self.probeNumber: Any = None
        self.torqueNumber: Any = None
        self.constraintNumber: Any = None
        self.drawingNumber: Any = None
        self._axis_local: np.ndarray | None = None  # the bearing axis in marker 0's frame
        self._impact_step = 0.0
        self.token = next(_TOKENS)  # identifies the handle's connector in its system (see is_live)

    # -- the physics, replaceable between runs ---------------------------------------------
    @property
    def joint(self) -> ClearanceJoint:
        """The joint's physics (geometry, contact law, friction law)."""
        return self._joint

    @joint.setter
    def joint(self, joint: ClearanceJoint) -> None:
        if not isinstance(joint, ClearanceJoint):
            raise ValueError(f"`joint` must be a ClearanceJoint, got {type(joint).__name__}")
        self._joint = joint
        if self.python_kernel is not None:
            self.python_kernel.joint = joint
        self._write_parameters()

    def set_impact_step(self, impact_step: float) -> None:
        """Redo a step in which a contact begins with this step [s] (implicit solvers); 0: off."""
        self._impact_step = float(impact_step)
        self._write_parameters()

    def _write_parameters(self) -> None:
        for number, role in ((self.objectNumber, MAIN), (self.probeNumber, PROBE), (self.torqueNumber, TORQUE)):
            if number is not None:
                p = parameters(self._joint, self.joint_id, role, self.max_penetration, self._impact_step,
                               compiled=self.python_kernel is None, slices=self.slices,
                               axis_journal=self.axis_journal, shoulders=self.shoulders)
                p[4][0] = float(self.token)
                self.mbs.SetObjectParameter(number, "stiffness", p)

    def is_live(self) -> bool:
        """Whether the joint's connector is still in its system (not removed by ``mbs.Reset()``)."""
        try:
            return self.mbs.GetObjectParameter(self.objectNumber, "stiffness")[4][0] == float(self.token)
        except Exception:  # the index no longer exists, or is another kind of object
            return False

    # -- state ---------------------------------------------------------------------------
    def reset(self) -> None:
        """Forget the contact history (a run also does so when it starts from its initial time)."""
        if self.python_kernel is not None:
            self.python_kernel.reset()
        else:
            kernel.COMPILED.reset(self.joint_id)

    def state(self) -> ContactState:
        """The contact history after the last accepted step (a spatial joint: that of its
        most penetrated slice or end face)."""
        if self.slices:
            return max(self._contact_states(), key=lambda s: s.delta)
        if self.python_kernel is not None:
            return self.python_kernel.current
        return ContactState(**kernel.COMPILED.history(self.joint_id)["current"])

    def _contact_states(self, which: str = "current") -> list[ContactState]:
        """The slices' histories, then the end faces' (with an axial clearance)."""
        if self.python_kernel is not None:
            return list(getattr(self.python_kernel, which))
        return [ContactState(**h) for h in kernel.COMPILED.slice_history(self.joint_id)[which]]

    def slice_states(self, which: str = "current") -> list[ContactState]:
        """A spatial joint's slice histories after the last accepted step (``which=
        "initial"``: at the run's initial state), slice 0 at ``z = -L/2``."""
        if not self.slices:
            raise ValueError(f"joint {self.name!r} is planar (slices=None): it has no slices")
        return self._contact_states(which)[:self.slices]

    def face_states(self, which: str = "current") -> list[ContactState]:
        """The end faces' contact histories (docs/physics.md section 9.6), face 0 at
        ``z = -L/2``; ``delta`` is the axial penetration."""
        self._check_faces()
        return self._contact_states(which)[self.slices:]

    def _check_faces(self) -> None:
        if self.shoulders is None:
            raise ValueError(f"joint {self.name!r} has no axial clearance (axial_clearance=None): it has no end faces")

    @property
    def slice_positions(self) -> np.ndarray:
        """Axial positions ``z_k`` [m] of a spatial joint's slice planes in the bearing's
        joint frame (docs/physics.md eq. (33))."""
        if not self.slices:
            raise ValueError(f"joint {self.name!r} is planar (slices=None): it has no slices")
        return np.array(slice_centres(self._joint.geometry.length, self.slices))

    def _initial_state(self) -> ContactState | None:
        if self.python_kernel is not None:
            k = self.python_kernel
            return (k.initial if not self.slices else k.initial[0]) if k.started else None
        h = kernel.COMPILED.history(self.joint_id)
        if not h["started"]:
            return None
        if self.slices:
            return ContactState(**kernel.COMPILED.slice_history(self.joint_id)["initial"][0])
        return ContactState(**h["initial"])

    def _initial_data(self) -> list[float]:
        """The data node's entries at the run's initial state."""
        if not self.slices:
            return data_values(self._initial_state())
        if self.python_kernel is not None:
            u, axial = self.python_kernel.initial_axis, self.python_kernel.initial_axial
        else:
            u, axial = kernel.COMPILED.initial_axis(self.joint_id)
        states = self._contact_states("initial")
        return spatial_data_values(states[0].time, u, axial, states)

    def _contact_impacts(self) -> list[list[ImpactRecord]]:
        if self.python_kernel is not None:
            return [list(r) for r in self.python_kernel.records]
        return [[ImpactRecord(*r) for r in rs] for rs in kernel.COMPILED.slice_records(self.joint_id)]

    def slice_impacts(self) -> list[list[ImpactRecord]]:
        """A spatial joint's ended contacts, per slice."""
        if not self.slices:
            raise ValueError(f"joint {self.name!r} is planar (slices=None): it has no slices")
        return self._contact_impacts()[:self.slices]

    def face_impacts(self) -> list[list[ImpactRecord]]:
        """The end faces' ended contacts (axial impacts), per face (face 0 at ``z = -L/2``)."""
        self._check_faces()
        return self._contact_impacts()[self.slices:]

    def impacts(self) -> list[ImpactRecord]:
        """Records of the contacts that ended in the last run, in order; a contact still
        going on at the end is :meth:`state` (``in_contact``).  A spatial joint: every
        slice's records, by onset time (one contact of a tilted journal may touch
        several slices, each a record), and the end faces' with an axial clearance."""
        if self.slices:
            return sorted((r for rs in self._contact_impacts() for r in rs), key=lambda r: r.onset_time)
        if self.python_kernel is not None:
            return list(self.python_kernel.records)
        return [ImpactRecord(*r) for r in kernel.COMPILED.records(self.joint_id)]

    @property
    def nodes(self) -> list[int]:
        """The nodes of the bearing's and the journal's bodies (where a body has one node)."""
        found = []
        for marker in self.markerNumbers:
            m = self.mbs.GetMarker(marker)
            body = m.get("bodyNumber", m.get("objectNumber"))
            node = self.mbs.GetObject(body).get("nodeNumber") if body is not None else None
            if node is not None and int(node) >= 0:
                found.append(int(node))
        return found

    @property
    def history(self) -> JointHistory:
        """The contact history of the last run: the state after the last accepted step, the
        records of the ended contacts, and every onset time."""
        state, impacts = self.state(), self.impacts()
        onset_times = [r.onset_time for r in impacts] + ([state.onset_time] if state.in_contact else [])
        return JointHistory(state, impacts, onset_times)

    def failure(self) -> tuple[str, float]:
        """Why and when the joint stopped the last run (``""`` if it did not)."""
        if self.python_kernel is not None:
            return self.python_kernel.failure, self.python_kernel.failure_time
        return tuple(kernel.COMPILED.failure(self.joint_id))

    def outputs(self) -> dict[str, np.ndarray]:
        """Recorded outputs: ``time`` and :data:`OUTPUT_COLUMNS`, SI units.

        Recorded at Exudyn's sensor write period (``solution.sensors.writePeriod``) from
        the data node, i.e. at accepted steps; the first row is the run's initial state.
        """
        if self.sensorNumber is None:
            raise RuntimeError(f"joint {self.name!r} was created with record=False: nothing was recorded")
        try:
            data = np.asarray(self.mbs.GetSensorStoredData(self.sensorNumber), dtype=float)
        except Exception:  # Exudyn raises when the sensor has no data yet
            data = np.zeros((0, 0))
        if data.ndim != 2 or data.shape[0] == 0:
            raise RuntimeError(f"joint {self.name!r} has no outputs yet: run a simulation first")
        initial = self._initial_state()
        if initial is not None and data[0, 0] == initial.time:  # the data node holds no state before the first step
            data = data.copy()
            data[0, 1:] = self._initial_data()
        if self.slices:
            n_joint, n_slice = len(SPATIAL_JOINT_COLUMNS), len(SLICE_COLUMNS)
            # after the sensor's time: the data node's own time, then SPATIAL_OUTPUT_COLUMNS
            out = {"time": data[:, 0], **{c: data[:, 2 + k] for k, c in enumerate(SPATIAL_OUTPUT_COLUMNS)}}
            end = 1 + n_joint + self.slices * n_slice
            block = data[:, 1 + n_joint:end].reshape(data.shape[0], self.slices, n_slice)
            for c in OUTPUT_COLUMNS:
                out[c] = block[:, :, SLICE_COLUMNS.index(c)]
            if self.shoulders is not None:
                faces = data[:, end:].reshape(data.shape[0], len(FACE_SIDES), n_slice)
                for c in OUTPUT_COLUMNS:
                    out[FACE_OUTPUT_PREFIX + c] = faces[:, :, SLICE_COLUMNS.index(c)]
            return out
        column = {c: data[:, k + 1] for k, c in enumerate(DATA_COLUMNS)}
        return {"time": data[:, 0], **{c: column[c] for c in OUTPUT_COLUMNS}}


@dataclass(frozen=True)
class JointHistory:
    """A joint's contact history after a run (:attr:`ClearanceJointHandle.history`)."""

    state: ContactState
    impacts: list[ImpactRecord]
    onset_times: list[float]

    @property
    def onsets(self) -> int:
        """Contacts begun in the run (impacts)."""
        return len(self.onset_times)

    @property
    def in_contact(self) -> bool:
        return self.state.in_contact

    @property
    def v0(self) -> float:
        return self.state.v0

    @property
    def delta(self) -> float:
        return self.state.delta


def joints_of(mbs: exu.MainSystem) -> list[ClearanceJointHandle]:
    """The clearance joints live in ``mbs`` (those of an earlier build, before ``mbs.Reset()``, dropped)."""
    live = [h for h in mbs.variables.get(REGISTRY_KEY, []) if h.is_live()]
    mbs.variables[REGISTRY_KEY] = live
    return live


def _physics(joint: ClearanceJoint | None, joint_parameters: dict) -> ClearanceJoint:
    if joint is None:
        return make_joint(**joint_parameters)
    if joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    if not isinstance(joint, ClearanceJoint):
        raise ValueError(f"`joint` must be a ClearanceJoint, got {type(joint).__name__}")
    return joint


def _check_system(mbs: Any) -> None:
    if not isinstance(mbs, exu.MainSystem):
        raise ValueError(f"`mbs` must be an exudyn MainSystem (exudyn.SystemContainer().AddSystem()), "
                         f"got {type(mbs).__name__}")


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
    _check_system(mbs)
    if isinstance(markerNumbers, (str, bytes)) or len(markerNumbers) != 2:
        raise ValueError(f"`markerNumbers` must be [bearing marker, journal marker], got {markerNumbers!r}")
    for k, marker in enumerate(markerNumbers):
        try:
            kind = mbs.GetMarker(marker)["markerType"]
        except Exception:  # Exudyn raises its own error types for a bad index
            raise ValueError(f"`markerNumbers[{k}]` {marker!r} is not a marker of this MainSystem") from None
        if kind not in _RIGID_MARKERS:
            raise ValueError(f"`markerNumbers[{k}]` is a {kind} marker; a clearance joint needs rigid markers "
                             f"(position and orientation): {', '.join(_RIGID_MARKERS)}")
    if int(markerNumbers[0]) == int(markerNumbers[1]):
        raise ValueError("`markerNumbers` names the same marker twice")
    axial_clearance = joint_parameters.pop("axial_clearance", None)
    shoulder_radius = joint_parameters.pop("shoulder_radius", None)
    joint = _physics(joint, joint_parameters)
    axis_local = _vector3("axis", axis)
    if not np.linalg.norm(axis_local) > 0.0:
        raise ValueError(f"`axis` must not be zero, got {axis!r}")
    _warn_non_unit(axis_local, axis)
    slices = _check_slices(slices)
    shoulders = _check_shoulders(axial_clearance, shoulder_radius, slices, constrainAxial, joint)
    if not isinstance(name, str):
        raise ValueError(f"`name` must be a string, got {name!r}")
    if bearingRotates is not None and not isinstance(bearingRotates, bool):
        raise ValueError(f"`bearingRotates` must be True, False or None (decide from the marker), got {bearingRotates!r}")
    for flag, value in (("constrainAxial", constrainAxial), ("record", record), ("show", show)):
        if not isinstance(value, bool):
            raise ValueError(f"`{flag}` must be True or False, got {value!r}")
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
    fns = _user_functions(handle)
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
    n_data = len(spatial_data_columns(slices, n_faces)) if slices else len(DATA_COLUMNS)
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
    mbs.variables.setdefault(REGISTRY_KEY, []).append(handle)
    if record:
        handle.sensorNumber = mbs.AddSensor(SensorNode(nodeNumber=handle.nodeNumber, storeInternal=True,
                                                       writeToFile=False,
                                                       outputVariableType=exu.OutputVariableType.Coordinates))
    return handle


#: Colours of the drawing (RGBA).
JOURNAL_COLOR, BEARING_COLOR = [0.3, 0.3, 0.8, 1.0], [0.7, 0.7, 0.7, 1.0]
#: Outer radius of the drawn bearing ring, relative to the bearing radius.
BEARING_RING = 1.4


def drawing_function(handle: ClearanceJointHandle,
                     configuration: Any = exu.ConfigurationType.Visualization) -> Any:
    """Graphics function of the joint: the journal as a cylinder of radius R_J and the bearing
    as a ring from R_B, both of the bearing length, along the bearing axis, at the markers'
    current poses.  Exudyn calls it only to render."""
    geometry = handle.joint.geometry

    def draw(mbs: exu.MainSystem, item: int) -> list:
        m_bearing, m_journal = handle.markerNumbers
        rot = np.asarray(mbs.GetMarkerOutput(m_bearing, exu.OutputVariableType.RotationMatrix,
                                             configuration=configuration)).reshape(3, 3)
        axis = rot @ handle._axis_local
        shift = 0.5 * geometry.length * axis
        out = []
        for marker, radius, inner, color in ((m_journal, geometry.journal_radius, None, JOURNAL_COLOR),
                                             (m_bearing, BEARING_RING * geometry.bearing_radius,
                                              geometry.bearing_radius, BEARING_COLOR)):
            centre = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.Position,
                                                    configuration=configuration))
            out.append(exu.graphics.Cylinder(pAxis=(centre - shift).tolist(), vAxis=(2.0 * shift).tolist(),
                                             radius=radius, radiusInner=inner, color=color))
        return out

    return draw


def _warn_non_unit(axis_local: np.ndarray, given: Any) -> None:
    length = float(np.linalg.norm(axis_local))
    if abs(length - 1.0) > AXIS_UNIT_TOLERANCE:
        warnings.warn(f"`axis` {given!r} is not a unit vector (length {length:.6g}); it is normalised", UserWarning,
                      stacklevel=3)


def _check_slices(slices: Any) -> int:
    """0 for the planar joint (None or 0), else the number of slices (an int >= 1)."""
    if slices is None:
        return 0
    if isinstance(slices, bool) or not isinstance(slices, (int, np.integer)):
        raise ValueError(f"`slices` must be None (planar joint) or an integer >= 1, got {slices!r}")
    if slices < 0:
        raise ValueError(f"`slices` must be None (planar joint) or an integer >= 1, got {slices!r}")
    return int(slices)


def _check_shoulders(axial_clearance: Any, shoulder_radius: Any, slices: int, constrain_axial: Any,
                     joint: ClearanceJoint) -> ShoulderGeometry | None:
    """The axial clearance of docs/physics.md section 9.6, or None where none is given."""
    if axial_clearance is None:
        if shoulder_radius is not None:
            raise ValueError(f"`shoulder_radius` ({shoulder_radius!r}) is given without `axial_clearance`; give both "
                             "for shoulder contact, or neither")
        return None
    play = check_positive("axial_clearance", axial_clearance)
    if not slices:
        raise ValueError("`axial_clearance` needs the spatial joint: give `slices` (e.g. "
                         f"{DEFAULT_SLICES}); the planar joint has no axial direction")
    if shoulder_radius is None:
        raise ValueError("`axial_clearance` needs the shoulder geometry: give `shoulder_radius`, the outer radius [m] "
                         "of the annulus where a shoulder meets a bearing end face (> `bearing_radius`)")
    r_s = check_positive("shoulder_radius", shoulder_radius)
    r_b = joint.geometry.bearing_radius
    if not r_s > r_b:
        raise ValueError(f"`shoulder_radius` must exceed `bearing_radius` {r_b} (the end face's annulus starts at the "
                         f"bearing radius), got {r_s}")
    if constrain_axial is True:
        raise ValueError("`constrainAxial=True` holds the journal axially, which leaves `axial_clearance` nothing to "
                         "do: give one or the other")
    return ShoulderGeometry(play, r_s, r_b)


def _user_functions(handle: ClearanceJointHandle) -> dict[str, Any]:
    if handle.python_kernel is not None:
        k = handle.python_kernel
        return {"force_torque": k.force_torque, "post_newton": k.post_newton, "probe": k.probe,
                "probe_post_newton": k.probe_post_newton, "torque": k.torque}
    c = kernel.COMPILED  # one function serves every role; the role is in the parameters
    return {"force_torque": c.force_torque, "post_newton": c.post_newton, "probe": c.force_torque,
            "probe_post_newton": c.post_newton, "torque": c.force_torque}


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
    _check_system(mbs)
    if isinstance(itemNumbers, (str, bytes)) or len(itemNumbers) != 2:
        raise ValueError(f"`itemNumbers` must be [bearing body, journal body], got {itemNumbers!r}")
    if not isinstance(useGlobalFrame, bool):
        raise ValueError(f"`useGlobalFrame` must be True or False, got {useGlobalFrame!r}")
    b0, b1 = itemNumbers
    for role, body in (("bearing body", b0), ("journal body", b1)):
        if body is None:
            raise ValueError(f"`itemNumbers` needs the {role}")
        _object_type(mbs, body, role)
    if int(b0) == int(b1):
        raise ValueError("`itemNumbers` names the same body twice; the bearing and the journal are on different bodies")
    if (_object_type(mbs, b0, "bearing body") == "Ground") and (_object_type(mbs, b1, "journal body") == "Ground"):
        raise ValueError("`itemNumbers` are both ground objects: one must be a moving body")
    p = _vector3("position", position)
    a = _vector3("axis", axis)
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

    The journal's centre is ``journal_point`` (x, y) in ``journal_body``'s frame, the
    bearing's ``bearing_point`` in ``bearing_body``'s; an ``ObjectKinematicTree`` body
    needs the link index (``journal_link`` / ``bearing_link``).  The axis is z.  Builds
    the rigid markers and calls :func:`AddClearanceJoint`.
    """
    _check_system(mbs)
    if max_penetration is not None:
        check_positive("max_penetration", max_penetration)
    markers = [_point_marker(mbs, bearing_body, bearing_point, bearing_link, "bearing"),
               _point_marker(mbs, journal_body, journal_point, journal_link, "journal")]
    if _object_type(mbs, journal_body, "journal") == "Ground" and _object_type(mbs, bearing_body, "bearing") == "Ground":
        raise ValueError("`journal_body` and `bearing_body` are both the ground: one must be a moving body")
    if journal_body == bearing_body and journal_link == bearing_link:
        raise ValueError("`journal_body` and `bearing_body` are the same body")
    return AddClearanceJoint(mbs, markers, name=name, joint=joint, backend=backend, maxPenetration=max_penetration,
                             bearingRotates=bearing_rotates, record=record, **joint_parameters)


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
