"""The impulse contact mode's Coulomb friction on each joint type: the scenes, and the rows
of ``python -m validation.cost modes_friction_types`` (tests/test_impulse_friction_types.py
and tests/test_impulse_friction_plane.py assert on the same runs).

Source problems, each with Newton's laws for a rigid body on a wall with Coulomb friction
``mu = 0.2``: a block sliding on a flat wall (it slows at ``mu g`` and stops, or on a slope
``a`` stays while ``tan a <= mu`` and slides at ``g (sin a - mu cos a)`` above); a disc or
ball sliding without spin (the slip falls at ``(1 + m R^2 / I) mu g`` until it rolls, at 2/3
of its speed for a disc, 5/7 for a ball: the angular momentum about the contact point is
kept, the bowling-ball problem, e.g. Meriam and Kraige, *Engineering Mechanics: Dynamics*);
and impacts under Newton's restitution with Coulomb's bound on the tangential impulse (R. M.
Brach, J. Appl. Mech. 56 (1989) 133-138): a body hitting at ``v_n`` slides through with the
tangential impulse ``mu (1 + e) m v_n`` where stopping its slip needs more, else its slip
stops.  The bodies are the joint-type scenes' (``_translational_scenes``: the 0.98 kg planar
slider and the box; ``_joint_type_scenes``: the 40 g pin, the steel ball; ``_spatial_scenes``:
the journal of four slices), each touching its wall at the start.
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

import exudyn as exu
import numpy as np

from exuclear.timescales import impact_restitution
from validation.cost import _joint_type_scenes as pins
from validation.cost import _spatial_scenes as journals
from validation.cost import _translational_scenes as sliders

#: Standard gravity [m/s^2] and the friction coefficient of every scene.
G, MU = 9.81, 0.2
FRICTION = f"coulomb:{MU}"
#: A slip direction in the tangent plane at the socket's bottom, or the box's lower wall
#: (x along the guide, z across the channel): along neither frame's axes.
DIRECTION = np.array([0.6, 0.0, 0.8])


class Run(NamedTuple):
    """A run: the joint, the body's states at the start and each step's end (the planar
    bodies: t, x, y, angle, their rates; the 3D bodies: t, position, velocity, angular
    velocity) and the step [s]."""

    joint: Any
    states: np.ndarray
    step: float


def whole_steps(end: float, step: float) -> float:
    """``end`` [s] rounded up to whole steps of ``step``, so that the steps are ``step`` and a
    stop or a roll's onset falls inside a step (at ``end = k t_s`` the steps ``end / N`` put
    ``t_s`` at a step's end wherever ``N / k`` is whole)."""
    return step * math.ceil(end / step - 1e-9)


def _recorded(mbs: exu.MainSystem, node: int, planar: bool) -> list:
    ov = exu.OutputVariableType
    kinds = (ov.Coordinates, ov.Coordinates_t) if planar else (ov.Position, ov.Velocity, ov.AngularVelocity)
    states: list = []  # Exudyn calls the post-step function at the start too

    def record(mbs: exu.MainSystem, t: float) -> bool:
        states.append((t, *(x for kind in kinds for x in mbs.GetNodeOutput(node, kind))))
        return True
    mbs.SetPostStepUserFunction(record)
    return states


def slider(step: float, end: float, **scene: Any) -> Run:
    """The planar slider (``_translational_scenes.slider``'s ``scene``) with friction, at fixed steps."""
    mbs, joint, states = sliders.slider(friction=FRICTION, **scene)
    pins.solve(mbs, step, end, adaptive=False)
    return Run(joint, np.array(states), step)


def lower_corners(joint: Any) -> tuple[dict, dict]:
    """The outputs of the planar slider's two lower corners, rear and front."""
    pairs = joint.outputs()
    return pairs["corner rear-lower / lower and upper walls"], pairs["corner front-lower / lower and upper walls"]


