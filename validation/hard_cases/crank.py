"""Hard cases of the slider-crank: against the SciPy reference, audits, stick-slip, three joints."""
from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import replace
from typing import NamedTuple

import numpy as np

import exuclear
from exuclear.models import slider_crank as sc_model
from exuclear.models.scene import Scene
from exuclear.models.slider_crank import SliderCrankParams
from validation import cross_check as cc
from validation.hard_cases.audit import Audit, _add_body_sensors, _audit_text, _finite, audit_minimal, audit_redundant
from validation.hard_cases.common import (
    COMPARE_TIME,
    CONVERGED,
    CONVERGED_STEP_ANGLE,
    EVERY_STEP,
    HIGH_RPM,
    MU_SLACK,
    PERTURBATION,
    QUICK_REVOLUTIONS,
    REVOLUTIONS,
    Outcome,
)
from validation.reference import slider_crank as sc_reference

# =======================================================================================
# slider-crank
# =======================================================================================


def _with_horizon(params: SliderCrankParams, seconds: float) -> SliderCrankParams:
    return replace(params, revolutions=seconds * params.crank_speed / (2.0 * math.pi))


class CrankRun(NamedTuple):
    """A slider-crank run at the library's default settings, outputs at every step."""

    model: Scene
    sim: exuclear.SimulationResult
    audit: Audit
    wall: float


def run_crank(params: SliderCrankParams, settings: exuclear.SolverSettings | None = None) -> CrankRun:
    """Build, integrate and audit (minimal or redundant formulation)."""
    start = time.perf_counter()
    model = sc_model.build(params)
    sensors = _add_body_sensors(model) if params.formulation == "redundant" else None
    settings = settings or replace(sc_model.default_settings(params), output_step=EVERY_STEP)
    sim = exuclear.simulate(model.mbs, settings)
    audit = audit_minimal(model, sim.steps) if sensors is None else audit_redundant(model, sensors)
    return CrankRun(model, sim, audit, time.perf_counter() - start)


class Agreement(NamedTuple):
    """The library at converged settings against the reference over a short horizon."""

    ecc: float          # max |delta e| / c up to the horizon
    peak_force: float   # relative difference of the peak contact force
    impacts: tuple[int, int]
    horizon: float      # [s]
    end: float          # [s]
    passed: bool
    note: str


def converged_settings(params: SliderCrankParams) -> exuclear.SolverSettings:
    """:data:`CONVERGED` tolerances, steps up to :data:`CONVERGED_STEP_ANGLE` of crank angle,
    outputs at every step longer than 1e-7 s (as the cross-check)."""
    variant = cc.Variant("minimal", "converged", (*CONVERGED, ("step", CONVERGED_STEP_ANGLE / params.crank_speed)))
    return cc.library_settings(params, variant)


def agreement(params: SliderCrankParams, seconds: float, step: float | None = None) -> Agreement:
    """Point-by-point comparison with the SciPy reference, as :mod:`validation.cross_check`
    does, over ``seconds`` (cut where a perturbed reference shows the motion sensitive);
    library settings :func:`converged_settings`, with the largest ``step`` [s] if given."""
    p = _with_horizon(params, seconds)
    ref = cc.reference_run(p)
    perturbed = cc.reference_run(replace(p, clearance=p.clearance * (1.0 + PERTURBATION)))
    t = ref.columns["time"]
    divergence = cc.eccentricity_difference(perturbed.columns, ref.columns) / p.clearance
    beyond = np.flatnonzero(divergence > cc.SENSITIVITY_LIMIT)
    horizon = float(t[beyond[0] - 1]) if len(beyond) else float(t[-1])
    settings = converged_settings(p)
    lib = sc_model.run(p, settings if step is None else replace(settings, step=step))
    # as the cross-check: at the library's own output instants, the reference (sampled every
    # cc.GRID_STEP) interpolated onto them
    keep = lib.columns["time"] <= horizon
    ecc = float(cc.eccentricity_difference(ref.columns, lib.columns)[keep].max() / p.clearance)
    ref_peak = cc.reference_peak_force(p, ref)
    peak = (lib.peak_force - ref_peak) / ref_peak
    impacts = (int(np.sum(lib.onset_times <= horizon)), int(np.sum(ref.onsets <= horizon)))
    limits = {c.key: c.limit for c in cc.SC_CRITERIA}
    passed = (lib.success and ref.success and ecc <= limits["ecc"] and abs(peak) <= limits["peak_force"]
              and impacts[0] == impacts[1])
    note = "" if lib.success and ref.success else f"library: {lib.message}; reference: {ref.message}"
    return Agreement(ecc, peak, impacts, horizon, float(t[-1]), passed, note)


