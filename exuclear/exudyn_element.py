"""Exudyn glue: the clearance joint as an Exudyn item, and the solver driver.

This is the only module of exuclear that imports exudyn or reads engine state.

Element.  The joint is an ``ObjectGenericODE2`` over the nodes of the journal body
and the bearing body, without mass, stiffness or damping matrices: only its
``forceUserFunction`` adds the generalized forces of MODEL.md section 4 to the
nodes' equations.  Exudyn differentiates that function numerically for the implicit
solvers' Jacobian.  A compiled backend can replace the Python force function by an
Exudyn symbolic one on the same object, and a minimal-coordinate body (a link of an
``ObjectKinematicTree``) by another ``_Side`` class; the physics in
:mod:`exuclear.joint` stays as it is.

Contact history.  ``v0`` changes once per accepted step: a post-step user function,
which Exudyn calls once before the first step (initial state, t = 0) and then after
every accepted step with that step's end state and time (never for rejected DOPRI5
steps or Newton iterations), calls :meth:`ContactHistory.accept`.  (The pre-step
function would not do: Exudyn calls it for every attempted step, with the system time
already set to the end of the attempt while the state is still at its start.)
Exudyn has one post-step function per system; exuclear installs one that serves all
joints and then calls any function the user had installed before.  A function
installed *after* the joints would replace it; :func:`simulate` detects that and
refuses.
"""
from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import ObjectGenericODE2, SensorUserFunction

from ._checks import check_positive, check_real
from .geometry import ContactKinematics, JointLoads, contact_kinematics
from .joint import ClearanceJoint, ContactHistory, make_joint
from .settings import METHODS, SolverSettings

_REGISTRY_KEY = "exuclear.joints"
_FAILURE_KEY = "exuclear.failure"
_MIN_STEP_KEY = "exuclear.min_step"
_HOOKS_KEY = "exuclear.hooks"

#: Attempts at one step after which a run is ended: DOPRI5 rejects a step a few times
#: at an impact, but at its minimum step Exudyn's DOPRI5 retries forever.
MAX_STEP_ATTEMPTS = 200

#: Default bound on the penetration beyond which a run is stopped as unphysical: the
#: larger of half the radial clearance and 0.1 % of the journal radius.  It is meant to
#: catch blow-ups (a journal sinking through its bearing), not hard impacts: the paper's
#: 0.3 m/s impact reaches 3.4 % of its 0.1 mm clearance, but a 1.3 m/s impact of a
#: crank pin already exceeds 10 %, and a 1 um clearance sees 0.4 um of static
#: penetration (contact theory itself assumes deformations far below the radius).
PENETRATION_LIMIT_CLEARANCE = 0.5
PENETRATION_LIMIT_RADIUS = 1e-3


def default_penetration_limit(geometry: Any) -> float:
    """The default penetration bound [m] of a joint, see :data:`PENETRATION_LIMIT_CLEARANCE`."""
    return max(PENETRATION_LIMIT_CLEARANCE * geometry.clearance, PENETRATION_LIMIT_RADIUS * geometry.journal_radius)

#: Columns of a joint's recorded output (after ``time``), SI units.
OUTPUT_COLUMNS = ("penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force",
                  "tangential_force", "slip_velocity", "v0", "in_contact")


# -- the sides of a joint -----------------------------------------------------------------
# A side turns the element's coordinates (q, q_t: the coordinates of its nodes, without
# reference values) into the position, velocity and angular velocity of the journal or
# bearing centre, and adds a force and moment at that centre to the generalized forces.
# ``offset`` is where the side's node starts in the element's coordinate vector.

class _GroundSide:
    """A point fixed in space (journal or bearing on the ground)."""

    node = None

    def __init__(self, x: float, y: float) -> None:
        self.x, self.y = x, y
        self.offset = 0

    def state(self, q: Sequence[float], q_t: Sequence[float]) -> tuple[float, float, float, float, float]:
        return self.x, self.y, 0.0, 0.0, 0.0

    def add_load(self, out: list[float], fx: float, fy: float, m: float, q: Sequence[float]) -> None:
        pass


