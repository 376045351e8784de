"""The impulse contact mode's scenes for the spatial revolute joint (``slices``), and their
rows of ``python -m validation.cost modes`` (tests/test_impulse_spatial.py asserts on the
same runs).

Source problems, each with an exact reference: a steel journal 30 mm long, of 9.9 mm in a
10 mm bearing held by the ground (c = 0.1 mm), in four slices, held axially
(``constrainAxial``).  Thrown flat across the bearing, its slices hit at once, the journal's
velocity jumping by the law's restitution (:func:`exuclear.timescales.impact_restitution`);
at rest under gravity the slices share the weight as a rigid journal's symmetric split,
``m g / 4``; elastic (cr 1) and tumbling, it keeps its energy.
"""
from __future__ import annotations

from typing import Any, NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import ObjectGround
from exudyn.utilities import InertiaCylinder

import exuclear
from exuclear.engine.impulse_group import ImpulsePairsHandle
from exuclear.timescales import closed_form_impact, impact_restitution
from validation.cost._joint_type_scenes import G, solve
from validation.cost._translational_scenes import first_jump

#: The journal's and the bearing's radii and the bearing's length [m]; the slices.
JOURNAL, BEARING, LENGTH, SLICES = 9.9e-3, 10e-3, 30e-3, 4
CLEARANCE = BEARING - JOURNAL
#: A steel journal as long as its bearing [kg].
INERTIA = InertiaCylinder(7850.0, LENGTH, JOURNAL, axis=2)
MASS = INERTIA.mass
#: The zoo's law: Hertz with Lankarani-Nikravesh damping.
LAW = {"law": "hertz+lankarani-nikravesh", "cr": 0.9}
#: The speed [m/s] the journal is thrown at across the bearing.
THROW_SPEED = 0.3


class Run(NamedTuple):
    """A run: the joint, the journal's states (t, position (3), velocity (3), angular
    velocity (3)) at the start and each step's end, and the step [s]."""

    joint: ImpulsePairsHandle
    states: np.ndarray
    step: float


def journal(velocity: Any = (0.0, 0.0, 0.0), spin: Any = (0.0, 0.0, 0.0), offset: Any = (0.0, 0.0, 0.0),
            gravity: float = 0.0, **law: Any) -> tuple[exu.MainSystem, ImpulsePairsHandle, list]:
    """The journal in its bearing along z (centred at the origin), its centre at ``offset``
    [m] moving at ``velocity`` [m/s] and turning at ``spin`` [rad/s], gravity ``-gravity``
    along y, held axially, in the impulse mode.  Returns mbs, the joint and the list its
    states are recorded in."""
    mbs, joint, states = spatial_journal(velocity, spin, offset, (0.0, -gravity, 0.0), constrainAxial=True,
                                         contact_mode="impulse", **law)
    if not isinstance(joint, ImpulsePairsHandle):
        raise RuntimeError(f"the joint is not in the impulse mode: {type(joint).__name__}")
    return mbs, joint, states


