"""The Python kernel: the clearance joint's Exudyn user functions, written in Python.

This is the readable statement of what the compiled kernel
(``exuclear/_kernel/clearance_kernel.cpp``) computes, with the same names and in the same
order.  The physics of one contact comes from :mod:`exuclear.spatial` (kinematics and
loads), :mod:`exuclear.contact`, :mod:`exuclear.friction` and
:func:`exuclear.joint.contact_response` (normal and friction force), and
:mod:`exuclear.history` (the contact history).  This module assembles a joint from its
contacts and keeps their histories the way Exudyn's calling pattern needs:

- **Contacts.**  A joint is a sequence of contacts (:class:`Contact`): its slices (the
  planar joint has one, whose motion is projected on the plane normal to the bearing
  axis), then its two end faces where it has an axial clearance.  One
  :meth:`Contact.response` (onset velocity, normal force, friction) serves them all; the
  kind of contact decides the stiffness (the law's share, or the face's flat punch), the
  slip that friction acts against and where the loads go.
- **Which history an evaluation uses.**  Exudyn evaluates forces many times per step
  (Runge-Kutta stages, Newton iterations, Jacobian perturbations, rejected attempts) and
  calls the post-Newton function once the step's state is final.  A joint keeps, per
  contact, the history at the start (``previous``) and at the end (``current``) of the
  last step it post-processed:

  - an evaluation at a time after ``current.time`` belongs to a new step: ``current``;
  - one at or before ``current.time`` belongs to a step computed again (a discontinuous
    iteration, a step redone with a smaller size): ``previous``;
  - one before ``previous.time`` starts a new run (``mbs.SolveDynamic`` from the initial
    state): the history is forgotten and this evaluation's state, the run's initial
    state, is accepted.  Exudyn's first evaluation of a run is at the initial state.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any, NamedTuple

from ..film import FilmLaw, FilmLoad
from ..friction import FrictionLaw
from ..geometry import ContactKinematics, contact_kinematics, joint_loads
from ..history import ContactState, ImpactRecord
from ..joint import ClearanceJoint, ContactResponse, contact_response
from ..spatial import (
    FACE_SIDES,
    V3,
    FaceKinematics,
    ShoulderGeometry,
    SliceKinematics,
    add_face_loads,
    add_slice_loads,
    face_kinematics,
    face_normal_force,
    finish_loads,
    friction_components,
    journal_axis,
    slice_centres,
    slice_kinematics,
)
from ..timescales import impact_duration
from .layout import RunStart, read

#: Error a post-Newton function returns to make Exudyn redo a step: anything above
#: Exudyn's ``discontinuous.iterationTolerance`` (default 1).
REDO_STEP_ERROR = 1e3
#: Relative slack on a step length compared with the impact step (Exudyn's steps carry round-off).
STEP_SLACK = 1e-9
#: The joint's own step control (:meth:`JointKernel.step_control`).  A contact with an impact
#: velocity that began before the step's last ``ONSET_TAIL`` is redone so that it begins in
#: the step's last ``ONSET_TARGET`` (its force then acts from about its onset on): an implicit
#: method charges the contact force at the step's end over the whole step, where it acted
#: only since the onset, and a contact that began halfway through a step several times
#: longer than the impact gives the step a spurious impulse (the paper's slider-crank at
#: 1e-5 s steps: 11.9 % of c off the reference with the rule off, 2.7 % with it on;
#: ``python -m validation.fine_steps``).
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
#: compression only (Exudyn holds a shortened step for its recovery steps).  Measured on the
#: paper's slider-crank (``python -m validation.fine_steps``): at 2e-6 s (impacts of about 40
#: steps) the rule took the path from 0.58 % to 1.78 % of c, at 5e-6 s (about 16) from 2.8 %
#: to 5.3 %; at 1e-5 s (about 8) it brought it from 11.9 % to 2.7 %.  Any threshold from 10 to
#: 15 steps gives the same paths there.
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
#: cut overshoots towards the solver's minimum step (measured on the zoo's piston engine: a
#: cut from 2.1e-7 s to 1.7e-8 s, where Exudyn's Newton then failed).
MAX_CUT = 0.1
#: ... and never below this many times the solver's minimum step, near which Exudyn's Newton
#: iteration fails (its residual falls to round-off): there the step is accepted and reported.
MIN_STEP_MARGIN = 10.0
#: Free flight lets the step grow (:meth:`JointKernel.step_growth`): after two accepted steps in
#: which none of the joint's contacts touched, the next step may last until the journal would
#: reach the wall at its present penetration rate, up to GROWTH_LIMIT times the step (and, on
#: the handle's side, ten of the joint's contact periods: steering.GROWTH_CONTACT_PERIODS).  Exudyn's
#: own rule doubles a step after 10 steps of at most 7 Newton iterations: from an impact's
#: microsecond steps back to a model's millisecond step that is 70 steps at best, and none
#: where the model's Newton takes more (measured on the zoo, README).  The limit keeps Newton's
#: predictor within its reach (a tenfold step from a converged state).
GROWTH_LIMIT = 10.0
#: ... and only where the journal's free flight allows at least this many times the step (a
#: smaller gain is left to Exudyn's own rule) ...
GROWTH_MIN = 2.0
#: ... and only where every contact's gap exceeds this fraction of the clearance: a journal
#: that rests on the wall at a step far longer than its contact period hovers, its contact
#: opening by nanometres for a step or two, and a longer step there shook it off (measured:
#: the zoo's double pendulum under exuclear.simulate's automatic steps of 1e-2 s, 34573 steps
#: instead of 4885); a journal that left the wall in an impact passes 1 % of c within microseconds.
GROWTH_GAP = 1e-2
#: A penetration beyond the joint's limit redoes the step with this fraction of it ...
PENETRATION_CUT = 0.25
#: ... this many times for one step's start (the step 4^4 = 256 times shorter); a penetration
#: still beyond the limit then is the contact's, not the step's: the step is accepted, the
#: joint's failure() says so and the handle warns (exuclear.simulate stops the run there).
PENETRATION_RETRIES = 4
_DIVERGED = "the state became non-finite (NaN or inf); the integration diverged"
#: ``mbs.variables`` key of the Python kernel's step group: ``[time, smallest allowance, joints that reported]``.
STEP_GROUP_KEY = "exuclear.step_group"

Kinematics = ContactKinematics | SliceKinematics | FaceKinematics


class KernelFailure(RuntimeError):
    """A joint's state cannot go on (non-finite, penetration beyond the limit)."""


