"""Hard cases (issue 6): stability at the edges, failure handling, bad input.

Source problem: docs/physics.md (the paper's journal-bearing scene, section 6.1, and slider-crank, 6.2)
and the study :mod:`validation.hard_cases`, whose helpers these tests use; the bad
inputs and their documented replies are those of :mod:`validation.bad_input` and
``docs/bad_input.md``.  The full study is marked slow.
"""
from __future__ import annotations

import math
import os
import re
import warnings
from dataclasses import replace

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams
from validation import bad_input
from validation import hard_cases as hc

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# --------------------------------------------------------------------------------------
# grazing and permanent contact
# --------------------------------------------------------------------------------------
def test_static_penetration_solves_the_law():
    # K_eff(delta) delta^1.5 = m g for Wang-Liu (delta-dependent K_eff), and the closed form
    # (m g / K)^(2/3) for the constant-stiffness Hertz law (docs/physics.md eqs. (9), (13)); Brent's method
    # converges to ~1e-14 relative, so 1e-12 only allows for round-off
    law = JournalBearingParams.paper().joint().law
    load = 0.04 * 9.81
    d_s = hc.static_penetration(law, load)
    k0 = math.pi * law.E_star * law.geometry.length / 2.0
    assert k0 * math.sqrt(1.0 / (2.0 * (law.geometry.clearance + d_s))) * d_s**1.5 == pytest.approx(load, rel=1e-12)
    hertz = JournalBearingParams.paper(law="hertz", cr=1.0).joint().law
    assert hc.static_penetration(hertz, load) == pytest.approx((load / hertz.stiffness(0.0)) ** (2 / 3), rel=1e-12)
    # the elastic step-load bound of a Hertz contact is 2.5^(2/3) delta_s (energy balance)
    assert hc.step_load_penetration(hertz, load) == pytest.approx(2.5 ** (2 / 3) * hc.static_penetration(hertz, load),
                                                                  rel=1e-10)
    with pytest.raises(ValueError, match="`load` must lie in"):
        hc.static_penetration(law, 1e12)


@pytest.fixture(scope="module")
def resting() -> hc.JournalRun:
    return hc.run_journal(hc.resting_params())


def test_resting_journal_settles_to_the_static_penetration(resting):
    assert resting.sim.success, resting.sim.message
    # the oscillation about delta_s decays as exp(-zeta omega t), zeta ~ 0.03 at the default
    # floor: < 1e-7 after 20 ms; tolerances allow ~6e-7 of delta_s; 1e-3 has a wide margin
    assert abs(hc.final_error(resting)) < 1e-3
    # set down at delta = 0 it never leaves the wall again (no chatter) ...
    assert len(resting.onsets) == 1
    # ... and overshoots at most to the elastic step-load bound (damping only lowers it)
    law = resting.params.joint().law
    bound = hc.step_load_penetration(law, resting.params.mass * resting.params.gravity)
    assert resting.delta_s < resting.out["penetration"].max() <= bound * (1 + 1e-3)
    assert all(np.all(np.isfinite(v)) for v in resting.out.values())


def test_resting_journal_energy_audit(resting):
    # gravity's work = kinetic energy + energy absorbed; the dissipated part is a trapezoid
    # rule over ~3600 steps of a 4.8 kHz oscillation: measured 2e-4 of the work; bound 1 %
    # (hc.AUDIT_LIMIT, its reason there)
    assert resting.audit.passed
    assert abs(resting.audit.relative) < hc.AUDIT_LIMIT


def test_grazing_impact_agrees_with_reference():
    # v0 = 1e-6 m/s (docs/physics.md section 8: the floor's regime); the reference integrates the same law
    # with DOP853 at rtol 1e-11, so the departure velocities agree to its tolerance
    params = JournalBearingParams.paper(impact_velocity=hc.SLOW_IMPACT_SPEED, end_time=hc.SLOW_IMPACT_TIME)
    settings = exuclear.SolverSettings(end_time=params.end_time, method="dopri5", step=hc.SLOW_STEP,
                                       rtol=hc.SLOW_RTOL, atol=hc.SLOW_ATOL, output_step=hc.SLOW_STEP / 10)
    x = hc.compare_impact(params, settings)
    assert x.library.success, x.library.message
    assert abs(x.errors["departure"]) < 1e-6
    # below the floor the damping term is scaled by v0 / v_min = 1e-3: almost elastic,
    # 1 - e ~ (2/3) D v0 / v_min = 1.2e-4 for cr = 0.9 (D = 0.174)
    assert 1 - 3e-4 < x.library.effective_restitution < 1 - 3e-5