class _RigidBody2DSide:
    """A point fixed on a body with a ``NodeRigidBody2D`` (coordinates x, y, phi)."""

    n_coordinates = 3

    def __init__(self, node: int, reference: Sequence[float], sx: float, sy: float) -> None:
        self.node = node
        self.x0, self.y0, self.phi0 = (float(v) for v in reference)
        self.sx, self.sy = sx, sy
        self.offset = 0

    def _arm(self, phi: float) -> tuple[float, float]:
        c, s = math.cos(phi), math.sin(phi)
        return c * self.sx - s * self.sy, s * self.sx + c * self.sy

    def state(self, q: Sequence[float], q_t: Sequence[float]) -> tuple[float, float, float, float, float]:
        i = self.offset
        rx, ry = self._arm(self.phi0 + q[i + 2])
        w = q_t[i + 2]
        return self.x0 + q[i] + rx, self.y0 + q[i + 1] + ry, q_t[i] - w * ry, q_t[i + 1] + w * rx, w

    def add_load(self, out: list[float], fx: float, fy: float, m: float, q: Sequence[float]) -> None:
        i = self.offset
        rx, ry = self._arm(self.phi0 + q[i + 2])
        out[i] += fx
        out[i + 1] += fy
        out[i + 2] += m + rx * fy - ry * fx  # moment of the force about the node


_REVOLUTE, _PRISMATIC_X, _PRISMATIC_Y = "RevoluteZ", "PrismaticX", "PrismaticY"


class _KinematicTreeSide:
    """A point fixed on a link of a planar ``ObjectKinematicTree`` (minimal coordinates).

    Planar forward kinematics of the chain from the base to the link, in Exudyn's
    convention: a joint frame sits at ``jointOffsets[j]`` and is turned by
    ``jointTransformations[j]`` (a rotation about Z) in its parent link's frame; the
    joint coordinate then turns it about Z (``RevoluteZ``) or shifts it along its X or Y
    axis (``PrismaticX/Y``).  The point's Jacobian maps the force and moment onto the
    joint coordinates (virtual work).
    """

    def __init__(self, node: int, reference: Sequence[float], tree: dict, link: int, sx: float, sy: float) -> None:
        self.node = node
        self.offset = 0
        self.n_coordinates = len(reference)
        self.q0 = [float(v) for v in reference]
        self.sx, self.sy = sx, sy
        parents = list(tree["linkParents"])
        types = [t.name for t in tree["jointTypes"]]
        # Exudyn's Vector3DList / Matrix3DList do not end iteration cleanly: index them
        offsets = [np.asarray(tree["jointOffsets"][k], dtype=float) for k in range(len(parents))]
        rotations = [np.asarray(tree["jointTransformations"][k], dtype=float) for k in range(len(parents))]
        base = np.asarray(tree["baseOffset"], dtype=float)
        chain = []
        k = link
        while k >= 0:
            chain.append(k)
            k = parents[k]
        chain.reverse()
        # per joint of the chain: (index, type, offset x, y in the parent frame, fixed angle)
        self.chain = []
        for j in chain:
            if types[j] not in (_REVOLUTE, _PRISMATIC_X, _PRISMATIC_Y):
                raise ValueError(f"kinematic-tree joint {j} is {types[j]}: only RevoluteZ, PrismaticX and "
                                 "PrismaticY joints keep the tree planar")
            rot = rotations[j]
            if abs(rot[2, 2] - 1.0) > 1e-12 or abs(offsets[j][2]) > 0.0:
                raise ValueError(f"kinematic-tree joint {j} leaves the XY plane: its transformation must be a "
                                 "rotation about Z and its offset must have z = 0")
            self.chain.append((j, types[j], offsets[j][0], offsets[j][1], math.atan2(rot[1, 0], rot[0, 0])))
        self.base = (base[0], base[1])

    def _kinematics(self, q: Sequence[float]) -> tuple[float, float, float, list]:
        """Point position, link angle and, per chain joint, (index, type, frame x, y, angle)."""
        x, y, angle = self.base[0], self.base[1], 0.0
        frames = []
        i = self.offset
        for j, kind, ox, oy, fixed in self.chain:
            c, s = math.cos(angle), math.sin(angle)
            x, y, angle = x + c * ox - s * oy, y + s * ox + c * oy, angle + fixed
            frames.append((j, kind, x, y, angle))
            qj = self.q0[j] + q[i + j]
            if kind == _REVOLUTE:
                angle += qj
            else:
                c, s = math.cos(angle), math.sin(angle)
                if kind == _PRISMATIC_X:
                    x, y = x + c * qj, y + s * qj
                else:
                    x, y = x - s * qj, y + c * qj
        c, s = math.cos(angle), math.sin(angle)
        return x + c * self.sx - s * self.sy, y + s * self.sx + c * self.sy, angle, frames

    @staticmethod
    def _column(kind: str, px: float, py: float, fx: float, fy: float, angle: float) -> tuple[float, float, float]:
        """d(point)/dq_j and d(angle)/dq_j for one joint with frame origin (fx, fy)."""
        if kind == _REVOLUTE:
            return -(py - fy), px - fx, 1.0
        c, s = math.cos(angle), math.sin(angle)
        return (c, s, 0.0) if kind == _PRISMATIC_X else (-s, c, 0.0)

    def state(self, q: Sequence[float], q_t: Sequence[float]) -> tuple[float, float, float, float, float]:
        px, py, _, frames = self._kinematics(q)
        vx = vy = w = 0.0
        for j, kind, fx, fy, angle in frames:
            dx, dy, da = self._column(kind, px, py, fx, fy, angle)
            qt = q_t[self.offset + j]
            vx, vy, w = vx + dx * qt, vy + dy * qt, w + da * qt
        return px, py, vx, vy, w

    def add_load(self, out: list[float], fx_: float, fy_: float, m: float, q: Sequence[float]) -> None:
        px, py, _, frames = self._kinematics(q)
        for j, kind, fx, fy, angle in frames:
            dx, dy, da = self._column(kind, px, py, fx, fy, angle)
            out[self.offset + j] += dx * fx_ + dy * fy_ + da * m


