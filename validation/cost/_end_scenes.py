"""The impulse contact mode's scenes at the ends of a joint: the spatial revolute joint's end
faces (``axial_clearance``) and a translational joint's finite guide (``guide_length``), each
in either mode (tests/test_impulse_ends.py asserts on the same runs; ``python -m
validation.cost modes_ends`` sets each against the compliant joint converged).

Source problems, each with an exact reference:

- the journal of :mod:`validation.cost._spatial_scenes` (30 mm of 9.9 mm in a 10 mm bearing,
  four slices) free along its axis with an axial play of 0.2 mm and shoulders of 12 mm
  (docs/physics.md section 9.6).  Thrown along the axis, a shoulder's impact on its end face
  holds the law's restitution; under a steady axial load (gravity along -z) the face carries
  ``m g``; elastic (cr 1) and thrown along and across the axis while it tilts, it keeps its
  energy; with Coulomb friction (mu 0.2), spinning on its face under that load it slows at
  ``mu m g R_e / I_zz`` (eq. (51)) and sticks, and an axial impact takes
  ``mu (1 + e) m v R_e`` from its spin's angular momentum while the spin slides through
  (Brach's law);
- the planar slider of :mod:`validation.cost._translational_scenes` (a 50 mm steel block,
  c = 0.1 mm) resting on its lower wall under gravity and sliding frictionless at 2.5 m/s
  out of a guide 0.15 m long.  While its lower corners are inside, each carries
  ``m g / 2``; once its front corner has passed the end, the block rests on its rear corner
  alone, a rigid body on one frictionless point (the reference: :func:`one_corner`, Newton's
  laws integrated by SciPy); once both have passed it, it flies free: a parabola.  Flying
  back into the guide, a corner inside hits its wall at the law's restitution while one
  beyond the end has none.
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from validation.cost._joint_type_scenes import G, solve
from validation.cost._spatial_scenes import CLEARANCE, INERTIA, spatial_journal
from validation.cost._translational_scenes import CLEARANCE as GUIDE_CLEARANCE
from validation.cost._translational_scenes import LAW as GUIDE_LAW
from validation.cost._translational_scenes import MASS as SLIDER_MASS
from validation.cost._translational_scenes import SIDE

#: The journal's total axial play and its shoulders' outer radius [m].
AXIAL_PLAY, SHOULDER = 2e-4, 12e-3
#: The speed [m/s] the journal is thrown at along its axis.
AXIAL_SPEED = 0.2
#: The end faces' friction: Coulomb's, as the other joint types' friction scenes
#: (validation/cost/_friction_scenes.py).
FACE_MU = 0.2
#: The guide's length [m], and the slider's speed along it [m/s]: its front corner passes the
#: guide's end at ``(GUIDE / 2 - SIDE / 2) / SLIDE_SPEED`` = 20 ms, its rear one some 20 ms
#: later, the block tilted by 0.05 rad, its rear corner's reaction still 0.36 m g.
GUIDE, SLIDE_SPEED = 0.15, 2.5
#: The planar slider's moment of inertia [kg m^2] (a square block: m (L^2 + H^2) / 12).
SLIDER_INERTIA = SLIDER_MASS * SIDE**2 / 6.0


class Run(NamedTuple):
    """A run: the joint, the body's states at the start and each step's end (the journal: t,
    position (3), velocity (3), angular velocity (3); the planar slider: t, x, y, angle,
    their rates), and the step [s]."""

    joint: Any
    states: np.ndarray
    step: float


def journal(velocity: Any = (0.0, 0.0, 0.0), spin: Any = (0.0, 0.0, 0.0), offset: Any = (0.0, 0.0, 0.0),
            gravity: Any = (0.0, 0.0, 0.0), mode: str = "impulse", **law: Any) -> tuple[exu.MainSystem, Any, list]:
    """The journal in its bearing along z (centred at the origin) with end faces, its centre at
    ``offset`` [m] moving at ``velocity`` [m/s] and turning at ``spin`` [rad/s] under
    ``gravity`` [m/s^2] (global), in contact mode ``mode``.  Returns mbs, the joint and the
    list its states are recorded in."""
    return spatial_journal(velocity, spin, offset, gravity, axial_clearance=AXIAL_PLAY, shoulder_radius=SHOULDER,
                           contact_mode=mode, **law)


def face_period(joint: Any) -> float:
    """The elastic contact duration [s] of the journal on a face, ``pi sqrt(m / K_f)``."""
    stiffness = 2.0 * joint.joint.law.E_star * SHOULDER  # eq. (52)
    return math.pi * math.sqrt(INERTIA.mass / stiffness)


def thrown_along(durations: float = 10.0, mode: str = "impulse", step: float | None = None) -> Run:
    """No gravity: the journal thrown from the centre along +z at :data:`AXIAL_SPEED` (its
    shoulder at z = -L/2 meets that face after ``g / 2``), at steps of ``durations`` face
    contact durations (or ``step``), across the axial play and back twice."""
    mbs, joint, states = journal(velocity=(0.0, 0.0, AXIAL_SPEED), mode=mode)
    step = durations * face_period(joint) if step is None else step
    solve(mbs, step, max(4.5 * AXIAL_PLAY / AXIAL_SPEED, 4 * step))
    return Run(joint, np.array(states), step)


def resting_on_face(step: float = 1e-4, end: float = 0.05, mode: str = "impulse") -> Run:
    """Gravity along -z: the journal's shoulder at z = +L/2 on its face at t = 0 (the journal
    at z = -g / 2), centred across its bearing (the slices never touch)."""
    mbs, joint, states = journal(offset=(0.0, 0.0, -0.5 * AXIAL_PLAY), gravity=(0.0, 0.0, -G), mode=mode)
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def rattle(step: float = 1e-5, end: float = 0.02, mode: str = "impulse") -> tuple[Run, np.ndarray]:
    """cr 1, no gravity: the journal thrown along its axis and across it while it tilts about
    x (5 rad/s) rattles between its end faces and its bearing's wall; returns the run and its
    kinetic energy at each state over the start's."""
    mbs, joint, states = journal(velocity=(0.02, -0.1, AXIAL_SPEED), spin=(5.0, 0.0, 0.0), mode=mode, cr=1.0)
    solve(mbs, step, end)
    s = np.array(states)
    inertia = np.asarray(INERTIA.inertiaTensor, dtype=float)
    spin = s[:, 7:10]  # global; the journal turns about x by less than 2c / L, its inertia taken as the start's
    energy = 0.5 * INERTIA.mass * (s[:, 4:7] ** 2).sum(axis=1) + 0.5 * np.einsum("ij,jk,ik->i", spin, inertia, spin)
    return Run(joint, s, step), energy / energy[0]


