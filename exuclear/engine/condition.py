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

from ..vectors import cross
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


class Poses(NamedTuple):
    """Two rigid markers' positions [m] and rotation matrices (3 x 3; None: not read) at one
    state, global."""

    positions: tuple[np.ndarray, np.ndarray]
    rotations: tuple[np.ndarray | None, np.ndarray | None]


class MarkerState:
    """Two rigid markers [0, 1] at the system's current coordinates: their poses, and their
    velocities and angular velocities as maps of their bodies' coordinate rates, each read
    from Exudyn once per state (the ODE2 coordinates, which alone move a rigid marker): a
    joint's contacts read the same two markers at one state, and a held step computed again
    measures its rows again at the state of its first computation (:meth:`forget` at a run's
    start: a body's reference coordinates may change between runs).

    A marker's velocity and angular velocity are linear in its body's coordinate rates,
    ``v = V q_t``, with maps that depend on the coordinates alone: Exudyn's marker outputs
    at unit coordinate velocities are their columns, probed for both markers at once where
    their bodies share no coordinate (any body with a rigid marker: rigid bodies of every
    rotation parameterization, beams' nodes, ANCF elements).
    """

    def __init__(self, mbs: exu.MainSystem, markers: Sequence[Any]) -> None:
        self.markers = list(markers)
        self._owners = [coordinate_owner(mbs, m) for m in self.markers]
        self._ltg: list[list[int]] | None = None  # each owner's global ODE2 indices (known once the system is assembled)
        self.index_arrays: list[np.ndarray] = []  # the same as arrays
        self._apart = False  # whether the two owners share no coordinate
        # the last poses and maps read, each with the coordinates of its state (a held step's
        # rows are measured again at the state they were, after the poses at another)
        self._poses: tuple[bytes, Poses | None] = (b"", None)
        self._maps: tuple[bytes, list[tuple[np.ndarray, np.ndarray | None]] | None] = (b"", None)

    @property
    def owners(self) -> list[tuple[str, int]]:
        """The body (object) or node whose coordinates move each marker."""
        return self._owners

    def indices(self, mbs: exu.MainSystem) -> list[list[int]]:
        """Each marker's owner's global ODE2 indices."""
        if self._ltg is None:
            data = mbs.systemData
            self._ltg = [[int(g) for g in (data.GetNodeLTGODE2(k) if kind == "node" else data.GetObjectLTGODE2(k))]
                         for kind, k in self._owners]
            self.index_arrays = [np.array(ltg, dtype=int) for ltg in self._ltg]
            self._apart = not set(self._ltg[0]) & set(self._ltg[1])
        return self._ltg

    def forget(self) -> None:
        """Nothing of the states read before (a new run)."""
        self._poses, self._maps = (b"", None), (b"", None)

    def poses(self, mbs: exu.MainSystem, rotations: tuple[bool, bool] = (True, True)) -> Poses:
        """The markers' positions and, where ``rotations`` asks, rotation matrices, now."""
        key = mbs.systemData.GetODE2Coordinates().tobytes()
        poses = self._poses[1] if self._poses[0] == key else None
        if poses is None or (rotations[0] and poses.rotations[0] is None) or \
                (rotations[1] and poses.rotations[1] is None):
            ov = exu.OutputVariableType
            positions = poses.positions if poses is not None else tuple(
                mbs.GetMarkerOutput(m, ov.Position) for m in self.markers)
            had = poses.rotations if poses is not None else (None, None)
            turned = tuple(r if r is not None or not want else
                           mbs.GetMarkerOutput(m, ov.RotationMatrix).reshape(3, 3)
                           for m, r, want in zip(self.markers, had, rotations))
            poses = Poses(positions, turned)  # type: ignore[arg-type]
            self._poses = (key, poses)
        return poses

    def maps(self, mbs: exu.MainSystem, angular: tuple[bool, bool]) -> list[tuple[np.ndarray, np.ndarray | None]]:
        """Each marker's velocity map ``V`` and, where ``angular`` asks, angular velocity map
        ``W`` (each ``m x 3``: row ``j`` the marker's velocity at a unit rate of its owner's
        ``j``-th coordinate), now."""
        key = mbs.systemData.GetODE2Coordinates().tobytes()
        maps = self._maps[1] if self._maps[0] == key else None
        if maps is None or any(want and w is None for want, (_, w) in zip(angular, maps)):
            had = (False, False) if maps is None else tuple(w is not None for _, w in maps)
            maps = self._probe(mbs, (angular[0] or had[0], angular[1] or had[1]))
            self._maps = (key, maps)
        return maps

    def _probe(self, mbs: exu.MainSystem, angular: tuple[bool, bool]) -> list[tuple[np.ndarray, np.ndarray | None]]:
        """The maps of :meth:`maps`, from the marker outputs at unit coordinate velocities
        (both markers' in one setting where their owners share no coordinate)."""
        data, ov = mbs.systemData, exu.OutputVariableType
        ltg = self.indices(mbs)
        v = data.GetODE2Coordinates_t().tolist()
        unit = [0.0] * len(v)  # lists: Exudyn reads them several times faster than arrays
        columns: list[tuple[list[Any], list[Any]]] = [([], []), ([], [])]
        groups = [(0, 1)] if self._apart else [(0,), (1,)]
        for group in groups:
            for j in range(max(len(ltg[k]) for k in group)):
                probed = [k for k in group if j < len(ltg[k])]
                for k in probed:
                    unit[ltg[k][j]] = 1.0
                data.SetODE2Coordinates_t(unit)
                for k in probed:
                    columns[k][0].append(mbs.GetMarkerOutput(self.markers[k], ov.Velocity))
                    if angular[k]:
                        columns[k][1].append(mbs.GetMarkerOutput(self.markers[k], ov.AngularVelocity))
                    unit[ltg[k][j]] = 0.0
        data.SetODE2Coordinates_t(v)
        return [(np.array(velocity, dtype=float).reshape(-1, 3),
                 np.array(spin, dtype=float).reshape(-1, 3) if wanted else None)
                for (velocity, spin), wanted in zip(columns, angular)]


