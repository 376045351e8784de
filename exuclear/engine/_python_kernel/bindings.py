"""The functions Exudyn calls (:class:`JointKernel`): ``force_torque`` (the connector's force),
``post_newton`` (the history update once per accepted step) and the bearing probe's and
torque connector's.  The compiled kernel's ``bindings.cpp``."""
from __future__ import annotations

import math
from typing import Any

from .joint_state import DIVERGED
from .kinematics import finish_loads, finite
from .layout import read
from .step_control import REDO_STEP_ERROR, JointStepControl


class JointKernel(JointStepControl):
    """One joint's user functions (the compiled kernel's ``force_torque`` and ``post_newton``)
    over its state (:class:`~.joint_state.JointState`) and step control
    (:class:`~.step_control.JointStepControl`); the package docstring says which history an
    evaluation uses."""

    def force_torque(self, mbs: Any, t: float, item: int, displacement: Any, rotation: Any, velocity: Any,
                     angular_velocity: Any, stiffness: Any, damping: Any, rot0: Any, rot1: Any, offset: Any) -> list:
        """``springForceTorqueUserFunction`` of the joint's connector: ``[F; T]`` in J0, F the
        force on the bearing, T minus the journal's moment about its marker point
        (docs/physics.md eqs. (41)-(45), (54); the planar eqs. (24)-(26))."""
        p, u, kins = self.joint_kinematics(displacement, rotation, velocity, angular_velocity,
                                           read(stiffness, "bearing_motion") != 0.0, t)
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
        p, u, kins = self.joint_kinematics(displacement, rotation, velocity, angular_velocity,
                                           read(stiffness, "bearing_motion") != 0.0, t)
        self.history_for(kins, t, u, p[2])
        advance = t > self.current[0].time
        base = self.current if advance else self.previous  # a repeated step starts again from its start
        if not all(finite(k) for k in kins):
            self._fail(DIVERGED, t)
        redo = self.impact_redo(kins, base, t, impact_step) \
            or self.step_control(kins, base, t, max_penetration, read(stiffness, "rate_limit"), impact_step)
        if redo > 0.0:
            self.steer_jacobian(math.inf)  # a step of another length: a Jacobian for it
            return [REDO_STEP_ERROR, redo, *data]
        states = self._accept_all(base, kins, t)
        if self.wear is not None:
            self.accept_wear(advance, kins, rotation[2], states, t - base[0].time, t)
        # the step before this one: free flight must have lasted both (a repeated step: unknown)
        before = self.previous if advance else None
        allow = self.step_growth(before, base, states, t, read(stiffness, "rate_limit"))
        if advance:
            self.previous = self.current
        self.current = states
        h = t - base[0].time
        switched = any(b.in_contact != s.in_contact for b, s in zip(base, states))  # a contact's stiffness came or went
        self.count_separations(advance, sum(1 for b, s in zip(base, states) if b.in_contact and not s.in_contact), h)
        self.tell_end(t)
        conformal = self.in_worn_contact(states)
        self.steer_jacobian(math.inf if switched else h, conformal)
        self.report_growth(mbs, t, allow, h)
        return [0.0, -1.0, *self.data_values(t, u, p[2], states)]