def sliding_slider(v0: float = 0.05, step: float = 1e-4) -> Run:
    """Gravity -y: the slider flat on its lower wall sliding at ``v0`` [m/s] along x, until
    1.6 times its stop ``v0 / (mu g)``."""
    return slider(step, whole_steps(1.6 * v0 / (MU * G), step), y0=-sliders.CLEARANCE, velocity=(v0, 0.0, 0.0), gravity=G)


def tilted_slider(tilt: float, step: float = 1e-4, end: float = 0.02) -> Run:
    """The slider at rest flat on a guide tilted so that ``tan a = tilt mu``."""
    return slider(step, end, y0=-sliders.CLEARANCE, gravity=G, slope=math.atan(tilt * MU))


def thrown_slider(tangential: float, v_n: float = 0.05, step: float = 1e-4) -> Run:
    """No gravity: the slider thrown flat at its lower wall at ``v_n`` [m/s], sliding at
    ``tangential``, 2.5 steps off the wall; 6 steps."""
    return slider(step, 6 * step, y0=-sliders.CLEARANCE + 2.5 * step * v_n, velocity=(tangential, -v_n, 0.0))


def pin(velocity: Any, end: float, step: float = 1e-5, start_gap: float = 0.0, gravity: float = G) -> Run:
    """The pin (a 40 g solid disc, R 4.9 mm, in a 10 mm slot) on the slot's lower flat side
    (or ``start_gap`` [m] above it) moving at ``velocity`` (x, y), gravity -y."""
    c = 0.5 * pins.WIDTH - pins.PIN
    mbs, joint, node = pins.pin_in_slot((0.0, -c + start_gap), velocity, gravity=(0.0, -gravity), friction=FRICTION)
    states = _recorded(mbs, node, planar=True)
    pins.solve(mbs, step, end, adaptive=False)
    return Run(joint, np.array(states), step)


def ball(velocity: Any, end: float, step: float, start_gap: float = 0.0, gravity: float = G) -> Run:
    """The steel ball (R 9.9 mm, c = 0.1 mm) at the socket's bottom (or ``start_gap`` [m]
    above it) moving at ``velocity`` (3D), gravity -y."""
    c = pins.SOCKET - pins.BALL
    mbs, joint, node = pins.ball_in_socket((0.0, -c + start_gap, 0.0), velocity, gravity=gravity, friction=FRICTION)
    states = _recorded(mbs, node, planar=False)
    pins.solve(mbs, step, end, adaptive=False)
    return Run(joint, np.array(states), step)


def spinning_journal(slip0: float = 0.01, step: float = 1e-5) -> Run:
    """The spatial journal (four slices) resting flat on its bearing's bottom, spinning at
    ``-slip0 / R``, gravity -y, until 1.5 times its roll's onset ``slip0 / (3 mu g)``."""
    mbs, joint, states = journals.journal(offset=(0.0, -journals.CLEARANCE, 0.0),
                                          spin=(0.0, 0.0, -slip0 / journals.JOURNAL), gravity=G, friction=FRICTION)
    pins.solve(mbs, step, whole_steps(1.5 * slip0 / (3.0 * MU * G), step), adaptive=False)
    return Run(joint, np.array(states), step)


def gliding_journal(axial: float, spin: float, step: float = 1e-4, end: float = 0.05) -> Run:
    """The spatial journal (four slices) free along its axis, resting flat on its bearing's
    bottom, sliding along the axis at ``axial`` [m/s] and spinning at ``spin`` [rad/s] about
    it, gravity -y, to ``end`` [s] (the issue's scene: 0.2 m/s, 50 rad/s)."""
    mbs, joint, states = journals.spatial_journal((0.0, 0.0, axial), (0.0, 0.0, spin), (0.0, -journals.CLEARANCE, 0.0),
                                                  (0.0, -G, 0.0), contact_mode="impulse", friction=FRICTION)
    pins.solve(mbs, step, whole_steps(end, step), adaptive=False)
    return Run(joint, np.array(states), step)


