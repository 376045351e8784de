"""A velocity-level condition between two rigid markers, switched on and off mid-run: the
Exudyn item the impulse contact mode (:mod:`~exuclear.engine.impulse`) holds a contact with.

One ``ObjectConnectorCoordinateVector`` between the coordinates of the markers' two bodies
(or nodes), ``n . (v_1 - v_0) = r`` in a direction ``n`` the mode chooses, off
(``activeConnector=False``) until held.  Its rows ``n^T dv/dq_t`` are Exudyn's marker
velocities at unit coordinate velocities, so any body with a rigid marker takes it (rigid
bodies of any rotation parameters, beams' nodes, ANCF cables).  Exudyn holds the step's end
velocities on it; its multiplier is the force along ``n``.

This module is engine glue only: which direction to hold, when and at which rate is the
mode's.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerNodeCoordinates,
    MarkerObjectODE2Coordinates,
    ObjectConnectorCoordinateVector,
    VObjectConnectorCoordinateVector,
)

from .bodies import coordinate_owner, node_ode2_size, object_nodes


class Plan(NamedTuple):
    """A setting of the condition: on or off, its rows (marker 0's, marker 1's) and the
    rate it holds."""

    active: bool
    rows: tuple[np.ndarray, ...]
    rate: float

    def same(self, other: "Plan") -> bool:
        """Whether two settings act the same (both off, or on with equal rows and rate)."""
        if self.active != other.active:
            return False
        return not self.active or (self.rate == other.rate and
                                   all(np.array_equal(x, y) for x, y in zip(self.rows, other.rows)))


OFF = Plan(False, (), 0.0)


class VelocityCondition:
    """``n . (v_1 - v_0) = r`` between ``markers`` [0, 1], off until :meth:`hold`.

    Attributes
    ----------
    objectNumber : int
        The ``ObjectConnectorCoordinateVector``.
    plan : Plan
        Its present setting.
    """

    def __init__(self, mbs: exu.MainSystem, markers: Sequence[Any], name: str) -> None:
        self.markers = list(markers)
        self._owners = [coordinate_owner(mbs, m) for m in self.markers]
        coordinate_markers, sizes = [], []
        for kind, number in self._owners:
            if kind == "node":
                coordinate_markers.append(mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=number)))
                sizes.append(node_ode2_size(mbs, number))
            else:
                coordinate_markers.append(mbs.AddMarker(MarkerObjectODE2Coordinates(objectNumber=number)))
                sizes.append(sum(node_ode2_size(mbs, n) for n in object_nodes(mbs, number)))
        self.objectNumber = mbs.AddObject(ObjectConnectorCoordinateVector(
            name=name, markerNumbers=coordinate_markers, scalingMarker0=np.zeros((1, sizes[0])),
            scalingMarker1=np.zeros((1, sizes[1])), offset=[0.0], velocityLevel=True, activeConnector=False,
            visualization=VObjectConnectorCoordinateVector()))
        self._ltg: list[np.ndarray] | None = None  # each owner's global ODE2 indices (known once the system is assembled)
        self.rows: tuple[np.ndarray, ...] = ()
        self.plan = OFF

    def measure(self, mbs: exu.MainSystem, normal: np.ndarray, arms: Sequence[Any] = (None, None)) -> float:
        """Sets the rows along ``normal`` (global) at the current state and returns the rate
        ``normal . (v_1 - v_0)`` there; ``arms`` (global, None: 0) move a marker's point to
        the point of its body ``r`` away, whose velocity is ``v + omega x r``."""
        data = mbs.systemData
        if self._ltg is None:
            self._ltg = [np.asarray(data.GetNodeLTGODE2(k) if kind == "node" else data.GetObjectLTGODE2(k), dtype=int)
                         for kind, k in self._owners]
        v = np.asarray(data.GetODE2Coordinates_t(), dtype=float)
        unit = np.zeros_like(v)
        rows = []
        ov = exu.OutputVariableType
        for marker, indices, arm in zip(self.markers, self._ltg, arms):
            row = np.zeros((1, len(indices)))
            for j, g in enumerate(indices):
                unit[g] = 1.0
                data.SetODE2Coordinates_t(unit)
                row[0, j] = normal @ np.asarray(mbs.GetMarkerOutput(marker, ov.Velocity), dtype=float)
                if arm is not None:  # n . (omega x r) = omega . (r x n)
                    row[0, j] += np.cross(arm, normal) @ np.asarray(mbs.GetMarkerOutput(marker, ov.AngularVelocity),
                                                                    dtype=float)
                unit[g] = 0.0
            rows.append(row)
        data.SetODE2Coordinates_t(v)
        self.rows = tuple(rows)
        return self.rate(v)

    def rate(self, x: np.ndarray) -> float:
        """``n . (x_1 - x_0)`` for the system's coordinate rates ``x`` (velocities or
        accelerations) through the rows of the last :meth:`measure`: the condition's own
        measure, ``S1 q1_t - S0 q0_t`` (Exudyn's ``ObjectConnectorCoordinateVector``
        subtracts marker 0's term)."""
        (row0, row1), (i0, i1) = self.rows, self._ltg
        return float(row1[0] @ x[i1]) - float(row0[0] @ x[i0])

    def multiplier(self, mbs: exu.MainSystem) -> float:
        """The condition's multiplier [N] (0 where it is off)."""
        if not self.plan.active:
            return 0.0
        force = mbs.GetObjectOutput(self.objectNumber, exu.OutputVariableType.Force)
        return force if isinstance(force, float) else float(np.ravel(force)[0])

    def hold(self, mbs: exu.MainSystem, end_rate: float) -> None:
        """On for the coming step, in the rows of the last :meth:`measure`, holding the
        step's end rate at ``end_rate``."""
        self.set(mbs, Plan(True, self.rows, float(end_rate)))

    def release(self, mbs: exu.MainSystem) -> None:
        """Off for the coming step."""
        self.set(mbs, OFF)

    def set(self, mbs: exu.MainSystem, plan: Plan) -> None:
        """The condition as ``plan`` says, with a fresh Jacobian (:func:`request_jacobian`)."""
        self.plan = plan
        if plan.active:
            mbs.SetObjectParameter(self.objectNumber, "scalingMarker0", plan.rows[0])
            mbs.SetObjectParameter(self.objectNumber, "scalingMarker1", plan.rows[1])
            mbs.SetObjectParameter(self.objectNumber, "offset", [plan.rate])
        self.switch(mbs, plan.active)

    def switch(self, mbs: exu.MainSystem, on: bool) -> None:
        """The condition on or off in Exudyn, with a fresh Jacobian."""
        mbs.SetObjectParameter(self.objectNumber, "activeConnector", on)
        request_jacobian(mbs)


def request_jacobian(mbs: exu.MainSystem) -> None:
    """A new Jacobian for the coming step: a modified Newton iteration on the Jacobian of
    the step before, without the condition's row or with its old normal, does not converge
    (on the paper's slider-crank it failed at the first resting contact)."""
    mbs.sys["dynamicSolver"].conv.jacobianUpdateRequested = True
