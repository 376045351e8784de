"""Issue 15, section 1: robust implicit runs (Newton tolerances, numerical chatter, failure causes,
steps chosen from the model).

The model of the issue: a steel bar (0.3 m, 0.6 kg) hanging on a clearance pin from the
ground, c = 10 um, gravity, released at 0.5 rad with the journal resting on the wall.
"""
import math
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    SensorNode,
)

import exuclear
from exuclear.engine.solver import AccuracyWarning, automatic_step
from exuclear.timescales import MIN_STEPS_PER_RUN, STEPS_PER_CONTACT_PERIOD, contact_period, penetration_at

LENGTH, MASS, CLEARANCE = 0.3, 0.6, 10e-6


def pendulum(theta0=0.5, mass=MASS, y_offset=0.0, velocity=0.0, backend=None):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    x, y = LENGTH / 2 * math.sin(theta0), -CLEARANCE - LENGTH / 2 * math.cos(theta0) + y_offset
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, y, theta0], initialVelocities=[velocity, 0, 0]))
    bar = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=mass * LENGTH**2 / 12))
    mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=bar)),
                                     loadVector=[0, -9.81, 0]))
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0])),
               mbs.AddMarker(MarkerBodyRigid(bodyNumber=bar, localPosition=[0, LENGTH / 2, 0]))]
    handle = exuclear.AddClearanceJoint(mbs, markers, journal_radius=10e-3 - CLEARANCE, bearing_radius=10e-3,
                                        length=15e-3, cr=0.9, name="pin", backend=backend)
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


def test_tighter_newton_tolerances_still_fail_and_the_message_names_them():
    # an absolute tolerance below the contact's round-off floor, set by the user, is kept
    # (Exudyn's default 1e-10 would be raised by the joint: exuclear.engine.steering); at fixed
    # steps (joint_steps=False) nothing shortens the step whose Newton stalls
    mbs, handle = pendulum()
    settings = exuclear.SolverSettings(end_time=0.5, method="generalized-alpha", step=1e-4, newton_rtol=1e-8,
                                       newton_atol=1e-11, joint_steps=False)
    result = exuclear.simulate(mbs, settings)
    assert not result.success
    assert "newton_rtol" in result.message
    assert "absoluteTolerance" not in handle.newton_changes


def test_newton_tolerances_are_mapped_and_refused_for_explicit_methods():
    ss = exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1, method="trapezoidal", newton_rtol=1e-5,
                                                              newton_atol=1e-4))
    assert (ss.timeIntegration.newton.relativeTolerance, ss.timeIntegration.newton.absoluteTolerance) == (1e-5, 1e-4)
    with pytest.raises(ValueError, match="newton_rtol"):
        exuclear.SolverSettings(end_time=1, method="dopri5", newton_rtol=1e-5)
    with pytest.raises(ValueError, match="newton_atol` must be positive"):
        exuclear.SolverSettings(end_time=1, method="generalized-alpha", newton_atol=0.0)


def test_newton_contractivity_is_mapped_checked_and_only_lowered_by_the_joint():
    ss = exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1, method="generalized-alpha",
                                                                     newton_contractivity=0.01))
    assert ss.timeIntegration.newton.modifiedNewtonContractivity == 0.01
    default = exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1, method="generalized-alpha"))
    assert default.timeIntegration.newton.modifiedNewtonContractivity == exu.SimulationSettings(
    ).timeIntegration.newton.modifiedNewtonContractivity  # None: Exudyn's value, which the joint lowers to 0.2
    for bad in (0.0, 1.5, float("nan")):
        with pytest.raises(ValueError, match="newton_contractivity"):
            exuclear.SolverSettings(end_time=1, method="generalized-alpha", newton_contractivity=bad)
    with pytest.raises(ValueError, match="applies to the implicit methods"):
        exuclear.SolverSettings(end_time=1, method="dopri5", newton_contractivity=0.1)
    # the user's own smaller value survives the joint's Newton steering (engine/steering.py)
    mbs, handle = pendulum()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 0.01, 10
    ss.timeIntegration.newton.modifiedNewtonContractivity = 0.05
    mbs.SolveDynamic(ss)
    assert "modifiedNewtonContractivity" not in handle.newton_changes
    assert mbs.sys["dynamicSolver"].newton.modifiedNewtonContractivity == 0.05


def test_linear_solver_is_mapped_and_checked():
    sparse = exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1, method="generalized-alpha",
                                                                        linear_solver="sparse"))
    assert sparse.linearSolver.solverType == exu.LinearSolverType.EigenSparse
    dense = exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1, method="trapezoidal"))
    assert dense.linearSolver.solverType == exu.LinearSolverType.EXUdense  # Exudyn's default
    with pytest.raises(ValueError, match="unknown `linear_solver` 'lu'"):
        exuclear.SolverSettings(end_time=1, method="generalized-alpha", linear_solver="lu")
    with pytest.raises(ValueError, match="applies to the implicit methods"):
        exuclear.SolverSettings(end_time=1, method="rk44", linear_solver="sparse")


