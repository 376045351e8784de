"""exuclear.check_convergence (issue 15, section 2): refinement rule, horizons on known
paths, a non-chaotic impact that agrees over the whole run, and the four-bar whose path
parts from the tighter run's.  In the runs, the tighter run is the reference; every
number checked is recomputed here from the two runs' raw records."""
from __future__ import annotations

import math

import numpy as np
import pytest

import exuclear
from exuclear import RunRecord, SolverSettings, check_convergence
from exuclear.convergence import JointRecord, refined_settings
from exuclear.history import ImpactRecord
from exuclear.models import four_bar
from exuclear.models.journal_bearing import JournalBearingParams, build, default_settings

C = 1e-4  # clearance of the synthetic records [m]


# ---------------------------------------------------------------------------------------
# the refinement rule
# ---------------------------------------------------------------------------------------

def test_refinement_rule_per_method():
    adaptive = refined_settings(SolverSettings(end_time=0.1, method="dopri5", step=1e-4, rtol=1e-7, atol=1e-10), 4.0)
    assert (adaptive.step, adaptive.rtol, adaptive.atol) == pytest.approx((2.5e-5, 2.5e-8, 2.5e-11), rel=1e-15)
    fixed = refined_settings(SolverSettings(end_time=0.1, method="rk44", step=1e-5), 2.0)
    assert (fixed.step, fixed.rtol) == (5e-6, 1e-6)  # tolerances unused by a fixed step: kept
    implicit = refined_settings(SolverSettings(end_time=0.1, method="generalized-alpha", step=2e-5,
                                               impact_step=1e-6), 4.0)
    assert (implicit.step, implicit.impact_step, implicit.rtol) == pytest.approx((5e-6, 2.5e-7, 1e-6), rel=1e-15)
    plain = refined_settings(SolverSettings(end_time=0.1, method="trapezoidal", step=1e-5), 10.0)
    assert plain.step == pytest.approx(1e-6, rel=1e-15) and plain.impact_step is None
    assert implicit.output_step == 1e-5  # the outputs are compared at the same interval


@pytest.mark.parametrize("kwargs, message", [
    ({"factor": 1.0}, "`factor` must exceed 1"),
    ({"factor": -2.0}, "`factor` must be positive"),
    ({"bound": 0.0}, "`bound` must be positive"),
    ({"bound": 2.0}, "`bound` must lie in"),
])
def test_bad_options_are_refused_before_any_run(kwargs, message):
    def never(settings):
        raise AssertionError("no run may start")

    with pytest.raises(ValueError, match=message):
        check_convergence(never, SolverSettings(end_time=0.1), **kwargs)


def test_a_callable_that_returns_no_record_is_refused():
    with pytest.raises(ValueError, match="must return a RunRecord"):
        check_convergence(lambda s: {"joints": {}}, SolverSettings(end_time=0.1))
    with pytest.raises(ValueError, match="nothing to compare"):
        RunRecord.from_handles(None, {})


# ---------------------------------------------------------------------------------------
# known paths (synthetic records): the horizon and the impact sequence
# ---------------------------------------------------------------------------------------

def _joint(t: np.ndarray, ex: np.ndarray, impacts: list[ImpactRecord]) -> JointRecord:
    zeros = np.zeros_like(t)
    out = {"time": t, "ecc_x": ex, "ecc_y": zeros, "normal_force": zeros, "tangential_force": zeros,
           "in_contact": zeros}
    return JointRecord(C, out, tuple(impacts))


def _impacts(onsets: list[float]) -> list[ImpactRecord]:
    return [ImpactRecord(t, 0.05, 500.0, 40e-6, 1e-6) for t in onsets]


def test_horizon_of_an_exponentially_growing_difference():
    # run and reference differ by 1e-4 c exp(t / tau): the difference reaches 1 % of c at
    # t* = tau ln(100), known in closed form
    tau, end = 0.05, 0.5
    t = np.linspace(0.0, end, 50001)  # 1e-5 s, the scenes' output interval
    base = 0.5 * C * np.sin(40.0 * t)
    onsets = [0.02 * k for k in range(1, 25)]
    reference = RunRecord({"J": _joint(t, base, _impacts(onsets))})
    extra = sorted(onsets + [0.4])  # the run has one impact more, at 0.4 s
    run = RunRecord({"J": _joint(t, base + 1e-4 * C * np.exp(t / tau), _impacts(extra))})
    calls = []

    def model(settings):
        calls.append(settings)
        return reference

    result = check_convergence(model, SolverSettings(end_time=end, method="generalized-alpha", step=1e-5),
                               baseline=run)
    assert len(calls) == 1 and calls[0].step == pytest.approx(2.5e-6)  # only the tighter run was made
    j = result.joints["J"]
    # linear interpolation of an exponential between 1e-5 s samples: error below
    # (1e-5)^2 / 8 / tau^2 relative, far below 1e-6 s in the crossing time
    assert j.horizon == pytest.approx(tau * math.log(100.0), abs=1e-6)
    assert not j.path_agrees and not result.path_agrees
    assert j.max_de == pytest.approx(1e-4 * math.exp(end / tau), rel=1e-12)
    assert f"agrees until t = {j.horizon:.6g} s" in result.report()
    # impacts: those before the horizon match one by one; the extra one ends the sequence
    before = sum(1 for t0 in onsets if t0 <= j.horizon)
    assert (j.impacts_in_horizon_ref, j.matched_in_horizon) == (before, before)
    assert j.impact_horizon == pytest.approx(0.4)
    assert (j.impacts, j.impacts_ref) == (25, 24)
    count = j.statistics[0]
    assert count.name == "impact count" and count.agrees  # |25 - 24| <= 2 sqrt(24)