def guide_slider(x0: float, y0: float, velocity: Any, gravity: float,
                 mode: str = "impulse") -> tuple[exu.MainSystem, Any, list]:
    """The planar slider in a ground guide :data:`GUIDE` long along x (centred at the origin),
    its centre at ``(x0, y0)`` moving at ``velocity`` (vx, vy, omega), gravity ``-gravity``
    along y, in contact mode ``mode``.  Returns mbs, the joint and the list its states (t, x,
    y, angle, their rates) are recorded in."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[x0, y0, 0],
                                       initialVelocities=list(velocity)))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=SLIDER_MASS, inertia=SLIDER_INERTIA))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
                      loadVector=[0, -SLIDER_MASS * gravity, 0]))
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, name="guide", itemNumbers=[ground, body], position=[0, 0, 0],
                                                   slider_length=SIDE, slider_height=SIDE, clearance=GUIDE_CLEARANCE,
                                                   guide_length=GUIDE, contact_mode=mode, **GUIDE_LAW)
    mbs.Assemble()
    states: list = []
    ov = exu.OutputVariableType

    def post_step(mbs: exu.MainSystem, t: float) -> bool:
        states.append((t, *mbs.GetNodeOutput(node, ov.Coordinates), *mbs.GetNodeOutput(node, ov.Coordinates_t)))
        return True
    mbs.SetPostStepUserFunction(post_step)
    return mbs, joint, states


def past_the_end(step: float = 1e-4, end: float = 0.06, mode: str = "impulse") -> Run:
    """Gravity -y: the planar slider on its guide's lower wall at t = 0, sliding frictionless
    along +x at :data:`SLIDE_SPEED` out of a guide :data:`GUIDE` long (module docstring)."""
    mbs, joint, states = guide_slider(0.0, -GUIDE_CLEARANCE, (SLIDE_SPEED, 0.0, 0.0), G, mode)
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def entering(step: float = 1e-4, end: float = 0.005) -> Run:
    """No gravity: the slider, wholly beyond the guide's end (1 mm past it), flies into the
    guide at 1 m/s while it drops at 0.05 m/s: its rear corners enter at 1 ms, and at 2 ms its
    rear-lower corner, inside, hits the lower wall, while the front-lower corner, still
    beyond the end, has no wall."""
    mbs, joint, states = guide_slider(0.5 * GUIDE + 0.5 * SIDE + 1e-3, 0.0, (-1.0, -0.05, 0.0), 0.0)
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def front_leaves() -> float:
    """When the flat slider's front-lower corner passes the guide's end [s] (its centre at
    ``SLIDE_SPEED t``)."""
    return (0.5 * GUIDE - 0.5 * SIDE) / SLIDE_SPEED


def one_corner(t: np.ndarray, y0: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The slider on its rear-lower corner alone (frictionless, on the wall), from rest flat
    at centre height ``y0`` at ``t[0]``: its angle [rad], its centre's height [m] and the
    corner's reaction [N] at the times ``t``, by Newton's laws for the rigid block,
    integrated by SciPy's DOP853 to 1e-12.  The corner ``r = R(theta) (-L/2, -H/2)`` keeps
    its height, so ``y = y0 + r_y(0) - r_y(theta)``, with ``r_y' = r_x`` and
    ``r_y'' = -r_y``; the reaction ``N`` (up) has the moment ``r_x N``:
    ``m y'' = N - m g``, ``I theta'' = r_x N``, whence
    ``theta'' = r_x m (g + r_y omega^2) / (I + m r_x^2)`` and
    ``N = m (g - r_x theta'' + r_y omega^2)``.  Valid while ``N > 0``."""
    from scipy.integrate import solve_ivp

    half, m, inertia = 0.5 * SIDE, SLIDER_MASS, SLIDER_INERTIA

    def corner(theta: float) -> tuple[float, float]:
        """r_x, r_y of the rear-lower corner."""
        s, c = math.sin(theta), math.cos(theta)
        return -half * c + half * s, -half * s - half * c

    def alpha(theta: float, omega: float) -> float:
        rx, ry = corner(theta)
        return rx * m * (G + ry * omega * omega) / (inertia + m * rx * rx)

    sol = solve_ivp(lambda _, x: [x[1], alpha(x[0], x[1])], (float(t[0]), float(t[-1])), [0.0, 0.0],
                    method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t)
    theta, omega = sol.y
    ry0 = corner(0.0)[1]
    height = np.array([y0 + ry0 - corner(a)[1] for a in theta])
    reaction = np.array([m * (G - corner(a)[0] * alpha(a, w) + corner(a)[1] * w * w) for a, w in zip(theta, omega)])
    return theta, height, reaction


