"""The impulse mode's settling of the trapezoidal rule's step-to-step alternation
(exuclear.engine.settling): a held contact and the model's own joints carry their static
reactions, step after step, checked against the statics of a bar on two supports; a
system with a stiff spring is left as the trapezoidal rule has it."""
import warnings

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    Force,
    MarkerBodyPosition,
    MarkerNodePosition,
    NodeRigidBody2D,
    ObjectConnectorSpringDamper,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
    SensorNode,
    SensorObject,
)

import exuclear
from exuclear.engine.impulse import ImpulseJointHandle

G = 9.81
MASS = 1.0  # kg, the bar
LENGTH = 0.2  # m, pivot to journal
CLEARANCE = 1e-4  # m
STEP = 1e-4  # s
END_TIME = 0.05  # s
KICK_TIME = 0.03  # s, more than 64 steps after the rest's onset (the held steps' settling)


def bar_on_two_supports(kick: float = 0.0):
    """A uniform bar along x from an ideal pin at the origin to a journal at x = LENGTH, in a
    ground bearing centred there; gravity -y; the journal starts at the bearing's centre
    and falls onto its bottom wall, where the mode holds it.  With ``kick`` [m/s], the
    step that starts at KICK_TIME starts with the bar turning about the pin so that the
    journal moves down into its wall at that rate.  Returns the system, the clearance joint
    and the pin's force sensor."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[LENGTH / 2, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=MASS * LENGTH**2 / 12))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[0, -MASS * G, 0]))
    pin = mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0, 0, 0])),
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[-LENGTH / 2, 0, 0]))]))
    sensor = mbs.AddSensor(SensorObject(objectNumber=pin, storeInternal=True, outputVariableType=exu.OutputVariableType.Force))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the clearance ratio's note: chosen here
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[LENGTH, 0, 0],
                                              bearing_radius=10e-3, journal_radius=10e-3 - CLEARANCE, length=10e-3,
                                              cr=0.1, contact_mode="impulse")
    assert isinstance(joint, ImpulseJointHandle)
    if kick:
        def turn(mbs, t):
            if abs(t - KICK_TIME) < 0.5 * STEP:
                omega = -kick / LENGTH  # the journal at x = LENGTH moves at omega LENGTH along y
                for configuration in (exu.ConfigurationType.Current, exu.ConfigurationType.StartOfStep):
                    mbs.systemData.SetODE2Coordinates_t([0.0, omega * LENGTH / 2, omega], configuration)
            return True
        mbs.SetPreStepUserFunction(turn)
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = END_TIME
    ss.timeIntegration.numberOfSteps = int(round(END_TIME / STEP))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.verboseMode = 0
    ss.solution.sensors.writePeriod = STEP
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joint's notes are not what this test checks
        assert mbs.SolveDynamic(ss)
    return mbs, joint, sensor


def test_a_held_contact_and_an_ideal_pin_carry_half_the_bar_each_step_after_step():
    # statics of a uniform bar on two supports at its ends: each carries m g / 2.  The bar
    # droops by c / L = 5e-4 rad and the contact's normal tilts by half that: the lever arms
    # change at second order, (5e-4)^2, so m g / 2 holds to 1e-6
    mbs, joint, sensor = bar_on_two_supports()
    impacts = joint.impacts()
    # the journal bounces (cr 0.1) and comes to rest: the last onset is the rest's, no chatter after it
    rest = impacts[-1].onset_time
    assert impacts[-1].restitution == 0.0 and all(i.restitution > 0.0 for i in impacts[:-1])
    pin = np.asarray(mbs.GetSensorStoredData(sensor))
    settled = pin[:, 0] > rest + 40 * STEP  # the settling halves what the onset left each step (n 2^-n)
    assert settled.sum() > 300
    # the pin's force as Exudyn reports it, on its first marker's side (the ground's): -m g / 2 along y
    np.testing.assert_allclose(pin[settled, 2], -MASS * G / 2, rtol=1e-6)
    # the trapezoidal rule would keep the onset's error in the accelerations alternating from
    # step to step in every multiplier (here the pin's force between 0 and m g, to the end);
    # settled, the pin's force changes from step to step by Newton's tolerance on the step's
    # residual (1e-8 relative, Exudyn's default) times the load
    assert np.abs(np.diff(pin[settled, 2])).max() < 1e-7 * MASS * G
    out = joint.outputs()
    held = out["time"] > rest + 40 * STEP
    np.testing.assert_allclose(out["normal_force"][held], MASS * G / 2, rtol=1e-6)


def test_a_normal_rate_the_held_state_carries_is_taken_out_in_one_step_and_the_reaction_returns():
    # the bar at rest on the held journal, its step at KICK_TIME started turning the journal
    # into its wall at 1e-4 m/s: the hold takes the rate out within the step (its multiplier
    # jumps by about 2 (m / 3) rate / h, the bar's mass at the journal being m / 3).  Under
    # the trapezoidal rule a position-level constraint ends each step at minus the normal
    # rate it started with, so a distance set from the rate the hold planned would keep that
    # rate alternating from step to step, and with it the multiplier by about
    # 4 (m / 3) rate / h = 1.3 N about m g / 2 (the settling takes 1.8 % of it a step: more
    # than half is left 40 steps on).  Set from the rate measured, the end rate is the one
    # aimed at from the step after the kick on, and the multipliers' alternation halves a
    # step (exuclear.engine.settling): the pin and the contact carry m g / 2 again, to the
    # test's tolerance above (a 1e-6 share of m g / 2 from the lever arms) and the
    # alternation's n 2^-n after 40 steps (below 1e-10 of the jump's)
    mbs, joint, sensor = bar_on_two_supports(kick=1e-4)
    assert joint.impacts()[-1].onset_time < KICK_TIME - 64 * STEP
    pin = np.asarray(mbs.GetSensorStoredData(sensor))
    after = pin[:, 0] > KICK_TIME + 40 * STEP
    assert after.sum() > 150
    np.testing.assert_allclose(pin[after, 2], -MASS * G / 2, rtol=1e-6)
    out = joint.outputs()
    held = out["time"] > KICK_TIME + 40 * STEP
    np.testing.assert_allclose(out["normal_force"][held], MASS * G / 2, rtol=1e-6)
    # the kick reached the contact: its multiplier jumped at the kick's step
    kicked = (out["time"] > KICK_TIME) & (out["time"] < KICK_TIME + 1.5 * STEP)
    assert out["normal_force"][kicked].max() > MASS * G / 2 + 0.1


def test_a_system_with_a_stiff_spring_is_not_settled_and_its_journal_stays_off_the_wall():
    # a bar on an ideal pin at the origin held level by a spring of 1e9 N/m at its middle,
    # its journal centred in the clearance: the spring carries m g at a deflection m g / k
    # (moments about the pin), and released undeflected and at rest the middle swings
    # between 0 and 2 m g / k (the trapezoidal rule keeps a linear oscillator's energy),
    # 2e-8 m against a clearance of 1e-4 m: the journal never reaches its wall.  The
    # spring's mode (omega^2 = k (L/2)^2 / (m L^2 / 3), omega h = 2.7) alternates from
    # step to step of itself, which the settling would damp as an error: settled, this
    # journal chattered on its wall (45 impacts); the system has a force element, so it is
    # not settled (exuclear.engine.settling)
    stiffness = 1e9
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[LENGTH / 2, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=MASS * LENGTH**2 / 12))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[0, -MASS * G, 0]))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0, 0, 0])),
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[-LENGTH / 2, 0, 0]))]))
    mbs.AddObject(ObjectConnectorSpringDamper(markerNumbers=[
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[LENGTH / 2, -0.05, 0])),
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[0, 0, 0]))],
        stiffness=stiffness, damping=0.0, referenceLength=0.05))
    middle = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Position))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the clearance ratio's note: chosen here
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[LENGTH, 0, 0],
                                              bearing_radius=10e-3, journal_radius=10e-3 - CLEARANCE, length=10e-3,
                                              cr=0.5, contact_mode="impulse")
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 0.2
    ss.timeIntegration.numberOfSteps = int(round(0.2 / STEP))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.verboseMode = 0
    ss.solution.sensors.writePeriod = STEP
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert mbs.SolveDynamic(ss)
    assert joint.impacts() == []
    y = np.asarray(mbs.GetSensorStoredData(middle))[:, 2]
    # the swing's bound, to the round-off of the trapezoidal rule's energy
    assert y.min() >= -2.0 * MASS * G / stiffness * (1.0 + 1e-6)
    assert y.max() <= 1e-15
