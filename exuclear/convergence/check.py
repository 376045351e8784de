"""The convergence check (:func:`check_convergence`) and its result (:class:`ConvergenceResult`)."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from ..checks import check_positive
from ..settings import SolverSettings
from .compare import (
    DEFAULT_BOUND,
    IMPACT_RTOL,
    JointComparison,
    SignalComparison,
    Statistic,
    _compare_joint,
    _compare_signal,
)
from .records import RunRecord
from .refine import DEFAULT_FACTOR, _describe, _end_time, _rule, refined_settings


@dataclass(frozen=True)
class ConvergenceResult:
    """Outcome of :func:`check_convergence`; :meth:`report` says it in words.

    Attributes
    ----------
    settings, reference_settings : SolverSettings or exu.SimulationSettings
        The user's settings (with the step the run chose where they said
        ``step="auto"``) and the tighter ones (the reference).
    factor, bound : float
        The refinement factor and the path bound (fraction of the clearance).
    run, reference : RunRecord
        Both runs' records.
    end : float
        End of the compared span [s]: where both runs have results.
    joints : dict of str to JointComparison
    signals : dict of str to SignalComparison
    horizon : float
        The earliest joint path horizon [s].
    path_agrees : bool
        Every joint's path stays within the bound over the whole run, and both runs completed.
    signals_agree : bool
        Every named signal stays within the bound over the whole run.
    """

    settings: Any
    reference_settings: Any
    factor: float
    bound: float
    run: RunRecord
    reference: RunRecord
    end: float
    joints: dict[str, JointComparison]
    signals: dict[str, SignalComparison]

    @property
    def horizon(self) -> float:
        return min((j.horizon for j in self.joints.values()), default=self.end)

    @property
    def complete(self) -> bool:
        """Both runs reached the end time."""
        return self.run.success and self.reference.success

    @property
    def path_agrees(self) -> bool:
        """Every joint's path agrees over the whole run, and both runs completed (signals aside)."""
        return self.complete and all(j.path_agrees for j in self.joints.values())

    @property
    def signals_agree(self) -> bool:
        """Every named signal agrees within the bound over the whole run."""
        return all(s.path_agrees for s in self.signals.values())

    def statistics_agree(self) -> bool:
        """Every statistical comparison of every joint and signal agrees."""
        return (all(s.agrees for j in self.joints.values() for s in j.statistics)
                and all(s.spectrum.agrees for s in self.signals.values()))

    def report(self) -> str:
        """The comparison in words: what agrees, over which horizon, and what only statistically."""
        pct = 100.0
        lines = [f"Convergence check: {_describe(self.settings)}",
                 f"  against a tighter run ({_rule(self.settings, self.factor)}): {_describe(self.reference_settings)};",
                 "  the tighter run is the reference, its difference the error of the run."]
        for label, rec in (("run", self.run), ("reference", self.reference)):
            if not rec.success:
                lines.append(f"  The {label} STOPPED EARLY at t = {rec.time_reached:.6g} s: {rec.message}")
        lines.append(f"  Compared over 0 .. {self.end:.6g} s{'' if self.complete else ' (where both have results)'}.")
        for name, j in self.joints.items():
            lines.append(f"Joint {name} (clearance {j.clearance * 1e3:.4g} mm):")
            if j.path_agrees:
                lines.append(f"  path: AGREES over the whole run: max |de|/c = {j.max_de:.2g} <= {self.bound:g}")
            else:
                lines.append(f"  path: agrees until t = {j.horizon:.6g} s ({j.horizon / self.end * pct:.0f} % of the "
                             f"run; max |de|/c {j.max_de_in_horizon:.2g} <= {self.bound:g} until then), then "
                             f"parts: max |de|/c = {j.max_de:.3g} over the run")
            lines.append(f"  impacts one by one up to t = {j.horizon:.6g} s: {j.matched_in_horizon} of "
                         f"{j.impacts_in_horizon_ref} reference impacts matched ({j.impacts_in_horizon} in the run); "
                         f"onset shift <= {j.onset_shift_max * 1e6:.3g} us, onset velocity within "
                         f"{j.onset_velocity_diff_max * pct:.2g} %, peak force within {j.peak_force_diff_max * pct:.2g} %")
            seq = ("over the whole run" if j.impact_horizon >= self.end
                   else f"until t = {j.impact_horizon:.6g} s ({j.impact_horizon / self.end * pct:.0f} % of the run)")
            lines.append(f"  impact sequence (onset, v0 and peak force within {IMPACT_RTOL * pct:g} %) matches {seq}")
            lines.append(f"  peak force: {j.peak_force:.5g} N vs {j.peak_force_ref:.5g} N "
                         f"({j.peak_force_rel * pct:+.2g} %) over the run; {j.peak_force_horizon:.5g} N vs "
                         f"{j.peak_force_horizon_ref:.5g} N ({j.peak_force_horizon_rel * pct:+.2g} %) within the horizon")
            lines.append("  statistics over the run (run vs reference):")
            lines += [f"    {_statistic_line(s)}" for s in j.statistics]
        if self.signals:
            lines.append("Signals (bound: the same fraction of each signal's range in the reference):")
            for s in self.signals.values():
                when = ("AGREES over the whole run" if s.path_agrees
                        else f"agrees until t = {s.horizon:.6g} s ({s.horizon / self.end * pct:.0f} % of the run)")
                lines.append(f"  {s.name}: {when}; max difference {s.max_diff_rel * pct:.2g} % of its range "
                             f"{s.scale:.4g}")
                lines.append(f"    {_statistic_line(s.spectrum)}")
        lines.append("Verdict:")
        parted = [s for s in self.signals.values() if not s.path_agrees]
        if not self.joints:
            lines.append("  no clearance joint was recorded: " + (
                "every signal agrees over the whole run at this bound." if not parted and self.complete else
                "signals part: " + ", ".join(f"{s.name} at t = {s.horizon:.6g} s" for s in parted) + "."))
        elif self.path_agrees:
            lines.append("  the joints' paths agree over the whole run at this bound: the settings are converged "
                         "for this model and run length.")
            if parted:
                lines.append("  but not every signal: " + ", ".join(f"{s.name} only until t = {s.horizon:.6g} s"
                                                                    for s in parted) + ".")
        else:
            lines.append(f"  trust the joints' paths up to t = {self.horizon:.6g} s only; after it the runs follow "
                         "different paths.")
            if parted:
                lines.append("  signals: " + ", ".join(f"{s.name} until t = {s.horizon:.6g} s" for s in parted) + ".")
            held = [s.name.split(" (")[0] for j in self.joints.values() for s in j.statistics if s.agrees]
            held += [s.spectrum.name.split(" (")[0] for s in self.signals.values() if s.spectrum.agrees]
            failed = [s.name.split(" (")[0] for j in self.joints.values() for s in j.statistics if not s.agrees]
            failed += [s.spectrum.name.split(" (")[0] for s in self.signals.values() if not s.spectrum.agrees]
            if held:
                lines.append(f"  agree only statistically: {', '.join(held)}.")
            if failed:
                lines.append(f"  do not agree even statistically: {', '.join(failed)}; tighten the settings "
                             "(or run longer for statistics) before using them.")
        return "\n".join(lines)