# --------------------------------------------------------------------------------------
# low restitution, every law
# --------------------------------------------------------------------------------------
LOW_CR_LAWS, _ = hc.low_restitution_laws()


def test_every_law_but_the_elastic_one_takes_low_restitution():
    # Hertz is elastic (cr = 1 only, docs/physics.md section 7); every other law must accept cr = 0.05
    assert sorted(LOW_CR_LAWS) == sorted(set(exuclear.contact.CONTACT_LAWS) - {"hertz"})


@pytest.mark.parametrize("law", LOW_CR_LAWS)
def test_low_restitution_no_negative_force_no_nan(law):
    params = JournalBearingParams.paper(law=law, cr=0.05)
    settings = replace(jb_model.default_settings(params), step=hc.LOW_CR_STEP, output_step=hc.LOW_CR_STEP / 10)
    x = hc.compare_impact(params, settings)
    assert x.library.success, x.library.message
    assert all(np.all(np.isfinite(v)) for v in x.out.values())
    assert x.out["normal_force"].min() >= 0.0
    assert 0.0 < x.library.departure_velocity < params.impact_velocity  # left the wall, lost energy
    # the cross-check's bounds against the reference (their reasons: cross_check.JB_CRITERIA)
    for criterion in hc.cc.JB_CRITERIA:
        assert abs(x.errors[criterion.key]) <= criterion.limit, criterion.label


# --------------------------------------------------------------------------------------
# high speed: energy audit
# --------------------------------------------------------------------------------------
def test_energy_audit_at_5000_rpm():
    # half a revolution at 5000 rpm (6 ms, 9 impacts, peak force 36 kN); audits as in the
    # study, against 1 % of the contact's gross work (hc.AUDIT_LIMIT, its reason there):
    # minimal run plus the flywheel round-off (measured 0.04 %, round-off 0.09 %),
    # redundant run (measured 0.01 %)
    params = SliderCrankParams.paper(crank_speed=5000 * math.pi / 30, revolutions=0.5)
    minimal = hc.run_crank(params)
    assert minimal.sim.success, minimal.sim.message
    assert minimal.model.joint.history.onsets >= 5
    assert minimal.audit.passed, minimal.audit
    redundant = hc.run_crank(replace(params, formulation="redundant"))
    assert redundant.sim.success, redundant.sim.message
    assert abs(redundant.audit.relative) < hc.AUDIT_LIMIT, redundant.audit


def test_audit_fails_when_energy_goes_missing():
    # the audit must fail when energy goes missing: drop the friction work from the books
    # (as a force mapped without its moment would) and the residual is that work
    params = SliderCrankParams.paper(friction="paper", revolutions=0.25, formulation="redundant")
    run = hc.run_crank(params)
    friction = sum(np.trapezoid(o["tangential_force"] * o["slip_velocity"], o["time"])
                   for o in (h.outputs() for h in run.model.joints.values()))
    assert friction > 10 * hc.AUDIT_LIMIT * run.audit.scale  # ten times the bound: no borderline case
    broken = run.audit._replace(dissipated=run.audit.dissipated - friction,
                                residual=run.audit.residual + friction)
    assert run.audit.passed and not broken.passed


