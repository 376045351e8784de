"""The conditions that hold a followed contact at ``|e| = d``
(:mod:`exuclear.engine.following`): :class:`VelocityCondition` (kept) and
:class:`DistanceCondition` (the first prototype's) on the Python kernel, and
:class:`CompiledCondition` on the compiled one.  Each is one Exudyn item between the
joint's bodies, off until the following mode switches it on; ``hold`` sets it for the
next step at an accepted step, ``fit`` again during a step of another length, and
``multiplier`` reads the normal force it carries."""
from __future__ import annotations

from collections import deque
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerNodeCoordinates,
    MarkerObjectODE2Coordinates,
    ObjectConnectorCoordinateVector,
    ObjectConnectorDistance,
    VObjectConnectorCoordinateVector,
    VObjectConnectorDistance,
)

#: The velocity condition asks for the normal rate that closes this share of the distance's
#: offset per step.
RATE_GAIN = 0.5
#: The configuration of the step's end, where the condition's normal is taken, is predicted
#: by the integrator's own update (generalized-alpha, Arnold and Bruls 2007:
#: ``q_1 = q_0 + h q_t0 + h^2 ((1/2 - beta) a_0 + beta a_1)`` in its algorithmic
#: accelerations ``a``), with the end's acceleration extrapolated from the accelerations of
#: the last three accepted steps (True).  Their difference over two steps is blind to a
#: step-to-step alternation, which a one-step difference triples.  Without it (False), the
#: second-order Taylor prediction ``q + h q_t + h^2 q_tt / 2``, whose normal is off by the
#: third-order term, ``theta^3 / 6`` for a turn ``theta`` per step: the condition's force
#: then has a tangential part that does work.  Measured on the frictionless orbiting journal
#: at 1e-4 s (``python -m validation.contact_follow orbit``): its kinetic energy drifts by
#: -2.2e-5 over four orbits with it, -1.5e-3 without (the compliant contact: -7.8e-6), and
#: the path is 0.55 % of c off the converged one, 1.5 % without.
PREDICT_JERK = True
#: The accepted steps whose accelerations give the end acceleration's slope (PREDICT_JERK).
JERK_STEPS = 3

class DistanceCondition:
    """``|e| = d`` by an ``ObjectConnectorDistance`` between the joint's markers (index 3)."""

    #: Exudyn's multiplier of a position constraint oscillates from step to step: the force
    #: is the mean of two steps.
    two_step_mean = True

    def __init__(self, mbs: exu.MainSystem, markers: list[int], distance: float, name: str) -> None:
        self.number = mbs.AddObject(ObjectConnectorDistance(
            name=name, markerNumbers=list(markers), distance=distance, activeConnector=False,
            visualization=VObjectConnectorDistance(show=False)))

    def multiplier(self, mbs: Any) -> float:
        return float(mbs.GetObjectOutput(self.number, exu.OutputVariableType.Force))

    def hold(self, mbs: Any, distance: float, h: float) -> None:
        mbs.SetObjectParameter(self.number, "distance", distance)

    def switch(self, mbs: Any, active: bool) -> None:
        mbs.SetObjectParameter(self.number, "activeConnector", bool(active))

    def fit(self, mbs: Any, t: float) -> None:
        """Nothing: the distance does not depend on the step."""


