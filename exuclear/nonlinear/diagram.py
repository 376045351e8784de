"""Orbit (bifurcation) diagrams: a driven model's Poincare samples over one parameter,
each value a run of the study runner (:func:`exuclear.study.run_study`: local cores,
a Dask scheduler, a resumable table, progress), or a sweep up and down carrying the
state from one value to the next (hysteresis: coexisting attractors)."""
from __future__ import annotations

import importlib
import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from ..settings import SolverSettings
from .chaos import classify
from .flow import Driven, exponent_of, run_sections

#: Keys of a row's parameter set that set the run rather than the model.
RUN_KEYS = ("periods", "transient_periods", "perturbation", "direction", "sweep_step")
#: Name of the function a scene module offers for the nonlinear tools: ``driven(values) -> Driven``.
SCENE_FUNCTION = "driven"


@dataclass(frozen=True)
class SceneModel:
    """A scene's :class:`Driven` by module path (importable in worker processes)."""

    module: str

    def __call__(self, params: Mapping[str, Any]) -> Driven:
        return getattr(importlib.import_module(self.module), SCENE_FUNCTION)(dict(params))


@dataclass(frozen=True)
class BuildModel:
    """A user's ``build(mbs, **params)`` as a :class:`Driven` factory."""

    build: Callable[..., Any]
    settings: SolverSettings
    period: float | Callable[[Mapping[str, Any]], float]
    observe: Callable[[Any, Any], Mapping[str, float]] | None = None

    def __call__(self, params: Mapping[str, Any]) -> Driven:
        period = self.period(dict(params)) if callable(self.period) else self.period
        return Driven(partial(self.build, **params), self.settings, period, self.observe, dict(params))


def scene_model(name: str) -> SceneModel:
    """The :class:`SceneModel` of a scene's short name (``"slider-crank"``, from the
    entry points of :mod:`exuclear.study`) or of a module path; ``ValueError`` if the
    module has no ``driven`` function."""
    from ..study import scene_names

    module = name if "." in name else scene_names().get(name)
    if module is None:
        raise ValueError(f"unknown scene {name!r}; known: {', '.join(sorted(scene_names()))}, or a module path")
    try:
        found = importlib.import_module(module)
    except ModuleNotFoundError as err:
        raise ValueError(f"unknown scene {name!r} (no module {module}: {err})") from None
    if not callable(getattr(found, SCENE_FUNCTION, None)):
        raise ValueError(f"scene {name!r} ({module}) has no `{SCENE_FUNCTION}(values)` function for the nonlinear tools")
    return SceneModel(module)


@dataclass
class OrbitRun:
    """One value of an orbit diagram (a study function): its Poincare samples, the
    verdict, the exponent where asked, the final state."""

    model: Callable[[Mapping[str, Any]], Driven]
    rtol: float = 1e-3
    atol: float = 0.0
    start: tuple | None = None  # the state a sweep carries in; set per run, in this process
    previous: Driven | None = None

    def __call__(self, params: dict) -> dict:
        run_keys = {k: params[k] for k in RUN_KEYS if k in params}
        driven = self.model({k: v for k, v in params.items() if k not in RUN_KEYS})
        start = None
        if self.start is not None:
            q, v = (np.asarray(x, dtype=float) for x in self.start)
            start = driven.carry(q, v, self.previous) if driven.carry and self.previous else (q, v)
        perturbation = run_keys.get("perturbation")
        perturbation = None if perturbation is None or (isinstance(perturbation, float) and math.isnan(perturbation)) \
            else float(perturbation)
        transient = int(run_keys.get("transient_periods", 0))
        run = run_sections(driven, periods=int(run_keys["periods"]), transient_periods=transient,
                           perturbation=perturbation, start=start)
        exponent = exponent_of(run, transient)[0] if perturbation is not None else math.nan
        samples = np.column_stack(list(run.samples.values())) if run.samples else np.zeros((0, 0))
        verdict = None
        if run.success and samples.shape[0] >= 2:
            verdict = classify(samples, exponent=None if math.isnan(exponent) else exponent, rtol=self.rtol,
                               atol=self.atol)
        return {**run.samples, "kind": verdict.kind if verdict else "", "period_n": verdict.period if verdict else 0,
                "K": verdict.K if verdict else math.nan, "exponent": exponent,
                "verdict": str(verdict) if verdict else "", "section_times": run.times,
                "final_q": run.final[0], "final_v": run.final[1], "steps": run.steps,
                "sim_wall_time": run.wall_time, "success": run.success, "message": run.message}