def test_a_shifted_impact_is_found_and_identical_paths_agree():
    t = np.linspace(0.0, 0.1, 10001)
    e = 0.9 * C * np.cos(30.0 * t)
    onsets = [0.01, 0.03, 0.05, 0.07]
    shifted = [0.01, 0.03, 0.05 + 100e-6, 0.07]  # 100 us: longer than the 40 us contact
    result = check_convergence(lambda s: RunRecord({"J": _joint(t, e, _impacts(onsets))}),
                               SolverSettings(end_time=0.1, method="generalized-alpha", step=1e-5),
                               baseline=RunRecord({"J": _joint(t, e, _impacts(shifted))}))
    j = result.joints["J"]
    assert result.path_agrees and j.horizon == pytest.approx(0.1) and j.max_de == 0.0
    assert j.impact_horizon == pytest.approx(0.05)  # the reference's onset of the shifted pair
    assert j.onset_shift_max == pytest.approx(100e-6)
    assert "AGREES over the whole run" in result.report()


# ---------------------------------------------------------------------------------------
# runs of the scenes
# ---------------------------------------------------------------------------------------

def _de(run: JointRecord, reference: JointRecord, end: float) -> tuple[np.ndarray, np.ndarray]:
    """|e - e_ref| / c on the reference's output times up to ``end``, computed here."""
    t_ref = reference.outputs["time"]
    keep = t_ref <= end
    t = t_ref[keep]
    dx = np.interp(t, run.outputs["time"], run.outputs["ecc_x"]) - reference.outputs["ecc_x"][keep]
    dy = np.interp(t, run.outputs["time"], run.outputs["ecc_y"]) - reference.outputs["ecc_y"][keep]
    return t, np.hypot(dx, dy) / reference.clearance


def test_journal_bearing_impact_agrees_over_the_whole_run():
    params = JournalBearingParams.paper()

    def model(settings):
        scene = build(params)
        return RunRecord.from_handles(exuclear.simulate(scene.mbs, settings), {"journal": scene.joint})

    result = check_convergence(model, default_settings(params))
    j = result.joints["journal"]
    assert result.complete and result.path_agrees and j.horizon == result.end == pytest.approx(params.end_time)
    a, b = result.run.joints["journal"], result.reference.joints["journal"]
    t, de = _de(a, b, result.end)
    assert j.max_de == pytest.approx(de.max(), rel=1e-12)
    # DOPRI5 at rtol 1e-9 and 4 times tighter: the peak penetrations differ by ~1e-7 c
    # (measured 3.7e-7 for the path); 1e-5 leaves a factor of 30 for round-off on other
    # platforms and is still a thousandth of the 1 % bound
    assert j.max_de < 1e-5
    # one impact in each, matched: onset at t = 0 in both (it starts in contact), onset
    # velocity the initial 0.3 m/s exactly
    assert len(a.impacts) == len(b.impacts) == 1 and j.matched_in_horizon == 1
    assert j.onset_shift_max == 0.0 and j.onset_velocity_diff_max == 0.0
    # peak force from accepted steps of 1e-7 s and 2.5e-8 s: relative difference 5.8e-6
    # measured; 1e-4 is four times the cross-check's agreement with the independent
    # SciPy reference (2.3e-5, README)
    assert abs(j.peak_force_rel) < 1e-4
    assert j.peak_force_rel == pytest.approx((a.impacts[0].peak_force - b.impacts[0].peak_force)
                                             / b.impacts[0].peak_force, rel=1e-6, abs=1e-12)
    report = result.report()
    assert "AGREES over the whole run" in report and "settings are converged" in report


@pytest.fixture(scope="module")
def four_bar_check():
    """The four-bar's documented case at its default settings against step / 4 (about 7 s)."""
    return four_bar.check_convergence(four_bar.FourBarParams.crank_rocker())


