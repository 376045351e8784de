"""The contact-following mode's per-step decisions (:class:`FollowState`, issue 34;
:mod:`exuclear.engine.following` says what the mode is and docs/guide/contact_following.md
what was tried for each rule): when a sustained contact is handed to the condition, the
distance it holds, when it is let go, and which steps are redone.  The compiled kernel's
``following.hpp``."""
from __future__ import annotations

import math
import warnings
from typing import Any

from ...timescales import contact_period, contact_stiffness, penetration_at
from ..steering import JACOBIAN_PER_STEP_ABOVE

#: Contact periods a contact must have lasted before the constraint takes it over: the
#: compliant contact's own oscillation after an impact has decayed by then (cr < 1), and a
#: journal that only grazes the wall never switches.
FOLLOW_PERIODS = 5.0
#: ... and a step of at least this share of the contact period, the share above which the
#: joint's Jacobian rule finds that the contact's stiffness stalls Newton (2.5 times the
#: mass term in Newton's matrix).  At shorter steps the compliant contact is resolved and
#: cheap, and the condition's own cost is not repaid (the zoo's 3D double pendulums, at
#: 0.23 contact periods); the paper's slider-crank, at 0.08, took the same steps and Newton
#: iterations either way.  The distance follows the load less well there too (the loop
#: gain's bound, FOLLOW_GAIN, moves it by a few per cent of its offset per step: the
#: slider-crank's path drifted along the wall to 5 % of c in the second revolution).
FOLLOW_STEP = JACOBIAN_PER_STEP_ABOVE
#: ... and a contact normal that turned by less than this [rad] over the last step: the
#: velocity condition holds the normal of the step's predicted end, off the true one by the
#: turn's error of prediction (the zoo's beam pendulum: a node of a fraction of a gram whose
#: contact point swings 0.2-0.4 rad per 2.5 ms step, |e| off d by several times the
#: penetration within a few steps).
FOLLOW_TURN = 0.1
#: A contact whose slip is within STICK_MARGIN times its friction law's smoothing band
#: (``smoothing_speed`` of :mod:`exuclear.friction`'s laws) stays compliant, and a followed
#: one is let go there (in a consistent state: ``|e| = d``,
#: no normal rate, the compliant force the multiplier): friction is a steep function of the
#: slip there, and Newton's iteration of the multiplier through it alternated (the 2D double
#: pendulum with friction at rest on its wall after 4.7 s, +-40 N about 27 N, until Exudyn
#: stopped; with friction from the last accepted multiplier, or the mean of the last two,
#: it stopped at 0.98 s and 1.1 s).  With the band itself (a margin of 1) Exudyn stopped at
#: 5.78 s, in the step where the slip fell through it from 2.5e-4 m/s; with 10 the 10 s run
#: ends (77196 steps, the compliant run 78321).
STICK_MARGIN = 10.0
#: A followed contact whose ``|e| - c`` is off the held ``d - c`` by more than this share of
#: it (the journal left the wall, or pressed in more than twice as far) is redone shorter,
#: then released (counted as ``lost``): the condition no longer holds the contact.  The
#: miss grows about linearly with the step (median 0.56 after a halving, the zoo's piston
#: engine on the Python kernel), so a tighter share is bought with shorter steps: at half
#: the penetration the compiled kernel redid 230 of the piston engine's steps over its 2 s
#: (5705 steps) and lost the beam pendulum's contact at each of its 11 engagements (50040
#: steps), at the whole 193 (5393 steps) and once in 5 (44450 steps, 3.24 c off its run at 64
#: times the steps, the compliant run 3.17 c; ``python -m validation.contact_follow_long
#: --models beam_pendulum_2d --refines 1,64 --ensemble 0 --follow-backend compiled``).
FOLLOW_HOLD = 1.0
#: ... and this share where the joint has friction: with the whole penetration the 2D double
#: pendulum with friction dissipated -0.920 +- 0.007 J over its 10 s (three runs, compiled
#: kernel), against -0.941 +- 0.005 J at half and the converged compliant run's -0.968 J
#: (``python -m validation.contact_follow_long --models double_pendulum_2d_friction --refines
#: 1,16 --ensemble 2 --follow-backend compiled``).
FOLLOW_HOLD_FRICTION = 0.5
#: ... after at most this many halvings of the step that did not hold it.
HOLD_REDOS = 3
#: ... and only where the integrator's spectral radius (``mbs.sys["dynamicSolver"].spectralRadius``)
#: is at most this: a contact carried by the condition has a step-to-step mode of its
#: multiplier that only the integrator's numerical damping takes out.  Measured on the zoo's
#: rigid-body tutorial over its 4 s (the trapezoidal rule, spectral radius 1), against the
#: compliant run at 64 times its steps: the multiplier swung by 182 N (90th percentile) about
#: 303 N, the kinetic energy grew, the contact was lost at 2.2 s and the run ended 37 c off
#: (the compliant run at the example's steps: 2.7 c); with the prediction without the
#: acceleration, or half the rate's gain, 35 c and 14 c.  The same model under
#: generalized-alpha at 0.9: held to the end, a swing of 2.3 N, 73 c off against the compliant
#: run's 78 c at the same settings (that integrator's own damping of the pendulum).
FOLLOW_MAX_RHO = 0.9
#: ... and at least this many accepted steps in contact (where the contact period is unknown,
#: this alone): the penetration rate of two steps must agree before the switch.
FOLLOW_MIN_STEPS = 3
#: ... and a penetration rate below this fraction of the law's ``v_min`` at the step's end:
#: the constraint removes the normal rate in one step, an impulse ``m delta_dot`` that starts
#: the multiplier's two-step oscillation (below); at ``v_min`` itself (1e-3 m/s) the orbiting
#: journal's multiplier swung between 0.3 and 1.7 times the load.
FOLLOW_RATE = 0.1
#: The constraint's distance moves to ``c + delta(lambda)`` by the share ``omega`` of its
#: offset per step, ``omega = min(1, FOLLOW_GAIN beta h^2 k / m)`` (``k`` the law's tangent
#: stiffness at the penetration, ``m`` the joint's effective mass, ``beta`` = 1/4): the
#: distance set between steps is reached in the next step, a jump that the index-3 multiplier
#: answers with about ``m jump / (beta h^2)``, while the target moves by ``d lambda / k`` for
#: a change ``d lambda`` of the multiplier.  The loop's gain is ``omega m / (beta h^2 k)``:
#: at most FOLLOW_GAIN.  At steps far longer than the contact period (``h^2 k / m >> 1``,
#: the regime the mode is for) omega is 1: the distance is the target.  Tried first: a rate
#: limit of ``v_min`` per step, then a limit on the rate's change per step; both jittered
#: with the multiplier at the paper's slider-crank (steps 0.08 contact periods), whose
#: multiplier they swung to +-2 kN about 30 N.  Where the effective mass is not known the
#: distance stays where it was switched on.
FOLLOW_GAIN = 0.25
GA_BETA = 0.25
#: The distance stays where it is while it is within this fraction of the static penetration
#: of its target ``c + delta(lambda)`` (a dead band): a tracker without one moves it up and
#: down every step, following the multiplier's two-step oscillation, which pumps the
#: oscillation up (measured on the orbiting journal: +-1e5 N about 4.6 kN within 0.15 ms).
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
#: Release where the low-passed multiplier (FOLLOW_FILTER) turns tensile (True), or the
#: multiplier itself (False: the velocity condition's, the distance condition's two-step
#: mean) with the step redone to end there (RELEASE_REDO).  On a journal looping inside its
#: bearing under gravity (``python -m validation.contact_follow loop``; it leaves the wall at
#: 120.45 deg) the low-pass lets it go 4.4 to 7.8 deg late, the multiplier itself within
#: 0.6 deg.  Kept for the zoo's 3D double pendulum with friction, whose path over 0.5 s ended
#: 0.52 c off the reference with it and 2.0 c off without when the mode engaged there at
#: about 0.2 contact periods, where the held distance lags the unloading (FOLLOW_GAIN), and the
#: compliant contact that takes over at the multiplier's zero pushes the journal off from the
#: lagging penetration (docs/guide/contact_following.md, "Release").
RELEASE_FILTERED = True
#: Redo the step in which the multiplier turned tensile at the share of it where its
#: straight line between the step's ends crosses zero (no less than RELEASE_SHORTEST of the
#: step), so that the release lands at the redone step's end, where the contact is let go
#: whatever the multiplier then (``release_due``).  Once per step start, and only without
#: RELEASE_FILTERED (a shorter step does not place the low-passed zero).
RELEASE_REDO = True
#: The shortest share of a step a release redoes it to.
RELEASE_SHORTEST = 0.05
#: The normal force friction acts from while following: "filtered" (the low-passed multiplier
#: of the accepted steps, explicit), "iterate" (Newton's present multiplier), "mean" (the
#: mean of the present and the last accepted multiplier) or "accepted" (the last accepted
#: multiplier).  Measured with the velocity condition over 0.5 s on the zoo's models with the
#: paper's friction law (probe off the compliant reference at 4x the steps; the compliant
#: run: 2D double pendulum 1734 steps 1.01 c, rigid-body tutorial 1909 steps 0.36 c, 3D
#: double pendulum 5846 steps 0.27 c): "iterate" 1722 steps 1.04 c, 2215 steps 0.40 c, and
#: the 3D pendulum stopped at 0.40 s (the friction's dependence on the multiplier is not in
#: Exudyn's Jacobian of the joint's force, so Newton iterates it as a fixed point, which
#: alternated there: +-30 N at steps of 1e-8 s); "mean" 1800 steps 0.94 c, 1602 steps 0.74 c,
#: 6803 steps 0.53 c; "accepted" 2654 steps 1.17 c, 1602 steps 1.01 c, 6317 steps 1.09 c with
#: 5 engagements; "filtered" 7505 steps 1.01 c on the 3D pendulum with 5 engagements and more
#: on the 2D one.  The orbiting journal with Coulomb friction (tests/test_contact_follow.py):
#: "iterate" and "mean" within the compliant model's error of the analytic speed.
FRICTION_FROM = "mean"
#: A release found at this fraction of the step or later is accepted where it is (no redo).
RELEASE_LATE = 0.9
#: The condition that holds a followed contact: "velocity" (:class:`VelocityCondition`) or
#: "distance" (:class:`DistanceCondition`, the first prototype's).  Measured on the zoo's
#: double pendulum over 0.5 s, with every other rule here: "distance" 4.23 Newton iterations
#: per step, "velocity" 3.16 (compliant 4.94), the same path; with the paper's friction
#: "distance" engaged 3 times and Exudyn stopped at 0.488 s, "velocity" engages once and
#: ends 0.94 c off the reference (compliant 1.01 c).
CONDITION = "velocity"
#: The distance's target is the penetration at which the law's force, with its damping at
#: the rate the move asks for, is the multiplier (True), not the static penetration.  On the
#: paper's slider-crank (when made to follow) it moved the path 4.75 % of c off the
#: reference against 6.5 % without; the contact's damping is 1.4 % of its force there.
DAMPED_TARGET = True
#: A step ending within this share of the run's end time (and no less than this in seconds) is
#: its last (:meth:`FollowState._park`).
END_SLACK = 1e-12
#: Relative tolerance of the damped target's penetration (:meth:`FollowState.damped_penetration`),
#: and its evaluations at most (a bisection over ``(0, c]`` to 1e-12 of a 1e-15 m root takes 80).
DAMPED_RTOL = 1e-12
DAMPED_MAX_ITER = 200
#: The secant's second point: this share of the first away from it.
DAMPED_FIRST = 1e-3


