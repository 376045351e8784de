"""The impulse contact mode of a clearance joint with one contact (:mod:`~exuclear.engine.modes`):
the planar revolute, the spherical and the pin-in-slot joint, each its contact pair
(:mod:`~exuclear.engine.impulse_pairs`: the eccentricity ``e`` of the journal's, ball's or
pin's centre, whose direction is the normal, and the gap ``|e| - c``).

Moreau-Jean time stepping inside Exudyn's generalized-alpha solver, at the user's step:

- **The condition.**  One velocity-level ``ObjectConnectorCoordinateVector`` between the
  coordinates of the joint's two bodies, ``n . (v_journal - v_bearing) = r``, off in free
  flight.  Its rows ``n^T dv/dq_t`` are Exudyn's marker velocities at unit coordinate
  velocities (any body with a rigid marker).  Exudyn holds the step's end velocities on it;
  under generalized-alpha with spectral radius 1 (the trapezoidal rule) the positions move
  by ``h (v0 + v1) / 2``.  Under numerical damping a jump leaks into the following steps
  through the algorithmic accelerations: the mode refuses such a run.
- **An impact** is a free step that ends in the wall (``|e| > c``): Exudyn computes it
  again (its discontinuous iteration) with the condition on, in the normal where the step
  met the wall, holding the end rate ``-e(v_n) v_n`` (``v_n`` the normal rate at the step's
  start, Moreau-Jean's), the restitution of the joint's law at the impact velocity
  (:func:`~exuclear.timescales.impact_restitution`).  The step's end accelerations,
  which carry the impulse, are replaced by its start's, so that the flight after the jump
  starts at ``v+`` whatever the length of its steps.
- **Resting contact.**  Where the rebound would land within :data:`REST_STEPS` steps under
  the normal acceleration at the step's start, the journal stays on the wall: the onset
  step is held by the condition (its end accelerations, which carry the approach's impulse,
  replaced by the free computation's, as at an impact), and the steps after it, where the
  contact is a centre distance and the joint has no friction, by a native Exudyn distance
  constraint whose Jacobian Exudyn forms at the step's end (:mod:`~exuclear.engine.impulse_hold`;
  no rows probed, no step computed again).  Elsewhere the condition is held from step to
  step at an end rate that takes back a share of the penetration, along the normal
  predicted for the step's end, with its rows there; a step held in a normal more than
  :data:`NORMAL_TOLERANCE` off the one it reached is computed again in the normal reached
  (from its third computation on, at the secant's fixed point: :func:`~exuclear.vectors.secant_normal`),
  and one whose normal turns by more than :data:`MAX_TURN` is computed again shorter where
  Exudyn's steps are adaptive.  Either lets go where its reaction pulls or the journal
  left the wall.
- **Friction** of a joint that has it, along the tangent its pair gives: Coulomb's, sliding
  loads and a sticking condition in the steps the condition holds
  (:mod:`~exuclear.engine.impulse_friction`, called where the condition is measured, held,
  released, checked and accepted).
- **Settling.**  The trapezoidal rule keeps an error in a step's start accelerations,
  which every jump and onset leaves, alternating from step to step in all multipliers of
  the model, undamped: each accepted step's end accelerations and velocities lose that
  alternation (:mod:`~exuclear.engine.settling`; not in a system with a flexible body, a
  spring, or a joint of several contacts with friction).
- **What is not computed**: the force pulse.  Each impact's peak force, duration and
  largest penetration follow from the law's closed form at the impact velocity and the
  effective mass the solver's impulse shows
  (:func:`~exuclear.timescales.closed_form_impact`).

The mode decides after each Newton iteration of a step, in the post-Newton function of a
connector of its own without force (the carrier): the system's pre-step, post-step and
post-Newton functions stay the user's, set before or after the joint.
"""
from __future__ import annotations

import math
import weakref
from collections.abc import Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeGenericData,
    ObjectConnectorRigidBodySpringDamper,
    ObjectGround,
    VObjectConnectorRigidBodySpringDamper,
    VObjectGround,
)

