"""The impulse contact mode (exuclear.engine.impulse) on the translational joints: each corner
against its two walls across a guide axis is a contact pair of its own
(exuclear.engine.impulse_guide), the corners' conditions solved together by Newton.  The
scenes are those of ``python -m validation.cost modes`` (validation/cost/_translational_scenes.py)."""
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine.impulse_guide import ImpulseGuideHandle
from exuclear.engine.modes import ENVIRONMENT_VARIABLE
from exuclear.timescales import impact_restitution
from validation.cost._translational_scenes import (
    CLEARANCE,
    MASS,
    THROW_SPEED,
    TURN,
    TURN_STEP,
    G,
    elastic,
    first_jump,
    jumps,
    resting,
    resting_box,
    thrown,
    thrown_box,
)

#: Newton's tolerance on the velocity condition bounds a jump's error: the tests of the
#: other joint types' restitution hold it to the same relative 1e-9.
JUMP_TOLERANCE = 1e-9


def test_a_slider_thrown_flat_hits_with_both_corners_of_a_wall_in_one_step():
    # no gravity: the slider crosses the guide without turning; at each wall both of its
    # corners there hit in the same step, each jump holding the law's restitution at the
    # onset velocity, which is the slider's: 0.3 m/s, then e(0.3) 0.3, ...
    run = thrown(0.0)
    impacts = run.joint.impacts()
    assert len(impacts) >= 6 and len(impacts) % 2 == 0  # two corners at each wall reached
    law = run.joint.joint.law
    speed = THROW_SPEED
    for first, second in zip(impacts[::2], impacts[1::2]):
        assert first.onset_time == second.onset_time
        assert {first.pair, second.pair} in ({"corner rear-lower / lower wall", "corner front-lower / lower wall"},
                                             {"corner rear-upper / upper wall", "corner front-upper / upper wall"})
        for impact in (first, second):
            assert impact.onset_velocity == pytest.approx(speed, rel=JUMP_TOLERANCE)
            assert impact.restitution == impact_restitution(law, impact.onset_velocity)
            # each corner's share of the impulse: half the slider's mass (symmetric)
            assert impact.effective_mass == pytest.approx(0.5 * MASS, rel=JUMP_TOLERANCE)
        speed *= impact_restitution(law, speed)
    for impact, before, after, restitution in jumps(run):
        assert before == pytest.approx(impact.onset_velocity, rel=JUMP_TOLERANCE)
        assert -after / before == pytest.approx(restitution, rel=JUMP_TOLERANCE)
    assert np.abs(run.states[:, 3]).max() < 1e-15  # it never turns


def test_a_turned_slider_hits_with_one_corner_and_the_laws_restitution():
    # turned by 2 mrad the rear-lower corner reaches the wall 100 um before the front one; at
    # steps of half a contact duration it hits alone, the slider spins and its corners hit
    # the walls one by one; each jump holds the corner's normal rate (in the rows of the
    # step's start) at -e(v) v, e the law's
    run = thrown(TURN, TURN_STEP)
    impacts = run.joint.impacts()
    assert impacts[0].pair == "corner rear-lower / lower wall"
    assert impacts[1].onset_time > impacts[0].onset_time
    assert len({i.onset_time for i in impacts}) >= 5  # most impacts are one corner's
    records = jumps(run)
    assert len(records) >= 4
    for impact, before, after, restitution in records:
        assert impact.restitution == restitution
        assert before == pytest.approx(impact.onset_velocity, rel=JUMP_TOLERANCE)
        assert -after / before == pytest.approx(restitution, rel=JUMP_TOLERANCE)


@pytest.mark.parametrize("angle", [0.0, TURN])
def test_steps_longer_than_the_flight_across_the_clearance_are_shortened_keeping_the_restitution(angle):
    # at 1000 contact durations a step is far longer than the slider's flight across the
    # clearance: the mode has Exudyn's adaptive step shorten those that would fly through
    # the wall (as for the journal), and each corner's jump keeps the law's restitution
    run = thrown(angle, durations=1000.0)
    assert len(run.states) > 4 + 1  # the run asked for 4 steps (and the start's post-step call)
    records = jumps(run)
    assert len(records) >= 20
    for impact, before, after, restitution in records:
        assert -after / before == pytest.approx(restitution, rel=JUMP_TOLERANCE)


@pytest.mark.parametrize("direction, wall", [((0, -1, 0), "lower"), ((0, 0, -1), "far")])
def test_a_box_thrown_flat_hits_with_four_corners_in_one_step(direction, wall):
    # no gravity: the box crosses the channel (across y, or across z) without turning; at the
    # wall its four corners there hit in one step.  Their four conditions span three
    # directions (the velocity across the wall and two turns): one stays off, held by the
    # three, and the impulse is shared as the least-squares split, a quarter each.  The
    # box's velocity across the wall jumps to -e(v) v
    run = thrown_box(direction)
    impacts = run.joint.impacts()
    first = [i for i in impacts if i.onset_time == impacts[0].onset_time]
    assert len(first) == 4 and all(i.pair.endswith(f"/ {wall} wall") for i in first)
    law = run.joint.joint.law
    for impact in first:
        assert impact.onset_velocity == pytest.approx(THROW_SPEED, rel=JUMP_TOLERANCE)
        assert impact.effective_mass == pytest.approx(0.25 * MASS, rel=JUMP_TOLERANCE)
    assert first_jump(run, int(np.argmax(np.abs(direction)))) == pytest.approx(
        impact_restitution(law, THROW_SPEED), rel=JUMP_TOLERANCE)
    assert np.abs(run.states[:, 7:10]).max() < 1e-12  # it never turns (rad/s)


