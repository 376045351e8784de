"""The impulse contact mode (exuclear.engine.impulse) on the spatial revolute joint: each slice
is a contact pair of its own (exuclear.engine.impulse_pairs.SlicePair), the slices held in a
step solved together (exuclear.engine.impulse_group).  The scenes are those of ``python -m
validation.cost modes`` (validation/cost/_spatial_scenes.py)."""
import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import LoadForceVector, LoadTorqueVector, MarkerBodyRigid, ObjectGround

import exuclear
from exuclear.timescales import closed_form_impact, impact_restitution
from validation.cost._joint_type_scenes import solve
from validation.cost._spatial_scenes import (
    BEARING,
    CLEARANCE,
    G,
    INERTIA,
    JOURNAL,
    LAW,
    LENGTH,
    MASS,
    SLICES,
    THROW_SPEED,
    elastic,
    resting,
    thrown_flat,
)
from validation.cost._translational_scenes import first_jump

#: Newton's tolerance on the velocity condition bounds a jump's error: the other joint
#: types' restitution tests hold it to the same relative 1e-9.
JUMP_TOLERANCE = 1e-9


def test_a_journal_thrown_flat_hits_with_every_slice_at_once_and_the_laws_restitution():
    # no gravity: the journal crosses its bearing parallel to it; at the wall its four slices
    # hit in one step.  Their wrenches span two directions (the force across the wall and the
    # tilt), so two conditions act and two are held by them; the impulse is split evenly (the
    # least-squares split), each slice's closed form is its share w / L of the law on its
    # share of the mass, and the journal's velocity jumps to -e(v) v
    run = thrown_flat()
    impacts = run.joint.impacts()
    law = run.joint.joint.law
    first = [i for i in impacts if i.onset_time == impacts[0].onset_time]
    assert len(first) == SLICES
    whole = closed_form_impact(law, MASS, THROW_SPEED)
    for impact in first:
        assert impact.onset_velocity == pytest.approx(THROW_SPEED, rel=JUMP_TOLERANCE)
        assert impact.effective_mass == pytest.approx(MASS / SLICES, rel=JUMP_TOLERANCE)
        assert impact.peak_force == pytest.approx(whole[0] / SLICES, rel=JUMP_TOLERANCE)
        assert impact.duration == pytest.approx(whole[1], rel=JUMP_TOLERANCE)
    assert first_jump(run, 1) == pytest.approx(impact_restitution(law, THROW_SPEED), rel=JUMP_TOLERANCE)
    assert np.abs(run.states[:, 7:10]).max() < 1e-12  # it never tilts (rad/s)


def test_a_journal_resting_flat_shares_its_weight_over_its_slices():
    # gravity -y presses the journal, touching at t = 0, on the bearing's bottom: all four
    # slices are held, two acting, and each carries m g / 4 (the rigid journal's symmetric
    # split, as the compliant joint's equal slices take it); no impact after the onsets
    run = resting()
    impacts = run.joint.impacts()
    assert len(impacts) == SLICES and all(i.onset_time == 0.0 and i.restitution == 0.0 for i in impacts)
    for out in run.joint.outputs().values():
        held = out["time"] > 100 * run.step
        # to round-off once the conditions have taken back the first steps' penetration
        assert np.allclose(out["normal_force"][held], MASS * G / SLICES, rtol=1e-9)


def test_an_elastic_tilting_journal_keeps_its_energy():
    # cr 1, no gravity: the journal crosses its bearing while tilting at 20 rad/s, so that its
    # end slices hit one at a time, dozens of times.  Its energy stays within 1 % (the issue's
    # target), and within 1e-4 at this step: each jump conserves the normal velocity exactly,
    # and the steps after it start from the trapezoidal rule's accelerations and velocities
    # less their step-to-step alternation (exuclear.engine.settling; with the alternation
    # left in them the change is 8e-4 here, python -m validation.cost modes); a quarter of
    # the step does not make it larger
    run, energy = elastic()
    impacts = run.joint.impacts()
    assert len(impacts) >= 40 and all(i.restitution == 1.0 for i in impacts)
    assert {i.pair for i in impacts} == {"slice 1 at z = -0.01125 m", "slice 4 at z = 0.01125 m"}
    drift = np.abs(energy - 1.0).max()
    assert drift < 1e-4
    _, finer = elastic(step=2.5e-6)
    assert np.abs(finer - 1.0).max() < drift


