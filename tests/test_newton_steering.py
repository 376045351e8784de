"""The joint's Newton settings for the implicit runs it starts (exuclear.engine.steering, issue 20).

Exudyn differentiates the joint's connector numerically with an increment of 1e-7 per unit
of coordinate, the size of a resting journal's penetration; its modified Newton then
converges linearly and takes more iterations per step than Exudyn's step recovery allows
(``adaptiveStepRecoveryIterations``, 7), so a step cut at an impact never grows back.  The
joint sets the solver's copy of the increment, and a Jacobian per step where the step is
longer than half its contact period.  Checked on the zoo's planar double pendulum
(doublePendulum2D.py, own settings: generalized-alpha at 1e-3 s, twice the elbow's contact
period).
"""
from __future__ import annotations

import warnings
import weakref

import exudyn as exu
import numpy as np
import pytest

from exuclear.engine.bodies import joint_contact_period
from exuclear.engine.steering import (
    ABSOLUTE_TOLERANCE,
    CONTRACTIVITY,
    JACOBIAN_PER_STEP_ABOVE,
    JACOBIAN_VOTES_KEY,
    RELATIVE_EPSILON,
    vote_jacobian,
)
from validation.exudyn_examples import (
    REGISTRY,
    double_pendulum_2d,
    double_pendulum_3d,
    kinematic_tree_chain,
    slider_crank_2d,
)

EXUDYN_EPSILON = exu.SimulationSettings().timeIntegration.newton.numericalDifferentiation.relativeEpsilon
EXUDYN_CONTRACTIVITY = exu.SimulationSettings().timeIntegration.newton.modifiedNewtonContractivity  # 0.5
EXUDYN_ABSOLUTE_TOLERANCE = exu.SimulationSettings().timeIntegration.newton.absoluteTolerance  # 1e-10
RECOVERY_ITERATIONS = exu.SimulationSettings().timeIntegration.adaptiveStepRecoveryIterations  # 7


def _run(build, end_time, steer=True):
    model = build(True, end_time)
    model.joint.steer_newton = steer
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    return model


def test_the_solver_copy_is_set_and_the_users_settings_are_not():
    # 3 ms of free flight at the example's 1e-3 s steps (its first impact comes at 4.1 ms): the
    # Jacobian per step is on at the run's end, where an impact's short steps would switch it off
    model = _run(double_pendulum_2d.build, 0.003)
    solver = model.mbs.sys["dynamicSolver"]
    assert solver.newton.numericalDifferentiation.relativeEpsilon == RELATIVE_EPSILON
    assert solver.newton.modifiedNewtonJacUpdatePerStep
    assert solver.newton.modifiedNewtonContractivity == CONTRACTIVITY
    assert solver.newton.absoluteTolerance == ABSOLUTE_TOLERANCE
    user = model.simulation_settings.timeIntegration.newton
    assert user.numericalDifferentiation.relativeEpsilon == EXUDYN_EPSILON
    assert user.absoluteTolerance == EXUDYN_ABSOLUTE_TOLERANCE
    assert not user.modifiedNewtonJacUpdatePerStep
    assert user.modifiedNewtonContractivity == EXUDYN_CONTRACTIVITY
    assert model.joint.newton_changes == {
        "numericalDifferentiation.relativeEpsilon": (EXUDYN_EPSILON, RELATIVE_EPSILON),
        "absoluteTolerance": (EXUDYN_ABSOLUTE_TOLERANCE, ABSOLUTE_TOLERANCE),
        "modifiedNewtonContractivity": (EXUDYN_CONTRACTIVITY, CONTRACTIVITY),
        "modifiedNewtonJacUpdatePerStep": (False, "while the step exceeds "
                                                  f"{JACOBIAN_PER_STEP_ABOVE * joint_contact_period(model.mbs, model.joint):.3g} s")}


def test_steer_newton_false_leaves_the_solver_as_the_user_set_it():
    model = _run(double_pendulum_2d.build, 0.05, steer=False)
    solver = model.mbs.sys["dynamicSolver"]
    assert solver.newton.numericalDifferentiation.relativeEpsilon == EXUDYN_EPSILON
    assert not solver.newton.modifiedNewtonJacUpdatePerStep
    assert model.joint.newton_changes == {}


def test_a_jacobian_per_step_only_where_the_step_exceeds_half_the_contact_period():
    # the 3D double pendulum runs at 1e-4 s, 0.23 of its elbow's contact period
    model = _run(double_pendulum_3d.build, 0.02)
    step = model.mbs.sys["dynamicSolver"].it.maxStepSize
    assert step < JACOBIAN_PER_STEP_ABOVE * joint_contact_period(model.mbs, model.joint)
    assert list(model.joint.newton_changes) == ["numericalDifferentiation.relativeEpsilon", "absoluteTolerance",
                                                "modifiedNewtonContractivity"]


