"""A newcomer's first hour (issue 48): what a user meets on the first model they build,
each test named after what it proves.  The four-bar of the guide's first model
(``validation/first_hour.py``) is the model of the solver tests."""
from __future__ import annotations

import warnings

import pytest

import exuclear

STEEL_JOINT = dict(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, journal_material="steel",
                   bearing_material="steel")


# -- 5. the main job is quiet about its own choices; warnings point at the caller -------------------


def test_the_main_job_is_quiet_about_its_own_choices_and_its_table_marks_a_law_out_of_range():
    from validation import journal_bearing as script

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning fails the test
        script.restitution_params()
        row = script.restitution_row(script.ImpactRunner(workers=1), "wang-liu")
    # Wang-Liu's damping (Zhiying-Qishao) is established for cr >= 0.3 (its cr_valid_from):
    # the grid's 0.1 and 0.2 lie below, and the table says so where the values are
    assert row.outside == (0.1, 0.2)
    table = script.restitution_md([row])
    assert "| wang-liu [1] | " in table and table.count("*") >= 2
    assert "[1] wang-liu at cr = 0.1, 0.2 (marked *): outside its source's range" in table


def test_a_validity_warning_points_at_the_user_s_line():
    with pytest.warns(exuclear.ValidityWarning, match="established for cr >= 0.3") as caught:
        exuclear.make_joint(law="wang-liu", cr=0.1, **STEEL_JOINT)
    assert caught[0].filename == __file__
    with pytest.warns(exuclear.ValidityWarning, match="friction coefficient") as caught:
        exuclear.make_joint(law="wang-liu", cr=0.9, friction="coulomb:1.5", **STEEL_JOINT)
    assert caught[0].filename == __file__


# -- 8. smaller: law names in any case ------------------------------------------------------------


def test_law_and_friction_names_are_case_insensitive():
    lower = exuclear.make_joint(law="wang-liu", cr=0.7, friction="coulomb:0.1", **STEEL_JOINT)
    assert exuclear.make_joint(law="Wang-Liu", cr=0.7, friction="Coulomb:0.1", **STEEL_JOINT) == lower
    pair = exuclear.make_joint(law="hertz+lankarani-nikravesh", cr=0.7, **STEEL_JOINT)
    assert exuclear.make_joint(law="Hertz+Lankarani-Nikravesh", cr=0.7, **STEEL_JOINT) == pair
    with pytest.raises(ValueError, match="unknown `law` 'wang liu'; known: "):
        exuclear.make_joint(law="wang liu", cr=0.7, **STEEL_JOINT)


# -- 3. a journal outside its bearing is refused by the plain SolveDynamic too --------------------


def _pendulum_journal(backend: str, offset: float, name: str = ""):
    """The README's free journal (c = 0.1 mm), its centre ``offset`` [m] from the bearing's."""
    import exudyn as exu
    from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[offset, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    joint = exuclear.CreateClearanceJoint(mbs, name=name, itemNumbers=[ground, pin], position=[0, 0, 0],
                                          law="wang-liu", cr=0.9, friction="none", backend=backend, **STEEL_JOINT)
    mbs.Assemble()
    return mbs, joint


@pytest.mark.parametrize("backend", ["compiled", "python"])
def test_a_journal_outside_its_bearing_is_refused_by_the_plain_solve_dynamic_too(backend):
    import exudyn as exu

    from exuclear.engine import kernel

    if backend == "compiled" and kernel.default_backend() != "compiled":
        pytest.skip("no compiled kernel here")
    mbs, joint = _pendulum_journal(backend, offset=1e-3)  # 10 clearances from the centre: 9 c beyond the wall
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 2e-4
    ss.solution.file.write = False
    with pytest.raises(Exception, match=r"joint #1: the journal starts outside its bearing \(penetration 0.0009 m, "
                                        r"9 clearances.*check the joint's `position` and the initial coordinates of "
                                        r"the bodies in `itemNumbers`"):
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    assert joint.failure()[0].startswith("the journal starts outside its bearing")
    assert mbs.systemData.GetTime() == 0.0  # not one step taken
    # exuclear.simulate says the same before its run
    with pytest.raises(ValueError, match=r"clearance joint #1: the journal starts outside its bearing.*`position`"):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4))
    # within the clearance it runs: the README's case, touching the wall
    mbs, joint = _pendulum_journal(backend, offset=1e-4)
    assert mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    assert len(joint.impacts()) == 1


# -- 8. smaller: names, not object numbers; a repr ------------------------------------------------


def test_messages_name_a_joint_by_its_name_or_its_place_among_the_joints_and_a_handle_has_a_repr():
    from exuclear.engine.registry import label

    mbs, joint = _pendulum_journal("python", offset=1e-4)
    assert label(joint) == "#1"
    text = repr(joint)
    assert text.startswith("<ClearanceJointHandle #1: planar, clearance 0.0001 m, WangLiu law, objectNumber ")
    named = _pendulum_journal("python", offset=1e-4, name="crank pin")[1]
    assert label(named) == "'crank pin'" and "<ClearanceJointHandle 'crank pin': " in repr(named)
    with pytest.raises(RuntimeError, match=r"joint #1 has no outputs yet"):
        joint.outputs()
