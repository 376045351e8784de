"""The zoo's interface and runner: Exudyn's own example models, each with one revolute
joint replaced by a clearance joint, run as their authors run them and through
:func:`exuclear.simulate`.

A model is a module of this package with ``EXAMPLE`` (the Exudyn example it follows),
``BODIES`` (the body and node types it covers), ``REPLACED`` (which revolute joint became
a clearance joint) and a ``build(clearance, end_time=None, **joint_options) -> ZooModel``
decorated with :func:`register`.  :func:`run_model` runs one model four ways (ideal,
clearance with the example's own settings, clearance through ``exuclear.simulate``, a
convergence check), :func:`run_zoo` all of them; ``python -m validation.exudyn_examples``
prints the table and writes ``zoo.csv`` and ``report.md``.
"""
from __future__ import annotations

import functools
import importlib
import math
import pkgutil
import re
import statistics
import time
import traceback
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import ModuleType
from typing import Any

import exudyn as exu
import numpy as np

import exuclear
from exuclear.settings import METHODS

# =======================================================================================
# the interface
# =======================================================================================


@dataclass
class ZooModel:
    """One assembled zoo model, ideal or with its clearance joint.

    Attributes
    ----------
    name : str
        The registered name.
    mbs : exudyn.MainSystem
        The assembled system.
    simulation_settings : exudyn.SimulationSettings
        The example's own solver settings (step, end time or the given ``end_time``,
        Newton settings as the example sets them); solution files off.
    solver_type : exudyn.DynamicSolverType
        The example's solver.
    joint : exuclear.ClearanceJointHandle or None
        The clearance joint; None for the ideal model.
    clearance : float or None
        Radial clearance c = R_B - R_J [m]; None for the ideal model.
    probe : callable ``mbs -> ndarray``
        A few observables at the end of a run (e.g. the position [m] of a point of a body
        that the replaced joint carries), compared between ideal and clearance models.
    solver_settings : exuclear.SolverSettings
        The example's settings for :func:`exuclear.simulate`, with ``step="auto"``
        (:func:`solver_settings_like`).
    energy : callable ``mbs -> (float, float)``, optional
        Kinetic and potential energy [J] of a conservative model, for the test of the
        ideal model (energy conservation); None where the model has drives or damping.
    probe_bound : float, optional
        ``k`` such that, over a short run (tens of ms) from the example's initial state,
        ``|probe - ideal probe| <= k (c + largest penetration)`` holds for geometric
        reasons the model's docstring gives (the journal's offset in the bearing, and the
        rotation the carried body loses while the journal crosses the gap); None: the
        tests do not check the probe.
    """

    name: str
    mbs: exu.MainSystem
    simulation_settings: exu.SimulationSettings
    solver_type: exu.DynamicSolverType
    joint: Any
    clearance: float | None
    probe: Callable[[exu.MainSystem], np.ndarray]
    solver_settings: exuclear.SolverSettings
    energy: Callable[[exu.MainSystem], tuple[float, float]] | None = None
    probe_bound: float | None = None


