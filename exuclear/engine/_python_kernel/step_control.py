"""The joint's own step control: a step longer than the joint's ``impact_step`` in which an
impact begins is redone at it (:meth:`JointStepControl.impact_redo`); a step in which a contact
begins too early, the penetration rate changes too much or the penetration exceeds the limit
is redone shorter (:meth:`JointStepControl.step_control`); free flight lets the solver's next step grow
(:meth:`JointStepControl.step_growth`, over a system's step group); the contacts that ended in
too long a step are counted.  The compiled kernel's ``step_control.hpp``."""
from __future__ import annotations

import math
from typing import Any

from ...history import ContactState
from .joint_state import JointState
from .kinematics import Kinematics
from .laws import impact_duration

#: Error a post-Newton function returns to make Exudyn redo a step: anything above
#: Exudyn's ``discontinuous.iterationTolerance`` (default 1).
REDO_STEP_ERROR = 1e3
#: Relative slack on a step length compared with the impact step (Exudyn's steps carry round-off).
STEP_SLACK = 1e-9
#: The joint's own step control (:meth:`JointStepControl.step_control`).  A contact with an impact
#: velocity that began before the step's last ``ONSET_TAIL`` is redone so that it begins in
#: the step's last ``ONSET_TARGET`` (its force then acts from about its onset on): an implicit
#: method charges the contact force at the step's end over the whole step, where it acted
#: only since the onset, and a contact that began halfway through a step several times
#: longer than the impact gives the step a spurious impulse (docs/validation/step_control.md,
#: ``python -m validation.cost fine_steps``).
ONSET_TAIL = 0.02
ONSET_TARGET = 0.01
#: A contact that began in the step's first ONSET_FLOOR (touching at its start) is resolved
#: from its start: it is not redone (that would shrink the step towards zero); the rate
#: criterion resolves the rest.
ONSET_FLOOR = 0.05
#: ... and only where the step is longer than the impact's duration (its estimate
#: :func:`exuclear.timescales.impact_duration` at the joint's effective mass) divided by
#: ONSET_IDLE_STEPS: a step that resolves the impact is left as the user chose it.  There a
#: redo makes the path worse, not better: an implicit method's errors in the compression and
#: the restitution of an impact cancel at equal steps, and a redo shortens the steps of the
#: compression only (``python -m validation.cost fine_steps``, docs/validation/step_control.md).
ONSET_IDLE_STEPS = 12.0
#: Exudyn's implicit solver redoes a rejected step with at most this fraction of it, whatever
#: step is recommended (``CSolverImplicitSecondOrderTimeInt::ReduceStepSize``: the smaller of
#: 0.75 h and the recommendation): an onset later than that in the step is placed at the end
#: of the second redone step (:func:`onset_step`), else it would fall at the next step's start.
SOLVER_STEP_CUT = 0.75
#: The recommended step's margin below the estimate (the rate's change is not linear in the
#: step: aim a little short, so that the redone step is accepted).
STEP_SAFETY = 0.8
#: The rate criterion shortens a step at most this much per attempt (a step still too long is
#: rejected again): the change of the rate is far from linear in a long step, and a larger
#: cut overshoots towards the solver's minimum step, where Exudyn's Newton fails.
MAX_CUT = 0.1
#: ... and never below this many times the solver's minimum step, near which Exudyn's Newton
#: iteration fails (its residual falls to round-off): there the step is accepted and reported.
MIN_STEP_MARGIN = 10.0
#: Free flight lets the step grow (:meth:`JointStepControl.step_growth`): after two accepted steps in
#: which none of the joint's contacts touched, the next step may last until the journal would
#: reach the wall at its present penetration rate, up to GROWTH_LIMIT times the step (and, on
#: the handle's side, ten of the joint's contact periods: steering.GROWTH_CONTACT_PERIODS), faster
#: than Exudyn's own rule (a doubling after 10 easy steps).  The limit keeps Newton's
#: predictor within its reach (a tenfold step from a converged state).
GROWTH_LIMIT = 10.0
#: ... and only where the journal's free flight allows at least this many times the step (a
#: smaller gain is left to Exudyn's own rule) ...
GROWTH_MIN = 2.0
#: ... and only where every contact's gap exceeds this fraction of the clearance: a journal
#: that rests on the wall at a step far longer than its contact period hovers, its contact
#: opening by nanometres for a step or two, and a longer step there shakes it off; a journal
#: that left the wall in an impact passes 1 % of c within microseconds.
GROWTH_GAP = 1e-2
#: A penetration beyond the joint's limit redoes the step with this fraction of it ...
PENETRATION_CUT = 0.25
#: ... this many times for one contact, counted from a step that starts out of contact (the
#: step 4^4 = 256 times shorter); a penetration still beyond the limit then is the contact's,
#: not the step's: the step is accepted, the joint's failure() says so and the handle warns
#: (exuclear.simulate stops the run there).  Counted per step instead, a contact whose
#: penetration passes the limit would be approached in ever shorter steps down to the
#: solver's minimum step.
PENETRATION_RETRIES = 4
#: ``mbs.variables`` key of the Python kernel's step group: ``[time, smallest allowance, joints that reported]``.
STEP_GROUP_KEY = "exuclear.step_group"