def test_a_slider_resting_flat_holds_two_corners_at_half_its_weight():
    # gravity -y presses the slider, touching at t = 0, on its lower wall: both lower corners
    # are held from the first step, each with the rigid slider's static share m g / 2 (the
    # analytic split, as validation/translational.py checks the compliant joint's), and no
    # impact after those onsets: no chatter
    run = resting()
    impacts = run.joint.impacts()
    assert [(i.onset_time, i.restitution) for i in impacts] == [(0.0, 0.0), (0.0, 0.0)]
    out = run.joint.outputs()
    for name in ("corner rear-lower / lower and upper walls", "corner front-lower / lower and upper walls"):
        held = out[name]["time"] > 100 * run.step
        # to round-off once the condition has taken back the first steps' penetration (the
        # rate gain halves it a step)
        assert np.allclose(out[name]["normal_force"][held], 0.5 * MASS * G, rtol=1e-9)
    for name in ("corner front-upper / lower and upper walls", "corner rear-upper / lower and upper walls"):
        assert not out[name]["normal_force"].any()
        assert out[name]["penetration"] == pytest.approx(-2 * CLEARANCE, abs=1e-15)  # H/2 + c - (H/2 + 2c)


def test_a_box_resting_flat_holds_four_corners_at_a_quarter_of_its_weight():
    # the box flat on its lower wall: four corners, three directions; the three acting
    # conditions carry the weight and the least-squares split gives each corner m g / 4,
    # the analytic static split of a rigid box (validation/translational.py's for the compliant joint)
    joint = resting_box()
    impacts = joint.impacts()
    assert len(impacts) == 4 and all(i.onset_time == 0.0 and i.restitution == 0.0 for i in impacts)
    out = joint.outputs()
    held = [name for name, o in out.items() if o["normal_force"].any()]
    assert sorted(held) == sorted(f"corner {c}-lower-{s} / lower and upper walls"
                                  for c in ("rear", "front") for s in ("far", "near"))
    for name in held:
        steady = out[name]["time"] > 100 * 1e-4
        assert np.allclose(out[name]["normal_force"][steady], 0.25 * MASS * G, rtol=1e-9)


def test_a_resting_slider_slides_frictionless_without_drag():
    # held on its lower wall, moving along the guide at 0.05 m/s: the conditions act across
    # the wall only, so x = x0 + v0 t (to round-off) and the slider stays flat on the wall
    run = resting(velocity=0.05)
    t, x, y, angle = run.states[:, :4].T
    assert len(run.joint.impacts()) == 2
    assert np.abs(x - 0.05 * t).max() < 1e-12
    assert np.abs(y + CLEARANCE).max() < 1e-12 and np.abs(angle).max() < 1e-12


def test_an_elastic_spinning_slider_rattling_in_its_guide_keeps_its_energy():
    # cr 1, no gravity: the slider spins at 2 rad/s and crosses the guide; its corners hit
    # both walls one by one, each at restitution 1 in its own normal
    run, energy = elastic()
    impacts = run.joint.impacts()
    assert len(impacts) >= 20 and len({i.pair for i in impacts}) == 4
    assert all(i.restitution == 1.0 for i in impacts)
    assert np.abs(energy - 1.0).max() < 0.01  # the target: within 1 %


def _slider_body():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.1, inertia=1e-4))
    return mbs, dict(itemNumbers=[ground, body], slider_length=0.04, slider_height=0.02, clearance=1e-4,
                     stiffness=1e9, cr=0.9)


def test_the_mode_takes_a_finite_guide(monkeypatch):
    # a finite guide's corners are the mode's pairs with the guide's end (tests/test_impulse_ends.py),
    # asked for by the argument or by the environment, silently
    mbs, guide = _slider_body()
    handle = exuclear.CreatePrismaticClearanceJoint(mbs, name="G", contact_mode="impulse", guide_length=0.2, **guide)
    assert isinstance(handle, ImpulseGuideHandle) and len(handle.pairs) == 4
    assert all(pair._pair.half_guide == 0.1 for pair in handle.pairs.values())
    monkeypatch.setenv(ENVIRONMENT_VARIABLE, "impulse")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        handle = exuclear.CreatePrismaticClearanceJoint(mbs, name="P", guide_length=0.2, **guide)
    assert isinstance(handle, ImpulseGuideHandle)