from ..timescales import impact_restitution
from ..joint import ClearanceJoint
from ..vectors import angle, norm, secant_normal
from .bodies import joint_mass
from .condition import MarkerState, Plan, VelocityCondition
from .impulse_friction import Frictionless, contact_friction
from .impulse_hold import DistanceHold, distance_of, native_hold_fits
from .impulse_pairs import ContactPair, contact_pair
from .impulse_run import (ALTERNATING_STEPS, LOST_THE_CONTACT, ClosedFormImpact, check_ran, closed_form_impacts,
                          run_settings, stopped)
from .settling import SETTLING_STEPS, held_mean, settling_of
from .state import moved_on, start_of_step

#: A held step aims its end rate at taking back this share of the gap per step.
RATE_GAIN = 0.5
#: A held step whose condition's normal is more than this [rad] off the normal it reached is
#: computed again (Exudyn's discontinuous iteration) in the normal reached: a journal that
#: slides along the wall turns the normal within the step (on the zoo's double pendulum by up
#: to 0.6 rad a step), and a condition in the normal of the step's start lets it into the
#: wall by ``|e| (1 - cos turn)`` a step; at this tolerance, by 5e-7 ``|e|``.
NORMAL_TOLERANCE = 1e-3
#: A held step in which the normal turns by more than this [rad] is computed again shorter,
#: where Exudyn's adaptive step allows (its error along the turning wall grows with the
#: square of the turn, and :data:`NORMAL_TOLERANCE`'s iteration converges slowly beyond it),
#: as is a step that ends more than :data:`LOST_CONTACT` clearances into the wall, or a free
#: one that ends more than :data:`CROSSING` clearances into it ...
MAX_TURN = 0.1
#: ... at this share of the step the turn asks for ...
STEP_SAFETY = 0.8
#: ... and never below this many times Exudyn's minimum step.
MIN_STEP_MARGIN = 10.0
#: A held journal more than this share of the clearance off its wall has left it: the
#: condition lets go (the journal's next contact is an impact).
OPEN_GAP = 0.05
#: A rebound that would land within this many steps is a resting contact: the bounces of a
#: journal on its wall would otherwise shrink geometrically, one impact a step (a Zeno
#: sequence the steps cannot resolve).
REST_STEPS = 2.0
#: A penetration beyond this many clearances stops the run: the positions are then off by
#: the journal's travel across the clearance (steps too long for it), or the condition lost
#: the contact.  The restitution of each jump stays the law's, the path does not.
LOST_CONTACT = 1.0
#: A free step that ends more than this many clearances into the wall flew across the whole
#: clearance (its diameter) within the step: the run stops (the path is lost, the jumps
#: would keep the law's restitution).
CROSSING = 2.0
#: Two step starts closer than this (relative) are one step, computed again by the solver.
REDO_TOLERANCE = 1e-12
#: The post-Newton error that has Exudyn compute a step again: anything above its
#: ``discontinuous.iterationTolerance`` (default 1).
REDO_ERROR = 1e3

#: The states of the condition between steps.
FREE, IMPACT, REST = "free", "impact", "rest"