def spatial_journal(velocity: Any, spin: Any, offset: Any, gravity: Any,
                    **joint: Any) -> tuple[exu.MainSystem, Any, list]:
    """The journal of :func:`journal` under ``gravity`` [m/s^2] (global), with the joint's
    options ``joint`` (the law's over :data:`LAW`; ``constrainAxial``, ``contact_mode``,
    ``axial_clearance``, ...).  Returns mbs, the joint and the list its states (t, position
    (3), velocity (3), angular velocity (3)) are recorded in."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.CreateRigidBody(inertia=INERTIA, referencePosition=[0, 0, 0], initialDisplacement=list(offset),
                               initialVelocity=list(velocity), initialAngularVelocity=list(spin),
                               gravity=list(gravity))
    handle = exuclear.CreateClearanceJoint(mbs, name="journal", itemNumbers=[ground, body], position=[0, 0, 0],
                                           axis=[0, 0, 1], journal_radius=JOURNAL, bearing_radius=BEARING,
                                           length=LENGTH, slices=SLICES, **{**LAW, **joint})
    mbs.Assemble()
    node = mbs.GetObject(body)["nodeNumber"]
    states: list = []  # Exudyn calls the post-step function at the start too
    ov = exu.OutputVariableType

    def post_step(mbs: exu.MainSystem, t: float) -> bool:
        states.append((t, *(x for q in (ov.Position, ov.Velocity, ov.AngularVelocity)
                            for x in mbs.GetNodeOutput(node, q))))
        return True
    mbs.SetPostStepUserFunction(post_step)
    return mbs, handle, states


def thrown_flat(durations: float = 10.0) -> Run:
    """No gravity: the journal thrown from the bearing's centre along -y at
    :data:`THROW_SPEED`, parallel to its bearing, at steps of ``durations`` contact durations,
    across the clearance and back twice."""
    mbs, joint, states = journal(velocity=(0.0, -THROW_SPEED, 0.0))
    step = durations * closed_form_impact(joint.joint.law, MASS, THROW_SPEED)[1]
    solve(mbs, step, max(4.5 * 2 * CLEARANCE / THROW_SPEED, 4 * step))
    return Run(joint, np.array(states), step)


def resting(step: float = 1e-4, end: float = 0.05) -> Run:
    """Gravity -y, the journal flat on the bearing's bottom at t = 0."""
    mbs, joint, states = journal(offset=(0.0, -CLEARANCE, 0.0), gravity=G)
    solve(mbs, step, end)
    return Run(joint, np.array(states), step)


def elastic(step: float = 1e-5, end: float = 0.02) -> tuple[Run, np.ndarray]:
    """cr 1, no gravity: the journal thrown across and along its bearing's plane while it
    tilts about x (20 rad/s: the slices at its ends move 0.2 m/s apart) rattles in its
    bearing; returns the run and its kinetic energy at each state over the start's."""
    mbs, joint, states = journal(velocity=(0.05, -0.3, 0.0), spin=(20.0, 0.0, 0.0), cr=1.0)
    solve(mbs, step, end)
    s = np.array(states)
    inertia = np.asarray(INERTIA.inertiaTensor, dtype=float)
    spin = s[:, 7:10]  # global; the journal turns about x by less than 2c / L, its inertia taken as the start's
    energy = 0.5 * MASS * (s[:, 4:7] ** 2).sum(axis=1) + 0.5 * np.einsum("ij,jk,ik->i", spin, inertia, spin)
    return Run(joint, s, step), energy / energy[0]


def spatial_rows() -> list[list[str]]:
    """The rows of ``python -m validation.cost modes`` for the spatial revolute joint: target,
    count, measured, met (the law's restitution within 2 %, the static split, the issue's 1 %)."""
    run = thrown_flat()
    impacts = run.joint.impacts()
    error = abs(first_jump(run, 1) / impact_restitution(run.joint.joint.law, THROW_SPEED) - 1.0)
    first = sum(i.onset_time == impacts[0].onset_time for i in impacts)
    rows = [[f"journal of {SLICES} slices thrown flat across its bearing, no gravity, 10 contact durations",
             f"{first} slices in the first impact step", f"restitution error {error:.1e}",
             "within 2 %: " + ("yes" if error <= 0.02 and first == SLICES else "no")]]
    run = resting()
    held = [o["normal_force"][o["time"] > 0.01] for o in run.joint.outputs().values()]
    error = max(np.abs(f / (MASS * G / SLICES) - 1.0).max() for f in held)
    after = len(run.joint.impacts()) - SLICES
    rows.append([f"journal of {SLICES} slices resting on its bearing's bottom, 1e-4 s, 0.05 s",
                 f"{after} impacts after the onsets", f"each slice's reaction off m g / {SLICES} by {error:.1e}",
                 "yes" if after == 0 and error <= 1e-6 else "no"])
    for step in (1e-5, 2.5e-6):
        run, energy = elastic(step=step)
        drift = float(np.abs(energy - 1.0).max())
        rows.append([f"elastic journal (cr 1) tilting at 20 rad/s across its bearing, {step:g} s, 0.02 s",
                     f"{len(run.joint.impacts())} slice impacts", f"energy change {drift:.1e}",
                     "within 1 %: " + ("yes" if drift <= 0.01 else "no")])
    return rows
