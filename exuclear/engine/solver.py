"""The solver driver: :func:`simulate`, a convenience around ``exudyn.SolveDynamic``.

A clearance joint needs none of this: ``mbs.SolveDynamic`` runs it as any Exudyn item
(its history starts again at each run's initial time).  :func:`simulate` adds what a
study wants: one typed settings object (:class:`exuclear.SolverSettings`), a method chosen
from the model (:func:`automatic_method`: an implicit one where the model has constraints),
the refusal of explicit methods for constrained models (Exudyn's explicit solvers would
silently drop the constraints), impact-aware steps, watchdogs for an adaptive step that collapses or
is retried without end, a step chosen from the model (``step="auto"``,
:func:`automatic_step`), and a result that says why a run stopped.  The watchdogs are
pre- and post-step functions installed for the run only; the user's own step functions
are called from them and restored afterwards.

With a numeric ``step`` and an implicit method, :func:`simulate` runs as a plain
``mbs.SolveDynamic`` with that step and Exudyn's defaults does (adaptive steps: Exudyn
shortens a step whose Newton iteration fails, the joints one they cannot resolve), so that
where the plain call reaches the end time, :func:`simulate` does too.  During its run the
system's variables hold its settings under :data:`SIMULATE_KEY`: the joints' notes then name
the :class:`SolverSettings` fields to change, not Exudyn's.
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import exudyn as exu

from ..exceptions import AccuracyWarning
from ..settings import DEFAULT_STEP, LINEAR_SOLVERS, METHODS, MIN_STEP_DEFAULT, SolverSettings
from ..timescales import MIN_STEPS_PER_RUN, step_from_contact_periods
from .arguments import check_system
from .bodies import joint_contact_period, unread_masses
from .diagnostics import check_model, started_aligned, tilt_note
from .registry import SIMULATE_KEY, joints_of, label

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

#: Attempts at one step after which a run is ended: DOPRI5 rejects a step a few times at
#: an impact, but at its minimum step Exudyn's DOPRI5 retries forever.
MAX_STEP_ATTEMPTS = 200

#: With impact-aware steps, Exudyn's own step reduction (after a failed Newton iteration)
#: may go this far below ``impact_step`` before the run fails.
IMPACT_STEP_FLOOR = 0.5


def simulation_settings(settings: SolverSettings) -> exu.SimulationSettings:
    """Map :class:`SolverSettings` onto ``exu.SimulationSettings`` (the only place).

    ``step="auto"`` needs the model: :func:`simulate` replaces it by
    :func:`automatic_step` before it maps the settings."""
    if settings.method_from_model:
        raise ValueError("`method` is 'auto', which is chosen from the model: run exuclear.simulate(mbs, settings), or "
                         "map dataclasses.replace(settings, method=exuclear.engine.solver.automatic_method(mbs, "
                         "settings))")
    if settings.automatic:
        raise ValueError("`step` is 'auto', which is chosen from the model: run exuclear.simulate(mbs, settings), or "
                         "map dataclasses.replace(settings, step=exuclear.engine.solver.automatic_step(mbs, settings))")
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime = settings.end_time
    ti.numberOfSteps = max(1, math.ceil(settings.end_time / settings.step - 1e-9))
    ti.verboseMode = settings.verbose
    if settings.explicit:
        ti.automaticStepSize = settings.adaptive
        ti.relativeTolerance = settings.rtol
        ti.absoluteTolerance = settings.atol
        ti.minimumStepSize = settings.min_step
    elif settings.steered:
        # the joints' step control (docs/guide/solver_path.md, "What the joint does to your steps"): a
        # joint's post-Newton function rejects a step its contact cannot resolve, with the step
        # to redo it at; Exudyn redoes a step whose Newton fails shorter (its defaults)
        ti.adaptiveStep = True  # down to Exudyn's minimumStepSize, 1e-8 s, or the user's min_step
        ti.discontinuous.useRecommendedStepSize = True
        if settings.min_step != MIN_STEP_DEFAULT:
            ti.minimumStepSize = settings.min_step
    elif settings.impact_step is None:
        ti.adaptiveStep = False  # fixed step: a rejected Newton step fails the run loudly
    else:
        # impact-aware steps: a joint's post-Newton function asks for impact_step at a contact
        # onset; Exudyn then doubles the step every recovery_steps steps
        ti.adaptiveStep = True
        ti.minimumStepSize = settings.impact_step * IMPACT_STEP_FLOOR
        ti.adaptiveStepIncrease = 2.0
        ti.adaptiveStepRecoverySteps = settings.recovery_steps
        ti.discontinuous.useRecommendedStepSize = True
    if not settings.explicit:
        ti.newton.relativeTolerance = settings.newton_rtol
        ti.newton.absoluteTolerance = settings.newton_atol
        ss.linearSolver.solverType = getattr(exu.LinearSolverType, LINEAR_SOLVERS[settings.linear_solver])
        if settings.newton_contractivity is not None:  # the joints only ever lower it (engine.steering)
            ti.newton.modifiedNewtonContractivity = settings.newton_contractivity
        ti.generalizedAlpha.spectralRadius = settings.spectral_radius
        ti.generalizedAlpha.computeInitialAccelerations = True
    ss.solution.file.write = False  # results come from sensors kept in memory
    ss.solution.sensors.writePeriod = settings.output_step
    return ss


@dataclass(frozen=True)
class SimulationResult:
    """Outcome of :func:`simulate`.

    ``success`` is False when the run stopped early; ``message`` then says why and what
    to try, and ``time_reached`` [s] how far it got.  ``wall_time`` is the solver call
    alone [s]; ``step`` [s] the step the run was given (the largest for adaptive
    methods), chosen from the model where the settings said ``"auto"``, and ``method`` the
    method, chosen likewise; ``steps`` the number of accepted time steps and ``rejected``
    the rejected ones (adaptive methods).  ``notes`` says where a finished run may not be
    converged (each also issued as an :class:`AccuracyWarning`), e.g. contact chatter
    that is a numerical artefact.
    """

    success: bool
    message: str
    wall_time: float
    steps: int
    rejected: int
    time_reached: float
    notes: tuple[str, ...] = ()
    step: float = math.nan
    method: str = ""


def _user_function(installed: Any) -> Any:
    return installed["function"] if isinstance(installed, dict) else None


class _Watchdog:
    """Pre- and post-step functions for one run: end a step retried without end and an
    adaptive step that collapsed to its minimum; the user's functions are called from them."""

    def __init__(self, mbs: exu.MainSystem, min_step: float, joints: tuple[ClearanceJointHandle, ...] = ()) -> None:
        self.mbs = mbs
        # a joint whose failure() speaks (a penetration beyond its limit that shorter steps did
        # not remove, accepted by the kernel so that a plain SolveDynamic goes on) ends the run
        self.failed = tuple(h._backend.failed for h in joints)
        self.user_pre = _user_function(mbs.GetPreStepUserFunction())
        self.user_post = _user_function(mbs.GetPostStepUserFunction())
        self.min_step = min_step
        self.last, self.attempts, self.problem = 0.0, 0, ""
        self.interrupted = False

    # Ctrl-C raises KeyboardInterrupt in the next Python code that runs, which during a solve
    # is one of these functions; Exudyn turns any exception there into its own error, so the
    # interrupt is noted here and raised again once the solver has returned.
    def pre_step(self, mbs: exu.MainSystem, t: float) -> bool:
        try:
            self.attempts += 1
            if self.attempts > MAX_STEP_ATTEMPTS:
                self.problem = (f"at t = {self.last:.6g} s, the solver retried one step {MAX_STEP_ATTEMPTS} times "
                                "without accepting it (Exudyn's DOPRI5 does so when its minimum step cannot meet the "
                                "tolerances); loosen the tolerances, lower `min_step`, or use an implicit method")
                raise RuntimeError(self.problem)  # returning False would not end Exudyn's retry loop
            return self.user_pre(mbs, t) if self.user_pre is not None else True
        except KeyboardInterrupt:
            self.interrupted = True
            raise

    def post_step(self, mbs: exu.MainSystem, t: float) -> bool:
        try:
            self.attempts = 0
            step, self.last = t - self.last, t
            for failed in self.failed:
                if failed():
                    return False  # simulate's result says why (the joint's failure)
            if 0.0 < step <= self.min_step:
                self.problem = (f"at t = {t:.6g} s, the adaptive step collapsed to the minimum step ({step:.3g} s), "
                                "where Exudyn would go on without error control; the problem is too stiff for this "
                                "explicit method here: try an implicit method, looser tolerances, or a smaller "
                                "`min_step`")
                return False
            return self.user_post(mbs, t) if self.user_post is not None else True
        except KeyboardInterrupt:
            self.interrupted = True
            raise

    def __enter__(self) -> _Watchdog:
        self.mbs.SetPreStepUserFunction(self.pre_step)
        self.mbs.SetPostStepUserFunction(self.post_step)
        return self

    def __exit__(self, *exc: Any) -> None:
        self.mbs.SetPreStepUserFunction(self.user_pre if self.user_pre is not None else 0)
        self.mbs.SetPostStepUserFunction(self.user_post if self.user_post is not None else 0)