# --------------------------------------------------------------------------------------
# stick-slip
# --------------------------------------------------------------------------------------
def test_stick_slip_reverses_the_slip_with_the_modified_coulomb_law():
    # the paper's law (mu_s 0.3, mu_d 0.25, v_s 0.1 mm/s, v_d 10 mm/s) on the slider-crank:
    # the rod turns back relative to the slider twice a revolution (crank at 90 and 270
    # degrees), and in permanent contact the slip must follow it through zero
    params = SliderCrankParams.paper(friction="paper", revolutions=1.0)
    run = hc.run_crank(params)
    assert run.sim.success, run.sim.message
    out = run.model.joint.outputs()
    law = run.model.joint.joint.friction
    assert isinstance(law, exuclear.friction.ModifiedCoulomb) and (law.mu_s, law.mu_d) == (0.3, 0.25)
    reversals, stick, mu = hc.slip_statistics(out, law.v_s)
    assert reversals >= 2
    assert 0.0 < stick < 1.0  # it passes through the stiction band, and slides too
    # |F_T| / F_N reaches mu_s (at |v_T| = v_s) and never exceeds it (1e-9: round-off)
    assert law.mu_s - 1e-3 < mu <= law.mu_s + hc.MU_SLACK
    ratio = out["tangential_force"][out["in_contact"] > 0] / out["normal_force"][out["in_contact"] > 0]
    assert ratio.min() < -law.mu_d + 1e-3 and ratio.max() > law.mu_d - 1e-3  # both directions of sliding


# --------------------------------------------------------------------------------------
# when a run cannot continue
# --------------------------------------------------------------------------------------
def test_too_soft_material_stops_with_time_joint_advice_and_kept_results():
    # E = 0.2 GPa lets the first impact sink past the 50 um bound (half the clearance)
    soft = exuclear.Material(2e8, 0.3, "soft")
    params = SliderCrankParams.paper(journal_material=soft, bearing_material=soft)
    result = sc_model.run(params)
    assert not result.success
    message = result.message
    assert message.startswith("stopped at t = ")
    assert "joint 'B'" in message and "penetration" in message and "exceeds the limit" in message
    assert "try a smaller step" in message and "check E (Pa)" in message
    assert "results up to then are kept" in message
    t_stop = float(message.split("t = ")[1].split(" s")[0])
    times = result.columns["time"]
    # outputs end at the last accepted step before the one that crossed the bound (default steps <= 1e-4 s)
    assert len(times) > 10 and times[-1] < t_stop <= times[-1] + 1e-4 and times[-1] < params.end_time
    assert np.all(np.isfinite(result.columns["contact_force"]))


def test_too_large_step_stops_with_time_and_advice():
    # generalized-alpha at a fixed 2e-4 s (no impact-aware steps) cannot resolve the impacts
    # (~40 us each): the penetration passes the joint's limit at t = 8 ms (with a coarser
    # Jacobian, Newton failed first; either way the run stops with the time and the advice)
    params = SliderCrankParams.paper(formulation="redundant")
    result = sc_model.run(params, replace(sc_model.default_settings(params), step=2e-4, impact_step=None,
                                          joint_steps=False))
    assert not result.success
    assert "stopped at t = " in result.message and re.search(r"try a smaller `?step", result.message)
    assert 0 < result.columns["time"][-1] < params.end_time


def test_non_finite_state_stops_with_joint_and_time():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[1e-4, 0, 0], initialVelocities=[math.nan, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    exuclear.CreateClearanceJoint(mbs, "J1", [ground, body], useGlobalFrame=False, **bad_input.PAPER, cr=0.9)
    mbs.Assemble()
    # issue 15: a NaN initial velocity is bad input, named as such before any step (no step advice)
    with pytest.raises(ValueError, match="initial velocity 0 .* is nan"):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3))


def test_cli_run_failure_writes_the_csv_and_says_incomplete(tmp_path):
    # a 1 um penetration bound stops the run in the first impact (its peak is ~5 um)
    path = tmp_path / "out.csv"
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = sc_model.main(["--max-penetration", "1e-6", "--csv", str(path)])
    assert status == 1
    assert "error: stopped at t = " in err.getvalue() and "INCOMPLETE" in err.getvalue()
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0].startswith("# INCOMPLETE: stopped at t = ") and lines[1].startswith("time,")  # marked in the file too
    data = np.loadtxt(path, delimiter=",", skiprows=2)
    assert 10 < len(data) and data[-1, 0] < sc_model.SliderCrankParams.paper().end_time


