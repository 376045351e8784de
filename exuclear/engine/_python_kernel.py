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
from typing import Any

from ..geometry import ContactKinematics, contact_kinematics, joint_loads
from ..history import ContactState, ImpactRecord
from ..joint import ClearanceJoint

#: Error a post-Newton function returns to make Exudyn redo a step: anything above
#: Exudyn's ``discontinuous.iterationTolerance`` (default 1).
REDO_STEP_ERROR = 1e3
#: Relative slack on a step length compared with the impact step (Exudyn's steps carry round-off).
STEP_SLACK = 1e-9


class KernelFailure(RuntimeError):
    """A joint's state cannot go on (non-finite, penetration beyond the limit)."""


class PythonJointKernel:
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
        v0 = history.onset_velocity(kin.delta, kin.delta_dot)
        joint = self.joint
        f_n = joint.law.normal_force(kin.delta, kin.delta_dot, v0)
        f_t = joint.friction.coefficient(kin.v_t) * f_n if joint.friction.active else 0.0
        loads = joint_loads(joint.geometry, kin, f_n, f_t)
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
        if state.normal_force != state.normal_force or abs(state.normal_force) == float("inf"):
            self._fail("the contact force became non-finite (NaN or inf)", t)
        if advance:
            self.previous = self.current
        self.current = state
        return [0.0, -1.0, *data_values(state)]

    def _fail(self, message: str, t: float) -> None:
        self.failure, self.failure_time = message, t
        raise KernelFailure(f"exuclear: {message}")


def _finite(kin: ContactKinematics) -> bool:
    return all(math.isfinite(v) for v in (kin.ex, kin.ey, kin.delta_dot, kin.v_t))


def data_values(s: ContactState) -> list[float]:
    """The data node's entries (layout.DATA_COLUMNS) for a state."""
    return [s.time, 0.0 if s.delta == float("-inf") else s.delta, s.delta_dot, s.ecc_x, s.ecc_y, s.normal_force,
            s.tangential_force, s.slip_velocity, s.v0, 1.0 if s.in_contact else 0.0, float(s.onsets), s.onset_time,
            s.peak_force, s.max_penetration]