@dataclass(frozen=True)
class Entry:
    """A registered model: its module (for EXAMPLE, BODIES, REPLACED), its build function
    and the keyword arguments fixed for this entry (a variant of a model)."""

    name: str
    module: ModuleType
    build: Callable[..., ZooModel]
    fixed: dict[str, Any] = field(default_factory=dict)

    def __call__(self, clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
        model = self.build(clearance, end_time, **{**self.fixed, **joint_options})
        model.name = self.name  # a variant's name, not its build's
        return model

    @property
    def example(self) -> str:
        return getattr(self.module, "EXAMPLE", "")

    @property
    def bodies(self) -> str:
        return getattr(self.module, "BODIES", "")

    @property
    def replaced(self) -> str:
        return getattr(self.module, "REPLACED", "")


#: The registered models by name, in the order of registration.
REGISTRY: dict[str, Entry] = {}
#: Modules of this package that failed to import: name -> first line of the error.
IMPORT_ERRORS: dict[str, str] = {}


def register(build: Callable[..., ZooModel] | None = None, *, name: str | None = None,
             **fixed: Any) -> Callable[..., ZooModel]:
    """Register a model's ``build``; returns it unchanged.

    ``@register`` registers it under its module's name.  ``register(build, name=...,
    **fixed)`` registers a variant: ``fixed`` are keyword arguments passed to every call
    (e.g. ``node_type="rxyz"`` or ``friction="paper"``).
    """
    if build is None:
        return functools.partial(register, name=name, **fixed)  # type: ignore[return-value]
    module = importlib.import_module(build.__module__)
    key = name or build.__module__.rsplit(".", 1)[-1]
    if key in REGISTRY and REGISTRY[key].build is not build:
        raise ValueError(f"zoo model {key!r} is registered twice (modules {REGISTRY[key].module.__name__} and "
                         f"{module.__name__})")
    REGISTRY[key] = Entry(key, module, build, dict(fixed))
    return build


def load_models() -> dict[str, Entry]:
    """Import every model module of this package (names not starting with ``_``); a module
    that fails to import is noted in :data:`IMPORT_ERRORS`, not raised."""
    package = importlib.import_module(__package__)
    for info in pkgutil.iter_modules(package.__path__):
        if info.name.startswith("_"):
            continue
        try:
            importlib.import_module(f"{__package__}.{info.name}")
        except Exception as err:  # a broken model must not stop the others
            IMPORT_ERRORS[info.name] = f"{type(err).__name__}: {_first_line(err)}"
    return REGISTRY


def model_names(text: str) -> list[str]:
    """The zoo models named in ``text`` (comma-separated), all modules loaded; ``ValueError``
    naming the unknown ones and the known ones (the validation scripts' ``--models``)."""
    load_models()
    names = [n for n in text.split(",") if n]
    unknown = [n for n in names if n not in REGISTRY]
    if unknown:
        raise ValueError(f"unknown model(s) {', '.join(unknown)}; known: {', '.join(sorted(REGISTRY))}")
    return names


# ---------------------------------------------------------------------------------------
# helpers for model authors
# ---------------------------------------------------------------------------------------

#: The zoo's joint physics: steel on steel, the Wang-Liu law (exuclear's default law), a
#: coefficient of restitution of 0.9, no friction unless a model or the runner asks.
JOINT_DEFAULTS: dict[str, Any] = {"law": "wang-liu", "cr": 0.9, "journal_material": "steel",
                                  "bearing_material": "steel", "friction": "none"}

#: Exudyn's solver types -> exuclear's method names (:data:`exuclear.settings.METHODS`).
METHOD_OF_SOLVER = {getattr(exu.DynamicSolverType, exudyn_name): method
                    for method, (exudyn_name, _explicit, _adaptive) in METHODS.items()}


def joint_parameters(bearing_radius: float, clearance: float, length: float, **joint_options: Any) -> dict[str, Any]:
    """Keyword arguments of :func:`exuclear.CreateClearanceJoint` for a zoo joint: bearing
    radius R_B [m], radial clearance c [m] (R_J = R_B - c), bearing length L [m], the
    :data:`JOINT_DEFAULTS` overridden by ``joint_options`` (e.g. ``friction="paper"``)."""
    return {"bearing_radius": bearing_radius, "journal_radius": bearing_radius - clearance, "length": length,
            **JOINT_DEFAULTS, **joint_options}


def example_settings(end_time: float, steps: int) -> exu.SimulationSettings:
    """``exu.SimulationSettings`` with an example's end time and number of steps, silent
    (verbose 0) and without a solution file: the zoo reads sensors and probes only."""
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = max(1, int(round(steps)))
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    return ss


def rigid_body_energy(bodies: list[Any], inertias: list[Any], gravity: Any) -> Callable[[exu.MainSystem], tuple]:
    """``ZooModel.energy`` of bodies made by ``mbs.CreateRigidBody``: kinetic energy and the
    gravity potential ``-m g . r`` of each centre of mass (0 at the origin) [J], for the
    bodies' ``RigidBodyInertia`` (``com`` in the body frame) and the gravity vector [m/s^2]."""
    g = np.asarray(gravity, dtype=float)

    def energy(mbs: exu.MainSystem) -> tuple[float, float]:
        kinetic = potential = 0.0
        for body, inertia in zip(bodies, inertias):
            com = [float(x) for x in inertia.com]
            v = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.Velocity, com))
            w = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.AngularVelocityLocal, com))
            r = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.Position, com))
            kinetic += 0.5 * inertia.mass * v @ v + 0.5 * w @ np.asarray(inertia.InertiaCOM()) @ w
            potential -= inertia.mass * g @ r
        return kinetic, potential

    return energy


def scaled_end(settings: exu.SimulationSettings, end_time: float | None) -> None:
    """Shorten (or lengthen) a run to ``end_time`` [s] at the same step; None: keep."""
    if end_time is None:
        return
    ti = settings.timeIntegration
    step = ti.endTime / ti.numberOfSteps
    ti.endTime = end_time
    ti.numberOfSteps = max(1, int(round(end_time / step)))


#: ``ZooModel.probe_bound`` of a probe that is a point of the body the journal carries, in
#: a short run from rest: the journal's offset in the bearing moves that body by at most
#: c + penetration (1x), and while the journal crosses the gap before its first contact
#: the body falls without the joint's load and so misses the rotation that load gave it
#: in the ideal model; the lever times that angle is of the order of the distance the
#: joint point travelled across the gap (at most c + penetration again, 1x for a lever as
#: long as the distance from the joint to the body's centre, up to 1x more for a probe
#: twice as far): 3 in all.  Measured in the zoo: 0.14 to 0.24 at 20 ms, up to 0.84 at 50 ms.
PROBE_BOUND_CARRIED = 3.0