@pytest.mark.parametrize("slices", [None, SLICES])
def test_constrain_axial_holds_the_journal_along_its_axis_in_the_mode(slices):
    # a 3D journal resting on its bearing under gravity -y, pushed along the axis by 1 N and
    # turned about x by 0.01 N m: constrainAxial's joint holds the axial translation (and,
    # for the planar joint, the two tilts), as in the compliant joint; without it the push
    # would move the journal 0.5 F t^2 / m = 0.34 m in 0.05 s
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.CreateRigidBody(inertia=INERTIA, referencePosition=[0, 0, 0], initialDisplacement=[0, -CLEARANCE, 0],
                               gravity=[0, -G, 0])
    marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
    mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0, 0, 1.0]))
    mbs.AddLoad(LoadTorqueVector(markerNumber=marker, loadVector=[0.01, 0, 0]))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=JOURNAL, bearing_radius=BEARING, length=LENGTH,
                                          slices=slices, constrainAxial=True, contact_mode="impulse", **LAW)
    assert joint.constraintNumber is not None
    mbs.Assemble()
    solve(mbs, 1e-4, 0.05)
    position = mbs.GetObjectOutputBody(body, exu.OutputVariableType.Position, localPosition=[0, 0, 0])
    assert abs(position[2]) < 1e-12  # the constraint holds the axis to Newton's tolerance
    if slices is None:  # the planar joint's constraint holds the tilts too
        assert np.abs(mbs.GetObjectOutputBody(body, exu.OutputVariableType.AngularVelocity,
                                              localPosition=[0, 0, 0])[:2]).max() < 1e-12


def test_a_spinning_journal_gliding_on_its_slices_runs_and_a_failed_newton_iteration_is_told(monkeypatch):
    # the scene: a journal free along its axis gliding at 0.2 m/s and spinning at
    # 50 rad/s on its slices with friction.  A tilt within the clearance turns the slices'
    # normals apart and makes three slices nearly dependent; the mode holds an independent set
    # (impulse_group.DEPENDENT_WRENCHES) and runs to the end at the example's step
    from exuclear.engine import impulse_group
    from validation.cost._spatial_scenes import spatial_journal

    def gliding():
        return spatial_journal((0.0, 0.0, 0.2), (0.0, 0.0, 50.0), (0.0, -CLEARANCE, 0.0), (0.0, -G, 0.0),
                               contact_mode="impulse", friction="coulomb:0.2")
    mbs, joint, states = gliding()
    solve(mbs, 1e-4, 0.02, adaptive=False)
    assert states[-1][0] == pytest.approx(0.02)
    # with every nearly dependent slice acting (a tolerance at round-off), the multipliers of
    # three nearly dependent slices grow with opposite signs and Exudyn's Newton iteration
    # fails: the joint says where, which contacts it held with which forces, and what to use
    monkeypatch.setattr(impulse_group, "DEPENDENT_WRENCHES", 1e-12)
    mbs, joint, states = gliding()
    with pytest.raises(exu.SolverError):
        solve(mbs, 1e-4, 0.02, adaptive=False)
    with pytest.raises(RuntimeError, match="Newton iteration failed") as told:
        joint.notes
    message = str(told.value)
    assert message.startswith("joint journal: slice 1") and "contact_mode='compliant'" in message
    assert "slice 2 at z = -0.00375 m" in message and "against their resultant" in message
