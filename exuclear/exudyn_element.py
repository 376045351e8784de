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

from ._checks import check_choice, check_positive, check_real
from ._ops import FLOAT_OPS
from .geometry import ContactKinematics, JointLoads, contact_kinematics, joint_loads, kinematics_along
from .joint import ClearanceJoint, ContactHistory, make_joint
from .settings import METHODS, SolverSettings

esym = exu.symbolic

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

#: With impact-aware steps, Exudyn's own step reduction (after a failed Newton
#: iteration) may go this far below ``impact_step`` before the run fails.
IMPACT_STEP_FLOOR = 0.5
#: Error a post-Newton function returns to make Exudyn redo a step: anything above
#: Exudyn's ``discontinuous.iterationTolerance`` (default 1).
_REDO_STEP_ERROR = 1e3

#: Force evaluation backends of the element, see :func:`add_clearance_joint`.
BACKENDS = {"python": "Python callback", "symbolic": "Exudyn symbolic expression, compiled"}

#: Columns of a joint's recorded output (after ``time``), SI units.
OUTPUT_COLUMNS = ("penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force",
                  "tangential_force", "slip_velocity", "v0", "in_contact")


# -- the sides of a joint -----------------------------------------------------------------
# A side turns the element's coordinates (q, q_t: the coordinates of its nodes, without
# reference values) into the position, velocity and angular velocity of the journal or
# bearing centre, and the Jacobian columns that map a force and moment at that centre
# onto the generalized forces: ``(k, dx/dq_k, dy/dq_k, dangle/dq_k)`` per coordinate.
# ``offset`` is where the side's node starts in the element's coordinate vector.  The
# math backend ``ops`` is floats for the Python callback and Exudyn symbolic numbers for
# the compiled one (:mod:`exuclear._ops`).

_State = tuple  # (x, y, vx, vy, omega, columns)


def _add_load(out: list, columns: Sequence[tuple], fx: Any, fy: Any, m: Any) -> None:
    """Add the virtual work of a force (fx, fy) and moment m at a side's point to ``out``."""
    for k, dx, dy, da in columns:
        out[k] += dx * fx + dy * fy + da * m


class _GroundSide:
    """A point fixed in space (journal or bearing on the ground)."""

    node = None

    def __init__(self, x: float, y: float) -> None:
        self.x, self.y = x, y
        self.offset = 0

    def state(self, q: Sequence[float], q_t: Sequence[float], ops: Any = FLOAT_OPS) -> _State:
        return self.x, self.y, 0.0, 0.0, 0.0, ()


class _RigidBody2DSide:
    """A point fixed on a body with a ``NodeRigidBody2D`` (coordinates x, y, phi)."""

    n_coordinates = 3

    def __init__(self, node: int, reference: Sequence[float], sx: float, sy: float) -> None:
        self.node = node
        self.x0, self.y0, self.phi0 = (float(v) for v in reference)
        self.sx, self.sy = sx, sy
        self.offset = 0

    def state(self, q: Sequence[float], q_t: Sequence[float], ops: Any = FLOAT_OPS) -> _State:
        i = self.offset
        w = q_t[i + 2]
        if self.sx == 0.0 and self.sy == 0.0:  # the point is the node: no arm, no trigonometry
            return (self.x0 + q[i], self.y0 + q[i + 1], q_t[i], q_t[i + 1], w,
                    ((i, 1.0, 0.0, 0.0), (i + 1, 0.0, 1.0, 0.0), (i + 2, 0.0, 0.0, 1.0)))
        phi = self.phi0 + q[i + 2]
        c, s = ops.cos(phi), ops.sin(phi)
        rx, ry = c * self.sx - s * self.sy, s * self.sx + c * self.sy
        return (self.x0 + q[i] + rx, self.y0 + q[i + 1] + ry, q_t[i] - w * ry, q_t[i + 1] + w * rx, w,
                ((i, 1.0, 0.0, 0.0), (i + 1, 0.0, 1.0, 0.0), (i + 2, -ry, rx, 1.0)))


_REVOLUTE, _PRISMATIC_X, _PRISMATIC_Y = "RevoluteZ", "PrismaticX", "PrismaticY"