def rear_leaves(t0: float, y0: float) -> float:
    """When the rear-lower corner passes the guide's end [s], on its own tilt
    (:func:`one_corner` from the front corner's leaving at ``t0``): its x is the centre's,
    ``SLIDE_SPEED t`` (no force along x), plus ``r_x(theta)``."""
    t = np.linspace(t0, t0 + 2.0 * SIDE / SLIDE_SPEED, 4001)
    theta = one_corner(t, y0)[0]
    x = SLIDE_SPEED * t + 0.5 * SIDE * (np.sin(theta) - np.cos(theta))
    k = int(np.argmax(x > 0.5 * GUIDE))
    return float(t[k - 1] + (0.5 * GUIDE - x[k - 1]) / (x[k] - x[k - 1]) * (t[k] - t[k - 1]))


def axial_bounce(step: float, mode: str = "impulse") -> Run:
    """The comparison scene of the end faces: gravity -y, the journal flat on its bearing's
    bottom at t = 0 and thrown along its axis at :data:`AXIAL_SPEED`, bouncing between its
    end faces (cr 0.9) for 20 ms."""
    mbs, joint, states = journal(velocity=(0.0, 0.0, AXIAL_SPEED), offset=(0.0, -CLEARANCE, 0.0),
                                 gravity=(0.0, -G, 0.0), mode=mode)
    solve(mbs, step, 0.02)
    return Run(joint, np.array(states), step)


def spinning_bounce(step: float, mode: str = "impulse") -> Run:
    """The comparison scene of the end faces' friction: no gravity, the journal spinning at
    50 rad/s thrown along its axis at :data:`AXIAL_SPEED`, bouncing between its end faces
    (cr 0.9, Coulomb mu :data:`FACE_MU`, each impact taking spin) for 20 ms; the slices never
    touch."""
    mbs, joint, states = journal(velocity=(0.0, 0.0, AXIAL_SPEED), spin=(0.0, 0.0, 50.0), mode=mode,
                                 friction=f"coulomb:{FACE_MU}")
    solve(mbs, step, 0.02)
    return Run(joint, np.array(states), step)


