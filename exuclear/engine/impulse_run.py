"""What the impulse contact mode (:mod:`~exuclear.engine.impulse`) needs of a run, checked
at its start, and what a run leaves: the check that its decisions ran to the run's end,
its impacts in closed form, and the note on impacts whose impulses added energy."""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import NamedTuple

import exudyn as exu
import numpy as np

from ..contact.law import ContactLaw
from ..timescales import closed_form_impact
from .steering import explicit_solver

#: Spectral radius of generalized-alpha the mode needs: 1 (the trapezoidal rule, under which
#: a velocity jump is exact).  Exudyn keeps the radius to round-off; the tolerance only
#: absorbs that.
SPECTRAL_RADIUS_TOLERANCE = 1e-12
#: An impact step whose impulses' work is more than this share of the sum of its terms'
#: sizes (``|P| (|v_before| + |v_after|) / 2`` of each row) added energy: below it the work
#: is round-off of the multipliers and rates (Exudyn's Newton iteration leaves them some
#: 1e-10 off), about a frictionless elastic jump's, whose exact work is 0.
GAIN_TOLERANCE = 1e-9


def run_settings(mbs: exu.MainSystem) -> tuple[int, float]:
    """Exudyn's discontinuous iterations per step and the run's own step [s], read at a run's
    start; ``ValueError`` saying what to set where the run cannot hold the mode's conditions
    (an explicit solver, numerical damping, fewer than two computations of a step)."""
    solver = getattr(mbs, "sys", {}).get("dynamicSolver")
    if solver is None or explicit_solver(solver):
        raise ValueError("an explicit solver (or a run not started by SolveDynamic) has no condition to hold the "
                         "contact")
    if abs(float(solver.spectralRadius) - 1.0) > SPECTRAL_RADIUS_TOLERANCE:
        raise ValueError(f"generalized-alpha's spectral radius is {float(solver.spectralRadius):g}: under numerical "
                         "damping the velocity jump leaks into the following steps; set "
                         "timeIntegration.generalizedAlpha.spectralRadius = 1")
    settings = getattr(mbs, "sys", {}).get("simulationSettings")
    iterations = int(settings.timeIntegration.discontinuous.maxIterations) if settings else 2
    ti = settings.timeIntegration if settings else None
    nominal = (ti.endTime - ti.startTime) / max(1, ti.numberOfSteps) if ti else solver.it.currentStepSize
    if iterations < 2:
        raise ValueError("it computes a step again where an impact begins, which needs "
                         "timeIntegration.discontinuous.maxIterations of at least 2 (Exudyn's default is 5)")
    return iterations, nominal


def check_ran(mbs: exu.MainSystem | None, name: str, last: float | None,
              held: Callable[[], str] = lambda: "") -> None:
    """That the joint ``name``'s decisions ran to the end of the last run of ``mbs`` (its last
    accepted step ended at ``last`` [s], None: none): ``ValueError`` under an explicit solver,
    ``RuntimeError`` where Exudyn's Newton iteration failed (``held()`` says what the joint
    held in its last solve) or Exudyn did not call them."""
    if mbs is None:
        return
    solver = getattr(mbs, "sys", {}).get("dynamicSolver")
    if last is None and solver is not None and explicit_solver(solver):
        # Exudyn's explicit solvers abort at their start on the mode's condition (a
        # constraint), before any step: its message names an object, not the joint
        raise ValueError(f"joint {name or '(unnamed)'}: contact_mode='impulse' cannot run under an explicit "
                         "solver: its condition is a constraint, which explicit solvers refuse; use "
                         "generalized-alpha (spectral radius 1), or contact_mode='compliant'")
    end = float(mbs.systemData.GetTime())
    if solver is not None and not explicit_solver(solver) and not solver.conv.newtonConverged:
        # a failed Newton iteration ends the run whether or not the solver's time moved past
        # the last accepted step (at the minimum step it stays there)
        raise RuntimeError(f"joint {name or '(unnamed)'}: the run ended at t = {max(end, last or 0.0):.6g} s, where Exudyn's Newton "
                           f"iteration failed{held()}; take shorter steps, or use contact_mode='compliant'")
    if end > (last or 0.0) + 1e-12 * max(1.0, end):
        raise RuntimeError(f"joint {name or '(unnamed)'}: the impulse mode did not run to t = {end:g} s (its "
                           f"last step ended at {last or 0.0:g} s): Exudyn did not call its post-Newton function (an "
                           "explicit solver, or timeIntegration.discontinuous.maxIterations = 0); use "
                           "generalized-alpha with its discontinuous iteration, or contact_mode='compliant'")


class ClosedFormImpact(NamedTuple):
    """One impact of the impulse mode (SI units): its time and velocity, with the peak force,
    the duration and the largest penetration the joint's law gives at that velocity in
    closed form (``closed_form`` is True: no force pulse was integrated), and the
    restitution the step applied."""

    onset_time: float
    onset_velocity: float
    peak_force: float
    duration: float
    max_penetration: float
    restitution: float
    effective_mass: float
    closed_form: bool = True


def closed_form_impacts(law: ContactLaw, records: Sequence[tuple[float, float, float, float]],
                        bodies_mass: Callable[[], float]) -> list[ClosedFormImpact]:
    """The impacts ``records`` (time, normal velocity, restitution, the impact step's impulse)
    of a contact whose law is ``law``, in closed form (:class:`ClosedFormImpact`)."""
    out = []
    for t, v, restitution, impulse in records:
        # the solver's own effective mass at the contact (closed loops included): the impact
        # step's impulse over the velocity change; a resting contact's first step also
        # carries the load, so there the bodies' reduced mass stands in
        if restitution > 0.0 and math.isfinite(impulse):
            mass = abs(impulse) / (v * (1.0 + restitution))
        else:
            mass = bodies_mass()
        peak, duration, depth = closed_form_impact(law, mass, v) if mass > 0.0 and v > 0.0 else (math.nan,) * 3
        out.append(ClosedFormImpact(t, v, peak, duration, depth, restitution, mass))
    return out


def gains_note(jumps: Sequence[tuple[float, float, float]]) -> list[str]:
    """The note on the impact steps ``jumps`` (time, work of the impulses [J], the sum of its
    terms' sizes; a joint's contacts' together, summed per step) whose impulses added energy:
    how many, the largest gain and its time (none: no note)."""
    steps: dict[float, np.ndarray] = {}
    for t, work, size in jumps:
        steps[t] = steps.get(t, np.zeros(2)) + (work, size)
    gains = [(t, work) for t, (work, size) in steps.items() if work > GAIN_TOLERANCE * size]
    if not gains:
        return []
    t, gain = max(gains, key=lambda g: g[1])
    return [f"{len(gains)} impacts added energy, up to {gain:.3g} J (at t = {t:.6g} s): Newton's restitution with "
            "Coulomb's bound stopped a slip coupled to the normal by a friction impulse along it (Kane and "
            "Levinson's paradox); contact_mode='compliant' integrates the pulse and dissipates"]