def _cos_sin(angle: Any, ops: Any) -> tuple[Any, Any]:
    """cos and sin of an angle; exact (1, 0) for the float 0 (a joint frame along X)."""
    if isinstance(angle, float) and angle == 0.0:
        return 1.0, 0.0
    return ops.cos(angle), ops.sin(angle)


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
            self.chain.append((j, types[j], float(offsets[j][0]), float(offsets[j][1]),
                               math.atan2(rot[1, 0], rot[0, 0])))
        self.base = (float(base[0]), float(base[1]))

    def state(self, q: Sequence[float], q_t: Sequence[float], ops: Any = FLOAT_OPS) -> _State:
        # forward kinematics: the frame of each chain joint, then the point.  Angles that are
        # still the float 0 need no trigonometry (see _cos_sin); this runs in every force
        # evaluation, so each cos/sin is computed once and reused for the Jacobian
        x, y, angle = self.base[0], self.base[1], 0.0
        frames = []  # per chain joint: (coordinate index, revolute?, frame x, y, cos, sin of the axis)
        i = self.offset
        for j, kind, ox, oy, fixed in self.chain:
            if ox != 0.0 or oy != 0.0:
                c, s = _cos_sin(angle, ops)
                x, y = x + c * ox - s * oy, y + s * ox + c * oy
            if fixed != 0.0:
                angle = angle + fixed
            qj = self.q0[j] + q[i + j] if self.q0[j] != 0.0 else q[i + j]
            if kind == _REVOLUTE:
                frames.append((i + j, True, x, y, 0.0, 0.0))
                angle = angle + qj
                continue
            c, s = _cos_sin(angle, ops)
            if kind == _PRISMATIC_Y:  # the axis is the frame's Y axis
                c, s = -s, c
            frames.append((i + j, False, x, y, c, s))
            x, y = x + c * qj, y + s * qj
        if self.sx != 0.0 or self.sy != 0.0:
            c, s = _cos_sin(angle, ops)
            x, y = x + c * self.sx - s * self.sy, y + s * self.sx + c * self.sy
        # Jacobian columns d(point)/dq_k, d(angle)/dq_k, and the velocity from them
        columns = []
        vx = vy = w = 0.0
        for k, revolute, fx, fy, c, s in frames:
            qt = q_t[k]
            if revolute:
                dx, dy = fy - y, x - fx
                columns.append((k, dx, dy, 1.0))
                vx, vy, w = vx + dx * qt, vy + dy * qt, w + qt
            else:
                columns.append((k, c, s, 0.0))
                vx, vy = vx + c * qt, vy + s * qt
        return x, y, vx, vy, w, columns


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
        self._compiled: _CompiledForce | None = None

    @property
    def backend(self) -> str:
        """``"python"`` or ``"symbolic"``: how the element's force is evaluated."""
        return "python" if self._compiled is None else "symbolic"

    def reset_history(self) -> None:
        """Forget the contact history (a run starts from the initial state)."""
        self.history.reset()
        if self._compiled is not None:
            self._compiled.push(self.history)

    # physics evaluated on the element's own coordinate slice
    def _evaluate(self, q: Sequence[float], q_t: Sequence[float]) -> tuple[ContactKinematics, _State, _State]:
        """Contact kinematics and both sides' states (with their Jacobian columns)."""
        journal, bearing = self._journal.state(q, q_t), self._bearing.state(q, q_t)
        xj, yj, vxj, vyj, wi, _ = journal
        xb, yb, vxb, vyb, wj, _ = bearing
        return contact_kinematics(self.joint.geometry, xj, yj, vxj, vyj, wi, xb, yb, vxb, vyb, wj), journal, bearing

    def kinematics(self, q: Sequence[float], q_t: Sequence[float]) -> ContactKinematics:
        return self._evaluate(q, q_t)[0]

    def _generalized_forces(self, journal: _State, bearing: _State, loads: JointLoads) -> list:
        out = [0.0] * self._n
        _add_load(out, journal[5], loads.fx, loads.fy, loads.m_i)
        _add_load(out, bearing[5], -loads.fx, -loads.fy, loads.m_j)
        return out

    def force_function(self, mbs: exu.MainSystem, t: float, item: int, q: list[float], q_t: list[float]) -> list[float]:
        """Exudyn ``forceUserFunction`` (Exudyn passes lists): no side effects (called in Newton iterations)."""
        kin, journal, bearing = self._evaluate(q, q_t)
        if kin.delta <= 0.0:
            return [0.0] * self._n
        return self._generalized_forces(journal, bearing, self.joint.response(kin, self.history).loads)

    def _current(self, configuration: Any = exu.ConfigurationType.Current) -> tuple[list[float], list[float]]:
        ltg = self.mbs.systemData.GetObjectLTGODE2(self.object_index)
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(configuration))[ltg].tolist()
        q_t = np.asarray(self.mbs.systemData.GetODE2Coordinates_t(configuration))[ltg].tolist()
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
        if self._compiled is not None:
            self._compiled.push(self.history)
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