def _side(mbs: exu.MainSystem, body: Any, point: Sequence[float], link: int | None, role: str) -> Any:
    try:
        sx, sy = (check_real(f"{role}_point", v) for v in point)
    except (TypeError, ValueError):
        raise ValueError(f"`{role}_point` must be two finite numbers (local x, y), got {point!r}") from None
    try:
        item = mbs.GetObject(body)
    except Exception:  # Exudyn raises its own error types for a bad index
        raise ValueError(f"`{role}_body` {body!r} is not an object of this MainSystem") from None
    kind = item["objectType"]
    if kind == "KinematicTree":
        n_links = len(item["linkParents"])
        if isinstance(link, bool) or not isinstance(link, int) or not 0 <= link < n_links:
            raise ValueError(f"`{role}_link` must be a link index 0..{n_links - 1} of the kinematic tree, got {link!r}")
        node = int(item["nodeNumber"])
        return _KinematicTreeSide(node, mbs.GetNode(node)["referenceCoordinates"], item, link, sx, sy)
    if link is not None:
        raise ValueError(f"`{role}_link` applies to an ObjectKinematicTree only, but `{role}_body` is a {kind}")
    if kind == "Ground":
        x, y = item["referencePosition"][:2]
        return _GroundSide(x + sx, y + sy)
    if kind == "RigidBody2D":
        node = int(item["nodeNumber"])
        return _RigidBody2DSide(node, mbs.GetNode(node)["referenceCoordinates"], sx, sy)
    raise ValueError(f"`{role}_body` must be an ObjectGround, ObjectRigidBody2D or ObjectKinematicTree, "
                     f"got an object of type {kind!r}")


