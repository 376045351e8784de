"""Coulomb friction of the impulse contact mode's held and hit contacts
(:mod:`~exuclear.engine.impulse`), for every contact pair (:mod:`~exuclear.engine.impulse_pairs`):
along one tangent where the contact slides in a plane (the planar revolute joint's journal,
the pin in its slot, a planar slider's corners, the spatial revolute joint's slices), in the
tangent plane for a ball in its socket and a box's corner on its wall.

Wherever the mode holds the normal condition for a step (an impact or a resting contact),
the contact's friction acts in the same step, at the slip of the contact points
(:func:`~exuclear.engine.impulse_pairs.contact_arms`), ``v_T = t . (v_1(P_1) - v_0(P_0))``
with ``t = n x a`` (``a`` the pair's ``plane``), or the slip vector ``v_T`` in the plane normal
to ``n`` (two tangents; a ball's docs/physics.md eqs. (96)-(97), a box's corner's slip over its
wall): for a journal docs/physics.md eq. (8),
``v_T = t . (v_J - v_B) - R_J w_J + R_B w_B``; for a pin the same in the slot's frame at the
slot's wall point (docs/physics.md section 14); for a corner its velocity along the guide's
axis over the wall's point under it (a point: no spin term); for a slice the journal's
slip at the slice in its tangent plane, around and along the axis (eq. (42)), only around
it where ``constrainAxial`` holds the axis; for an end face the journal's spin at the annulus's friction radius
(:class:`SpinFriction`).

- **Sliding**: a force ``F_T = mu(|v_T|) F_N`` along the slip's direction ``d`` at the step's
  start (``sign(v_T) t`` along one tangent) at the contact points, eqs. (24)-(26):
  Exudyn loads at the joint's two markers, ``-F_T d`` with the moment ``r_1 x (-F_T d)`` on
  the inner body and ``F_T d`` with ``r_0 x F_T d`` on the outer one (``r`` the arms to the
  contact points; a journal's moments ``R_J F_T a`` and ``-R_B F_T a``), fixed over the step,
  in the tangent plane of the rows the step's normal condition has.  ``F_N`` is that condition's end
  multiplier in the same step (:meth:`ContactFriction.check` says why the end's), which the
  loads change in a closed loop: after Exudyn's Newton iteration the mode compares the load
  with ``mu`` times the multiplier it produced and, more than :data:`LOAD_TOLERANCE` apart,
  has Exudyn compute the step again with the load set anew (inside Exudyn's discontinuous
  iteration: along the slope of load against its target that the step before measured, then
  along the secant through the step's last two computations; the plain iteration, load =
  target, converges slowly where the load moves the multiplier about as much as itself).
  In a settled system (:mod:`~exuclear.engine.settling`: every system of rigid bodies whose
  joints with friction have one contact each) Exudyn's Newton iteration runs to at most
  :data:`NEWTON_RELATIVE_TOLERANCE` in the steps that hold a contact with friction, which
  the loop needs of the multiplier (:func:`steer_newton`).
- **Sticking**: where the step's end slip points against the slip the load opposed (the slip
  would reverse within the step), or the contact stuck in the step before, velocity-level
  conditions hold the end slip at 0, one per tangent (their rows those of the contact points,
  which give eq. (8)'s spin terms); their multipliers are the friction force, kept while the
  step's friction impulse is within ``mu_s`` times its normal one (the cone
  ``|F_T| <= mu_s F_N``), else the contact slides the way the multipliers point (Coulomb's
  friction cone).
- **Impacts**: the same two cases at the impact step, whose impulses are the step's end
  forces times ``h / 2`` (the trapezoidal rule from the free flight's zero): the tangential
  impulse is ``mu`` times the normal one while the contact slides through the impact, or what
  stops the slip where that is within ``mu`` times the normal one.  This is Newton's
  restitution with Coulomb's bound on the tangential impulse, the algebraic impact law of
  R. M. Brach, "Rigid body collisions", J. Appl. Mech. 56 (1989) 133-138, and the impulse law
  of Moreau-Jean time stepping (Acary and Brogliato, *Numerical Methods for Nonsmooth
  Dynamical Systems*, 2008, section 10.1).  Where the contact point's normal and tangential
  inverse masses are coupled (its arm to the centre of mass off the normal), stopping the
  slip can need a tangential impulse along it, which does positive work: with a restitution
  near 1 the impact adds energy (T. R. Kane and D. A. Levinson, *Dynamics: Theory and
  Applications*, 1985; Kane's paradox).  The work of the contact's impulses over each impact
  step is computed and a gain told in the notes (:meth:`ContactFriction.accept`).

The friction coefficient is the joint's law's: ``mu(v_T)`` at the step's end slip while
sliding (at least at the law's smoothing speed, below which the law's regularisation would
take it to zero), and the law's value at its smoothing speed as the sticking bound
(``mu`` of :class:`~exuclear.friction.Coulomb`, ``mu_s`` of the paper's law).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import LoadForceVector, LoadTorqueVector

from ..friction import FrictionLaw
from ..joint import ClearanceJoint
from .condition import VelocityCondition
from .impulse_pairs import ContactPair, Eccentricity, FacePair, contact_arms
from .impulse_run import gains_note
from .settling import held_mean, settling_of
from .steering import explicit_solver

#: A sliding load more than this share of ``mu F_N`` off the step's own ``mu F_N`` has Exudyn
#: compute the step again with the load set anew.  A steady slide's first load comes from the
#: steps before and is kept where it is this close: friction coefficients are known to a few
#: percent at best, and a tighter tolerance has Exudyn compute most sliding steps twice.
#: A journal whose normal force does not depend on the friction (a single body on its wall)
#: agrees after one computation.
LOAD_TOLERANCE = 1e-3
#: A sticking multiplier beyond ``mu_s F_N`` by more than this share of it slides: the
#: multiplier of a contact on its friction cone's edge carries Newton's round-off.
CONE_TOLERANCE = 1e-9
#: A tangent carried over from the last measure into a new tangent plane keeps its direction
#: where its part in the plane is at least this long (the normal turned by less than 60
#: degrees): the tangents then turn with the normal, and the slip's and the forces'
#: components along them keep their meaning from step to step.
CARRY = 0.5
#: The largest ``newton.relativeTolerance`` of a settled system's steps in which a contact
#: with friction is held (the solver's copy of the settings; the user's are not changed, and
#: are the other steps').  The sliding loads are ``mu`` times the normal condition's end
#: multiplier, which Exudyn's Newton iteration leaves off by its residual; at Exudyn's default
#: (1e-8) that error changed a mechanism's normal multiplier by some percent between
#: computations of one step at the same load, the loads did not converge within the
#: discontinuous iterations, and their error grew from step to step into an alternation that
#: let the contact go (the zoo's 3D double pendulum with friction, at 1e-9 still at four
#: times its steps; docs/design/settling.md).  An impact step keeps the user's: at 1e-10,
#: Newton did not converge in a ball's impact step of 1e-8 s.
NEWTON_RELATIVE_TOLERANCE = 1e-10
#: ``mbs.variables`` key of the contacts with friction held in the coming step (their ids).
HELD_KEY = "exuclear.friction_held"
#: Changes between sliding and sticking within one step after which the contact keeps the
#: last: each change is a computation of the step, and one slide, one stick and one slide
#: in the sticking multiplier's direction is Coulomb's law's whole decision.
MAX_SWITCHES = 3

OFF, SLIDE, STICK = "off", "slide", "stick"


class ContactFriction:
    """The friction of one impulse-mode contact: the sticking conditions (one per tangent) and
    the sliding loads (module docstring).  The mode calls :meth:`measure` where it sets its
    normal rows, :meth:`hold` and :meth:`release` with its normal condition, :meth:`check`
    after each Newton iteration of a held step and :meth:`accept` at each accepted step.
    Slips, directions and forces are held as components along the tangents of the last
    :meth:`measure` (forces on the outer body: the bearing, socket, slot, guide), so that a
    step measured again in a turned normal keeps them along its new tangents."""

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, markers: Sequence[Any], pair: ContactPair,
                 conditions: Sequence[VelocityCondition]) -> None:
        self._law: FrictionLaw = joint.friction
        self._pair = pair
        self._markers = list(markers)
        self.conditions = list(conditions)  # the sticking conditions, one per tangent, between the same markers
        self._forces = [mbs.AddLoad(LoadForceVector(markerNumber=m, loadVector=[0.0, 0.0, 0.0]))
                        for m in self._markers]
        self._torques = [mbs.AddLoad(LoadTorqueVector(markerNumber=m, loadVector=[0.0, 0.0, 0.0]))
                         for m in self._markers]
        self._tangents = np.zeros((len(self.conditions), 3))  # the rows' tangents (global, unit)
        self._arms = (np.zeros(3), np.zeros(3))  # marker 0's and marker 1's to the contact points (global)
        self._stick_mu = abs(self._law.coefficient(self._law.smoothing_speed))
        self.tell_gains = True  # the notes tell this contact's energy gains (a joint of several: its own, together)
        self._reset()

    def _reset(self) -> None:
        k = len(self.conditions)
        self._state, self._force = OFF, 0.0  # the sliding load [N] along _direction
        self._direction = np.zeros(k)  # the slip's direction (unit) the sliding load opposes
        self._fresh = True  # the next hold starts a new step (its state decided from the slip)
        self._slip = np.zeros(k)  # the slip at the state of the last measure (the step's start velocities)
        # the normal and the friction force at the step's start that Coulomb's law adds to the
        # end's (an unsettled system's last accepted step's end forces, which its accelerations
        # carry into the step; 0 after flight, an impact, or the onset of a rest, whose end
        # accelerations the mode replaces by the free computation's, and in a settled system,
        # whose law holds per end force: ContactFriction.check)
        self._normal0, self._friction0 = 0.0, np.zeros(k)
        self._normal_sum = 0.0  # start plus end normal force of the last computed step
        self._sums: tuple[float, ...] = ()  # those of the last three accepted held steps
        self._ends: tuple[np.ndarray, ...] = ()  # the end forces of the held steps since the onset (its own first)
        self._slope = 0.0  # d(target load) / d(load) of the last step the secant measured
        self._switches = 0
        self._secant: tuple[float, float] | None = None  # the last (load, its miss) of this step
        self._off_by = 0.0  # the largest mismatch of an accepted sliding load, in shares of mu F_N
        self._reversed = 0  # accepted sliding steps whose slip reversed, with no computation left to stick
        self._records: list[tuple[float, float, float, float]] = []  # t, slip, friction force, sticking
        self.jumps: list[tuple[float, float, float]] = []  # of impact steps: t, work [J], its terms' sizes

    # -- the mode's hooks ---------------------------------------------------------------
    @property
    def acting(self) -> bool:
        """Whether the friction acts in the coming step."""
        return self._state != OFF

    def reset(self, mbs: exu.MainSystem) -> bool:
        """A new run: off; returns whether the last run's friction acted in this step."""
        acted = self._state != OFF
        self._reset()
        self._apply(mbs, OFF)
        steer_newton(mbs, self, held=False)
        return acted

    def measure(self, mbs: exu.MainSystem, normal: np.ndarray, ecc: Eccentricity) -> None:
        """The sticking conditions' rows at the current state, along the tangents of the
        mode's ``normal`` (``t = n x a``, or two normal to ``n``) at the pair's contact points
        for its eccentricity ``ecc`` there, and the slip at the current velocities."""
        self._tangents = tangents(mbs, self._pair, self._markers, normal, self._tangents[0])
        # the rows of the contact points: for a journal t . (w x R n) = -R w . a, eq. (8)
        self._arms = contact_arms(self._pair, normal, ecc)
        self._slip = np.array([c.measure(mbs, t, arms=self._arms) for c, t in zip(self.conditions, self._tangents)])

    def hold(self, mbs: exu.MainSystem) -> None:
        """The friction of the coming step, in the rows of the last :meth:`measure`: at a new
        step, sticking where it stuck before or the slip is within the law's smoothing speed,
        else sliding against the slip at ``mu`` times the end normal force the held steps
        before foretell (0 at a contact's first step); where the mode computes the same step
        again, the setting it had, in the new rows."""
        state = self._state
        if self._fresh or state == OFF:
            self._fresh, self._switches, self._secant = False, 0, None
            speed = float(np.linalg.norm(self._slip))
            state = STICK if state == STICK or speed <= self._law.smoothing_speed else SLIDE
            if state == SLIDE:
                self._direction = self._slip / speed
                # the normal force sum of the coming step, extrapolated from the held steps
                # before: the sums zigzag from step to step as the end multipliers alternate,
                # so from the step two back along the trend of the steps of the other parity
                s = self._sums
                guess = s[1] + s[2] - s[0] if len(s) == 3 else self._normal_sum
                self._force = self._sliding_force(self._sliding_mu(speed), guess - self._normal0)
        self._apply(mbs, state)

    def release(self, mbs: exu.MainSystem) -> None:
        """No friction in the coming step (the normal condition lets go)."""
        self._apply(mbs, OFF)
        self._fresh = True
        self.forget()
        self._normal_sum, self._sums, self._slope = 0.0, (), 0.0  # the next contact's first guess: no friction
        self._ends = ()
        steer_newton(mbs, self, held=False)

    def forget(self) -> None:
        """The last step's end forces are not in the accelerations the next step starts from
        (the mode replaced them by the free computation's)."""
        self._normal0, self._friction0 = 0.0, np.zeros(len(self.conditions))

    def check(self, mbs: exu.MainSystem, normal_force: float, left: int) -> bool:
        """After Exudyn's Newton iteration of a step the normal condition held at the end
        multiplier ``normal_force``: whether Exudyn must compute it again (it can ``left``
        more times) with the friction set anew, Coulomb's law not met by the step's impulses.
        A change between sliding and sticking may take the last computation, a sliding
        load's refinement not: a slip that reverses under a refined load must still stick.

        Under the trapezoidal rule a step's impulses are ``h / 2`` times its start and end
        forces.  In a system the settling leaves as it is, a held condition's end multipliers
        alternate about the load from step to step (:mod:`~exuclear.engine.impulse`), through
        0 and below: the friction cone holds for the sums of start and end forces, not for each
        end force.  In a settled one (:mod:`~exuclear.engine.settling`) an end multiplier is
        the contact's force, and the accelerations the next step starts from carry the end
        forces filtered alike (the filters are linear): the cone holds per end force (the start
        forces are 0 here, :meth:`forget`).  Either way a sliding load is ``mu`` times the end
        normal force, so that over steps that slide alike the step's friction impulse is
        ``mu`` times its normal one (a load set to make up the step before's miss,
        ``mu (N_0 + N_1) - F_0``, keeps that miss alternating, and the two alternations can
        grow into each other)."""
        self._normal_sum = self._normal0 + normal_force
        bound = max(self._normal_sum, 0.0)
        if self._state == STICK:
            stick = self._friction0 + self._sticking_force(mbs)  # the step's start plus end force
            size = float(np.linalg.norm(stick))
            if size <= self._stick_mu * bound * (1.0 + CONE_TOLERANCE) or not self._switch(left):
                return False
            # the contact slides the way the friction impulse it needed points (F_T opposes v_T)
            self._direction = stick / size
            self._force = self._sliding_force(self._sliding_mu(0.0), normal_force)
            self._apply(mbs, SLIDE)
            return True
        if self._state != SLIDE:
            return False
        end_slip = self._rates(np.asarray(mbs.systemData.GetODE2Coordinates_t(), dtype=float))
        if end_slip @ self._direction < 0.0:  # the slip reversed within the step
            if self._switch(left):
                self._apply(mbs, STICK)
                return True
            self._reversed += 1  # accepted: the load pushed the slip across 0 within this step
            return False
        speed = float(np.linalg.norm(end_slip))
        target = self._sliding_force(self._sliding_mu(speed), normal_force)
        # the size of the step's friction forces (its end normal force may alternate through 0)
        scale = max(self._sliding_mu(speed) * max(abs(normal_force), 0.5 * bound), abs(self._force))
        off = abs(target - self._force)
        if off <= LOAD_TOLERANCE * scale:
            return False
        if left < 2:
            self._off_by = max(self._off_by, off / scale)
            return False
        # the load whose miss is 0: on the secant through the last two computations, or, at
        # the step's first, along the slope the step before measured (in a closed loop the
        # load moves the normal multiplier, and with it its own target)
        miss = target - self._force
        slope = self._slope
        if self._secant is not None and self._force != self._secant[0]:
            slope = 1.0 + (miss - self._secant[1]) / (self._force - self._secant[0])
            self._slope = slope
        load = self._force + miss / (1.0 - slope) if slope < 1.0 else target
        if not 0.0 <= load / (self._stick_mu * normal_force or math.inf) <= 1.0:
            load = target  # beyond what Coulomb's law can ask (a slip-dependent mu bends the secant)
        self._secant = (self._force, miss)
        self._force = load
        self._apply(mbs, SLIDE)
        return True

    def accept(self, mbs: exu.MainSystem, t_end: float, held: bool,
               jump: tuple[VelocityCondition, float, float] | None = None) -> None:
        """An accepted step that ended at ``t_end``: its record (``held``: a resting step; an
        impact's friction is an impulse, recorded as 0 as its normal force is), its end
        forces as the next step's start, and the next hold starts a new step.  ``jump``: an
        impact step or a held contact's onset, (its normal condition, that condition's end
        multiplier, the step [s]), whose impulses' work is checked (:meth:`_jump_work`)."""
        self._fresh = True
        if jump is not None and self._state != OFF:
            self.jumps.append((t_end, *self._jump_work(mbs, *jump)))
        if self._state == OFF:
            self._records.append((t_end, 0.0, 0.0, 0.0))
            return
        slip = self._rates(np.asarray(mbs.systemData.GetODE2Coordinates_t(), dtype=float))
        force = self._sticking_force(mbs) if self._state == STICK else self._force * self._direction
        self._ends = (*self._ends[-3:], force) if held else ()
        if settling_of(mbs).active:
            # the end forces are the contact's own (the settling takes the alternation out of
            # the accelerations the next step starts from): the next step's law holds for its
            # end forces alone, and the record is the held steps' mean the normal force's is
            recorded = held_mean(self._ends[1:]) if len(self._ends) > 1 else force
            self.forget()
            steer_newton(mbs, self, held)
        else:
            # the step's friction impulse over h: the mean of its start and end forces
            recorded = 0.5 * (self._friction0 + force)
            self._normal0, self._friction0 = self._normal_sum - self._normal0, force
        self._records.append((t_end, self._component(slip), self._component(recorded) if held else 0.0,
                              float(self._state == STICK)))
        self._sums = (self._sums + (self._normal_sum,))[-3:] if held else ()

    def snapshot(self) -> dict[str, Any]:
        """The setting the step was computed with, to be taken back where Exudyn computes it
        again (:meth:`restore`)."""
        return {"_state": self._state, "_force": self._force, "_direction": self._direction,
                "_tangents": self._tangents, "_arms": self._arms, "rows": [c.rows for c in self.conditions],
                "_normal0": self._normal0, "_friction0": self._friction0, "_ends": self._ends,
                "records": len(self._records), "jumps": len(self.jumps)}

    def restore(self, mbs: exu.MainSystem | None, saved: dict[str, Any]) -> None:
        """The setting of :meth:`snapshot` back, applied for Exudyn's computation of the step."""
        saved = dict(saved)
        del self._records[saved.pop("records"):]
        del self.jumps[saved.pop("jumps"):]
        for condition, rows in zip(self.conditions, saved.pop("rows")):
            condition.rows = rows
        state = saved.pop("_state")
        self.__dict__.update(saved)
        self._fresh, self._switches, self._secant = False, 0, None
        if mbs is not None:
            self._apply(mbs, state)

    def setting(self) -> tuple:
        """How the friction's items are set now (:meth:`matches`)."""
        return self._state, self._load(self._state), self._arms, [c.plan for c in self.conditions]

    def matches(self, setting: tuple) -> bool:
        """Whether the items are set as ``setting`` (of :meth:`setting`) says: the same
        sticking conditions, or the same sliding loads, or none."""
        state, load, arms, plans = setting
        if state != self._state or not all(p.same(c.plan) for p, c in zip(plans, self.conditions)):
            return False
        return state != SLIDE or (np.array_equal(load, self._load(state))
                                  and all(np.array_equal(a, b) for a, b in zip(arms, self._arms)))

    def outputs(self) -> dict[str, np.ndarray]:
        """At the end of each step: ``slip_velocity`` (eq. (8), the held or hit contact's; 0
        in flight), ``friction_force`` (``F_T`` of eqs. (24)-(26): the sliding load or the
        sticking multiplier; 0 in flight and at impacts) and ``sticking`` (1 where the contact
        stuck).  Along one tangent both are signed along ``t = n x a``; in a tangent plane
        they are the slip's speed ``|v_T|`` and the friction's size ``|F_T|``.  The friction
        force is the step's friction impulse over the step (the mean of its start and end
        forces), in a settled system the mean of the held steps' end forces the mode's
        normal force is (:func:`~exuclear.engine.settling.held_mean`)."""
        data = np.array(self._records, dtype=float).reshape(-1, 4)
        return {"slip_velocity": data[:, 1], "friction_force": data[:, 2], "sticking": data[:, 3]}

    @property
    def notes(self) -> list[str]:
        """Where Exudyn's discontinuous iterations ran out before Coulomb's law was met (a
        sliding load off ``mu F_N``, or a slip that reversed under its load), and impacts
        whose impulses added energy (Kane and Levinson's paradox)."""
        notes = []
        if self._off_by > 0.0:
            notes.append(f"the sliding friction of some steps was up to {self._off_by:.3g} of mu F_N off Coulomb's")
        if self._reversed:
            notes.append(f"the slip of {self._reversed} steps reversed under the sliding friction, where the contact "
                         "would have stuck")
        if notes:
            notes[-1] += ("; Exudyn's discontinuous iterations ran out first: raise "
                          "timeIntegration.discontinuous.maxIterations")
        return notes + (gains_note(self.jumps) if self.tell_gains else [])

    # -- inside -------------------------------------------------------------------------
    def _jump_work(self, mbs: exu.MainSystem, normal: VelocityCondition, normal_force: float,
                   h: float) -> tuple[float, float]:
        """The work [J] of the contact's impulses over an impact step of length ``h``, and the
        sum of its terms' sizes: for each row (the ``normal`` condition's, the tangents')
        ``P (v_0 + v_1) / 2``, exact for an impulsive jump (``dT = dv^T M (v_0 + v_1) / 2`` with
        ``M dv = J^T P``), the rates ``v`` at the step's start and end.  ``P`` is the impulse on
        the inner body's rates, ``-(h/2)`` times the end force on the outer body (the
        trapezoidal rule from the start's free flight): the normal multiplier
        ``normal_force``, the sticking multipliers or the sliding load."""
        data = mbs.systemData
        rates = [np.asarray(data.GetODE2Coordinates_t(configuration=c), dtype=float)
                 for c in (exu.ConfigurationType.StartOfStep, exu.ConfigurationType.Current)]
        force = self._sticking_force(mbs) if self._state == STICK else self._force * self._direction
        impulses = -0.5 * h * np.concatenate(([normal_force], force))
        start, end = (np.concatenate(([normal.rate(x)], self._rates(x))) for x in rates)
        return 0.5 * float(impulses @ (start + end)), 0.5 * float(np.abs(impulses) @ (np.abs(start) + np.abs(end)))

    def _rates(self, x: np.ndarray) -> np.ndarray:
        """The slip for the system's coordinate rates ``x``, through the rows (components)."""
        return np.array([c.rate(x) for c in self.conditions])

    def _sticking_force(self, mbs: exu.MainSystem) -> np.ndarray:
        """The sticking conditions' end force on the outer body (components)."""
        return np.array([c.multiplier(mbs) for c in self.conditions])

    def _load(self, state: str) -> np.ndarray:
        """The sliding load on the outer body (global) in ``state``."""
        return self._tangents.T @ (self._force * self._direction) if state == SLIDE else np.zeros(3)

    def _component(self, vector: np.ndarray) -> float:
        """What the outputs record of a tangential vector (components): along one tangent
        its component (signed), in a tangent plane its length."""
        return float(vector[0]) if len(vector) == 1 else float(np.linalg.norm(vector))

    def _sliding_mu(self, speed: float) -> float:
        """``|mu(v_T)|`` of the law, at no less than its smoothing speed."""
        return abs(self._law.coefficient(max(abs(speed), self._law.smoothing_speed)))

    def _sliding_force(self, mu: float, normal_end: float) -> float:
        """The end load along the slip's direction, ``mu N_1``; where the step's normal forces
        sum to a pull (the mode lets go after it), the one whose step impulse is 0."""
        if self._normal0 + normal_end <= 0.0:
            return -float(self._friction0 @ self._direction)
        return mu * normal_end

    def _switch(self, left: int) -> bool:
        """Whether the contact may change between sliding and sticking in this computation."""
        if left < 1 or self._switches >= MAX_SWITCHES:
            return False
        self._switches += 1
        self._secant = None
        return True

    def _apply(self, mbs: exu.MainSystem, state: str) -> None:
        """The items as ``state`` says: the sticking conditions on or off, the sliding loads
        (``F_T`` along the slip's direction) or none."""
        for condition in self.conditions:
            if state == STICK and not (self._state == STICK and condition.plan.active
                                       and condition.plan.rows is condition.rows):
                condition.hold(mbs, 0.0)
            elif state != STICK and condition.plan.active:
                condition.release(mbs)
        for items, loads in zip(zip(self._forces, self._torques), self._loads(self._load(state))):
            for item, vector in zip(items, loads):
                mbs.SetLoadParameter(item, "loadVector", [float(x) for x in vector])
        self._state = state

    def _loads(self, force: np.ndarray) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """The force and the moment at the outer and at the inner marker of the friction
        ``force`` on the outer body: ``F_T d`` on the outer body, ``-F_T d`` on the inner one,
        each at its contact point."""
        return tuple((vector, np.cross(arm, vector)) for arm, vector in zip(self._arms, (force, -force)))


