"""The zoo's runs of one model and their verdicts.

:func:`run_model` runs a registered model (:mod:`._common`) four ways: ideal (the
example as its author wrote it), with the clearance joint at the example's own settings,
through :func:`exuclear.simulate`, and a convergence check; every failure becomes a
field of its row, never an exception.
"""
from __future__ import annotations

import math
import re
import statistics
import time
import traceback
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import exudyn as exu
import numpy as np

import exuclear

from ._common import REGISTRY, Entry, ZooModel, _first_line, joint_peaks

#: Wall-clock limit of one run [s] (full run; --quick uses QUICK_TIME_LIMIT): a model that
#: is slow under some settings must not hold up the others.
TIME_LIMIT = 300.0
QUICK_TIME_LIMIT = 60.0

#: Verdict thresholds (documented in _report.md).  A run that reached its end silently is
#: "wrong, no word" when its largest penetration exceeds PENETRATION_WRONG of the
#: clearance: a penetration of a tenth of the gap on a steel-steel joint of the zoo's
#: sizes needs contact forces far above the bodies' weights and inertia loads (issue 20:
#: 0.35 c and 6.6 kN on a 1 kg bar, where a converged run stays below 0.05 c), i.e. a step
#: that overshoots the contact; or when it exceeds REFERENCE_FACTOR times the penetration
#: of exuclear.simulate at its automatic step (steps the joints control; explicit
#: fixed-step methods: ten steps per contact period).
PENETRATION_WRONG = 0.1
REFERENCE_FACTOR = 3.0
#: ... but not where the convergence check's 4x refined run reaches the same penetration within
#: this fraction: a contact that deep under the model's own loads is physics, not an overshoot
#: (the planar slider-crank's crank pin under 2.45 kN: 0.105 c at the automatic step and at 4x
#: the steps, slider_crank_2d's docstring).
CONVERGED_PENETRATION = 0.1


class _TimeLimit:
    """A post-step function that ends a run after ``seconds`` of wall time (a user's own
    post-step function keeps being called)."""

    def __init__(self, mbs: exu.MainSystem, seconds: float) -> None:
        self.mbs, self.seconds, self.hit = mbs, seconds, False
        installed = mbs.GetPostStepUserFunction()
        self.user = installed["function"] if isinstance(installed, dict) else None

    def post_step(self, mbs: exu.MainSystem, t: float) -> bool:
        if time.perf_counter() - self.start > self.seconds:
            self.hit = True
            return False
        return self.user(mbs, t) if self.user is not None else True

    def __enter__(self) -> _TimeLimit:
        self.start = time.perf_counter()
        self.mbs.SetPostStepUserFunction(self.post_step)
        return self

    def __exit__(self, *exc: Any) -> None:
        self.mbs.SetPostStepUserFunction(self.user if self.user is not None else 0)

#: Longest message kept in a row (characters).
MESSAGE_CHARS = 400


def _all_lines(err: BaseException | str) -> str:
    """An error's whole message on one line (Exudyn puts the user function's own error
    on the second and later lines), cut at :data:`MESSAGE_CHARS`."""
    text = " / ".join(line.strip() for line in str(err).strip().splitlines() if line.strip())
    return text[:MESSAGE_CHARS] or type(err).__name__


@dataclass
class _Run:
    """One solver call's outcome."""

    reached: bool
    time_reached: float
    wall: float
    steps: int
    message: str = ""
    time_limit: bool = False
    warnings: tuple[str, ...] = ()