def test_the_sparse_solver_gives_the_dense_solvers_motion():
    # the same Newton iterations solved by another linear solver: the same resting pendulum to
    # round-off (its contact force balances the weight, 1e-6 relative is far above round-off)
    runs = []
    for linear_solver in ("dense", "sparse"):
        mbs, handle = pendulum()
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.1, method="generalized-alpha", step=1e-4,
                                                                linear_solver=linear_solver))
        assert result.success, result.message
        runs.append(handle.state())
    assert runs[1].delta == pytest.approx(runs[0].delta, rel=1e-6)
    assert runs[1].normal_force == pytest.approx(runs[0].normal_force, rel=1e-6)


def test_numerical_chatter_is_reported():
    # steps of 1e-3 s are 2.9 contact periods: the journal leaves the wall again and again
    mbs, handle = pendulum()
    settings = exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step=1e-3, impact_step=1e-6)
    with pytest.warns(AccuracyWarning, match="numerical chatter"):
        result = exuclear.simulate(mbs, settings)
    assert result.success and handle.history.onsets > 10
    assert len(result.notes) == 1 and "'pin'" in result.notes[0]


def _plain_run(step, backend=None):
    """The resting pendulum through a plain mbs.SolveDynamic (Exudyn's generalized-alpha,
    adaptive steps of at most ``step``) with impact-aware steps of 1e-6 s from each onset,
    as exuclear.simulate sets them; its joint's notes and kernel counters."""
    mbs, handle = pendulum(backend=backend)
    handle.set_impact_step(1e-6)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 1.0, round(1.0 / step)
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AccuracyWarning)
        mbs.SolveDynamic(ss)
        notes = handle.notes
    return handle, notes, [str(w.message) for w in caught], handle._backend.step_control()


def test_numerical_chatter_of_a_plain_run_is_told():
    # the same chatter on the main path: the joint counts the contacts that end in a step
    # longer than a tenth of its contact period and says so after the run, naming itself
    handle, notes, warned, control = _plain_run(1e-3)
    assert handle.history.onsets > 10 and control["long_separations"] > 0
    assert len(notes) == 1 and "'pin'" in notes[0] and "numerical chatter" in notes[0]
    assert warned == notes
    period = contact_period(handle.joint.law, MASS, MASS * 9.81)
    assert control["separation_step"] == pytest.approx(period / STEPS_PER_CONTACT_PERIOD)
    # a quarter of the contact period resolves the contact: one onset, nothing to say
    handle, notes, warned, control = _plain_run(1e-4)
    assert handle.history.onsets == 1 and notes == [] and warned == [] and control["separations"] == 0


@pytest.mark.skipif(exuclear.engine.kernel.COMPILED is None, reason="no compiled kernel")
def test_both_kernels_count_the_same_separations():
    counts = [tuple(_plain_run(1e-3, backend)[3][k] for k in ("separations", "long_separations"))
              for backend in ("compiled", "python")]
    assert counts[0] == counts[1] and counts[0][1] > 0


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


# -- issue 15: steps chosen from the model (SolverSettings(step="auto"))

def swing_period(end_time, **settings):
    """Run the pendulum (released at 0.5 rad) for ``end_time`` [s]; return the result, the
    joint's contact onsets and the mean period [s] between downward zero crossings of the
    angle, each interpolated linearly between outputs 1 ms apart."""
    theta0 = 0.5
    mbs, handle = pendulum(theta0)
    sensor = mbs.AddSensor(SensorNode(nodeNumber=0, storeInternal=True, writeToFile=False,
                                      outputVariableType=exu.OutputVariableType.Coordinates))
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=end_time, output_step=1e-3, **settings))
    data = mbs.GetSensorStoredData(sensor)
    t, theta = data[:, 0], theta0 + data[:, 3]  # the sensor gives displacements from the reference angle
    k = np.nonzero((theta[:-1] > 0.0) & (theta[1:] <= 0.0))[0]
    crossings = t[k] + (t[k + 1] - t[k]) * theta[k] / (theta[k] - theta[k + 1])
    return result, handle.history.onsets, (crossings[-1] - crossings[0]) / (len(crossings) - 1)


