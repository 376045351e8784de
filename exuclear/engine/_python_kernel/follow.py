"""The contact-following mode of a planar joint (issue 34, opt-in: ``contact_mode="follow"``).

A contact that has lasted several contact periods with a small penetration rate is carried
by an ``ObjectConnectorDistance`` between the joint's two markers (docs/guide/contact_following.md):
the journal centre is held at ``|e| = c + delta(lambda)`` from the bearing centre, where
``delta(lambda)`` is the law's static penetration at the constraint's multiplier ``lambda``
(the normal force), set once per accepted step; the compliant normal force is not applied
while the constraint holds, friction acts from ``lambda``.  The constraint is switched on
and off with its ``activeConnector`` flag between accepted steps (from the joint's
post-Newton function, whose accepted state is the next step's start), and switched on only
where position and normal rate agree with it (its distance set to the present ``|e|``, the
rate below ``v_min``): a switch in an inconsistent state is an impulse
(/work/shared/research/contact-following.md).  It releases where the multiplier turns
tensile; the step in which it turns is redone shorter once, so that the release lands
near the step's end.
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu

from ...timescales import contact_period, penetration_at

#: Contact periods a contact must have lasted before the constraint takes it over: the
#: compliant contact's own oscillation after an impact has decayed by then (cr < 1), and a
#: journal that only grazes the wall never switches.
FOLLOW_PERIODS = 5.0
#: ... and at least this many accepted steps in contact (where the contact period is unknown,
#: this alone): the penetration rate of two steps must agree before the switch.
FOLLOW_MIN_STEPS = 3
#: ... and a penetration rate below this fraction of the law's ``v_min`` at the step's end:
#: the constraint removes the normal rate in one step, an impulse ``m delta_dot`` that starts
#: the multiplier's two-step oscillation (below); at ``v_min`` itself (1e-3 m/s) the orbiting
#: journal's multiplier swung between 0.3 and 1.7 times the load.
FOLLOW_RATE = 0.1
#: The constraint's distance follows ``c + delta(lambda)`` at most at this fraction of the law's
#: ``v_min`` (per unit of the last step's length): the distance set between steps is reached in
#: the next step, so a jump of it is a normal velocity, an impulse through the multiplier
#: (measured: the orbiting journal's first update, 0.6 um in a 2.7 us step, took the
#: multiplier from +5 kN to -6e7 N and threw the journal off the wall).
FOLLOW_DISTANCE_RATE = 1.0
#: ... and only where it is more than this fraction of the static penetration off the target
#: ``c + delta(lambda)`` (a dead band; then to within it): a tracker without one moves the
#: distance up and down by its rate limit every step, following the multiplier's two-step
#: oscillation, a normal velocity of +-v_min that pumps the oscillation up (measured on the
#: orbiting journal: the multiplier swung to +-1e5 N about 4.6 kN within 0.15 ms).
FOLLOW_DEAD_BAND = 5e-3
#: The target follows the multiplier low-passed over some steps (an exponential mean of
#: the two-step means with this weight on the newest): the distance then moves one way to
#: its target, not with the oscillation.
FOLLOW_FILTER = 0.2
#: Newton's absolute tolerance while the constraint holds: this fraction of the static
#: penetration (and no less than ``FOLLOW_ATOL_FORCE`` times the normal force, the round-off of
#: the force residual).  Exudyn's residual is one norm over the force residuals [N] and the
#: constraint equations [m], and the joint's own absolute tolerance (1e-8, for the compliant
#: contact's round-off, steering.py) accepts a distance constraint violated by 1e-8 m: at steps
#: where the free journal drifts off the circle by less than that, Newton stops at its first
#: iterate with a zero multiplier, and the violation grows until a later step corrects it by an
#: impulse (measured: the orbiting journal at 1e-5 s, lambda 0, then 261 N, then -874 N about
#: 12.5 N, released).
FOLLOW_ATOL_SHARE = 1e-4
FOLLOW_ATOL_FORCE = 1e-13
#: A release found at this fraction of the step or later is accepted where it is (no redo).
RELEASE_LATE = 0.9


class FollowState:
    """One joint's following mode: the distance connector, whether it holds, its
    multiplier at the last accepted step, and counts of what it did."""

    def __init__(self, law: Any, clearance: float) -> None:
        self.law, self.clearance = law, clearance
        self.mbs: Any = None
        self.object: Any = None  # the ObjectConnectorDistance (set by AddClearanceJoint)
        self.reset()

    def reset(self) -> None:
        self.active = False
        self.multiplier = 0.0  # lambda, mean of the last two accepted steps [N] (contact sense: > 0 presses)
        self.raw = 0.0  # lambda at the last accepted step
        self.filtered = 0.0  # the low-passed lambda the distance's target is set from
        self.steps_in_contact = 0
        self.on_count = self.off_count = self.redone = 0
        self.followed_steps = 0
        self.last_redo = -math.inf
        self.distance = 0.0  # the constraint's distance [m]
        self.saved_tolerance: float | None = None  # Newton's absolute tolerance before the switch
        self.switch_on_times: list[float] = []
        self.switch_off_times: list[float] = []

    # -- reading and setting the constraint --------------------------------------------
    def normal_force(self, mbs: Any) -> float:
        """The normal force the friction acts from: the mean of the multiplier at the present
        state and at the last accepted step.  Exudyn's generalized-alpha multiplier of a
        position constraint (index 3) oscillates from step to step about the physical force
        (measured on the orbiting journal: 5077, 3637, 6020, 2749 ... N about 4620 N after the
        switch, the amplitude decaying slowly at spectral radius 0.9); the mean of two steps
        is the physical force (4600 N)."""
        return 0.5 * (self.read_multiplier(mbs) + self.raw)

    def read_multiplier(self, mbs: Any) -> float:
        """The constraint's multiplier at the present state (Newton's iterate during a step):
        the normal force [N], positive where the wall presses the journal inwards (the
        connector's ``Force``, positive in tension)."""
        return float(mbs.GetObjectOutput(self.object, exu.OutputVariableType.Force))

    def _set(self, mbs: Any, active: bool, distance: float | None = None) -> None:
        if distance is not None:
            self.distance = float(distance)
            mbs.SetObjectParameter(self.object, "distance", self.distance)
        mbs.SetObjectParameter(self.object, "activeConnector", bool(active))
        self.active = active

    def static_penetration(self, force: float) -> float:
        """``delta(lambda)``: the law's static penetration at the normal force ``force`` [m]."""
        return penetration_at(self.law, force) if force > 0.0 else 0.0

    # -- the decisions, once per step ----------------------------------------------------
    def restart(self, mbs: Any) -> None:
        """A new run begins (from the initial state): the compliant contact, the constraint off."""
        if self.active:
            self._set(mbs, False)
        self.reset()

    def _tolerance(self, mbs: Any, delta: float, force: float) -> None:
        """Newton's absolute tolerance for the constraint (FOLLOW_ATOL_SHARE), the user's back
        where ``delta`` is None."""
        try:
            newton = mbs.sys["dynamicSolver"].newton
        except Exception:  # not in a SolveDynamic run
            return
        if self.saved_tolerance is None:
            self.saved_tolerance = newton.absoluteTolerance
        newton.absoluteTolerance = min(self.saved_tolerance, max(FOLLOW_ATOL_SHARE * delta, FOLLOW_ATOL_FORCE * force))

    def _restore_tolerance(self, mbs: Any) -> None:
        if self.saved_tolerance is None:
            return
        try:
            mbs.sys["dynamicSolver"].newton.absoluteTolerance = self.saved_tolerance
        except Exception:  # the run is gone
            pass
        self.saved_tolerance = None

    def release_step(self, mbs: Any, h: float, start: float, can_shorten: bool) -> float:
        """While following, at the end of the step of length ``h`` from ``start``: 0 to accept
        it, else the shorter step to redo it with, so that a release (the multiplier turning
        tensile) lands near its end; once per step start."""
        lam = self.normal_force(mbs)
        if lam >= 0.0 or not can_shorten or not self.multiplier > 0.0:
            return 0.0
        share = self.multiplier / (self.multiplier - lam)  # lambda's zero, linear over the step
        if share >= RELEASE_LATE or start == self.last_redo:
            return 0.0
        self.last_redo = start
        self.redone += 1
        return max(share, 0.05) * h

    def after_step(self, mbs: Any, t: float, h: float, delta: float, delta_dot_start: float, delta_dot: float,
                   in_contact: bool, onset_time: float, normal_force: float, mass: float) -> None:
        """An accepted step of length ``h`` ending at ``t``: release, update ``delta(lambda)``, or switch on."""
        if self.active:
            raw = self.read_multiplier(mbs)
            lam = 0.5 * (raw + self.raw)
            self.raw = raw
            if lam <= 0.0:
                self._set(mbs, False)
                self._restore_tolerance(mbs)
                self.off_count += 1
                self.switch_off_times.append(t)
                self.multiplier = self.raw = 0.0
                self.steps_in_contact = 0
                return
            self.multiplier = lam
            self.filtered += FOLLOW_FILTER * (lam - self.filtered)
            self.followed_steps += 1
            delta_lam = self.static_penetration(self.filtered)
            off = self.clearance + delta_lam - self.distance
            band = FOLLOW_DEAD_BAND * delta_lam
            if abs(off) > band:
                most = FOLLOW_DISTANCE_RATE * self.law.v_min * h
                move = math.copysign(min(most, abs(off) - 0.5 * band), off)
                self._set(mbs, True, self.distance + move)
            self._tolerance(mbs, self.distance - self.clearance, lam)
            return
        self.steps_in_contact = self.steps_in_contact + 1 if in_contact and delta > 0.0 else 0
        if self.steps_in_contact < FOLLOW_MIN_STEPS or not normal_force > 0.0:
            return
        v_min = self.law.v_min
        if abs(delta_dot) > FOLLOW_RATE * v_min:
            return
        if mass > 0.0 and math.isfinite(mass):
            if t - onset_time < FOLLOW_PERIODS * contact_period(self.law, mass, normal_force):
                return
        # consistent: the distance is the present |e|, the rate is small
        self._set(mbs, True, self.clearance + delta)
        self._tolerance(mbs, delta, normal_force)
        self.multiplier = self.raw = self.filtered = normal_force
        self.on_count += 1
        self.switch_on_times.append(t)

    def counts(self) -> dict[str, Any]:
        return {"on": self.on_count, "off": self.off_count, "redone": self.redone, "followed_steps": self.followed_steps,
                "active": self.active}
