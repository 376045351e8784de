"""Running the sweeps and the diagnostic runs of the report (tolerance ladder, contact
histories, v0 floored at the first impact's speed)."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

import exuclear
from exuclear.models.slider_crank import SliderCrankParams, SliderCrankResult
from validation.slider_crank.cases import TOLERANCE_LADDER, Runner, Sweep, Variant, case_values, describe, ideal_params
from validation.slider_crank.metrics import (
    CaseMetrics,
    HistoryStats,
    IdealForce,
    closed_form_error,
    history_stats,
    ideal_force_stats,
    metrics_of,
    response_lag,
    tangential_mode_range,
)

# -- running the study ----------------------------------------------------------------

#: A finished sweep: each variant with its parameters, result and metrics.
SweepRows = list[tuple[Variant, SliderCrankParams, SliderCrankResult, CaseMetrics]]


#: The extreme cases of the tolerance ladder: (cr, friction).
LADDER_CASES = ((0.3, "paper"), (0.9, "none"))


def sweep_cases(sweep: Sweep, **changes: object) -> list[tuple[Variant, SliderCrankParams]]:
    """Each variant of ``sweep`` with its parameters (and ``changes`` on top)."""
    return [(v, SliderCrankParams.paper(**v.changes, **changes)) for v in sweep.variants]


def ladder_cases(revolutions: float) -> list[tuple[SliderCrankParams, float, float]]:
    """``(params, rtol, atol)`` of the tolerance ladder."""
    return [(SliderCrankParams.paper(cr=cr, friction=friction, revolutions=revolutions), rtol, atol)
            for cr, friction in LADDER_CASES for rtol, atol in TOLERANCE_LADDER]


def first_runs(sweeps: Sequence[Sweep], revolutions: float) -> list[dict[str, object]]:
    """Every run that waits for no other: the ideal mechanism, the sweeps, the tolerance
    ladder and the contact histories (:func:`case_values`), for one call of the runner."""
    cases = [case_values(ideal_params(revolutions))]
    cases += [case_values(p) for s in sweeps for _, p in sweep_cases(s)]
    cases += [case_values(p, rtol, atol) for p, rtol, atol in ladder_cases(revolutions)]
    cases += [case_values(p, every_step=True) for s in sweeps for _, p in sweep_cases(s)]
    return cases


def run_sweep(runner: Runner, sweep: Sweep, ideal: dict[str, np.ndarray], index: int, total: int) -> SweepRows:
    """Every variant of ``sweep`` with its metrics (run first if not run yet)."""
    print(f"sweep {index}/{total}: {sweep.title}", flush=True)
    rows = []
    for variant, params in sweep_cases(sweep):
        result = runner.result(params)
        rows.append((variant, params, result, metrics_of(params, result, ideal)))
    return rows


def sweep_lags(rows: SweepRows, ideal: dict[str, np.ndarray]) -> list[float]:
    """Lag of each variant's response behind the first variant's (see :func:`response_lag`)."""
    reference = rows[0][2]
    return [response_lag(result.columns, reference.columns, ideal) if result.success and reference.success
            else float("nan") for _, _, result, _ in rows]


@dataclass
class Diagnostics:
    """The diagnostic runs of the report."""

    tolerance: list[tuple[str, float, SliderCrankResult, CaseMetrics]]
    histories: dict[tuple[str, str], HistoryStats]     # (sweep stem, variant value) -> stats
    frozen_v_min: float
    frozen: dict[str, SweepRows]                       # friction -> cr sweep with v0 floored
    ideal_force: IdealForce
    mode_range: tuple[float, float]
    closed_form_error: float                           # max |fx / m_slider - a_slider of the ideal run| [m/s^2]


def tolerance_ladder(runner: Runner, ideal: dict[str, np.ndarray],
                     revolutions: float) -> list[tuple[str, float, SliderCrankResult, CaseMetrics]]:
    """The extreme cases (cr 0.3 with friction, cr 0.9 without) at each tolerance of the ladder."""
    print("diagnostics: solver tolerance ladder", flush=True)
    rows = []
    for params, rtol, atol in ladder_cases(revolutions):
        result = runner.result(params, rtol, atol)
        rows.append((describe(params), rtol, result, metrics_of(params, result, ideal)))
    return rows


def contact_histories(runner: Runner, sweeps: Sequence[Sweep]) -> dict[tuple[str, str], HistoryStats]:
    """:func:`history_stats` of every clearance case, from runs recording every step."""
    print("diagnostics: contact histories at every accepted step", flush=True)
    stats = {}
    for sweep in sweeps:
        for variant, params in sweep_cases(sweep):
            hist = runner.history(params)
            if hist.success:
                stats[(sweep.stem, variant.value)] = history_stats(params, hist)
    return stats


def frozen_v0_sweeps(runner: Runner, sweeps: Sequence[Sweep], v_min: float,
                     ideal: dict[str, np.ndarray]) -> dict[str, SweepRows]:
    """The restitution sweeps again with ``v_min`` raised to ``v_min`` (a parameter of the law)."""
    print(f"diagnostics: restitution sweeps with v0 floored at the first impact's {v_min:.4g} m/s", flush=True)
    cr_sweeps = [sweep for sweep in sweeps if sweep.kind == "cr"]
    runner.run([case_values(p) for sweep in cr_sweeps for _, p in sweep_cases(sweep, v_min=v_min)])
    frozen = {}
    for sweep in cr_sweeps:
        rows = []
        for variant, params in sweep_cases(sweep, v_min=v_min):
            result = runner.result(params)
            rows.append((variant, params, result, metrics_of(params, result, ideal)))
        frozen[sweep.friction] = rows
    return frozen


def run_diagnostics(runner: Runner, sweeps: Sequence[Sweep], ideal: dict[str, np.ndarray],
                    revolutions: float) -> Diagnostics:
    """All diagnostic runs (see the module docstring)."""
    tolerance = tolerance_ladder(runner, ideal, revolutions)
    histories = contact_histories(runner, sweeps)
    firsts = [h.v0_first for h in histories.values()]
    v_min = max(firsts) if firsts else exuclear.contact.V_MIN_DEFAULT
    frozen = frozen_v0_sweeps(runner, sweeps, v_min, ideal)
    paper = SliderCrankParams.paper(revolutions=revolutions)
    force = ideal_force_stats(paper)
    return Diagnostics(tolerance, histories, v_min, frozen, force, tangential_mode_range(paper, force),
                       closed_form_error(paper, ideal))
