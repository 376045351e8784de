"""The two backends of a clearance joint's handle: the compiled kernel and the Python one.

Both have the same methods, so that :class:`~exuclear.engine.handle.ClearanceJointHandle`
never asks which one it holds: the user functions to give Exudyn, the joint id and the
``compiled`` flag to write into the parameters, and what a run left behind (per-contact
states and records, the journal's initial pose, why a run stopped).  Per-contact
sequences list the slices (one for the planar joint), then the end faces.
"""
from __future__ import annotations

import weakref
from typing import Any

import numpy as np

from ..history import ContactState, ImpactRecord
from ..joint import ClearanceJoint
from ..spatial import ShoulderGeometry
from . import kernel
from ._python_kernel import JointKernel

V3 = tuple[float, float, float]


class Backend:
    """What a handle asks of its backend (the interface; see the module docstring)."""

    #: Whether the parameters must have a compiled form (law and friction codes).
    compiled: bool
    #: The joint's id in the compiled kernel's table (-1: none).
    joint_id: int

    def user_functions(self) -> dict[str, Any]:
        """The user functions of the joint's connector, the probe and the torque connector."""
        raise NotImplementedError

    def set_joint(self, joint: ClearanceJoint) -> None:
        """New physics between runs (the compiled kernel reads it from the parameters)."""

    def reset(self) -> None:
        """Forget the contact history."""
        raise NotImplementedError

    def started(self) -> bool:
        """Whether a run has accepted its initial state."""
        raise NotImplementedError

    def states(self, which: str = "current") -> list[ContactState]:
        """Per contact, the history after the last accepted step (``"current"``), before it
        (``"previous"``) or at the run's initial state (``"initial"``)."""
        raise NotImplementedError

    def records(self) -> list[list[ImpactRecord]]:
        """Per contact, the records of the contacts that ended in the last run."""
        raise NotImplementedError

    def initial_pose(self) -> tuple[V3, float]:
        """The journal's axis and axial displacement at the run's initial state (J0)."""
        raise NotImplementedError

    def failure(self) -> tuple[str, float]:
        """Why and when the kernel stopped the last run (``""`` if it did not)."""
        raise NotImplementedError

    def failed(self) -> bool:
        """Whether :meth:`failure` has something to say (cheap enough to ask every step)."""
        raise NotImplementedError

    def set_run_start(self, callback: Any) -> None:
        """The callable the kernel calls once per run start; it returns the joint's
        :class:`~exuclear.engine.layout.RunStart`."""
        raise NotImplementedError

    def step_control(self) -> dict[str, Any]:
        """What the joint's own step control did in the last run (the kernel's ``StepControl``)."""
        raise NotImplementedError

    def wear_profiles(self) -> dict[str, Any]:
        """A worn joint's profiles after the last accepted step: ``bearing``, ``journal``,
        ``slip`` and ``stability`` per node (the kernel's ``WearState``); a spatial joint's
        slices x nodes, one row per slice."""
        raise NotImplementedError


class PythonBackend(Backend):
    """The Python kernel (:class:`~exuclear.engine._python_kernel.JointKernel`)."""

    compiled = False
    joint_id = -1

    def __init__(self, joint: ClearanceJoint, slices: int, axis_journal: V3,
                 shoulders: ShoulderGeometry | None) -> None:
        self.kernel = JointKernel(joint, slices, axis_journal, shoulders)

    def user_functions(self) -> dict[str, Any]:
        k = self.kernel
        return {"force_torque": k.force_torque, "post_newton": k.post_newton, "probe": k.probe,
                "probe_post_newton": k.probe_post_newton, "torque": k.torque}

    def set_joint(self, joint: ClearanceJoint) -> None:
        self.kernel.joint = joint

    def reset(self) -> None:
        self.kernel.reset()

    def started(self) -> bool:
        return self.kernel.started

    def states(self, which: str = "current") -> list[ContactState]:
        return list(getattr(self.kernel, which))

    def records(self) -> list[list[ImpactRecord]]:
        return [list(r) for r in self.kernel.records]

    def initial_pose(self) -> tuple[V3, float]:
        return self.kernel.initial_axis, self.kernel.initial_axial

    def failure(self) -> tuple[str, float]:
        return self.kernel.failure, self.kernel.failure_time

    def failed(self) -> bool:
        return bool(self.kernel.failure)

    def set_run_start(self, callback: Any) -> None:
        self.kernel.run_start = callback

    def step_control(self) -> dict[str, Any]:
        return self.kernel.control.as_dict()

    def wear_profiles(self) -> dict[str, Any]:
        wears = self.kernel.wear
        if self.kernel.planar:
            p = wears[0].current
            return {"bearing": p.bearing, "journal": p.journal, "slip": p.slip, "stability": p.stability}
        return {k: np.array([getattr(w.current, k) for w in wears]) for k in ("bearing", "journal", "slip", "stability")}


