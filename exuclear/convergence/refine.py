"""The convergence check's tighter run: its settings from the user's (:func:`refined_settings`)."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from ..checks import check_positive
from ..settings import SolverSettings

#: Default refinement factor: steps (and tolerances of adaptive methods) divided by 4.  A
#: second-order method's error then drops 16-fold, so the difference to the tighter run
#: is the user's error to within about 7 %; a factor of 2 (4-fold, within 33 %) would
#: blur that, and 10 would cost 10 times the user's run.
DEFAULT_FACTOR = 4.0


def refined_settings(settings: SolverSettings, factor: float = DEFAULT_FACTOR) -> SolverSettings:
    """The tighter settings of the check.

    Explicit adaptive methods (DOPRI5, ODE23): ``rtol``, ``atol`` and the largest step
    divided by ``factor`` (an error-controlled method at a tighter tolerance, its step
    limit with it).  Explicit fixed-step (RK44): the step divided.  Implicit methods
    (generalized-alpha, trapezoidal): the step and, with impact-aware steps, the
    ``impact_step`` divided; with steps the joints control (``joint_steps``), their
    ``rate_limit`` divided.  The output interval and everything else are kept.

    ``step="auto"`` has no number to divide until the model is built: give the settings
    with the step the run chose (``result.step``); :func:`check_convergence` does so.

    An ``exu.SimulationSettings`` (for a plain ``mbs.SolveDynamic``, which is given the
    solver type separately) is refined as a copy: ``timeIntegration.numberOfSteps``
    times ``factor`` (the step, and the largest step of adaptive solvers, divided),
    ``minimumStepSize`` divided, and with ``automaticStepSize`` (explicit adaptive
    solvers; implicit ones ignore these) ``relativeTolerance``, ``absoluteTolerance`` and
    a given ``initialStepSize`` divided.  The copy is an
    :class:`exuclear.engine.steering.RefinedSimulationSettings`, which also carries
    ``factor`` to the clearance joints' own step control: each joint of a run given these
    settings divides its ``rate_limit`` by it for that run.
    """
    if check_positive("factor", factor) <= 1.0:
        raise ValueError(f"`factor` must exceed 1 (the reference must be tighter), got {factor}")
    if _exudyn_settings(settings):
        return _refined_exudyn_settings(settings, factor)
    if not isinstance(settings, SolverSettings):
        raise ValueError(f"`settings` must be a SolverSettings or an exu.SimulationSettings, got "
                         f"{type(settings).__name__}")
    if settings.method_from_model:
        raise ValueError("`method` is 'auto', which is chosen from the model: refine the settings with the method "
                         "the run chose, dataclasses.replace(settings, method=result.method)")
    if settings.automatic:
        raise ValueError("`step` is 'auto', which is chosen from the model: refine the settings with the step the "
                         "run chose, dataclasses.replace(settings, step=result.step)")
    step = settings.step / factor
    changes: dict[str, Any] = {"step": step, "min_step": min(settings.min_step, step)}
    if settings.explicit and settings.adaptive:
        changes.update(rtol=settings.rtol / factor, atol=settings.atol / factor)
    elif not settings.explicit and settings.impact_step is not None:
        changes["impact_step"] = settings.impact_step / factor
    elif settings.steered:  # the joints' step control is the accuracy of these steps
        changes["rate_limit"] = settings.rate_limit / factor
    return replace(settings, **changes)


def _exudyn_settings(settings: object) -> bool:
    """Whether ``settings`` is an ``exu.SimulationSettings`` (told by its shape: this
    module does not import exudyn)."""
    return hasattr(getattr(settings, "timeIntegration", None), "numberOfSteps")


def _refined_exudyn_settings(settings: Any, factor: float) -> Any:
    """A copy of the ``exu.SimulationSettings`` ``settings``, refined (:func:`refined_settings`)."""
    from ..engine.steering import RefinedSimulationSettings  # exudyn is imported where its settings are given

    # a copy (the user's settings stay as they are) whose joints divide their rate_limit by factor
    tighter = RefinedSimulationSettings(settings, getattr(settings, "joint_refinement", 1.0) * factor)
    ti = tighter.timeIntegration
    ti.numberOfSteps = math.ceil(settings.timeIntegration.numberOfSteps * factor - 1e-9)
    ti.minimumStepSize = settings.timeIntegration.minimumStepSize / factor
    if ti.automaticStepSize:
        ti.relativeTolerance = settings.timeIntegration.relativeTolerance / factor
        ti.absoluteTolerance = settings.timeIntegration.absoluteTolerance / factor
        ti.initialStepSize = settings.timeIntegration.initialStepSize / factor  # 0: the solver's own choice
    return tighter


def _end_time(settings: Any) -> float:
    return float(settings.timeIntegration.endTime) if _exudyn_settings(settings) else settings.end_time


def _rule(settings: Any, factor: float) -> str:
    if _exudyn_settings(settings):
        tolerances = "rtol, atol, " if settings.timeIntegration.automaticStepSize else ""
        return f"{tolerances}step and minimum step / {factor:g}"
    if settings.explicit and settings.adaptive:
        return f"rtol, atol and largest step / {factor:g}"
    if settings.explicit:
        return f"step / {factor:g}"
    if settings.steered:
        return f"largest step / {factor:g} (the joints' step control unchanged)"
    return f"step{' and impact step' if settings.impact_step is not None else ''} / {factor:g}"


def _describe(settings: Any) -> str:
    if _exudyn_settings(settings):
        ti = settings.timeIntegration
        s = (f"exu.SimulationSettings, {ti.numberOfSteps:.0f} steps of {(ti.endTime - ti.startTime) / ti.numberOfSteps:.3g} s, "
             f"minimum step {ti.minimumStepSize:.3g} s")
        if ti.automaticStepSize:
            s += f", rtol {ti.relativeTolerance:.3g}, atol {ti.absoluteTolerance:.3g}"
        return s
    s = f"{settings.method}, step {settings.step:.3g} s"
    if settings.explicit and settings.adaptive:
        s += f" (largest), rtol {settings.rtol:.3g}, atol {settings.atol:.3g}"
    if settings.impact_step is not None:
        s += f", impact step {settings.impact_step:.3g} s"
    if settings.steered:
        s += " (largest; the joints control the steps)"
    return s