class VelocityCondition:
    """The contact's normal rate at velocity level: ``n . (v_journal - v_bearing) = r``, an
    ``ObjectConnectorCoordinateVector`` with ``velocityLevel`` over the ODE2 coordinates of
    the markers' bodies (``MarkerObjectODE2Coordinates``) or nodes (``MarkerNodeCoordinates``).
    Its rows ``n^T dv/dq_t`` of both markers are Exudyn's marker velocities at unit
    coordinate velocities (any body type: rigid 2D and 3D with any rotation parameters,
    beams, cables), in the normal ``n`` predicted for the step's end (:meth:`_rows`); the
    rate ``r`` closes RATE_GAIN of the offset of ``|e|`` from ``d`` per step, so the
    position does not drift.  Its multiplier has no step-to-step oscillation of its own
    (the index-3 one of :class:`DistanceCondition`): on the zoo's double pendulum it varies
    by a median 0.5 % from step to step."""

    two_step_mean = False

    def __init__(self, mbs: exu.MainSystem, markers: list[int], distance: float, name: str) -> None:
        self.markers = list(markers)
        self.owners = [_coordinate_owner(mbs, m) for m in self.markers]
        coordinate_markers, sizes = [], []
        for kind, number in self.owners:
            if kind == "node":
                coordinate_markers.append(mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=number)))
                sizes.append(_node_ode2_size(mbs, number))
            else:
                coordinate_markers.append(mbs.AddMarker(MarkerObjectODE2Coordinates(objectNumber=number)))
                sizes.append(sum(_node_ode2_size(mbs, n) for n in _object_nodes(mbs, number)))
        self.sizes = sizes
        self.ltg: list[np.ndarray] | None = None
        self.number = mbs.AddObject(ObjectConnectorCoordinateVector(
            name=name, markerNumbers=coordinate_markers, scalingMarker0=np.zeros((1, sizes[0])),
            scalingMarker1=np.zeros((1, sizes[1])), offset=[0.0], velocityLevel=True, activeConnector=False,
            visualization=VObjectConnectorCoordinateVector()))
        self.axis = np.array([0.0, 0.0, 1.0])
        self.start: tuple | None = None  # (t, q, q_t, q_tt) at the last accepted step
        self.before: tuple | None = None  # (start, scheme, held, norm) of the step before it (fit)
        #: generalized-alpha's (a_alg, alpha_m, alpha_f, beta) at that step, None where unknown
        self.scheme: tuple | None = None
        self.accelerations: deque = deque(maxlen=JERK_STEPS)  # (t, q_tt) of the last accepted steps held
        self.step = self.held = self.norm = 0.0

    def multiplier(self, mbs: Any) -> float:
        return float(np.ravel(mbs.GetObjectOutput(self.number, exu.OutputVariableType.Force))[0])

    def _axis(self, mbs: Any) -> np.ndarray:
        """The bearing's axis (global), the global z axis for a position marker."""
        try:
            return np.asarray(mbs.GetMarkerOutput(self.markers[0], exu.OutputVariableType.RotationMatrix),
                              dtype=float).reshape(3, 3)[:, 2]
        except Exception:  # a marker without orientation
            return self.axis

    def _eccentricity(self, mbs: Any, axis: np.ndarray) -> np.ndarray:
        """``e``, the journal centre from the bearing centre in the bearing's plane (global)."""
        p = [np.asarray(mbs.GetMarkerOutput(m, exu.OutputVariableType.Position), dtype=float) for m in self.markers]
        e = p[1] - p[0]
        return e - (e @ axis) * axis

    def _global_indices(self, mbs: Any) -> list[np.ndarray]:
        if self.ltg is None:
            data = mbs.systemData
            self.ltg = [np.asarray(data.GetNodeLTGODE2(n) if kind == "node" else data.GetObjectLTGODE2(n), dtype=int)
                        for kind, n in self.owners]
            if [len(i) for i in self.ltg] != self.sizes:
                raise RuntimeError(f"contact_mode='follow': coordinate count {self.sizes} of the joint's bodies "
                                   f"differs from Exudyn's {[len(i) for i in self.ltg]}")
        return self.ltg

    def hold(self, mbs: Any, distance: float, h: float) -> None:
        """At an accepted step: keeps its state as the next step's start, and sets the rows
        and the rate for a next step of length ``h`` (:meth:`fit` sets them again where
        the step Exudyn takes has another length)."""
        data = mbs.systemData
        if self.start is None:  # switched on: no history of this engagement
            self.accelerations.clear()
        # the last start, for a step that another joint has redone after this one accepted it (fit)
        self.before = (self.start, self.scheme, self.held, self.norm) if self.start is not None else None
        self.start = (data.GetTime(), np.asarray(data.GetODE2Coordinates(), dtype=float),
                      np.asarray(data.GetODE2Coordinates_t(), dtype=float),
                      np.asarray(data.GetODE2Coordinates_tt(), dtype=float))
        while self.accelerations and self.accelerations[-1][0] >= self.start[0]:
            self.accelerations.pop()  # a step accepted, then redone for another joint: its state is gone
        self.accelerations.append((self.start[0], self.start[3]))
        self.scheme = _integrator_state(mbs, self.start[0], self.start[3].shape)
        self.held = float(distance)
        self.norm = float(np.linalg.norm(self._eccentricity(mbs, self._axis(mbs))))  # |e| at the start
        self._rows(mbs, h)

    def fit(self, mbs: Any, t: float) -> None:
        """From the force function, at Newton's iterate of a step ending at ``t``: the rows
        and the rate again if the step is not the one they were set for (Exudyn shortens a
        step it redoes and grows it after some steps; the turn of the predicted normal is
        the step's).  Measured without it on the zoo's 3D double pendulum with friction:
        the multiplier turned tensile at each step shortened to an eighth, 10 releases in 0.5 s."""
        if self.start is None:
            return
        if t < self.start[0] and self.before is not None:
            # the step that ended at the start is redone (another joint asked for it after this
            # one accepted it): back to that step's start, as the joint's kernel goes back to
            # its previous history
            self.start, self.scheme, self.held, self.norm = self.before
            self.before = None
            while self.accelerations and self.accelerations[-1][0] > self.start[0]:
                self.accelerations.pop()
            self.step = 0.0
        h = t - self.start[0]
        if h > 0.0 and abs(h - self.step) > 1e-9 * h:
            data = mbs.systemData
            q, v = np.asarray(data.GetODE2Coordinates(), dtype=float), np.asarray(data.GetODE2Coordinates_t(), dtype=float)
            try:
                self._rows(mbs, h)
            finally:
                data.SetODE2Coordinates(q)
                data.SetODE2Coordinates_t(v)

    def _predicted(self, h: float) -> np.ndarray:
        """The coordinates at the end of a step of length ``h`` from the kept start: the
        integrator's update with the end acceleration extrapolated (PREDICT_JERK; the start's
        while the engagement has fewer than JERK_STEPS accepted steps), or the second-order
        Taylor prediction where the integrator's state is not known."""
        t0, q0, v0, a0 = self.start
        if not (PREDICT_JERK and self.scheme is not None):
            return q0 + h * v0 + 0.5 * h * h * a0
        aa0, alpha_m, alpha_f, beta = self.scheme
        a1 = a0
        if len(self.accelerations) == JERK_STEPS:
            t_back, a_back = self.accelerations[0]
            a1 = a0 + (h / (t0 - t_back)) * (a0 - a_back)
        aa1 = ((1.0 - alpha_f) * a1 + alpha_f * a0 - alpha_m * aa0) / (1.0 - alpha_m)
        return q0 + h * v0 + h * h * ((0.5 - beta) * aa0 + beta * aa1)

    def _rows(self, mbs: Any, h: float) -> None:
        """The condition ``n . v_1 = RATE_GAIN (d - |e_0|) / h`` on the end velocity of a step
        of length ``h`` from the kept start, in the normal ``n`` of the configuration
        predicted for the step's end (:meth:`_predicted`), whose rows ``n^T dv/dq_t`` are
        taken there too (Exudyn evaluates the condition at the step's end; rows of the step's
        start are off by the bodies' turning over the step).  A journal whose velocity is
        tangent to the circle at both ends of a step moves off it by ``c theta^4`` for a turn
        ``theta`` of its normal per step (``h (v_0 + v_1) / 2``, generalized-alpha's
        ``beta / gamma = 1/2``).  Tried and dropped: the chord's bisector with
        ``n . v_1 = -n . v_0``, exact for a circle, but the start rate mirrored at every step
        is an undamped two-step mode (the orbiting journal let go within 70 steps).  Leaves
        the coordinates at the start's."""
        ov = exu.OutputVariableType
        data = mbs.systemData
        _, q0, v0, _ = self.start
        self.step = h
        predicted = self._predicted(h)
        data.SetODE2Coordinates(predicted)
        e = self._eccentricity(mbs, self._axis(mbs))  # the bearing's axis turns with it
        n = e / float(np.linalg.norm(e))
        unit = np.zeros_like(v0)
        rows = []
        for marker, indices in zip(self.markers, self._global_indices(mbs)):
            row = np.zeros((1, len(indices)))
            for j, g in enumerate(indices):
                unit[g] = 1.0
                data.SetODE2Coordinates_t(unit)
                row[0, j] = n @ np.asarray(mbs.GetMarkerOutput(marker, ov.Velocity), dtype=float)
                unit[g] = 0.0
            rows.append(row)
        data.SetODE2Coordinates(q0)
        data.SetODE2Coordinates_t(v0)
        mbs.SetObjectParameter(self.number, "scalingMarker0", rows[0])
        mbs.SetObjectParameter(self.number, "scalingMarker1", rows[1])
        rate = RATE_GAIN * (self.held - self.norm) / h if h > 0.0 else 0.0
        mbs.SetObjectParameter(self.number, "offset", [rate])

    def switch(self, mbs: Any, active: bool) -> None:
        mbs.SetObjectParameter(self.number, "activeConnector", bool(active))
        if not active:
            self.start = None