def _solve_plain(model: ZooModel, time_limit: float) -> _Run:
    """``mbs.SolveDynamic`` with the example's own settings, bounded in wall time."""
    mbs, end = model.mbs, model.simulation_settings.timeIntegration.endTime
    message = ""
    with warnings.catch_warnings(record=True) as caught, _TimeLimit(mbs, time_limit) as limit:
        warnings.simplefilter("always")
        start = time.perf_counter()
        try:
            ok = bool(mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type))
            if not ok:
                message = "SolveDynamic returned False"
        except Exception as err:  # Exudyn raises its own error types on solver failure
            message = f"{type(err).__name__}: {_all_lines(err)}"
        wall = time.perf_counter() - start
        if model.joint is not None:
            _ = model.joint.notes  # the joint's AccuracyWarnings about the run, issued at the first access
    t = mbs.systemData.GetTime()
    steps = int(mbs.sys["dynamicSolver"].it.currentStepIndex) - 1 if "dynamicSolver" in mbs.sys else -1
    reached = not message and not limit.hit and t >= end * (1 - 1e-9)
    if limit.hit:
        message = f"time limit ({time_limit:g} s wall) at t = {t:.4g} s"
    ws = tuple(f"{w.category.__name__}: {_all_lines(str(w.message))}" for w in caught
               if not issubclass(w.category, DeprecationWarning))
    return _Run(reached, t, wall, steps, message, limit.hit, ws)


def _solve_simulate(model: ZooModel, time_limit: float) -> tuple[_Run, Any]:
    """``exuclear.simulate`` with the model's ``solver_settings``, bounded in wall time."""
    mbs = model.mbs
    with warnings.catch_warnings(record=True) as caught, _TimeLimit(mbs, time_limit) as limit:
        warnings.simplefilter("always")
        try:
            result = exuclear.simulate(mbs, model.solver_settings)
        except Exception as err:  # a refused model (ValueError) is a row, not a stop
            return _Run(False, 0.0, math.nan, -1, f"{type(err).__name__}: {_first_line(err)}"), None
    end = model.solver_settings.end_time
    reached = result.success and not limit.hit and result.time_reached >= end * (1 - 1e-9)
    message = result.message if not result.success else ""
    if limit.hit:
        message = f"time limit ({time_limit:g} s wall) at t = {result.time_reached:.4g} s"
    ws = tuple(f"{w.category.__name__}: {_all_lines(str(w.message))}" for w in caught
               if not issubclass(w.category, DeprecationWarning))
    return _Run(reached, result.time_reached, result.wall_time, result.steps, _all_lines(message) if message else "",
                limit.hit, ws), result


def _median_wall(build: Callable[[], ZooModel], repeats: int, time_limit: float) -> tuple[_Run, ZooModel]:
    """Build and run ``repeats`` times; the last run with the median wall time."""
    runs, model = [], None
    for _ in range(repeats):
        model = build()
        run = _solve_plain(model, time_limit)
        runs.append(run)
        if not run.reached:
            break
    run = replace(runs[-1], wall=statistics.median(r.wall for r in runs))
    return run, model


#: Words of advice (whole words): a message that names the joint and contains one of
#: these says what to do.
ADVICE = re.compile(r"\b(try|use|give|reduce|smaller|larger|raise|lower|increase|loosen)\b")


def _told(message: str, ws: tuple[str, ...], joint: Any) -> bool:
    """Whether a message or warning names the clearance joint (its name, or ``joint``
    and its object number) and says what to do (:data:`ADVICE_WORDS`)."""
    if joint is None:
        return False
    names = [f"joint {joint.objectNumber!r}", f"joint {int(joint.objectNumber)}"]
    if joint.name:
        names += [joint.name]
    for text in (message, *ws):
        low = text.lower()
        if any(n.lower() in low for n in names) and ADVICE.search(low):
            return True
    return False


#: The verdict of a silent run deeper than PENETRATION_WRONG where no refined run was made
#: (--quick, --no-convergence): whether that depth is the model's is not known.
UNCHECKED_DEPTH = "deeper than 0.1 c, unchecked"


def verdict(run: _Run, pen_ratio: float, ref_pen_ratio: float | None, joint: Any,
            refined_pen_ratio: float | None = None, checked: bool = True) -> str:
    """The verdict of a clearance run (rule in _report.md); ``refined_pen_ratio``: the largest
    penetration [c] of its convergence check's refined run, where one was made; ``checked``
    False: no refined run will be made (a deep run is then :data:`UNCHECKED_DEPTH`)."""
    if run.time_limit:
        return "time limit"
    if not run.reached:
        return "told" if _told(run.message, run.warnings, joint) else "crash"
    converged = (refined_pen_ratio is not None and refined_pen_ratio > 0
                 and abs(pen_ratio - refined_pen_ratio) <= CONVERGED_PENETRATION * refined_pen_ratio)
    beyond_reference = ref_pen_ratio is not None and ref_pen_ratio > 0 and pen_ratio > REFERENCE_FACTOR * ref_pen_ratio
    too_deep = (pen_ratio > PENETRATION_WRONG and not converged) or beyond_reference
    if too_deep:
        if _told("", run.warnings, joint):
            return "told"
        return UNCHECKED_DEPTH if not checked and not beyond_reference else "wrong, no word"
    return "right"


