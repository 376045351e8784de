"""Coulomb friction in the impulse contact mode on the joint types whose contact slides along
one tangent (exuclear.engine.impulse_friction): a planar slider's corners, a pin in its slot,
the spatial revolute joint's slices; each against Newton's laws (sliding at mu F_N against the
slip, sticking within the friction cone, Brach's impact law), on the scenes of
validation/cost/_friction_scenes.py; and an impact whose friction adds energy (Kane and
Levinson's paradox) on a tilted bar in its guide."""
import math
import re

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine.impulse_friction import LOAD_TOLERANCE
from exuclear.engine.impulse_guide import ImpulseGuideHandle
from exuclear.timescales import impact_restitution
from validation.cost import _friction_scenes as scenes
from validation.cost import _joint_type_scenes as pins
from validation.cost._translational_scenes import CLEARANCE, LAW, MASS, SIDE

G, MU = scenes.G, scenes.MU


def test_a_slider_flat_on_its_wall_slides_at_mu_g_then_sticks():
    # a rigid block sliding on a flat wall: m dv/dt = -mu m g until it stops at t_s = v0 / (mu g),
    # x(t) = v0 t - mu g t^2 / 2, then it stays.  Its two lower corners carry the weight, and the
    # friction mu N at the wall, H/2 below the centre, tilts the split: the moment balance about
    # the centre gives N_front - N_rear = mu m g H / L; at rest each carries m g / 2
    v0, step = 0.05, 1e-4
    t_stop = v0 / (MU * G)  # 25.5 ms, inside a step
    joint, states, _ = scenes.sliding_slider(v0, step)
    t, x, y, angle = states[:, 0], states[:, 1], states[:, 2], states[:, 3]
    reference = np.where(t < t_stop, v0 * t - 0.5 * MU * G * t**2, 0.5 * v0 * t_stop)
    # bound mu g h^2 (2e-9 m, 2e-5 clearances): the trapezoidal rule integrates the constant
    # friction exactly; the stop falls within one step, which slides and sticks as a whole
    assert np.abs(x - reference).max() <= MU * G * step**2
    assert np.abs(y + CLEARANCE).max() < 1e-12 and np.abs(angle).max() < 1e-12  # flat on the wall, held
    rear, front = scenes.lower_corners(joint)
    sliding = (rear["time"] > 3 * step) & (rear["time"] < t_stop - 3 * step)  # the three-step means settled
    for corner in (rear, front):
        # each corner's friction is mu times its own normal force (signed along t = n x z, the
            # guide's -x on the lower wall), to the mode's load tolerance
        assert np.all(np.abs(np.abs(corner["friction_force"][sliding]) / (MU * corner["normal_force"][sliding]) - 1.0)
                      <= LOAD_TOLERANCE)
    # bound: the load tolerance on each corner's friction, whose moment sets the split
    split = front["normal_force"][sliding] - rear["normal_force"][sliding]
    assert np.abs(split / (MU * MASS * G * SIDE / SIDE) - 1.0).max() <= 2 * LOAD_TOLERANCE  # H = L = SIDE
    stuck = rear["time"] > t_stop + step
    for corner in (rear, front):
        assert np.all(corner["sticking"][stuck] == 1.0)
        assert np.abs(corner["slip_velocity"][stuck]).max() < 1e-12  # Newton's tolerance on the held slip
        assert np.abs(corner["friction_force"][stuck][3:]).max() < 1e-9 * MASS * G  # no load along the wall
        # bound 1e-12: Newton's tolerance on the held conditions
        assert corner["normal_force"][-1] == pytest.approx(0.5 * MASS * G, rel=1e-12)
    assert len(joint.impacts()) == 2  # the two corners' rest onsets, nothing after


