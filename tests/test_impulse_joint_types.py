"""The impulse contact mode (exuclear.engine.impulse) on the spherical and the pin-in-slot
joint: each joint type is its contact pair (exuclear.engine.impulse_pairs), the eccentricity
whose direction is the normal and the gap |e| - c; the mode's decisions are the revolute
joint's (tests/test_impulse_mode.py).  The scenes are those of ``python -m validation.cost
modes`` (validation/cost/_joint_type_scenes.py)."""
import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectRigidBody2D

import exuclear
from exuclear.timescales import closed_form_impact, impact_restitution
from validation.cost._joint_type_scenes import (
    BALL,
    BALL_MASS,
    THROW,
    THROW_SPEED,
    G,
    LAW,
    PIN,
    PIN_MASS,
    SLOT_LENGTH,
    SOCKET,
    WIDTH,
    ball_in_socket,
    bouncing_pin,
    dropped_ball,
    elastic_ball,
    jump_restitution,
    resting_ball,
    sliding_pin,
    solve,
    steps_taken,
    thrown_ball,
)


@pytest.mark.parametrize("durations", [10.0, 1000.0])
def test_a_ball_thrown_in_3d_rebounds_with_the_laws_restitution_along_its_normal(durations):
    # no gravity: the ball flies off-centre across the socket in 3D and hits its wall at normals
    # off the coordinate planes; each impact step's jump is along one normal n (the difference
    # of the velocities), holds the end rate -e(v) v (e the law's restitution at the onset
    # velocity v, to Newton's tolerance on the velocity condition) and keeps the tangential
    # velocity (frictionless).  At 1000 contact durations the steps are longer than the flight
    # across the clearance: the mode has Exudyn shorten those (as for the journal)
    mbs, joint, records, step = thrown_ball(durations)
    assert len(records) >= 8
    if durations > 100:  # the run's end is 4 steps: the mode had Exudyn shorten those that flew across
        assert steps_taken(mbs) > 4
    tilted = 0
    for jump in records:
        n, restitution = jump_restitution(jump)
        assert jump.impact.onset_velocity == pytest.approx(n @ jump.before, rel=1e-9)
        assert jump.impact.restitution == impact_restitution(joint.joint.law, jump.impact.onset_velocity)
        assert restitution == pytest.approx(jump.impact.restitution, rel=1e-9)
        tilted += bool(np.abs(n).min() > 0.1)
    assert tilted >= len(records) // 2  # the normals lie off the coordinate planes


def test_a_ball_dropped_in_its_socket_rebounds_with_the_laws_restitution_then_rests():
    # gravity -y; the ball falls from the socket's centre onto its wall at sqrt(2 g c) and
    # bounces at the law's restitution (each jump to Newton's tolerance, along -y) until the
    # rebound would land within two steps: then it rests, held by the condition, with the
    # ideal joint's reaction m g
    c = SOCKET - BALL
    joint, records, step = dropped_ball()
    bounces = [r for r in records if r.impact.restitution > 0.0]
    assert len(bounces) >= 10
    # Moreau-Jean's impact velocity is the rate at the start of the step in which the ball
    # reached the wall: the fall's sqrt(2 g c) less up to a step's g h
    assert math.sqrt(2 * G * c) - G * step <= records[0].impact.onset_velocity <= math.sqrt(2 * G * c)
    for impact, before, after in bounces:
        assert after[1] / -before[1] == pytest.approx(impact_restitution(joint.joint.law, impact.onset_velocity),
                                                      rel=1e-9)
    assert records[-1].impact.restitution == 0.0  # the last is the rest's onset
    out = joint.outputs()
    rest = out["time"] > records[-1].impact.onset_time + 100 * step
    assert rest.sum() > 100
    # the condition holds the ideal joint's reaction once it has taken back the onset's
    # penetration (RATE_GAIN: a factor 0.5 a step, 1e-30 of it after 100 steps)
    assert np.allclose(out["normal_force"][rest], BALL_MASS * G, rtol=1e-9)
    assert np.allclose(out["ecc_y"][rest], -c, rtol=1e-12)
    assert np.abs(out["ecc_x"][rest]).max() < 1e-15 and np.abs(out["ecc_z"][rest]).max() < 1e-15


def test_an_elastic_ball_keeps_its_energy():
    # cr = 1: no damping, restitution 1; the ball falls from the socket's centre with a
    # sideways velocity and bounces about the socket's bottom
    joint, drift = elastic_ball()
    assert len(joint.impacts()) >= 10
    assert np.abs(drift).max() <= 0.01 * G * (SOCKET - BALL)  # the target: within 1 %


