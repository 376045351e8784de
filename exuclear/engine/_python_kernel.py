"""The Python kernel: the clearance joint's Exudyn user functions, written in Python.

This is the readable statement of what the compiled kernel
(``exuclear/_kernel/clearance_kernel.cpp``) computes: the physics comes from
:mod:`exuclear.geometry`, :mod:`exuclear.contact`, :mod:`exuclear.friction` and
:mod:`exuclear.history`, and this module adds only the bookkeeping that Exudyn's calling
pattern needs.  It is also the path for laws written in Python.

Which history an evaluation uses.  Exudyn evaluates forces many times per step (Runge-
Kutta stages, Newton iterations, Jacobian perturbations, rejected attempts) and calls the
post-Newton function once the step's state is final.  A joint keeps the history at the
start (``previous``) and at the end (``current``) of the last step it post-processed:

- an evaluation at a time after ``current.time`` belongs to a new step: ``current``;
- one at or before ``current.time`` belongs to a step computed again (a discontinuous
  iteration, a step redone with a smaller size): ``previous``;
- one before ``previous.time`` starts a new run (``mbs.SolveDynamic`` from the initial
  state): the history is forgotten and this evaluation's state, the run's initial state,
  is accepted.  Exudyn's first evaluation of a run is at the initial state.
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

from ..geometry import ContactKinematics, contact_kinematics
from ..history import ContactState, ImpactRecord
from ..joint import ClearanceJoint
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
    journal_axis,
    slice_centres,
    slice_friction,
    slice_kinematics,
)

#: Error a post-Newton function returns to make Exudyn redo a step: anything above
#: Exudyn's ``discontinuous.iterationTolerance`` (default 1).
REDO_STEP_ERROR = 1e3
#: Relative slack on a step length compared with the impact step (Exudyn's steps carry round-off).
STEP_SLACK = 1e-9


class KernelFailure(RuntimeError):
    """A joint's state cannot go on (non-finite, penetration beyond the limit)."""


class _Failing:
    """What both kernels do when a run cannot go on: record why and when, and raise
    (the compiled kernel's ``fail``)."""

    failure: str
    failure_time: float

    def _fail(self, message: str, t: float) -> None:
        self.failure, self.failure_time = message, t
        raise KernelFailure(f"exuclear: {message}")

    def _check_force(self, state: ContactState, t: float) -> None:
        if not math.isfinite(state.normal_force):
            self._fail("the contact force became non-finite (NaN or inf)", t)