def gliding_reference(axial: float, spin: float, t: np.ndarray) -> np.ndarray:
    """Coulomb's law for :func:`gliding_journal`, its centre held at the bearing's bottom:
    the friction ``mu m g`` against the slip ``(v_a, R w)`` of the contact line, so that
    ``dv_a/dt = -mu g v_a / |s|`` and ``d(R w)/dt = -mu g (m R^2 / I) R w / |s| = -2 mu g R w
    / |s|`` (``I = m R^2 / 2``), both reaching 0 at once; SciPy's DOP853 at rtol 1e-10.
    Returns ``v_a`` and ``w`` at the times ``t`` (rows)."""
    from scipy.integrate import solve_ivp

    def slowing(_: float, slip: np.ndarray) -> list[float]:
        speed = math.hypot(*slip)
        return [0.0, 0.0] if speed == 0.0 else [-MU * G * slip[0] / speed, -2.0 * MU * G * slip[1] / speed]

    def stops(_: float, slip: np.ndarray) -> float:
        return math.hypot(*slip) - 1e-9 * math.hypot(axial, journals.JOURNAL * spin)
    stops.terminal = True
    slip0 = [axial, journals.JOURNAL * spin]
    solution = solve_ivp(slowing, (0.0, float(t[-1])), slip0, method="DOP853", rtol=1e-10, atol=1e-14,
                         events=stops, dense_output=True)
    end = solution.t[-1]
    slip = np.where(t <= end, solution.sol(np.minimum(t, end)), 0.0)
    return np.array([slip[0], slip[1] / journals.JOURNAL])


def sliding_box(v0: float = 0.02, step: float = 1e-4) -> Run:
    """The box flat on the channel's lower wall sliding at ``v0`` along :data:`DIRECTION`,
    gravity -y, until 1.5 times its stop ``v0 / (mu g)``."""
    mbs, joint, states = sliders.box(offset=(0.0, -sliders.CLEARANCE, 0.0), velocity=v0 * DIRECTION, gravity=G,
                                     friction=FRICTION)
    pins.solve(mbs, step, whole_steps(1.5 * v0 / (MU * G), step), adaptive=False)
    return Run(joint, np.array(states), step)


def brach(tangential: float, v_n: float, e: float, inertia_factor: float) -> float:
    """The tangential speed after an impact at ``v_n`` with slip ``tangential`` (module
    docstring) of a body whose slip changes by ``inertia_factor`` (``1 + m R^2 / I``) times
    its centre's velocity change: slides through, or the slip stopped."""
    slide = MU * (1.0 + e) * v_n
    return tangential - slide if inertia_factor * slide < tangential else tangential * (1.0 - 1.0 / inertia_factor)