def test_a_resting_ball_has_one_impact_and_the_ideal_joints_reaction():
    # gravity -y presses the ball, touching at t = 0, on the socket's bottom
    joint = resting_ball()
    assert len(joint.impacts()) == 1  # the onset of the rest, nothing after it
    out = joint.outputs()
    held = out["time"] > 100 * 1e-4
    # as the journal's (tests/test_impulse_mode.py): m g to round-off once the condition has
    # taken back the first steps' penetration
    assert np.allclose(out["normal_force"][held], BALL_MASS * G, rtol=1e-9)
    assert np.abs(out["penetration"]).max() < 2.0 * G * 1e-4**2  # Moreau-Jean's: below 2 g h^2


@pytest.mark.parametrize("where, bounces", [("flat side", 8), ("end cap", 4)])
def test_a_pin_rebounds_with_the_laws_restitution_at_a_flat_side_and_at_an_end_cap(where, bounces):
    # no gravity, a slot at 30 degrees: the pin flies across the slot (onto the flat sides)
    # or along it (onto the end caps) and back; each impact's onset velocity is the last
    # one's times the law's restitution at that velocity (Newton's tolerance on the velocity
    # condition), and the normal is the slot's normal or its axis.  Along the axis the path
    # is unstable: each end cap (radius c) focuses like a mirror of radius c, 2 c << the
    # caps' distance L, so a deviation from the axis grows by about 2 L / c = 400 a bounce,
    # from round-off to 1e-4 rad by the fifth impact: the end caps' run stops after four
    joint, direction = bouncing_pin(where, bounces)
    law = joint.joint.law
    impacts = joint.impacts()
    assert len(impacts) == bounces
    for before, after in zip(impacts, impacts[1:]):
        assert after.onset_velocity / before.onset_velocity == pytest.approx(
            impact_restitution(law, before.onset_velocity), rel=1e-9)
    out = joint.outputs()
    near = out["penetration"] > -0.5 * (0.5 * WIDTH - PIN)  # the steps' ends near a wall
    ecc = np.column_stack([out["ecc_x"], out["ecc_y"]])[near]
    assert near.sum() >= bounces // 2  # the steps are about half the flight across the slot
    # there the eccentricity lies along the expected normal: to round-off on the flat side
    # (pin minus its foot on the segment), and at the end caps within the path's deviation
    # from the axis (above: below 1e-9 rad before the fifth impact)
    assert np.abs(np.abs(ecc @ direction) / np.linalg.norm(ecc, axis=1) - 1.0).max() < 1e-9
    assert np.abs(out["ecc_z"]).max() == 0.0  # the plane's


def test_a_pin_slides_along_the_flat_side_then_swings_in_the_end_cap():
    # the pin rests on the slot's lower flat side (touching at t = 0) under gravity tilted
    # towards the slot's right end, and slides there frictionless: held by the condition, its
    # x is x0 + v0 t + g_x t^2 / 2 (the trapezoidal rule integrates a constant acceleration
    # exactly; Newton's tolerance on the condition is far below 1e-12 m).  Past the segment's
    # end (x > a) the contact turns around the end cap (the held step is computed again in
    # the normal reached): the pin, at v_a = sqrt(v0^2 + 2 g_x (a - x0)) = 0.033 m/s, swings
    # up the cap, held, to the angle where its energy is spent, and back onto the flat side
    step = 1e-4
    swing = sliding_pin(step)
    joint, states = swing.joint, swing.states
    out = joint.outputs()
    assert len(joint.impacts()) == 1 and joint.impacts()[0].restitution == 0.0  # resting from its first step
    flat = swing.flat()
    t = states[flat, 0]
    assert flat.sum() > 100
    assert np.abs(states[flat, 1] - (swing.x0 + swing.v0 * t + 0.5 * swing.gravity[0] * t**2)).max() < 1e-12
    assert np.abs(states[flat, 2] + swing.c).max() < 1e-12  # on the wall, y = -c
    # in the cap, energy conservation sets the swing's top (Swing.top_angle), 67 degrees from
    # -y: below 90 from the cap's lowest point, so the normal force stays compressive.  The
    # largest sampled angle is within 0.2 degrees of it (a step turns the normal by up to
    # v_a h / c = 1.9 degrees, but the angle is flat at the swing's top)
    turned = np.arctan2(out["ecc_x"], -out["ecc_y"])
    assert np.degrees(turned.max()) == pytest.approx(math.degrees(swing.top_angle()), abs=0.2)
    assert (turned[int(np.argmax(turned)):] == 0.0).any()  # and back onto the flat side (its foot inside the segment)
    held = out["time"] > 100 * step
    assert (out["normal_force"][held] > 0.0).all()
    # while the normal turns, a held step ends off the arc by about the sagitta of the arc it
    # covers, (v_a h)^2 / (8 c) (the rate gain takes it back over the next steps)
    assert np.abs(out["penetration"][held]).max() < swing.arrival_speed2() * step**2 / (8.0 * swing.c)
    # frictionless, the held contact does no work: the energy is kept up to the steps' error,
    # second order in the step (halving the step divides it by about 4); below 1 % of the
    # swing's |g| c
    drift = np.abs(swing.energy() - swing.energy()[0]).max()
    finer = sliding_pin(0.5 * step)
    assert drift < 0.01 * math.hypot(*swing.gravity) * swing.c
    assert drift / np.abs(finer.energy() - finer.energy()[0]).max() > 3.0