def test_automatic_fixed_step_of_the_pendulum_holds_contact_and_period():
    # The 10 s run: at the default 1e-5 s it took 43.9 s.  The automatic fixed step
    # is a tenth of the contact period (3.5e-5 s), where the journal stays on the wall (one
    # onset, the initial contact) and the swing period is DOPRI5's.  Measured: 0.9113776 s
    # against DOPRI5's 0.9113779 s (3e-7 relative); single periods scatter by 3e-6 relative
    # through the interpolated crossings, so 1e-5 bounds the difference of the means with a
    # margin (generalized-alpha's own period error, ~(omega h)^2, is 6e-8 here).
    result, onsets, period = swing_period(10.0, method="generalized-alpha", step="auto", joint_steps=False)
    assert result.success, result.message
    law = exuclear.make_joint(journal_radius=10e-3 - CLEARANCE, bearing_radius=10e-3, length=15e-3, cr=0.9).law
    assert result.step == pytest.approx(contact_period(law, MASS, MASS * 9.81) / STEPS_PER_CONTACT_PERIOD, rel=1e-12)
    assert onsets == 1 and result.notes == ()
    reference, ref_onsets, ref_period = swing_period(3.0, method="dopri5")  # three swings, rtol 1e-6
    assert reference.success and ref_onsets == 1
    assert period == pytest.approx(ref_period, rel=1e-5)


def test_automatic_joint_steps_of_the_pendulum_hold_contact_and_the_integrators_period():
    # step="auto" with an implicit method: the joint controls the steps, the largest
    # end_time / 1000 = 1e-2 s (issue 20).  The journal stays on the wall (one onset), in
    # 5991 steps against the fixed rule's 284640 (measured), and the period is DOPRI5's up
    # to the integrator's own period elongation at that step, (omega h)^2 / 12 for the
    # average-acceleration Newmark rule that generalized-alpha approaches (4.0e-4 here;
    # measured 3.3e-4)
    result, onsets, period = swing_period(10.0, method="generalized-alpha", step="auto")
    assert result.success, result.message
    assert result.step == pytest.approx(10.0 / MIN_STEPS_PER_RUN)
    assert onsets == 1 and result.notes == ()
    _reference, _onsets, ref_period = swing_period(3.0, method="dopri5")
    elongation = (2.0 * math.pi / ref_period * result.step) ** 2 / 12.0
    assert 0.0 <= period / ref_period - 1.0 <= 1.5 * elongation


def test_automatic_step_rules():
    mbs, _ = pendulum()
    # explicit adaptive methods control their step by error: the largest step stays the default
    assert automatic_step(mbs, exuclear.SolverSettings(end_time=1.0, step="auto")) == exuclear.SolverSettings(
        end_time=1.0).step
    # rk44 is fixed-step: the contact period rules it as it does fixed implicit steps
    alpha = automatic_step(mbs, exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step="auto",
                                                        joint_steps=False))
    assert alpha < 1.0 / MIN_STEPS_PER_RUN
    assert automatic_step(mbs, exuclear.SolverSettings(end_time=1.0, method="rk44", step="auto")) == alpha
    # implicit steps the joints control: the largest step is end_time / MIN_STEPS_PER_RUN
    steered = exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step="auto")
    assert steered.steered and automatic_step(mbs, steered) == pytest.approx(1.0 / MIN_STEPS_PER_RUN)
    # a run shorter than MIN_STEPS_PER_RUN steps of the contact rule is bounded by its duration
    short = exuclear.SolverSettings(end_time=1e-3, method="generalized-alpha", step="auto", joint_steps=False)
    assert automatic_step(mbs, short) == pytest.approx(1e-3 / MIN_STEPS_PER_RUN)
    # without a clearance joint: end_time / MIN_STEPS_PER_RUN
    free = exu.SystemContainer().AddSystem()
    node = free.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
    free.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1.0))
    free.Assemble()
    settings = exuclear.SolverSettings(end_time=2.0, method="generalized-alpha", step="auto")
    assert automatic_step(free, settings) == pytest.approx(2.0 / MIN_STEPS_PER_RUN)
    result = exuclear.simulate(free, settings)
    assert result.success and result.step == pytest.approx(2.0 / MIN_STEPS_PER_RUN) and result.steps == MIN_STEPS_PER_RUN


def test_automatic_step_bad_values():
    with pytest.raises(ValueError, match="`step` must be a positive number .* or 'auto'"):
        exuclear.SolverSettings(end_time=1.0, step="fast")
    with pytest.raises(ValueError, match="`step` must be a positive number .* or 'auto'"):
        exuclear.SolverSettings(end_time=1.0, step=None)
    with pytest.raises(ValueError, match="chosen from the model"):  # the mapping alone does not know the model
        exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step="auto"))
    mbs, _ = pendulum()
    settings = exuclear.SolverSettings(end_time=1.0, method="generalized-alpha", step="auto", impact_step=1e-3)
    with pytest.raises(ValueError, match="`impact_step` must not exceed the step, but `step` 'auto' chose 3.51e-05 s"):
        exuclear.simulate(mbs, settings)
