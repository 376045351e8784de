"""The joint's own step control (issue 20): a plain ``mbs.SolveDynamic`` with the user's
settings either resolves the contact (the joint rejects a step too long for its state and
Exudyn redoes it shorter) or says clearly what was not resolved, never through Exudyn's
"check your Python code!"."""
from __future__ import annotations

import warnings

import exudyn as exu
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine import kernel

#: The paper's departure velocity of the journal impact [m/s] (README, models/journal_bearing.py).
DEPARTURE = 0.269
#: 1 %: the issue's accuracy target for a plain run at a long step.
RTOL = 1e-2

BACKENDS = (["compiled"] if kernel.COMPILED is not None else []) + ["python"]


def impact(backend: str = exuclear.DEFAULT_BACKEND, **options):
    """The README's journal impact: a 0.04 kg journal touching the bearing wall at 0.3 m/s."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[1e-4, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    joint = exuclear.CreateClearanceJoint(
        mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1], journal_radius=9.9e-3,
        bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.9, journal_material="steel",
        bearing_material="steel", friction="none", name="pin", backend=backend,
        **options)
    mbs.Assemble()
    return mbs, node, joint


def solve(mbs, steps: int, solver=exu.DynamicSolverType.GeneralizedAlpha, adaptive: bool = True,
          end_time: float = 2e-4):
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime, ti.numberOfSteps, ti.adaptiveStep, ti.verboseMode = end_time, steps, adaptive, 0
    ss.solution.sensors.writePeriod = end_time / 100
    mbs.SolveDynamic(ss, solverType=solver)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("steps", [1, 2, 20], ids=["one step", "1e-4 s", "1e-5 s"])
def test_a_plain_run_at_a_long_step_gives_the_papers_departure_velocity(backend, steps):
    # the impact lasts about 40 us: one to 20 implicit steps over 0.2 ms cannot resolve it,
    # the joint's step control does (measured: 0.2669 to 0.2685 m/s)
    mbs, node, joint = impact(backend)
    with warnings.catch_warnings():
        warnings.simplefilter("error", exuclear.AccuracyWarning)  # resolved: nothing to say
        solve(mbs, steps)
        assert joint.notes == []
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]
    assert -v == pytest.approx(DEPARTURE, rel=RTOL)
    counts = joint.counts  # it was the joint that shortened the steps, and it says how often
    assert counts["rejected_steps"] > 0 and counts["unresolved_steps"] == 0 and counts["over_limit_steps"] == 0
    assert counts["impacts"] == 1  # one impact: the journal leaves the wall at 0.269 m/s
    assert mbs.systemData.GetTime() == pytest.approx(2e-4)


def test_a_fixed_step_too_long_finishes_and_warns_with_the_joint_and_a_step():
    mbs, _node, joint = impact()
    with pytest.warns(exuclear.AccuracyWarning) as caught:  # told at the first unresolved step
        solve(mbs, 20, adaptive=False)  # no "check your Python code!": the run reaches its end
    assert mbs.systemData.GetTime() == pytest.approx(2e-4)
    assert len(caught) == 1
    message = str(caught[0].message)
    assert "joint 'pin'" in message and "adaptiveStep is False" in message and "use a step of at most" in message
    advice = float(message.split("use a step of at most ")[1].split(" s")[0])
    assert 0.0 < advice < 1e-5  # shorter than the step given
    with warnings.catch_warnings():
        warnings.simplefilter("error", exuclear.AccuracyWarning)  # warned once per run and kind
        assert len(joint.impacts()) == 1
        notes = joint.notes
        joint.outputs()
    # kept, with the run's count of unresolved steps
    assert len(notes) == 1 and "joint 'pin'" in notes[0] and "so far" not in notes[0]


def test_a_penetration_beyond_the_limit_at_a_fixed_step_is_told_not_raised():
    mbs, _node, joint = impact(maxPenetration=1e-6)  # the impact reaches 3.4 um
    solve(mbs, 20, adaptive=False)
    assert mbs.systemData.GetTime() == pytest.approx(2e-4)
    reason, when = joint.failure()
    assert reason.startswith("penetration ") and "exceeds the limit 1e-06 m" in reason and 0.0 < when < 2e-4
    notes = joint.notes
    assert any("joint 'pin'" in n and "beyond the joint's limit" in n for n in notes)


def test_a_physical_penetration_beyond_the_limit_is_accepted_after_shorter_steps_and_told():
    # adaptive steps: the joint shortens the step 4 times, then the penetration is the contact's
    mbs, _node, joint = impact(maxPenetration=1e-6)
    solve(mbs, 20)
    assert mbs.systemData.GetTime() == pytest.approx(2e-4)
    assert joint.failure()[0].startswith("penetration ")


def test_the_explicit_impact_step_still_overrides():
    # set_impact_step (exuclear.simulate's impact-aware steps) takes over from the joint's
    # rate criterion: the joint rejects no step of its own
    mbs, _node, joint = impact()
    joint.set_impact_step(1e-6)
    solve(mbs, 2)
    assert mbs.systemData.GetTime() == pytest.approx(2e-4)
    assert joint._backend.step_control()["rejected"] == 0


@pytest.mark.skipif(kernel.COMPILED is None, reason="no compiled kernel")
@pytest.mark.parametrize("adaptive", [True, False])
def test_compiled_and_python_step_control_agree(adaptive):
    runs = []
    for backend in ("compiled", "python"):
        mbs, node, joint = impact(backend)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", exuclear.AccuracyWarning)
            solve(mbs, 20, adaptive=adaptive)
            control = joint._backend.step_control()
        runs.append((mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0],
                     int(mbs.sys["dynamicSolver"].it.currentStepIndex), control["rejected"],
                     control["unresolved"], control["unresolved_advice"]))
    (v_c, *rest_c), (v_p, *rest_p) = runs
    assert v_c == pytest.approx(v_p, rel=1e-12, abs=1e-15)  # round-off (no fused multiply-add)
    assert rest_c == rest_p


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_non_finite_state_stops_the_run_naming_the_joint(backend):
    # the one condition that still ends a run from the user function: Exudyn appends its
    # own words, but the message and joint.failure() name the joint and the cause
    mbs, _node, joint = impact(backend)
    functions = joint.user_functions()
    stiffness = joint.parameters()
    nan = float("nan")
    args = (mbs, 0.0, 0, [1e-4, 0.0, 0.0], [0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [0.0, 0.0, 0.0], stiffness,
            [[0.0] * 6] * 6, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.0] * 6)
    functions["force_torque"](*args)  # the run's initial state: the run-start callback names the joint
    data = [0.0] * 14
    bad = (mbs, 1e-6, 0, data, [nan, 0.0, 0.0], *args[4:])
    with pytest.raises(Exception, match=r"joint 'pin': the state became non-finite"):
        functions["post_newton"](*bad)
    reason, when = joint.failure()
    assert "non-finite" in reason and when == pytest.approx(1e-6)
