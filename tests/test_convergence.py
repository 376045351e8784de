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


# ---------------------------------------------------------------------------------------
# step="auto" and the plain mbs.SolveDynamic path (issue 21)
# ---------------------------------------------------------------------------------------

def _readme_journal(ss):
    """The README's journal impact, run by a plain ``mbs.SolveDynamic`` with ``ss``."""
    import exudyn as exu
    from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[1e-4, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, cr=0.9)
    mbs.Assemble()
    ok = mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.DOPRI5)
    return RunRecord.from_mbs(mbs, {"J": joint}, success=ok)


def test_a_plain_solve_dynamic_run_is_checked_with_its_own_simulation_settings():
    # the user's main path had no way in: run(ss: exu.SimulationSettings) -> RunRecord.from_mbs
    import exudyn as exu

    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 2e-4  # as in the README: Exudyn's 100 steps, DOPRI5's default tolerances
    ss.solution.sensors.writePeriod = 1e-6
    result = check_convergence(_readme_journal, ss)
    tighter = result.reference_settings.timeIntegration
    assert tighter.numberOfSteps == 400 and ss.timeIntegration.numberOfSteps == 100  # the user's copy is kept
    assert (tighter.relativeTolerance, tighter.absoluteTolerance) == pytest.approx((2.5e-9, 2.5e-9), rel=1e-15)
    assert tighter.endTime == 2e-4 and result.reference_settings.solution.sensors.writePeriod == 1e-6
    # one impact, not chaotic: the whole run agrees, as the SolverSettings path's journal impact does
    assert result.complete and result.end == pytest.approx(2e-4) and result.path_agrees
    assert result.joints["J"].impacts == result.joints["J"].impacts_ref == 1
    assert "exu.SimulationSettings, 100 steps of 2e-06 s" in result.report()


@pytest.fixture(scope="module")
def double_pendulum():
    pytest.importorskip("validation.exudyn_examples")
    from validation.exudyn_examples import double_pendulum_3d

    return double_pendulum_3d


def test_step_auto_refines_the_step_the_run_chose(double_pendulum):
    # SolverSettings(step="auto") made refined_settings divide a string: TypeError
    def run(settings):
        model = double_pendulum.build(True, end_time=0.02)
        return RunRecord.from_handles(exuclear.simulate(model.mbs, settings), {"elbow": model.joint})

    settings = double_pendulum.build(True, end_time=0.02).solver_settings
    assert settings.step == "auto"
    result = check_convergence(run, settings)
    chosen = result.run.step  # result.step of the user's run: min(T_c / 10, end_time / 1000)
    assert 0.0 < chosen <= 0.02 / 1000 and result.settings.step == chosen
    assert result.reference_settings.step == pytest.approx(chosen / 4, rel=1e-15) == result.reference.step
    assert result.complete and f"step {chosen:.3g} s" in result.report()
    with pytest.raises(ValueError, match="`step` is 'auto'"):
        refined_settings(settings)  # no model, no number: said, not a TypeError


def test_the_zoo_double_pendulum_checked_on_its_plain_path(double_pendulum):
    def run(ss):
        model = double_pendulum.build(True, end_time=0.02)
        ok = model.mbs.SolveDynamic(ss, solverType=model.solver_type)
        return RunRecord.from_mbs(model.mbs, {"elbow": model.joint}, success=ok)

    ss = double_pendulum.build(True, end_time=0.02).simulation_settings  # the 1e-4 s steps
    result = check_convergence(run, ss, factor=2.0)
    assert result.reference_settings.timeIntegration.numberOfSteps == 2 * ss.timeIntegration.numberOfSteps == 400
    assert result.complete and result.run.time_reached == pytest.approx(0.02)
    assert set(result.joints) == {"elbow"}