class SpinFriction(ContactFriction):
    """The friction of an end face (:class:`~exuclear.engine.impulse_pairs.FacePair`): as the
    compliant face's (docs/physics.md eqs. (51), (54)), against the relative spin about the
    journal's axis ``u`` at the annulus's friction radius ``R_e``, ``v_T = R_e u . (w_1 - w_0)``,
    a couple ``R_e F_T u`` on the bearing and its negative on the journal; the shoulder's
    sliding across the face is not resisted (section 9.6, approximation (ii)).  One
    tangent, ``u`` (the couple's axis), whose sticking condition holds the relative spin;
    sliding, sticking and impacts as :class:`ContactFriction` decides them."""

    def measure(self, mbs: exu.MainSystem, normal: np.ndarray, ecc: Eccentricity) -> None:
        """The sticking condition's rows ``R_e u^T dw/dq_t`` at the current state, and the slip."""
        u = self._pair.spin_axis(ecc)
        self._tangents = u[None, :]
        self._slip = np.array([spin_rate(mbs, c, self._pair.friction_radius * u) for c in self.conditions])

    def _loads(self, force: np.ndarray) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """No force; the couple ``R_e F_T u`` on the bearing, its negative on the journal."""
        couple = self._pair.friction_radius * force
        return (np.zeros(3), couple), (np.zeros(3), -couple)