@pytest.mark.parametrize("tilt", [0.5, 2.0])
def test_a_slider_on_a_tilted_guide_sticks_below_the_friction_angle_and_slides_above(tilt):
    # a block at rest on a slope of angle a: it stays while tan a <= mu_s (Coulomb's law of
    # static friction, the friction m g sin a within mu m g cos a), else it slides down at
    # g (sin a - mu cos a).  ``tilt``: tan a over mu
    slope = math.atan(tilt * MU)
    joint, states, step = scenes.tilted_slider(tilt)
    t, x = states[:, 0], states[:, 1]
    end = t[-1]
    rear, front = scenes.lower_corners(joint)
    assert not joint.notes  # Coulomb's law met in every step
    if tilt < 1.0:
        assert np.abs(x).max() < 1e-12  # it does not move (Newton's tolerance on the held slip)
        assert np.all(rear["sticking"][1:] == 1.0) and np.all(front["sticking"][1:] == 1.0)
        # the two corners hold the slope's pull, m g sin a (bound: Newton's tolerance)
        held = rear["friction_force"][-1] + front["friction_force"][-1]
        assert abs(held) == pytest.approx(MASS * G * math.sin(slope), rel=1e-9)
    else:
        a = G * (math.sin(slope) - MU * math.cos(slope))
        # bound 1e-9 of the travel: the trapezoidal rule integrates the constant acceleration
        # exactly (the first step, which starts sticking, slides within its computations)
        assert np.abs(x + 0.5 * a * t**2).max() <= 1e-9 * 0.5 * a * end**2
        after = rear["time"] > 3 * step
        assert np.all(rear["sticking"][after] == 0.0) and np.all(front["sticking"][after] == 0.0)


@pytest.mark.parametrize("tangential", [0.05, 0.005])
def test_a_slider_thrown_flat_at_its_wall_follows_brachs_law(tangential):
    # both lower corners hit in one step (no gravity, the slider flat): the normal impulse is
    # P_n = m (1 + e) v_n, the rebound e v_n, and the corners' friction impulses mu times
    # their normal ones while the slider slides through (dv_x = -mu (1 + e) v_n), else what
    # stops the slip (v_x = 0); the corners' conditions keep it flat (no turn), the moment of
    # the friction impulse taken by the split of the normal ones
    v_n = 0.05
    joint, states, _ = scenes.thrown_slider(tangential, v_n)
    impacts = joint.impacts()
    assert len(impacts) == 2 and impacts[0].onset_time == impacts[1].onset_time
    e = impact_restitution(joint.joint.law, v_n)
    vx, vy, w = states[-1, 4:7]
    # bound 1e-9: the jump is the step's end velocities, to Newton's tolerance
    assert vy == pytest.approx(e * v_n, rel=1e-9)
    assert abs(w) < 1e-9 * v_n / SIDE
    slide = MU * (1.0 + e) * v_n
    expected = tangential - slide if slide < tangential else 0.0
    assert vx == pytest.approx(expected, abs=1e-9 * v_n)


def test_a_pin_on_its_slots_flat_side_slides_at_mu_g_then_rolls():
    # a solid disc (I = m R^2 / 2) sliding without spin on a flat wall: dv/dt = -mu g,
    # R dw/dt = -2 mu g (its spin at its radius turns it towards rolling), the slip falls at
    # 3 mu g until it rolls at t_s = v0 / (3 mu g) with v = 2 v0 / 3 (its angular momentum
    # about the contact point is kept: the bowling-ball problem); the slot's side is flat
    v0, step = 0.01, 1e-5
    t_roll = v0 / (3.0 * MU * G)
    joint, states, _ = scenes.pin((v0, 0.0), scenes.whole_steps(1.5 * t_roll, step), step)
    t, vx, w = states[:, 0], states[:, 4], states[:, 6]
    # after the settling's first 40 steps (it halves what the onset left each step, n 2^-n;
    # exuclear.engine.settling), while which the sliding loads are mu F_N to the mode's
    # LOAD_TOLERANCE; bound 1e-9: the trapezoidal rule integrates the constant friction exactly
    sliding = (t > 40 * step) & (t < t_roll - 2 * step)
    assert -np.polyfit(t[sliding], vx[sliding], 1)[0] == pytest.approx(MU * G, rel=1e-9)
    assert vx[-1] == pytest.approx(2.0 * v0 / 3.0, rel=1e-9)  # the kept angular momentum, to round-off
    assert abs(vx[-1] + pins.PIN * w[-1]) < 1e-12  # rolls: no slip
    out = joint.outputs()
    assert np.all(out["sticking"][out["time"] > t_roll + step] == 1.0)
    assert out["normal_force"][-1] == pytest.approx(pins.PIN_MASS * G, rel=1e-12)  # m g, Newton's tolerance