# -- the element ---------------------------------------------------------------------------
class ClearanceJointHandle:
    """A clearance joint added to an Exudyn system; returned by :func:`add_clearance_joint`.

    Attributes
    ----------
    joint : ClearanceJoint
        The physics (geometry, contact law, friction law).
    history : ContactHistory
        The contact state of the last accepted step.
    object_index : int
        Index of the joint's ``ObjectGenericODE2`` in the system.
    sensor_index : int or None
        Index of the sensor that records :data:`OUTPUT_COLUMNS`, if recording.
    """

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, journal: Any, bearing: Any, name: str,
                 max_penetration: float) -> None:
        self.mbs = mbs
        self.joint = joint
        self.name = name
        self.max_penetration = max_penetration
        self.history = ContactHistory()
        self._journal, self._bearing = journal, bearing
        self.nodes: list[int] = []  # the element's nodes; a node shared by both sides appears once
        self._n = 0
        for side in (journal, bearing):
            if side.node is None:
                continue
            if side.node in self.nodes:
                side.offset = journal.offset  # only the journal can have claimed it
                continue
            side.offset = self._n
            self.nodes.append(side.node)
            self._n += side.n_coordinates
        self.object_index: int = -1
        self.sensor_index: int | None = None

    # physics evaluated on the element's own coordinate slice
    def kinematics(self, q: Sequence[float], q_t: Sequence[float]) -> ContactKinematics:
        xj, yj, vxj, vyj, wi = self._journal.state(q, q_t)
        xb, yb, vxb, vyb, wj = self._bearing.state(q, q_t)
        return contact_kinematics(self.joint.geometry, xj, yj, vxj, vyj, wi, xb, yb, vxb, vyb, wj)

    def _generalized_forces(self, q: Sequence[float], loads: JointLoads) -> list[float]:
        out = [0.0] * self._n
        self._journal.add_load(out, loads.fx, loads.fy, loads.m_i, q)
        self._bearing.add_load(out, -loads.fx, -loads.fy, loads.m_j, q)
        return out

    def force_function(self, mbs: exu.MainSystem, t: float, item: int, q: np.ndarray, q_t: np.ndarray) -> list[float]:
        """Exudyn ``forceUserFunction``: no side effects (called in Newton iterations)."""
        kin = self.kinematics(q, q_t)
        if kin.delta <= 0.0:
            return [0.0] * self._n
        return self._generalized_forces(q, self.joint.response(kin, self.history).loads)

    def _current(self, configuration: Any = exu.ConfigurationType.Current) -> tuple[np.ndarray, np.ndarray]:
        ltg = self.mbs.systemData.GetObjectLTGODE2(self.object_index)
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(configuration))[ltg]
        q_t = np.asarray(self.mbs.systemData.GetODE2Coordinates_t(configuration))[ltg]
        return q, q_t

    def accept_current_state(self, time: float) -> str:
        """Update the contact history from the system's current (accepted) state at ``time``.

        Returns an empty string, or a message saying why the run cannot go on: a
        non-finite state, or a penetration beyond ``max_penetration``.
        """
        kin = self.kinematics(*self._current())
        if not all(math.isfinite(v) for v in kin):
            return (f"joint {self.name!r}: the state became non-finite (NaN or inf); the integration diverged. "
                    "Try a smaller step or tighter tolerances")
        if kin.delta > self.max_penetration:
            c = self.joint.geometry.clearance
            return (f"joint {self.name!r}: penetration {kin.delta:.3g} m exceeds the limit {self.max_penetration:.3g} m "
                    f"({self.max_penetration / c:.0%} of the clearance). The contact is too soft for the load, the "
                    "step too large, or a unit is off: check E (Pa) and lengths (m), try a smaller step, or raise "
                    "`max_penetration` if such penetrations are physical")
        self.history.accept(kin.delta, kin.delta_dot, time)
        return ""

    def _sensor_function(self, mbs: exu.MainSystem, t: float, sensors: Any, factors: Any, configuration: Any) -> list[float]:
        kin = self.kinematics(*self._current(configuration))
        r = self.joint.response(kin, self.history)
        return [kin.delta, kin.delta_dot, kin.ex, kin.ey, r.f_n, r.f_t, kin.v_t, r.v0, float(kin.delta > 0.0)]

    def outputs(self) -> dict[str, np.ndarray]:
        """Recorded outputs: ``time`` and :data:`OUTPUT_COLUMNS` as arrays (SI units)."""
        if self.sensor_index is None:
            raise RuntimeError(f"joint {self.name!r} was added with record=False: nothing was recorded")
        data = np.asarray(self.mbs.GetSensorStoredData(self.sensor_index))
        return {"time": data[:, 0], **{c: data[:, k + 1] for k, c in enumerate(OUTPUT_COLUMNS)}}