#: The comparison scenes: name, the run at a step in a mode, the scene's step [s], the
#: positions compared (the state's columns, each times a length [m]), the play they are
#: measured in [m], and a rate compared as a share of its start (a column, or None).
COMPARED = (
    ("journal bouncing between its end faces, 20 ms", axial_bounce, 1e-4, ((1, 1.0), (2, 1.0), (3, 1.0)),
     CLEARANCE, None),
    ("spinning journal bouncing between its end faces with friction, 20 ms", spinning_bounce, 1e-4,
     ((1, 1.0), (2, 1.0), (3, 1.0)), CLEARANCE, 9),
    ("slider leaving a finite guide, 60 ms", lambda step, mode: past_the_end(step=step, mode=mode), 1e-4,
     ((1, 1.0), (2, 1.0), (3, 0.5 * SIDE)), GUIDE_CLEARANCE, None),
)


def _positions(run: Run, columns: Any, times: np.ndarray) -> np.ndarray:
    """The compared positions of ``run`` at ``times`` (linear between its states)."""
    return np.array([scale * np.interp(times, run.states[:, 0], run.states[:, k]) for k, scale in columns]).T


def compared_rows(refine: tuple[int, ...] = (1, 4), reference: int = 1024, check: int = 256) -> list[list[str]]:
    """Each comparison scene's rows: the impulse mode and the compliant joint at the scene's
    step over ``refine``, against the compliant joint at the step over ``reference`` (its
    distance from the one at the step over ``check`` says it has converged); the largest
    distance of the positions (the slider's turn as its corner's travel, ``L/2`` times the
    angle) over the run, in plays (c), and of the compared rate, as a share of its start, at
    the times two steps or more from the converged run's impacts."""
    rows = []
    for name, scene, step, columns, play, rate in COMPARED:
        converged = scene(step / reference, "compliant")
        times = converged.states[:: reference, 0]
        target = _positions(converged, columns, times)
        # the rate jumps at each impact, within the step that ends at or after it: compared in flight
        onsets = np.array([i.onset_time for i in converged.joint.impacts()])
        flight = np.array([not np.any(np.abs(t - onsets) <= 2.0 * step) for t in times])

        def distance(run: Run) -> str:
            text = f"{np.abs(_positions(run, columns, times) - target).max() / play:.3g}"
            if rate is not None:
                off = np.interp(times, run.states[:, 0], run.states[:, rate]) - \
                    np.interp(times, converged.states[:, 0], converged.states[:, rate])
                text += f"; spin {np.abs(off[flight]).max() / abs(converged.states[0, rate]):.2g} of its start"
            return text
        rows.append([name, f"compliant at step / {reference} (the converged run)",
                     f"{distance(scene(step / check, 'compliant'))} (compliant at step / {check})", "-"])
        for factor in refine:
            run = scene(step / factor, "impulse")
            rows.append([name, f"impulse at step / {factor}" if factor > 1 else f"impulse at {step:g} s",
                         distance(run), str(len(run.joint.impacts()))])
            rows.append([name, f"compliant at step / {factor}" if factor > 1 else f"compliant at {step:g} s",
                         distance(scene(step / factor, "compliant")), "-"])
    return rows


def spinning_on_face(spin: float = 50.0, step: float = 1e-4, end: float = 0.15) -> Run:
    """Gravity along -z: the journal's shoulder on the face at z = +L/2 from t = 0, spinning
    about the axis at ``spin`` [rad/s], with Coulomb friction :data:`FACE_MU`: the face's
    couple ``mu m g R_e`` slows it (docs/physics.md eq. (51)) until it sticks."""
    mbs, joint, states = journal(offset=(0.0, 0.0, -0.5 * AXIAL_PLAY), spin=(0.0, 0.0, spin),
                                 gravity=(0.0, 0.0, -G), friction=f"coulomb:{FACE_MU}")
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def spinning_impact(spin: float = 50.0, durations: float = 10.0) -> Run:
    """No gravity: the journal thrown along +z at :data:`AXIAL_SPEED` while spinning at
    ``spin`` [rad/s], with Coulomb friction :data:`FACE_MU`: its shoulder's impact on the face
    at z = -L/2 takes ``mu (1 + e) m v R_e`` out of its spin's angular momentum (the spin
    slides through the impact), until the next impact."""
    mbs, joint, states = journal(velocity=(0.0, 0.0, AXIAL_SPEED), spin=(0.0, 0.0, spin),
                                 friction=f"coulomb:{FACE_MU}")
    step = durations * face_period(joint)
    solve(mbs, step, 1.5 * AXIAL_PLAY / AXIAL_SPEED)
    return Run(joint, np.array(states), step)
