"""Where the impulse contact mode's run time goes: Exudyn's own solve against the mode's
decisions in Python.

Each zoo model named runs once with its own settings in the impulse mode (spectral radius
1, as ``python -m validation.cost modes`` runs it) under :mod:`cProfile`; the script prints
the run's wall time, the time spent inside the mode's post-Newton functions (the carriers'
``_post_newton``, the mode's decisions, Python), the rest (Exudyn's solve and everything
it calls that is not the mode), the calls and the time per call, and the held steps
computed again in the normal they reached (refines).  Profiling slows Python code more than
compiled code, so the shares are upper bounds of the mode's share in an unprofiled run;
take them on a quiet machine.  ``--calls N``: per model, the ``N`` functions with the most
time of their own, with their calls per accepted step (deterministic, unlike the times:
comparable on a busy machine).

``--budget R``: without the profiler, the median of ``R`` runs of each model four ways, all
at spectral radius 1: the ideal model; the ideal model with one post-Newton function that
decides nothing (a connector of the impulse mode's carrier type whose function returns at
once: the floor any decision in Python after each Newton solve pays, Exudyn's call into
Python); the same function after the reads and writes through Exudyn's Python interface
that a natively held step of the mode makes (the floor of the mode's steadiest step in
Python); and the impulse mode, its post-Newton functions timed from Python (wall clock
around each call), the rest its Exudyn solve with the mode's items.  Each over the ideal
model's wall time, the Jacobians Exudyn's Newton formed in the mode's run and in the ideal
model's (``newtonJacobiCount``), and the decisions per accepted step [us] next to the ideal
model's whole step [us].  One run in the mode before, not timed: a process's first run in the
mode imports modules.

::

    python -m validation.cost modes_profile [--models a,b] [--calls N] [--budget R]
"""
from __future__ import annotations

import argparse
import cProfile
import pstats
import statistics
import time
import warnings
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeGenericData,
    ObjectConnectorRigidBodySpringDamper,
    ObjectGround,
)

from validation._tables import markdown_table
from validation.cost.modes import _build, _run
from validation.exudyn_examples._common import load_models

#: Models profiled by default: a held contact on rigid bodies, one on a flexible body, a
#: translational joint's corners.
DEFAULT_MODELS = ("double_pendulum_3d_rxyz", "ancf_pendulum", "slider_crank_floating")


def _profile(name: str) -> tuple[float, str, bool, str, dict]:
    """A zoo model's impulse run under cProfile: wall [s], "steps / Newton", success, the
    error's first line, and the profiler's stats ((file, line, function) -> (cc, calls,
    own time, cumulative time, callers))."""
    model = _build(name, True, "impulse")
    profiler = cProfile.Profile()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        profiler.enable()
        wall, steps, ok, problem = _run(model, 1.0)
        profiler.disable()
    return wall, steps, ok, problem, pstats.Stats(profiler).stats


def profile_row(name: str, stats: dict, wall: float, steps: str, ok: bool, problem: str) -> list[str]:
    """One model's row: wall [s], the mode's decisions [s] and share, calls, per call [us],
    refines."""
    decisions = [v for k, v in stats.items() if k[2] == "_post_newton" and "exuclear" in k[0]]
    # a joint with several contacts extends the one-contact handle's function (super()): its
    # calls from another _post_newton are inside the outer one's time already
    nested = [c for v in decisions for key, c in v[4].items() if key[2] == "_post_newton"]
    calls = sum(v[1] for v in decisions) - sum(c[1] for c in nested)
    mode = sum(v[3] for v in decisions) - sum(c[3] for c in nested)
    # a held step computed again in the normal it reached: _refine sets the condition anew
    refines = sum(c[1] for k, v in stats.items() if k[2] == "_aim" for key, c in v[4].items() if key[2] == "_refine")
    return [name, steps if ok else f"stopped: {problem[:60]}", f"{wall:.3g}", f"{mode:.3g}", f"{mode / wall:.0%}",
            f"{wall - mode:.3g}", str(calls), f"{1e6 * mode / max(calls, 1):.0f}", str(refines)]


