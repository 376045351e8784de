"""One joint's state (:class:`JointState`): per contact, its history at the start and at the
end of the last accepted step and its records, which history an evaluation uses
(:meth:`JointState.history_for`, the package docstring), the joint's kinematics, and the
data node's entries of its histories (:func:`data_values`).  The compiled kernel's
``joint_state.hpp``."""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from ...geometry import BearingGeometry
from ...history import ContactState, ImpactRecord
from ...joint import ClearanceJoint
from ...spatial import ShoulderGeometry
from .contacts import Ball, BoxCorner, Contact, Corner, Face, PlanarSlice, Slice, SlotSlice
from .film import Film, FilmInput, slice_film_input
from .kinematics import (
    FACE_SIDES,
    V3,
    Kinematics,
    ball_kinematics,
    box_corner_kinematics,
    contact_kinematics,
    corner_kinematics,
    face_kinematics,
    finite,
    journal_axis,
    leave_guide,
    rotation_xyz,
    slice_centres,
    slice_kinematics,
    slot_kinematics,
)
from .layout import STEP_CONTROL, RunStart
from .wear import CONFORMAL_DEPTH, WearState

DIVERGED = "the state became non-finite (NaN or inf); the integration diverged"


class KernelFailure(RuntimeError):
    """A joint's state cannot go on (non-finite, penetration beyond the limit)."""


class StepControl:
    """What the joint's own step control holds through a run (the compiled kernel's
    ``StepControl``): the fields of :data:`~exuclear.engine.layout.STEP_CONTROL` at their
    defaults, the run-start record's set by :meth:`JointState.start_run`; the handle reads the
    steps the joint rejected and those it could not resolve, and says so in an
    :class:`~exuclear.exceptions.AccuracyWarning`."""

    def __init__(self, runs: int = 0) -> None:
        for field in STEP_CONTROL:
            setattr(self, field.name, field.default)
        self.runs = runs

    def as_dict(self) -> dict[str, Any]:
        return {field.name: getattr(self, field.name) for field in STEP_CONTROL}


