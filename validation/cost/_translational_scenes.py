"""The impulse contact mode's scenes for the translational joints, and their rows of
``python -m validation.cost modes`` (tests/test_impulse_translational.py asserts on the same
runs).

Source problems, each with an exact reference: a planar slider (a 50 mm x 50 mm steel
block, the zoo's ``slider_crank_floating`` slider's size, c = 0.1 mm) in a guide held by the
ground, and a box (50 mm cube) in a channel.  Thrown at a wall, each corner's impact holds
the law's restitution (:func:`exuclear.timescales.impact_restitution`) at its onset
velocity; at rest under gravity the held corners share the weight as a rigid slider's
symmetric static split (``m g / 2`` for the slider's two corners, ``m g / 4`` for the box's
four, as ``validation/translational.py`` checks the compliant joint); held and sliding
frictionless its path is ``x0 + v0 t``; elastic (cr 1) it keeps its energy.
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D
from exudyn.utilities import InertiaCuboid

import exuclear
from exuclear.engine.impulse_guide import ImpulseGuideHandle
from exuclear.prismatic import CORNER_SIGNS
from exuclear.timescales import closed_form_impact, impact_restitution
from validation.cost._joint_type_scenes import G, solve

#: The slider's (and the box's) side and the play per side [m].
SIDE, CLEARANCE = 0.05, 1e-4
#: Steel [kg/m^3]; the planar slider's mass is its block's.
DENSITY = 7850.0
MASS = DENSITY * SIDE**3
#: The zoo's corner law (slider_crank_floating): Lankarani-Nikravesh damping, whose
#: restitution is velocity independent above ``v_min``.
LAW = {"stiffness": 1e10, "exponent": 1.5, "damping": "lankarani-nikravesh", "cr": 0.9}
#: The speed [m/s] a slider is thrown at across the guide: its flight across the clearance
#: (2 c / v, 0.67 ms) is longer than one contact duration of the law at this speed (0.42 ms
#: for the 0.98 kg block) and shorter than ten.
THROW_SPEED = 0.3
#: A turn [rad] of the thrown slider, and the step [contact durations] at which its
#: rear-lower corner hits the wall steps before its front-lower one (the corners TURN L =
#: 100 um apart across the guide, the slider's travel in a step 63 um): one corner at a time.
TURN, TURN_STEP = 2e-3, 0.5


class Run(NamedTuple):
    """A run: the joint, the slider's states (t, x, y, angle, their rates: the planar
    slider's node; t, position (3), velocity (3), angular velocity (3): the box's) at the
    start and each step's end, and the step [s]."""

    joint: ImpulseGuideHandle
    states: np.ndarray
    step: float


def _impulse(joint: Any) -> ImpulseGuideHandle:
    if not isinstance(joint, ImpulseGuideHandle):
        raise RuntimeError(f"the joint is not in the impulse mode: {type(joint).__name__}")
    return joint


def slider(y0: float = 0.0, angle: float = 0.0, velocity: Any = (0.0, 0.0, 0.0), gravity: float = 0.0,
           slope: float = 0.0, **law: Any) -> tuple[exu.MainSystem, ImpulseGuideHandle, list]:
    """The planar slider in a ground guide along x (its centre at the origin), its centre at
    ``(0, y0)`` turned by ``angle`` [rad], moving at ``velocity`` (vx, vy, omega); gravity
    ``gravity`` down a guide tilted by ``slope`` [rad] (``-gravity (sin slope, cos slope)``
    in the guide's x, y: the guide's x rises by ``slope``).  Returns mbs, the joint and the
    list its states are recorded in."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, y0, angle],
                                       initialVelocities=list(velocity)))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=MASS * SIDE**2 / 6.0))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[-MASS * gravity * math.sin(slope), -MASS * gravity * math.cos(slope), 0]))
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, name="guide", itemNumbers=[ground, body], position=[0, 0, 0],
                                                   slider_length=SIDE, slider_height=SIDE, clearance=CLEARANCE,
                                                   contact_mode="impulse", **{**LAW, **law})
    mbs.Assemble()
    states: list = []  # Exudyn calls the post-step function at the start too
    ov = exu.OutputVariableType

    def post_step(mbs: exu.MainSystem, t: float) -> bool:
        states.append((t, *mbs.GetNodeOutput(node, ov.Coordinates), *mbs.GetNodeOutput(node, ov.Coordinates_t)))
        return True
    mbs.SetPostStepUserFunction(post_step)
    return mbs, _impulse(joint), states


def box(offset: Any = (0.0, 0.0, 0.0), velocity: Any = (0.0, 0.0, 0.0), gravity: float = 0.0,
        **law: Any) -> tuple[exu.MainSystem, ImpulseGuideHandle, list]:
    """The box (a steel cube) in a ground channel along x, c = c_z, its centre at ``offset``
    [m] moving at ``velocity`` [m/s], gravity ``-gravity`` along y.  Returns mbs, the joint
    and the list its states are recorded in."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.CreateRigidBody(inertia=InertiaCuboid(DENSITY, [SIDE] * 3), referencePosition=[0, 0, 0],
                               initialDisplacement=list(offset), initialVelocity=list(velocity),
                               gravity=[0, -gravity, 0])
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, name="box", itemNumbers=[ground, body], position=[0, 0, 0],
                                                   slider_length=SIDE, slider_height=SIDE, slider_width=SIDE,
                                                   clearance=CLEARANCE, contact_mode="impulse", **{**LAW, **law})
    mbs.Assemble()
    node = mbs.GetObject(body)["nodeNumber"]
    states: list = []
    ov = exu.OutputVariableType

    def post_step(mbs: exu.MainSystem, t: float) -> bool:
        states.append((t, *(x for q in (ov.Position, ov.Velocity, ov.AngularVelocity) for x in mbs.GetNodeOutput(node, q))))
        return True
    mbs.SetPostStepUserFunction(post_step)
    return mbs, _impulse(joint), states


