"""The joint's contact mode (``contact_mode`` of :func:`~exuclear.engine.connector.CreateClearanceJoint`).

- ``"compliant"`` (the default): the contact law at every step.
- ``"follow"``: the opt-in prototype of issue 34 (docs/guide/contact_following.md, which
  says what was tried for each choice and what it measured).  The planar joint, dry and
  unworn, with implicit solvers only (the condition is an algebraic equation) that damp its
  step-to-step mode (FOLLOW_MAX_RHO; elsewhere it stays compliant and says so);
  ``handle.follow_counts()`` says what it did.  On the compiled kernel where the joint is
  between rigid bodies (2D, or 3D with Euler parameters, Tait-Bryan angles or a Lie-group
  rotation vector), their nodes' own markers or the ground (:func:`compiled_refusal`; its
  ``following.hpp`` takes the same decisions, :class:`CompiledEvents` is its way to Exudyn),
  else on the Python kernel.

The following mode (:class:`FollowState` in the Python kernel's ``following.py``, held by the
Python kernel's joint, which calls it from its force and post-Newton functions):

- **Switching on.** A contact that has lasted FOLLOW_MIN_STEPS accepted steps and
  FOLLOW_PERIODS contact periods, at steps of at least FOLLOW_STEP contact periods, with a
  penetration rate below FOLLOW_RATE ``v_min`` and a normal that turned by less than
  FOLLOW_TURN over the step, is handed to a condition (CONDITION) that holds ``|e| = d``,
  ``d`` set to the present ``|e|`` so that the switch is no impulse (an Exudyn constraint
  switched on in an inconsistent state corrects it by an impulse: a mass point 1 mm beyond
  a distance constraint, switched on, drew 15.5 kN, then -358 kN, where its physical force is 1-30 N).
- **The condition.** :class:`VelocityCondition` (the kept one): the normal rate at velocity
  level, ``n . (v_journal - v_bearing) = r``, in the normal predicted for the step's end,
  its rows set again at the step Exudyn actually takes; the rate ``r`` brings ``|e|`` back
  to ``d``.  :class:`DistanceCondition` (dropped): ``|e| = d`` at position level, whose
  index-3 multiplier oscillates from step to step.
- **While it holds.** The compliant normal force is not applied; the condition's multiplier
  ``lambda`` is the normal force; friction acts from it (FRICTION_FROM); the distance
  follows ``c + delta(lambda)``, the law's penetration at that force (with its damping at
  the rate it asks, DAMPED_TARGET), with a loop gain below 1 (FOLLOW_GAIN).
- **Release.** Where the low-passed multiplier turns tensile (RELEASE_FILTERED; or the
  multiplier itself, the step redone to end there, RELEASE_REDO), or where the slip comes
  within STICK_MARGIN of the friction law's smoothing band.  A step on which ``|e|`` left
  ``d`` by more than FOLLOW_HOLD of the penetration (FOLLOW_HOLD_FRICTION with friction) is
  redone at half its length (HOLD_REDOS times at most); then the contact is let go
  (``lost``) and stays compliant until it ends.
- **Exudyn.** The flag ``activeConnector`` and the condition's parameters are set from the
  joint's post-Newton function at an accepted step (and its rows from the force function
  where the step differs); each switch requests a Jacobian, and Newton's absolute tolerance
  is scaled to the penetration while the condition holds.  On the compiled kernel the joint's
  own connector is off while the condition holds (its load is zero then, but Exudyn would
  evaluate it at each Newton iterate and differentiate it numerically at each Jacobian), and
  a carrier between two ground markers runs the joint's post-Newton function
  (:func:`_add_carrier`).
"""
from __future__ import annotations

import warnings
import weakref
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    ObjectConnectorRigidBodySpringDamper,
    ObjectGround,
    VObjectConnectorRigidBodySpringDamper,
    VObjectGround,
)

from ..checks import check_choice
from ..exceptions import AccuracyWarning
from ..joint import ClearanceJoint
from . import kernel
from ._python_kernel.following import CONDITION, FollowState
from .follow_conditions import CompiledCondition, DistanceCondition, VelocityCondition, compiled_sides

#: How the joint carries a sustained contact.
CONTACT_MODES = {"compliant": "the compliant contact law at every step (the default)",
                 "follow": "a sustained contact carried by a velocity-level condition at the law's penetration "
                           "(opt-in prototype: planar dry joint, implicit solvers; compiled between rigid "
                           "bodies)"}

#: The mode of a joint built without ``contact_mode`` ("compliant").  A study sets it to
#: "follow" for a whole model's joints (validation/contact_follow.py); a joint whose mode
#: comes from here runs on the Python kernel where the compiled one cannot follow it
#: (:func:`compiled_refusal`), whatever its ``backend`` asks.
DEFAULT_CONTACT_MODE = "compliant"



