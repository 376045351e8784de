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
from exuclear.engine import DEFAULT_BACKEND, kernel
from exuclear.engine.steering import RefinedSimulationSettings

#: The paper's departure velocity of the journal impact [m/s] (README, models/journal_bearing.py).
DEPARTURE = 0.269
#: 1 %: the issue's accuracy target for a plain run at a long step.
RTOL = 1e-2

BACKENDS = (["compiled"] if kernel.COMPILED is not None else []) + ["python"]


def impact(backend: str = DEFAULT_BACKEND, **options):
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
          end_time: float = 2e-4, recovery_steps: int | None = None, joint_refinement: float | None = None):
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime, ti.numberOfSteps, ti.adaptiveStep, ti.verboseMode = end_time, steps, adaptive, 0
    if recovery_steps is not None:
        ti.adaptiveStepRecoverySteps = recovery_steps
    ss.solution.sensors.writePeriod = end_time / 100
    if joint_refinement is not None:  # a convergence check's tighter run (exuclear.convergence.refined_settings)
        ss = RefinedSimulationSettings(ss, joint_refinement)
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


# -- free flight lets the step grow (JointKernel.step_growth) ---------------------------------

def test_time_to_wall_is_the_first_root_of_the_gap():
    from exuclear.engine._python_kernel import time_to_wall
    # delta + delta_dot tau + delta_ddot tau^2 / 2 = 0 with a gap of 1 (delta = -1)
    assert time_to_wall(-1.0, 2.0, 0.0) == pytest.approx(0.5)          # straight at the wall
    assert time_to_wall(-1.0, 0.0, 2.0) == pytest.approx(1.0)          # from rest, pulled at it
    assert time_to_wall(-1.0, -1.0, 4.0) == pytest.approx(1.0)         # moving away, turned back
    assert time_to_wall(-1.0, 1.0, -0.4) == pytest.approx((1.0 - 0.2 ** 0.5) / 0.4)  # slowed, reaches it
    assert time_to_wall(-1.0, 1.0, -0.6) == float("inf")               # slowed, turns before it
    assert time_to_wall(-1.0, -1.0, -1.0) == float("inf")              # moving away, pushed away