def _constraint_objects(mbs: exu.MainSystem) -> list[str]:
    found = []
    for i in range(mbs.systemData.NumberOfObjects()):
        if len(mbs.systemData.GetObjectLTGAE(i)) > 0:
            found.append(f"{i} ({mbs.GetObject(i)['objectType']})")
    return found


def _joints_in_contact(joints: list[ClearanceJointHandle]) -> str:
    """Which joints were in contact at the last accepted state, for failure messages."""
    names = []
    for h in joints:
        state = h.state()
        if state.in_contact:
            names.append(f"{label(h)} (penetration {state.delta:.3g} m)")
    return f"; in contact then: {', '.join(names)}" if names else "; no clearance joint was in contact then"


def automatic_method(mbs: exu.MainSystem, settings: SolverSettings) -> str:
    """The method that ``SolverSettings(method="auto")`` stands for in the assembled ``mbs``:
    ``"generalized-alpha"`` where the model has constraints (objects with algebraic
    equations: joints, coordinate constraints, which Exudyn's explicit solvers would drop)
    or the settings give an option only the implicit methods take; else ``"dopri5"``, the
    adaptive explicit method whose error control resolves a free journal's impacts (the
    paper's numbers come from it).  ``settings.method`` where it is not ``"auto"``."""
    if not settings.method_from_model:
        return settings.method
    return "generalized-alpha" if settings.implicit_options or _constraint_objects(mbs) else "dopri5"