class CompiledCondition:
    """The velocity condition of the compiled kernel's following mode (``following.hpp``):
    ``n . (v_journal - v_bearing) = r`` as :class:`VelocityCondition`, an
    ``ObjectConnectorCoordinateVector`` whose constraint and Jacobian functions are the
    kernel's, called by Exudyn without Python.  They take the rows ``n^T dv/dq_t`` at Newton's
    first iterate of each step with its end acceleration extrapolated, for the bodies of
    :func:`compiled_sides`; the kernel keeps the distance and the rate.  Here: the switch
    and the multiplier."""

    two_step_mean = False

    def __init__(self, mbs: exu.MainSystem, markers: list[int], name: str, functions: tuple[Any, Any]) -> None:
        coordinate_markers = []
        for kind, number in (_coordinate_owner(mbs, m) for m in markers):  # a body's, or a node's own marker
            coordinate = MarkerNodeCoordinates(nodeNumber=number) if kind == "node" else \
                MarkerObjectODE2Coordinates(objectNumber=number)
            coordinate_markers.append(mbs.AddMarker(coordinate))
        # one algebraic equation: Exudyn counts them from scalingMarker0's rows
        self.number = mbs.AddObject(ObjectConnectorCoordinateVector(
            name=name, markerNumbers=coordinate_markers, scalingMarker0=np.zeros((1, 1)), velocityLevel=True,
            activeConnector=False, constraintUserFunction=functions[0], jacobianUserFunction=functions[1],
            visualization=VObjectConnectorCoordinateVector()))

    def multiplier(self, mbs: Any) -> float:
        """Once per followed step: Exudyn gives one equation's force as a float (no array to unpack)."""
        force = mbs.GetObjectOutput(self.number, exu.OutputVariableType.Force)
        return force if isinstance(force, float) else float(np.ravel(force)[0])

    def hold(self, mbs: Any, distance: float, h: float) -> None:
        """Nothing: the kernel holds the distance and sets the rows."""

    def switch(self, mbs: Any, active: bool) -> None:
        mbs.SetObjectParameter(self.number, "activeConnector", bool(active))

    def fit(self, mbs: Any, t: float) -> None:
        """Nothing: the rows are Newton's first iterate's, whatever the step."""