def steer_newton(mbs: exu.MainSystem, contact: ContactFriction, held: bool) -> None:
    """Exudyn's Newton tolerance for the coming step of a settled run (its solver's copy):
    at most :data:`NEWTON_RELATIVE_TOLERANCE` while ``contact`` or another contact with
    friction of ``mbs`` is ``held``, else the user's."""
    solver = getattr(mbs, "sys", {}).get("dynamicSolver")
    if solver is None or explicit_solver(solver) or not settling_of(mbs).active:
        return
    contacts = mbs.variables.setdefault(HELD_KEY, set())
    (contacts.add if held else contacts.discard)(id(contact))
    user = float(mbs.sys["simulationSettings"].timeIntegration.newton.relativeTolerance)
    solver.newton.relativeTolerance = min(user, NEWTON_RELATIVE_TOLERANCE) if contacts else user


def spin_rate(mbs: exu.MainSystem, condition: VelocityCondition, vector: np.ndarray) -> float:
    """Sets ``condition``'s rows to ``vector . (w_1 - w_0)``, the markers' angular velocities
    along ``vector`` (global) at the current state, and returns that rate."""
    maps = condition.state.maps(mbs, (True, True))
    condition.rows = tuple((spin @ vector).reshape(1, -1) for _, spin in maps)
    return condition.rate(mbs.systemData.GetODE2Coordinates_t())