def _same(x: float, y: float) -> bool:
    """Whether ``x`` is ``y`` up to STEP_SLACK; an unset time (-inf) matches itself only, never a finite time."""
    return x == y or (math.isfinite(y) and abs(x - y) <= STEP_SLACK * abs(y) + 1e-300)


class JointStepControl(JointState):
    """A joint's own step control over its :class:`~.joint_state.JointState` (the compiled
    kernel's ``step_control.hpp``): the steps it redoes shorter, the growth it allows after
    free flight, its Jacobian asks and the separations it counts."""

    def count_separations(self, advance: bool, ended: int, h: float) -> None:
        """Count the contacts that ended in an accepted step of length ``h``, and those of them
        in a step longer than the run-start callback's ``separation_step`` (numerical chatter,
        :func:`exuclear.engine.diagnostics.chatter_note`); a step accepted again from the same start
        (redone after another item rejected it) replaces its first count."""
        c = self.control
        if not advance:
            c.separations -= c.last_ended
            c.long_separations -= c.last_long
        c.last_ended = ended
        c.last_long = ended if h > c.separation_step * (1.0 + STEP_SLACK) else 0
        c.separations += c.last_ended
        c.long_separations += c.last_long

    def steer_jacobian(self, step: float, conformal: bool = False) -> None:
        """Ask for a Jacobian per step while the step the joint accepts is longer than the
        run-start callback's ``jacobian_step`` (:mod:`exuclear.engine.steering`), and for the step
        after one in which a contact opened or closed (its stiffness came or went) or that it
        redoes or grows (a step of another length, whose Newton matrix's mass term
        ``M / (beta h^2)`` an older Jacobian does not hold): ``step`` inf.  Also while a worn
        joint is in contact (``conformal``): in its imprint the contact's normal (the overlaps'
        resultant, docs/physics.md eq. (75)) turns fast with sideways motion, an older
        Jacobian misses that stiffness and Exudyn's step recovery never lets a cut step grow
        back (docs/validation/step_control.md).  Through the
        callback's ``jacobian_per_step``: a call where the ask changes, not per step."""
        c = self.control
        wanted = conformal or step > c.jacobian_step
        if wanted == c.jacobian_on:
            return
        c.jacobian_on = wanted
        ask = getattr(self.run_start, "jacobian_per_step", None)
        if ask is not None:
            try:
                ask(wanted)
            except Exception:  # never end a run for a Jacobian: the setting stays as it was
                pass

    def impact_redo(self, kins: list[Kinematics], base: tuple[ContactState, ...], t: float,
                    impact_step: float) -> float:
        """Where the joint has an ``impact_step`` and the step ``[base.time, t]`` is longer, the
        step to redo it with (``impact_step``) when an impact begins in it: a contact begins, or
        it is the run's first step and the run begins in an impact (``|v0| > v_min``); else 0."""
        if not (impact_step > 0.0 and t - base[0].time > impact_step * (1.0 + STEP_SLACK)):
            return 0.0
        start = base[0].time == self.initial[0].time  # the step from the run's initial state
        v_min = self._joint.law.v_min
        begins = any((not b.in_contact and k.delta > 0.0) or (start and b.in_contact and abs(b.v0) > v_min)
                     for k, b in zip(kins, base))
        return impact_step if begins else 0.0

    def step_growth(self, before: tuple[ContactState, ...] | None, base: tuple[ContactState, ...],
                    states: tuple[ContactState, ...], t: float, kappa: float) -> float:
        """The next step this joint allows after the accepted step ``[base.time, t]``, where it
        would let it grow beyond Exudyn's own rule; 0 where it asks for none.  Only in free
        flight: no contact touched in this step or in the one ``before`` it, every gap above
        GROWTH_GAP of the clearance, no film (a journal that rests on the wall opens its
        contact for single steps, and a longer step there shakes it off).  The allowance is the time until the journal would reach the wall
        with the penetration rate and its change over the step (:func:`time_to_wall`; a step
        that ends beyond the wall all the same is redone by the onset rule of
        :meth:`step_control`, and a step that ends before it cannot hold a whole contact), at
        most GROWTH_LIMIT times the step, and only where that is GROWTH_MIN times the step or
        more, and at most the run-start callback's ``growth_cap``.  Only where the joint can
        steer the steps (an implicit solver that shortens steps); with an ``impact_step`` too,
        whose redo rule then catches a grown step that ends beyond the wall."""
        c = self.control
        h = t - base[0].time
        if not (c.can_shorten and c.rate and kappa > 0.0 and self.film is None and h > 0.0
                and before is not None):
            return 0.0
        allow = min(GROWTH_LIMIT * h, c.growth_cap)
        gap = GROWTH_GAP * self._joint.geometry.clearance
        for a, b, s in zip(before, base, states):
            if a.in_contact or b.in_contact or s.in_contact or -s.delta < gap:
                return 0.0
            if s.delta == -math.inf:  # no wall under it (a corner beyond its guide's end): it limits nothing
                continue
            allow = min(allow, time_to_wall(s.delta, s.delta_dot, (s.delta_dot - b.delta_dot) / h))
        return allow if allow >= GROWTH_MIN * h else 0.0

    def report_growth(self, mbs: Any, t: float, allow: float, h: float) -> None:
        """Tell the step group of the joint's system (``mbs.variables``) this joint's
        allowance for the step after ``t`` (:meth:`step_growth`); the last of the system's
        joints to report lets the solver's next step grow to the smallest allowance, through
        the run-start callback's ``grow``: one joint's free flight never lengthens a step that
        another joint's contact needs short.  A system whose joints run in both kernels never
        completes a group (each kernel counts its own), and so keeps Exudyn's own rule."""
        grow = getattr(self.run_start, "grow", None)
        if grow is None:
            return
        group = mbs.variables.get(STEP_GROUP_KEY)
        if group is None or group[0] != t:
            group = mbs.variables[STEP_GROUP_KEY] = [t, math.inf, set()]
        group[1] = min(group[1], allow)
        group[2].add(id(self))
        if len(group[2]) == self.control.group_size and group[1] >= GROWTH_MIN * h:
            self.steer_jacobian(math.inf)  # the grown step: a Jacobian for it
            grow(group[1])

    def step_control(self, kins: list[Kinematics], base: tuple[ContactState, ...], t: float,
                     max_penetration: float, kappa: float, impact_step: float = 0.0) -> float:
        """Whether the step ``[base.time, t]`` resolves the joint's contacts: 0 if so (accept
        it), else the shorter step to redo it with.  A step the solver cannot shorten (its
        settings forbid it, its minimum step, or the same step came back unshortened) is
        accepted and counted for the handle's warning, as is a penetration beyond the limit
        that shorter steps do not remove.

        - onset: a contact with an impact velocity (``|v0| > v_min``) that began before the
          step's last ``ONSET_TAIL``, in a step longer than the impact needs
          (``ONSET_IDLE_STEPS``), is redone to begin at the end of a step (:func:`onset_step`);
        - rate: ``|delta_dot_end - delta_dot_start| > kappa max(|v0|, v_min)`` in a contact
          (or one that began or ended in the step): several steps per velocity reversal,
          with neither the mass nor the law in the criterion.  Settled contacts (``|v0|`` at
          the ``v_min`` floor) are limited too: exempting them, as if the implicit
          integrator's damping took care of their stiff oscillation, left deeper penetrations
          in more steps (docs/validation/step_control.md);
        - held: a step through which a contact is held (in contact at both ends), longer than
          the run-start callback's ``contact_cap`` (steering.HELD_CONTACT_PERIODS contact
          periods), is redone at ``contact_cap``;
        - separation: a step in which a contact ends, longer than the run-start callback's
          ``separation_step`` (a tenth of the contact period, steering.separation_step), is
          redone at that step: a contact that opens in a longer step of an implicit method
          rings and may close again without a physical cause (numerical chatter, which
          :func:`exuclear.engine.diagnostics.chatter_note` reports where the step could not be
          shortened).
        """
        c = self.control
        h = t - base[0].time
        if not h > 0.0:
            return 0.0
        repeated = _same(t, c.last_time) and _same(h, c.last_step)  # the solver did not shorten it
        shortens = c.can_shorten and not repeated and h > c.min_step * (1.0 + STEP_SLACK)
        deepest = max(k.delta for k in kins)
        if deepest > max_penetration:
            if not _same(base[0].time, c.retry_start) and not any(b.in_contact for b in base):
                c.retry_start, c.retries = base[0].time, 0  # a new contact: its own retries
            if shortens and c.retries < PENETRATION_RETRIES:
                c.retries += 1
                c.rejected += 1
                c.last_time, c.last_step = t, h
                h_new = h * PENETRATION_CUT
                return h_new if h_new > c.min_step else c.min_step * (1.0 + STEP_SLACK)
        h_new = self._rate_control(kins, base, t, h, shortens, kappa, impact_step)
        if deepest > max_penetration and h_new == 0.0:
            # accepted beyond the limit: the run goes on, the handle says so (a simulate run
            # stops); a step the rate rules redo is judged again when it comes back
            if c.over_limit == 0:
                c.over_time, c.over_step = t, h
                self.failure = f"penetration {deepest:.4g} m exceeds the limit {max_penetration:.4g} m"
                self.failure_time = t
            c.over_limit += 1
            c.deepest = max(c.deepest, deepest)
            if c.over_limit == 1:
                self.tell()
        return h_new

    def _rate_control(self, kins: list[Kinematics], base: tuple[ContactState, ...], t: float, h: float,
                      shortens: bool, kappa: float, impact_step: float) -> float:
        """The onset, rate, held and separation rules of :meth:`step_control` for the step
        ``h`` ending at ``t``: 0 to accept it, else the shorter step to redo it with."""
        c = self.control
        kappa *= c.rate_scale
        if not c.rate or impact_step > 0.0:  # an explicit impact_step overrides the rate criterion
            kappa = 0.0
        if not kappa > 0.0:
            return 0.0
        h_rec, rate_exceeded, held_over = math.inf, False, False
        h_need = math.inf  # the rate criterion's estimate without the cap: the advice of a note
        v_min = self._joint.law.v_min
        for kin, b in zip(kins, base):
            if kin.delta <= 0.0 and not b.in_contact:
                continue  # free flight: nothing limits the step
            onset = not b.in_contact
            v0 = b.onset_velocity(kin.delta, kin.delta_dot)
            impact = abs(v0) > v_min
            if impact and onset and b.delta != -math.inf and not self._resolves_impact(h, v0):
                share = b.delta / (b.delta - kin.delta)  # the onset's fraction of the step
                if 1.0 - share > ONSET_TAIL and share > ONSET_FLOOR:
                    h_rec = min(h_rec, onset_step(h, share))
            if b.in_contact and kin.delta > 0.0 and h > c.contact_cap * (1.0 + STEP_SLACK):
                h_rec = min(h_rec, c.contact_cap)  # a held contact: at most HELD_CONTACT_PERIODS
                held_over = True
            if b.in_contact and kin.delta <= 0.0 and h > c.separation_step * (1.0 + STEP_SLACK):
                h_rec = min(h_rec, c.separation_step)  # a contact that opens: resolved, not chatter
            change = abs(kin.delta_dot - b.delta_dot)
            allowed = kappa * (abs(v0) if impact else v_min)
            if change > allowed:
                h_rate = STEP_SAFETY * h * allowed / change
                if impact:
                    h_need = min(h_need, h_rate)
                h_rec = min(h_rec, max(h_rate, MAX_CUT * h))
                # reported only for an impact: a settled contact's rate at a fixed step is the
                # load's (the resting pendulum of tests/test_robust.py is right at its step)
                rate_exceeded = rate_exceeded or impact
        if h_rec == math.inf:
            return 0.0
        floor = MIN_STEP_MARGIN * c.min_step
        h_rec = max(h_rec, floor)
        if shortens and h > floor * (1.0 + STEP_SLACK):
            c.rejected += 1
            c.last_time, c.last_step = t, h
            return h_rec if h_rec > c.min_step else c.min_step * (1.0 + STEP_SLACK)
        if held_over:  # accepted through a held contact longer than the cap: say so
            if c.held_long == 0:
                c.held_time, c.held_step = t, h
            c.held_long += 1
            if c.held_long == 1:
                self.tell()
        if rate_exceeded:  # accepted unresolved: say so after the run
            if c.unresolved == 0:
                c.unresolved_time, c.unresolved_step = t, h
            c.unresolved += 1
            c.unresolved_advice = min(c.unresolved_advice, max(h_need, floor))
            if c.unresolved == 1:
                self.tell()  # with its advice
        return 0.0

    def _resolves_impact(self, h: float, v0: float) -> bool:
        """Whether a step ``h`` resolves an impact at ``v0``: at most the impact's duration
        divided by ONSET_IDLE_STEPS (False where the joint's effective mass is unknown)."""
        mass = self.control.impact_mass
        if not (mass > 0.0 and math.isfinite(mass)):
            return False
        return h * ONSET_IDLE_STEPS <= impact_duration(self._joint.law, mass, v0)