def _registry(mbs: exu.MainSystem) -> list[ClearanceJointHandle]:
    return mbs.variables.setdefault(_REGISTRY_KEY, [])


def _user_function(previous: Any) -> Any:
    return previous["function"] if isinstance(previous, dict) else None


def _install_hooks(mbs: exu.MainSystem) -> None:
    """Install the post-step function that updates every joint's history, and a
    pre-step watchdog that ends a step retried without end (see :data:`MAX_STEP_ATTEMPTS`)."""
    user_post, user_pre = _user_function(mbs.GetPostStepUserFunction()), _user_function(mbs.GetPreStepUserFunction())
    joints = _registry(mbs)
    last = [0.0]  # time of the previous accepted state
    attempts = [0]  # attempts at the coming step

    def pre_step(mbs_: exu.MainSystem, t: float) -> bool:
        attempts[0] += 1
        if attempts[0] > MAX_STEP_ATTEMPTS:
            message = (f"at t = {last[0]:.6g} s, the solver retried one step {MAX_STEP_ATTEMPTS} times without "
                       "accepting it (Exudyn's DOPRI5 does so when its minimum step cannot meet the tolerances); "
                       "loosen the tolerances, lower `min_step`, or use an implicit method")
            mbs_.variables[_FAILURE_KEY] = message
            raise RuntimeError(message)  # returning False would not end Exudyn's retry loop
        return user_pre(mbs_, t) if user_pre is not None else True

    def post_step(mbs_: exu.MainSystem, t: float) -> bool:
        attempts[0] = 0
        step, last[0] = t - last[0], t
        problem = ""
        if 0.0 < step <= mbs_.variables.get(_MIN_STEP_KEY, 0.0):
            problem = (f"the adaptive step collapsed to the minimum step ({step:.3g} s), where Exudyn would go on "
                       "without error control; the problem is too stiff for this explicit method here: try an "
                       "implicit method, looser tolerances, or a smaller `min_step`")
        for handle in joints:
            problem = problem or handle.accept_current_state(t)
        if problem:  # stop the run and say why
            mbs_.variables[_FAILURE_KEY] = f"at t = {t:.6g} s, {problem}"
            return False
        return user_post(mbs_, t) if user_post is not None else True

    mbs.SetPostStepUserFunction(post_step)
    mbs.SetPreStepUserFunction(pre_step)
    mbs.variables[_HOOKS_KEY] = (pre_step, post_step)


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
    **joint_parameters: Any,
) -> ClearanceJointHandle:
    """Add a planar revolute clearance joint between two bodies of an Exudyn system.

    The journal (radius ``R_J``) is fixed on ``journal_body`` at ``journal_point``; the
    bearing hole (radius ``R_B``) on ``bearing_body`` at ``bearing_point`` (local body
    coordinates [m]).  Contact, friction and the loads on both bodies follow MODEL.md
    sections 1-4.  Works in the XY plane.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system; call before ``mbs.Assemble()``.
    journal_body, bearing_body : ObjectIndex
        An ``ObjectRigidBody2D`` (with ``NodeRigidBody2D``), an ``ObjectGround``, or a
        planar ``ObjectKinematicTree`` (RevoluteZ/PrismaticX/PrismaticY joints, then
        give the link); at most one of them may be the ground, and both may be links of
        the same tree.  Other body types raise ``ValueError``.
    journal_point, bearing_point : (float, float)
        Journal and bearing centres in the body (link) frames [m].
    journal_link, bearing_link : int, optional
        Link index when the body is an ``ObjectKinematicTree``.
    joint : ClearanceJoint, optional
        The joint physics, ready built.  If omitted, it is built by
        :func:`exuclear.make_joint` from ``joint_parameters``: ``journal_radius``,
        ``bearing_radius``, ``length``, ``law``, ``cr``, ``journal_material``,
        ``bearing_material``, ``E_star``, ``friction``, ``v_min``.
    record : bool
        Record :data:`OUTPUT_COLUMNS` at ``SolverSettings.output_step`` intervals
        (read them with :meth:`ClearanceJointHandle.outputs`).
    name : str
        Label for messages.
    max_penetration : float, optional
        Largest admissible penetration [m]; default :func:`default_penetration_limit`.
        :func:`simulate` stops a run beyond it, or when the joint's state is not
        finite, and reports time, joint and reason.

    Returns
    -------
    ClearanceJointHandle
    """
    if joint is None:
        joint = make_joint(**joint_parameters)
    elif joint_parameters:
        raise ValueError(f"give either `joint` or joint parameters, not both (got {sorted(joint_parameters)})")
    elif not isinstance(joint, ClearanceJoint):
        raise ValueError(f"`joint` must be a ClearanceJoint, got {type(joint).__name__}")
    journal = _side(mbs, journal_body, journal_point, journal_link, "journal")
    bearing = _side(mbs, bearing_body, bearing_point, bearing_link, "bearing")
    if journal.node is None and bearing.node is None:
        raise ValueError("`journal_body` and `bearing_body` are both the ground: one must be a moving body")
    if journal_body == bearing_body and journal_link == bearing_link:
        raise ValueError("`journal_body` and `bearing_body` are the same body")
    if max_penetration is None:
        max_penetration = default_penetration_limit(joint.geometry)
    check_positive("max_penetration", max_penetration)
    registry = _registry(mbs)
    handle = ClearanceJointHandle(mbs, joint, journal, bearing, name or f"clearance joint {len(registry)}",
                                  max_penetration)
    handle.object_index = int(mbs.AddObject(ObjectGenericODE2(
        nodeNumbers=handle.nodes, forceUserFunction=handle.force_function, name=f"exuclear {handle.name}")))
    if record:
        handle.sensor_index = int(mbs.AddSensor(SensorUserFunction(
            sensorNumbers=[], sensorUserFunction=handle._sensor_function, storeInternal=True, writeToFile=False)))
    registry.append(handle)
    if len(registry) == 1:
        _install_hooks(mbs)
    return handle