def tangents(mbs: exu.MainSystem, pair: ContactPair, markers: Sequence[Any], normal: np.ndarray,
             first: np.ndarray | None = None) -> np.ndarray:
    """The tangents (rows, global, unit) along which the contact of ``pair`` between
    ``markers`` slides at the current state for the normal ``normal``: ``n x a`` for a pair
    with a ``plane`` ``a`` (marker 0's frame), else :func:`tangent_plane` (carrying ``first``
    over)."""
    if pair.plane is None:
        return tangent_plane(normal, first)
    rotation = np.asarray(mbs.GetMarkerOutput(markers[0], exu.OutputVariableType.RotationMatrix), dtype=float)
    return np.cross(normal, rotation.reshape(3, 3) @ np.asarray(pair.plane, dtype=float))[None, :]


def tangent_plane(normal: np.ndarray, first: np.ndarray | None = None) -> np.ndarray:
    """Two unit tangents (rows, global) normal to ``normal`` and to each other: the first
    ``first`` (a tangent of the last measure) with its part along ``normal`` taken out, where
    that is at least :data:`CARRY` long, else one normal to the axis farthest from ``normal``
    (which changes with the normal: the tangents would jump)."""
    if first is not None:
        carried = first - (first @ normal) * normal
        size = float(np.linalg.norm(carried))
        if size >= CARRY:
            carried /= size
            return np.array([carried, np.cross(normal, carried)])
    helper = np.zeros(3)
    helper[int(np.argmin(np.abs(normal)))] = 1.0  # the axis farthest from the normal
    first = np.cross(normal, helper)
    first /= float(np.linalg.norm(first))
    return np.array([first, np.cross(normal, first)])


