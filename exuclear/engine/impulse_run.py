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
#: What a stop for a held contact's penetration says of the steps (:func:`stopped`).
LOST_THE_CONTACT = ("the steps are too long for the motion across the clearance, or the condition could not follow the "
                    "contact; take shorter steps")
#: A penetration's stop is laid to the trapezoidal rule's alternation (:func:`stopped`) where the
#: held contact's end multipliers changed sign at each of its last this many held steps: a load
#: that turns changes sign once, the alternation at every step.
ALTERNATING_STEPS = 4


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


def stopped(name: str, t: float, reason: str, steps: str = "", held: Sequence[tuple[float, float]] = (),
            step: float = 0.0) -> str:
    """The message of a run the joint ``name`` stops at ``t`` [s] for ``reason``.  A stop for a
    penetration says ``steps``, what the steps' length did, unless the end multipliers ``held``
    ((time [s], multiplier [N]) of the held steps, the last last; none in a system the mode
    settles: :mod:`~exuclear.engine.settling`) changed sign at each of the last
    :data:`ALTERNATING_STEPS`, the last of them within the run's own ``step`` [s] before the
    stop: then the trapezoidal rule's alternation asked the contact to pull, and shorter steps
    do not take it out."""
    head = f"joint {name or '(unnamed)'}: contact_mode='impulse' stops the run at t = {t:.6g} s: {reason}"
    forces = [force for _, force in held[-ALTERNATING_STEPS:]]
    if len(forces) < ALTERNATING_STEPS or not steps or t - held[-1][0] > step or \
            any(a * b >= 0.0 for a, b in zip(forces, forces[1:])):
        return f"{head}{': ' + steps if steps else ''}; or use contact_mode='compliant'"
    return (f"{head}: its held contact's multiplier changed sign at each of its last {len(forces)} held steps (between "
            f"{min(forces):.3g} and {max(forces):.3g} N, the last at t = {held[-1][0]:.6g} s): under the trapezoidal "
            "rule (spectral radius 1) a system the mode does not settle (a flexible body, a force element) keeps a "
            "step-to-step alternation in every multiplier, undamped (a stiff mode with omega h >> 1 alternates of "
            "itself, a jump's error returns at each step, a position-level prescribed coordinate whose rate jumps "
            "alternates about that rate; an ideal joint's reaction alternates alike), here larger than the contact's "
            "load, and a clearance joint cannot pull; shorter steps do not take it out: use contact_mode='compliant', "
            "under numerical damping (spectral radius below 1)")


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