def _steps_and_contacts(backend, joints=1, impact_step=None):
    """The journal impact followed by its free flight across the bearing (2 ms in steps of at
    most 1 ms); with ``joints=2`` a second journal rests pressed on its own bearing's wall all
    along; with ``impact_step`` the impact-aware steps of ``joint.set_impact_step``.  Returns
    the accepted steps [(t, h)] and the first journal's impacts."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[1e-4, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    law = dict(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.9, backend=backend)
    joint = exuclear.CreateClearanceJoint(mbs, name="pin", itemNumbers=[ground, pin], position=[0, 0, 0],
                                          axis=[0, 0, 1], **law)
    if joints == 2:
        from exudyn.itemInterface import Force, MarkerNodePosition
        rest = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[1, 0, 0], initialCoordinates=[0, -1e-4, 0]))
        body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=rest, mass=0.04, inertia=2e-6))
        mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=rest)), loadVector=[0, -10.0, 0]))
        exuclear.CreateClearanceJoint(mbs, name="rest", itemNumbers=[ground, body], position=[1, 0, 0],
                                      axis=[0, 0, 1], **law)
    if impact_step is not None:
        joint.set_impact_step(impact_step)
    steps = []
    mbs.SetPostStepUserFunction(lambda m, t: steps.append((t, m.sys["dynamicSolver"].it.currentStepSize)) or True)
    mbs.Assemble()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # impact-aware steps double every 100 steps, as exuclear.simulate's (recovery_steps):
        # Exudyn's 10 would double them within the 40 us of an impact
        solve(mbs, 2, end_time=2e-3, recovery_steps=None if impact_step is None else 100)
    return steps, joint.impacts()


@pytest.mark.parametrize("impact_step", [None, 1e-6], ids=["joint-steered", "impact-aware"])
@pytest.mark.parametrize("backend", BACKENDS)
def test_free_flight_grows_the_step_back_and_the_next_impact_keeps_its_speed(backend, impact_step):
    # after the impact the journal crosses the 0.2 mm of its bearing at 0.269 m/s in 0.74 ms;
    # from the impact's microsecond steps Exudyn's own rule (double after 10 steps) needs some
    # 70 steps to reach 0.1 ms, the joint's free flight tenfold per step (GROWTH_LIMIT) a few.
    # With an impact_step as well: Exudyn's rule (double every 100 steps) would need some 500
    # steps from the impact's 1e-6 s to 0.1 ms; a grown step that passes the bearing's centre
    # (where the gap's rate turns: time_to_wall sees the journal moving away) and reaches the
    # far wall is redone at impact_step and grows again (36 steps, measured)
    steps, impacts = _steps_and_contacts(backend, impact_step=impact_step)
    assert len(impacts) >= 2
    first_end = impacts[0].onset_time + impacts[0].duration
    flight = [t for t, _h in steps if first_end < t < impacts[1].onset_time]
    assert len(flight) <= (20 if impact_step is None else 40)
    # the free flight holds its speed (no gravity): the second impact comes at the departure speed
    assert impacts[1].onset_velocity == pytest.approx(DEPARTURE, rel=RTOL)


@pytest.mark.parametrize("impact_step", [None, 1e-6], ids=["joint-steered", "impact-aware"])
def test_both_kernels_grow_the_same_steps(impact_step):
    if kernel.COMPILED is None:
        pytest.skip("no compiled kernel")
    (s_c, _), (s_p, _) = (_steps_and_contacts(backend, impact_step=impact_step) for backend in ("compiled", "python"))
    assert len(s_c) == len(s_p)
    assert max(abs(a[0] - b[0]) for a, b in zip(s_c, s_p)) <= 1e-12


def test_one_joint_in_contact_keeps_the_others_free_flight_from_growing_the_step():
    # the second journal rests on its wall all along: the step grows by Exudyn's own rule
    # only (at most twice the step before), never by the first joint's free flight
    steps, impacts = _steps_and_contacts(DEFAULT_BACKEND, joints=2)
    first_end = impacts[0].onset_time + impacts[0].duration
    h = [h for t, h in steps if t > first_end]
    assert max(b / a for a, b in zip(h, h[1:])) <= 2.0 * (1 + 1e-9)
    single, _ = _steps_and_contacts(DEFAULT_BACKEND)
    h1 = [h for t, h in single if t > first_end]
    assert max(b / a for a, b in zip(h1, h1[1:])) > 2.0


# -- the rate criterion's KAPPA, per joint and per simulate run -------------------------------

def test_rate_limit_is_a_checked_joint_parameter():
    from exuclear.engine.layout import read
    mbs, _node, joint = impact()
    assert joint.rate_limit == exuclear.settings.RATE_LIMIT_DEFAULT == 0.1
    joint.rate_limit = 0.02
    assert read(mbs.GetObjectParameter(joint.objectNumber, "stiffness"), "rate_limit") == 0.02
    with pytest.raises(ValueError, match="`rate_limit` must be non-negative"):
        joint.rate_limit = -0.1


def test_a_smaller_rate_limit_takes_more_steps_in_the_impact():
    # the criterion's cost: KAPPA 0.01 asks for ten times the steps per reversal of 0.1
    rejected = {}
    for kappa in (0.1, 0.01):
        mbs, _node, joint = impact()
        joint.rate_limit = kappa
        solve(mbs, 2)
        rejected[kappa] = joint.counts["rejected_steps"]
    assert rejected[0.01] > 2 * rejected[0.1]


def test_simulate_sets_the_runs_rate_limit_and_restores_the_joints_own():
    mbs, node, joint = impact()
    joint.rate_limit = 0.05
    settings = exuclear.SolverSettings(end_time=2e-4, method="generalized-alpha", step=1e-4, joint_steps=True,
                                       rate_limit=0.01)
    result = exuclear.simulate(mbs, settings)
    assert result.success, result.message
    assert joint.counts["rejected_steps"] > 20  # the run's 0.01 (0.05 takes some 8)
    assert joint.rate_limit == 0.05
    # and the convergence check tightens it with the steps
    assert exuclear.convergence.refined_settings(settings).rate_limit == pytest.approx(0.0025)


def test_a_convergence_checks_tighter_plain_run_refines_the_joints_steps():
    # check_convergence on a plain mbs.SolveDynamic gives its tighter run RefinedSimulationSettings
    # with joint_refinement = factor: the joints' rate_limit is divided for that run only, the
    # same steps as a joint given rate_limit / factor
    rejected = []
    for kappa, factor in ((0.1, 10.0), (0.01, None)):
        mbs, _node, joint = impact()
        joint.rate_limit = kappa
        if factor is None:
            solve(mbs, 2)
        else:
            solve(mbs, 2, joint_refinement=factor)
            assert joint.rate_limit == kappa  # the joint's own value is kept
        rejected.append(joint.counts["rejected_steps"])
    assert rejected[0] == rejected[1] > 20



def _orbiting(backend: str, step_periods: float, end_time: float = 0.5, joint_refinement: float | None = None,
              adaptive: bool = True):
    """A 0.5 kg journal orbiting inside a ground bearing (c = 0.1 mm) at 0.05 m/s, pressed on
    the wall by its centripetal load alone and started at the law's static penetration under
    it: a contact held throughout, whose load does not change, at user steps of
    ``step_periods`` contact periods (the period under the journal's weight at standard
    gravity, as the joint estimates it where the model has no gravity load,
    exuclear.engine.bodies; the formula of exuclear.timescales).  Returns
    the period and the accepted steps through which the contact was held."""
    from exuclear.engine.bodies import STANDARD_GRAVITY
    from exuclear.timescales import contact_period, penetration_at

    mass, speed = 0.5, 0.05
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    law = exuclear.make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, cr=1.0).law
    r = 1e-4
    for _ in range(3):  # |e| = c + delta(m v^2 / |e|)
        r = 1e-4 + penetration_at(law, mass * speed**2 / r)
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[r, 0, 0],
                                       initialVelocities=[0, speed, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=1e-5))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], journal_radius=9.9e-3,
                                          bearing_radius=10e-3, length=15e-3, cr=1.0, name="pin", backend=backend)
    mbs.Assemble()
    period = contact_period(law, mass, mass * STANDARD_GRAVITY)
    held, last = [], [0.0, False]

    def post_step(mbs, t):
        state = joint.state()
        if last[1] and state.in_contact:
            held.append(t - last[0])
        last[:] = [t, state.in_contact]
        return True

    mbs.SetPostStepUserFunction(post_step)
    solve(mbs, round(end_time / (step_periods * period)), end_time=end_time, joint_refinement=joint_refinement,
          adaptive=adaptive)
    return period, held, joint


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_held_contact_takes_steps_of_at_most_its_cap(backend):
    # the user's step is 20 contact periods; a step through which the contact is held lasts at
    # most HELD_CONTACT_PERIODS of them (steering.py has what longer ones cost the beam pendulum)
    from exuclear.engine.steering import HELD_CONTACT_PERIODS

    period, held, joint = _orbiting(backend, 20.0)
    cap = HELD_CONTACT_PERIODS * period
    assert len(held) > 50
    assert max(held) <= cap * (1.0 + 1e-9)
    assert max(held) > 0.9 * cap  # the cap sets the held steps: the steady load leaves the rate rule nothing
    # a convergence check's tighter run divides it with the joints' rate_limit
    period, held, joint = _orbiting(backend, 20.0, joint_refinement=2.0)
    assert max(held) <= 0.5 * cap * (1.0 + 1e-9)


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_held_contact_at_a_fixed_step_over_its_cap_is_told(backend):
    # adaptiveStep False: the cap cannot shorten the step; the joint accepts it and says so
    # once, naming itself, what it held and the step the cap asks for
    from exuclear.engine.steering import HELD_CONTACT_PERIODS

    with pytest.warns(exuclear.AccuracyWarning, match="'pin'.*held the contact through more than") as caught:
        period, held, joint = _orbiting(backend, 20.0, end_time=0.05, adaptive=False)
    assert min(held) > 5.0 * HELD_CONTACT_PERIODS * period  # the user's fixed steps, held through, over the cap
    assert joint.counts["held_long_steps"] == len(held)
    note = [str(w.message) for w in caught if "held the contact" in str(w.message)]
    advice = float(note[0].split("use a step of at most ")[1].split(" s")[0])
    assert advice == pytest.approx(HELD_CONTACT_PERIODS * period, rel=1e-2)  # 3 significant digits in the note


@pytest.mark.skipif(kernel.COMPILED is None, reason="no compiled kernel")
def test_both_kernels_hold_the_same_steps():
    runs = [_orbiting(backend, 20.0, end_time=0.1)[1] for backend in ("compiled", "python")]
    assert len(runs[0]) == len(runs[1]) and max(runs[0]) == pytest.approx(max(runs[1]), rel=1e-9)