def thrown_box(direction: Any, durations: float = 1.0) -> Run:
    """No gravity: the box thrown flat from the channel's centre at :data:`THROW_SPEED` along
    ``direction`` (a unit vector across the channel: each wall's four corners hit at once),
    at steps of ``durations`` contact durations, for the flight to the wall and back twice."""
    mbs, joint, states = box(velocity=THROW_SPEED * np.asarray(direction, dtype=float))
    step = durations * closed_form_impact(joint.joint.law, MASS, THROW_SPEED)[1]
    solve(mbs, step, max(4.5 * 2 * CLEARANCE / THROW_SPEED, 4 * step))
    return Run(joint, np.array(states), step)


def corner_rate(state: np.ndarray, corner: int, angle: float) -> float:
    """The normal rate [m/s] towards the lower wall of the planar slider's ``corner``
    (:data:`exuclear.prismatic.CORNER_SIGNS`) at ``state`` (a row of :class:`Run`'s states),
    its lever arm at the slider's ``angle`` (the rows of an impact step's start)."""
    sx, sy = CORNER_SIGNS[corner]
    arm_x = 0.5 * SIDE * (math.cos(angle) * sx - math.sin(angle) * sy)
    return -(state[5] + state[6] * arm_x)


def first_jump(run: Run, axis: int) -> float:
    """``-v+ / v-`` of the body's velocity along the global ``axis`` over the first impact's
    step (the restitution of a body thrown flat; ``run.states`` with the velocity in
    columns 4 to 6)."""
    k = int(np.argmin(np.abs(run.states[:, 0] - run.joint.impacts()[0].onset_time)))
    return -float(run.states[k + 1, 4 + axis]) / float(run.states[k, 4 + axis])


def thrown(angle: float, durations: float = 1.0) -> Run:
    """No gravity: the slider thrown from the guide's centre onto its lower wall at
    :data:`THROW_SPEED`, turned by ``angle`` (0: flat, both lower corners hit at once), at
    steps of ``durations`` contact durations (beyond 1.6 longer than the flight across the
    clearance: the mode shortens those that would fly through the wall), for the flight down
    and back twice, or four steps."""
    mbs, joint, states = slider(angle=angle, velocity=(0.0, -THROW_SPEED, 0.0))
    step = durations * closed_form_impact(joint.joint.law, MASS, THROW_SPEED)[1]
    solve(mbs, step, max(4.5 * 2 * CLEARANCE / THROW_SPEED, 4 * step))
    return Run(joint, np.array(states), step)


def jumps(run: Run) -> list[tuple[Any, float, float, float]]:
    """Each impact of the planar slider's lower corners: (the impact, its corner's normal rate
    at the step's start and at its end, both in the rows of the start, the law's restitution
    at the onset velocity)."""
    times = run.states[:, 0]
    out = []
    for impact in run.joint.impacts():
        if not impact.pair.endswith("/ lower wall"):
            continue
        corner = ("rear-lower", "front-lower").index(impact.pair.split()[1])
        k = int(np.argmin(np.abs(times - impact.onset_time)))
        before, after = run.states[k], run.states[k + 1]
        out.append((impact, corner_rate(before, corner, before[3]), corner_rate(after, corner, before[3]),
                    impact_restitution(run.joint.joint.law, impact.onset_velocity)))
    return out