def test_the_jacobian_per_step_follows_the_steps_the_joint_accepts():
    # the planar double pendulum with the paper's friction: its sliding contact keeps the
    # steps near a quarter of the elbow's contact period (the rate criterion), its impacts
    # and flights far shorter, between steps of the example's 1e-3 s
    model = REGISTRY["double_pendulum_2d_friction"](True, 0.5)
    threshold = JACOBIAN_PER_STEP_ABOVE * joint_contact_period(model.mbs, model.joint)
    rows = []

    def record(mbs, t):  # after the accepted step and its post-Newton call
        solver = mbs.sys["dynamicSolver"]
        touching = model.joint._backend.states()[0].in_contact
        rows.append((solver.it.lastStepSize, solver.newton.modifiedNewtonJacUpdatePerStep, touching))
        return True

    model.mbs.SetPostStepUserFunction(record)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    steps = np.array([h for h, _, _ in rows])
    on = np.array([flag for _, flag, _ in rows])
    touching = np.array([t for _, _, t in rows])
    assert on[steps > threshold * (1.0 + 1e-9)].all()  # a step longer than T_c / 2: a Jacobian for the next
    switched = np.flatnonzero(touching[1:] != touching[:-1]) + 1
    assert len(switched) > 0 and on[switched].all()  # a contact opened or closed: a Jacobian for the next
    assert (~on).sum() > 0.5 * len(rows)  # most steps here are short and run on the Jacobian they have
    assert model.joint._backend.step_control()["jacobian_step"] == pytest.approx(threshold)


def test_an_absolute_tolerance_the_user_set_is_kept():
    # any value other than Exudyn's default counts as set: looser stays looser, tighter stays
    # tighter (and the joint's note on a stopped run names it, tests/test_stop_notes.py)
    for atol in (1e-6, 1e-11):
        model = double_pendulum_2d.build(True, 0.02)
        model.simulation_settings.timeIntegration.newton.absoluteTolerance = atol
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        assert model.mbs.sys["dynamicSolver"].newton.absoluteTolerance == atol
        assert "absoluteTolerance" not in model.joint.newton_changes


def test_the_relative_tolerance_the_user_set_is_kept_and_the_absolute_one_ends_newton_at_the_floor():
    # the zoo's slider-crank keeps SliderCrank.py's relativeTolerance 1e-10, below the crank
    # pin's round-off floor: Exudyn stops when either tolerance is met, so with the joint's
    # absolute 1e-8 in place of Exudyn's 1e-10 the example's own run gets past t = 0.027 s,
    # where it stopped before (to 0.061 s, where the loaded pin's floor exceeds 1e-8:
    # OWN_SETTINGS_FAIL in tests/test_exudyn_examples.py)
    model = slider_crank_2d.build(True, 0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.sys["dynamicSolver"].newton.relativeTolerance == slider_crank_2d.NEWTON_RTOL
    assert model.joint.newton_changes["absoluteTolerance"] == (EXUDYN_ABSOLUTE_TOLERANCE, ABSOLUTE_TOLERANCE)
    assert model.joint.notes == []


def test_a_jacobian_per_step_while_any_joint_asks_for_it():
    class Solver:
        class newton:  # noqa: N801 - Exudyn's attribute name
            modifiedNewtonJacUpdatePerStep = False

    class System:
        variables = {JACOBIAN_VOTES_KEY: [weakref.ref(Solver), False, {}]}

    vote_jacobian(System, 1, True)
    vote_jacobian(System, 2, False)
    assert Solver.newton.modifiedNewtonJacUpdatePerStep
    vote_jacobian(System, 1, False)
    assert not Solver.newton.modifiedNewtonJacUpdatePerStep
    vote_jacobian(System, 2, True)
    assert Solver.newton.modifiedNewtonJacUpdatePerStep


def test_a_users_own_jacobian_per_step_is_kept():
    model = double_pendulum_2d.build(True, 0.2)
    model.simulation_settings.timeIntegration.newton.modifiedNewtonJacUpdatePerStep = True
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.sys["dynamicSolver"].newton.modifiedNewtonJacUpdatePerStep
    assert "modifiedNewtonJacUpdatePerStep" not in model.joint.newton_changes


def test_an_explicit_solver_is_left_alone():
    model = _run(kinematic_tree_chain.build, 0.05)  # explicit Euler: no Newton
    assert model.joint.newton_changes == {}


def test_newton_converges_within_exudyns_step_recovery_and_the_steps_grow_back():
    # 1 s: some 20 impacts settling into permanent contact.  Exudyn's own settings: 8 to 8.5
    # Newton iterations per step (more than the 7 that let a step grow) and 20085 to 26810
    # iterations; steered: 5.3 to 6.2 per step and 11128 to 12431 in all, 0.46 to 0.55 of
    # them (measured as the step control changed, which moves the bounce sequence; before the
    # joint let free flight grow the step, 7002 steps against 2330)
    steered, own = _run(double_pendulum_2d.build, 1.0), _run(double_pendulum_2d.build, 1.0, steer=False)
    counts = {}
    for name, model in (("steered", steered), ("own", own)):
        it = model.mbs.sys["dynamicSolver"].it
        counts[name] = (it.newtonStepsCount / it.currentStepIndex, it.currentStepIndex, it.newtonStepsCount)
    assert counts["own"][0] > RECOVERY_ITERATIONS
    assert counts["steered"][0] < RECOVERY_ITERATIONS
    assert counts["steered"][1] < counts["own"][1]
    assert counts["steered"][2] < 0.7 * counts["own"][2]
    # both runs resolve the same contacts: the largest penetration of their impact records
    # (every accepted step, whatever the output interval) agrees to 1 %
    pen = [max(r.max_penetration for r in m.joint.impacts()) for m in (steered, own)]
    assert pen[0] == pytest.approx(pen[1], rel=0.01)