def automatic_step(mbs: exu.MainSystem, settings: SolverSettings) -> float:
    """The step [s] that ``SolverSettings(step="auto")`` stands for in the assembled ``mbs``.

    Implicit methods whose steps the joints control (``settings.steered``): the largest
    step ``end_time / 1000`` (:data:`~exuclear.timescales.MIN_STEPS_PER_RUN`); the joints
    shorten the steps where their contacts begin, are held or end.  Fixed-step methods
    (implicit with ``joint_steps=False``, RK44): a tenth of the shortest contact period of
    the model's clearance joints, and no more than ``end_time / 1000``
    (:func:`exuclear.timescales.step_from_contact_periods`).  A joint's period is its
    two bodies' reduced mass on the tangent stiffness of its law under the weight of
    that mass (``joint_contact_period``, the estimate of the chatter check; the rule and
    its reasons are in the docstring of :class:`SolverSettings`).  Explicit adaptive
    methods control their step by their error estimate: the largest step stays
    :data:`~exuclear.settings.DEFAULT_STEP` (within ``end_time``).

    ``ValueError`` if a joint's period cannot be estimated (a body whose mass is not
    read from its Exudyn object).  ``method="auto"`` is chosen first (:func:`automatic_method`).
    """
    if settings.method_from_model:
        settings = replace(settings, method=automatic_method(mbs, settings))
    if settings.explicit and settings.adaptive:
        return min(DEFAULT_STEP, settings.end_time)
    if settings.steered:
        return settings.end_time / MIN_STEPS_PER_RUN
    periods = []
    for handle in joints_of(mbs):
        period = joint_contact_period(mbs, handle)
        if not period > 0.0:
            raise ValueError(f"`step` 'auto': the contact period of clearance joint {label(handle)} "
                             f"cannot be estimated, because the mass of {unread_masses(mbs, handle) or 'one of its bodies'} "
                             "is not read from its Exudyn object; give `step` in seconds")
        periods.append(period)
    return step_from_contact_periods(periods, settings.end_time)


