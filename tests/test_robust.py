"""Issue 15, section 1: robust implicit runs (Newton tolerances, numerical chatter, failure causes).

The model of the issue: a steel bar (0.3 m, 0.6 kg) hanging on a clearance pin from the
ground, c = 10 um, gravity, released at 0.5 rad with the journal resting on the wall.
"""
import math
import warnings

import exudyn as exu
import pytest
from exudyn.itemInterface import LoadMassProportional, MarkerBodyMass, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine.solver import AccuracyWarning
from exuclear.timescales import contact_period, penetration_at

LENGTH, MASS, CLEARANCE = 0.3, 0.6, 10e-6


def pendulum(theta0=0.5, mass=MASS, y_offset=0.0, velocity=0.0):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    x, y = LENGTH / 2 * math.sin(theta0), -CLEARANCE - LENGTH / 2 * math.cos(theta0) + y_offset
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, y, theta0], initialVelocities=[velocity, 0, 0]))
    bar = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=mass * LENGTH**2 / 12))
    mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=bar)),
                                     loadVector=[0, -9.81, 0]))
    handle = exuclear.add_clearance_joint(mbs, bar, ground, journal_point=(0, LENGTH / 2), journal_radius=10e-3 - CLEARANCE,
                                          bearing_radius=10e-3, length=15e-3, cr=0.9, name="pin")
    mbs.Assemble()
    return mbs, handle


@pytest.mark.parametrize("step", [1e-4, 1e-5])
def test_resting_pendulum_runs_with_the_default_newton_tolerances(step):
    # before: Newton failed at 0.13 s (1e-4 s) with "relative error 1.74e-08" against 1e-8
    mbs, handle = pendulum()
    end = 0.5 if step == 1e-4 else 0.1
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=end, method="generalized-alpha", step=step))
    assert result.success, result.message
    assert handle.history.onsets == 1 and handle.history.in_contact  # stays on the wall, as DOPRI5 says


def test_exudyn_newton_tolerances_still_fail_and_the_message_names_them():
    mbs, _ = pendulum()
    settings = exuclear.SolverSettings(end_time=0.5, method="generalized-alpha", step=1e-4, newton_rtol=1e-8,
                                       newton_atol=1e-10)
    result = exuclear.simulate(mbs, settings)
    assert not result.success
    assert "newton_rtol" in result.message


def test_newton_tolerances_are_mapped_and_refused_for_explicit_methods():
    ss = exuclear.simulation_settings(exuclear.SolverSettings(end_time=1, method="trapezoidal", newton_rtol=1e-5,
                                                              newton_atol=1e-4))
    assert (ss.timeIntegration.newton.relativeTolerance, ss.timeIntegration.newton.absoluteTolerance) == (1e-5, 1e-4)
    with pytest.raises(ValueError, match="newton_rtol"):
        exuclear.SolverSettings(end_time=1, method="dopri5", newton_rtol=1e-5)
    with pytest.raises(ValueError, match="newton_atol` must be positive"):
        exuclear.SolverSettings(end_time=1, method="generalized-alpha", newton_atol=0.0)


def test_numerical_chatter_is_reported():
    # steps of 1e-3 s are 2.9 contact periods: the journal leaves the wall again and again
    mbs, handle = pendulum()
    settings = exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step=1e-3, impact_step=1e-6)
    with pytest.warns(AccuracyWarning, match="numerical chatter"):
        result = exuclear.simulate(mbs, settings)
    assert result.success and handle.history.onsets > 10
    assert len(result.notes) == 1 and "'pin'" in result.notes[0]


def test_resolved_contact_gives_no_chatter_note():
    mbs, handle = pendulum()
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step=1e-4,
                                                                impact_step=1e-6))
    assert result.success and result.notes == () and handle.history.onsets == 1


def test_contact_period_of_the_pendulum():
    # the linearised contact mode: k = dF/d(delta) at the static penetration under m g
    law = exuclear.make_joint(journal_radius=10e-3 - CLEARANCE, bearing_radius=10e-3, length=15e-3, cr=0.9).law
    delta = penetration_at(law, MASS * 9.81)
    assert law.elastic_force(delta) == pytest.approx(MASS * 9.81, rel=1e-9)
    k = 1.5 * MASS * 9.81 / delta  # F ~ delta^1.5 (Wang-Liu softens slightly: K falls with delta)
    assert contact_period(law, MASS, MASS * 9.81) == pytest.approx(2 * math.pi * math.sqrt(MASS / k), rel=0.01)


@pytest.mark.parametrize("kwargs, cause", [
    (dict(mass=0.0), "journal body .* has mass 0.0"),
    (dict(y_offset=-1e-3), "journal starts outside its bearing"),
    (dict(velocity=math.nan), "initial velocity 0 .* is nan"),
])
@pytest.mark.parametrize("method", ["generalized-alpha", "dopri5"])
def test_failure_names_the_likely_cause(kwargs, cause, method):
    # before: zero mass "succeeded" (generalized-alpha) or got step advice; the others got step advice
    mbs, _ = pendulum(**kwargs)
    with pytest.raises(ValueError, match=cause):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.01, method=method, step=1e-4))
