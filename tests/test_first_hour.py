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


# -- 7. the guide's first model: a driven four-bar built with Exudyn's items ----------------------


def test_the_guide_s_four_bar_runs_with_a_plain_solve_dynamic_within_the_play_of_the_ideal_mechanism():
    from validation import first_hour

    # 0.1 s: half a crank revolution, with the first impacts of the journal's start (centred)
    r = first_hour.against_ideal(step=1e-4, end_time=0.1)
    assert r["impacts"] >= 1 and r["max_eps"] >= 1.0  # the journal reached the wall: the joint has play
    # the rocker within what the play allows (validation/first_hour.py rocker_bound, the linearised loop
    # closure at the smallest transmission angle); 2 % for the linearisation (c / c_rocker = 5e-4) and
    # the interpolation of the sensor rows at the write period (1e-4 s)
    assert r["difference"] <= 1.02 * r["bound"]
    # and it is the play that moves it: the journal on the wall moves the rocker by a sizeable share
    assert r["difference"] >= 0.3 * r["bound"]


# -- 1. exuclear.simulate is never worse than the plain call with the same step -------------------


def test_simulate_reaches_the_end_where_the_plain_call_with_the_same_step_does_with_a_method_that_fits():
    from validation import first_hour

    # 0.05 s holds the journal's first flight and impacts, where exuclear.simulate at a numeric
    # step (fixed steps then) stopped at 0.0022 s while the plain call ran on
    end = 0.05
    mbs, joint, _ = first_hour.four_bar()
    assert first_hour.run_plain(mbs, 1e-4, end) and mbs.systemData.GetTime() == pytest.approx(end)
    plain_impacts = len(joint.impacts())
    mbs, joint, _ = first_hour.four_bar()
    with warnings.catch_warnings():
        warnings.simplefilter("error", exuclear.AccuracyWarning)  # nothing to warn of where the plain call is quiet
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=end, step=1e-4))
    assert result.success and result.time_reached == pytest.approx(end), result.message
    # the default method fits the model: its constraints (joints, the drive) need an implicit one
    assert result.method == "generalized-alpha"
    # the same run as the plain call: its settings map onto Exudyn's defaults (adaptive steps,
    # the joints' step control), so it meets the same impacts (a chaotic model: counts of runs
    # that differ only in round-off may differ, but these two differ in nothing)
    assert len(joint.impacts()) == plain_impacts >= 1
    # a model without constraints keeps DOPRI5, whose error control resolves a free journal
    mbs, _joint = _pendulum_journal("python", offset=1e-4)
    assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4)).method == "dopri5"


def test_simulate_s_advice_names_only_settings_its_users_can_set():
    from validation import first_hour

    # fixed steps (joint_steps=False): Newton fails at the first impact, 2.2 ms in
    mbs, _joint, _ = first_hour.four_bar()
    settings = exuclear.SolverSettings(end_time=0.05, step=1e-4, joint_steps=False)
    with pytest.warns(exuclear.AccuracyWarning) as caught:
        result = exuclear.simulate(mbs, settings)
    assert not result.success
    said = [result.message, *result.notes, *(str(w.message) for w in caught)]
    assert not [s for s in said if "timeIntegration" in s or "verboseMode" in s], said
    assert any("joint_steps=True" in s for s in said), said  # the setting that lets the solver shorten the step


# -- 2. advice is consistent -----------------------------------------------------------------------


def _note(control_changes: dict, running: bool = False, adaptive: bool = True) -> str:
    """The joint's note on an unresolved step after a plain run of the README's journal
    (DOPRI5 or generalized-alpha, ``adaptive``: Exudyn's step control on or off), with the
    kernel's step-control record changed by ``control_changes``."""
    import exudyn as exu

    from exuclear.engine.diagnostics import step_notes

    mbs, joint = _pendulum_journal("python", offset=1e-4)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 2e-4
    ss.timeIntegration.numberOfSteps = 200
    ss.timeIntegration.adaptiveStep = adaptive
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    control = {**joint._backend.step_control(), **control_changes}
    return " ".join(text for _kind, text in step_notes(joint, control, running))


def test_a_note_never_asks_for_a_step_at_or_above_the_one_it_took_nor_for_a_setting_in_force():
    # the step taken (1e-7 s) is already what the joint's estimate asks for, and the shortest it
    # takes (10 x Exudyn's minimum step, 1e-8 s): the note says what would go further
    note = _note({"unresolved": 1, "unresolved_time": 1e-7, "unresolved_step": 1e-7, "unresolved_advice": 1e-7})
    assert "a step of 1e-07 s did not resolve the contact" in note and "use a step of" not in note
    assert "a smaller minimum step (timeIntegration.minimumStepSize)" in note
    # a step within the estimate, above that floor: no step would; the model is the likely cause
    note = _note({"unresolved": 1, "unresolved_time": 5e-6, "unresolved_step": 5e-6, "unresolved_advice": 1e-5})
    assert "use a step of" not in note and "a shorter step alone will not resolve it" in note
    assert "units (E in Pa, lengths in m)" in note
    # a step longer than the advice: the advice, and Exudyn's adaptive step (its default) not asked for again
    note = _note({"unresolved": 1, "unresolved_time": 1e-5, "unresolved_step": 1e-5, "unresolved_advice": 1e-6})
    assert "use a step of at most 1e-06 s (timeIntegration.numberOfSteps)" in note
    assert "adaptiveStep" not in note
    # fixed steps: the note asks for what would let the solver shorten them
    note = _note({"unresolved": 1, "unresolved_time": 1e-5, "unresolved_step": 1e-5, "unresolved_advice": 1e-6},
                 adaptive=False)
    assert "(timeIntegration.adaptiveStep is False)" in note and "timeIntegration.adaptiveStep = True" in note


def test_step_auto_does_not_warn_about_the_step_it_chose():
    from validation import first_hour

    # the joints control the steps (largest end_time / 1000) and shorten those in which a
    # contact begins, is held or ends: no note asks for another step
    mbs, joint, _ = first_hour.four_bar()
    with warnings.catch_warnings():
        warnings.simplefilter("error", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.2, step="auto"))
    assert result.success and result.step == pytest.approx(0.2 / 1000) and result.notes == ()
    assert joint.notes == [] and joint.counts["impacts"] >= 1
    # its contacts end in steps of at most a tenth of the contact period: none is counted as chatter
    control = joint._backend.step_control()
    assert control["separations"] >= 1 and control["long_separations"] == 0


@pytest.mark.parametrize("backend", ["compiled", "python"])
def test_the_chatter_warning_comes_at_the_end_of_the_run_not_at_the_first_read_of_the_impacts(backend):
    import exudyn as exu
    import test_robust  # issue 15's resting pendulum

    from exuclear.engine import kernel

    if backend == "compiled" and kernel.default_backend() != "compiled":
        pytest.skip("no compiled kernel here")
    # steps of 1e-3 s, 2.9 of its contact periods, and impact-aware steps from each onset (which
    # replace the joint's other rules): it leaves the wall again and again (test_robust's chatter)
    mbs, joint = test_robust.pendulum(backend=backend)
    joint.set_impact_step(1e-6)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 1.0, 1000
    ss.solution.file.write = False
    with pytest.warns(exuclear.AccuracyWarning, match="may be numerical chatter"):
        mbs.SolveDynamic(ss)
    with warnings.catch_warnings():
        warnings.simplefilter("error", exuclear.AccuracyWarning)  # told once, at the end of the run
        impacts = joint.impacts()
    assert len(impacts) > 10 and any("chatter" in note for note in joint.notes)