class StepControl:
    """What the joint's own step control did in the last run (the compiled kernel's
    ``StepControl``): whether the solver can shorten a step (from the run-start callback),
    the steps the joint rejected, and those it could not resolve (read by the handle, which
    says so in an :class:`~exuclear.engine.solver.AccuracyWarning`)."""

    def __init__(self, runs: int = 0) -> None:
        self.can_shorten, self.min_step, self.label, self.runs = True, 0.0, "", runs
        self.rate = True  # False: an explicit solver's error control sets the step (no rate criterion)
        self.group_size = 1  # the clearance joints of the joint's system (from the run-start callback)
        self.rate_scale = 1.0  # the factor on rate_limit for this run (a convergence check's tighter run: < 1)
        self.growth_cap = math.inf  # the longest step free flight may grow to [s] (steering.GROWTH_CONTACT_PERIODS)
        self.jacobian_step = math.inf  # the step above which the joint asks for a Jacobian per step [s] (newton.py)
        self.jacobian_on = False  # whether it asks now
        self.separation_step = math.inf  # a contact that ends in a longer step is not resolved [s] (handle.py)
        self.impact_mass = math.nan  # the effective mass of the joint's impacts [kg] (nan: unknown)
        self.separations = 0  # contacts that ended in the run
        self.long_separations = 0  # ... in a step longer than separation_step: maybe numerical chatter
        self.last_ended = self.last_long = 0  # what the last accepted step added (taken back if it is redone)
        self.rejected = 0
        self.unresolved, self.unresolved_time, self.unresolved_step = 0, 0.0, 0.0
        self.unresolved_advice = math.inf
        self.over_limit, self.over_time, self.over_step, self.deepest = 0, 0.0, 0.0, 0.0
        self.last_time, self.last_step = -math.inf, 0.0  # the last rejected step
        self.retry_start, self.retries = -math.inf, 0

    def as_dict(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in (
            "runs", "can_shorten", "min_step", "rate", "label", "group_size", "rate_scale", "growth_cap",
            "jacobian_step", "jacobian_on", "separation_step", "impact_mass", "separations", "long_separations", "rejected",
            "unresolved", "unresolved_time", "unresolved_step", "unresolved_advice", "over_limit", "over_time", "over_step", "deepest")}


def _same(x: float, y: float) -> bool:
    return abs(x - y) <= STEP_SLACK * abs(y) + 1e-300


class _Accepted(NamedTuple):
    """A contact's kinematics as :meth:`ContactState.accept` reads them; ``v_t`` is the slip
    the contact's friction acts against (and its output ``slip_velocity``)."""

    delta: float
    delta_dot: float
    ex: float
    ey: float
    v_t: float