class JointState:
    """One joint's state (the compiled kernel's ``JointState``): per
    contact a :class:`ContactState` at the start and at the end of the last step, and its
    records (module docstring).

    The joint's type (``joint.geometry.joint_type``) decides its contacts.  A revolute
    joint: ``slices`` 0 for the planar joint, else the spatial joint's number of slices N;
    ``axis_journal`` the journal axis in the journal marker's frame; ``shoulders`` the
    axial clearance (section 9.6) or None.  The end faces follow the slices in every
    per-contact sequence (states, records, data).  A spherical joint: one contact, the ball
    (section 13), whose motion is the spatial joint's (its loads end as a slice's).  A
    translational (prismatic) joint: its eight corner-wall pairs (:data:`exuclear.prismatic.PAIRS`),
    in the plane normal to z, or the spatial one's 32 (:data:`exuclear.prismatic.BOX_PAIRS`),
    whose loads end as a slice's.
    """

    def __init__(self, joint: ClearanceJoint, slices: int = 0, axis_journal: Any = (0.0, 0.0, 1.0),
                 shoulders: ShoulderGeometry | None = None) -> None:
        self.spherical = joint.geometry.joint_type == "spherical"
        self.prismatic = joint.geometry.joint_type == "prismatic"
        self.planar = slices == 0 and not (self.spherical or self.prismatic)
        # the planar joint and the ball: one contact; the slider: its pairs
        self.slices = len(joint.geometry.pairs) if self.prismatic else 1 if slices == 0 else slices
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
        self.r_j, self.r_b = g.inner_radius, g.outer_radius
        if self.spherical:
            self.centres: tuple[float, ...] = ()
            self.contacts: list[Contact] = [Ball(joint)]
        elif self.prismatic:
            self.centres = ()
            self.contacts = [BoxCorner(joint) if g.spatial else Corner(joint)] * self.slices
        else:
            self.centres = slice_centres(g.length, self.slices)                           # eq. (33)
            if self.planar:  # a pin in a slot is the planar slice against the slot's centre segment
                slice_contact = SlotSlice(joint) if g.joint_type == "pin-slot" else PlanarSlice(joint)
            else:
                slice_contact = Slice(joint, 1.0 / self.slices)
            self.contacts = [slice_contact] * self.slices
        if self.shoulders is not None:
            self.contacts += [Face(joint, self.shoulders)] * len(FACE_SIDES)
        self.film = Film(joint.film, 1.0 if self.planar else 1.0 / self.slices) if joint.film is not None else None
        # the planar joint's one wear state; a spatial joint's per slice, each on its length L / N (section 11.7)
        self.wear: list[WearState] | None = None
        if joint.wear is not None:
            slice_geometry = g if self.planar else BearingGeometry(g.journal_radius, g.bearing_radius,
                                                                   g.length / self.slices)
            self.wear = [WearState(joint.wear, slice_geometry, joint.law, k) for k in range(self.slices)]

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
        for w in self.wear or ():
            w.reset()

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
        self._call_back("note")

    def tell_end(self, t: float) -> None:
        """The accepted step that reaches the run's end time (the run-start record's
        ``end_time``) tells the handle once, through the run-start callback's ``finished()``:
        Python then warns of what the whole run left unresolved (its chatter count is complete
        only now)."""
        c = self.control
        if c.finished or not t >= c.end_time * (1.0 - 1e-12):
            return
        c.finished = True
        self._call_back("finished")

    def _call_back(self, name: str) -> None:
        """Call the run-start callback's method ``name`` (a warning it issues, never an error
        that would end the run)."""
        method = getattr(self.run_start, name, None)
        if method is not None:
            try:
                method()
            except Exception:  # a warning filter that raises: the notes keep it
                pass

    # -- bookkeeping -------------------------------------------------------------------
    def wear_profiles(self, t: float, k: int = 0) -> Any:
        """The wear profiles of slice ``k`` an evaluation at time ``t`` uses (as :meth:`history_for`
        chooses the history, module docstring of :mod:`.wear`)."""
        w = self.wear[k]
        if not self.started or t < self.previous[0].time:
            return w.initial
        return w.previous if t <= self.current[0].time else w.current

    def joint_kinematics(self, displacement: Any, rotation: Any, velocity: Any, angular_velocity: Any,
                         bearing_motion: bool = True, t: float = 0.0) -> tuple[V3, V3, list[Kinematics]]:
        """The journal's centre and axis, and the kinematics of each contact: the slices
        (the planar joint's one, eqs. (1)-(8); a spatial joint's, eqs. (35)-(40)), then the
        end faces (eqs. (48)-(51)) where there is an axial clearance.  ``bearing_motion``
        False: the bearing's spin is taken as 0 (its probe is off: layout.uses_bearing_motion).
        A worn joint's slice is the contact of the worn surfaces (eqs. (75), (76)) at time ``t``.
        A spherical joint: its ball (eqs. (93)-(96)); ``u`` is then the socket frame's z axis."""
        w_j = self.omega_bearing if bearing_motion else (0.0, 0.0, 0.0)
        if self.spherical:
            p = (displacement[0], displacement[1], displacement[2])
            dv = (velocity[0], velocity[1], velocity[2])
            dw = (angular_velocity[0], angular_velocity[1], angular_velocity[2])
            return p, (0.0, 0.0, 1.0), [ball_kinematics(self.r_j, self.r_b, p, dv, dw, w_j)]
        if self.prismatic:
            g = self._joint.geometry
            half_length, half_guide = 0.5 * g.slider_length, g.half_guide
            if g.spatial:  # the box's corners against the channel's walls
                p = (displacement[0], displacement[1], displacement[2])
                a = rotation_xyz((rotation[0], rotation[1], rotation[2]))
                dv = (velocity[0], velocity[1], velocity[2])
                dw = (angular_velocity[0], angular_velocity[1], angular_velocity[2])
                kins = [leave_guide(box_corner_kinematics(half_length, self.r_j, g.half_width, self.r_b,
                                                          g.channel_half_width, corner, wall, p, a, dv, dw, w_j),
                                    half_guide) for corner, wall in g.pairs]
                return p, (0.0, 0.0, 1.0), kins
            # the slider's corners in the plane normal to z
            kins = [leave_guide(corner_kinematics(half_length, self.r_j, self.r_b, corner, wall, displacement[0],
                                                  displacement[1], rotation[2], velocity[0], velocity[1],
                                                  angular_velocity[2], w_j[2]), half_guide)
                    for corner, wall in g.pairs]
            return (displacement[0], displacement[1], 0.0), (0.0, 0.0, 1.0), kins
        if self.planar:  # the motion projected on the plane normal to the axis: eqs. (1)-(8)
            omega_j = w_j[2]
            omega_i = angular_velocity[2] + omega_j  # the journal's own spin
            g = self._joint.geometry
            if g.joint_type == "pin-slot":  # the pin against the slot's centre segment (exuclear/slot.py)
                kin = slot_kinematics(g, 0.5 * g.slot_length, displacement[0], displacement[1], velocity[0],
                                      velocity[1], omega_i, omega_j)
            else:
                kin = contact_kinematics(g, displacement[0], displacement[1], velocity[0], velocity[1], omega_i, 0.0,
                                         0.0, 0.0, 0.0, omega_j)
            if self.wear is not None:
                kin = self.wear[0].kinematics(self.wear_profiles(t), kin, rotation[2], velocity[0], velocity[1],
                                              omega_i, omega_j)
            if self.film is not None:
                self.film_inputs = [FilmInput(displacement[0], displacement[1], velocity[0], velocity[1], omega_i,
                                              omega_j)]
            return (displacement[0], displacement[1], 0.0), (0.0, 0.0, 1.0), [kin]
        p = (displacement[0], displacement[1], displacement[2])
        u = journal_axis((rotation[0], rotation[1], rotation[2]), self.axis_journal)      # eq. (34)
        dv = (velocity[0], velocity[1], velocity[2])
        dw = (angular_velocity[0], angular_velocity[1], angular_velocity[2])
        kins: list[Kinematics] = [slice_kinematics(self.r_j, self.r_b, z, p, u, dv, dw, w_j) for z in self.centres]
        if self.wear is not None:  # each slice's worn contact in its plane, psi its turn about the axis (section 11.7)
            kins = [w.slice_kinematics(self.wear_profiles(t, k), kin, rotation[2], p, u, dv, dw, w_j)
                    for k, (w, kin) in enumerate(zip(self.wear, kins))]
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
            for w in self.wear or ():
                w.reset()
            self.current = tuple(ContactState(time=t).accept(c.accepted(k), c, t)[0]
                                 for k, c in zip(kins, self.contacts))
            if self.film is not None:
                films = [self.film.with_outputs(c, k) for c, k in zip(self.current, self.film_inputs)]
                self.current = (*films, *self.current[len(films):])
            self.previous = self.initial = self.current
            self.started = True
            if not all(finite(k) for k in kins):
                self._fail(DIVERGED, t)
            if self.control.refusal:  # e.g. a journal outside its bearing
                self._fail(self.control.refusal, t)
        return self.previous if t <= self.current[0].time else self.current

    def accept_wear(self, advance: bool, kins: list[Kinematics], psi: float, states: Any, h: float, t: float) -> None:
        """The wear of an accepted step of length ``h`` [s] ending at ``t`` in the states ``kins``
        with the contacts' ``states`` (their normal forces; ``advance``: a new step, else one
        computed again, as in ``post_newton``), slice by slice: each with its slip, ``|v_t| h``
        (planar) or ``|v_s| h`` (a spatial slice, eq. (42)), and its normal force; stops the
        run where a profile's update would be unstable (eq. (81))."""
        for k, (wear, kin, state) in enumerate(zip(self.wear, kins, states)):
            slip = (abs(kin.v_t) if self.planar else kin.speed) * h
            base = wear.current if advance else wear.previous
            new = wear.accept(base, kin, psi, state.normal_force, slip)
            if advance:
                wear.previous = wear.current
            wear.current = new
            why = wear.unstable(slip, h, "" if self.planar else f" of slice {k}")
            if why:
                self._fail(why, t)

    def in_worn_contact(self, states: Any) -> bool:
        """Whether a slice is in contact on profiles deeper than CONFORMAL_DEPTH of its
        penetration (its contact conformal, section 11.1)."""
        return self.wear is not None and any(s.in_contact and w.current.worn
                                             and w.current.deepest > CONFORMAL_DEPTH * s.delta
                                             for w, s in zip(self.wear, states))

    def data_values(self, t: float, u: Any, axial: float, states: Any) -> list[float]:
        """The data node's entries for the contacts' ``states``: :func:`data_values` of the
        one slice for the planar joint, :func:`spatial_data_values` for the spatial joint,
        :func:`data_values` and the ball's ``ecc_z`` (``axial``) for the spherical joint."""
        lubricated = self.film is not None
        if self.spherical:
            return [*data_values(states[0]), axial]
        if self.prismatic:
            return pair_data_values(t, states)
        if self.planar:
            return data_values(states[0], lubricated)
        return spatial_data_values(t, u, axial, states, self.slices if lubricated else 0)



def data_values(s: ContactState, lubricated: bool = False) -> list[float]:
    """The data node's entries (layout.DATA_COLUMNS; then layout.FILM_DATA_COLUMNS where
    the joint is ``lubricated``) for a state."""
    film = [s.film_fx, s.film_fy, s.film_torque] if lubricated else []
    return [s.time, 0.0 if s.delta == float("-inf") else s.delta, s.delta_dot, s.ecc_x, s.ecc_y, s.normal_force,
            s.tangential_force, s.slip_velocity, s.v0, 1.0 if s.in_contact else 0.0, float(s.onsets), s.onset_time,
            s.peak_force, s.max_penetration, *film]


def pair_data_values(t: float, states: Any) -> list[float]:
    """The translational joint's data-node entries (layout.pair_data_columns): time, then each
    corner-wall pair's ``data_values`` without the time."""
    out = [t]
    for s in states:
        out.extend(data_values(s)[1:])
    return out


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
