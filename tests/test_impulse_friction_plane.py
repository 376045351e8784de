"""Coulomb friction in the impulse contact mode where the slip has a tangent plane
(exuclear.engine.impulse_friction, two sticking conditions and the cone |F_T| <= mu_s F_N):
a ball in its socket and a box slider's corners on their wall, against Newton's laws, on the
scenes of validation/cost/_friction_scenes.py."""
import numpy as np
import pytest

from exuclear.engine.impulse_friction import LOAD_TOLERANCE
from validation.cost import _friction_scenes as scenes
from validation.cost._translational_scenes import MASS

G, MU, DIRECTION = scenes.G, scenes.MU, scenes.DIRECTION


def test_a_ball_in_its_socket_slides_straight_at_mu_g_then_rolls():
    # a solid ball (I = 2 m R^2 / 5) sliding without spin on its socket's bottom: friction
    # mu m g against the slip, so its centre slows at mu g along a straight line (the slip's
    # direction does not turn: the friction's moment spins the ball about the axis normal to
    # the slip and the normal), and the slip falls at (1 + m R^2 / I) mu g = 3.5 mu g until it
    # rolls at t_s = v0 / (3.5 mu g), at 5 v0 / 7 (the angular momentum about the contact
    # point is kept)
    v0, step = 1e-3, 1e-6
    t_roll = v0 / (3.5 * MU * G)  # 0.15 ms
    joint, states, _ = scenes.ball(v0 * DIRECTION, scenes.whole_steps(1.5 * t_roll, step), step)
    t, v = states[:, 0], states[:, 4:7]
    sliding = (t > 2 * step) & (t < t_roll - 2 * step)
    speed = v[:, [0, 2]] @ DIRECTION[[0, 2]]
    # bound 0.5 %: the socket is a sphere of radius c for the ball's centre, whose slope pulls
    # the ball back by g x / c (0.1 % of mu g at the slide's end, x = 0.1 um) and whose
    # curvature adds v^2 / c to the normal's g (0.1 %)
    assert -np.polyfit(t[sliding], speed[sliding], 1)[0] == pytest.approx(MU * G, rel=5e-3)
    assert speed[-1] == pytest.approx(5.0 * v0 / 7.0, rel=5e-3)
    # a straight path: the velocity across the slip's direction in the tangent plane stays 0
    # (bound: round-off of the velocities, 1e-12 of v0)
    across = v[:, 0] * DIRECTION[2] - v[:, 2] * DIRECTION[0]
    assert np.abs(across).max() < 1e-12 * v0
    out = joint.outputs()
    slid = (out["time"] > 3 * step) & (out["sticking"] == 0.0)  # the three-step means settled
    # the slip's speed and the friction's size, mu times the normal force (the load tolerance)
    assert np.all(np.abs(out["friction_force"][slid] / (MU * out["normal_force"][slid]) - 1.0) <= LOAD_TOLERANCE)
    rolled = out["time"] > t_roll + 2 * step
    assert rolled.any() and np.all(out["sticking"][rolled] == 1.0)
    assert np.abs(out["slip_velocity"][rolled]).max() < 1e-12  # Newton's tolerance on the held slip
    assert len(joint.impacts()) == 1  # the rest's onset


@pytest.mark.parametrize("tangential", [0.3, 0.05])
def test_a_ball_thrown_at_its_socket_follows_brachs_law(tangential):
    # no gravity: the ball hits the socket's bottom at v_n with a slip ``tangential`` along
    # DIRECTION: the normal impulse P_n = m (1 + e) v_n; the slip stopped where that needs
    # P = m v_T / 3.5 (the ball's 1/m + R^2/I = 3.5/m) within mu P_n (the ball leaves rolling
    # at 5 v_T / 7), else it slides through with mu P_n along the slip: dv = -mu (1 + e) v_n
    v_n, step = 0.1, 1e-8
    joint, states, _ = scenes.ball(tangential * DIRECTION - [0.0, v_n, 0.0], 6 * step, step,
                                   start_gap=2.5 * step * v_n, gravity=0.0)
    impacts = joint.impacts()
    assert len(impacts) == 1
    e = impacts[0].restitution
    v = states[-1, 4:7]
    slide = MU * (1.0 + e) * v_n
    # bound 1e-3: the step's normal is where it met the wall, turned from the bottom's by the
    # ball's travel until then (up to 7.5e-9 m at 0.3 m/s, 7.5e-5 rad on the socket's
    # sphere of radius c for the ball's centre), along which the rebound is held: the
    # tangential speed times that turn, 3e-4 of e v_n, goes into the vertical (5.3e-4 measured)
    assert v[1] == pytest.approx(e * v_n, rel=1e-3)
    expected = tangential - slide if 3.5 * slide < tangential else 5.0 * tangential / 7.0
    assert v[[0, 2]] == pytest.approx(expected * DIRECTION[[0, 2]], rel=1e-3)


def test_a_box_flat_on_its_wall_slides_straight_at_mu_g_then_sticks():
    # the box (a 50 mm steel cube) on the channel's lower wall, sliding obliquely across the
    # guide's axis: its four lower corners' friction slows it at mu g along a straight line
    # until it stops at t_s = v0 / (mu g), then it sticks, each corner holding m g / 4
    v0, step = 0.02, 1e-4
    t_stop = v0 / (MU * G)  # 10 ms, inside a step; the box moves 8 um across the channel by then, c = 100 um
    joint, states, _ = scenes.sliding_box(v0, step)
    t, p, w = states[:, 0], states[:, 1:4], states[:, 7:10]
    along = p[:, [0, 2]] @ DIRECTION[[0, 2]]
    reference = np.where(t < t_stop, v0 * t - 0.5 * MU * G * t**2, 0.5 * v0 * t_stop)
    # bound mu g h^2: the trapezoidal rule integrates the constant friction exactly; the stop
    # falls within one step, which slides and sticks as a whole
    assert np.abs(along - reference).max() <= MU * G * step**2
    assert np.abs(p[:, 0] * DIRECTION[2] - p[:, 2] * DIRECTION[0]).max() < 1e-15  # a straight path (round-off)
    assert np.abs(w).max() < 1e-12  # flat, held: no turn
    corners = [out for out in joint.outputs().values() if out["normal_force"].any()]
    assert len(corners) == 4
    for out in corners:
        assert out["sticking"][-1] == 1.0 and abs(out["slip_velocity"][-1]) < 1e-12
        # bound 1e-12: Newton's tolerance on the held conditions, the least-squares split
        assert out["normal_force"][-1] == pytest.approx(0.25 * MASS * G, rel=1e-12)
    # the corners' friction during the slide sums to mu m g
    slid = (corners[0]["time"] > 3 * step) & (corners[0]["time"] < t_stop - 3 * step)
    total = sum(out["friction_force"][slid] for out in corners)
    assert np.all(np.abs(total / (MU * MASS * G) - 1.0) <= LOAD_TOLERANCE)