def _agreement_text(a: Agreement) -> str:
    span = f"{a.end * 1e3:.0f} ms" if a.horizon >= a.end else f"{a.horizon * 1e3:.1f} of {a.end * 1e3:.0f} ms (sensitive)"
    return (f"vs reference over {span}: max abs(de)/c {a.ecc:.1e}, peak force {a.peak_force:+.2%}, "
            f"impacts {a.impacts[0]}/{a.impacts[1]}" + (f" ({a.note})" if a.note else ""))


def _crank_summary(run: CrankRun, label: str = "audit") -> tuple[bool, str, dict[str, float]]:
    """Completion, finiteness, penetration limits and the audit of a slider-crank run."""
    problems, worst, peak, impacts = [], 0.0, 0.0, 0
    for name, handle in run.model.joints.items():
        out = handle.outputs()
        if not _finite(out):
            problems.append(f"non-finite outputs at {name}")
        worst = max(worst, float(out["penetration"].max() / handle.max_penetration))
        peak = max(peak, float(np.hypot(out["normal_force"], out["tangential_force"]).max()))
        impacts += handle.history.onsets
    if not run.sim.success:
        problems.append(f"FAILED: {run.sim.message}")
    if not run.audit.passed:
        problems.append(f"{label} beyond its bound")
    text = (f"{run.sim.time_reached:.3g} s in {run.sim.steps} steps; {impacts} impacts; peak force {peak:.0f} N; "
            f"max penetration {worst:.0%} of the limit; {_audit_text(run.audit, label)}")
    values = {"steps": run.sim.steps, "impacts": impacts, "peak_force_N": peak, "penetration_over_limit": worst,
              "audit": run.audit.relative}
    return not problems, text + ("; " + "; ".join(problems) if problems else ""), values


def _redundant_audit(params: SliderCrankParams) -> tuple[bool, str, float]:
    """The same case in redundant coordinates (generalized-alpha at its default steps),
    audited without a flywheel: completes, finite, audit within 1 %."""
    run = run_crank(replace(params, formulation="redundant"))
    finite = all(_finite(h.outputs()) for h in run.model.joints.values())
    passed = run.sim.success and finite and run.audit.passed
    text = _audit_text(run.audit, "redundant-coordinate audit")
    if not run.sim.success:
        text += f" (FAILED: {run.sim.message})"
    elif not finite:
        text += " (non-finite outputs)"
    return passed, text, run.audit.relative


def _slider_crank(params: SliderCrankParams, compare: bool, quick: bool,
                  settings: exuclear.SolverSettings | None = None) -> tuple[CrankRun, bool, str, dict[str, float]]:
    """Minimal run with its audit, the redundant-coordinate audit and, if ``compare``, the reference."""
    run = run_crank(params, settings)
    passed, text, values = _crank_summary(run, "minimal-coordinate audit")
    ok, audit_text, relative = _redundant_audit(params)
    passed, text = passed and ok, f"{text}; {audit_text}"
    values["redundant_audit"] = relative
    if compare:
        a = agreement(params, min(COMPARE_TIME / (2 if quick else 1), params.end_time))
        passed, text = passed and a.passed, f"{text}; {_agreement_text(a)}"
        values.update(ref_ecc=a.ecc, ref_peak_force=a.peak_force, ref_impacts=a.impacts[0])
    return run, passed, text, values


def crank_case(changes: dict[str, object], compare: bool = True, revolutions: float = REVOLUTIONS,
               quick_revolutions: float = QUICK_REVOLUTIONS) -> Callable[[bool], Outcome]:
    """A slider-crank case (see :func:`_slider_crank`)."""
    def run(quick: bool) -> Outcome:
        with warnings.catch_warnings(record=True) as caught:  # shown in the table, not on the console
            warnings.simplefilter("always", exuclear.UnitWarning)
            params = SliderCrankParams.paper(revolutions=quick_revolutions if quick else revolutions, **changes)
            _, passed, text, values = _slider_crank(params, compare, quick)
        if caught:
            text = f"UnitWarning (expected): {caught[0].message}; " + text
        return Outcome(text, passed, values)
    return run