def onset_step(h: float, share: float) -> float:
    """The step to redo a step ``h`` with, whose contact began at ``share`` of it, so that the
    contact begins in the last ONSET_TARGET of a step: of this one, or, where Exudyn would not
    shorten it that little (SOLVER_STEP_CUT), of the second of two equal steps."""
    steps = 1.0 if share / (1.0 - ONSET_TARGET) <= SOLVER_STEP_CUT else 2.0
    return h * share / (steps - ONSET_TARGET)


def time_to_wall(delta: float, delta_dot: float, delta_ddot: float) -> float:
    """The time [s] until a journal in free flight, at penetration ``delta`` < 0 (the gap is
    ``-delta``) with the rate ``delta_dot`` and its rate ``delta_ddot``, reaches the wall: the
    smallest positive root of ``delta + delta_dot tau + delta_ddot tau^2 / 2 = 0``; inf where
    the journal does not come back at that rate and acceleration."""
    if delta_ddot == 0.0:
        return -delta / delta_dot if delta_dot > 0.0 else math.inf
    disc = delta_dot * delta_dot - 2.0 * delta_ddot * delta
    if disc < 0.0:
        return math.inf  # moving away and slowing down towards the wall: it turns before it
    # the root of the smaller magnitude, free of cancellation: 2 (-delta) / (delta_dot + sqrt(disc))
    # for a journal moving towards the wall; else the root on the far side of the turn
    q = delta_dot + math.copysign(math.sqrt(disc), delta_dot if delta_dot != 0.0 else 1.0)
    roots = (-2.0 * delta / q if q != 0.0 else math.inf, -q / delta_ddot)
    positive = [r for r in roots if r > 0.0]
    return min(positive) if positive else math.inf