# -- one contact ------------------------------------------------------------------------------
class Contact:
    """One contact of a joint: its normal law ``normal_force(delta, delta_dot, v0)``, its
    share of it, and the joint's friction law.  Subclasses say which slip friction acts
    against and where the loads go (the compiled kernel's ``ContactKind``)."""

    def __init__(self, normal_force: Callable[[float, float, float], float], friction: FrictionLaw,
                 share: float = 1.0) -> None:
        self.normal_force, self.friction, self.share = normal_force, friction, share

    def slip(self, kin: Kinematics) -> float:
        """The slip [m/s] friction acts against: the signed circumferential ``v_t``."""
        return kin.v_t

    def accepted(self, kin: Kinematics) -> _Accepted:
        """What :meth:`response` and :meth:`ContactState.accept` read of this contact's kinematics."""
        return _Accepted(kin.delta, kin.delta_dot, kin.ex, kin.ey, self.slip(kin))

    def response(self, kin: _Accepted, history: ContactState) -> ContactResponse:
        """Forces of the contact state ``kin`` given its last accepted ``history``
        (:func:`exuclear.joint.contact_response`)."""
        return contact_response(self.normal_force, self.friction, kin.delta, kin.delta_dot, kin.v_t, history,
                                self.share)

    def add_loads(self, loads: list[float], u: V3, kin: Any, r: ContactResponse) -> None:
        raise NotImplementedError


class PlanarSlice(Contact):
    """The planar joint's one slice: the whole law, friction along the tangent (eq. (20))
    against the signed slip ``v_T``.  Its kinematics and loads are those of a spatial slice
    for the motion projected on the plane normal to the axis, evaluated in the reduced form
    they take there, eqs. (1)-(8) and (24)-(26) (:func:`exuclear.geometry.contact_kinematics`,
    :func:`exuclear.geometry.joint_loads`): the planar joint keeps its results bit for bit
    (some scenes change course on a last-bit change of the force)."""

    def __init__(self, joint: ClearanceJoint) -> None:
        super().__init__(joint.law.normal_force, joint.friction)
        self.geometry = joint.geometry

    def add_loads(self, loads: list[float], u: V3, kin: ContactKinematics, r: ContactResponse) -> None:
        """``F = -F_i``, ``T = -M_i`` and the bearing's moment beyond ``T``, ``m_j + m_i``
        (the whole of it: no ``p x F`` is added for the planar joint)."""
        fx, fy, m_i, m_j = joint_loads(self.geometry, kin, r.f_n, r.f_t)
        loads[0] += -fx
        loads[1] += -fy
        loads[5] += -m_i
        loads[8] += m_j + m_i


class Slice(Contact):
    """A slice of the spatial joint: its share ``w / L`` of the law (eq. (41)), friction
    against the slip speed ``|v_s|``, along the slip (eq. (42))."""

    def __init__(self, joint: ClearanceJoint, share: float) -> None:
        super().__init__(joint.law.normal_force, joint.friction, share)
        self.r_j = joint.geometry.journal_radius

    def slip(self, kin: SliceKinematics) -> float:
        """The slip speed ``|v_s|`` of the contact points (eq. (42))."""
        return kin.speed

    def add_loads(self, loads: list[float], u: V3, kin: SliceKinematics, r: ContactResponse) -> None:
        f_t, f_a = friction_components(r.f_t, kin)                                        # eq. (42)
        add_slice_loads(loads, self.r_j, u, kin, r.f_n, f_t, f_a)


class Face(Contact):
    """An end face (docs/physics.md section 9.6): eq. (9) with the flat-punch stiffness
    ``K_f delta`` and the law's ``D`` and ``v_min`` (eq. (53)), friction against the
    circumferential slip at the friction radius, loads of eq. (54)."""

    def __init__(self, joint: ClearanceJoint, shoulders: ShoulderGeometry) -> None:
        law = joint.law
        self.k_face = shoulders.face_stiffness(law.E_star)                              # eq. (52)
        self.damping_factor, self.v_min = law.damping_factor, law.v_min
        self.friction_radius = shoulders.friction_radius                                # eq. (51)
        super().__init__(self._normal_force, joint.friction)

    def _normal_force(self, delta: float, delta_dot: float, v0: float) -> float:
        return face_normal_force(self.k_face, self.damping_factor, self.v_min, delta, delta_dot, v0)

    def add_loads(self, loads: list[float], u: V3, kin: FaceKinematics, r: ContactResponse) -> None:
        add_face_loads(loads, self.friction_radius, u, kin, r.f_n, r.f_t)                # eq. (54)


class FilmInput(NamedTuple):
    """What the film law takes (:meth:`exuclear.film.FilmLaw.blended_load`): the eccentricity
    ``e`` [m] in the bearing's joint frame, ``de/dt`` [m/s] as the connector hands it over
    (``A0^T (v1 - v0)``: the inertial derivative in the bearing frame's components, without
    the frame-rotation term), and the spins [rad/s] of journal and bearing about the axis.
    With that velocity the absolute spins are the consistent pair: ``dphi/dt`` is then the
    inertial angle rate of ``e``, and ``omega_eff = omega_J + omega_B - 2 dphi/dt`` equals
    ``omega_J - omega_B - 2 dphi_rel/dt`` of the bearing's rotating frame (docs/physics.md
    section 10.6)."""

    ex: float
    ey: float
    vx: float
    vy: float
    omega_journal: float
    omega_bearing: float


