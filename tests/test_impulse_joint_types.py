"""The impulse contact mode (exuclear.engine.impulse) on the spherical and the pin-in-slot
joint: each joint type is its contact pair (exuclear.engine.impulse_pairs), the eccentricity
whose direction is the normal and the gap |e| - c; the mode's decisions are the revolute
joint's (tests/test_impulse_mode.py)."""
import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D
from exudyn.utilities import InertiaSphere

import exuclear
from exuclear.engine.impulse import ImpulseJointHandle
from exuclear.timescales import closed_form_impact, impact_restitution

G = 9.81
#: A steel ball of 9.9 mm in a socket of 10 mm (c = 0.1 mm), the zoo's spherical joint.
BALL, SOCKET = 9.9e-3, 10e-3
BALL_MASS = 7850.0 * 4.0 / 3.0 * math.pi * BALL**3  # kg, steel
#: A pin of 4.9 mm in a slot 10 mm wide (c = 0.1 mm) whose end centres lie 20 mm apart.
PIN, WIDTH, SLOT_LENGTH = 4.9e-3, 10e-3, 20e-3
PIN_MASS = 0.04  # kg
LAW = {"law": "hertz+lankarani-nikravesh", "cr": 0.9}


def solve(mbs, step, end_time, adaptive=True):
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = int(round(end_time / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0  # the mode's (trapezoidal rule)
    ss.timeIntegration.adaptiveStep = adaptive
    ss.timeIntegration.verboseMode = 0
    return mbs.SolveDynamic(ss)


def recorder(mbs, node, out):
    """A post-step function appending (t, position (3), velocity (3)) of ``node``."""
    ov = exu.OutputVariableType

    def post_step(mbs, t):
        out.append((t, *mbs.GetNodeOutput(node, ov.Position), *mbs.GetNodeOutput(node, ov.Velocity)))
        return True
    mbs.SetPostStepUserFunction(post_step)


def ball_in_socket(start, velocity, gravity=0.0, **law):
    """A steel ball (its centre of mass at its centre) in a socket held by the ground, centred
    at the origin; the ball's centre at ``start`` [m] moving at ``velocity`` [m/s]; returns
    mbs, the joint and the ball's node."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    ball = mbs.CreateRigidBody(inertia=InertiaSphere(BALL_MASS, BALL), referencePosition=[0, 0, 0],
                               initialDisplacement=list(start), initialVelocity=list(velocity),
                               gravity=[0, -gravity, 0])
    joint = exuclear.CreateSphericalClearanceJoint(mbs, name="ball", itemNumbers=[ground, ball], position=[0, 0, 0],
                                                   ball_radius=BALL, socket_radius=SOCKET, contact_mode="impulse",
                                                   **{**LAW, **law})
    assert isinstance(joint, ImpulseJointHandle)
    mbs.Assemble()
    return mbs, joint, mbs.GetObject(ball)["nodeNumber"]


def jumps(joint, states, initial):
    """Each impact's velocities before and after its step (rows of ``states`` at the step's
    start and end; ``initial`` where it starts the run)."""
    times = states[:, 0]
    out = []
    for impact in joint.impacts():
        k = int(np.argmin(np.abs(times - impact.onset_time)))
        before = states[k, 4:7] if abs(times[k] - impact.onset_time) < 1e-12 else initial
        after = states[int(np.searchsorted(times, impact.onset_time * (1 + 1e-12) + 1e-15)), 4:7]
        out.append((impact, before, after))
    return out


@pytest.mark.parametrize("durations", [10.0, 1000.0])
def test_a_ball_thrown_in_3d_rebounds_with_the_laws_restitution_along_its_normal(durations):
    # no gravity: the ball flies off-centre across the socket in 3D and hits its wall at normals
    # off the coordinate planes; each impact step's jump is along one normal n (the difference
    # of the velocities), holds the end rate -e(v) v (e the law's restitution at the onset
    # velocity v, to Newton's tolerance on the velocity condition) and keeps the tangential
    # velocity (frictionless).  At 1000 contact durations the steps are longer than the flight
    # across the clearance: the mode has Exudyn shorten those (as for the journal)
    c = SOCKET - BALL
    speed = 0.3
    direction = np.array([0.48, 0.6, 0.64])  # unit, off every coordinate plane
    mbs, joint, node = ball_in_socket([0.5 * c, -0.3 * c, 0.2 * c], speed * direction)
    law = joint.joint.law
    step = durations * closed_form_impact(law, BALL_MASS, speed)[1]
    states = []
    recorder(mbs, node, states)
    assert solve(mbs, step, max(30 * 2 * c / speed, 4 * step))
    records = jumps(joint, np.array(states), speed * direction)
    assert len(records) >= 8
    tilted = 0
    for impact, before, after in records:
        n = (before - after) / np.linalg.norm(before - after)
        assert impact.onset_velocity == pytest.approx(n @ before, rel=1e-9)
        assert impact.restitution == impact_restitution(law, impact.onset_velocity)
        assert -(n @ after) / (n @ before) == pytest.approx(impact.restitution, rel=1e-9)
        tilted += bool(np.abs(n).min() > 0.1)
    assert tilted >= len(records) // 2  # the normals lie off the coordinate planes


def test_a_ball_dropped_in_its_socket_rebounds_with_the_laws_restitution_then_rests():
    # gravity -y; the ball falls from the socket's centre onto its wall at sqrt(2 g c) and
    # bounces at the law's restitution (each jump to Newton's tolerance, along -y) until the
    # rebound would land within two steps: then it rests, held by the condition, with the
    # ideal joint's reaction m g
    c = SOCKET - BALL
    mbs, joint, node = ball_in_socket([0, 0, 0], [0, 0, 0], gravity=G)
    law = joint.joint.law
    step = 10.0 * closed_form_impact(law, BALL_MASS, math.sqrt(2 * G * c))[1]
    states = []
    recorder(mbs, node, states)
    assert solve(mbs, step, 0.3)
    records = jumps(joint, np.array(states), np.zeros(3))
    bounces = [r for r in records if r[0].restitution > 0.0]
    assert len(bounces) >= 10
    # Moreau-Jean's impact velocity is the rate at the start of the step in which the ball
    # reached the wall: the fall's sqrt(2 g c) less up to a step's g h
    assert math.sqrt(2 * G * c) - G * step <= records[0][0].onset_velocity <= math.sqrt(2 * G * c)
    for impact, before, after in bounces:
        assert after[1] / -before[1] == pytest.approx(impact_restitution(law, impact.onset_velocity), rel=1e-9)
    assert records[-1][0].restitution == 0.0  # the last is the rest's onset
    out = joint.outputs()
    rest = out["time"] > records[-1][0].onset_time + 100 * step
    assert rest.sum() > 100
    # the condition holds the ideal joint's reaction once it has taken back the onset's
    # penetration (RATE_GAIN: a factor 0.5 a step, 1e-30 of it after 100 steps)
    assert np.allclose(out["normal_force"][rest], BALL_MASS * G, rtol=1e-9)
    assert np.allclose(out["ecc_y"][rest], -c, rtol=1e-12)
    assert np.abs(out["ecc_x"][rest]).max() < 1e-15 and np.abs(out["ecc_z"][rest]).max() < 1e-15


def test_an_elastic_ball_keeps_its_energy():
    # cr = 1: no damping, restitution 1; the ball falls off-centre from the socket's centre
    # with a sideways velocity and bounces around the socket's bottom
    c = SOCKET - BALL
    mbs, joint, node = ball_in_socket([0, 0, 0], [0.01, 0, 0.005], gravity=G, cr=1.0)
    states = []
    recorder(mbs, node, states)
    assert solve(mbs, 1e-5, 0.1)
    assert len(joint.impacts()) >= 10
    states = np.array(states)
    energy = 0.5 * (states[:, 4:7] ** 2).sum(axis=1) + G * states[:, 2]  # per kg
    assert np.abs(energy - 0.5 * (0.01**2 + 0.005**2)).max() <= 0.01 * G * c  # the target: within 1 %


def test_a_resting_ball_has_one_impact_and_the_ideal_joints_reaction():
    # gravity -y presses the ball, touching at t = 0, on the socket's bottom
    c = SOCKET - BALL
    mbs, joint, _ = ball_in_socket([0, -c, 0], [0, 0, 0], gravity=G)
    assert solve(mbs, 1e-4, 0.05)
    assert len(joint.impacts()) == 1  # the onset of the rest, nothing after it
    out = joint.outputs()
    held = out["time"] > 100 * 1e-4
    # as the journal's (tests/test_impulse_mode.py): m g to round-off once the condition has
    # taken back the first steps' penetration
    assert np.allclose(out["normal_force"][held], BALL_MASS * G, rtol=1e-9)
    assert np.abs(out["penetration"]).max() < 2.0 * G * 1e-4**2  # Moreau-Jean's: below 2 g h^2
