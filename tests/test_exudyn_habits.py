"""A clearance joint behaves as one of Exudyn's own items (issue 11's contract).

Each test does what an Exudyn user does with a model (a direct ``mbs.SolveDynamic``,
``mbs.Reset()`` and a rebuild, their own step functions, sensors, solution files,
drawing) and checks it against a reference run or a number with a known source.
"""
from __future__ import annotations

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine.connector import drawing_function

R_B, R_J, L = 10e-3, 9.9e-3, 15e-3
C = R_B - R_J
PAPER = dict(journal_radius=R_J, bearing_radius=R_B, length=L, law="wang-liu", cr=0.9)


def _impact_scene(mbs, **joint):
    """The paper's journal-bearing impact (docs/physics.md section 6.1), built the Exudyn way:
    centred in the reference configuration, touching the wall at the start."""
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[C, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], **{**PAPER, **joint})
    return handle, node


def _settings(tmp_path=None):
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 2e-4
    ss.timeIntegration.numberOfSteps = 200
    ss.solution.sensors.writePeriod = 1e-6
    if tmp_path is None:
        ss.solution.file.write = False
    else:
        ss.solution.file.write = True
        ss.solution.file.name = str(tmp_path / "solution.txt")
        ss.solution.file.writePeriod = 1e-5
    return ss


def _departure(mbs, node):
    return -mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]


def test_reset_and_rebuild_runs_the_new_joint():
    mbs = exu.SystemContainer().AddSystem()
    handle, node = _impact_scene(mbs)
    mbs.Assemble()
    assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4)).success
    first = _departure(mbs, node)
    mbs.Reset()
    handle2, node = _impact_scene(mbs, cr=0.5)  # rebuilt with another restitution
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4))
    assert result.success, result.message
    assert exuclear.engine.connector.joints_of(mbs) == [handle2]  # the old joint is gone
    assert first == pytest.approx(0.269, abs=5e-4)  # the paper's departure velocities at cr 0.9 and 0.5
    assert _departure(mbs, node) == pytest.approx(0.145, abs=5e-4)


@pytest.mark.parametrize("when", ["before", "after"])
def test_user_step_functions_run_and_stay_installed(when):
    mbs = exu.SystemContainer().AddSystem()
    calls = []

    def user_post_step(mbs_, t):
        calls.append(t)
        return True

    if when == "before":
        mbs.SetPostStepUserFunction(user_post_step)
    handle, node = _impact_scene(mbs)
    if when == "after":
        mbs.SetPostStepUserFunction(user_post_step)
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4))
    assert result.success, result.message
    assert len(calls) == result.steps + 1  # Exudyn calls it after every step and once at the start
    assert _departure(mbs, node) == pytest.approx(0.269, abs=5e-4)
    assert mbs.GetPostStepUserFunction()["function"] is user_post_step  # restored after the run
    calls.clear()
    mbs.SolveDynamic(_settings(), solverType=exu.DynamicSolverType.DOPRI5)  # and a direct solve
    assert calls and _departure(mbs, node) == pytest.approx(0.269, abs=5e-4)


def test_ctrl_c_in_a_run_raises_keyboard_interrupt():
    mbs = exu.SystemContainer().AddSystem()

    def interrupt(mbs_, t):
        if t > 5e-5:
            raise KeyboardInterrupt  # what Ctrl-C does in the next Python code that runs
        return True

    mbs.SetPostStepUserFunction(interrupt)
    _impact_scene(mbs)
    mbs.Assemble()
    with pytest.raises(KeyboardInterrupt):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4))


def test_solution_file_holds_the_run(tmp_path):
    # SolutionViewer reads this file: it must exist, with the state of every write period
    from exudyn.utilities import LoadSolutionFile

    mbs = exu.SystemContainer().AddSystem()
    handle, node = _impact_scene(mbs)
    mbs.Assemble()
    mbs.SolveDynamic(_settings(tmp_path), solverType=exu.DynamicSolverType.DOPRI5)
    solution = LoadSolutionFile(str(tmp_path / "solution.txt"))
    data = np.asarray(solution["data"])
    assert data.shape[0] >= 20 + 1  # 2e-4 s written every 1e-5 s, and the initial state
    assert data[-1, 0] == pytest.approx(2e-4)
    assert data[-1, 1] == pytest.approx(mbs.GetNodeOutput(node, exu.OutputVariableType.Displacement)[0])