def resolved_settings(mbs: exu.MainSystem, settings: SolverSettings) -> SolverSettings:
    """``settings`` with ``method="auto"`` replaced by :func:`automatic_method` and
    ``step="auto"`` by :func:`automatic_step`: what :func:`simulate` runs."""
    if settings.method_from_model:
        settings = replace(settings, method=automatic_method(mbs, settings))
    if not settings.automatic:
        return settings
    step = automatic_step(mbs, settings)
    for name in ("impact_step", "min_step"):
        value = getattr(settings, name)
        if value is not None and value > step:
            raise ValueError(f"`{name}` must not exceed the step, but `step` 'auto' chose {step:.3g} s for this model "
                             f"and {name} = {value:g} s; give a smaller `{name}` or `step` in seconds")
    return replace(settings, step=step, joint_steps=settings.steered)


def simulate(mbs: exu.MainSystem, settings: SolverSettings) -> SimulationResult:
    """Assemble if needed and integrate ``mbs`` with ``settings``.

    ``settings.step`` ``"auto"`` is replaced by :func:`automatic_step` (the run's
    ``result.step``).  Explicit methods are refused for systems with constraints (joints, coordinate
    constraints): Exudyn's explicit solvers would silently ignore them.  Every clearance
    joint starts from the initial state (its history is reset).

    A run that cannot go on (solver failure, a non-finite joint state, a penetration
    beyond a joint's limit, a collapsed or endlessly retried step) returns
    ``success=False`` with a message naming the time, the joint and what to try; what the
    sensors recorded up to then is kept.  Ctrl-C raises ``KeyboardInterrupt``.
    """
    check_system(mbs)
    if not isinstance(settings, SolverSettings):
        raise ValueError(f"`settings` must be a SolverSettings, got {type(settings).__name__}")
    if not mbs.systemIsConsistent:
        mbs.Assemble()
    joints = joints_of(mbs)
    check_model(mbs, joints)
    aligned = [started_aligned(mbs, h) for h in joints]  # read before the run changes the state
    settings = resolved_settings(mbs, settings)
    if settings.explicit:
        constrained = _constraint_objects(mbs)
        if constrained:
            raise ValueError(
                f"method {settings.method!r} is explicit and Exudyn's explicit solvers ignore constraints, but objects "
                f"{', '.join(constrained)} are constraints; use 'generalized-alpha' or 'trapezoidal', "
                "or a minimal-coordinate model")
    rate_limits = [handle.rate_limit for handle in joints]
    for handle in joints:
        handle.reset()
        handle.set_impact_step(settings.impact_step or 0.0)
        if not settings.explicit:
            handle.rate_limit = settings.rate_limit
    ss = simulation_settings(settings)
    solver_type = getattr(exu.DynamicSolverType, METHODS[settings.method][0])
    min_step = settings.min_step * (1.0 + 1e-6) if settings.adaptive else 0.0  # Exudyn may land a hair above it
    start = time.perf_counter()
    mbs.variables[SIMULATE_KEY] = settings  # the joints' notes of this run name its settings
    try:
        return _run(mbs, settings, joints, ss, solver_type, min_step, rate_limits, aligned, start)
    finally:
        mbs.variables.pop(SIMULATE_KEY, None)