def test_four_bar_path_stops_agreeing_within_the_run(four_bar_check):
    result = four_bar_check
    p = four_bar.FourBarParams.crank_rocker()
    assert result.complete and result.end == pytest.approx(p.end_time)
    j = result.joints["B"]
    # a finite horizon, shorter than the run
    assert not result.path_agrees and 0.0 < j.horizon < 0.9 * result.end
    # the horizon is what it claims, recomputed from the raw outputs: |de|/c stays under
    # 1 % before it and exceeds 1 % within two output intervals (2e-5 s) after it
    a, b = result.run.joints["B"], result.reference.joints["B"]
    t, de = _de(a, b, result.end)
    assert de[t < j.horizon].max() <= result.bound
    assert de[(t >= j.horizon) & (t <= j.horizon + 2e-5)].max() > result.bound
    assert j.max_de == pytest.approx(de.max(), rel=1e-12) and j.max_de > 5 * result.bound
    report = result.report()
    assert f"path: agrees until t = {j.horizon:.6g} s" in report
    assert f"trust the joints' paths up to t = {j.horizon:.6g} s only" in report
    assert "agree only statistically" in report


def test_four_bar_impacts_before_the_horizon_are_the_same(four_bar_check):
    j = four_bar_check.joints["B"]
    a, b = four_bar_check.run.joints["B"], four_bar_check.reference.joints["B"]
    # counts from the raw records
    assert (j.impacts, j.impacts_ref) == (len(a.impacts), len(b.impacts))
    n_a = int(np.sum(a.onset_times <= j.horizon))
    n_b = int(np.sum(b.onset_times <= j.horizon))
    assert (j.impacts_in_horizon, j.impacts_in_horizon_ref) == (n_a, n_b)
    # while the paths agree to 1 % of c, the impact sequences are the same
    assert n_a == n_b == j.matched_in_horizon > 10
    # onsets: paths 1 % of c apart reach the wall at most about 0.01 c / |v0| apart (a
    # slow approach makes the onset time ill-conditioned: 318 us at 14 mm/s here); a
    # factor 2 for the approach's curvature (the acceleration over that time)
    for r in b.impacts:
        if r.onset_time > j.horizon:
            break
        nearest = a.impacts[int(np.argmin(np.abs(a.onset_times - r.onset_time)))]
        allowed = max(r.duration, 2.0 * four_bar_check.bound * b.clearance / abs(r.onset_velocity))
        assert abs(nearest.onset_time - r.onset_time) <= allowed


# ---------------------------------------------------------------------------------------
# command lines
# ---------------------------------------------------------------------------------------

def test_slider_crank_flag_reports_agreement_on_a_short_run(capsys):
    from exuclear.models import slider_crank

    # half a revolution of the paper's case: the start-up impacts only, no chaos
    assert slider_crank.main(["--revolutions", "0.5", "--check-convergence"]) == 0
    out = capsys.readouterr().out
    assert "Convergence check: dopri5" in out and "rtol, atol and largest step / 4" in out
    assert "Joint B (clearance 0.1 mm):" in out
    assert "path: AGREES over the whole run" in out


def test_four_bar_command_line(capsys):
    assert four_bar.main(["--revolutions", "0.25", "--check-convergence"]) == 0
    out = capsys.readouterr().out
    assert "four-bar, generalized-alpha" in out and "step and impact step / 4" in out
    assert "Joint B (clearance 0.5 mm):" in out and "Signals" in out
    assert four_bar.main(["--rpm", "0"]) == 2
    assert "error: `rpm` must be non-zero" in capsys.readouterr().err


def test_signals_only_horizon_relative_to_the_range():
    # a signal of range 2 (a sine) and a run that drifts linearly by 2 % of the range over
    # the run: it leaves 1 % of the range at half the run, in closed form
    t = np.linspace(0.0, 1.0, 100001)
    y_ref = np.sin(2.0 * np.pi * 5.0 * t)
    run = RunRecord({}, {"y": (t, y_ref + 0.04 * t)})
    result = check_convergence(lambda s: RunRecord({}, {"y": (t, y_ref)}),
                               SolverSettings(end_time=1.0, method="generalized-alpha", step=1e-5), baseline=run)
    s = result.signals["y"]
    assert s.scale == pytest.approx(2.0, rel=1e-6)  # sampled sine: peaks hit to 1e-6
    assert s.horizon == pytest.approx(0.5, abs=1e-5) and not s.path_agrees and not result.signals_agree
    assert s.spectrum.agrees  # a slow drift moves no line of a 5 Hz sine
    assert "signals part: y at t = 0.5" in result.report()