#: Recorded outputs per run of exuclear.simulate in the zoo: the penetration peaks come
#: from the per-step impact records, so the outputs only serve the convergence check,
#: which compares paths on this grid.
OUTPUTS_PER_RUN = 2000


def solver_settings_like(settings: exu.SimulationSettings, solver_type: exu.DynamicSolverType,
                         **changes: Any) -> exuclear.SolverSettings:
    """The :class:`exuclear.SolverSettings` of an example's settings, for ``exuclear.simulate``:
    its end time, method, spectral radius and linear solver; ``step="auto"`` (an implicit method: steps
    the joints control, at most ``end_time / 1000``; fixed-step methods: ten steps per
    contact period); exuclear's Newton tolerances (an absolute 1e-8 instead of Exudyn's 1e-10,
    because stiff contact leaves a round-off floor under the residual, see
    :data:`exuclear.settings.NEWTON_ATOL_DEFAULT`)."""
    if solver_type not in METHOD_OF_SOLVER:
        raise ValueError(f"`solver_type` {solver_type} has no exuclear method; one of {sorted(METHOD_OF_SOLVER)}")
    method = METHOD_OF_SOLVER[solver_type]
    end = settings.timeIntegration.endTime
    kw: dict[str, Any] = {"end_time": end, "method": method, "step": "auto", "output_step": end / OUTPUTS_PER_RUN}
    if not METHODS[method][1]:
        kw["spectral_radius"] = settings.timeIntegration.generalizedAlpha.spectralRadius
        sparse = settings.linearSolver.solverType == exu.LinearSolverType.EigenSparse
        kw["linear_solver"] = "sparse" if sparse else "dense"
    kw.update(changes)
    return exuclear.SolverSettings(**kw)


def joint_peaks(joint: Any) -> tuple[float, float]:
    """Largest penetration [m] and largest contact force [N] of the last run, from the
    per-step impact records (every accepted step, whatever the output interval), the
    contact still open at the end, and the penetration of the step that stopped a run at
    the joint's limit (that step is never accepted, so no record holds it)."""
    pen, force = 0.0, 0.0
    for r in joint.impacts():
        pen, force = max(pen, r.max_penetration), max(force, r.peak_force)
    s = joint.state()
    if s.in_contact:
        pen, force = max(pen, s.max_penetration), max(force, s.peak_force)
    reason = joint.failure()[0]
    if reason.startswith("penetration "):  # "penetration 4.787e-05 m exceeds the limit ..."
        try:
            pen = max(pen, float(reason.split()[1]))
        except (IndexError, ValueError):
            pass  # another wording: the records' value stands
    return pen, force


# =======================================================================================
# the runner
# =======================================================================================

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


def _first_line(err: BaseException | str) -> str:
    text = str(err).strip()
    return text.splitlines()[0] if text else type(err).__name__


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


def verdict(run: _Run, pen_ratio: float, ref_pen_ratio: float | None, joint: Any,
            refined_pen_ratio: float | None = None) -> str:
    """The verdict of a clearance run (rule in _report.md); ``refined_pen_ratio``: the largest
    penetration [c] of its convergence check's refined run, where one was made."""
    if run.time_limit:
        return "time limit"
    if not run.reached:
        return "told" if _told(run.message, run.warnings, joint) else "crash"
    converged = (refined_pen_ratio is not None and refined_pen_ratio > 0
                 and abs(pen_ratio - refined_pen_ratio) <= CONVERGED_PENETRATION * refined_pen_ratio)
    too_deep = (pen_ratio > PENETRATION_WRONG and not converged) or (
        ref_pen_ratio is not None and ref_pen_ratio > 0 and pen_ratio > REFERENCE_FACTOR * ref_pen_ratio)
    if too_deep:
        return "told" if _told("", run.warnings, joint) else "wrong, no word"
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


