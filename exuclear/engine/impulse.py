"""The impulse contact mode of a planar revolute clearance joint (:mod:`~exuclear.engine.modes`).

Moreau-Jean time stepping inside Exudyn's generalized-alpha solver, at the user's step:

- **The condition.**  One velocity-level ``ObjectConnectorCoordinateVector`` between the
  coordinates of the joint's two bodies, ``n . (v_journal - v_bearing) = r``, off in free
  flight.  Its rows ``n^T dv/dq_t`` are Exudyn's marker velocities at unit coordinate
  velocities (any body with a rigid marker), in the normal ``n = e / |e|`` of the step's
  start.  Under generalized-alpha with spectral radius 1 (the trapezoidal rule) Exudyn
  holds the mean of the step's start and end velocities on such a condition
  (/work/shared/research/nonsmooth-impacts-in-exudyn.md), so the offset that gives the end
  rate ``v1`` is ``(v0 + v1) / 2``.  Under numerical damping the jump leaks into the
  following steps through the algorithmic accelerations: the mode refuses such a run.
- **An impact** is a step whose start gap closes within it (``|e| - c + h v_n >= 0`` with
  ``v_n > 0``): the condition is on for that step with the end rate ``-e(v_n) v_n``, the
  restitution of the joint's law at the impact velocity
  (:func:`exuclear.contact.restitution_of_damping`; below the law's ``v_min`` its damping
  term weighs ``v_n / v_min`` of ``D``), and off again after it.
- **Resting contact.**  Where the rebound would land within :data:`REST_STEPS` steps under
  the normal acceleration at the step's start, the journal stays on the wall: the condition
  is held from step to step with a rate that takes the penetration back, critically damped
  (:meth:`ImpulseJointHandle._resting_rate`), and let go where its reaction pulls.
- **What is not computed**: the force pulse.  Each impact's peak force, duration and
  largest penetration follow from the law's closed form at the impact velocity and the
  effective mass the solver's impulse shows (:func:`closed_form_impact`).

The mode runs from a pre-step function chained before the system's own (the one set when
the joint is built); a pre-step function set later replaces it, which the handle's outputs
detect and refuse.
"""
from __future__ import annotations

import math
import weakref
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

from ..contact import restitution_of_damping
from ..joint import ClearanceJoint
from ..timescales import stored_energy
from .bodies import joint_mass
from .steering import explicit_solver

#: The resting condition takes the penetration back at the rate ``RATE_GAIN / h``
#: (critically damped): about 0.75 of it is left after each step.
RATE_GAIN = 0.5
#: A rebound that would land within this many steps is a resting contact: the bounces of a
#: journal on its wall would otherwise shrink geometrically, one impact a step (a Zeno
#: sequence the steps cannot resolve).
REST_STEPS = 2.0
#: Spectral radius of generalized-alpha the mode needs: 1 (module docstring).  Exudyn keeps
#: the radius to round-off; the tolerance only absorbs that.
SPECTRAL_RADIUS_TOLERANCE = 1e-12
#: A penetration beyond this many clearances stops the run: the positions are then off by
#: the journal's travel across the clearance (steps too long for it), or the condition lost
#: the contact.  The restitution of each jump stays the law's, the path does not.
LOST_CONTACT = 1.0
#: Two step starts closer than this (relative) are one step, redone by the solver.
REDO_TOLERANCE = 1e-12
#: Samples of the compression phase in which :func:`closed_form_impact` looks for the peak force.
PEAK_SAMPLES = 64
#: Relative tolerance of the bisections of :func:`closed_form_impact`.
DEPTH_RTOL = 1e-10

#: The states of the condition between steps.
FREE, IMPACT, LANDING, REST = "free", "impact", "landing", "rest"


class ClosedFormImpact(NamedTuple):
    """One impact of the impulse mode (SI units): its time and velocity, with the peak force,
    the duration and the largest penetration the joint's law gives at that velocity in
    closed form (``closed_form`` is True: no force pulse was integrated), and the
    restitution the step applied."""

    onset_time: float
    onset_velocity: float
    peak_force: float
    duration: float
    max_penetration: float
    restitution: float
    effective_mass: float
    closed_form: bool = True


def impact_restitution(law: Any, speed: float) -> float:
    """The restitution of the joint's law for an impact at ``speed`` [m/s] > 0: its damping
    factor ``D``, taken at ``D speed / v_min`` below ``v_min`` (docs/physics.md eq. (9):
    the onset velocity in the damping term is at least ``v_min``)."""
    d = law.damping_factor * min(1.0, speed / law.v_min)
    return restitution_of_damping(d) if d > 0.0 else 1.0


