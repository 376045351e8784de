"""Coulomb friction in the impulse contact mode (exuclear.engine.impulse_friction): sliding
at mu F_N against the slip, sticking within the friction cone, and Brach's impact law, each
against Newton's laws for a disc-shaped journal on its bearing's wall."""
import math
import re
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    CoordinateConstraint,
    Force,
    MarkerNodeCoordinate,
    MarkerNodePosition,
    NodePointGround,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
)

import exuclear
from exuclear.engine.impulse import RATE_GAIN, ImpulseJointHandle
from exuclear.engine.impulse_friction import LOAD_TOLERANCE
from validation.cost.modes_friction import bar_energy, swinging_bar

G = 9.81
MU = 0.3
#: The journal: 40 g, a solid disc (I = m R^2 / 2) of radius 9 mm in a 10 mm bearing held by
#: the ground; a 1 mm clearance keeps the wall's curvature out of the short runs below
#: (the journal's travel along it stays below 2e-3 clearances).
MASS, BEARING, CLEARANCE = 0.04, 10e-3, 1e-3
RADIUS = BEARING - CLEARANCE
INERTIA = 0.5 * MASS * RADIUS**2


def journal(*, y=-CLEARANCE, velocity=(0.0, 0.0), spin=0.0, gravity=(0.0, -G), cr=0.9, hold_spin=False,
            mass=MASS, inertia=INERTIA, offset=(0.0, 0.0), mu=MU):
    """A journal at (0, y) in a ground bearing centred at the origin (touching its bottom
    wall at the default y), Coulomb friction ``mu``; ``hold_spin``: its rotation held by a
    coordinate constraint; its body's centre of mass ``offset`` from the journal's centre
    (the velocities are the centre of mass's).  Returns (mbs, node, joint, energy records)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[*offset, 0], initialCoordinates=[0, y, 0],
                                       initialVelocities=[velocity[0], velocity[1], spin]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=inertia))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
                      loadVector=[mass * gravity[0], mass * gravity[1], 0]))
    if hold_spin:
        fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[fixed, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node,
                                                                                                       coordinate=2))]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a 10 % clearance ratio warns: chosen here (module constants)
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0],
                                              bearing_radius=BEARING, journal_radius=RADIUS, length=10e-3, cr=cr,
                                              friction=f"coulomb:{mu}", contact_mode="impulse")
    assert isinstance(joint, ImpulseJointHandle)
    mbs.Assemble()
    energy = []

    def record(mbs, t):
        p = mbs.GetNodeOutput(node, exu.OutputVariableType.Position)
        v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
        w = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]
        energy.append(0.5 * mass * (v[0]**2 + v[1]**2) + 0.5 * inertia * w * w
                      - mass * (gravity[0] * p[0] + gravity[1] * p[1]))
        return True

    mbs.SetPostStepUserFunction(record)
    return mbs, node, joint, energy


def solve(mbs, step, end_time):
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = int(round(end_time / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.verboseMode = 0
    assert mbs.SolveDynamic(ss)


def velocities(mbs, node):
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
    return v[0], v[1], mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]


def test_a_spinning_journal_slides_at_coulombs_deceleration_then_rolls():
    # Newton's laws for a disc on a wall with friction mu m g at the contact (the sliding-to-
    # rolling transition of a disc or ball, e.g. Meriam and Kraige, Engineering Mechanics:
    # Dynamics, the bowling-ball problem): at the bottom n = (0, -1), t = (-1, 0), and the
    # slip eq. (8) is v_T = -v_x - R w.  Sliding with v_T > 0 the journal gets F = mu m g along
    # +x and the moment R mu m g, so m dv_x/dt = mu m g, I dw/dt = R mu m g and
    # dv_T/dt = -mu g (1 + m R^2 / I) = -3 mu g until v_T = 0 at t_s = v_T0 / (3 mu g);
    # then it rolls (v_T = 0) at v_x = v_T0 / 3, w = -v_x / R, as long as the friction it
    # needs stays within the cone (here 0: the wall is flat to 2e-3 clearances)
    slip0 = 0.01  # m/s, a spin of -slip0 / R at rest on the wall
    mbs, node, joint, _ = journal(spin=-slip0 / RADIUS)
    step = 1e-5
    t_stick = slip0 / (3.0 * MU * G)  # 1.13 ms
    solve(mbs, step, 1.5 * t_stick)
    assert len(joint.impacts()) == 1  # the onset of the rest
    out = joint.outputs()
    t, slip = out["time"], out["slip_velocity"]
    sliding = out["sticking"] == 0.0
    # the slide: the slip falls at 3 mu g.  Bound 1 %: the normal force differs from m g by
    # the centripetal m v_x^2 / c (below 1e-3 m g here) and the tilt of the wall the journal
    # moved along (below 2e-3 rad); the trapezoidal rule integrates a constant force exactly
    rate = -np.polyfit(t[sliding & (t > 5 * step)], slip[sliding & (t > 5 * step)], 1)[0]
    assert rate == pytest.approx(3.0 * MU * G, rel=0.01)
    # mu F_N, to the mode's tolerance on the sliding load
    assert np.all(np.abs(out["friction_force"][sliding][2:] / (MU * out["normal_force"][sliding][2:]) - 1.0)
                  <= LOAD_TOLERANCE)
    # the change to rolling within a step of t_s, and sticking from there on
    first = t[~sliding][0]
    assert abs(first - t_stick) <= step
    assert np.all(~sliding[t > first])
    assert np.abs(slip[t > first]).max() < 1e-12  # Newton's tolerance on the held slip
    vx, _, w = velocities(mbs, node)
    # bound 1 %: as the slide's rate; the rolling journal then climbs the wall's curvature
    # (2e-3 rad by the run's end), which slows it by about 0.3 %
    assert vx == pytest.approx(slip0 / 3.0, rel=0.01)
    # rolling, v_T = 0 along the wall's tangent there, turned from the bottom's by the
    # journal's travel (below 2e-3 rad)
    assert w == pytest.approx(-vx / RADIUS, rel=2e-3)


def test_a_spinning_bearing_drags_its_journal_with_its_own_spin_in_the_slip():
    # the bearing, a disc of inertia I_B held at the origin, spins at W; the journal rests at
    # its bottom.  The slip eq. (8) is v_T = -v_x - R_J w + R_B W, R_B W at the start; the
    # friction F_T = mu m g (v_T > 0) gives the journal the force F_T along +x and the moment
    # R_J F_T, the bearing the moment -R_B F_T (eq. (26)), so that
    # dv_T/dt = -F_T (1/m + R_J^2/I + R_B^2/I_B) until the journal rolls on the bearing, and
    # the two spins' changes keep I_B dW / R_B = -I dw / R_J (Newton's third law at the contact)
    spin, bearing_inertia = 1.0, 1e-3
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddNode(NodePointGround())
    hub = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0, 0, spin]))
    bearing = mbs.AddObject(ObjectRigidBody2D(nodeNumber=hub, mass=1.0, inertia=bearing_inertia))
    for k in (0, 1):  # the bearing's centre held, its rotation free
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground,
                                                                                             coordinate=0)),
                                                          mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub,
                                                                                             coordinate=k))]))
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, -CLEARANCE, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=INERTIA))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[0, -MASS * G, 0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a 10 % clearance ratio warns: chosen here (module constants)
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[bearing, body], position=[0, 0, 0],
                                              bearing_radius=BEARING, journal_radius=RADIUS, length=10e-3, cr=0.9,
                                              friction=f"coulomb:{MU}", contact_mode="impulse")
    mbs.Assemble()
    step = 1e-5
    rate = MU * G * MASS * (1.0 / MASS + RADIUS**2 / INERTIA + BEARING**2 / bearing_inertia)
    solve(mbs, step, 1e-3)  # sliding throughout: t_s = R_B W / rate = 1.13 ms
    out = joint.outputs()
    sliding = (out["sticking"] == 0.0) & (out["time"] > 5 * step)
    assert sliding.sum() > 90
    # R_B W less the first step's slide (the onset step slides already), that slide's rate
    # within 1 % as below
    assert abs(out["slip_velocity"][0] - (BEARING * spin - rate * step)) <= 0.01 * rate * step
    # bound 1 %, as for the spinning journal (the wall's tilt and the centripetal force)
    slope = -np.polyfit(out["time"][sliding], out["slip_velocity"][sliding], 1)[0]
    assert slope == pytest.approx(rate, rel=0.01)
    w_journal = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]
    w_bearing = mbs.GetNodeOutput(hub, exu.OutputVariableType.AngularVelocity)[2]
    # the moments of eqs. (25)-(26) to Newton's tolerance on the multipliers
    assert bearing_inertia * (w_bearing - spin) / BEARING == pytest.approx(-INERTIA * w_journal / RADIUS, rel=1e-6)


@pytest.mark.parametrize("tilt_deg", [10.0, 30.0])
def test_a_journal_on_a_tilted_wall_sticks_below_the_friction_angle_and_slides_above(tilt_deg):
    # gravity tilted by the angle a from the wall's normal, the journal's rotation held: a
    # block on an incline (Newton's laws): it stays where tan a <= mu (the friction angle is
    # atan 0.3 = 16.7 degrees) with the friction force m g sin a, within mu m g cos a; above,
    # it slides at g (sin a - mu cos a)
    a = math.radians(tilt_deg)
    mbs, node, joint, _ = journal(gravity=(G * math.sin(a), -G * math.cos(a)), hold_spin=True)
    end = 1e-3
    solve(mbs, 1e-5, end)
    assert len(joint.impacts()) == 1
    out = joint.outputs()
    held = out["time"] > 2e-5  # after the onset step
    vx, vy, _ = velocities(mbs, node)
    if math.tan(a) <= MU:
        assert np.all(out["sticking"][held] == 1.0)
        # at rest to round-off: the held condition's end rate takes back RATE_GAIN of the gap a
        # step, and the gap |e| - c is known to the round-off of |e| (an ulp of the clearance)
        assert math.hypot(vx, vy) <= RATE_GAIN * 2.0 * np.spacing(CLEARANCE) / 1e-5
        # the friction and normal forces: the load's components to round-off of the multipliers,
        # once the settling took out what the onset left (it halves that each step, n 2^-n:
        # below 1e-9 after 40 steps; exuclear.engine.settling)
        settled = out["time"] > 41 * 1e-5
        assert np.allclose(out["friction_force"][settled], -MASS * G * math.sin(a), rtol=1e-9)
        assert np.allclose(out["normal_force"][settled], MASS * G * math.cos(a), rtol=1e-9)
    else:
        assert np.all(out["sticking"] == 0.0)
        # bound 0.5 %: the journal slides 1.2e-6 m along the curved wall (its tilt turns by
        # 1.2e-3 rad, and the tangential load by g (cos a + mu sin a) times that, 0.25 % of the
        # slide's acceleration on average over the run)
        assert vx == pytest.approx(G * (math.sin(a) - MU * math.cos(a)) * end, rel=0.005)
        # mu F_N, to the mode's tolerance on the sliding load
        assert np.allclose(out["friction_force"][held] / out["normal_force"][held], -MU, rtol=LOAD_TOLERANCE, atol=0)


@pytest.mark.parametrize("tangential", [1.0, 0.2])
def test_an_oblique_impact_follows_brachs_law(tangential):
    # Newton's restitution with Coulomb's bound on the tangential impulse (R. M. Brach, J.
    # Appl. Mech. 56 (1989) 133-138): the normal impulse is P_n = m (1 + e) v_n; the slip
    # v_T = -v_x - R w (at the bottom wall) is stopped where that needs a tangential impulse
    # P = v_T / (1/m + R^2/I) within mu P_n, else the journal slides through the impact with
    # the tangential impulse mu P_n: dv_x = mu P_n / m against the slip, dw = R mu P_n / I.
    # No gravity; the journal starts 1e-8 m off the wall, moving at (tangential, -0.3) m/s
    v_n = 0.3
    mbs, node, joint, _ = journal(y=-CLEARANCE + 1e-8, velocity=(tangential, -v_n), gravity=(0.0, 0.0))
    solve(mbs, 1e-7, 1e-5)
    impacts = joint.impacts()
    assert len(impacts) == 1
    e = impacts[0].restitution
    vx, vy, w = velocities(mbs, node)
    p_n = MASS * (1.0 + e) * v_n
    needed = tangential / (1.0 / MASS + RADIUS**2 / INERTIA)  # the impulse that stops the slip
    # bound 0.2 %: the impact step's normal is where the step met the wall, turned from the
    # bottom's by the journal's travel until then (1.3e-4 rad at 1 m/s), which turns a share
    # of the normal impulse, 4.5e-4 of the friction impulse, into the tangent; the flight
    # after the impact stays clear of the wall
    if needed > MU * p_n:  # slides through
        assert vx == pytest.approx(tangential - MU * p_n / MASS, rel=2e-3)
        assert w == pytest.approx(-RADIUS * MU * p_n / INERTIA, rel=2e-3)
    else:  # sticks: the slip is stopped
        assert vx == pytest.approx(tangential - needed / MASS, rel=2e-3)
        assert w == pytest.approx(-vx / RADIUS, rel=2e-3)
    assert vy == pytest.approx(e * v_n, rel=2e-3)  # the normal jump keeps the law's restitution


def test_friction_never_adds_energy():
    # an elastic journal (cr 1) thrown spinning into its bearing under gravity bounces,
    # slides and sticks: friction only dissipates (eq. (27)), so its energy never grows;
    # the bound is round-off of the energy (1e-12 of it, about 1e-15 J)
    mbs, node, joint, energy = journal(y=0.0, velocity=(0.2, 0.1), spin=100.0, cr=1.0)
    solve(mbs, 1e-5, 0.05)
    assert len(joint.impacts()) >= 3
    out = joint.outputs()
    assert out["sticking"].any() and (np.abs(out["slip_velocity"]) > 1e-3).any()  # it stuck and it slid
    energy = np.array(energy)
    assert np.diff(energy).max() <= 1e-12 * energy[0]
    assert energy[-1] < 0.9 * energy[0]  # and it does dissipate
    # the disc's contact point lies on the normal through its centre of mass: no coupling
    assert not any("Kane and Levinson" in note for note in joint.notes)


def test_a_frictionless_joint_has_no_friction_items_or_outputs():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=mbs.AddNode(NodeRigidBody2D()), mass=1.0, inertia=1.0))
    loads = mbs.systemData.NumberOfLoads()
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], bearing_radius=10e-3,
                                          journal_radius=9.9e-3, length=10e-3, cr=0.9, contact_mode="impulse")
    assert mbs.systemData.NumberOfLoads() == loads
    mbs.Assemble()
    solve(mbs, 1e-4, 1e-3)
    assert "friction_force" not in joint.outputs()


def test_a_swinging_bar_loses_the_friction_work_at_its_pin():
    # a 1 m bar of 1 kg on a 50 um pin with friction, released horizontal: the held journal
    # slides and sticks along its wall while the bar swings.  The joint's power is minus the
    # contact's (eq. (27)), so the bar's energy falls by the friction work, the integral of
    # F_T v_T, and never grows.  Bounds: the friction work summed over the steps from the
    # steps' mean friction force and end slip, first order in the step (measured 0.25 %
    # off), within 1 %; a step's energy increase within 1e-8 J, the trapezoidal rule's own
    # energy error on the bar (the frictionless run's steps: up to 5e-7 J while impacts last,
    # the held sliding contact's 3e-9 J)
    mbs, node, joint = swinging_bar(f"coulomb:{MU}", "impulse")
    energy = []

    def record(mbs, t):
        energy.append((t, bar_energy(mbs, node)))
        return True

    mbs.SetPostStepUserFunction(record)
    step = 1e-4
    solve(mbs, step, 1.0)  # the bar swings back: its journal sticks at the turn
    out = joint.outputs()
    rest = out["time"] >= 0.1  # the impacts of the journal's fall are over (onsets below 0.1 s)
    assert max(i.onset_time for i in joint.impacts()) < 0.1
    assert out["sticking"][rest].any() and (out["sticking"][rest] == 0.0).any()
    work = np.sum((out["friction_force"] * out["slip_velocity"] * step)[rest][1:])
    energy = np.array(energy)
    energy = energy[energy[:, 0] >= 0.1, 1]
    lost = energy[0] - energy[-1]
    assert lost > 0.05  # J: the friction takes a share of the swing's m g L / 2 = 4.9 J
    assert lost == pytest.approx(work, rel=0.01)
    assert np.diff(energy).max() < 1e-8


def test_an_impact_that_adds_energy_is_told():
    # Kane and Levinson's paradox: a 0.5 kg rod of 0.2 m (I = m l^2 / 12) carries the journal
    # 0.1 m off its centre of mass, at 45 degrees up the rod; with cr 1 and friction it hits
    # the bottom wall moving at (0.1, -0.3) m/s without spin, elastic (e = 1 at any velocity).
    # At the contact point P (the journal's centre plus R n) the inverse mass in (n, t),
    # t = n x z, is W = I/m + k k^T / I_z with k = z x (P - centre of mass): its coupling
    # W_nt moves the slip under the normal impulse.  Brach's law: the stop u+ = (-e u_n, 0)
    # needs p = W^-1 (-(1 + e) u_n, -u_t); along the slip (p_t u_t > 0) and within mu |p_n|,
    # the contact sticks and the impulses' work p . (u- + u+) / 2 is a gain.  No gravity;
    # the journal starts 1e-8 m off the wall
    mass, length, arm, angle, mu = 0.5, 0.2, 0.1, math.radians(45.0), 0.6
    inertia = mass * length**2 / 12
    offset = arm * np.array([math.cos(angle), math.sin(angle)])  # centre of mass from the journal's centre
    velocity = np.array([0.1, -0.3])
    mbs, node, joint, energy = journal(y=-CLEARANCE + 1e-8, velocity=velocity, gravity=(0.0, 0.0), cr=1.0, mass=mass,
                                       inertia=inertia, offset=offset, mu=mu)
    solve(mbs, 1e-7, 1e-5)
    [impact] = joint.impacts()
    e = impact.restitution
    assert e == pytest.approx(1.0, abs=1e-12)
    n, t = np.array([0.0, -1.0]), np.array([-1.0, 0.0])
    r = RADIUS * n - offset  # the contact point from the centre of mass
    k = np.array([-r[1], r[0]])
    basis = np.array([n, t])
    w = np.eye(2) / mass + np.outer(basis @ k, basis @ k) / inertia
    u = basis @ velocity  # (u_n, u_t) before: the body does not spin
    p = np.linalg.solve(w, [-(1.0 + e) * u[0], -u[1]])
    assert p[0] < 0.0 and p[1] * u[1] > 0.0 and abs(p[1]) <= mu * abs(p[0])  # a stop along the slip, in the cone
    gain = 0.5 * (p[0] * (1.0 - e) * u[0] + p[1] * u[1])
    [note] = [note for note in joint.notes if "Kane and Levinson" in note]
    assert note.startswith("1 impacts added energy") and "contact_mode='compliant'" in note
    told = float(re.search(r"up to (\S+) J", note).group(1))
    # bounds: the note's 3 digits; the body's own energy gain, measured 2e-5 off the closed
    # form (the impact's normal is where the step met the wall, turned by the journal's travel)
    assert told == pytest.approx(gain, rel=5e-3)
    assert energy[-1] - 0.5 * mass * velocity @ velocity == pytest.approx(gain, rel=1e-3)