class FollowState:
    """One joint's following mode: the distance connector, whether it holds, its
    multiplier at the last accepted step, and counts of what it did."""

    def __init__(self, law: Any, clearance: float, name: str = "", friction: bool = False) -> None:
        self.law, self.clearance, self.name = law, clearance, name
        self.hold = FOLLOW_HOLD_FRICTION if friction else FOLLOW_HOLD  # the share of holds()
        self.condition: Any = None  # DistanceCondition or VelocityCondition (set by AddClearanceJoint)
        self.reset()

    def reset(self) -> None:
        self.active = False
        self.multiplier = 0.0  # lambda, mean of the last two accepted steps [N] (contact sense: > 0 presses)
        self.raw = 0.0  # lambda at the last accepted step
        self.filtered = 0.0  # the low-passed lambda the distance's target is set from
        self.steps_in_contact = 0
        self.onset_rate = 0.0  # the contact's onset rate v0 (its damping's scale), set by the kernel
        self.on_count = self.off_count = self.redone = self.lost = 0
        self.barred = False
        self.damping_checked = False  # the integrator's spectral radius, read at the run's first contact
        self.end_time = math.inf  # the run's end time [s], read with it
        self.parked = False  # the condition switched off at the run's last step, holding the contact (_park)
        self.undamped = False  # ... above FOLLOW_MAX_RHO: the run stays compliant
        self.hold_start, self.hold_redos = -math.inf, 0
        self.release_due = False  # a step redone to end where the multiplier turns tensile (release_step)
        self.followed_steps = 0
        self.last_redo = -math.inf
        self.distance = 0.0  # the constraint's distance [m]

        self.saved_tolerance: float | None = None  # Newton's absolute tolerance before the switch
        self.switch_on_times: list[float] = []
        self.switch_off_times: list[float] = []

    # -- reading and setting the constraint --------------------------------------------
    def friction_force(self, mbs: Any) -> float:
        """The normal force friction acts from while following (FRICTION_FROM)."""
        if FRICTION_FROM == "filtered":
            return self.filtered
        if FRICTION_FROM == "iterate":
            return self.read_multiplier(mbs)
        if FRICTION_FROM == "accepted":
            return self.raw
        return self.normal_force(mbs)

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
        return self.condition.multiplier(mbs)

    def _set(self, mbs: Any, active: bool, distance: float | None = None, h: float = 0.0) -> None:
        if distance is not None:
            self.distance = float(distance)
        if active:
            self.condition.hold(mbs, self.distance, h)
        if active != self.active:
            self.condition.switch(mbs, active)
            _request_jacobian(mbs)
        self.active = active

    def damped_penetration(self, force: float, delta: float, h: float) -> float:
        """The penetration ``x`` where the law's force, elastic and damping at the rate
        ``(x - delta) / h`` from the present ``delta``, is ``force``: the secant method from
        ``delta`` inside a bracket on ``(0, c]`` that each evaluation narrows, bisecting where
        the secant leaves it or the force is NaN (the force grows with ``x``; NaN beyond a
        line-contact law's largest penetration counts as above any force).  To DAMPED_RTOL of
        ``x``: 5.0 evaluations per step on the zoo's double pendulum over 2 s, where a bisection
        over ``(0, c]`` took 60."""
        def excess(x: float) -> float:
            f = self.law.normal_force(x, (x - delta) / h, self.onset_rate)
            return math.inf if math.isnan(f) else f - force

        lo, hi = 0.0, self.clearance
        x = min(max(delta, DAMPED_RTOL * hi), hi)
        x0 = g0 = math.nan  # the previous iterate and its excess
        for _ in range(DAMPED_MAX_ITER):
            g = excess(x)
            if g >= 0.0:
                hi = x
            else:
                lo = x
            if hi - lo <= DAMPED_RTOL * hi:
                break
            if math.isnan(x0):  # the second point: a small step the way the force asks
                step = x * (-DAMPED_FIRST if g >= 0.0 else DAMPED_FIRST)
            elif math.isfinite(g) and math.isfinite(g0) and g != g0:
                step = -g * (x - x0) / (g - g0)
            else:
                step = math.nan
            x0, g0 = x, g
            if math.isfinite(step) and abs(step) <= DAMPED_RTOL * x:
                return x + step
            x = x + step if lo < x + step < hi else 0.5 * (lo + hi)  # NaN fails the test: bisect
        return 0.5 * (lo + hi)

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
        it, else the shorter step to redo it with, so that the release lands at its end
        (RELEASE_REDO); once per step start.  Marks the contact to be let go at the redone
        step's end (:meth:`after_step`)."""
        if not RELEASE_REDO or RELEASE_FILTERED:
            return 0.0
        lam = self.normal_force(mbs) if self.condition.two_step_mean else self.read_multiplier(mbs)
        if lam >= 0.0 or not can_shorten or not self.multiplier > 0.0:
            return 0.0
        share = self.multiplier / (self.multiplier - lam)  # lambda's zero, linear over the step
        if share >= RELEASE_LATE or start == self.last_redo:
            return 0.0
        self.last_redo = start
        self.redone += 1
        self.release_due = True
        return max(share, RELEASE_SHORTEST) * h

    @staticmethod
    def sticking(friction: Any, slip: float) -> bool:
        """Whether the slip lies within STICK_MARGIN times the friction law's smoothing band."""
        return friction.active and abs(slip) < STICK_MARGIN * friction.smoothing_speed

    def holds(self, delta: float) -> bool:
        """Whether the penetration ``delta`` (``|e| - c``) is within FOLLOW_HOLD (with friction
        FOLLOW_HOLD_FRICTION) of the held ``d - c``."""
        held = self.distance - self.clearance
        return abs(delta - held) <= self.hold * held

    def hold_step(self, delta: float, h: float, start: float, can_shorten: bool, min_step: float) -> float:
        """While following, at the end of the step of length ``h`` from ``start`` where the
        penetration is ``delta``: 0 to accept it, else the shorter step to redo it with where
        ``|e|`` left ``d`` by more than FOLLOW_HOLD of the penetration (the condition's error
        falls with the fourth power of the normal's turn per step; the force function sets
        its rows for the shorter step).  At most HOLD_REDOS halvings per step start; then
        :meth:`after_step` lets the contact go (``lost``)."""
        if self.holds(delta) or not can_shorten or 0.5 * h < min_step:
            return 0.0
        if start != self.hold_start:
            self.hold_start, self.hold_redos = start, 0
        if self.hold_redos >= HOLD_REDOS:
            return 0.0
        self.hold_redos += 1
        self.redone += 1
        return 0.5 * h

    def _track(self, mbs: Any, h: float, lam: float, mean: float, mass: float) -> None:
        """Move the distance towards ``c + delta(lambda)`` (the low-passed multiplier), outside
        the dead band, by the share ``omega`` of its offset (FOLLOW_GAIN)."""
        self.filtered += FOLLOW_FILTER * (lam - self.filtered)
        target = self.filtered if self.condition.two_step_mean else mean
        if not (mass > 0.0 and math.isfinite(mass) and h > 0.0 and target > 0.0):
            return
        if DAMPED_TARGET and not self.condition.two_step_mean:
            delta_lam = self.damped_penetration(target, self.distance - self.clearance, h)
        else:
            delta_lam = self.static_penetration(target)
        off = self.clearance + delta_lam - self.distance
        if abs(off) <= FOLLOW_DEAD_BAND * delta_lam:
            return
        k = contact_stiffness(self.law, delta_lam)
        omega = min(1.0, FOLLOW_GAIN * GA_BETA * h * h * k / mass)
        self.distance += omega * off

    def _release(self, mbs: Any, t: float) -> None:
        self._set(mbs, False)
        self._restore_tolerance(mbs)
        self.off_count += 1
        self.switch_off_times.append(t)
        self.multiplier = self.raw = 0.0
        self.steps_in_contact = 0
        self.release_due = False

    def after_step(self, mbs: Any, t: float, h: float, delta: float, delta_dot_start: float, delta_dot: float,
                   in_contact: bool, onset_time: float, normal_force: float, mass: float, turn: float = 0.0,
                   sticking: bool = False) -> None:
        """An accepted step of length ``h`` ending at ``t``, over which the contact's normal
        turned by ``turn`` [rad], ``sticking`` where its slip is within the friction law's
        smoothing band: release, update ``delta(lambda)``, or switch on; at the run's last
        step, park the condition (:meth:`_park`)."""
        if self.parked:  # the run's last step redone for another joint after the park: compliant since
            self.parked = False
            self.off_count += 1
        self._decide(mbs, t, h, delta, delta_dot, in_contact, onset_time, normal_force, mass, turn, sticking)
        if self.active and t >= self.end_time - END_SLACK * max(1.0, abs(self.end_time)):
            self._park(mbs)

    def _park(self, mbs: Any) -> None:
        """Switch the condition off at the run's last accepted step, where it still holds the
        contact: a run started again on the same system (another ``SolveDynamic``) would find
        it on while Exudyn computes its initial accelerations, before the joint's first force
        evaluation restarts the mode (measured on the zoo's 2D double pendulum over 1 s: the
        second run ended 0.9 mm from the first on the Python kernel).  The contact counts as
        held (``counts()["active"]``)."""
        self._set(mbs, False)
        self._restore_tolerance(mbs)
        self.parked = True

    def _decide(self, mbs: Any, t: float, h: float, delta: float, delta_dot: float, in_contact: bool,
                onset_time: float, normal_force: float, mass: float, turn: float, sticking: bool) -> None:
        """:meth:`after_step`'s decisions."""
        if self.active:
            raw = self.read_multiplier(mbs)
            mean = 0.5 * (raw + self.raw)  # the distance's target: a two-step oscillation fed back through it grows
            lam = mean if self.condition.two_step_mean else raw
            self.raw = raw
            filtered = self.filtered + FOLLOW_FILTER * (lam - self.filtered)
            if self.release_due or (filtered if RELEASE_FILTERED else lam) <= 0.0 or sticking:
                self._release(mbs, t)  # sticking: |e| = d and no normal rate, the compliant force is lambda
                return
            if not self.holds(delta):  # the condition no longer holds |e| = d
                self.lost += 1
                self.barred = True
                self._release(mbs, t)
                return
            self.multiplier = lam
            self.followed_steps += 1
            self._track(mbs, h, lam, mean, mass)
            self._set(mbs, True, h=h)  # the distance (and the velocity condition's rows) for the next step
            self._tolerance(mbs, self.distance - self.clearance, lam)
            return
        self.steps_in_contact = self.steps_in_contact + 1 if in_contact and delta > 0.0 else 0
        if self.steps_in_contact == 0:
            self.barred = False
        if self.barred:  # a contact the condition lost stays compliant until it ends (no churning)
            return
        if self.steps_in_contact < FOLLOW_MIN_STEPS or not normal_force > 0.0:
            return
        if not self.damping_checked:
            self._check_damping(mbs)
        if self.undamped:
            return
        v_min = self.law.v_min
        if abs(delta_dot) > FOLLOW_RATE * v_min or abs(turn) > FOLLOW_TURN or sticking:
            return
        if mass > 0.0 and math.isfinite(mass):
            period = contact_period(self.law, mass, normal_force)
            if t - onset_time < FOLLOW_PERIODS * period or h < FOLLOW_STEP * period:
                return
        # consistent: the distance is the present |e|, the rate is small
        self._set(mbs, True, self.clearance + delta, h)
        self._tolerance(mbs, delta, normal_force)
        self.multiplier = self.raw = self.filtered = normal_force

        self.on_count += 1
        self.switch_on_times.append(t)

    def _check_damping(self, mbs: Any) -> None:
        """Whether the run's integrator damps the condition's two-step mode (FOLLOW_MAX_RHO);
        says once per run where it does not, and the joint stays compliant.  Reads the run's
        end time too (:meth:`_park`)."""
        self.damping_checked = True
        try:
            solver = mbs.sys["dynamicSolver"]
            rho = float(solver.spectralRadius)
            self.end_time = float(solver.it.endTime)
        except Exception:  # not an implicit SolveDynamic run: the condition's own refusal applies
            return
        if rho <= FOLLOW_MAX_RHO:
            return
        self.undamped = True
        warnings.warn(f"clearance joint {self.name!r}: contact_mode='follow' stays compliant in this run: the "
                      f"integrator's spectral radius is {rho:g} (the trapezoidal rule or Newmark without damping are "
                      f"1), which leaves the condition's multiplier a step-to-step oscillation that is not damped; "
                      f"the mode engages with generalized-alpha at spectralRadius <= {FOLLOW_MAX_RHO:g} (Exudyn's "
                      "default)", UserWarning, stacklevel=2)

    def counts(self) -> dict[str, Any]:
        return {"on": self.on_count, "off": self.off_count, "lost": self.lost, "redone": self.redone,
                "followed_steps": self.followed_steps,
                "active": self.active or self.parked}


def _request_jacobian(mbs: Any) -> None:
    """A Jacobian at the next Newton iteration: the switched constraint's row changes from
    ``lambda = 0`` to the distance condition (or back).  Without it Exudyn's modified Newton
    keeps the Jacobian of the inactive constraint, finds ``lambda = 0`` and accepts the step
    on its relative tolerance, the constraint's residual (metres, 6e-10) negligible beside
    the forces' (measured: the slider-crank at 5e-6 s steps, the constraint unmet and let go
    at every engagement, 31 switches)."""
    try:
        mbs.sys["dynamicSolver"].conv.jacobianUpdateRequested = True
    except Exception:  # not in a SolveDynamic run
        pass