class PythonJointKernel(_Failing):
    """One joint's user functions and table entry; the compiled kernel's ``JointState``."""

    def __init__(self, joint: ClearanceJoint) -> None:
        self.joint = joint
        self.reset()

    def reset(self) -> None:
        self.started = False
        self.previous = self.current = self.initial = ContactState()
        self.records: list[ImpactRecord] = []
        self.omega_bearing = 0.0
        self.torque_correction = 0.0
        self.failure, self.failure_time = "", 0.0

    # -- bookkeeping -------------------------------------------------------------------
    def _kinematics(self, displacement: Any, velocity: Any, angular_velocity: Any) -> ContactKinematics:
        omega_j = self.omega_bearing
        omega_i = angular_velocity[2] + omega_j
        return contact_kinematics(self.joint.geometry, displacement[0], displacement[1], velocity[0], velocity[1],
                                  omega_i, 0.0, 0.0, 0.0, 0.0, omega_j)

    def history_for(self, kin: ContactKinematics, t: float) -> ContactState:
        """The history an evaluation at time ``t`` uses (module docstring)."""
        if not self.started or t < self.previous.time:
            self.records = []
            self.failure = ""
            self.current, _ = ContactState(time=t).accept(kin, self.joint, t)
            self.previous = self.initial = self.current
            self.started = True
            if not _finite(kin):
                self._fail("the state became non-finite (NaN or inf); the integration diverged", t)
        return self.previous if t <= self.current.time else self.current

    # -- Exudyn user functions ---------------------------------------------------------
    def force_torque(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
                     angular_velocity: Any, stiffness: Any, damping: Any, rot0: Any, rot1: Any, offset: Any) -> list:
        """``springForceTorqueUserFunction`` of the joint's connector: ``[F; T]`` in the
        bearing's joint frame, F = -F_i and T = -M_i (docs/physics.md eqs. (24)-(26))."""
        kin = self._kinematics(displacement, velocity, angular_velocity)
        history = self.history_for(kin, t)
        if kin.delta <= 0.0:
            self.torque_correction = 0.0
            return [0.0] * 6
        loads = self.joint.response(kin, history).loads
        self.torque_correction = loads.m_j + loads.m_i  # the bearing's moment beyond -M_i
        return [-loads.fx, -loads.fy, 0.0, 0.0, 0.0, -loads.m_i]

    def probe(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
              angular_velocity: Any, *parameters: Any) -> list:
        """The bearing-spin probe (marker 0 the bearing, marker 1 the ground): records the
        bearing's angular velocity about the axis; applies nothing."""
        self.omega_bearing = -angular_velocity[2]
        return [0.0] * 6

    def torque(self, mbs: Any, t: float, item: int, *arguments: Any) -> list:
        """The bearing-torque connector: the bearing's moment beyond what the joint applies."""
        return [0.0, 0.0, 0.0, 0.0, 0.0, self.torque_correction]

    def probe_post_newton(self, mbs: Any, t: float, item: int, data: Any, displacement: Any, rotation: Any,
                          velocity: Any, angular_velocity: Any, *parameters: Any) -> list:
        self.omega_bearing = -angular_velocity[2]
        return [0.0, -1.0, *data]

    def post_newton(self, mbs: Any, t: float, item: int, data: Any, displacement: Any, rotation: Any, velocity: Any,
                    angular_velocity: Any, stiffness: Any, *parameters: Any) -> list:
        """``postNewtonStepUserFunction``: the history update, once per accepted step.
        Returns ``[error, recommended step, data...]``."""
        max_penetration, impact_step = stiffness[0][4], stiffness[0][5]
        kin = self._kinematics(displacement, velocity, angular_velocity)
        self.history_for(kin, t)
        advance = t > self.current.time
        base = self.current if advance else self.previous  # a repeated step starts again from its start
        if not _finite(kin):
            self._fail("the state became non-finite (NaN or inf); the integration diverged", t)
        if kin.delta > max_penetration:
            self._fail(f"penetration {kin.delta:.4g} m exceeds the limit {max_penetration:.4g} m", t)
        if (impact_step > 0.0 and not base.in_contact and kin.delta > 0.0
                and t - base.time > impact_step * (1.0 + STEP_SLACK)):
            return [REDO_STEP_ERROR, impact_step, *data]  # a contact begins in a long step: redo it
        del self.records[base.closed:]
        state, record = base.accept(kin, self.joint, t)
        if record is not None:
            self.records.append(record)
        self._check_force(state, t)
        if advance:
            self.previous = self.current
        self.current = state
        return [0.0, -1.0, *data_values(state)]



def _finite(kin: ContactKinematics | SliceKinematics) -> bool:
    return all(math.isfinite(v) for v in (kin.ex, kin.ey, kin.delta_dot, kin.v_t))


def data_values(s: ContactState) -> list[float]:
    """The data node's entries (layout.DATA_COLUMNS) for a state."""
    return [s.time, 0.0 if s.delta == float("-inf") else s.delta, s.delta_dot, s.ecc_x, s.ecc_y, s.normal_force,
            s.tangential_force, s.slip_velocity, s.v0, 1.0 if s.in_contact else 0.0, float(s.onsets), s.onset_time,
            s.peak_force, s.max_penetration]


# -- the spatial joint (docs/physics.md section 9) -------------------------------------------
class _ScaledLaw:
    """A slice's share ``w / L`` of the joint's contact law (eq. (41))."""

    def __init__(self, law: Any, share: float) -> None:
        self.law, self.share = law, share

    def normal_force(self, delta: float, delta_dot: float, v0: float) -> float:
        return self.share * self.law.normal_force(delta, delta_dot, v0)


class _SliceResponse(NamedTuple):
    f_n: float
    f_t: float
    v0: float


class _SliceJoint:
    """What :meth:`ContactState.accept` reads of a joint, for one slice: its share of the
    law, and the joint's friction law (applied to the slip speed, eq. (42)); ``response``
    gives the slice's force magnitudes as :meth:`ClearanceJoint.response` does a joint's."""

    def __init__(self, joint: ClearanceJoint, share: float) -> None:
        self.law, self.friction = _ScaledLaw(joint.law, share), joint.friction

    def response(self, kin: Any, history: ContactState) -> _SliceResponse:
        if kin.delta <= 0.0:
            return _SliceResponse(0.0, 0.0, history.v0 if history.in_contact else 0.0)
        v0 = history.onset_velocity(kin.delta, kin.delta_dot)
        f_n = self.law.normal_force(kin.delta, kin.delta_dot, v0)
        f_t = self.friction.coefficient(kin.v_t) * f_n if self.friction.active else 0.0
        return _SliceResponse(f_n, f_t, v0)


class _SliceAccepted(NamedTuple):
    """A slice's kinematics as :meth:`ContactState.accept` reads them; ``v_t`` is the slip
    speed ``|v_s|`` (the slice records friction magnitudes)."""

    delta: float
    delta_dot: float
    ex: float
    ey: float
    v_t: float