class Film:
    """The oil film of a lubricated joint (docs/physics.md section 10): one more kind of
    contact, without history, acting at every eccentricity (at the blended one of eq. (70)
    near the wall), added to the dry contact's loads (the compiled kernel's ``FILM``)."""

    def __init__(self, film: FilmLaw, share: float = 1.0) -> None:
        self.law, self.share = film, share

    def load(self, kin: FilmInput) -> FilmLoad:
        """Film force on the journal and viscous moments, eqs. (68)-(70)."""
        return self.law.blended_load(kin.ex, kin.ey, kin.vx, kin.vy, kin.omega_journal, kin.omega_bearing)

    def add_loads(self, loads: list[float], r: FilmLoad) -> None:
        """``F = -F_film`` on the bearing, ``T = -M_J``, and the bearing's moment beyond
        ``T``, ``M_B + M_J`` (as the planar slice's, eqs. (24)-(26))."""
        loads[0] += -r.fx
        loads[1] += -r.fy
        loads[5] += -r.torque_journal
        loads[8] += r.torque_bearing + r.torque_journal

    def add_slice_loads(self, loads: list[float], u: V3, kin: SliceKinematics, r: FilmLoad) -> None:
        """A spatial slice's share ``w / L`` of the film (docs/physics.md section 10.8): ``-F``
        on the bearing at the slice's axis point, ``F`` on the journal at ``c = p + s u``, the
        viscous moments about the bearing axis: ``T = s u x (-F) - M_J z``, and the bearing's
        moment beyond ``T`` (before ``p x F``), ``e x F + (M_B + M_J) z``."""
        w = self.share
        fx, fy, m_j, m_b = w * r.fx, w * r.fy, w * r.torque_journal, w * r.torque_bearing
        sx, sy, sz = kin.s * u[0], kin.s * u[1], kin.s * u[2]
        loads[0] += -fx
        loads[1] += -fy
        loads[3] += sz * fy                     # (s u) x (-F), F in the plane
        loads[4] += -sz * fx
        loads[5] += -(sx * fy - sy * fx) - m_j
        loads[8] += (kin.ex * fy - kin.ey * fx) + (m_b + m_j)

    def with_outputs(self, state: ContactState, kin: FilmInput) -> ContactState:
        """``state`` with the film's outputs at ``kin`` (the data node's film columns): a
        slice's share of the force and of the journal's moment."""
        r = self.load(kin)
        w = self.share
        return replace(state, film_fx=w * r.fx, film_fy=w * r.fy, film_torque=w * r.torque_journal)