# -- solving ------------------------------------------------------------------------------
def simulation_settings(settings: SolverSettings) -> exu.SimulationSettings:
    """Map :class:`SolverSettings` onto ``exu.SimulationSettings`` (the only place)."""
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime = settings.end_time
    ti.numberOfSteps = max(1, math.ceil(settings.end_time / settings.step - 1e-9))
    ti.verboseMode = settings.verbose
    if settings.explicit:
        ti.automaticStepSize = settings.adaptive
        ti.relativeTolerance = settings.rtol
        ti.absoluteTolerance = settings.atol
        ti.minimumStepSize = settings.min_step
    else:
        ti.adaptiveStep = False  # fixed step: a rejected Newton step fails the run loudly
        ti.generalizedAlpha.spectralRadius = settings.spectral_radius
        ti.generalizedAlpha.computeInitialAccelerations = True
    ss.solution.file.write = False  # results come from sensors kept in memory
    ss.solution.sensors.writePeriod = settings.output_step
    return ss


@dataclass(frozen=True)
class SimulationResult:
    """Outcome of :func:`simulate`.

    ``success`` is False when the run stopped early; ``message`` then says why and what
    to try, and ``time_reached`` [s] how far it got.  ``wall_time`` is the solver call
    alone [s]; ``steps`` the number of accepted time steps and ``rejected`` the
    rejected ones (adaptive methods).
    """

    success: bool
    message: str
    wall_time: float
    steps: int
    rejected: int
    time_reached: float