def test_a_spinning_slot_s_wall_strikes_a_free_pin_with_the_laws_restitution():
    # no gravity: a free slot body spins at 2 rad/s about its centre, a free pin sits 6 mm
    # along the slot at rest; the slot's flat side sweeps onto the pin at about w x = 0.012
    # m/s.  The gap's rate is the pin's velocity against the slot's material point at the
    # pin's foot S on the segment, n . (v_pin - v_c - w x r_S): with the slot's centre's
    # velocity instead it is 0 and the strike would be missed.  Each impact step's jump holds
    # that rate at -e(v) v, in the rows of the step's start (S there) and the normal n of
    # the pin's velocity change (the impulse acts through the pin's centre), to Newton's tolerance
    mbs = exu.SystemContainer().AddSystem()
    hub = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0, 0, 2.0]))
    slot = mbs.AddObject(ObjectRigidBody2D(nodeNumber=hub, mass=1.0, inertia=0.01))
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[6e-3, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=PIN_MASS, inertia=0.5 * PIN_MASS * PIN**2))
    joint = exuclear.CreatePinSlotClearanceJoint(
        mbs, itemNumbers=[slot, pin], position=[0, 0, 0], pin_radius=PIN, slot_width=WIDTH, slot_length=SLOT_LENGTH,
        length=10e-3, contact_mode="impulse", **LAW)
    mbs.Assemble()
    states = []
    ov = exu.OutputVariableType

    def post_step(mbs, t):
        states.append((t, *(x for n in (hub, node) for q in (ov.Coordinates, ov.Coordinates_t)
                             for x in mbs.GetNodeOutput(n, q))))
        return True
    mbs.SetPostStepUserFunction(post_step)
    assert solve(mbs, 1e-4, 0.1)
    states = np.array(states)  # t, slot (x, y, angle), its rates, pin (x, y, angle), its rates
    impacts = [i for i in joint.impacts() if i.restitution > 0.0]
    assert len(impacts) >= 2
    for impact in impacts:
        k = int(np.argmin(np.abs(states[:, 0] - impact.onset_time)))
        before, after = states[k], states[k + 1]
        assert before[0] == pytest.approx(impact.onset_time, abs=1e-12)
        dv = after[10:12] - before[10:12]
        n = np.append(dv / np.linalg.norm(dv), 0.0)
        axis = np.array([math.cos(before[3]), math.sin(before[3]), 0.0])
        foot = np.clip(np.append(before[7:9] - before[1:3], 0.0) @ axis, -0.5 * SLOT_LENGTH, 0.5 * SLOT_LENGTH) * axis

        def rate(s):
            return n @ (np.append(s[10:12] - s[4:6], 0.0) - np.cross([0.0, 0.0, s[6]], foot))
        assert abs(rate(before)) == pytest.approx(impact.onset_velocity, rel=1e-9)
        assert -rate(after) / rate(before) == pytest.approx(impact_restitution(joint.joint.law, impact.onset_velocity),
                                                            rel=1e-9)


def test_a_ball_stopped_by_fixed_steps_too_long_for_its_flight_is_named_as_the_ball():
    # at fixed steps of 1000 contact durations a free step carries the thrown ball across the
    # whole clearance (its diameter) into the far wall: the run stops, and the message names
    # the joint and the ball (not a journal) and what to do
    c = SOCKET - BALL
    mbs, joint, _ = ball_in_socket([0.5 * c, -0.3 * c, 0.2 * c], THROW_SPEED * THROW)
    step = 1000.0 * closed_form_impact(joint.joint.law, BALL_MASS, THROW_SPEED)[1]
    assert step * THROW_SPEED > 2.0 * c  # the step is longer than the flight across the socket
    with pytest.raises(Exception):
        solve(mbs, step, 4 * step, adaptive=False)
    with pytest.raises(ValueError, match="joint ball: .*the ball's flight across the clearance; take shorter steps"):
        joint.impacts()