#: The compiled condition's side kinds (``kinematics.hpp`` SideKind): a body marker's object type
#: and, for a 3D rigid body, its node type; a node's own marker (``MarkerNodeRigid``, as on a
#: beam's node) by its node type alone.
COMPILED_SIDES = {("Ground", ""): 0, ("RigidBody2D", "RigidBody2D"): 1, ("RigidBody", "RigidBodyEP"): 2,
                  ("RigidBody", "RigidBodyRxyz"): 3, ("RigidBody", "RigidBodyRotVecLG"): 4}
COMPILED_NODE_SIDES = {node: kind for (_, node), kind in COMPILED_SIDES.items() if node}


def compiled_sides(mbs: Any, markers: list[int]) -> list[tuple[int, list[float], np.ndarray]] | None:
    """The compiled condition's two sides (``following.hpp`` ConditionSide): per marker, its
    kind (:data:`COMPILED_SIDES`), its position in its body (on the ground: global) and its
    frame there (rotation matrix); None where a marker is on another body (the Python
    kernel's condition takes any)."""
    sides = []
    for m in markers:
        info = mbs.GetMarker(m)
        if info.get("markerType") == "NodeRigid" and "nodeNumber" in info:  # at the node, in its frame
            kind = COMPILED_NODE_SIDES.get(mbs.GetNode(int(info["nodeNumber"]))["nodeType"])
            if kind is None:
                return None
            sides.append((kind, [0.0, 0.0, 0.0], np.eye(3)))
            continue
        if info.get("markerType") not in ("BodyRigid", "BodyPosition") or "bodyNumber" not in info:
            return None
        body = mbs.GetObject(int(info["bodyNumber"]))
        node = mbs.GetNode(int(body["nodeNumber"]))["nodeType"] if "nodeNumber" in body else ""
        kind = COMPILED_SIDES.get((body["objectType"], node))
        if kind is None:
            return None
        frame = np.asarray(info["localHT"], dtype=float) if "localHT" in info else np.eye(4)
        local = np.ravel(info.get("localPosition", frame[:3, 3])).astype(float)
        if kind == 0:
            local = local + np.ravel(body.get("referencePosition", [0.0, 0.0, 0.0]))
        sides.append((kind, [float(v) for v in local], frame[:3, :3].copy()))
    return sides


