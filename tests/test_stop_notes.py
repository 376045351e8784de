"""Issue 30, item 4: a run that Exudyn ends early while a clearance joint is in the model
leaves a note (an AccuracyWarning and ``joint.notes``) naming the joint, the time, the
joint's regime with |e|/c, and the cause Exudyn's solver flags give
(``exuclear.engine.diagnostics.stopped_note``), whatever the regime: free flight, metal contact,
the film or its blend.  And item 3's IFToMM four-bar, which stops at its change point.
"""
from __future__ import annotations

import warnings

import pytest

import exuclear
from validation.exudyn_examples import REGISTRY, four_bar_iftomm, load_models

load_models()
#: Newton tolerances no residual reaches (below the round-off of any force): Newton fails in
#: the first step, whatever the regime.
UNREACHABLE = 1e-16


def _stop(model, adaptive=False):
    ti = model.simulation_settings.timeIntegration
    ti.newton.relativeTolerance = ti.newton.absoluteTolerance = UNREACHABLE
    ti.adaptiveStep = adaptive
    with pytest.raises(Exception, match="SolveDynamic terminated"):
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    with pytest.warns(exuclear.AccuracyWarning, match="ended the run") as caught:
        notes = model.joint.notes
    assert len(notes) == 1 and str(caught[0].message) == notes[0]
    return notes[0]


def test_a_stop_in_free_flight_is_told():
    # the IFToMM four-bar's journal starts centred; with 10 fixed steps over 1 ms the step
    # after t = 2e-4 s fails, before the journal has crossed its 50 um gap
    model = four_bar_iftomm.build(True, 0.001)
    model.simulation_settings.timeIntegration.numberOfSteps = 10
    note = _stop(model)
    assert "joint 'middle pivot'" in note and "at t = 0.0002 s of 0.001 s" in note
    assert "its Newton did not converge at the fixed step (timeIntegration.adaptiveStep is False)" in note
    assert "in free flight (|e|/c = 0.00" in note  # 0.0011 at the last accepted step, 2e-4 s
    assert "absoluteTolerance >= 1e-08, now 1e-16" in note  # the user's tolerance, kept and named


def test_a_stop_in_the_film_is_told():
    # the zoo's lubricated piston engine: its big end rides on the film from the start
    # (eps below eps_film = 0.9, test_exudyn_examples.py), and Exudyn's step reduction meets
    # the minimum step in the first step
    model = REGISTRY["piston_engine_lubricated"](True, 0.01)
    note = _stop(model, adaptive=True)
    assert "joint 'big end 0'" in note and "at t = 0 s of 0.01 s" in note
    assert "the step reduction reached the minimum step (1e-08 s)" in note
    assert "carried by the film (|e|/c = " in note and "<= eps_film = 0.9)" in note


def test_a_user_stop_is_told_without_advice():
    model = four_bar_iftomm.build(True, 0.05)
    model.mbs.SetPostStepUserFunction(lambda mbs, t: t < 0.02 - 1e-12)
    model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    with pytest.warns(exuclear.AccuracyWarning, match="stopped by the user"):
        notes = model.joint.notes
    t = model.mbs.systemData.GetTime()  # the first accepted step at or after 0.02 s
    assert 0.02 <= t < 0.025 and f"at t = {t:.6g} s of 0.05 s" in notes[0] and "|e|/c = " in notes[0] and "try" not in notes[0]


def test_the_iftomm_four_bar_stops_at_its_change_point_and_says_so():
    # fourBarMechanismIftomm.py's own settings (1e-2 s, Exudyn's default tolerances): the
    # cranks reach the ground line at t = 0.71 s, where the joints' constraint Jacobian
    # loses rank; the middle pivot is in contact, Newton's residual stalls at short steps
    # (the ideal model stops there too at 1e-5 s steps, four_bar_iftomm's docstring).  The
    # joint's absolute tolerance is set (1e-8); the note names the cause and the regime.
    model = four_bar_iftomm.build(True)
    with pytest.raises(Exception, match="SolveDynamic terminated"):
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.systemData.GetTime() == pytest.approx(0.7115, abs=5e-4)
    assert model.joint.newton_changes["absoluteTolerance"] == (1e-10, 1e-8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        notes = model.joint.notes
    assert len(notes) == 1
    assert "step reduction reached the minimum step" in notes[0] and "in metal contact (|e|/c = 1.00" in notes[0]
    assert "singular position of the mechanism" in notes[0]