# --------------------------------------------------------------------------------------
# the resting-journal scene of exuclear.models.journal_bearing
# --------------------------------------------------------------------------------------
def test_journal_bearing_scene_checks_its_new_inputs():
    with pytest.raises(ValueError, match="`start_gap` must not exceed the clearance"):
        jb_model.build(JournalBearingParams.paper(start_gap=2e-4))
    with pytest.raises(ValueError, match="nothing moves"):
        jb_model.build(JournalBearingParams.paper(impact_velocity=0.0))
    with pytest.raises(ValueError, match="`gravity` must be non-negative"):
        jb_model.build(JournalBearingParams.paper(gravity=-9.81))
    with pytest.raises(ValueError, match=r"run\(\) summarises one impact"):
        jb_model.run(JournalBearingParams.paper(gravity=9.81))
    # a journal started at the centre (start_gap = c, with round-off) is accepted
    c = JournalBearingParams.paper().joint().geometry.clearance
    jb_model.build(JournalBearingParams.paper(start_gap=1e-4, impact_velocity=0.0, gravity=9.81))
    assert abs(1e-4 - c) < 1e-18


# --------------------------------------------------------------------------------------
# bad input: every row of docs/bad_input.md
# --------------------------------------------------------------------------------------
with open(os.path.join(ROOT, bad_input.DOC), encoding="utf-8") as _f:
    DOC_LINES = set(_f.read().splitlines())


def _row_id(case: bad_input.BadInput) -> str:
    return f"{case.surface}: {bad_input._machine_free(case.code)[:60]}"


@pytest.mark.parametrize("case", bad_input.BAD_INPUTS, ids=_row_id)
def test_bad_input_row_is_documented(case):
    # the table says what the library answers today (regenerate it with
    # `python -m validation.bad_input --write docs/bad_input.md` when a reply changes)
    reply = bad_input.attempt(case)
    assert bad_input.table_row(case, reply) in DOC_LINES


@pytest.mark.parametrize("case", [
    pytest.param(c, marks=pytest.mark.xfail(strict=True, reason=c.gap)) if c.gap else c
    for c in bad_input.BAD_INPUTS], ids=_row_id)
def test_bad_input_gets_the_reply_the_rules_ask_for(case):
    reply = bad_input.attempt(case)
    assert reply.kind != "traceback"
    assert case.satisfied_by(reply), reply
    if case.surface == "CLI" and reply.kind.startswith("exit 2"):
        assert reply.message.splitlines()[-1].split("error: ")[-1]  # says why


@pytest.mark.parametrize("args, message", [
    (("exuclear.models.slider_crank", "--clearance-joints", "XB"), "error: `clearance_joints` must name some of O, A, B"),
    (("exuclear.models.journal_bearing", "--mass", "nan"), "error: `mass` must be finite, got nan"),
])
def test_cli_bad_input_in_a_real_process(args, message):
    # the in-process replies above stand for real runs: two of them as `python -m`
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    assert message in proc.stderr and "Traceback" not in proc.stderr


def test_unit_warnings_do_not_stop_a_valid_run():
    # a likely unit mistake is a warning, not an error: the run goes on
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        params = SliderCrankParams.paper(clearance=1e-3, revolutions=0.05)
    assert any(issubclass(w.category, exuclear.UnitWarning) for w in caught)
    assert sc_model.run(params).success


# --------------------------------------------------------------------------------------
# the study
# --------------------------------------------------------------------------------------
@pytest.mark.slow
def test_quick_study_writes_its_report(tmp_path, capsys):
    # the whole quick study (about a minute): every case passes, and the report has them all
    status = hc.main(["--quick", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert f"case {len(hc.CASES)}/{len(hc.CASES)}:" in out
    report = (tmp_path / "hard_cases.md").read_text(encoding="utf-8")
    for case in hc.CASES:
        assert case.title in report
    for name in ("hard_cases.csv", "v_min_floor.csv", "resting_journal.png", "stick_slip.png"):
        assert (tmp_path / name).exists()
    assert status == 0, report