# -- one joint --------------------------------------------------------------------------------
class JointKernel:
    """One joint's user functions and state (the compiled kernel's ``JointState``): per
    contact a :class:`ContactState` at the start and at the end of the last step, and its
    records (module docstring).

    ``slices`` 0 for the planar joint, else the spatial joint's number of slices N;
    ``axis_journal`` the journal axis in the journal marker's frame; ``shoulders`` the
    axial clearance (section 9.6) or None.  The end faces follow the slices in every
    per-contact sequence (states, records, data).
    """

    def __init__(self, joint: ClearanceJoint, slices: int = 0, axis_journal: Any = (0.0, 0.0, 1.0),
                 shoulders: ShoulderGeometry | None = None) -> None:
        self.planar = slices == 0
        self.slices = 1 if self.planar else slices
        self.axis_journal = tuple(float(v) for v in axis_journal)
        self.shoulders = shoulders
        self.n_contacts = self.slices + (len(FACE_SIDES) if shoulders is not None else 0)
        self.joint = joint
        #: called once per run start, returns the joint's :class:`~exuclear.engine.layout.RunStart`;
        #: None: none.  Its ``note()`` warns of an unresolved step, its ``grow(step)`` lets the solver's
        #: next step grow (:meth:`report_growth`).
        self.run_start: Callable[[], RunStart] | None = None
        self.control = StepControl()
        self.reset()

    @property
    def joint(self) -> ClearanceJoint:
        return self._joint

    @joint.setter
    def joint(self, joint: ClearanceJoint) -> None:
        g = joint.geometry
        self._joint = joint
        self.r_j, self.r_b = g.journal_radius, g.bearing_radius
        self.centres = slice_centres(g.length, self.slices)                               # eq. (33)
        slice_contact = PlanarSlice(joint) if self.planar else Slice(joint, 1.0 / self.slices)
        self.contacts: list[Contact] = [slice_contact] * self.slices
        if self.shoulders is not None:
            self.contacts += [Face(joint, self.shoulders)] * len(FACE_SIDES)
        self.film = Film(joint.film, 1.0 if self.planar else 1.0 / self.slices) if joint.film is not None else None

    def reset(self) -> None:
        self.started = False
        empty = tuple(ContactState() for _ in range(self.n_contacts))
        self.previous = self.current = self.initial = empty
        self.records: list[list[ImpactRecord]] = [[] for _ in range(self.n_contacts)]
        self.omega_bearing = (0.0, 0.0, 0.0)
        self.film_inputs: list[FilmInput] = []
        self.torque_correction = (0.0, 0.0, 0.0)
        self.initial_axis, self.initial_axial = (0.0, 0.0, 1.0), 0.0
        self.failure, self.failure_time = "", 0.0
        self.control = StepControl(self.control.runs)  # the run-start callback is kept

    def _fail(self, message: str, t: float) -> None:
        """Record why and when the run cannot go on, and raise (the compiled kernel's ``fail``)."""
        self.failure, self.failure_time = message, t
        who = f"joint {self.control.label}: " if self.control.label else ""
        raise KernelFailure(f"exuclear: {who}{message} at t = {t:.6f} s (joint.failure() says more)")

    def start_run(self) -> None:
        """A new run begins: forget the last run's step control and ask the handle (once per
        run) whether the solver can shorten steps, its minimum step and the joint's name."""
        self.control = c = StepControl(self.control.runs + 1)
        if self.run_start is not None:
            try:
                record = self.run_start()
                for name in RunStart._fields:
                    setattr(c, name, getattr(record, name))
                c.jacobian_on = c.jacobian_step < math.inf  # steer_newton asked for it at the first step
            except Exception:  # never end a run for a label: keep the defaults
                pass

    def tell(self) -> None:
        """The first step of a run that the joint could not resolve (of each kind) is told at
        once, through the run-start callback's ``note()`` (Python issues the AccuracyWarning,
        with its advice): a run that Exudyn then stops is not silent either."""
        note = getattr(self.run_start, "note", None)
        if note is not None:
            try:
                note()
            except Exception:  # a warning filter that raises: the notes keep it
                pass

    # -- bookkeeping -------------------------------------------------------------------
    def _kinematics(self, displacement: Any, rotation: Any, velocity: Any, angular_velocity: Any,
                    bearing_motion: bool = True) -> tuple[V3, V3, list[Kinematics]]:
        """The journal's centre and axis, and the kinematics of each contact: the slices
        (the planar joint's one, eqs. (1)-(8); a spatial joint's, eqs. (35)-(40)), then the
        end faces (eqs. (48)-(51)) where there is an axial clearance.  ``bearing_motion``
        False: the bearing's spin is taken as 0 (its probe is off: layout.uses_bearing_motion)."""
        w_j = self.omega_bearing if bearing_motion else (0.0, 0.0, 0.0)
        if self.planar:  # the motion projected on the plane normal to the axis: eqs. (1)-(8)
            omega_j = w_j[2]
            omega_i = angular_velocity[2] + omega_j  # the journal's own spin
            kin = contact_kinematics(self._joint.geometry, displacement[0], displacement[1], velocity[0], velocity[1],
                                     omega_i, 0.0, 0.0, 0.0, 0.0, omega_j)
            if self.film is not None:
                self.film_inputs = [FilmInput(displacement[0], displacement[1], velocity[0], velocity[1], omega_i,
                                              omega_j)]
            return (displacement[0], displacement[1], 0.0), (0.0, 0.0, 1.0), [kin]
        p = (displacement[0], displacement[1], displacement[2])
        u = journal_axis((rotation[0], rotation[1], rotation[2]), self.axis_journal)      # eq. (34)
        dv = (velocity[0], velocity[1], velocity[2])
        dw = (angular_velocity[0], angular_velocity[1], angular_velocity[2])
        kins: list[Kinematics] = [slice_kinematics(self.r_j, self.r_b, z, p, u, dv, dw, w_j) for z in self.centres]
        if self.film is not None:
            self.film_inputs = [slice_film_input(k, p, u, dv, dw, w_j) for k in kins]
        if self.shoulders is not None:
            g, play = self._joint.geometry, self.shoulders.axial_clearance
            r_e = self.shoulders.friction_radius
            kins += [face_kinematics(g.length, play, r_e, side, p, u, dv, dw, w_j) for side in FACE_SIDES]
        return p, u, kins

    def _accept_all(self, base: tuple[ContactState, ...], kins: list[Kinematics], t: float
                    ) -> tuple[ContactState, ...]:
        states = []
        for k, (kin, b, c) in enumerate(zip(kins, base, self.contacts)):
            del self.records[k][b.closed:]
            state, record = b.accept(c.accepted(kin), c, t)
            if record is not None:
                self.records[k].append(record)
            if not math.isfinite(state.normal_force):
                self._fail("the contact force became non-finite (NaN or inf)", t)
            states.append(state)
        if self.film is not None:
            for i, kin in enumerate(self.film_inputs):
                states[i] = self.film.with_outputs(states[i], kin)
        return tuple(states)

    def history_for(self, kins: list[Kinematics], t: float, u: V3, axial: float) -> tuple[ContactState, ...]:
        """The contacts' history an evaluation at time ``t`` uses (module docstring); ``u``,
        ``axial``: the journal's axis and axial displacement, kept for the initial outputs."""
        if not self.started or t < self.previous[0].time:
            self.initial_axis, self.initial_axial = u, axial
            self.records = [[] for _ in range(self.n_contacts)]
            self.failure = ""
            self.start_run()
            self.current = tuple(ContactState(time=t).accept(c.accepted(k), c, t)[0]
                                 for k, c in zip(kins, self.contacts))
            if self.film is not None:
                films = [self.film.with_outputs(c, k) for c, k in zip(self.current, self.film_inputs)]
                self.current = (*films, *self.current[len(films):])
            self.previous = self.initial = self.current
            self.started = True
            if not all(_finite(k) for k in kins):
                self._fail(_DIVERGED, t)
        return self.previous if t <= self.current[0].time else self.current

    # -- Exudyn user functions ---------------------------------------------------------
    def force_torque(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
                     angular_velocity: Any, stiffness: Any, damping: Any, rot0: Any, rot1: Any, offset: Any) -> list:
        """``springForceTorqueUserFunction`` of the joint's connector: ``[F; T]`` in J0, F the
        force on the bearing, T minus the journal's moment about its marker point
        (docs/physics.md eqs. (41)-(45), (54); the planar eqs. (24)-(26))."""
        p, u, kins = self._kinematics(displacement, rotation, velocity, angular_velocity,
                                      read(stiffness, "bearing_motion") != 0.0)
        history = self.history_for(kins, t, u, p[2])
        loads = [0.0] * 9
        for kin, h, c in zip(kins, history, self.contacts):
            if kin.delta <= 0.0:
                continue
            c.add_loads(loads, u, kin, c.response(c.accepted(kin), h))
        if self.film is not None:  # the film acts at every eccentricity (section 10.5), on every slice
            for kin, film_input in zip(kins, self.film_inputs):
                r = self.film.load(film_input)
                if self.planar:
                    self.film.add_loads(loads, r)
                else:
                    self.film.add_slice_loads(loads, u, kin, r)
        if self.planar:  # the planar slice's loads hold the bearing's whole moment (eq. (26))
            self.torque_correction = (loads[6], loads[7], loads[8])
            return loads[:6]
        total = finish_loads(loads, p)
        self.torque_correction = total.correction  # the bearing's moment beyond T (eq. (45))
        return [*total.force, *total.torque]

    def probe(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
              angular_velocity: Any, *parameters: Any) -> list:
        """The bearing-spin probe (marker 0 the bearing, marker 1 the ground): records the
        bearing's angular velocity (J0); applies nothing."""
        self.omega_bearing = (-angular_velocity[0], -angular_velocity[1], -angular_velocity[2])
        return [0.0] * 6

    def torque(self, mbs: Any, t: float, item: int, *arguments: Any) -> list:
        """The bearing-torque connector: the bearing's moment beyond what the joint applies (eq. (45))."""
        return [0.0, 0.0, 0.0, *self.torque_correction]

    def probe_post_newton(self, mbs: Any, t: float, item: int, data: Any, displacement: Any, rotation: Any,
                          velocity: Any, angular_velocity: Any, *parameters: Any) -> list:
        self.omega_bearing = (-angular_velocity[0], -angular_velocity[1], -angular_velocity[2])
        return [0.0, -1.0, *data]

    def post_newton(self, mbs: Any, t: float, item: int, data: Any, displacement: Any, rotation: Any, velocity: Any,
                    angular_velocity: Any, stiffness: Any, *parameters: Any) -> list:
        """``postNewtonStepUserFunction``: the contacts' history update, once per accepted
        step.  Returns ``[error, recommended step, data...]``."""
        max_penetration, impact_step = read(stiffness, "max_penetration"), read(stiffness, "impact_step")
        p, u, kins = self._kinematics(displacement, rotation, velocity, angular_velocity,
                                      read(stiffness, "bearing_motion") != 0.0)
        self.history_for(kins, t, u, p[2])
        advance = t > self.current[0].time
        base = self.current if advance else self.previous  # a repeated step starts again from its start
        if not all(_finite(k) for k in kins):
            self._fail(_DIVERGED, t)
        if impact_step > 0.0 and t - base[0].time > impact_step * (1.0 + STEP_SLACK) and self._impact_begins(kins, base):
            self.steer_jacobian(math.inf)  # a step of another length: a Jacobian for it
            return [REDO_STEP_ERROR, impact_step, *data]
        redo = self.step_control(kins, base, t, max_penetration, read(stiffness, "rate_limit"), impact_step)
        if redo > 0.0:
            self.steer_jacobian(math.inf)
            return [REDO_STEP_ERROR, redo, *data]
        states = self._accept_all(base, kins, t)
        # the step before this one: free flight must have lasted both (a repeated step: unknown)
        before = self.previous if advance else None
        allow = self.step_growth(before, base, states, t, read(stiffness, "rate_limit"))
        if advance:
            self.previous = self.current
        self.current = states
        h = t - base[0].time
        switched = any(b.in_contact != s.in_contact for b, s in zip(base, states))  # a contact's stiffness came or went
        self.count_separations(advance, sum(1 for b, s in zip(base, states) if b.in_contact and not s.in_contact), h)
        self.steer_jacobian(math.inf if switched else h)
        self.report_growth(mbs, t, allow, h)
        return [0.0, -1.0, *self.data_values(t, u, p[2], states)]

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

    def steer_jacobian(self, step: float) -> None:
        """Ask for a Jacobian per step while the step the joint accepts is longer than the
        run-start callback's ``jacobian_step`` (:mod:`exuclear.engine.steering`), and for the step
        after one in which a contact opened or closed (its stiffness came or went) or that it
        redoes or grows (a step of another length, whose Newton matrix's mass term
        ``M / (beta h^2)`` an older Jacobian does not hold): ``step`` inf.  Through the callback's
        ``jacobian_per_step``: a call where the ask changes, not per step."""
        c = self.control
        wanted = step > c.jacobian_step
        if wanted == c.jacobian_on:
            return
        c.jacobian_on = wanted
        ask = getattr(self.run_start, "jacobian_per_step", None)
        if ask is not None:
            try:
                ask(wanted)
            except Exception:  # never end a run for a Jacobian: the setting stays as it was
                pass

    def _impact_begins(self, kins: list[Kinematics], base: tuple[ContactState, ...]) -> bool:
        """Whether an impact begins in the step from ``base``, which an ``impact_step`` then
        redoes: a contact begins in it, or it is the run's first step and the run begins in
        an impact (``|v0| > v_min``)."""
        start = base[0].time == self.initial[0].time
        v_min = self._joint.law.v_min
        return any((not b.in_contact and k.delta > 0.0) or (start and b.in_contact and abs(b.v0) > v_min)
                   for k, b in zip(kins, base))

    def step_growth(self, before: tuple[ContactState, ...] | None, base: tuple[ContactState, ...],
                    states: tuple[ContactState, ...], t: float, kappa: float) -> float:
        """The next step this joint allows after the accepted step ``[base.time, t]``, where it
        would let it grow beyond Exudyn's own rule; 0 where it asks for none.  Only in free
        flight: no contact touched in this step or in the one ``before`` it, every gap above
        GROWTH_GAP of the clearance, no film (a journal that rests on the wall opens its
        contact for single steps, and a longer step there shakes it off, measured on the zoo's
        double pendulum).  The allowance is the time until the journal would reach the wall
        with the penetration rate and its change over the step (:func:`time_to_wall`; a step
        that ends beyond the wall all the same is redone by the onset rule of
        :meth:`step_control`, and a step that ends before it cannot hold a whole contact), at
        most GROWTH_LIMIT times the step, and only where that is GROWTH_MIN times the step or
        more, and at most the run-start callback's ``growth_cap``.  Only where the joint can
        steer the steps (an implicit solver that shortens steps); with an ``impact_step`` too,
        whose redo rule then catches a grown step that ends beyond the wall (the redundant
        slider-crank: 18257 -> 15272 steps, 4.9e-3 -> 3.6e-3 c, README "Speed")."""
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
          integrator's damping took care of their stiff oscillation, left penetrations 5x
          simulate's on the zoo's piston engine and cost more steps (measured: piston engine
          0.027 c in 19463 steps exempt, 0.0042 c in 9432 limited; beam pendulum 87796 and
          31981 steps over 0.05 s).
        """
        c = self.control
        h = t - base[0].time
        if not h > 0.0:
            return 0.0
        repeated = _same(t, c.last_time) and _same(h, c.last_step)  # the solver did not shorten it
        shortens = c.can_shorten and not repeated and h > c.min_step * (1.0 + STEP_SLACK)
        deepest = max(k.delta for k in kins)
        if deepest > max_penetration:
            if not _same(base[0].time, c.retry_start):
                c.retry_start, c.retries = base[0].time, 0
            if shortens and c.retries < PENETRATION_RETRIES:
                c.retries += 1
                c.rejected += 1
                c.last_time, c.last_step = t, h
                h_new = h * PENETRATION_CUT
                return h_new if h_new > c.min_step else c.min_step * (1.0 + STEP_SLACK)
            if c.over_limit == 0:  # accepted: the run goes on, the handle says so (a simulate run stops)
                c.over_time, c.over_step = t, h
                self.failure = f"penetration {deepest:.4g} m exceeds the limit {max_penetration:.4g} m"
                self.failure_time = t
            c.over_limit += 1
            c.deepest = max(c.deepest, deepest)
            if c.over_limit == 1:
                self.tell()
        kappa *= c.rate_scale
        if not c.rate or impact_step > 0.0:  # an explicit impact_step overrides the rate criterion
            kappa = 0.0
        if not kappa > 0.0:
            return 0.0
        h_rec, rate_exceeded = math.inf, False
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
            change = abs(kin.delta_dot - b.delta_dot)
            allowed = kappa * (abs(v0) if impact else v_min)
            if change > allowed:
                h_rate = STEP_SAFETY * h * allowed / change
                if impact:
                    h_need = min(h_need, h_rate)
                h_rec = min(h_rec, max(h_rate, MAX_CUT * h))
                # reported only for an impact: a settled contact's rate at a fixed step is the
                # load's (measured: the resting pendulum of tests/test_robust.py, right at its step)
                rate_exceeded = rate_exceeded or impact
        if h_rec == math.inf:
            return 0.0
        floor = MIN_STEP_MARGIN * c.min_step
        h_rec = max(h_rec, floor)
        if shortens and h > floor * (1.0 + STEP_SLACK):
            c.rejected += 1
            c.last_time, c.last_step = t, h
            return h_rec if h_rec > c.min_step else c.min_step * (1.0 + STEP_SLACK)
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

    def data_values(self, t: float, u: Any, axial: float, states: Any) -> list[float]:
        """The data node's entries for the contacts' ``states``: :func:`data_values` of the
        one slice for the planar joint, :func:`spatial_data_values` for the spatial joint."""
        lubricated = self.film is not None
        if self.planar:
            return data_values(states[0], lubricated)
        return spatial_data_values(t, u, axial, states, self.slices if lubricated else 0)


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


def _finite(kin: Kinematics) -> bool:
    return all(math.isfinite(v) for v in (kin.ex, kin.ey, kin.delta_dot, kin.v_t))


def data_values(s: ContactState, lubricated: bool = False) -> list[float]:
    """The data node's entries (layout.DATA_COLUMNS; then layout.FILM_DATA_COLUMNS where
    the joint is ``lubricated``) for a state."""
    film = [s.film_fx, s.film_fy, s.film_torque] if lubricated else []
    return [s.time, 0.0 if s.delta == float("-inf") else s.delta, s.delta_dot, s.ecc_x, s.ecc_y, s.normal_force,
            s.tangential_force, s.slip_velocity, s.v0, 1.0 if s.in_contact else 0.0, float(s.onsets), s.onset_time,
            s.peak_force, s.max_penetration, *film]


def spatial_data_values(t: float, u: Any, axial: float, states: Any, film_slices: int = 0) -> list[float]:
    """The spatial data node's entries (layout.spatial_data_columns): time, journal axis
    x, y (tilt, rad for small angles), axial displacement, then each slice's
    ``data_values`` without the time (with an axial clearance, the two end faces follow),
    then, for a lubricated joint (``film_slices`` its slices), each slice's film columns."""
    out = [t, u[0], u[1], axial]
    for s in states:
        out.extend(data_values(s)[1:])
    for s in states[:film_slices]:
        out.extend((s.film_fx, s.film_fy, s.film_torque))
    return out


def slice_film_input(kin: SliceKinematics, p: V3, u: V3, dv: V3, dw: V3, w_j: V3) -> FilmInput:
    """A spatial slice's film input (docs/physics.md section 10.8): the eccentricity of its
    axis point ``c = p + s u`` and its rate in the bearing's rotating frame, ``dv - w_j x p +
    dw x s u`` (the ``w`` of eq. (38)), with the journal's spin relative to the bearing
    ``dw . u`` and the bearing's 0: the rotating frame's pair (the planar joint takes the
    inertial one; both give the same ``omega_eff``)."""
    su = (kin.s * u[0], kin.s * u[1], kin.s * u[2])
    wx = dv[0] - (w_j[1] * p[2] - w_j[2] * p[1]) + (dw[1] * su[2] - dw[2] * su[1])
    wy = dv[1] - (w_j[2] * p[0] - w_j[0] * p[2]) + (dw[2] * su[0] - dw[0] * su[2])
    return FilmInput(kin.ex, kin.ey, wx, wy, dw[0] * u[0] + dw[1] * u[1] + dw[2] * u[2], 0.0)