def _statistic_line(s: Statistic) -> str:
    verdict = "agrees" if s.agrees else "DIFFERS"
    if math.isnan(s.value):
        return f"{s.name}: {s.rule}"
    if s.name.startswith("spectrum"):
        return f"{s.name} {s.value:.3g}: {verdict} ({s.rule})"
    return f"{s.name}: {s.value:.4g} vs {s.reference:.4g}: {verdict} ({s.rule})"


def _end(rec: RunRecord) -> float:
    ends = [rec.time_reached] + [float(j.outputs["time"][-1]) for j in rec.joints.values() if j.outputs["time"].size]
    ends += [float(t[-1]) for t, _ in rec.signals.values() if t.size]
    return min(ends)


def check_convergence(run: Callable[[Any], RunRecord], settings: Any, *,
                      factor: float = DEFAULT_FACTOR, bound: float = DEFAULT_BOUND,
                      baseline: RunRecord | None = None) -> ConvergenceResult:
    """Rerun a model at tighter settings and compare (module docstring).

    Parameters
    ----------
    run : callable
        ``run(settings) -> RunRecord``: builds the model, runs it with the given
        settings and returns its record.  Called once with ``settings`` (unless
        ``baseline`` is given), then once with the tighter settings.  Joints and signals
        are matched by name.  Either path:

        - ``settings`` a :class:`SolverSettings`: ``run`` calls
          ``result = exuclear.simulate(mbs, settings)`` and returns
          ``RunRecord.from_handles(result, {"B": joint})``;
        - ``settings`` an ``exu.SimulationSettings``: ``run`` calls
          ``mbs.SolveDynamic(settings, solverType=...)`` and returns
          ``RunRecord.from_mbs(mbs, {"B": joint})``.
    settings : SolverSettings or exu.SimulationSettings
        The user's settings (:func:`refined_settings` makes the tighter ones).  With
        ``step="auto"`` the first run chooses the step (its record's ``step``, from
        ``result.step``), and that step is refined.
    factor : float
        Refinement factor (> 1), see :func:`refined_settings`; default :data:`DEFAULT_FACTOR`.
    bound : float
        Path bound as a fraction of each joint's clearance (and of each signal's range),
        in (0, 1]; default :data:`DEFAULT_BOUND` (1 %).
    baseline : RunRecord, optional
        The record of a run at ``settings`` already made (saves one run).

    Returns
    -------
    ConvergenceResult
    """
    if not callable(run):
        raise ValueError(f"`run` must be a callable run(settings) -> RunRecord, got {type(run).__name__}")
    automatic = isinstance(settings, SolverSettings) and (settings.automatic or settings.method_from_model)
    if not automatic:
        refined_settings(settings, factor)  # bad settings or factor fail before any run
    elif check_positive("factor", factor) <= 1.0:
        raise ValueError(f"`factor` must exceed 1 (the reference must be tighter), got {factor}")
    if not 0.0 < check_positive("bound", bound) <= 1.0:
        raise ValueError(f"`bound` must lie in (0, 1] (a fraction of the clearance), got {bound}")
    first = baseline if baseline is not None else run(settings)
    label = "baseline" if baseline is not None else "run(settings)"
    if not isinstance(first, RunRecord):
        raise ValueError(f"{label} must return a RunRecord (RunRecord.from_handles or .from_mbs), got "
                         f"{type(first).__name__}")
    if automatic and settings.method_from_model:  # the method the model chose is the one refined
        if not first.method:
            raise ValueError(f"`method` is 'auto' but {label}'s record does not say which method the run chose: build "
                             "it with RunRecord.from_handles(result, ...), whose result.method it is")
        settings = replace(settings, method=first.method)
    if automatic and settings.automatic:  # the step the model chose is the one refined
        if not math.isfinite(first.step):
            raise ValueError(f"`step` is 'auto' but {label}'s record does not say which step the run chose: build it "
                             "with RunRecord.from_handles(result, ...), whose result.step it is")
        settings = replace(settings, step=first.step, joint_steps=settings.steered)
    reference_settings = refined_settings(settings, factor)
    # the joints' own steps are refined with the solver's: exuclear.simulate sets their rate_limit
    # from the refined SolverSettings, a plain mbs.SolveDynamic's joints read the factor from
    # the refined exu.SimulationSettings (RefinedSimulationSettings)
    second = run(reference_settings)
    if not isinstance(second, RunRecord):
        raise ValueError(f"run(tighter settings) must return a RunRecord (RunRecord.from_handles or .from_mbs), got "
                         f"{type(second).__name__}")
    if set(first.joints) != set(second.joints) or set(first.signals) != set(second.signals):
        raise ValueError(f"the two runs recorded different joints or signals: {sorted(first.joints)} "
                         f"{sorted(first.signals)} and {sorted(second.joints)} {sorted(second.signals)}")
    end = min(_end(first), _end(second), _end_time(settings))
    joints = {k: _compare_joint(first.joints[k], second.joints[k], end, bound) for k in second.joints}
    signals = {k: _compare_signal(k, first.signals[k], second.signals[k], end, bound) for k in second.signals}
    return ConvergenceResult(settings, reference_settings, float(factor), float(bound), first, second, end,
                             joints, signals)