def compiled_refusal(mbs: exu.MainSystem, markers: list[int]) -> str:
    """Why the compiled kernel cannot follow this joint ("" where it can): its following mode
    (``following.hpp``) is for a joint between rigid bodies (2D, or 3D with Euler parameters,
    Tait-Bryan angles or a Lie-group rotation vector), their nodes' own markers (a beam's node)
    or the ground, with the compiled kernel called without Python."""
    if kernel.STATUS != kernel.STATUS_DIRECT:
        return f"the compiled kernel is not available ({kernel.STATUS})"
    if compiled_sides(mbs, markers) is None:
        return ("a marker is not on a 2D rigid body (ObjectRigidBody2D), a 3D one (NodeRigidBodyEP, "
                "NodeRigidBodyRxyz or NodeRigidBodyRotVecLG), such a node's own MarkerNodeRigid or the ground")
    return ""


def resolve(contact_mode: str | None, joint: ClearanceJoint, slices: int | None, backend: str | None,
            mbs: exu.MainSystem, markers: list[int]) -> tuple[str, str | None]:
    """The joint's mode (``contact_mode``, or :data:`DEFAULT_CONTACT_MODE` where None) and its
    backend: for the following mode the compiled kernel where it can follow the joint
    (:func:`compiled_refusal`) and ``backend`` does not ask for Python, else Python; refuses,
    with the reason, what the following mode's prototype does not cover yet."""
    inherited = contact_mode is None
    mode = check_choice("contact_mode", DEFAULT_CONTACT_MODE if inherited else contact_mode, CONTACT_MODES)
    if mode != "follow":
        return mode, backend
    if slices:
        raise ValueError("contact_mode='follow' is for the planar joint only so far (no `slices`)")
    if joint.film is not None or joint.wear is not None:
        raise ValueError("contact_mode='follow' is for a dry joint without wear so far")
    refusal = compiled_refusal(mbs, markers) if backend != "python" else "backend='python'"
    if backend == "compiled" and refusal and not inherited:
        raise ValueError(f"contact_mode='follow' runs on the compiled kernel only for a joint between "
                         f"rigid bodies or the ground so far, and here {refusal}: give backend='python' or none")
    # a prototype whose paths are not yet right in every model: said where it is chosen
    warnings.warn("contact_mode='follow' is a prototype (docs/guide/contact_following.md): over seconds it is as near "
                  "a converged run as the compliant contact where the motion is regular and frictionless, but with "
                  "friction it dissipated 2.4 to 3.4 % less than a converged run on the compiled kernel, and on the "
                  "Python kernel one run in six dissipated 15 % less with peak forces 3.5 times the converged run's "
                  "(the zoo's 2D double pendulum over 10 s), and on the Python kernel the 3D double pendulum's path "
                  "ended 2.4 c off where the compliant contact's is 0.12 c (0.5 s at twice its example's step); it "
                  "carries the load but not the "
                  "contact's own vibration about it (the gallery's pendulum: 0.02 N RMS where compliant runs at 4 to 64 "
                  "times its steps have 3.1 to 3.8 N at 235 Hz); it saves Newton iterations, not steps; compare a run "
                  "with the compliant contact before trusting it", AccuracyWarning, stacklevel=4)
    return mode, "python" if refusal else "compiled"