def _accepted(kin: SliceKinematics | FaceKinematics) -> _SliceAccepted:
    if isinstance(kin, FaceKinematics):  # an end face records its signed circumferential slip
        return _SliceAccepted(kin.delta, kin.delta_dot, kin.ex, kin.ey, kin.v_t)
    return _SliceAccepted(kin.delta, kin.delta_dot, kin.ex, kin.ey, kin.speed)


class _FaceLaw:
    """An end face's contact law, eq. (53): ``K_f delta`` with the joint law's ``D`` and ``v_min``."""

    def __init__(self, law: Any, k_face: float) -> None:
        self.k_face, self.damping_factor, self.v_min = k_face, law.damping_factor, law.v_min

    def normal_force(self, delta: float, delta_dot: float, v0: float) -> float:
        return face_normal_force(self.k_face, self.damping_factor, self.v_min, delta, delta_dot, v0)


class _FaceJoint(_SliceJoint):
    """What :meth:`ContactState.accept` reads of a joint, for one end face: the face law
    and the joint's friction law applied to the circumferential slip (eq. (53))."""

    def __init__(self, joint: ClearanceJoint, k_face: float) -> None:
        self.law, self.friction = _FaceLaw(joint.law, k_face), joint.friction


class SpatialJointKernel(_Failing):
    """The spatial joint's user functions: one :class:`ContactState` per slice, with the
    planar joint's history rules (module docstring) applied to all slices at once.

    ``slices`` N, ``axis_journal`` the journal axis in the journal marker's frame;
    ``shoulders`` the axial clearance (section 9.6) or None.  With shoulders, the two end
    faces follow the slices in every per-contact sequence (states, records, data).
    """

    def __init__(self, joint: ClearanceJoint, slices: int, axis_journal: Any,
                 shoulders: ShoulderGeometry | None = None) -> None:
        self.slices = slices
        self.axis_journal = tuple(float(v) for v in axis_journal)
        self.shoulders = shoulders
        self.contacts = slices + (len(FACE_SIDES) if shoulders is not None else 0)
        self.joint = joint
        self.reset()

    @property
    def joint(self) -> ClearanceJoint:
        return self._joint

    @joint.setter
    def joint(self, joint: ClearanceJoint) -> None:
        g = joint.geometry
        self._joint = joint
        self.centres = slice_centres(g.length, self.slices)
        self.share = 1.0 / self.slices  # w / L, eq. (41)
        self.slice_joint = _SliceJoint(joint, self.share)
        self.contact_joints = [self.slice_joint] * self.slices
        if self.shoulders is not None:
            self.friction_radius = self.shoulders.friction_radius                              # eq. (51)
            self.face_law = _FaceLaw(joint.law, self.shoulders.face_stiffness(joint.law.E_star))  # eq. (52)
            self.contact_joints += [_FaceJoint(joint, self.face_law.k_face)] * len(FACE_SIDES)

    def reset(self) -> None:
        self.started = False
        empty = tuple(ContactState() for _ in range(self.contacts))
        self.previous = self.current = self.initial = empty
        self.records: list[list[ImpactRecord]] = [[] for _ in range(self.contacts)]
        self.omega_bearing = (0.0, 0.0, 0.0)
        self.torque_correction = (0.0, 0.0, 0.0)
        self.initial_axis, self.initial_axial = (0.0, 0.0, 1.0), 0.0
        self.failure, self.failure_time = "", 0.0

    # -- bookkeeping -------------------------------------------------------------------
    def _kinematics(self, displacement: Any, rotation: Any, velocity: Any, angular_velocity: Any
                    ) -> tuple[V3, V3, list[SliceKinematics | FaceKinematics]]:
        """The journal's centre and axis, and the kinematics of each contact: the slices,
        then the end faces (eqs. (48)-(51)) where there is an axial clearance."""
        g = self._joint.geometry
        p = (displacement[0], displacement[1], displacement[2])
        u = journal_axis((rotation[0], rotation[1], rotation[2]), self.axis_journal)     # eq. (34)
        dv = (velocity[0], velocity[1], velocity[2])
        dw = (angular_velocity[0], angular_velocity[1], angular_velocity[2])
        kins: list[SliceKinematics | FaceKinematics] = [
            slice_kinematics(g.journal_radius, g.bearing_radius, z, p, u, dv, dw, self.omega_bearing)
            for z in self.centres]
        if self.shoulders is not None:
            play = self.shoulders.axial_clearance
            kins += [face_kinematics(g.length, play, self.friction_radius, side, p, u, dv, dw, self.omega_bearing)
                     for side in FACE_SIDES]
        return p, u, kins

    def history_for(self, kins: list[SliceKinematics], t: float, u: V3, axial: float) -> tuple[ContactState, ...]:
        """The slices' history an evaluation at time ``t`` uses (the planar rules); ``u``,
        ``axial``: the journal's axis and axial displacement, kept for the initial outputs."""
        if not self.started or t < self.previous[0].time:
            self.initial_axis, self.initial_axial = u, axial
            self.records = [[] for _ in range(self.contacts)]
            self.failure = ""
            self.current = tuple(ContactState(time=t).accept(_accepted(k), j, t)[0]
                                 for k, j in zip(kins, self.contact_joints))
            self.previous = self.initial = self.current
            self.started = True
            if not all(_finite(k) for k in kins):
                self._fail("the state became non-finite (NaN or inf); the integration diverged", t)
        return self.previous if t <= self.current[0].time else self.current

    # -- Exudyn user functions ---------------------------------------------------------
    def force_torque(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
                     angular_velocity: Any, stiffness: Any, damping: Any, rot0: Any, rot1: Any, offset: Any) -> list:
        """``[F; T]`` in J0: F the force on the bearing, T minus the journal's moment about
        its marker point (docs/physics.md eqs. (41)-(45))."""
        p, u, kins = self._kinematics(displacement, rotation, velocity, angular_velocity)
        history = self.history_for(kins, t, u, p[2])
        joint, r_j = self._joint, self._joint.geometry.journal_radius
        loads = [0.0] * 9
        for kin, h in zip(kins[:self.slices], history):
            if kin.delta <= 0.0:
                continue
            v0 = h.onset_velocity(kin.delta, kin.delta_dot)
            f_n = self.share * joint.law.normal_force(kin.delta, kin.delta_dot, v0)                  # eq. (41)
            mu = joint.friction.coefficient(kin.speed) if joint.friction.active else 0.0
            f_t, f_a = slice_friction(mu, f_n, kin)                                                  # eq. (42)
            add_slice_loads(loads, r_j, u, kin, f_n, f_t, f_a)
        for kin, h in zip(kins[self.slices:], history[self.slices:]):  # the end faces, section 9.6
            if kin.delta <= 0.0:
                continue
            v0 = h.onset_velocity(kin.delta, kin.delta_dot)
            f_n = self.face_law.normal_force(kin.delta, kin.delta_dot, v0)                           # eq. (53)
            f_t = joint.friction.coefficient(kin.v_t) * f_n if joint.friction.active else 0.0        # eq. (53)
            add_face_loads(loads, self.friction_radius, u, kin, f_n, f_t)                            # eq. (54)
        total = finish_loads(loads, p)
        self.torque_correction = total.correction
        return [*total.force, *total.torque]

    def probe(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
              angular_velocity: Any, *parameters: Any) -> list:
        """The bearing-spin probe: records the bearing's angular velocity (J0); applies nothing."""
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
        """The slices' history update, once per accepted step; ``[error, step, data...]``."""
        max_penetration, impact_step = stiffness[0][4], stiffness[0][5]
        p, u, kins = self._kinematics(displacement, rotation, velocity, angular_velocity)
        self.history_for(kins, t, u, p[2])
        advance = t > self.current[0].time
        base = self.current if advance else self.previous
        if not all(_finite(k) for k in kins):
            self._fail("the state became non-finite (NaN or inf); the integration diverged", t)
        deepest = max(k.delta for k in kins)
        if deepest > max_penetration:
            self._fail(f"penetration {deepest:.4g} m exceeds the limit {max_penetration:.4g} m", t)
        if impact_step > 0.0 and t - base[0].time > impact_step * (1.0 + STEP_SLACK) and any(
                not b.in_contact and k.delta > 0.0 for k, b in zip(kins, base)):
            return [REDO_STEP_ERROR, impact_step, *data]  # a contact begins in a long step: redo it
        states = []
        for k, (kin, b, j) in enumerate(zip(kins, base, self.contact_joints)):
            del self.records[k][b.closed:]
            state, record = b.accept(_accepted(kin), j, t)
            if record is not None:
                self.records[k].append(record)
            self._check_force(state, t)
            states.append(state)
        if advance:
            self.previous = self.current
        self.current = tuple(states)
        return [0.0, -1.0, *spatial_data_values(t, u, p[2], self.current)]



def spatial_data_values(t: float, u: Any, axial: float, states: Any) -> list[float]:
    """The spatial data node's entries (layout.spatial_data_columns): time, journal axis
    x, y (tilt, rad for small angles), axial displacement, then each slice's
    ``data_values`` without the time (with an axial clearance, the two end faces follow)."""
    out = [t, u[0], u[1], axial]
    for s in states:
        out.extend(data_values(s)[1:])
    return out