def orbit_diagram(model: str | Callable[..., Any], parameter: str, values: Sequence[Any], *, periods: int,
                  transient_periods: int = 0, fixed: Mapping[str, Any] | None = None,
                  settings: SolverSettings | None = None, period: float | Callable | None = None,
                  observe: Callable | None = None, exponent: bool = False, perturbation: float = 1e-6,
                  sweep: bool = False, out: str | os.PathLike | None = None, workers: int | None = None,
                  scheduler: str | None = None, progress: bool = True, rtol: float = 1e-3, atol: float = 0.0):
    """The orbit (bifurcation) diagram of a driven model over one parameter.

    Every value is run for ``transient_periods + periods`` driving periods and sampled
    at the end of each of the last ``periods`` (:func:`~exuclear.nonlinear.run_sections`),
    then classified (:func:`~exuclear.nonlinear.classify`).

    Parameters
    ----------
    model : str or callable
        A scene: its short name (``"slider-crank"``) or a module path
        (``"exuclear.models.driven_pendulum"``) of a module with ``driven(values) ->
        Driven``.  Or a user's ``build(mbs, **params)`` adding one copy of the model
        (then ``settings`` and ``period`` are needed, and ``observe`` may be given, as
        :class:`Driven` describes them).  Must be importable by name to run in worker
        processes (a module-level function; cloudpickle takes others where installed).
    parameter : str
        The parameter swept; ``values`` its values.
    periods, transient_periods : int
        Sampled periods and periods run first and left out.
    fixed : mapping, optional
        Other parameters, the same for every value.
    settings, period, observe
        For a user's ``build``: the solver settings, the driving period [s] (a number,
        or a function of the parameter set, e.g. of a crank speed), what to record.
    exponent : bool
        Also the largest Lyapunov exponent of each value (a second copy beside the
        first, :func:`~exuclear.nonlinear.lyapunov`; twice the cost), at ``perturbation``.
    sweep : bool
        False (default): every value independent, from the model's initial state, on
        the study runner.  True: in this process, up through ``values`` in their order,
        then down again, each value starting from the state the previous one ended in
        (:attr:`Driven.carry`); the rows say ``direction`` ("up", "down") and
        ``sweep_step``.
    out : path, optional
        The table (CSV), appended row by row and resumed when run again.
    workers, scheduler, progress
        As :func:`exuclear.study.run_study` (independent values only).
    rtol, atol : float
        Tolerance of the period test (:func:`~exuclear.nonlinear.classify`).

    Returns
    -------
    DataFrame
        One row per value (and direction): the parameters, the run's keys (``periods``,
        ``transient_periods``, ``perturbation``), one column per observable holding its
        samples (a list), ``section_times``, ``kind`` ("period-N", "quasi-periodic",
        "chaotic", "aperiodic"), ``period_n``, ``K``, ``exponent`` [1/s], ``verdict`` (the
        classification as text), ``final_q``, ``final_v`` (the state at the end),
        ``steps``, ``sim_wall_time`` and the runner's status columns.
    """
    from ..study import Study, run_study

    if isinstance(model, str):
        factory: Callable = scene_model(model)
        if settings is not None or period is not None or observe is not None:
            raise ValueError("`settings`, `period` and `observe` are for a user's build; a scene has its own")
    elif callable(model):
        if settings is None or period is None:
            raise ValueError("a user's `build` needs `settings` (SolverSettings) and `period` (the driving period [s])")
        factory = BuildModel(model, settings, period, observe)
    else:
        raise ValueError(f"`model` must be a scene name or a function build(mbs, **params), got {model!r}")
    if not isinstance(parameter, str) or not parameter:
        raise ValueError(f"`parameter` must be a parameter's name, got {parameter!r}")
    values = list(values)
    if not values:
        raise ValueError("`values` is empty")
    fixed = dict(fixed or {})
    if parameter in fixed:
        raise ValueError(f"`{parameter}` is swept: it must not be in `fixed` too")
    clash = sorted(set(fixed) & set(RUN_KEYS))
    if clash:
        raise ValueError(f"`fixed` must not name the run's own keys {clash}")
    keys = {"periods": periods, "transient_periods": transient_periods,
            "perturbation": float(perturbation) if exponent else None}
    function = OrbitRun(factory, rtol, atol)
    study = Study(function, name=f"orbit diagram over {parameter}")
    runs = [{parameter: v, **fixed, **keys} for v in values]
    for run in runs[:1]:
        factory({k: v for k, v in run.items() if k not in RUN_KEYS})  # bad parameters fail before any run
    if not sweep:
        return run_study(study, runs, out, workers=workers, scheduler=scheduler, progress=progress)
    if scheduler is not None or (workers or 1) > 1:
        raise ValueError("a sweep runs its values one after the other in this process: give no `workers` or `scheduler`")
    return _sweep(study, function, runs, out, progress)


def _sweep(study: Any, function: OrbitRun, runs: list[dict], out: Any, progress: bool):
    """Up through ``runs``, then down, each run starting from the last one's final state;
    each row through :func:`run_study` (so the table is resumed: a row already in it
    gives its final state to the next)."""
    import pandas as pd

    from ..study import run_study

    steps = [{**r, "direction": "up", "sweep_step": i} for i, r in enumerate(runs)]
    steps += [{**r, "direction": "down", "sweep_step": len(runs) + i} for i, r in enumerate(reversed(runs[:-1]))]
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(steps), desc=study.name, unit="run", dynamic_ncols=True)
    rows = []
    try:
        for step in steps:
            row = run_study(study, [step], out, workers=1, progress=False)
            rows.append(row)
            ok = bool(row["success"].iloc[0])
            function.start = (row["final_q"].iloc[0], row["final_v"].iloc[0]) if ok else None
            function.previous = function.model({k: v for k, v in step.items() if k not in RUN_KEYS}) if ok else None
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return pd.concat(rows, ignore_index=True)