def case_high_speed(quick: bool) -> Outcome:
    """5000 rpm: the slider-crank case, plus the reference comparison at the step bound of
    500 rpm (1e-5 s), reported but not judged (it shows why the bound scales with speed)."""
    outcome = crank_case({"crank_speed": HIGH_RPM * math.pi / 30.0})(quick)
    params = SliderCrankParams.paper(crank_speed=HIGH_RPM * math.pi / 30.0)
    fixed = agreement(params, COMPARE_TIME / (2 if quick else 1), step=1e-5)
    note = (f" (not judged: the same comparison with steps up to 1e-5 s, as at 500 rpm: max abs(de)/c {fixed.ecc:.1e}, "
            f"impacts {fixed.impacts[0]}/{fixed.impacts[1]})")
    return Outcome(outcome.measured + note, outcome.passed, {**outcome.values, "ref_ecc_step_1e-5": fixed.ecc})


def stick_slip_params(quick: bool) -> SliderCrankParams:
    """The stick-slip case: the paper's slider-crank with its friction law."""
    return SliderCrankParams.paper(friction="paper", revolutions=QUICK_REVOLUTIONS * 2 if quick else REVOLUTIONS)


def case_stick_slip(quick: bool) -> Outcome:
    """The paper's modified Coulomb law on the slider-crank: the slip must reverse in contact."""
    params = stick_slip_params(quick)
    run, passed, text, values = _slider_crank(params, True, quick)
    out = run.model.joint.outputs()
    law = run.model.joint.joint.friction
    reversals, stick, mu = slip_statistics(out, law.v_s)
    ok = reversals >= params.revolutions and mu <= law.mu_s + MU_SLACK
    text = (f"{reversals} slip reversals in contact over {params.revolutions:g} revolutions; {stick:.1%} of the "
            f"contact time in the stiction band abs(v_T) < v_s; max abs(F_T)/F_N {mu:.6f}; " + text)
    values.update(reversals=reversals, stick_share=stick, max_mu=mu)
    return Outcome(text, passed and ok, values, {"stick_slip": (params, out, law)})


def slip_statistics(out: dict[str, np.ndarray], v_s: float) -> tuple[int, float, float]:
    """Sign changes of the slip velocity between consecutive in-contact records, the share
    of contact time with ``|v_T| < v_s``, and the largest ``|F_T| / F_N``."""
    contact = out["in_contact"] > 0.0
    v = out["slip_velocity"]
    both = contact[1:] & contact[:-1]
    reversals = int(np.sum(both & (v[1:] * v[:-1] < 0.0)))
    dt = np.diff(out["time"])
    in_band = both & (np.abs(v[1:]) < v_s)
    stick = float(dt[in_band].sum() / dt[both].sum()) if both.any() else 0.0
    f_n = out["normal_force"][contact]
    mu = float(np.max(np.abs(out["tangential_force"][contact]) / f_n, initial=0.0, where=f_n > 0.0))
    return reversals, stick, mu


def case_three_joints(quick: bool) -> Outcome:
    """Clearance at O, A and B: redundant formulation, generalized-alpha."""
    params = SliderCrankParams.paper(formulation="redundant", clearance_joints=("O", "A", "B"),
                                     revolutions=QUICK_REVOLUTIONS if quick else REVOLUTIONS)
    run = run_crank(params)
    passed, text, values = _crank_summary(run)
    # slider against the ideal mechanism: each joint shifts the loop by at most c + its
    # penetration; along X directly, across through the rod angle (|tan phi| <= r / sqrt(l^2 - r^2))
    p, mbs = params, run.model.mbs
    x = np.asarray(mbs.GetSensorStoredData(run.model.sensors["slider_x"]))
    ideal = sc_reference.ideal_kinematics(p, x[:, 0])["slider_x"]
    deviation = float(np.abs(x[:, 1] - ideal).max())
    slack = sum(p.clearance + max(h.outputs()["penetration"].max(), 0.0) for h in run.model.joints.values())
    bound = (1.0 + p.crank_length / math.sqrt(p.rod_length**2 - p.crank_length**2)) * slack
    text = f"slider off the ideal mechanism by {deviation * 1e6:.1f} um (bound {bound * 1e6:.1f} um); " + text
    values.update(slider_deviation_m=deviation, deviation_bound_m=bound)
    return Outcome(text, passed and deviation <= bound, values)