@pytest.mark.parametrize("tangential", [0.3, 0.05])
def test_a_pin_thrown_at_its_slots_side_follows_brachs_law(tangential):
    # no gravity: the disc hits the flat side at v_n; the normal impulse m (1 + e) v_n, the
    # slip v_x stopped where that needs m v_x / 3 (the disc's 1/m + R^2/I = 3/m) within mu
    # times it, else the disc slides through: dv_x = -mu (1 + e) v_n, R dw = -2 mu (1 + e) v_n
    v_n, step = 0.1, 1e-5
    joint, states, _ = scenes.pin((tangential, -v_n), 6 * step, step, start_gap=2.5 * step * v_n, gravity=0.0)
    impacts = joint.impacts()
    assert len(impacts) == 1
    e = impacts[0].restitution
    vx, vy, w = states[-1, 4:7]
    slide = MU * (1.0 + e) * v_n
    # bound 1e-9: the jump is the step's end velocities, to Newton's tolerance (the side is flat)
    assert vy == pytest.approx(e * v_n, rel=1e-9)
    if 3.0 * slide < tangential:  # slides through
        assert vx == pytest.approx(tangential - slide, rel=1e-9)
        assert pins.PIN * w == pytest.approx(-2.0 * slide, rel=1e-9)
    else:  # sticks: rolls off
        assert vx == pytest.approx(2.0 * tangential / 3.0, rel=1e-9)
        assert abs(vx + pins.PIN * w) < 1e-9 * v_n


def test_a_spinning_spatial_journal_slides_on_its_slices_then_rolls():
    # the spatial journal (four slices, a solid steel cylinder, I = m R^2 / 2 about its axis)
    # resting flat on its bearing's bottom and spinning at -v_T0 / R: each slice's friction
    # mu times its share of the weight; Newton's laws as for the planar journal
    # (tests/test_impulse_friction.py): the slip falls at 3 mu g until it rolls
    slip0, step = 0.01, 1e-5
    joint, _, _ = scenes.spinning_journal(slip0, step)
    t_roll = slip0 / (3.0 * MU * G)
    outputs = joint.outputs()
    assert len(outputs) == 4
    first = outputs["slice 1 at z = -0.01125 m"]
    t, slip = first["time"], first["slip_velocity"]
    early = (t > 3 * step) & (t < 0.3 * t_roll)
    # bound 0.5 %: the rolling journal's centre moves on a circle of radius c in the
    # bearing (the wall's curvature is 1/c for the centre), whose slope pulls it back at
    # g x / c, about 1.5 % of mu g by 0.3 t_s (the journal's travel 1.5 um against c = 100 um)
    assert -np.polyfit(t[early], slip[early], 1)[0] == pytest.approx(3.0 * MU * G, rel=5e-3)
    for name, out in outputs.items():
        sliding = (out["time"] > 3 * step) & (out["sticking"] == 0.0)
        # each slice's friction is mu times its own normal force, to the mode's load tolerance
        assert np.all(np.abs(np.abs(out["friction_force"][sliding]) / (MU * out["normal_force"][sliding]) - 1.0)
                      <= LOAD_TOLERANCE), name
        assert out["sticking"][-1] == 1.0 and abs(out["slip_velocity"][-1]) < 1e-12, name
        # the slices share the load equally (the journal flat, the least-squares split)
        assert out["normal_force"][-1] == pytest.approx(first["normal_force"][-1], rel=1e-12), name
    # the change to rolling within 3 % of t_s: the wall's curvature above slows the slip's fall
    assert t[first["sticking"] == 1.0][0] == pytest.approx(t_roll, rel=0.03)



