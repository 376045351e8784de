"""The Python kernel: the clearance joint's Exudyn user functions, written in Python.

This is the readable statement of what the compiled kernel (``exuclear/_kernel/``)
computes, with the same names and in the same order, and split by role into modules of
the same names as the compiled kernel's headers: :mod:`.layout` (what the kernel reads
from the parameters), :mod:`.kinematics`, :mod:`.laws`, :mod:`.contacts`, :mod:`.film`,
:mod:`.joint_state` (a joint's histories, which one an evaluation uses, the data node's
entries), :mod:`.step_control` (the joint's own step control) and :mod:`.bindings`
(:class:`JointKernel`, the functions Exudyn calls).

The physics of one contact comes from :mod:`exuclear.spatial` (kinematics and
loads), :mod:`exuclear.contact`, :mod:`exuclear.friction` and
:func:`exuclear.joint.contact_response` (normal and friction force), and
:mod:`exuclear.history` (the contact history).  This package assembles a joint from its
contacts and keeps their histories the way Exudyn's calling pattern needs:

- **Contacts.**  A joint is a sequence of contacts (:class:`~.contacts.Contact`): a revolute
  joint's slices (the planar joint has one, whose motion is projected on the plane normal to
  the bearing axis), then its two end faces where it has an axial clearance; a spherical
  joint's one ball (:mod:`exuclear.spherical`).  The joint type in the parameters says which.  One
  :meth:`~.contacts.Contact.response` (onset velocity, normal force, friction) serves them all; the
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

from .bindings import JointKernel
from .joint_state import KernelFailure, StepControl, data_values, pair_data_values, spatial_data_values
from .step_control import (
    GROWTH_GAP,
    GROWTH_LIMIT,
    GROWTH_MIN,
    MAX_CUT,
    MIN_STEP_MARGIN,
    ONSET_FLOOR,
    ONSET_IDLE_STEPS,
    ONSET_TAIL,
    ONSET_TARGET,
    PENETRATION_CUT,
    PENETRATION_RETRIES,
    REDO_STEP_ERROR,
    SOLVER_STEP_CUT,
    STEP_SAFETY,
    STEP_SLACK,
    onset_step,
    time_to_wall,
)

__all__ = ["GROWTH_GAP", "GROWTH_LIMIT", "GROWTH_MIN", "MAX_CUT", "MIN_STEP_MARGIN", "ONSET_FLOOR", "ONSET_IDLE_STEPS",
           "ONSET_TAIL", "ONSET_TARGET", "PENETRATION_CUT", "PENETRATION_RETRIES", "REDO_STEP_ERROR", "SOLVER_STEP_CUT",
           "STEP_SAFETY", "STEP_SLACK", "JointKernel", "KernelFailure", "StepControl", "data_values", "onset_step",
           "pair_data_values", "spatial_data_values", "time_to_wall"]