class Frictionless:
    """The hooks of :class:`ContactFriction` for a frictionless joint: nothing to do."""

    notes: list[str] = []
    jumps: list[tuple[float, float, float]] = []
    acting = False
    tell_gains = False

    def reset(self, mbs: exu.MainSystem) -> bool:
        return False

    def measure(self, mbs: exu.MainSystem, normal: np.ndarray, ecc: Eccentricity) -> None:
        pass

    def hold(self, mbs: exu.MainSystem) -> None:
        pass

    def release(self, mbs: exu.MainSystem) -> None:
        pass

    def forget(self) -> None:
        pass

    def check(self, mbs: exu.MainSystem, normal_force: float, left: int) -> bool:
        return False

    def accept(self, mbs: exu.MainSystem, t_end: float, held: bool, jump: Any = None) -> None:
        pass

    def snapshot(self) -> dict[str, Any]:
        return {}

    def setting(self) -> tuple:
        return ()

    def matches(self, setting: tuple) -> bool:
        return True

    def restore(self, mbs: exu.MainSystem | None, saved: dict[str, Any]) -> None:
        pass

    def outputs(self) -> dict[str, np.ndarray]:
        return {}


def contact_friction(mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                     pair: ContactPair, condition: Callable[[str, int], VelocityCondition]) -> ContactFriction | Frictionless:
    """The friction of an impulse-mode joint between ``markers`` [outer, inner] whose contact
    is ``pair``: its items where the joint's law has friction, the sticking conditions made by
    ``condition`` (given a name and the index of its tangent in :func:`tangents`; a joint with
    several contacts holds them with the others'),
    one for a pair that slides along one tangent, two for one that slides in a tangent plane
    (``plane`` None: a ball, a box's corner), one against the spin for an end face
    (:class:`SpinFriction`); else hooks that do nothing."""
    if not joint.friction.active:
        return Frictionless()
    label = f"{name}:stick" if name else ""
    spin = isinstance(pair, FacePair)
    names = [label] if spin or pair.plane is not None else [f"{label} 1" if name else "", f"{label} 2" if name else ""]
    kind = SpinFriction if spin else ContactFriction
    return kind(mbs, joint, markers, pair, [condition(n, k) for k, n in enumerate(names)])