def calls_rows(stats: dict, steps: str, count: int) -> list[list[str]]:
    """The ``count`` functions with the most time of their own: calls per accepted step,
    calls, own time [s]."""
    accepted = max(int(steps.split("/")[0]), 1)
    top = sorted(stats.items(), key=lambda item: -item[1][2])[:count]
    return [[f"{function} ({path.rsplit('/', 1)[-1]}:{line})", f"{v[1] / accepted:.3f}", str(v[1]), f"{v[2]:.3g}"]
            for (path, line, function), v in top]


def _decide_nothing(mbs: Any, t: float, item: int, data: Any, *frame: Any) -> list:
    """A post-Newton function that accepts every Newton solve at once."""
    return [0.0, -1.0, *data]


def _exchange(markers: list[int], carrier: int) -> Any:
    """A post-Newton function that accepts every Newton solve after the reads and writes
    through Exudyn's Python interface that the impulse mode's natively held step makes
    (:mod:`exuclear.engine.impulse_hold`, :mod:`exuclear.engine.settling`): the step, a
    connector's displacement and velocity of its markers, a marker's rotation matrix, a
    multiplier, the velocities and accelerations read and written (back unchanged) and one
    parameter written (unchanged)."""
    ov = exu.OutputVariableType

    def exchange(mbs: Any, t: float, item: int, data: Any, *frame: Any) -> list:
        step = mbs.sys["dynamicSolver"].it.currentStepSize, mbs.systemData.GetTime()
        poses = [mbs.GetObjectOutput(carrier, output) for output in (ov.DisplacementLocal, ov.VelocityLocal)]
        rotation = mbs.GetMarkerOutput(markers[0], ov.RotationMatrix)
        mbs.GetObjectOutput(carrier, ov.ForceLocal)
        state = mbs.systemData
        velocities, accelerations = np.array(state.GetODE2Coordinates_t()), np.array(state.GetODE2Coordinates_tt())
        state.SetODE2Coordinates_t(velocities)
        state.SetODE2Coordinates_tt(accelerations)
        mbs.SetObjectParameter(carrier, "activeConnector", True)
        del step, poses, rotation
        return [0.0, -1.0, *data]
    return exchange


def _add_carrier(mbs: Any, exchange: bool) -> None:
    """A connector without force between two ground markers (the impulse mode's carrier,
    :mod:`exuclear.engine.impulse`, without the mode) whose post-Newton function decides
    nothing, after the mode's reads and writes where ``exchange`` (:func:`_exchange`)."""
    ground = mbs.AddObject(ObjectGround())
    ends = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)) for _ in range(2)]
    carrier = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
        markerNumbers=ends, nodeNumber=mbs.AddNode(NodeGenericData(initialCoordinates=[0.0], numberOfDataCoordinates=1)),
        postNewtonStepUserFunction=_decide_nothing))
    if exchange:
        mbs.SetObjectParameter(carrier, "postNewtonStepUserFunction", _exchange(ends, carrier))
    mbs.Assemble()


def _timed_decisions(mbs: Any) -> list[float]:
    """Every Python post-Newton function of ``mbs`` wrapped to add its wall time [s] to the
    one-element list returned."""
    spent = [0.0]

    def timed(function: Any) -> Any:
        def call(*args: Any) -> list:
            start = time.perf_counter()
            try:
                return function(*args)
            finally:
                spent[0] += time.perf_counter() - start
        return call

    for item in range(mbs.systemData.NumberOfObjects()):
        function = mbs.GetObject(item).get("postNewtonStepUserFunction", 0)
        if isinstance(function, dict) and function.get("type") == "Python":
            mbs.SetObjectParameter(item, "postNewtonStepUserFunction", timed(function["function"]))
    return spent