def closed_form_impact(law: Any, mass: float, speed: float) -> tuple[float, float, float]:
    """Peak force [N], duration [s] and largest penetration [m] of one impact of ``mass``
    [kg] at ``speed`` [m/s] on ``F_e(delta) (1 + D' delta_dot / speed)`` (``D'`` as in
    :func:`impact_restitution`).  Along the compression ``u = delta_dot / speed`` falls from 1
    to 0 and ``int_0^delta F_e = m speed^2 ((1 - u) / D' - ln((1 + D') / (1 + D' u)) / D'^2)``
    (Lankarani and Nikravesh 1990, eq. (13), for any ``F_e``; ``(1 - u^2) / 2`` for ``D' = 0``);
    the peak is the largest force over :data:`PEAK_SAMPLES` points of it.  The duration is
    ``pi delta_max / speed`` (:func:`exuclear.timescales.impact_duration`'s estimate)."""
    d = law.damping_factor * min(1.0, speed / law.v_min)
    scale = mass * speed * speed

    def energy(u: float) -> float:  # the stored energy at the rate ratio u
        if d < 1e-8:  # the series' first term: the logarithm's difference loses its digits
            return 0.5 * scale * (1.0 - u * u)
        return scale * ((1.0 - u) / d - math.log((1.0 + d) / (1.0 + d * u)) / (d * d))

    def depth(target: float) -> float:  # the penetration that stores ``target``
        lo, hi = 0.0, law.geometry.clearance
        if not stored_energy(law, hi) > target:
            return hi
        while hi - lo > DEPTH_RTOL * hi:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if stored_energy(law, mid) >= target else (mid, hi)
        return 0.5 * (lo + hi)

    delta_max = depth(energy(0.0))
    peak = law.elastic_force(delta_max)
    for k in range(1, PEAK_SAMPLES):
        u = k / PEAK_SAMPLES
        peak = max(peak, law.elastic_force(depth(energy(u))) * (1.0 + d * u))
    return peak, math.pi * delta_max / speed, delta_max