class VelocityCondition:
    """``n . (v_1 - v_0) = r`` between ``markers`` [0, 1] (a :class:`MarkerState` of them,
    shared with what else reads them, or their numbers), off until :meth:`hold`.

    Attributes
    ----------
    objectNumber : int
        The ``ObjectConnectorCoordinateVector``.
    plan : Plan
        Its present setting.
    """

    def __init__(self, mbs: exu.MainSystem, markers: MarkerState | Sequence[Any], name: str) -> None:
        self.state = markers if isinstance(markers, MarkerState) else MarkerState(mbs, markers)
        self.markers = self.state.markers
        coordinate_markers, sizes = [], []
        for kind, number in self.state.owners:
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
        self.rows: tuple[np.ndarray, ...] = ()
        self.plan = OFF

    def measure(self, mbs: exu.MainSystem, normal: Sequence[float], arms: Sequence[Any] = (None, None)) -> float:
        """Sets the rows along ``normal`` (global) at the current state and returns the rate
        ``normal . (v_1 - v_0)`` there; ``arms`` (global, None: 0) move a marker's point to
        the point of its body ``r`` away, whose velocity is ``v + omega x r``."""
        maps = self.state.maps(mbs, (arms[0] is not None, arms[1] is not None))
        n = np.asarray(normal, dtype=float)
        rows = []
        for (velocity, spin), arm in zip(maps, arms):
            row = velocity @ n
            if arm is not None:  # n . (omega x r) = omega . (r x n)
                row += spin @ np.asarray(cross(arm, n))
            rows.append(row.reshape(1, -1))
        self.rows = tuple(rows)
        return self.rate(mbs.systemData.GetODE2Coordinates_t())

    def rate(self, x: np.ndarray) -> float:
        """``n . (x_1 - x_0)`` for the system's coordinate rates ``x`` (velocities or
        accelerations) through the rows of the last :meth:`measure`: the condition's own
        measure, ``S1 q1_t - S0 q0_t`` (Exudyn's ``ObjectConnectorCoordinateVector``
        subtracts marker 0's term)."""
        (row0, row1), (i0, i1) = self.rows, self.state.index_arrays
        return float(row1[0] @ x[i1]) - float(row0[0] @ x[i0])

    def multiplier(self, mbs: exu.MainSystem) -> float:
        """The condition's multiplier [N] (0 where it is off)."""
        return scalar_force(mbs, self.objectNumber) if self.plan.active else 0.0

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


def scalar_force(mbs: exu.MainSystem, number: int) -> float:
    """The ``Force`` output [N] of a one-equation Exudyn constraint (its multiplier), which
    Exudyn gives as a float or a one-element array."""
    force = mbs.GetObjectOutput(number, exu.OutputVariableType.Force)
    return force if isinstance(force, float) else float(np.ravel(force)[0])


def request_jacobian(mbs: exu.MainSystem) -> None:
    """A new Jacobian for the coming step: a modified Newton iteration on the Jacobian of
    the step before, without the condition's row or with its old normal, does not converge
    (on the paper's slider-crank it failed at the first resting contact)."""
    mbs.sys["dynamicSolver"].conv.jacobianUpdateRequested = True