def _own_convergence(entry: Entry, model: ZooModel, own: _Run, end_time: float | None, time_limit: float,
                     refined_pen: list[float]) -> str:
    """``exuclear.check_convergence`` of the own-settings run (a plain ``mbs.SolveDynamic``)
    against the same model at 4x the steps, its joints' step control refined with them; the
    refined run's largest penetration [m] goes to ``refined_pen``."""
    if not own.reached:
        return "not checked: the own-settings run did not finish"

    def run(settings: exu.SimulationSettings) -> exuclear.RunRecord:
        m = entry(True, end_time)
        with _TimeLimit(m.mbs, time_limit) as limit:
            try:
                ok, message = bool(m.mbs.SolveDynamic(settings, solverType=m.solver_type)), ""
            except Exception as err:  # Exudyn raises its own error types on solver failure
                ok, message = False, _first_line(err)
        if limit.hit:
            raise TimeoutError(f"time limit ({time_limit:g} s wall) of the refined run at t = "
                               f"{m.mbs.systemData.GetTime():.4g} s")
        refined_pen.append(joint_peaks(m.joint)[0] if ok else 0.0)
        return exuclear.RunRecord.from_mbs(m.mbs, {"joint": m.joint}, success=ok, message=message)

    baseline = exuclear.RunRecord.from_mbs(model.mbs, {"joint": model.joint})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        check = exuclear.check_convergence(run, model.simulation_settings, baseline=baseline)
    return _convergence_verdict(check)


def _convergence_verdict(check: Any) -> str:
    """One line of a convergence check: how far the path agrees, else whether the statistics do."""
    if check.path_agrees:
        return f"path agrees (max |de|/c {check.joints['joint'].max_de:.2g})"
    if not check.complete:
        return "refined run stopped early"
    stats = "statistics agree" if check.statistics_agree() else "statistics differ"
    return f"path agrees until t = {check.horizon:.3g} s of {check.end:.3g} s; {stats}"


def _convergence(entry: Entry, model: ZooModel, result: Any, time_limit: float, refined_pen: list[float]) -> str:
    """``exuclear.check_convergence`` of the simulate run against a 4x refined run, whose
    largest penetration [m] goes to ``refined_pen``."""
    if result is None or not result.success:
        return "not checked: the simulate run did not finish"
    settings = replace(model.solver_settings, step=result.step, joint_steps=model.solver_settings.steered)

    def run(s: exuclear.SolverSettings) -> exuclear.RunRecord:
        m = entry(True, model.solver_settings.end_time)
        limit = _TimeLimit(m.mbs, time_limit)
        with limit:
            r = exuclear.simulate(m.mbs, s)
        if limit.hit:
            raise TimeoutError(f"time limit ({time_limit:g} s wall) of the refined run at t = {r.time_reached:.4g} s")
        refined_pen.append(joint_peaks(m.joint)[0] if r.success else 0.0)
        return exuclear.RunRecord.from_handles(r, {"joint": m.joint})

    baseline = exuclear.RunRecord.from_handles(result, {"joint": model.joint})
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            check = exuclear.check_convergence(run, settings, baseline=baseline)
    except TimeoutError as err:
        return f"not checked: {err}"
    return _convergence_verdict(check)


def _newton_per_step(model: ZooModel) -> float:
    it = model.mbs.sys["dynamicSolver"].it
    return it.newtonStepsCount / max(it.currentStepIndex - 1, 1)


