"""Hard cases of the journal-bearing scene: the journal under gravity and single impacts."""
from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import NamedTuple

import numpy as np

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models.journal_bearing import JournalBearingParams
from validation import cross_check as cc
from validation.hard_cases.audit import Audit, _finite, audit_journal, static_penetration, step_load_penetration
from validation.hard_cases.common import (
    AUDIT_LIMIT,
    DROPPED_TIME,
    EVERY_STEP,
    GRAVITY,
    LOW_CR_STEP,
    LOW_CRS,
    RESTING_ATOL,
    RESTING_CR,
    RESTING_RTOL,
    RESTING_STEP,
    RESTING_TIME,
    SETTLED_SHARE,
    SLOW_ATOL,
    SLOW_IMPACT_SPEED,
    SLOW_IMPACT_TIME,
    SLOW_RTOL,
    SLOW_STEP,
    STATIC_LIMIT,
    STEP_LOAD_SLACK,
    Outcome,
)
from validation.reference import journal_bearing as jb_reference

# =======================================================================================
# journal under gravity
# =======================================================================================


class JournalRun(NamedTuple):
    """A run of the journal under gravity."""

    params: JournalBearingParams
    sim: exuclear.SimulationResult
    out: dict[str, np.ndarray]
    onsets: list[float]
    audit: Audit
    delta_s: float
    wall: float


def resting_params(start_gap: float = 0.0, v_min: float = exuclear.contact.V_MIN_DEFAULT, gravity: float = GRAVITY,
                   end_time: float = RESTING_TIME) -> JournalBearingParams:
    """The paper's journal (docs/physics.md section 6.1) at rest under gravity, ``start_gap`` from the wall."""
    return JournalBearingParams.paper(cr=RESTING_CR, impact_velocity=0.0, gravity=gravity, start_gap=start_gap,
                                      v_min=v_min, end_time=end_time)


def run_journal(params: JournalBearingParams) -> JournalRun:
    """Build and integrate the journal under gravity; outputs at every step."""
    start = time.perf_counter()
    scene = jb_model.build(params)
    mbs, handle = scene.mbs, scene.joint
    settings = exuclear.SolverSettings(end_time=params.end_time, method="dopri5", step=RESTING_STEP, rtol=RESTING_RTOL,
                                       atol=RESTING_ATOL, output_step=EVERY_STEP)
    sim = exuclear.simulate(mbs, settings)
    out = handle.outputs()
    law = handle.joint.law
    return JournalRun(params, sim, out, list(handle.history.onset_times), audit_journal(params, handle),
                      static_penetration(law, params.mass * params.gravity), time.perf_counter() - start)


def settle_time(run: JournalRun, band: float = 0.01) -> float:
    """First time after which the penetration stays within ``band`` of ``delta_s`` [s]
    (NaN if it never does)."""
    t, d = run.out["time"], run.out["penetration"]
    outside = np.flatnonzero(np.abs(d / run.delta_s - 1.0) > band)
    if len(outside) == 0:
        return float(t[0])
    k = outside[-1] + 1
    return float(t[k]) if k < len(t) else math.nan


def final_error(run: JournalRun) -> float:
    """Mean penetration over the last 10 % of the run, relative to ``delta_s``, minus 1."""
    t, d = run.out["time"], run.out["penetration"]
    tail = t >= 0.9 * t[-1]
    return float(d[tail].mean() / run.delta_s - 1.0)


def case_resting(quick: bool) -> Outcome:
    run = run_journal(resting_params())
    law = JournalBearingParams.paper(cr=RESTING_CR).joint().law
    bound = step_load_penetration(law, run.params.mass * run.params.gravity)
    err, peak = final_error(run), float(run.out["penetration"].max())
    passed = (run.sim.success and _finite(run.out) and abs(err) <= STATIC_LIMIT and len(run.onsets) == 1
              and peak <= bound * (1.0 + STEP_LOAD_SLACK) and abs(run.audit.relative) <= AUDIT_LIMIT)
    measured = (f"delta_s = {run.delta_s * 1e9:.3f} nm (analytic); final penetration {err:+.1e} off; "
                f"{len(run.onsets)} onset; peak {peak / run.delta_s:.3f} delta_s (bound {bound / run.delta_s:.3f}); "
                f"settled to 1 % at {settle_time(run) * 1e3:.2f} ms; {run.sim.steps} steps; audit residual "
                f"{run.audit.relative:+.2%} of gravity's work")
    if not run.sim.success:
        measured += f"; FAILED: {run.sim.message}"
    return Outcome(measured, passed, {"delta_s_m": run.delta_s, "final_error": err, "onsets": len(run.onsets),
                                      "peak_over_delta_s": peak / run.delta_s, "audit": run.audit.relative})


