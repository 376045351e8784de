"""What a run gives the convergence check: the joints' and the signals' records (:class:`RunRecord`)."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..history import ImpactRecord


@dataclass(frozen=True)
class JointRecord:
    """One clearance joint's results of a run (copies, SI units).

    ``outputs``: ``time`` and :data:`exuclear.engine.OUTPUT_COLUMNS` as recorded; ``impacts``:
    the contacts of the run in order, the last one still open at the end if
    ``last_open`` (its duration then runs to the end of the run); ``clearance`` [m].
    """

    clearance: float
    outputs: dict[str, np.ndarray]
    impacts: tuple[ImpactRecord, ...]
    last_open: bool = False

    @property
    def onset_times(self) -> np.ndarray:
        return np.array([r.onset_time for r in self.impacts])

    @classmethod
    def from_handle(cls, handle: Any) -> JointRecord:
        """The record of a :class:`exuclear.ClearanceJointHandle` after a run."""
        out = {k: np.array(v, dtype=float) for k, v in handle.outputs().items()}
        impacts = list(handle.impacts())
        state = handle.state()
        if state.in_contact:  # the contact going on at the end, so far
            impacts.append(ImpactRecord(state.onset_time, state.v0, state.peak_force,
                                        state.time - state.onset_time, state.max_penetration))
        return cls(handle.joint.geometry.clearance, out, tuple(impacts), bool(state.in_contact))


@dataclass(frozen=True)
class RunRecord:
    """What :func:`check_convergence` compares of one run.

    Parameters
    ----------
    joints : dict of str to JointRecord
        The clearance joints by name.
    signals : dict of str to (ndarray, ndarray)
        Named signals as ``(time, values)``, shapes (n,) and (n,), any units.
    success, message : bool, str
        Whether the run reached its end time, and why not.
    time_reached : float
        Simulated time reached [s].
    wall_time : float
        Wall time of the solver [s] (reported, not compared).
    step : float
        The step the run was given [s] (the largest for adaptive methods), as
        ``result.step`` says; NaN where unknown.  With ``SolverSettings(step="auto")``
        the check refines this step.
    method : str
        The method of the run, as ``result.method`` says; ``""`` where unknown.  With
        ``SolverSettings(method="auto")`` the check refines the run with this method.
    """

    joints: dict[str, JointRecord]
    signals: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    success: bool = True
    message: str = ""
    time_reached: float = math.inf
    wall_time: float = math.nan
    step: float = math.nan
    method: str = ""

    @classmethod
    def from_handles(cls, result: Any, joints: Mapping[str, Any],
                     signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None) -> RunRecord:
        """The record of a finished run: ``result`` from :func:`exuclear.simulate`,
        ``joints`` the clearance-joint handles by name, ``signals`` named ``(time, values)``."""
        return cls(*_recorded(joints, signals), success=bool(result.success), message=str(result.message),
                   time_reached=float(result.time_reached), wall_time=float(result.wall_time),
                   step=float(getattr(result, "step", math.nan)), method=str(getattr(result, "method", "")))

    @classmethod
    def from_mbs(cls, mbs: Any, joints: Mapping[str, Any],
                 signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None, *, success: bool = True,
                 message: str = "") -> RunRecord:
        """The record of a run made by a plain ``mbs.SolveDynamic``: ``joints`` the
        clearance-joint handles by name, ``signals`` named ``(time, values)``;
        ``success`` what ``SolveDynamic`` returned.  The time reached is the system's
        time after the run."""
        return cls(*_recorded(joints, signals), success=bool(success), message=str(message),
                   time_reached=float(mbs.systemData.GetTime()))


def _recorded(joints: Mapping[str, Any], signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None
              ) -> tuple[dict[str, JointRecord], dict[str, tuple[np.ndarray, np.ndarray]]]:
    """The joints' records and the signals as float arrays, checked."""
    if not isinstance(joints, Mapping):
        raise ValueError(f"`joints` must map names to clearance-joint handles, got {joints!r}")
    if not joints and not signals:
        raise ValueError("nothing to compare: give clearance-joint handles (`joints`) or `signals`")
    sig = {}
    for name, pair in (signals or {}).items():
        t, y = (np.array(v, dtype=float).reshape(-1) for v in pair)
        if t.shape != y.shape:
            raise ValueError(f"signal {name!r}: time and values differ in length ({t.size} and {y.size})")
        sig[str(name)] = (t, y)
    return {str(k): JointRecord.from_handle(h) for k, h in joints.items()}, sig