def friction_type_rows() -> list[list[str]]:
    """Per scene: the case, Newton's law and what the mode gives (module docstring)."""
    rows = []
    v0 = 0.05
    run = sliding_slider(v0)
    t, x = run.states[:, 0], run.states[:, 1]
    t_stop = v0 / (MU * G)
    reference = np.where(t < t_stop, v0 * t - 0.5 * MU * G * t**2, 0.5 * v0 * t_stop)
    rear, front = lower_corners(run.joint)
    rows.append(["planar slider flat on its wall at 0.05 m/s, 1e-4 s", "x = v0 t - mu g t^2 / 2, stops at v0 / (mu g), "
                 "then m g / 2 per corner",
                 f"x within {np.abs(x - reference).max():.2g} m; corners at rest "
                 f"{rear['normal_force'][-1] / (0.5 * sliders.MASS * G) - 1.0:.1e}, "
                 f"{front['normal_force'][-1] / (0.5 * sliders.MASS * G) - 1.0:.1e} off m g / 2"])
    for tilt in (0.5, 2.0):
        run = tilted_slider(tilt)
        t, x = run.states[:, 0], run.states[:, 1]
        slope = math.atan(tilt * MU)
        a = G * (math.sin(slope) - MU * math.cos(slope))
        if tilt < 1.0:
            held = sum(c["friction_force"][-1] for c in lower_corners(run.joint))
            rows.append([f"the slider at rest on a guide tilted to tan a = {tilt:g} mu", "stays, friction m g sin a",
                         f"largest |x| {np.abs(x).max():.1g} m; friction {abs(held) / (sliders.MASS * G * math.sin(slope)) - 1.0:.1e} off"])
        else:
            rows.append([f"the same at tan a = {tilt:g} mu, 0.02 s", "slides at g (sin a - mu cos a)",
                         f"x within {np.abs(x + 0.5 * a * t**2).max() / (0.5 * a * t[-1]**2):.1e} of its travel"])
    for tangential in (0.05, 0.005):
        run = thrown_slider(tangential)
        e = impact_restitution(run.joint.joint.law, 0.05)
        vx, vy, w = run.states[-1, 4:7]
        expected = brach(tangential, 0.05, e, 1.0)
        rows.append([f"the slider thrown flat at its wall, 0.05 m/s, sliding at {tangential:g} m/s",
                     "slides through" if expected > 0.0 else "the slip stopped",
                     f"v_x {abs(vx - expected):.1e} m/s off; rebound {vy / (e * 0.05) - 1.0:.1e} off e v_n; turn {abs(w):.1g} rad/s"])
    v0 = 0.01
    run = pin((v0, 0.0), whole_steps(1.5 * v0 / (3.0 * MU * G), 1e-5))
    t, vx = run.states[:, 0], run.states[:, 4]
    sliding = (t > 2 * run.step) & (t < v0 / (3.0 * MU * G) - 2 * run.step)
    rows.append(["a pin sliding without spin on its slot's flat side at 0.01 m/s, 1e-5 s",
                 "slows at mu g, rolls at 2 v0 / 3",
                 f"{-np.polyfit(t[sliding], vx[sliding], 1)[0] / (MU * G) - 1.0:.1e} off mu g; "
                 f"{vx[-1] / (2.0 * v0 / 3.0) - 1.0:.1e} off 2 v0 / 3"])
    for tangential in (0.3, 0.05):
        run = pin((tangential, -0.1), 6e-5, start_gap=2.5e-6, gravity=0.0)
        e = run.joint.impacts()[0].restitution
        expected = brach(tangential, 0.1, e, 3.0)
        rows.append([f"the pin thrown at its slot's side, 0.1 m/s, sliding at {tangential:g} m/s",
                     "slides through" if 3.0 * MU * (1.0 + e) * 0.1 < tangential else "the slip stopped",
                     f"v_x {run.states[-1, 4] / expected - 1.0:.1e} off"])
    run = spinning_journal()
    first = next(iter(run.joint.outputs().values()))
    t, slip = first["time"], first["slip_velocity"]
    t_roll = 0.01 / (3.0 * MU * G)
    early = (t > 3 * run.step) & (t < 0.3 * t_roll)
    rows.append(["the spatial journal (4 slices) spinning on its bearing's bottom, 1e-5 s",
                 "slip falls at 3 mu g, rolls at t_s",
                 f"{-np.polyfit(t[early], slip[early], 1)[0] / (3.0 * MU * G) - 1.0:.1e} off 3 mu g; rolls at "
                 f"{t[first['sticking'] == 1.0][0] / t_roll - 1.0:+.1e} of t_s (the bearing's curvature)"])
    rows.append(gliding_row(0.05, 0.0, "the spatial journal free along its axis sliding along it at 0.05 m/s, 1e-4 s",
                            "slows at mu g, stops at v0 / (mu g)"))
    rows.append(gliding_row(0.2, 50.0, "the same sliding at 0.2 m/s and spinning at 50 rad/s (R w = 0.495 m/s), 1e-4 s",
                            "Coulomb's law against the slip (v_a, R w), centre at the bottom (SciPy)"))
    v0 = 1e-3
    t_roll = v0 / (3.5 * MU * G)
    run = ball(v0 * DIRECTION, whole_steps(1.5 * t_roll, 1e-6), 1e-6)
    t, v = run.states[:, 0], run.states[:, 4:7]
    speed = v[:, [0, 2]] @ DIRECTION[[0, 2]]
    sliding = (t > 2 * run.step) & (t < t_roll - 2 * run.step)
    across = np.abs(v[:, 0] * DIRECTION[2] - v[:, 2] * DIRECTION[0]).max()
    rows.append(["a ball sliding without spin in its socket at 1 mm/s obliquely, 1e-6 s",
                 "a straight path, slows at mu g, rolls at 5 v0 / 7",
                 f"across the path {across:.1g} m/s; {-np.polyfit(t[sliding], speed[sliding], 1)[0] / (MU * G) - 1.0:.1e} "
                 f"off mu g; {speed[-1] / (5.0 * v0 / 7.0) - 1.0:.1e} off 5 v0 / 7 (the socket's curvature)"])
    for tangential in (0.3, 0.05):
        run = ball(tangential * DIRECTION - [0.0, 0.1, 0.0], 6e-8, 1e-8, start_gap=2.5e-9, gravity=0.0)
        e = run.joint.impacts()[0].restitution
        expected = brach(tangential, 0.1, e, 3.5)
        rows.append([f"the ball thrown at its socket, 0.1 m/s, sliding at {tangential:g} m/s obliquely",
                     "slides through" if 3.5 * MU * (1.0 + e) * 0.1 < tangential else "the slip stopped",
                     f"tangential {np.linalg.norm(run.states[-1, [4, 6]]) / expected - 1.0:.1e} off; "
                     f"rebound {run.states[-1, 5] / (e * 0.1) - 1.0:.1e} off e v_n"])
    v0 = 0.02
    run = sliding_box(v0)
    t, p = run.states[:, 0], run.states[:, 1:4]
    t_stop = v0 / (MU * G)
    along = p[:, [0, 2]] @ DIRECTION[[0, 2]]
    reference = np.where(t < t_stop, v0 * t - 0.5 * MU * G * t**2, 0.5 * v0 * t_stop)
    corners = [out for out in run.joint.outputs().values() if out["normal_force"].any()]
    split = max(abs(out["normal_force"][-1] / (0.25 * sliders.MASS * G) - 1.0) for out in corners)
    rows.append(["the box flat on its wall at 0.02 m/s obliquely, 1e-4 s",
                 "a straight path, x = v0 t - mu g t^2 / 2, stops, then m g / 4 per corner",
                 f"along the path within {np.abs(along - reference).max():.2g} m; {len(corners)} corners at rest "
                 f"{split:.1e} off m g / 4"])
    return rows


def gliding_row(axial: float, spin: float, case: str, law: str) -> list[str]:
    """The row of :func:`gliding_journal` against :func:`gliding_reference`, while the
    journal's centre lies between its end slices (beyond, its weight tips it over the last
    slice, which the reference does not have)."""
    run = gliding_journal(axial, spin)
    t, s = run.states[:, 0], run.states[:, [6, 9]]
    inside = run.states[:, 3] < journals.LENGTH * 3.0 / 8.0  # the end slices' centres at +-3L/8
    reference = gliding_reference(axial, spin, t[inside])
    off = np.abs(s[inside].T - reference).max(axis=1)
    return [case, law, f"v_a within {off[0]:.1e} m/s, R w within {journals.JOURNAL * off[1]:.1e} m/s to "
                       f"{t[inside][-1]:.3g} s; the journal ends at v_a = {s[-1, 0]:.2g} m/s, w = {s[-1, 1]:.3g} rad/s"]