class CompiledBackend(Backend):
    """The compiled kernel: one entry of its table, released when the backend is collected
    (its handle is gone), so that building many models does not grow the table."""

    compiled = True

    def __init__(self, joint: ClearanceJoint, slices: int = 0) -> None:
        if kernel.COMPILED is None:
            raise ValueError(f"backend 'compiled' is not available: {kernel.REASON}")
        self.joint_id = kernel.COMPILED.new_joint()
        self._release = weakref.finalize(self, kernel.COMPILED.release, self.joint_id)
        self.slices = slices
        self.set_joint(joint)

    def set_joint(self, joint: ClearanceJoint) -> None:
        """The physics is in the parameters, except what a joint's wear starts from: its
        initial profiles (one row per slice of a spatial joint, section 11.7), the length each
        row stands for (``L / N``) and the law's E* (for the Hertz strip), given here; its worn
        profiles so far are forgotten, as the Python kernel's ``JointState.joint`` does."""
        wear = joint.wear
        if wear is None:
            kernel.COMPILED.set_wear(self.joint_id, [], [], 0.0, 0.0)
            return
        rows = max(self.slices, 1)
        zero = [0.0] * wear.nodes
        bearing = [list(wear.profile_row("bearing", k)) if wear.bearing is not None else zero for k in range(rows)]
        journal = [list(wear.profile_row("journal", k)) if wear.journal is not None else zero for k in range(rows)]
        length = joint.geometry.length if not self.slices else joint.geometry.length / self.slices
        kernel.COMPILED.set_wear(self.joint_id, bearing, journal, float(joint.law.E_star), length)

    def user_functions(self) -> dict[str, Any]:
        c = kernel.COMPILED  # one function serves every role; the role is in the parameters
        return {"force_torque": c.force_torque, "post_newton": c.post_newton, "probe": c.force_torque,
                "probe_post_newton": c.post_newton, "torque": c.force_torque}

    def reset(self) -> None:
        kernel.COMPILED.reset(self.joint_id)

    def started(self) -> bool:
        return kernel.COMPILED.history(self.joint_id)["started"]

    def states(self, which: str = "current") -> list[ContactState]:
        return [ContactState(**h) for h in kernel.COMPILED.history(self.joint_id)[which]]

    def records(self) -> list[list[ImpactRecord]]:
        return [[ImpactRecord(*r) for r in rs] for rs in kernel.COMPILED.records(self.joint_id)]

    def initial_pose(self) -> tuple[V3, float]:
        u, axial = kernel.COMPILED.initial_axis(self.joint_id)
        return tuple(u), axial

    def failure(self) -> tuple[str, float]:
        return tuple(kernel.COMPILED.failure(self.joint_id))

    def failed(self) -> bool:
        return kernel.COMPILED.failed(self.joint_id)

    def set_run_start(self, callback: Any) -> None:
        kernel.COMPILED.set_run_start(self.joint_id, callback)

    def step_control(self) -> dict[str, Any]:
        return dict(kernel.COMPILED.step_control(self.joint_id))

    def wear_profiles(self) -> dict[str, Any]:
        rows = kernel.COMPILED.wear_profiles(self.joint_id)  # per slice (the planar joint: one)
        return {k: np.array(v[0] if not self.slices else v) for k, v in dict(rows).items()}


def make_backend(name: str, joint: ClearanceJoint, slices: int, axis_journal: V3,
                 shoulders: ShoulderGeometry | None) -> Backend:
    """The backend called ``name`` (``"compiled"`` or ``"python"``) for one joint."""
    if name == "compiled":
        return CompiledBackend(joint, slices)
    return PythonBackend(joint, slices, axis_journal, shoulders)