class ImpulseJointHandle:
    """A clearance joint in the impulse mode; returned by :func:`exuclear.CreateClearanceJoint`,
    :func:`exuclear.CreateSphericalClearanceJoint` and :func:`exuclear.CreatePinSlotClearanceJoint`
    with ``contact_mode="impulse"``.

    Attributes
    ----------
    objectNumber : int
        The velocity-level condition (``ObjectConnectorCoordinateVector``).
    carrierNumber : int
        The connector without force whose post-Newton function runs the mode.
    markerNumbers : list
        [bearing (socket, slot) marker, journal (ball, pin) marker].
    contact_mode : str
        ``"impulse"``.
    constraintNumber : int or None
        The ``ObjectJointGeneric`` of ``constrainAxial=True`` (the revolute joint), else None.
    holdNumber : int or None
        The ``ObjectConnectorDistance`` that holds a resting or sliding contact where the
        contact is a centre distance and the joint has no friction
        (:mod:`~exuclear.engine.impulse_hold`), else None.
    """

    contact_mode = "impulse"
    constraintNumber: int | None = None
    settled_with_friction = True  # a system with this contact's friction is settled (exuclear.engine.settling)

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                 pair: ContactPair) -> None:
        self._mbs = weakref.ref(mbs)
        self._pair = pair
        self.name, self._joint = name, joint
        self.markerNumbers = list(markers)
        self._markers = self._marker_state(mbs)
        self._condition = self._new_condition(mbs, name)
        self.objectNumber = self._condition.objectNumber
        # the contact's Coulomb friction (exuclear.engine.impulse_friction), hooked in where the
        # normal condition is measured, held, released, checked and accepted
        self._friction = contact_friction(mbs, joint, name, self.markerNumbers, pair,
                                          lambda label, k: self._new_condition(mbs, label, tangent=k))
        frictionless = isinstance(self._friction, Frictionless)
        settling_of(mbs).friction_groups |= not (frictionless or self.settled_with_friction)
        # held by a native Exudyn constraint where it fits (exuclear.engine.impulse_hold)
        self._native = DistanceHold(mbs, self.markerNumbers, name, pair.clearance) \
            if native_hold_fits(mbs, self.markerNumbers, pair, frictionless) else None
        self.holdNumber = None if self._native is None else self._native.objectNumber
        # the carrier: a connector without force between two ground markers, whose post-Newton
        # function is the mode's (an item's own function: a user's pre-step or post-Newton
        # function, set before or after the joint, leaves it in place)
        ground = mbs.AddObject(ObjectGround(visualization=VObjectGround(show=False)))
        ends = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)) for _ in range(2)]
        self.carrierNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
            name=f"{name}:carrier" if name else "", markerNumbers=ends,
            nodeNumber=mbs.AddNode(NodeGenericData(initialCoordinates=[0.0], numberOfDataCoordinates=1)),
            postNewtonStepUserFunction=self._post_newton,
            visualization=VObjectConnectorRigidBodySpringDamper(show=False)))
        self._iterations = 2  # Exudyn's discontinuous iterations per step (read at each run's start)
        self._nominal = 1.0  # the run's own step [s] (read at each run's start)
        self._reset()

    @property
    def joint(self) -> ClearanceJoint:
        return self._joint

    def _marker_state(self, mbs: exu.MainSystem) -> MarkerState:
        """The markers' poses and velocity maps, read once per state (the contact's conditions
        share it, and a joint with several contacts shares one among them)."""
        return MarkerState(mbs, self.markerNumbers)

    def _new_condition(self, mbs: exu.MainSystem, name: str, tangent: int | None = None) -> VelocityCondition:
        """The contact's condition, or its friction's sticking condition along its ``tangent``
        (the index of :func:`~exuclear.engine.impulse_friction.tangents`; a joint with several
        contacts gives its own, which knows the others)."""
        return VelocityCondition(mbs, self._markers, name)

    # -- the run ------------------------------------------------------------------------
    def _reset(self) -> None:
        self._state = FREE
        self._impacts: list[tuple[float, float, float, float]] = []  # (t, v-, e, impulse of the step)
        self._records: list[tuple[float, ...]] = []  # t, ecc_x, ecc_y, ecc_z, gap, force
        # (t, end multiplier) of the last held steps: the reaction's mean and what a stop says
        self._held_ends: tuple[tuple[float, float], ...] = ()
        self._step = 0.0
        self._resting = 0
        self._problem = ""
        self._left_pen = 0.0
        self._start: float | None = None  # the start [s] of the step the condition is set for
        self._open_at: float | None = None  # the start [s] of a step computed again free: its contact had no wall
        self._saved: dict[str, Any] | None = None  # the state before the last accepted step
        self._free_accelerations = np.zeros(0)  # the end accelerations of an impact step computed free
        # a held step: (its start's eccentricity e0 and gap, h, the normal it is held in)
        self._held: tuple[np.ndarray, float, float, np.ndarray] | None = None
        self._tried: tuple[np.ndarray, np.ndarray] | None = None  # the last computation's normal and the one it reached
        self._markers.forget()

    def _post_newton(self, mbs: exu.MainSystem, t: float, item: int, data: Any, *frame: Any) -> list:
        """The carrier's ``postNewtonStepUserFunction``: ``[error, recommended step, data]``."""
        self._shorter = -1.0
        error = self._after_newton(mbs, t)
        return [error, self._shorter, *data]

    def _after_newton(self, mbs: exu.MainSystem, t_end: float) -> float:
        """After Exudyn's Newton iteration of the step that ends at ``t_end``: 0 accepts the
        step (and sets the condition for the next one), :data:`REDO_ERROR` has Exudyn compute
        it again from its start with the condition set anew."""
        it = mbs.sys["dynamicSolver"].it
        h = float(it.currentStepSize)
        t = t_end - h
        tol = REDO_TOLERANCE * max(1.0, abs(t_end))
        if self._start is None or t < self._start - tol:
            if self._saved is not None and abs(t - self._saved["_start"]) <= tol:
                # Exudyn computes again a step the mode had accepted (another item asked for it):
                # the state before that step; computed once more where the condition or the
                # friction it had is not the one this computation had
                applied, rubbing = self._condition.plan, self._friction.setting()
                plan, moved = self._restore(mbs)
                if moved or not plan.same(applied) or not self._friction.matches(rubbing):
                    self._condition.set(mbs, plan)
                    return REDO_ERROR
            else:
                active = self._condition.plan.active
                active = (self._native is not None and self._native.release(mbs)) or active
                self._reset()  # a new run
                settling_of(mbs).forget(mbs)
                active = self._friction.reset(mbs) or active
                self._check_solver(mbs)
                self._start = t
                if active:  # the last run's condition or friction acted in this step
                    self._condition.release(mbs)
                    return REDO_ERROR
        elif t > self._start + tol:
            self._stop(t, "Exudyn took a step the mode did not see")
        # (the condition and the native hold are never on together: one of the two is 0)
        force = self._condition.multiplier(mbs) + (self._native.multiplier(mbs) if self._native else 0.0)
        e, gap, axial = self._end_gap(mbs)
        left = self._iterations - int(it.discontinuousIteration) - 1  # computations left
        redo = left > 0
        if self._state == FREE and gap > 0.0 and redo and t != self._open_at and \
                self._contact(mbs, t, h, np.asarray(e, dtype=float), gap):
            return REDO_ERROR
        if self._state == REST and gap == -math.inf and redo:
            # no wall under the held contact at the step's end (a corner past a finite guide's end):
            # the step computed again free (held, the end's force would act a step too long), and no
            # contact starts in it again (a corner at the end within round-off: caught in the wall it left)
            self._release(mbs, FREE)
            self._open_at = t
            return REDO_ERROR
        if self._state == REST and self._held is not None:
            e = np.asarray(e, dtype=float)
            turn = angle(self._held[0], e)
            # the journal slides along the wall faster than the condition's normal can follow
            if turn > MAX_TURN and redo and self._shorten(mbs, h, MAX_TURN / turn):
                return REDO_ERROR
            if redo and self._refine(mbs, e, h):
                return REDO_ERROR
        if self._state != FREE and self._friction.check(mbs, force, left):  # Coulomb's law not met yet
            return REDO_ERROR
        clearance = self._pair.clearance
        if gap > LOST_CONTACT * clearance:
            if redo and self._shorten(mbs, h, LOST_CONTACT * clearance / gap):
                return REDO_ERROR
            self._stop(t_end, f"the {self._pair.body} is {gap:.3g} m into the wall, more than {LOST_CONTACT:g} times the "
                              f"clearance ({clearance:.3g} m)", LOST_THE_CONTACT)
        self._saved = self._snapshot()
        self._left_pen = max(self._left_pen, gap)
        if self._state == IMPACT:  # the impact step's impulse (the trapezoid of 0 and its multiplier): the effective mass
            tk, vk, ek, _ = self._impacts[-1]
            self._impacts[-1] = (tk, vk, ek, 0.5 * force * h)
        # the resting multiplier alternates from step to step about the load under the
        # trapezoidal rule: in the first steps after a jump, while the settling takes the
        # alternation out (exuclear.engine.settling), and undamped in a system the settling
        # leaves as it is: the held steps' mean (settling.held_mean) with this rest's held steps
        # before (up to two), from the first after the onset
        before = self._held_ends[len(self._held_ends) + 1 - min(max(self._resting, 1), 3):]
        reaction = held_mean((*(f for _, f in before), force)) if self._state == REST else force
        self._records.append((t_end, *e, gap, reaction if self._state == REST else 0.0))
        if self._state == REST:  # (the last ALTERNATING_STEPS, at least the mean's three; impulse_run.stopped)
            self._held_ends = (*self._held_ends[1 - ALTERNATING_STEPS:], (t_end, force))
        jump = self._state == IMPACT or (self._state == REST and self._resting == 0)  # an impact or a rest's onset
        self._friction.accept(mbs, t_end, self._state == REST, (self._condition, force, h) if jump else None)
        self._settle(mbs)
        if self._state == IMPACT:
            self._release(mbs, FREE)
        elif self._state == REST:
            if self._resting == 0 and len(self._free_accelerations):
                self._friction.forget()
            self._resting += 1
            # the condition pulls the journal onto the wall, or the journal left the wall (a
            # condition would act at a distance)
            if (self._resting > 2 and reaction < 0.0) or gap < -OPEN_GAP * clearance:
                self._release(mbs, FREE)
            else:
                self._hold_on(mbs, e, gap, h, axial, force, reaction if self._resting > SETTLING_STEPS else None)
        self._start, self._step = t_end, h
        return 0.0

    def _hold_on(self, mbs: exu.MainSystem, e: Sequence[float], gap: float, h: float, axial: float,
                 force: float, reaction: float | None) -> None:
        """The held contact for the coming step, from an accepted held step that ended at
        eccentricity ``e``, gap ``gap`` and axial offset ``axial`` with the multiplier ``force``
        (its three-step mean ``reaction``; None in the onset's settling steps, whose
        multiplier settles from the onset's impulse):
        the native constraint where it takes it (:meth:`~exuclear.engine.impulse_hold.DistanceHold.takes`),
        else the velocity-level condition along the normal predicted for the step's end."""
        native = self._native
        if native is not None and native.takes(mbs, settling_of(mbs).active, axial, force, reaction, h):
            if not native.active:  # from the onset step's velocity-level condition
                native.start(mbs, distance_of(e, axial))
                self._condition.release(mbs)
            self._held = None
            # the gap it holds (a measured one moves the distance by Newton's residual each step)
            native.advance(mbs, e, self._resting_rate(native.distance - self._pair.reach), h)
            return
        e = np.asarray(e, dtype=float)
        if settling_of(mbs).active:
            # the step's end predicted from the settled end state, whose accelerations carry no
            # alternation (exuclear.engine.settling): the normal reached follows to third
            # order in the step, and a step is computed again in it less often
            with moved_on(mbs, h, accelerations=True):
                ahead = self._gap(mbs)[0]
        else:  # (accelerations that alternate from step to step: from the positions)
            ahead = e if self._held is None else 2.0 * e - self._held[0]
        self._aim(mbs, e, gap, ahead / norm(ahead), h)

    def _settle(self, mbs: exu.MainSystem) -> None:
        """The end state of an accepted step, as the next step starts from it
        (:mod:`~exuclear.engine.settling`).  An impact step's end accelerations carry the
        impulse (about ``2 (v+ - v-) / h``), a resting onset step's the approach's: the free
        computation's stand in for them, so that the flight after the jump starts at ``v+``
        whatever its steps, and the settling's history starts there.  Any other step loses
        the trapezoidal rule's alternation (a free one only in the settling's steps after a
        jump or a release)."""
        settling = settling_of(mbs)
        if self._state == IMPACT or (self._state == REST and self._resting == 0 and len(self._free_accelerations)):
            mbs.systemData.SetODE2Coordinates_tt(self._free_accelerations)
            settling.restart(mbs)
        else:
            settling.settle(mbs, held=self._state == REST)

    def _shorten(self, mbs: exu.MainSystem, h: float, share: float) -> bool:
        """Whether Exudyn can compute the step again at ``share`` of its length (times
        :data:`STEP_SAFETY`): where its steps are adaptive and above
        :data:`MIN_STEP_MARGIN` times its minimum step."""
        it = mbs.sys["dynamicSolver"].it
        floor = MIN_STEP_MARGIN * float(it.minStepSize)
        if not it.adaptiveStep or h <= floor:
            return False
        self._shorter = max(h * STEP_SAFETY * share, floor)
        return True

    def _contact(self, mbs: exu.MainSystem, t: float, h: float, end: np.ndarray, end_gap: float) -> bool:
        """Whether a free step that ended ``end_gap`` [m] into the wall is an impact or the
        onset of a resting contact (not a journal that started in the wall and leaves it);
        where it is, the condition is set from the state at the step's start, for Exudyn to
        compute the step again with it."""
        self._free_accelerations = np.array(mbs.systemData.GetODE2Coordinates_tt())
        if end_gap > CROSSING * self._pair.clearance:
            if self._shorten(mbs, h, self._pair.clearance / end_gap):
                return True
            self._stop(t, f"a free step ended {end_gap:.3g} m into the wall, more than the clearance's diameter",
                       f"the steps are longer than the {self._pair.body}'s flight across the clearance; take shorter steps")
        with start_of_step(mbs):
            # the rows at the step's start, in the normal where it met the wall (the start's
            # points elsewhere where the journal crossed the bearing's centre)
            start, rate, gap = self._kinematics(mbs, end / norm(end))
            if gap >= 0.0 and end_gap <= gap:
                return False
            accel = self._closing_acceleration(mbs)
            # Moreau-Jean's impact velocity: the normal rate at the step's start (one that
            # reached the wall only under its load, not approaching at the start, rests)
            restitution = impact_restitution(self._joint.law, rate) if rate > 0.0 else 0.0
            rebound = restitution * rate
            if rate <= 0.0 or gap > OPEN_GAP * self._pair.clearance or \
                    (accel > 0.0 and 2.0 * rebound / accel <= REST_STEPS * h):
                # (a journal in the wall at the step's start is held, which takes its penetration back)
                self._state, self._resting, restitution = REST, 0, 0.0
                self._held = None
                self._aim(mbs, start, gap, end / norm(end), h)
            else:
                self._state = IMPACT
                self._hold(mbs, -rebound)
        self._impacts.append((t, rate, restitution, math.nan))
        return True

    def _aim(self, mbs: exu.MainSystem, e: np.ndarray, gap: float, ahead: np.ndarray, h: float) -> None:
        """The condition of a held step started at eccentricity ``e`` and gap ``gap``, acting
        along ``ahead``, the normal expected at the step's end, that holds the
        end rate of :meth:`_resting_rate` (from the gap alone: an end rate aimed at a gap,
        ``2 (gap1 - gap) / h - v0``, alternates about the motion, undamped under the
        trapezoidal rule, and so would the multipliers)."""
        # the rows at the step's end: the trapezoidal rule's force there, J(q1)^T lambda1, is
        # the one its end accelerations carry into the next step, whose condition holds
        # J(q1) v1; with rows at the middle the force's lever arms lag the velocities it holds
        # and the held contact does work, about its force times the turn of the rows over
        # half a step, each step (a pendulum's energy then drifts at first order in the step)
        with moved_on(mbs, h):
            self._kinematics(mbs, ahead)
        self._held, self._tried = (e, gap, h, ahead), None
        self._hold(mbs, self._resting_rate(gap))

    def _refine(self, mbs: exu.MainSystem, e: np.ndarray, h: float) -> bool:
        """Whether a held step that ended at ``e`` was held in a normal more than
        :data:`NORMAL_TOLERANCE` off the one it reached (the journal slides along the wall);
        where it was, the condition is set again in the normal of ``e``, for Exudyn to
        compute the step again; where it was computed so before, at the secant's normal
        through the two computations: the normal reached moves against the one held (the
        multiplier's tangential share pushes the journal back along the wall), and repeating
        the reached normal leaves that share of the miss per computation (0.81 on the zoo's
        rigid_body_tutorial3 at its step: the iterations ran out with misses of tens of mrad)."""
        if self._held is None:
            return False
        begin, gap, planned, normal = self._held
        if planned == h and angle(normal, e) <= NORMAL_TOLERANCE:
            return False
        reached = e / norm(e)
        aim = secant_normal(*self._tried, normal, reached) if self._tried and planned == h else None
        with start_of_step(mbs, accelerations=False):  # the rows and the normal read positions and velocities
            self._aim(mbs, begin, gap, reached if aim is None else np.asarray(aim), h)
        self._tried = (normal, reached)
        return True

    def _check_solver(self, mbs: exu.MainSystem) -> None:
        """The run's solver the mode needs (:func:`~exuclear.engine.impulse_run.run_settings`)."""
        try:
            self._iterations, self._nominal = run_settings(mbs)
        except ValueError as problem:
            self._problem = (f"joint {self.name or '(unnamed)'}: contact_mode='impulse' refuses this run: {problem}; "
                             "or use contact_mode='compliant'")
            raise ValueError(self._problem) from None

    def _end_gap(self, mbs: exu.MainSystem) -> tuple[Sequence[float], float, float]:
        """The eccentricity, the gap and the axial offset (0: not measured) at a step's end;
        a natively held pair's from the hold's displacement of the markers (on or off, its
        ``p1 - p0``) and the outer one's rotation, on floats: all a free step's decision reads."""
        if self._native is None:
            return (*self._gap(mbs), 0.0)
        ov = exu.OutputVariableType
        rotation = mbs.GetMarkerOutput(self.markerNumbers[0], ov.RotationMatrix).tolist() if self._pair.rotations[0] else None
        e, axial = self._pair.centre_offset(mbs.GetObjectOutput(self._native.objectNumber, ov.Displacement).tolist(), rotation)
        return e, norm(e) - self._pair.reach, axial

    def _gap(self, mbs: exu.MainSystem) -> tuple[np.ndarray, float]:
        """The eccentricity ``e`` (global, the joint type's: :mod:`~exuclear.engine.impulse_pairs`)
        and the gap ``|e| - c`` at the current state (``-inf`` where no wall lies under the
        contact: a corner beyond a finite guide's end, which cannot hold and starts no contact)."""
        ecc = self._pair.eccentricity(self._markers.poses(mbs, self._pair.rotations))
        return ecc.e, norm(ecc.e) - self._pair.reach if ecc.wall else -math.inf  # no wall: open

    def _kinematics(self, mbs: exu.MainSystem, normal: np.ndarray) -> tuple[np.ndarray, float, float]:
        """The eccentricity, the rate along ``normal`` and the gap at the current state; sets
        the rows in ``normal``, at the outer body's point where ``e`` starts (and the
        friction's tangential rows, at the same state)."""
        ecc = self._pair.eccentricity(self._markers.poses(mbs, self._pair.rotations))
        e, arm, inner = ecc.e, ecc.arm, ecc.inner_arm
        self._friction.measure(mbs, normal, ecc)
        return e, self._condition.measure(mbs, normal, arms=(arm, inner)), norm(e) - self._pair.reach

    def _closing_acceleration(self, mbs: exu.MainSystem) -> float:
        """The normal acceleration towards the wall at the current state, ``n^T dv/dq_t q_tt``
        (the rows' part; the centripetal part ``d(n^T dv/dq_t)/dt q_t`` is left out: it
        only sets whether a rebound counts as resting)."""
        return self._condition.rate(np.asarray(mbs.systemData.GetODE2Coordinates_tt(), dtype=float))

    def _resting_rate(self, gap: float) -> float:
        """The end rate [m/s] a held step aims at (:meth:`_aim`): ``-RATE_GAIN gap / h`` at the
        run's own step ``h`` (not a step Exudyn shortened, whose rate would pull the journal
        back at any speed)."""
        return -RATE_GAIN * gap / self._nominal

    def _hold(self, mbs: exu.MainSystem, end_rate: float) -> None:
        """The condition on for the coming step, in the rows of :meth:`_kinematics`' last
        call, holding its end rate at ``end_rate``."""
        self._condition.hold(mbs, end_rate)
        self._friction.hold(mbs)

    def _release(self, mbs: exu.MainSystem, state: str) -> None:
        if self._state == REST:
            settling_of(mbs).reopen()
        self._condition.release(mbs)
        if self._native is not None:
            self._native.release(mbs, hand_over=False)
        self._friction.release(mbs)
        self._state = state

    def _snapshot(self) -> dict[str, Any]:
        """What an accepted step changes, to be taken back where Exudyn computes it again."""
        # the records and impacts only grow, but for the last impact's impulse, set as its step is accepted
        return {"_state": self._state, "plan": self._condition.plan, "_step": self._step,
                "_resting": self._resting, "_left_pen": self._left_pen,
                "_start": self._start, "records": len(self._records), "impacts": len(self._impacts),
                "last_impact": self._impacts[-1] if self._impacts else None, "_held_ends": self._held_ends,
                "friction": self._friction.snapshot(), "native": self._native and self._native.setting()}

    def _restore(self, mbs: exu.MainSystem) -> tuple[Plan, bool]:
        """The state before the last accepted step back; returns the condition's setting then,
        and whether the native hold's differed (and was set back)."""
        saved, self._saved = dict(self._saved or {}), None
        held = saved.pop("native")
        moved = self._native is not None and self._native.restore(mbs, held)
        del self._records[saved.pop("records"):]
        del self._impacts[saved.pop("impacts"):]
        last = saved.pop("last_impact")
        if last is not None:
            self._impacts[-1] = last
        plan, self._tried = saved.pop("plan"), None
        self._friction.restore(self._mbs(), saved.pop("friction"))
        self.__dict__.update(saved)
        return plan, moved

    def _stop(self, t: float, reason: str, steps: str = "") -> None:
        ends = () if settling_of(self._mbs()).active else self._held_ends  # settled, the multipliers do not alternate
        self._problem = stopped(self.name, t, reason, steps, ends, self._nominal)
        raise ValueError(self._problem)

    # -- what a run leaves ----------------------------------------------------------------
    def _check_ran(self) -> None:
        if self._problem:
            raise ValueError(self._problem)
        check_ran(self._mbs(), self.name, self._records[-1][0] if self._records else None, self._held_contacts)

    def _held_contacts(self) -> str:
        """What the joint held in its last Newton solve, for the error of a run whose Newton
        iteration failed there ('': nothing beyond the joint's name; a joint of several
        contacts names them)."""
        return ""

    def impacts(self) -> list[ClosedFormImpact]:
        """The impacts of the last run, resting contacts' onsets included (restitution 0), with
        the closed-form peak force, duration and largest penetration (:class:`ClosedFormImpact`)."""
        self._check_ran()
        mbs = self._mbs()
        # where the impact step's impulse does not give the effective mass, the bodies' reduced mass
        return closed_form_impacts(self._joint.law, self._impacts,
                                   lambda: joint_mass(mbs, self) if mbs is not None else math.nan)

    def outputs(self) -> dict[str, np.ndarray]:
        """At the end of each step of the last run: ``time``, ``ecc_x``, ``ecc_y``, ``ecc_z``
        (the eccentricity, global: the journal's or ball's centre relative to the bearing's
        or socket's, the pin's relative to the slot's nearest centre-segment point),
        ``penetration`` (``|e| - c``, negative in free flight) and ``normal_force`` (the
        resting condition's multiplier, as a mean over its last three steps weighted 1/4,
        1/2, 1/4, two on the first held steps; 0 in free flight and at impacts: an impact's
        impulse is not a force)."""
        self._check_ran()
        keys = ("time", "ecc_x", "ecc_y", "ecc_z", "penetration", "normal_force")
        data = np.array(self._records, dtype=float).reshape(-1, len(keys))
        out = {key: data[:, k] for k, key in enumerate(keys)}
        return out | self._friction.outputs()  # with friction: slip_velocity, friction_force, sticking

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
        return notes + self._friction.notes


def add_impulse_joint(mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                      frame: np.ndarray) -> ImpulseJointHandle:
    """The impulse mode's items for a joint between ``markers`` [bearing, journal] (socket and
    ball, slot and pin) whose joint frame is ``frame`` in the bearing marker's frame: the
    condition and the carrier, for the joint type's contact pair
    (:func:`~exuclear.engine.impulse_pairs.contact_pair`)."""
    return ImpulseJointHandle(mbs, joint, name, markers, contact_pair(joint.geometry, frame))