def test_the_record_keeps_an_impact_shorter_than_the_output_interval():
    # E* = 1e20 Pa: an impact of ~1e-8 s, far shorter than any output interval; the
    # per-impact record is kept at every accepted step, so its peak force is there
    mbs = exu.SystemContainer().AddSystem()
    handle, node = _impact_scene(mbs, E_star=1e20)
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4, output_step=1e-4))
    assert result.success, result.message
    (record,) = handle.impacts()
    assert record.onset_velocity == pytest.approx(0.3)  # touching at the start: the exact onset rate
    assert record.peak_force > 0.0 and 0.0 < record.duration < 1e-6
    assert _departure(mbs, node) == pytest.approx(0.3 * 0.9, rel=0.02)  # the law's restitution at any stiffness


def test_replacing_the_joint_physics_takes_effect_in_the_next_run():
    mbs = exu.SystemContainer().AddSystem()
    handle, node = _impact_scene(mbs)
    mbs.Assemble()
    handle.joint = exuclear.make_joint(**{**PAPER, "cr": 0.3})
    assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4)).success
    assert _departure(mbs, node) == pytest.approx(0.098, abs=5e-4)  # the paper's value at cr 0.3


def test_drawing_puts_journal_and_bearing_at_their_markers():
    mbs = exu.SystemContainer().AddSystem()
    handle, node = _impact_scene(mbs)
    mbs.Assemble()
    journal, bearing = drawing_function(handle, exu.ConfigurationType.Current)(mbs, handle.drawingNumber)
    for item, centre, radius in ((journal, [C, 0, 0], R_J), (bearing, [0, 0, 0], 1.4 * R_B)):
        points = np.asarray(item["points"]).reshape(-1, 3)
        assert points[:, 0].max() - points[:, 0].min() == pytest.approx(2 * radius, rel=1e-3)
        assert 0.5 * (points[:, 0].max() + points[:, 0].min()) == pytest.approx(centre[0], abs=1e-12)
        assert points[:, 2].max() - points[:, 2].min() == pytest.approx(L)  # along the axis, the bearing length


def test_outputs_before_a_run_say_so():
    mbs = exu.SystemContainer().AddSystem()
    handle, _ = _impact_scene(mbs)
    mbs.Assemble()
    with pytest.raises(RuntimeError, match="no outputs yet: run a simulation first"):
        handle.outputs()


@pytest.mark.parametrize("bad,match", [({"name": 123}, "`name` must be a string"),
                                       ({"record": "no"}, "`record` must be True or False"),
                                       ({"axis": [0, 0, 0]}, "`axis` must not be zero")])
def test_bad_joint_options_are_refused(bad, match):
    mbs = exu.SystemContainer().AddSystem()
    with pytest.raises(ValueError, match=match):
        _impact_scene(mbs, **bad)


def test_constrain_axial_holds_axial_motion_and_tilt_as_the_revolute_joint_did():
    # a 3D journal pushed along the axis and tilted: with constrainAxial=True the joint also
    # holds axial translation and tilt (an implicit method, as for any Exudyn joint)
    from exudyn.utilities import InertiaCylinder

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    inertia = InertiaCylinder(density=7800.0, length=L, outerRadius=R_J, axis=2)
    body = mbs.CreateRigidBody(inertia=inertia, referencePosition=[0, 0, 0], initialVelocity=[0.1, 0, 0.2],
                               initialAngularVelocity=[3.0, -2.0, 0.0], returnDict=True)
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body["bodyNumber"]], position=[0, 0, 0],
                                           constrainAxial=True, **PAPER)
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-3, method="generalized-alpha", step=1e-5))
    assert result.success, result.message
    assert handle.constraintNumber is not None
    node = body["nodeNumber"]
    position = mbs.GetNodeOutput(node, exu.OutputVariableType.Position)
    omega = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)
    # held: generalized-alpha enforces the constraint on positions (to round-off) and the
    # rates follow to the Newton tolerance: 1e-6 of the 2-3 rad/s the journal started with
    assert abs(position[2]) < 1e-12 and abs(omega[0]) < 3e-6 and abs(omega[1]) < 3e-6
    # the in-plane motion stays free: 0.1 m/s crosses the 0.1 mm clearance in 1 ms and hits the wall
    assert handle.history.onsets >= 1 and handle.impacts()[0].onset_time == pytest.approx(1e-3, rel=0.05)