class ImpulseJointHandle:
    """A planar revolute clearance joint in the impulse mode; returned by
    :func:`exuclear.CreateClearanceJoint` with ``contact_mode="impulse"``.

    Attributes
    ----------
    objectNumber : int
        The velocity-level condition (``ObjectConnectorCoordinateVector``).
    markerNumbers : list
        [bearing marker, journal marker].
    contact_mode : str
        ``"impulse"``.
    """

    contact_mode = "impulse"

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                 axis: np.ndarray) -> None:
        self._mbs = weakref.ref(mbs)
        self._axis_local = np.asarray(axis, dtype=float)
        self.name, self._joint = name, joint
        self.markerNumbers = list(markers)
        self._owners = [_coordinate_owner(mbs, m) for m in self.markerNumbers]
        coordinate_markers, sizes = [], []
        for kind, number in self._owners:
            if kind == "node":
                coordinate_markers.append(mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=number)))
                sizes.append(_node_ode2_size(mbs, number))
            else:
                coordinate_markers.append(mbs.AddMarker(MarkerObjectODE2Coordinates(objectNumber=number)))
                sizes.append(sum(_node_ode2_size(mbs, n) for n in _object_nodes(mbs, number)))
        self._sizes = sizes
        self.objectNumber = mbs.AddObject(ObjectConnectorCoordinateVector(
            name=name, markerNumbers=coordinate_markers, scalingMarker0=np.zeros((1, sizes[0])),
            scalingMarker1=np.zeros((1, sizes[1])), offset=[0.0], velocityLevel=True, activeConnector=False,
            visualization=VObjectConnectorCoordinateVector()))
        self._ltg: list[np.ndarray] | None = None
        self._user_pre = _installed(mbs.GetPreStepUserFunction())
        mbs.SetPreStepUserFunction(self._pre_step)
        self._reset()

    @property
    def joint(self) -> ClearanceJoint:
        return self._joint

    # -- the run ------------------------------------------------------------------------
    def _reset(self) -> None:
        self._state = FREE
        self._impacts: list[tuple[float, float, float, float]] = []  # (t, v-, e, multiplier of the step)
        self._pending: int | None = None  # the impact whose step's multiplier is read next
        self._rows: list[np.ndarray] = []
        self._records: list[tuple[float, float, float, float, float]] = []  # t, ecc_x, ecc_y, gap, force
        self._step = self._force = 0.0
        self._resting = 0
        self._problem = ""
        self._left_pen = 0.0

    def _pre_step(self, mbs: exu.MainSystem, t: float) -> bool:
        if not self._records or t <= self._records[-1][0]:  # a new run
            self._reset()
            self._check_solver(mbs)
        self._step_decision(mbs, t)
        return self._user_pre(mbs, t) if self._user_pre is not None else True

    def _check_solver(self, mbs: exu.MainSystem) -> None:
        solver = getattr(mbs, "sys", {}).get("dynamicSolver")
        problem = ""
        if solver is None or explicit_solver(solver):
            problem = "an explicit solver (or a run not started by SolveDynamic) has no condition to hold the contact"
        elif abs(float(solver.spectralRadius) - 1.0) > SPECTRAL_RADIUS_TOLERANCE:
            problem = (f"generalized-alpha's spectral radius is {float(solver.spectralRadius):g}: under numerical "
                       "damping the velocity jump leaks into the following steps; set "
                       "timeIntegration.generalizedAlpha.spectralRadius = 1")
        if problem:
            self._problem = (f"joint {self.name or '(unnamed)'}: contact_mode='impulse' refuses this run: {problem}; "
                             "or use contact_mode='compliant'")
            raise ValueError(self._problem)

    def _kinematics(self, mbs: exu.MainSystem) -> tuple[np.ndarray, float, float]:
        """The eccentricity ``e`` (global, in the bearing's plane), the normal rate and the gap
        ``|e| - c`` at the current state; sets the rows in the normal ``e / |e|``."""
        ov = exu.OutputVariableType
        axis = np.asarray(mbs.GetMarkerOutput(self.markerNumbers[0], ov.RotationMatrix), dtype=float).reshape(3, 3) @ self._axis_local
        p = [np.asarray(mbs.GetMarkerOutput(m, ov.Position), dtype=float) for m in self.markerNumbers]
        e = p[1] - p[0]
        e = e - (e @ axis) * axis
        norm = float(np.linalg.norm(e))
        n = e / norm if norm > 0.0 else np.zeros(3)
        data = mbs.systemData
        if self._ltg is None:
            self._ltg = [np.asarray(data.GetNodeLTGODE2(k) if kind == "node" else data.GetObjectLTGODE2(k), dtype=int)
                         for kind, k in self._owners]
        v = np.asarray(data.GetODE2Coordinates_t(), dtype=float)
        unit = np.zeros_like(v)
        rows = []
        for marker, indices in zip(self.markerNumbers, self._ltg):
            row = np.zeros((1, len(indices)))
            for j, g in enumerate(indices):
                unit[g] = 1.0
                data.SetODE2Coordinates_t(unit)
                row[0, j] = n @ np.asarray(mbs.GetMarkerOutput(marker, ov.Velocity), dtype=float)
                unit[g] = 0.0
            rows.append(row)
        data.SetODE2Coordinates_t(v)
        self._rows = rows
        return e, self._normal(v), norm - self._joint.geometry.clearance

    def _normal(self, x: np.ndarray) -> float:
        """``n . (x_journal - x_bearing)`` for the coordinates' rates ``x`` (velocities or
        accelerations) through the rows: the condition's own measure, ``S1 q1_t - S0 q0_t``
        (Exudyn's ``ObjectConnectorCoordinateVector`` subtracts marker 0's term)."""
        (bearing, journal), (i_b, i_j) = self._rows, self._ltg
        return float(journal[0] @ x[i_j]) - float(bearing[0] @ x[i_b])

    def _closing_acceleration(self, mbs: exu.MainSystem) -> float:
        """The normal acceleration towards the wall at the current state, ``n^T dv/dq_t q_tt``
        (the rows' part; the centripetal part ``d(n^T dv/dq_t)/dt q_t`` is left out: it
        only sets whether a rebound counts as resting)."""
        return self._normal(np.asarray(mbs.systemData.GetODE2Coordinates_tt(), dtype=float))

    def _resting_rate(self, mbs: exu.MainSystem, rate: float, gap: float, h: float) -> float:
        """The end rate of a resting step: the trapezoidal rule's ``v0 + h (a0 + a1) / 2`` with
        the end acceleration ``a1 = -w^2 gap - 2 w v0`` (critically damped, ``w = RATE_GAIN / h``),
        so that the held rate takes back the penetration smoothly and the acceleration the
        solver derives from it keeps no step-to-step alternation (a rate jumped to its target
        leaves one, undamped under the trapezoidal rule, in the multipliers)."""
        w = RATE_GAIN / h
        return rate + 0.5 * h * (self._closing_acceleration(mbs) - w * w * gap - 2.0 * w * rate)

    def _multiplier(self, mbs: exu.MainSystem) -> float:
        force = mbs.GetObjectOutput(self.objectNumber, exu.OutputVariableType.Force)
        return force if isinstance(force, float) else float(np.ravel(force)[0])

    def _hold(self, mbs: exu.MainSystem, end_rate: float) -> None:
        """The condition on for the coming step, holding its end rate at ``end_rate``."""
        mbs.SetObjectParameter(self.objectNumber, "scalingMarker0", self._rows[0])
        mbs.SetObjectParameter(self.objectNumber, "scalingMarker1", self._rows[1])
        mbs.SetObjectParameter(self.objectNumber, "offset", [end_rate])
        mbs.SetObjectParameter(self.objectNumber, "activeConnector", True)
        _request_jacobian(mbs)


    def _release(self, mbs: exu.MainSystem, state: str) -> None:
        mbs.SetObjectParameter(self.objectNumber, "activeConnector", False)
        _request_jacobian(mbs)
        self._state = state

    def _step_decision(self, mbs: exu.MainSystem, t_end: float) -> None:
        """At the start of the step that ends at ``t_end`` (Exudyn's pre-step time)."""
        h = float(mbs.sys["dynamicSolver"].it.currentStepSize)
        t = t_end - h
        if self._records and abs(t - self._records[-1][0]) <= REDO_TOLERANCE * max(1.0, abs(t)):
            self._problem = (f"joint {self.name or '(unnamed)'}: contact_mode='impulse' stops the run at t = {t:.6g} s: "
                             "Exudyn redoes a step there (its Newton iteration did not converge with the contact's "
                             "condition, as where a held contact slides along the wall), and the mode's decisions "
                             "are taken once per step; use contact_mode='compliant'")
            raise ValueError(self._problem)
        force = self._multiplier(mbs) if self._state in (IMPACT, REST) else 0.0
        if self._pending is not None:  # the impact step's multiplier: its impulse, the effective mass
            tk, vk, ek, _ = self._impacts[self._pending]
            self._impacts[self._pending] = (tk, vk, ek, force * self._step)
            self._pending = None
        e, rate, gap = self._kinematics(mbs)
        self._left_pen = max(self._left_pen, gap)
        clearance = self._joint.geometry.clearance
        if gap > LOST_CONTACT * clearance:
            self._problem = (f"joint {self.name or '(unnamed)'}: contact_mode='impulse' stops the run at t = {t:.6g} s: "
                             f"the journal is {gap:.3g} m into the wall, more than {LOST_CONTACT:g} times the "
                             f"clearance ({clearance:.3g} m): the steps are too long for the motion across the "
                             "clearance, or the condition could not follow the contact; take shorter steps or use "
                             "contact_mode='compliant'")
            raise ValueError(self._problem)
        # the resting multiplier alternates from step to step about the load under the
        # trapezoidal rule (an undamped mode of the held velocity's acceleration): its
        # two-step mean is the reaction
        reaction = 0.5 * (force + self._force) if self._state == REST and self._resting > 1 else force
        self._force = force
        self._records.append((t, float(e[0]), float(e[1]), gap, reaction if self._state == REST else 0.0))
        if self._state == IMPACT:
            # the impact step held its end rate at the mean of v- and v+; the free step after
            # it lands on v+ through the step's algorithmic acceleration (module docstring),
            # so no contact is looked for in it
            self._release(mbs, LANDING)
        elif self._state == LANDING:
            self._state = FREE
        elif self._state == REST:
            self._resting += 1
            if self._resting > 2 and reaction < 0.0:  # the condition pulls the journal onto the wall
                self._release(mbs, FREE)
            else:
                self._hold(mbs, self._resting_rate(mbs, rate, gap, h))
        if self._state == FREE and gap + h * rate >= 0.0 and rate > 0.0:
            restitution = impact_restitution(self._joint.law, rate)
            rebound = restitution * rate
            accel = self._closing_acceleration(mbs)
            if accel > 0.0 and 2.0 * rebound / accel <= REST_STEPS * h:
                self._state, self._resting = REST, 0
                self._hold(mbs, self._resting_rate(mbs, rate, max(gap, 0.0), h))
                restitution = 0.0
            else:
                self._state = IMPACT
                self._hold(mbs, 0.5 * (rate - rebound))
            self._impacts.append((t, rate, restitution, math.nan))
            self._pending = len(self._impacts) - 1
        self._step = h

    # -- what a run leaves ----------------------------------------------------------------
    def _check_ran(self) -> None:
        if self._problem:
            raise ValueError(self._problem)
        mbs = self._mbs()
        if mbs is None:
            return
        end = float(mbs.systemData.GetTime())
        last = self._records[-1][0] if self._records else 0.0
        if end > last + 2.0 * self._step + 1e-12 * max(1.0, end):
            raise RuntimeError(f"joint {self.name or '(unnamed)'}: the impulse mode did not run to t = {end:g} s (its "
                               f"last step began at {last:g} s): a pre-step function set after the joint was built "
                               "replaced the mode's; set yours before building the joint, or use "
                               "contact_mode='compliant'")

    def impacts(self) -> list[ClosedFormImpact]:
        """The impacts of the last run, resting contacts' onsets included (restitution 0), with
        the closed-form peak force, duration and largest penetration (:class:`ClosedFormImpact`)."""
        self._check_ran()
        law = self._joint.law
        out = []
        for t, v, restitution, impulse in self._impacts:
            # the solver's own effective mass at the contact (closed loops included): the impact
            # step's impulse over the velocity change; a resting contact's first step also
            # carries the load, so there the bodies' reduced mass (joint_mass) stands in
            mass = abs(impulse) / (v * (1.0 + restitution)) if restitution > 0.0 and math.isfinite(impulse) else \
                joint_mass(self._mbs(), self)
            peak, duration, depth = closed_form_impact(law, mass, v) if mass > 0.0 else (math.nan,) * 3
            out.append(ClosedFormImpact(t, v, peak, duration, depth, restitution, mass))
        return out

    def outputs(self) -> dict[str, np.ndarray]:
        """At the start of each step of the last run: ``time``, ``ecc_x``, ``ecc_y`` (the
        eccentricity, global), ``penetration`` (``|e| - c``, negative in free flight) and
        ``normal_force`` (the resting condition's multiplier over the step before, 0 in
        free flight and at impacts; an impact's impulse is not a force)."""
        self._check_ran()
        data = np.array(self._records, dtype=float).reshape(-1, 5)
        return {key: data[:, k] for k, key in enumerate(("time", "ecc_x", "ecc_y", "penetration", "normal_force"))}

    @property
    def notes(self) -> list[str]:
        """What the last run did that a reader should know: impacts whose law's duration
        was not short against the step (there the compliant contact resolves the pulse and
        the jump replaces it), and the penetration the steps left."""
        notes = []
        long = [i for i in self.impacts() if i.restitution > 0.0 and i.duration > self._step]
        if long:
            notes.append(f"{len(long)} impacts lasted longer than the step ({self._step:.3g} s) by the law's closed "
                         "form: the impulse mode took each as a jump; contact_mode='compliant' resolves their "
                         "force pulses")
        if self._left_pen > 0.0:
            notes.append(f"the steps left a penetration of up to {self._left_pen:.3g} m (Moreau-Jean's, about the "
                         "impact velocity times the step); the law's own is in impacts()")
        return notes