def _constraint_objects(mbs: exu.MainSystem) -> list[str]:
    found = []
    for i in range(mbs.systemData.NumberOfObjects()):
        if len(mbs.systemData.GetObjectLTGAE(i)) > 0:
            found.append(f"{i} ({mbs.GetObject(i)['objectType']})")
    return found


def simulate(mbs: exu.MainSystem, settings: SolverSettings) -> SimulationResult:
    """Assemble if needed and integrate ``mbs`` with ``settings``.

    Explicit methods are refused for systems with constraints (joints, coordinate
    constraints): Exudyn's explicit solvers would silently ignore them.  Resets
    every clearance joint's contact history, since the run starts from the
    system's initial values.

    A run that cannot go on (solver failure, a non-finite joint state, a penetration
    beyond a joint's limit) returns ``success=False`` with a message naming the time,
    the joint and what to try; what the sensors recorded up to then is kept.
    """
    if not isinstance(settings, SolverSettings):
        raise ValueError(f"`settings` must be a SolverSettings, got {type(settings).__name__}")
    if not mbs.systemIsConsistent:
        mbs.Assemble()
    joints = _registry(mbs)
    if joints:
        installed = (_user_function(mbs.GetPreStepUserFunction()), _user_function(mbs.GetPostStepUserFunction()))
        if any(a is not b for a, b in zip(installed, mbs.variables[_HOOKS_KEY], strict=True)):
            raise RuntimeError(
                "the pre- or post-step user function that exuclear installed (contact history, failure checks) "
                "was replaced; set your own step functions before adding clearance joints (exuclear then calls them)")
    if settings.explicit:
        constrained = _constraint_objects(mbs)
        if constrained:
            raise ValueError(
                f"method {settings.method!r} is explicit and Exudyn's explicit solvers ignore constraints, but objects "
                f"{', '.join(constrained)} are constraints; use 'generalized-alpha' or 'trapezoidal', "
                "or a minimal-coordinate model")
    for handle in joints:
        handle.history.reset()
    mbs.variables[_FAILURE_KEY] = ""
    # with some slack, as Exudyn's controller may land a hair above its minimum
    mbs.variables[_MIN_STEP_KEY] = settings.min_step * (1.0 + 1e-6) if settings.adaptive else 0.0
    ss = simulation_settings(settings)
    solver_type = getattr(exu.DynamicSolverType, METHODS[settings.method][0])
    start = time.perf_counter()
    try:
        ok = bool(exu.SolveDynamic(mbs, ss, solverType=solver_type))
        message = "" if ok else "Exudyn's solver reported failure"
    except Exception as err:  # Exudyn raises its own error types on solver failure
        ok, message = False, f"{type(err).__name__}: {err}"
    wall = time.perf_counter() - start
    it = mbs.sys["dynamicSolver"].it
    t_reached = mbs.systemData.GetTime()
    if mbs.variables[_FAILURE_KEY]:
        return SimulationResult(False, f"stopped {mbs.variables[_FAILURE_KEY]}; results up to then are kept", wall,
                                int(it.currentStepIndex) - 1, int(it.rejectedAutomaticStepSizeSteps), t_reached)
    if not ok:
        message += (f" (stopped at t = {t_reached:.6g} s of {settings.end_time:g} s; try a smaller `step`"
                    f"{' or tolerances' if settings.adaptive else ''})")
    return SimulationResult(ok, message, wall, int(it.currentStepIndex) - 1, int(it.rejectedAutomaticStepSizeSteps),
                            t_reached)