class _SymbolicOps:
    """The math backend of :mod:`exuclear._ops` on Exudyn symbolic numbers."""

    sqrt = staticmethod(esym.sqrt)
    sin = staticmethod(esym.sin)
    cos = staticmethod(esym.cos)
    abs = staticmethod(esym.abs)
    sign = staticmethod(esym.sign)

    @staticmethod
    def min(a: Any, b: Any) -> Any:
        return esym.min(_real(a), _real(b))

    @staticmethod
    def max(a: Any, b: Any) -> Any:
        return esym.max(_real(a), _real(b))

    @staticmethod
    def where(condition: Any, if_true: Any, if_false: Any) -> Any:
        return esym.IfThenElse(_real(condition), _real(if_true), _real(if_false))


def _real(x: Any) -> Any:
    return x if isinstance(x, esym.Real) else esym.Real(float(x))


#: Lower bound of |e| where the compiled force divides by it [m]: at |e| = 0 (a centred
#: journal, far from contact) the normal is undefined and the force zero; this keeps the
#: zero force from becoming 0 * NaN.
_ECC_FLOOR = 1e-300


class _CompiledForce:
    """The joint's generalized forces as one Exudyn symbolic (compiled) expression.

    The formulas are those of the Python callback, recorded once on symbolic numbers:
    the sides' kinematics, :func:`exuclear.geometry.kinematics_along`,
    :meth:`ContactLaw.force_expression`, :meth:`FrictionLaw.expression` and
    :func:`exuclear.geometry.joint_loads`.  The contact history enters as named
    symbolic values that :meth:`push` sets once per accepted step.  Exudyn's symbolic
    expressions are trees that do not share common subexpressions: every use of ``|e|``
    re-evaluates it, so deep kinematic chains make this slower, not faster (measured in
    ``validation/work_precision.py``).
    """

    def __init__(self, handle: ClearanceJointHandle) -> None:
        ops, n, tag = _SymbolicOps(), handle._n, f"exuclear{handle.object_index}_"
        self.in_contact, self.v0, self.has_previous, self.delta0, self.delta_dot0 = (
            esym.Real(tag + name, 0.0) for name in ("in_contact", "v0", "has_previous", "delta0", "delta_dot0"))
        q, q_t = esym.Vector("q", [0.0] * n), esym.Vector("q_t", [0.0] * n)
        journal, bearing = handle._journal.state(q, q_t, ops), handle._bearing.state(q, q_t, ops)
        ex, ey = journal[0] - bearing[0], journal[1] - bearing[1]
        ecc = esym.sqrt(ex * ex + ey * ey)
        inverse = 1.0 / esym.max(ecc, esym.Real(_ECC_FLOOR))
        kin = kinematics_along(handle.joint.geometry, ex, ey, ecc, ex * inverse, ey * inverse,
                               journal[2] - bearing[2], journal[3] - bearing[3], journal[4], bearing[4])
        # ContactHistory.onset_velocity, on the pushed history
        onset = ops.where(self.has_previous > 0.5,
                          self.delta_dot0 + (kin.delta_dot - self.delta_dot0) * self.delta0 / (self.delta0 - kin.delta),
                          kin.delta_dot)
        v0 = ops.where(self.in_contact > 0.5, self.v0, onset)
        joint = handle.joint
        f_n = joint.law.force_expression(kin.delta, kin.delta_dot, v0, ops)
        f_t = joint.friction.expression(kin.v_t, ops) * f_n if joint.friction.active else 0.0
        loads = joint_loads(joint.geometry, kin, f_n, f_t)
        out = [0.0] * n
        _add_load(out, journal[5], loads.fx, loads.fy, loads.m_i)
        _add_load(out, bearing[5], -loads.fx, -loads.fy, loads.m_j)
        arguments = {"mbs": handle.mbs, "t": esym.Real("t", 0.0), "itemNumber": esym.Real("itemNumber", 0),
                     "q": q, "q_t": q_t}
        self.function = esym.UserFunction()
        # the dictionary that exudyn.advancedUtilities.ConvertFunctionToSymbolic would record,
        # built here because that helper sizes the coordinate vectors at zero
        self.function.SetUserFunctionFromDict(handle.mbs, {
            "functionName": f"exuclear_force_{handle.object_index}", "argList": list(arguments.values()),
            "argTypeList": ["MainSystem", "Real", "Index", "StdVector", "StdVector"],
            "returnValue": esym.Vector([_real(v) for v in out]), "returnType": "StdVector"},
            "forceUserFunction", exu.ObjectIndex(handle.object_index), "None")
        self._arguments = arguments  # the expression tree refers to these: keep them alive

    def push(self, history: ContactHistory) -> None:
        """Hand the accepted contact history to the expression."""
        self.in_contact.SetValue(1.0 if history.in_contact else 0.0)
        self.v0.SetValue(history.v0)
        has_previous = history.delta != float("-inf")
        self.has_previous.SetValue(1.0 if has_previous else 0.0)
        if has_previous:
            self.delta0.SetValue(history.delta)
            self.delta_dot0.SetValue(history.delta_dot)


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
    backend: str = "python",
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
    backend : str
        How the force is evaluated: ``"python"`` (a Python callback, the default) or
        ``"symbolic"`` (the same formulas recorded as an Exudyn symbolic expression and
        evaluated in compiled code).  The contact history is updated in Python once per
        accepted step either way, and that fixed cost per step is what remains: on a
        body against the ground (the journal-bearing scene) ``"symbolic"`` saves about
        a tenth of the run time; on the slider-crank it is 2 to 4 times slower, because
        Exudyn's symbolic expressions share no subexpressions and re-evaluate the
        joint's kinematics at every use (measured by ``validation/work_precision.py``).

    Returns
    -------
    ClearanceJointHandle
    """
    _check_system(mbs)
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
    check_choice("backend", backend, BACKENDS)
    if max_penetration is None:
        max_penetration = default_penetration_limit(joint.geometry)
    check_positive("max_penetration", max_penetration)
    registry = _registry(mbs)
    handle = ClearanceJointHandle(mbs, joint, journal, bearing, name or f"clearance joint {len(registry)}",
                                  max_penetration)
    handle.object_index = int(mbs.AddObject(ObjectGenericODE2(
        nodeNumbers=handle.nodes, forceUserFunction=handle.force_function, name=f"exuclear {handle.name}")))
    if backend == "symbolic":
        handle._compiled = _CompiledForce(handle)
        mbs.SetObjectParameter(handle.object_index, "forceUserFunction", handle._compiled.function)
        handle.reset_history()
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
    elif settings.impact_step is None:
        ti.adaptiveStep = False  # fixed step: a rejected Newton step fails the run loudly
    else:
        # impact-aware steps: the post-Newton function of simulate() asks for impact_step at
        # a contact onset; Exudyn then doubles the step every recovery_steps steps
        ti.adaptiveStep = True
        ti.minimumStepSize = settings.impact_step * IMPACT_STEP_FLOOR
        ti.adaptiveStepIncrease = 2.0
        ti.adaptiveStepRecoverySteps = settings.recovery_steps
        ti.discontinuous.useRecommendedStepSize = True
    if not settings.explicit:
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


def _check_system(mbs: Any) -> None:
    if not isinstance(mbs, exu.MainSystem):
        raise ValueError(f"`mbs` must be an exudyn MainSystem (exudyn.SystemContainer().AddSystem()), "
                         f"got {type(mbs).__name__}")


def _joints_in_contact(joints: list[ClearanceJointHandle]) -> str:
    """Which joints were in contact at the last accepted state, for failure messages."""
    names = [f"{h.name!r} (penetration {h.history.delta:.3g} m)" for h in joints if h.history.in_contact]
    return f"; in contact then: {', '.join(names)}" if names else "; no clearance joint was in contact then"


def _impact_steps(joints: list[ClearanceJointHandle], impact_step: float) -> Any:
    """Post-Newton function of impact-aware steps: redo a step longer than ``impact_step``
    in which a joint that was free at the last accepted state has come into contact."""
    longest = impact_step * (1.0 + 1e-9)  # Exudyn's step may carry round-off

    def post_newton(mbs: exu.MainSystem, t: float) -> list[float]:
        if mbs.sys["dynamicSolver"].it.currentStepSize > longest:
            for handle in joints:
                if not handle.history.in_contact and handle.kinematics(*handle._current()).delta > 0.0:
                    return [_REDO_STEP_ERROR, impact_step]
        return [0.0, -1.0]

    return post_newton


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
    _check_system(mbs)
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
        handle.reset_history()
    if settings.impact_step is not None:
        if _user_function(mbs.GetPostNewtonUserFunction()) is not None:
            raise ValueError("`impact_step` needs the system's post-Newton user function, but one is installed; "
                             "remove it or use a fixed step")
        mbs.SetPostNewtonUserFunction(_impact_steps(joints, settings.impact_step))
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
    if settings.impact_step is not None:
        mbs.SetPostNewtonUserFunction(0)  # a later run with fixed steps must not inherit it
    it = mbs.sys["dynamicSolver"].it
    t_reached = mbs.systemData.GetTime()
    if mbs.variables[_FAILURE_KEY]:
        return SimulationResult(False, f"stopped {mbs.variables[_FAILURE_KEY]}; results up to then are kept", wall,
                                int(it.currentStepIndex) - 1, int(it.rejectedAutomaticStepSizeSteps), t_reached)
    if not ok:
        message += (f" (stopped at t = {t_reached:.6g} s of {settings.end_time:g} s{_joints_in_contact(joints)}; "
                    f"try a smaller `step`{' or tolerances' if settings.adaptive else ''})")
    return SimulationResult(ok, message, wall, int(it.currentStepIndex) - 1, int(it.rejectedAutomaticStepSizeSteps),
                            t_reached)