class CompiledEvents:
    """What the compiled kernel's following mode (``following.hpp``) asks of Python: the
    condition's multiplier once per followed step, and at events the switch, Newton's
    tolerance, the integrator's damping and a new run.  Exudyn's side of these is
    :class:`FollowState`'s, whose per-step decisions the kernel takes itself.  Holds its
    system weakly, as the run-start callback does."""

    def __init__(self, mbs: exu.MainSystem, follow: FollowState, joint: int, carrier: int) -> None:
        self._mbs, self.follow = weakref.ref(mbs), follow
        self._joint, self._carrier = joint, carrier

    def _carry(self, mbs: exu.MainSystem, followed: bool) -> None:
        """While the condition holds the contact the joint's connector is off, and its carrier
        (:func:`add_constraint`) runs the joint's post-Newton function: Exudyn then neither
        evaluates the joint's (zero) load at each Newton iterate nor differentiates it
        numerically at each Jacobian."""
        mbs.SetObjectParameter(self._joint, "activeConnector", not followed)
        mbs.SetObjectParameter(self._carrier, "activeConnector", followed)

    def multiplier(self) -> float:
        mbs = self._mbs()
        return self.follow.read_multiplier(mbs) if mbs is not None else 0.0

    def switch(self, active: bool) -> None:
        mbs = self._mbs()
        if mbs is None:
            return
        self.follow._set(mbs, active)
        self._carry(mbs, active)
        if not active:
            self.follow._restore_tolerance(mbs)

    def tolerance(self, delta: float, force: float) -> None:
        mbs = self._mbs()
        if mbs is not None:
            self.follow._tolerance(mbs, delta, force)

    def damped(self) -> bool:
        """Whether the run's integrator damps the condition's step-to-step mode (says where not)."""
        mbs = self._mbs()
        if mbs is not None:
            self.follow._check_damping(mbs)
        return not self.follow.undamped

    def guess_share(self) -> float:
        """The share ``k`` of ``h^2 a_1`` (the end acceleration ``a_1``) in the end position that
        Exudyn's first Newton iterate leaves out (it takes ``a_1 = 0``; CSolverImplicitSecondOrder's
        initial update): ``beta (1 - alpha_f) / (1 - alpha_m)`` of the solver's generalized-alpha
        (Newmark: ``alpha_f = alpha_m = 0``); 0 where the solver is not known (the kernel then
        takes the first iterate as it is)."""
        mbs = self._mbs()
        solver = getattr(mbs, "sys", {}).get("dynamicSolver") if mbs is not None else None
        try:
            return float(solver.newmarkBeta) * (1.0 - float(solver.alphaF)) / (1.0 - float(solver.alphaM))
        except (AttributeError, TypeError, RuntimeError):
            return 0.0

    def end_time(self) -> float:
        """The run's end time [s] (inf where the solver is not known), read with the damping."""
        return self.follow.end_time

    def restart(self) -> None:
        mbs = self._mbs()
        if mbs is not None:
            self.follow.restart(mbs)
            self._carry(mbs, False)


def add_constraint(mbs: exu.MainSystem, handle: Any, name: str) -> None:
    """The following mode's constraint between the joint's markers, off until a contact is
    sustained, and its state on the joint's kernel (the compiled kernel's table, or the
    Python kernel's :class:`FollowState`)."""
    geometry = handle.joint.geometry
    follow = FollowState(handle.joint.law, geometry.clearance, name or str(handle.objectNumber),
                         friction=handle.joint.friction.active)
    # the condition and the carrier are objects the user did not add: their names say whose they
    # are (Exudyn's own messages give object numbers, e.g. an explicit solver's refusal of constraints)
    owner = name or f"clearance joint {handle.objectNumber}"
    condition_name = f"{owner}:follow"
    markers = list(handle.markerNumbers)
    if handle.backend == "compiled":
        compiled = kernel.COMPILED
        follow.condition = CompiledCondition(mbs, markers, condition_name,
                                             (compiled.follow_constraint, compiled.follow_jacobian))
        (kind0, local0, frame0), (kind1, local1, _) = compiled_sides(mbs, markers)
        # the joint frame J0 in the bearing's body: its marker's frame turned by rotationMarker0
        frame0 = frame0 @ np.asarray(mbs.GetObjectParameter(handle.objectNumber, "rotationMarker0"), dtype=float)
        handle.carrierNumber = _add_carrier(mbs, handle, f"{owner}:carrier")
        events = CompiledEvents(mbs, follow, handle.objectNumber, handle.carrierNumber)
        compiled.set_follow(handle._backend.joint_id, follow.condition.number, events, kind0, local0,
                            frame0.tolist(), kind1, local1)
        handle.followNumber = follow.condition.number
        return
    kind = {"distance": DistanceCondition, "velocity": VelocityCondition}[CONDITION]
    follow.condition = kind(mbs, markers, geometry.clearance, condition_name)
    handle.followNumber = follow.condition.number
    handle._backend.kernel.follow = follow


def _add_carrier(mbs: exu.MainSystem, handle: Any, name: str) -> int:
    """The compiled following mode's carrier: a connector between two ground markers (no
    coordinates: no load, nothing to differentiate) on the joint's data node, with the joint's
    functions, off until a contact is followed (:meth:`CompiledEvents._carry`).  Its post-Newton
    function is then the joint's, with the joint's relative motion from the condition's last
    evaluation (the kernel's ``carrier_post_newton``)."""
    functions = handle.user_functions()
    ground = mbs.AddObject(ObjectGround(visualization=VObjectGround(show=False)))
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0])) for _ in range(2)]
    return mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
        name=name, markerNumbers=markers, nodeNumber=handle.nodeNumber,
        springForceTorqueUserFunction=functions["force_torque"], postNewtonStepUserFunction=functions["post_newton"],
        activeConnector=False, visualization=VObjectConnectorRigidBodySpringDamper(show=False)))