def case_dropped(quick: bool) -> Outcome:
    c = JournalBearingParams.paper().joint().geometry.clearance
    run = run_journal(resting_params(start_gap=c, end_time=DROPPED_TIME))
    err = final_error(run)
    last = run.onsets[-1] if run.onsets else math.nan
    passed = (run.sim.success and _finite(run.out) and abs(err) <= STATIC_LIMIT
              and last <= SETTLED_SHARE * run.params.end_time and abs(run.audit.relative) <= AUDIT_LIMIT)
    measured = (f"{len(run.onsets)} impacts, the last at {last * 1e3:.1f} ms; final penetration {err:+.1e} off "
                f"delta_s; settled to 1 % at {settle_time(run) * 1e3:.1f} ms; {run.sim.steps} steps; "
                f"audit residual {run.audit.relative:+.2%} of gravity's work")
    if not run.sim.success:
        measured += f"; FAILED: {run.sim.message}"
    return Outcome(measured, passed, {"impacts": len(run.onsets), "last_onset_s": last, "final_error": err,
                                      "audit": run.audit.relative})


# =======================================================================================
# single impacts
# =======================================================================================


class ImpactComparison(NamedTuple):
    """An impact in the library and in the reference, and their relative differences."""

    library: jb_model.ImpactResult
    out: dict[str, np.ndarray]
    reference: dict
    errors: dict[str, float]


def compare_impact(params: JournalBearingParams, settings: exuclear.SolverSettings | None = None) -> ImpactComparison:
    """Run one impact in the library and in the reference; errors keyed as
    :data:`validation.cross_check.JB_CRITERIA`."""
    lib, out = jb_model.run(params, settings)
    ref = jb_reference.simulate(params)
    pairs = {"departure": (lib.departure_velocity, ref["departure_velocity"]),
             "peak_force": (lib.max_force, ref["max_force"]),
             "peak_penetration": (lib.max_penetration, ref["max_penetration"]),
             "duration": (lib.contact_duration, ref["contact_duration"])}
    return ImpactComparison(lib, out, ref, {k: (a - b) / b for k, (a, b) in pairs.items()})


def _impact_checks(x: ImpactComparison, keys: Sequence[str]) -> tuple[bool, list[str]]:
    """Completed, left the wall, finite, F_N >= 0, and the given criteria of the cross-check."""
    problems = []
    if not (x.library.success and x.reference["success"]):
        problems.append(f"FAILED: {x.library.message} {x.reference['message']}".strip())
    if not _finite(x.out):
        problems.append("non-finite outputs")
    if x.out["normal_force"].min() < 0.0:
        problems.append("negative normal force")
    limits = {c.key: c.limit for c in cc.JB_CRITERIA}
    problems += [f"{k} off by {x.errors[k]:.1e} (bound {limits[k]:g})" for k in keys if not abs(x.errors[k]) <= limits[k]]
    return not problems, problems


def case_slow_impact(quick: bool) -> Outcome:
    params = JournalBearingParams.paper(impact_velocity=SLOW_IMPACT_SPEED, end_time=SLOW_IMPACT_TIME)
    settings = exuclear.SolverSettings(end_time=params.end_time, method="dopri5", step=SLOW_STEP, rtol=SLOW_RTOL,
                                       atol=SLOW_ATOL, output_step=SLOW_STEP / 10)
    x = compare_impact(params, settings)
    passed, problems = _impact_checks(x, ("departure",))
    cr_eff = x.library.effective_restitution
    measured = (f"effective restitution {cr_eff:.6f} (cr = {params.cr:g}: v0 = 1e-6 m/s is below the floor "
                f"v_min = {params.v_min:g} m/s); departure velocity {x.errors['departure']:+.1e} off the reference; "
                f"peak penetration {x.library.max_penetration * 1e9:.3f} nm, contact {x.library.contact_duration * 1e3:.3f} ms")
    if problems:
        measured += "; " + "; ".join(problems)
    return Outcome(measured, passed, {"effective_restitution": cr_eff, "departure_error": x.errors["departure"]})


def low_restitution_case(law: str, cr: float) -> Callable[[bool], Outcome]:
    def run(quick: bool) -> Outcome:
        params = JournalBearingParams.paper(law=law, cr=cr)
        settings = replace(jb_model.default_settings(params), step=LOW_CR_STEP, output_step=LOW_CR_STEP / 10)
        x = compare_impact(params, settings)
        passed, problems = _impact_checks(x, tuple(c.key for c in cc.JB_CRITERIA))
        worst = max(abs(v) for v in x.errors.values())
        measured = (f"effective restitution {x.library.effective_restitution:.4f}; min F_N "
                    f"{x.out['normal_force'].min():g} N; largest difference from the reference {worst:.1e}")
        if problems:
            measured += "; " + "; ".join(problems)
        return Outcome(measured, passed, {"effective_restitution": x.library.effective_restitution,
                                          "min_force_N": float(x.out["normal_force"].min()), "worst_error": worst})
    return run


def low_restitution_laws() -> tuple[list[str], list[str]]:
    """Laws that accept every cr of :data:`LOW_CRS`, and notes on the others."""
    laws, notes = [], []
    for law in exuclear.contact.CONTACT_LAWS:
        try:
            for cr in LOW_CRS:
                JournalBearingParams.paper(law=law, cr=cr).joint()
        except ValueError as err:
            notes.append(f"{law}: {err}")
            continue
        laws.append(law)
    return laws, notes