def test_a_journal_free_along_its_axis_slides_along_it_at_mu_g_and_stops():
    # the spatial journal (four slices) free along its axis, flat on its bearing's bottom,
    # sliding along the axis: the slices' friction acts along it (the compliant slice's eq. (42))
    # and the journal slows at mu g, stops at v0 / (mu g) (25.5 ms) and stays
    v0 = 0.05
    run = scenes.gliding_journal(v0, 0.0)
    t, v = run.states[:, 0], run.states[:, 6]
    # bound mu g h (2e-4 m/s): the trapezoidal rule integrates the constant friction exactly;
    # the stop falls within one step, which slides and sticks as a whole
    assert np.abs(v - np.maximum(v0 - MU * G * t, 0.0)).max() <= MU * G * run.step
    # stuck, held by the sticking conditions: 0 to Newton's round-off (1e-20 m/s)
    assert np.abs(v[t > v0 / (MU * G) + run.step]).max() < 1e-15
    # the friction along the axis, at the contact line under the axis: nothing turns or lifts it
    assert np.abs(run.states[:, [4, 5, 7, 8, 9]]).max() < 1e-12


def test_a_spinning_journal_sliding_along_its_axis_slows_as_coulombs_law_says():
    # the scene: the journal free along its axis slides at 0.2 m/s and spins at
    # 50 rad/s (R w = 0.495 m/s) on its slices.  Coulomb's law against the contact's whole slip
    # (v_a, R w): both components slow along the slip's direction, R w twice as fast as v_a
    # (m R^2 / I = 2), against SciPy's solution of those two equations
    axial, spin = 0.2, 50.0
    run = scenes.gliding_journal(axial, spin)
    t = run.states[:, 0]
    reference = scenes.gliding_reference(axial, spin, t)
    # bound 3 % of the change mu g t (2 mu g t for R w): the reference holds the centre at the
    # bottom; the circumferential friction rolls it up the wall to where tan(phi) = mu, the
    # normal force m g cos(phi) up to 1.9 % below m g, and it swings about that angle (period
    # 2 pi sqrt(c / g) = 20 ms), the centripetal v^2 / c adding to the normal force
    assert np.all(np.abs(run.states[:, 6] - reference[0]) <= 0.03 * MU * G * t + 1e-12)
    assert np.all(scenes.journals.JOURNAL * np.abs(run.states[:, 9] - reference[1]) <= 0.06 * MU * G * t + 1e-12)
    assert run.states[-1, 0] == pytest.approx(0.05)  # to the end, no stop


#: The tilted bar's mass [kg], length and height [m], and its turn [rad] (the rear-lower
#: corner the lowest, 40 um below the front-lower one; the upper ones 0.16 mm and more below their wall).
BAR, TILT = (1.0, 0.2, 0.04), 2e-4


def bar_inertia() -> float:
    return BAR[0] * (BAR[1] ** 2 + BAR[2] ** 2) / 12.0


def _tilted_bar(vx: float) -> tuple[ImpulseGuideHandle, np.ndarray, np.ndarray]:
    """No gravity: a planar slider of 1 kg, 0.2 m by 0.04 m (I = m (L^2 + H^2) / 12), cr 1,
    ``coulomb:0.6``, turned by TILT so that its rear-lower corner is 1e-8 m above the lower
    wall (the other corners far from theirs), moving at (``vx``, -0.3) m/s without spin;
    1e-5 s at steps of 1e-7 s: that corner's one impact.  Returns the joint, the corner
    from the centre of mass at the start (the lever of its impulses) and the states."""
    half_length, half_height = 0.5 * BAR[1], 0.5 * BAR[2]
    lever = np.array([[math.cos(TILT), -math.sin(TILT)], [math.sin(TILT), math.cos(TILT)]]) @ [-half_length,
                                                                                               -half_height]
    y0 = -(half_height + CLEARANCE) - lever[1] + 1e-8
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, y0, TILT],
                                       initialVelocities=[vx, -0.3, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=BAR[0], inertia=bar_inertia()))
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0],
                                                   slider_length=BAR[1], slider_height=BAR[2], clearance=CLEARANCE,
                                                   contact_mode="impulse", friction="coulomb:0.6",
                                                   **{**LAW, "cr": 1.0})
    assert isinstance(joint, ImpulseGuideHandle)
    mbs.Assemble()
    states = scenes._recorded(mbs, node, planar=True)
    pins.solve(mbs, 1e-7, 1e-5)
    return joint, lever, np.array(states)


