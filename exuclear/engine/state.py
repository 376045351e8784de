"""A system's state as arrays, for tools that run copies of a model side by side or
carry a state from one run to the next (:mod:`exuclear.nonlinear`): which coordinates a
group of items owns, the coordinates, velocities and accelerations now, and setting them;
and, for a ``with`` block, the state at the step's start or moved on at its velocities.

Only the ODE2 coordinates (second-order: positions and velocities) are read and set; the
clearance joints' data coordinates (their contact history) stay with their joints.
"""
from __future__ import annotations

import contextlib
from collections.abc import Iterator, Sequence

import exudyn as exu
import numpy as np

from .handle import ClearanceJointHandle
from .registry import joints_of


def new_system() -> exu.MainSystem:
    """An empty system in a container of its own."""
    return exu.SystemContainer().AddSystem()


def object_count(mbs: exu.MainSystem) -> int:
    """The number of objects in ``mbs`` (the first object a following build will add)."""
    return int(mbs.systemData.NumberOfObjects())


def coordinates_of(mbs: exu.MainSystem, objects: range) -> np.ndarray:
    """The ODE2 coordinate indices of the objects ``objects`` (assembled ``mbs``), sorted."""
    found: set[int] = set()
    for i in objects:
        found.update(int(k) for k in mbs.systemData.GetObjectLTGODE2(i))
    return np.array(sorted(found), dtype=int)


def constraint_objects(mbs: exu.MainSystem, objects: range) -> list[int]:
    """The objects among ``objects`` that add algebraic equations (joints, constraints)."""
    return [i for i in objects if len(mbs.systemData.GetObjectLTGAE(i)) > 0]


def ode1_size(mbs: exu.MainSystem) -> int:
    """The number of first-order (ODE1) coordinates of the assembled ``mbs``."""
    return len(mbs.systemData.GetODE1Coordinates())


def joints_among(mbs: exu.MainSystem, objects: range) -> list[ClearanceJointHandle]:
    """The clearance joints of ``mbs`` whose connector is one of ``objects``."""
    return [h for h in joints_of(mbs) if int(h.objectNumber) in objects]


def current(mbs: exu.MainSystem, accelerations: bool = False) -> tuple[np.ndarray, ...]:
    """The ODE2 coordinates and velocities now (and the accelerations, which explicit
    solvers hold after an accepted step)."""
    data = mbs.systemData
    q, v = np.asarray(data.GetODE2Coordinates()), np.asarray(data.GetODE2Coordinates_t())
    return (q, v, np.asarray(data.GetODE2Coordinates_tt())) if accelerations else (q, v)


def initial(mbs: exu.MainSystem) -> tuple[np.ndarray, np.ndarray]:
    """The ODE2 coordinates and velocities a run starts from."""
    data, config = mbs.systemData, exu.ConfigurationType.Initial
    return (np.asarray(data.GetODE2Coordinates(configuration=config)),
            np.asarray(data.GetODE2Coordinates_t(configuration=config)))


def set_state(mbs: exu.MainSystem, q: np.ndarray, v: np.ndarray, *, at_start: bool = False) -> None:
    """Set the ODE2 coordinates and velocities now (between two steps of a run: the
    explicit solvers take the next step from them) or, ``at_start``, those a run starts
    from."""
    config = exu.ConfigurationType.Initial if at_start else exu.ConfigurationType.Current
    mbs.systemData.SetODE2Coordinates(np.asarray(q, dtype=float).tolist(), configuration=config)
    mbs.systemData.SetODE2Coordinates_t(np.asarray(v, dtype=float).tolist(), configuration=config)


def eccentricity(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> tuple[np.ndarray, np.ndarray]:
    """A joint's eccentricity ``e`` (journal centre minus bearing centre) [m] and its rate
    [m/s] in the joint frame's x, y (:attr:`ClearanceJointHandle.frame`, turned with the
    bearing body), now."""
    ov = exu.OutputVariableType
    bearing, journal = handle.markerNumbers
    rot = np.asarray(mbs.GetMarkerOutput(bearing, ov.RotationMatrix), dtype=float).reshape(3, 3)
    axes = rot @ np.asarray(mbs.GetObject(handle.objectNumber)["rotationMarker0"], dtype=float)

    def relative(kind: exu.OutputVariableType) -> np.ndarray:
        return np.asarray(mbs.GetMarkerOutput(journal, kind), dtype=float) - np.asarray(
            mbs.GetMarkerOutput(bearing, kind), dtype=float)

    # the rate is that of e in the global frame, read in the joint's axes: exact for a
    # bearing that does not turn (the slider's), the relative velocity of the centres otherwise
    return (axes.T @ relative(ov.Position))[:2], (axes.T @ relative(ov.Velocity))[:2]


def names(joints: Sequence[ClearanceJointHandle]) -> list[str]:
    """How the joints' observables are named: their names, else ``joint<object number>``."""
    return [h.name or f"joint{h.objectNumber}" for h in joints]


@contextlib.contextmanager
def start_of_step(mbs: exu.MainSystem, accelerations: bool = True) -> Iterator[None]:
    """The state at the start of the step in the current configuration, where marker outputs
    are read, for the ``with`` block (its coordinates and velocities, and its accelerations
    where ``accelerations``); the step's end state back after it.  (The vectors go to Exudyn
    as lists, which it reads several times faster than arrays.)"""
    data, start = mbs.systemData, exu.ConfigurationType.StartOfStep
    end = [data.GetODE2Coordinates().tolist(), data.GetODE2Coordinates_t().tolist()]
    data.SetODE2Coordinates(data.GetODE2Coordinates(configuration=start).tolist())
    data.SetODE2Coordinates_t(data.GetODE2Coordinates_t(configuration=start).tolist())
    if accelerations:
        end.append(data.GetODE2Coordinates_tt().tolist())
        data.SetODE2Coordinates_tt(data.GetODE2Coordinates_tt(configuration=start).tolist())
    try:
        yield
    finally:
        data.SetODE2Coordinates(end[0])
        data.SetODE2Coordinates_t(end[1])
        if accelerations:
            data.SetODE2Coordinates_tt(end[2])


@contextlib.contextmanager
def moved_on(mbs: exu.MainSystem, dt: float, accelerations: bool = False) -> Iterator[None]:
    """The coordinates moved on by ``dt`` [s] at their present velocities, for the ``with``
    block (the impulse mode's held step reads its condition's rows there, and predicts its
    normal there, :mod:`~exuclear.engine.impulse`); the present ones back after it.  With
    ``accelerations``: ``q + dt v + dt^2 (3 a - a_0) / 4``, ``a_0`` the accelerations at the
    step's start, the trapezoidal rule's step of length ``dt`` under accelerations that go
    on changing as they did over the last step of that length."""
    data = mbs.systemData
    q = data.GetODE2Coordinates()
    moved = q + dt * data.GetODE2Coordinates_t()
    if accelerations:
        start = data.GetODE2Coordinates_tt(configuration=exu.ConfigurationType.StartOfStep)
        moved += 0.25 * dt * dt * (3.0 * data.GetODE2Coordinates_tt() - start)
    data.SetODE2Coordinates(moved.tolist())
    try:
        yield
    finally:
        data.SetODE2Coordinates(q.tolist())