def _run(mbs: exu.MainSystem, settings: SolverSettings, joints: list[ClearanceJointHandle],
         ss: exu.SimulationSettings, solver_type: Any, min_step: float, rate_limits: list[float],
         aligned: list[bool], start: float) -> SimulationResult:
    """The solve of :func:`simulate` and its result, notes read while :data:`SIMULATE_KEY` is set."""
    def result(*args: Any) -> SimulationResult:
        return SimulationResult(*args, step=settings.step, method=settings.method)

    with _Watchdog(mbs, min_step, joints=tuple(joints)) as watchdog:
        try:
            with warnings.catch_warnings():  # the joints' notes are issued with the result's
                warnings.simplefilter("ignore", AccuracyWarning)
                ok = bool(exu.SolveDynamic(mbs, ss, solverType=solver_type))
            message = "" if ok else "Exudyn's solver reported failure"
        except KeyboardInterrupt:
            raise
        except Exception as err:  # Exudyn raises its own error types on solver failure
            ok, message = False, f"{type(err).__name__}: {err}"
    wall = time.perf_counter() - start
    for handle, rate_limit in zip(joints, rate_limits):
        handle.set_impact_step(0.0)  # a later mbs.SolveDynamic must not inherit it
        handle.rate_limit = rate_limit
    if watchdog.interrupted:
        raise KeyboardInterrupt(f"simulation interrupted at t = {mbs.systemData.GetTime():.6g} s")
    it = mbs.sys["dynamicSolver"].it
    steps, rejected = int(it.currentStepIndex) - 1, int(it.rejectedAutomaticStepSizeSteps)
    t_reached = mbs.systemData.GetTime()
    step_notes = []
    with warnings.catch_warnings():  # the joints' own notes are issued below, with the run's
        warnings.simplefilter("ignore", AccuracyWarning)
        for handle in joints:
            step_notes += handle.notes
    for handle in joints:
        reason, when = handle.failure()
        if reason:
            return result(False, f"stopped at t = {when:.6g} s, joint {label(handle)}: {reason}. "
                          f"{_advice(reason, handle)}; results up to then are kept", wall, steps, rejected, t_reached)
    if watchdog.problem:
        return result(False, f"stopped {watchdog.problem}; results up to then are kept", wall, steps, rejected,
                      t_reached)
    if not ok:
        message += (f" (stopped at t = {t_reached:.6g} s of {settings.end_time:g} s{_joints_in_contact(joints)}; "
                    f"{_solver_advice(message, settings)})")
        for note in step_notes:  # with each joint's note on the stop: its regime and |e|/c then
            warnings.warn(note, AccuracyWarning, stacklevel=2)
        return result(ok, message, wall, steps, rejected, t_reached, tuple(step_notes))
    notes = tuple(step_notes)  # with the joints' numerical chatter of implicit runs (diagnostics.chatter_note)
    notes += tuple(n for n in (tilt_note(h, a) for h, a in zip(joints, aligned)) if n)
    for note in notes:
        warnings.warn(note, AccuracyWarning, stacklevel=2)
    return result(ok, message, wall, steps, rejected, t_reached, notes)


def _solver_advice(message: str, settings: SolverSettings) -> str:
    """What to try after Exudyn's solver failed, by its likely cause."""
    if "singular" in message or "not invertible" in message:
        return ("the system's mass matrix or Jacobian is singular: a body without mass or inertia, or redundant "
                "constraints, is the likely cause; a smaller step will not help")
    if not settings.explicit and ("Newton" in message or "SolveDynamic terminated" in message):
        shorten = ("joint_steps=True (Exudyn then shortens a step whose Newton fails), " if not settings.steered
                   and settings.impact_step is None else "")
        return (f"Newton did not converge: try {shorten}a smaller `step`, or looser `newton_rtol` / `newton_atol` "
                f"(now {settings.newton_rtol:g} / {settings.newton_atol:g}) if the residual stalls at round-off")
    return f"try a smaller `step`{' or tolerances' if settings.adaptive else ''}"


def _advice(reason: str, handle: ClearanceJointHandle) -> str:
    if reason.startswith("penetration"):
        c = handle.joint.geometry.clearance
        return (f"The limit is {handle.max_penetration / c:.0%} of the clearance. The contact is too soft for the load, "
                "the step too large, or a unit is off: check E (Pa) and lengths (m), try a smaller step, or raise "
                "`max_penetration` if such penetrations are physical")
    return "Try a smaller step or tighter tolerances"