def run_model(name: str, quick: bool = False, convergence: bool = True,
              end_time: float | None = None) -> dict[str, Any]:
    """Run one registered model (module docstring); every failure becomes a field of the row."""
    entry = REGISTRY[name]
    repeats = 1 if quick else 3
    limit = QUICK_TIME_LIMIT if quick else TIME_LIMIT
    row: dict[str, Any] = {"model": name, "example": entry.example, "bodies": entry.bodies,
                           "replaced": entry.replaced}
    try:
        ideal_run, ideal = _median_wall(lambda: entry(False, end_time), repeats, limit)
        row.update(ideal_ok=ideal_run.reached, ideal_wall=ideal_run.wall, ideal_steps=ideal_run.steps,
                   ideal_message=ideal_run.message)
        probe_ideal = np.asarray(ideal.probe(ideal.mbs), dtype=float) if ideal_run.reached else None

        own, model = _median_wall(lambda: entry(True, end_time), repeats, limit)
        own_model = model
        c = model.clearance
        pen, force = joint_peaks(model.joint)
        row.update(clearance_um=c * 1e6, own_reached=own.reached, own_time=own.time_reached, own_message=own.message,
                   own_wall=own.wall, own_steps=own.steps, own_impacts=len(model.joint.impacts()), own_pen_c=pen / c,
                   own_force=force,
                   own_warnings=" | ".join(own.warnings))
        if own.reached and probe_ideal is not None:
            row["probe_diff"] = float(np.linalg.norm(np.asarray(model.probe(model.mbs), dtype=float) - probe_ideal))
        row["own_ratio"] = own.wall / ideal_run.wall if ideal_run.reached and own.reached else math.nan
        row["own_newton"] = _newton_per_step(model)

        model = entry(True, end_time)
        sim, result = _solve_simulate(model, limit)
        spen, sforce = joint_peaks(model.joint) if result is not None else (math.nan, math.nan)
        row.update(sim_reached=sim.reached, sim_time=sim.time_reached, sim_message=sim.message, sim_wall=sim.wall,
                   sim_steps=sim.steps, sim_step=getattr(result, "step", math.nan),
                   sim_impacts=len(model.joint.impacts()) if result is not None else -1, sim_pen_c=spen / c,
                   sim_force=sforce, sim_warnings=" | ".join(sim.warnings),
                   sim_verdict=verdict(sim, spen / c, None, model.joint, checked=convergence and not quick))
        if sim.reached and probe_ideal is not None:
            row["sim_probe_diff"] = float(np.linalg.norm(np.asarray(model.probe(model.mbs), dtype=float) - probe_ideal))
        row["sim_ratio"] = sim.wall / ideal_run.wall if ideal_run.reached and sim.reached else math.nan
        row["verdict"] = verdict(own, pen / c, spen / c if sim.reached else None, model.joint,
                                 checked=convergence and not quick)
        if quick or not convergence:
            row["own_convergence"] = row["convergence"] = ("not checked: --quick" if quick else
                                                           "not checked: --no-convergence")
        else:
            own_refined: list[float] = []
            sim_refined: list[float] = []
            for key, check in (("own_convergence",
                                lambda: _own_convergence(entry, own_model, own, end_time, limit, own_refined)),
                               ("convergence", lambda: _convergence(entry, model, result, limit, sim_refined))):
                try:
                    row[key] = check()
                except Exception as err:  # the check is an extra: its failure is recorded
                    row[key] = f"not checked: {type(err).__name__}: {_first_line(err)}"
            # a deep penetration that the refined run reaches too is the model's (CONVERGED_PENETRATION)
            if own_refined and own_refined[-1] > 0.0:
                row["verdict"] = verdict(own, pen / c, spen / c if sim.reached else None, model.joint,
                                         own_refined[-1] / c)
            if sim_refined and sim_refined[-1] > 0.0:
                row["sim_verdict"] = verdict(sim, spen / c, None, model.joint, sim_refined[-1] / c)
    except Exception as err:  # a failing model is a row, never a stop
        row["verdict"] = "runner error"
        row["error"] = f"{type(err).__name__}: {_first_line(err)} ({traceback.extract_tb(err.__traceback__)[-1].name})"
    return row