def budget_row(name: str, repeats: int) -> list[str]:
    """One model's budget (module docstring): the ideal model's wall [s] and step [us]; the
    empty decision's, the hold's exchange's and the impulse mode's wall over it; the mode's
    decisions and the rest over it; the mode's steps and Newton iterations; the Jacobians
    Exudyn's Newton formed in the mode's run and in the ideal model's; the decisions per
    accepted step [us]."""
    walls: dict[str, list[float]] = {"ideal": [], "empty": [], "exchange": [], "impulse": [], "decisions": []}
    steps, jacobians = {}, {}
    _run(_build(name, True, "impulse"), 1.0)  # not timed: the imports of a process's first run in the mode
    for _ in range(repeats):
        for way in ("ideal", "empty", "exchange", "impulse"):
            model = _build(name, way == "impulse", "impulse" if way == "impulse" else None)
            if way in ("empty", "exchange"):
                _add_carrier(model.mbs, way == "exchange")
            spent = _timed_decisions(model.mbs) if way == "impulse" else [0.0]
            wall, steps[way], ok, problem = _run(model, 1.0)
            if not ok:
                return [name, f"{way} stopped: {problem[:60]}"] + ["-"] * 8
            walls[way].append(wall)
            jacobians[way] = model.mbs.sys["dynamicSolver"].it.newtonJacobiCount
            if way == "impulse":
                walls["decisions"].append(spent[0])
    ideal, empty, exchange, impulse, decisions = (statistics.median(walls[k]) for k in walls)
    accepted = {way: max(int(s.split("/")[0]), 1) for way, s in steps.items()}
    return [name, f"{ideal:.3g} ({1e6 * ideal / accepted['ideal']:.0f})", f"{empty / ideal:.2f}x", f"{exchange / ideal:.2f}x",
            f"{impulse / ideal:.2f}x", f"{decisions / ideal:.2f}x", f"{(impulse - decisions) / ideal:.2f}x",
            steps["impulse"], f"{jacobians['impulse']} / {jacobians['ideal']}", f"{1e6 * decisions / accepted['impulse']:.0f}"]


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_profile",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", default=",".join(DEFAULT_MODELS),
                    help="zoo models, comma-separated (default: %(default)s)")
    ap.add_argument("--calls", type=int, default=0,
                    help="also list each model's N functions with the most time of their own (default: none)")
    ap.add_argument("--budget", type=int, default=0, metavar="R",
                    help="instead of the profile, the unprofiled budget over the ideal model, median of R runs "
                         "(module docstring; default: no budget)")
    args = ap.parse_args(argv)
    if args.calls < 0:
        ap.error(f"--calls must be at least 0, got {args.calls}")
    if args.budget < 0:
        ap.error(f"--budget must be at least 0, got {args.budget}")
    load_models(None)
    if args.budget:
        rows = [budget_row(name, args.budget) for name in args.models.split(",") if name]
        print(markdown_table(["model", "ideal [s] (per step [us])", "empty decision / ideal", "the hold's exchange / ideal",
                              "impulse / ideal",
                              "decisions / ideal", "the rest / ideal", "impulse steps / Newton", "Jacobians impulse / ideal",
                              "decisions per step [us]"], rows))
        return
    rows = []
    for name in (n for n in args.models.split(",") if n):
        wall, steps, ok, problem, stats = _profile(name)
        rows.append(profile_row(name, stats, wall, steps, ok, problem))
        if args.calls:
            print(f"\n{name}:\n" + markdown_table(["function", "calls per step", "calls", "own time [s]"],
                                                   calls_rows(stats, steps, args.calls)), flush=True)
    print("\n" + markdown_table(["model", "steps / Newton", "wall [s]", "mode's decisions [s]", "share",
                                 "the rest [s]", "calls", "per call [us]", "refines"], rows))


if __name__ == "__main__":
    main()