def resting(step: float = 1e-4, end: float = 0.05, velocity: float = 0.0) -> Run:
    """Gravity -y, the slider flat on its lower wall at t = 0 (y = -c), moving along the guide
    at ``velocity`` [m/s]."""
    mbs, joint, states = slider(y0=-CLEARANCE, velocity=(velocity, 0.0, 0.0), gravity=G)
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def resting_box(step: float = 1e-4, end: float = 0.05) -> ImpulseGuideHandle:
    """Gravity -y, the box flat on its lower wall at t = 0, centred across z."""
    mbs, joint, _ = box((0.0, -CLEARANCE, 0.0), gravity=G)
    solve(mbs, step, end)
    return joint


def elastic(step: float = 1e-5, end: float = 0.05) -> tuple[Run, np.ndarray]:
    """cr 1, no gravity: the slider spinning at 2 rad/s and moving across and along the
    guide rattles between its walls; returns the run and the kinetic energy at each state
    over the start's."""
    mbs, joint, states = slider(velocity=(0.02, -0.05, 2.0), cr=1.0)
    solve(mbs, step, end)
    s = np.array(states)
    energy = 0.5 * MASS * (s[:, 4] ** 2 + s[:, 5] ** 2) + 0.5 * (MASS * SIDE**2 / 6.0) * s[:, 6] ** 2
    return Run(joint, s, step), energy / energy[0]


def translational_rows() -> list[list[str]]:
    """The rows of ``python -m validation.cost modes`` for the slider and the box: target,
    count, measured, met (the law's restitution within 2 %, the static split, the issue's 1 %)."""
    rows = []
    for angle, what, step in ((0.0, "flat (two corners at once)", 1.0),
                              (TURN, "turned 2 mrad (one corner at a time)", TURN_STEP)):
        for durations in (step, 1000.0):
            run = thrown(angle, durations)
            records = jumps(run)
            error = max(abs(-after / before / e - 1.0) for _, before, after, e in records)
            rows.append([f"slider thrown {what} across its guide, no gravity, step {durations:g} contact duration(s)",
                         f"{len(run.joint.impacts())} corner impacts, {len(run.states) - 1} steps "
                         f"({max(4, round(4.5 * 2 * CLEARANCE / THROW_SPEED / run.step))} asked)",
                         f"largest restitution error {error:.1e}", "within 2 %: " + ("yes" if error <= 0.02 else "no")])
    for direction, wall in (((0, -1, 0), "lower"), ((0, 0, -1), "far")):
        run = thrown_box(direction)
        impacts = run.joint.impacts()
        jump = first_jump(run, int(np.argmax(np.abs(direction))))
        error = abs(jump / impact_restitution(run.joint.joint.law, THROW_SPEED) - 1.0)
        first = sum(i.onset_time == impacts[0].onset_time for i in impacts)
        rows.append([f"box thrown flat onto its {wall} wall, no gravity, 1 contact duration",
                     f"{first} corners in the first impact step", f"restitution error {error:.1e}",
                     "within 2 %: " + ("yes" if error <= 0.02 and first == 4 else "no")])
    for label, joint, share, corners in (("slider", resting().joint, 0.5, 2), ("box", resting_box(), 0.25, 4)):
        out = joint.outputs()
        held = [o["normal_force"][o["time"] > 0.01] for o in out.values() if o["normal_force"].any()]
        error = max(np.abs(f / (share * MASS * G) - 1.0).max() for f in held)
        after = len(joint.impacts()) - corners
        rows.append([f"{label} resting flat on its lower wall, 1e-4 s, 0.05 s",
                     f"{len(held)} corners held, {after} impacts after their onsets",
                     f"each reaction off m g {'/ 2' if corners == 2 else '/ 4'} by {error:.1e} after 100 steps",
                     "yes" if after == 0 and len(held) == corners and error <= 1e-6 else "no"])
    run = resting(velocity=0.05)
    t = run.states[:, 0]
    path = np.abs(run.states[:, 1] - 0.05 * t).max()
    rows.append(["slider held on its lower wall sliding at 0.05 m/s, frictionless, 1e-4 s, 0.05 s",
                 f"{len(run.joint.impacts()) - 2} impacts after the onsets", f"x off x0 + v0 t by {path:.1e} m",
                 "yes" if path < 1e-9 else "no"])
    run, energy = elastic()
    drift = float(np.abs(energy - 1.0).max())
    rows.append(["elastic slider (cr 1) spinning at 2 rad/s across its guide, 1e-5 s, 0.05 s",
                 f"{len(run.joint.impacts())} corner impacts", f"energy change {drift:.1e}",
                 "within 1 %: " + ("yes" if drift <= 0.01 else "no")])
    return rows