@pytest.mark.parametrize("vx", [0.05, 0.0])
def test_a_tilted_bar_whose_corner_stops_its_slip_along_it_gains_energy_and_is_told(vx):
    # Kane and Levinson's paradox on a joint of several contacts (the guide's corners, their
    # impulses' work summed per step): the rear-lower corner strikes alone.  At the corner,
    # r from the centre of mass, the inverse mass in (n, t) (n = (0, -1) into the wall,
    # t = n x z) is W = I/m + k k^T / I_z with k = z x r; its coupling W_nt = -r_x r_y / I_z
    # (0.1 m by 0.02 m of lever) moves the slip under the normal impulse.  Brach's law with
    # e = 1: the stop u+ = (-u_n, 0) needs p = W^-1 (-2 u_n, -u_t).  Slipping at 0.05 m/s the
    # stop is along the slip (p_t u_t > 0), at 0.24 of p_n, inside mu = 0.6: the impact adds
    # p_t u_t / 2.  Not slipping (vx 0) the stop holds the slip at 0 (p_t at 0.52 of p_n, in
    # the cone), and the work p_t (0 + 0) / 2 + p_n (u_n - u_n) / 2 is 0: no note
    joint, lever, states = _tilted_bar(vx)
    impacts = joint.impacts()
    assert [i.pair for i in impacts] == ["corner rear-lower / lower wall"] and impacts[0].restitution == 1.0
    n, t = np.array([0.0, -1.0]), np.array([-1.0, 0.0])
    basis = np.array([n, t])
    k = basis @ [-lever[1], lever[0]]
    w = np.eye(2) / BAR[0] + np.outer(k, k) / bar_inertia()
    u = basis @ [vx, -0.3]  # (u_n, u_t) before: the bar does not spin
    p = np.linalg.solve(w, [-2.0 * u[0], -u[1]])
    assert p[0] < 0.0 and abs(p[1]) <= 0.6 * abs(p[0])  # the stop is inside the cone: the corner sticks
    gain = 0.5 * p[1] * u[1]
    vx1, vy1, spin = states[-1, 4:7]
    energy = 0.5 * BAR[0] * (vx1**2 + vy1**2) + 0.5 * bar_inertia() * spin**2 - 0.5 * BAR[0] * (vx**2 + 0.3**2)
    told = [note for note in joint.notes if "Kane and Levinson" in note]
    if vx == 0.0:
        assert not told
        # bound: the exact work is 0; Newton's tolerance on the jump's rates (1e-9 of 0.3 m/s)
        # times the impulse, as the mode's round-off bound on a step's work
        assert abs(energy) < 1e-9 * abs(p[0]) * 0.3
        return
    assert p[1] * u[1] > 0.0  # along the slip: a gain
    [note] = told
    assert note.startswith("1 impacts added energy") and "contact_mode='compliant'" in note
    # bounds: the note's 3 digits; the bar's own gain to Newton's tolerance on the jump's
    # rates (1e-9; the wall's normal is fixed and the bar hits without spin, so the lever is
    # the start's)
    assert float(re.search(r"up to (\S+) J", note).group(1)) == pytest.approx(gain, rel=5e-3)
    assert energy == pytest.approx(gain, rel=1e-9)