def run_model(name: str, quick: bool = False, convergence: bool = True, end_time: float | None = None) -> dict[str, Any]:
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
                   own_wall=own.wall, own_steps=own.steps, own_pen_c=pen / c, own_force=force,
                   own_warnings=" | ".join(own.warnings))
        if own.reached and probe_ideal is not None:
            row["probe_diff"] = float(np.linalg.norm(np.asarray(model.probe(model.mbs), dtype=float) - probe_ideal))
        row["own_ratio"] = own.wall / ideal_run.wall if ideal_run.reached and own.reached else math.nan

        model = entry(True, end_time)
        sim, result = _solve_simulate(model, limit)
        spen, sforce = joint_peaks(model.joint) if result is not None else (math.nan, math.nan)
        row.update(sim_reached=sim.reached, sim_time=sim.time_reached, sim_message=sim.message, sim_wall=sim.wall,
                   sim_steps=sim.steps, sim_step=getattr(result, "step", math.nan), sim_pen_c=spen / c,
                   sim_force=sforce, sim_warnings=" | ".join(sim.warnings),
                   sim_verdict=verdict(sim, spen / c, None, model.joint))
        if sim.reached and probe_ideal is not None:
            row["sim_probe_diff"] = float(np.linalg.norm(np.asarray(model.probe(model.mbs), dtype=float) - probe_ideal))
        row["sim_ratio"] = sim.wall / ideal_run.wall if ideal_run.reached and sim.reached else math.nan
        row["verdict"] = verdict(own, pen / c, spen / c if sim.reached else None, model.joint)
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


#: Columns of the printed table (all columns go to zoo.csv).
TABLE_COLUMNS = ["model", "ideal_wall", "ideal_steps", "own_reached", "own_time", "own_wall", "own_steps", "own_pen_c",
                 "own_force", "probe_diff", "own_ratio", "sim_reached", "sim_wall", "sim_steps", "sim_pen_c",
                 "sim_ratio", "verdict", "sim_verdict", "own_convergence", "convergence"]


def run_zoo(names: list[str] | None = None, quick: bool = False, convergence: bool = True,
            end_time: float | None = None, out: Path | None = None, progress: bool = True) -> Any:
    """Run the models (all registered ones by default); returns the table (pandas
    DataFrame) and writes ``zoo.csv`` and ``report.md`` into ``out`` if given."""
    import pandas as pd

    load_models()
    names = list(REGISTRY) if not names else names
    unknown = [n for n in names if n not in REGISTRY and n not in IMPORT_ERRORS]
    if unknown:
        raise ValueError(f"unknown zoo model(s) {unknown}; registered: {sorted(REGISTRY)}")
    rows = []
    for name in names:
        if name in IMPORT_ERRORS:
            rows.append({"model": name, "verdict": "import error", "error": IMPORT_ERRORS[name]})
            continue
        if progress:
            print(f"[zoo] {name} ...", flush=True)
        t0 = time.perf_counter()
        rows.append(run_model(name, quick, convergence, end_time))
        if progress:
            print(f"[zoo] {name}: {rows[-1].get('verdict')} ({time.perf_counter() - t0:.0f} s)", flush=True)
    for name in IMPORT_ERRORS:
        if name not in names and not any(r["model"] == name for r in rows):
            rows.append({"model": name, "verdict": "import error", "error": IMPORT_ERRORS[name]})
    table = pd.DataFrame(rows)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        table.to_csv(out / "zoo.csv", index=False)
        (out / "report.md").write_text(report(table, quick, end_time))
    return table


def show(table: Any) -> str:
    """The printed table: :data:`TABLE_COLUMNS` that exist, numbers rounded."""
    cols = [c for c in TABLE_COLUMNS if c in table.columns]
    return table[cols].to_string(index=False, float_format=lambda x: f"{x:.3g}")


def report(table: Any, quick: bool, end_time: float | None) -> str:
    """The Markdown report: _report.md filled with the tables and the run's notes."""
    template = (Path(__file__).with_name("_report.md")).read_text()
    cols = [c for c in TABLE_COLUMNS if c in table.columns]
    messages = []
    for _, r in table.iterrows():
        for key in ("ideal_message", "own_message", "own_warnings", "sim_message", "sim_warnings", "error"):
            value = r.get(key)
            if isinstance(value, str) and value:
                messages.append(f"- `{r['model']}` {key}: {value}")
    models = "\n".join(f"- `{e.name}`: {e.example} ({e.bodies}); replaced: {e.replaced}"
                       + (f"; with {', '.join(f'{k}={v!r}' for k, v in e.fixed.items())}" if e.fixed else "")
                       for e in REGISTRY.values())
    return template.format(
        mode="quick (one run per timing, no convergence check)" if quick else "full (median of 3 timings)",
        end_time="the examples' own" if end_time is None else f"{end_time:g} s for every model",
        exudyn=exu.__version__, exuclear=getattr(exuclear, "__version__", "?"),
        models=models, table=table[cols].to_markdown(index=False, floatfmt=".3g") if _has_tabulate()
        else "```\n" + show(table) + "\n```",
        messages="\n".join(messages) or "(none)", pen_wrong=PENETRATION_WRONG, ref_factor=REFERENCE_FACTOR,
        converged=CONVERGED_PENETRATION,
        time_limit=QUICK_TIME_LIMIT if quick else TIME_LIMIT)


def _has_tabulate() -> bool:
    try:
        import tabulate  # noqa: F401
    except ImportError:
        return False
    return True