def test_a_run_continued_from_where_it_stopped_keeps_the_contact_history():
    # Exudyn's continuation: the state reached becomes the initial state and the next run
    # starts at the time reached. Split in the middle of the impact (at 20 us of ~35 us), the
    # two runs must give the single run's record and departure velocity (to round-off: the
    # continued run's step times are summed from another start).
    def settings(t0, t1):
        ss = exu.SimulationSettings()
        ss.timeIntegration.startTime, ss.timeIntegration.endTime = t0, t1
        ss.timeIntegration.numberOfSteps = int(round((t1 - t0) / 1e-6))
        ss.solution.file.write = False
        return ss

    runs = []
    for split in (None, 2e-5):
        mbs = exu.SystemContainer().AddSystem()
        handle, node = _impact_scene(mbs)
        mbs.Assemble()
        if split is not None:
            mbs.SolveDynamic(settings(0.0, split), solverType=exu.DynamicSolverType.RK44)
            assert handle.history.in_contact  # stopped inside the impact
            data = mbs.systemData
            data.SetODE2Coordinates(data.GetODE2Coordinates(), configuration=exu.ConfigurationType.Initial)
            data.SetODE2Coordinates_t(data.GetODE2Coordinates_t(), configuration=exu.ConfigurationType.Initial)
        mbs.SolveDynamic(settings(split or 0.0, 2e-4), solverType=exu.DynamicSolverType.RK44)
        runs.append((handle.impacts(), _departure(mbs, node)))
    (single, v_single), (split, v_split) = runs
    assert len(single) == len(split) == 1
    assert np.allclose(single[0], split[0], rtol=1e-12, atol=0.0) and v_split == pytest.approx(v_single, rel=1e-12)


def _rss_kb() -> int:
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmRSS"))


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=pytest.mark.skipif(
    exuclear.engine.kernel.STATUS != "direct", reason="compiled kernel not available"))])
def test_memory_stays_bounded_over_hundreds_of_models(backend):
    # a study builds and runs many models in one process: each model's system, handle and
    # kernel state must be freed with it (before: ~51 kB kept per model, and one more entry
    # of the compiled kernel's table each time), also when one system is reset and rebuilt
    import gc
    import tracemalloc

    from exuclear.engine import kernel

    def one_model():
        mbs = exu.SystemContainer().AddSystem()
        _impact_scene(mbs, backend=backend)
        mbs.Assemble()
        assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-5)).success

    for _ in range(20):  # warm-up: caches, Exudyn's first-use allocations
        one_model()
    gc.collect()
    in_use = kernel.COMPILED.joints_in_use() if kernel.COMPILED is not None else 0
    tracemalloc.start()
    try:
        before, rss = tracemalloc.get_traced_memory()[0], _rss_kb()
        n = 300 if backend == "compiled" else 100  # the Python kernel is slow under tracemalloc
        for _ in range(n):
            one_model()
        gc.collect()
        grown, rss_grown = tracemalloc.get_traced_memory()[0] - before, _rss_kb() - rss
    finally:
        tracemalloc.stop()
    assert grown < 200 * n  # bytes: < 0.2 kB per model of Python memory (a leak was ~50 kB)
    assert rss_grown < 10 * n  # kB: < 10 kB per model of process memory, C++ included (it was ~70 kB)
    if kernel.COMPILED is not None:
        assert kernel.COMPILED.joints_in_use() <= in_use  # every model's kernel entry was released

    mbs = exu.SystemContainer().AddSystem()  # one system, reset and rebuilt
    for _ in range(50):
        mbs.Reset()
        _impact_scene(mbs, backend=backend)
        mbs.Assemble()
    assert len(exuclear.engine.connector.joints_of(mbs)) == 1
    gc.collect()
    if kernel.COMPILED is not None:
        assert kernel.COMPILED.joints_in_use() <= in_use + 1  # only the live joint keeps its entry