def _integrator_state(mbs: Any, t: float, shape: tuple) -> tuple | None:
    """``(a_alg, alpha_m, alpha_f, beta)`` of the generalized-alpha solver running ``mbs``
    (``mbs.sys["dynamicSolver"]``, stored by ``mbs.SolveDynamic``) at its accepted step
    ending at ``t``; None for another solver, Newmark's (radius 1), or a stored solver that is
    not at ``t`` (a run by a solver object of the user's own)."""
    solver = getattr(mbs, "sys", {}).get("dynamicSolver")
    try:
        if not (float(solver.spectralRadius) < 1.0 and abs(float(solver.it.currentTime) - t) <= 1e-12 * max(1.0, abs(t))):
            return None
        aa = np.asarray(solver.GetAAlgorithmic(), dtype=float)
        state = (aa, float(solver.alphaM), float(solver.alphaF), float(solver.newmarkBeta))
    except (AttributeError, TypeError, RuntimeError):
        return None
    return state if aa.shape == shape else None


def _coordinate_owner(mbs: Any, marker: int) -> tuple[str, int]:
    """The body (object) or node whose coordinates move the marker."""
    info = mbs.GetMarker(marker)
    for key, kind in (("bodyNumber", "object"), ("objectNumber", "object"), ("nodeNumber", "node")):
        if key in info:
            return kind, int(info[key])
    raise ValueError(f"contact_mode='follow': marker {marker} ({info.get('markerType')}) is on no body or node")


def _object_nodes(mbs: Any, number: int) -> list[int]:
    info = mbs.GetObject(number)
    if "nodeNumbers" in info:
        return [int(n) for n in info["nodeNumbers"]]
    return [int(info["nodeNumber"])] if "nodeNumber" in info else []


def _node_ode2_size(mbs: Any, number: int) -> int:
    info = mbs.GetNode(number)
    if "Ground" in info["nodeType"]:
        return 0
    if "numberOfODE2Coordinates" in info:
        return int(info["numberOfODE2Coordinates"])
    return len(info["referenceCoordinates"])