def add_impulse_joint(mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                      axis: np.ndarray) -> ImpulseJointHandle:
    """The impulse mode's items for a planar revolute joint between ``markers`` [bearing,
    journal] whose bearing axis is ``axis`` in the bearing marker's frame: the condition and
    the pre-step function."""
    return ImpulseJointHandle(mbs, joint, name, markers, axis)


def _request_jacobian(mbs: exu.MainSystem) -> None:
    """A new Jacobian for the coming step: a modified Newton iteration on the Jacobian of
    the step before, without the condition's row or with its old normal, does not converge
    (on the paper's slider-crank it failed at the first resting contact)."""
    mbs.sys["dynamicSolver"].conv.jacobianUpdateRequested = True


def _installed(installed: Any) -> Any:
    return installed["function"] if isinstance(installed, dict) else None


def _coordinate_owner(mbs: Any, marker: Any) -> tuple[str, int]:
    """The body (object) or node whose coordinates move the marker."""
    info = mbs.GetMarker(marker)
    for key, kind in (("bodyNumber", "object"), ("objectNumber", "object"), ("nodeNumber", "node")):
        if key in info:
            return kind, int(info[key])
    raise ValueError(f"contact_mode='impulse': marker {int(marker)} ({info.get('markerType')}) is on no body or node")


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
