"""The clearance joints of a system: kept in ``mbs.variables`` under :data:`REGISTRY_KEY`,
as Exudyn keeps a model's own data with its system, so that :func:`exuclear.simulate`, the
joints' run-start callbacks and the model checks find them from ``mbs`` alone."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import exudyn as exu

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

#: ``mbs.variables`` key of the joints created in a system (for exuclear.simulate).
REGISTRY_KEY = "exuclear.joints"
#: ``mbs.variables`` key that holds the :class:`~exuclear.SolverSettings` of the
#: :func:`exuclear.simulate` run under way: the joints' notes then name the settings its user
#: can set (:func:`simulate_settings`).
SIMULATE_KEY = "exuclear.simulate"


def register(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> None:
    """Keep ``handle`` with its system (:func:`joints_of`); the joints of an earlier build,
    before ``mbs.Reset()``, are let go (their kernel state is released with their handle)."""
    mbs.variables[REGISTRY_KEY] = [*joints_of(mbs), handle._system_view()]


def joints_of(mbs: exu.MainSystem) -> list[ClearanceJointHandle]:
    """The clearance joints live in ``mbs`` (those of an earlier build, before ``mbs.Reset()``, dropped)."""
    live = [h for h in mbs.variables.get(REGISTRY_KEY, []) if h.is_live()]
    mbs.variables[REGISTRY_KEY] = live
    return live


def handle_of(mbs: exu.MainSystem, token: int) -> ClearanceJointHandle | None:
    """The joint of ``mbs`` whose handle has ``token`` (live or not), or None."""
    return next((h for h in mbs.variables.get(REGISTRY_KEY, []) if h.token == token), None)


def simulate_settings(mbs: exu.MainSystem) -> Any:
    """The :class:`~exuclear.SolverSettings` of the :func:`exuclear.simulate` run of ``mbs``
    under way, or None (a plain ``mbs.SolveDynamic``)."""
    return mbs.variables.get(SIMULATE_KEY)


def label(handle: ClearanceJointHandle) -> str:
    """How messages name a joint: its name (quoted), else ``#k``, the k-th clearance joint
    created in its system (``#1`` the first), which a model's author can tell without
    looking up connector numbers."""
    if handle.name:
        return repr(handle.name)
    try:
        number = next(k for k, h in enumerate(joints_of(handle.mbs), start=1) if h == handle)
    except (RuntimeError, StopIteration):  # its system is gone, or it was dropped with an earlier build
        return f"(connector {handle.objectNumber})"
    return f"#{number}"
