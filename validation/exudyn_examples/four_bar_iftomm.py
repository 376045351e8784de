"""Planar double four-bar, after Exudyn's IFToMM benchmark model
main/pythonDev/TestModels/fourBarMechanismIftomm.py (jgerstmayr/EXUDYN).

The example: five ``ObjectRigidBody2D`` bars (1 m, 1 kg, the inertia of a slender rod
``InertiaRodX``, m L^2 / 12): three cranks standing on the ground points (0, 0), (1, 0) and
(2, 0) and two couplers along the top from (0, 1) to (1, 1) and from (1, 1) to (2, 1);
seven ``RevoluteJoint2D`` close the two parallelograms (the middle crank, the left coupler's
right end and the right coupler's left end meet at (1, 1)); gravity -9.81 m/s^2 in y as a
mass-proportional load; the mechanism starts upright with the velocities of the cranks
turning clockwise at 1 rad/s (couplers at 1 m/s along x).  Generalized-alpha with spectral
radius 0.95 and initial accelerations, modified Newton, Exudyn's default Newton tolerances,
400 steps over 4 s (1e-2 s).  This is not the zoo's ``four_bar_3d`` (fourBarMechanism3D.py:
three 50 kg cuboids on 3D nodes, one redundant loop, started at rest): here five light
planar bars pass through the parallelograms' change points, the benchmark's subject.

Kept: bodies, loads, initial velocities, joints, solver and its settings.  Changed: no
renderer, no sensors, no plots.  ``energy`` is None although the model is conservative: the
example's coarse step with spectral radius 0.95 changes the total energy by 3.3e-5 of the
energy exchanged in the zoo's first 0.05 s (the example prints 0.114 J over its 4 s), above
the zoo's energy check (1e-5), which is meant for steps that resolve the motion.
Replaced: the middle crank's ground pivot at (1, 0): the bearing in the ground, the journal
on the middle crank; a pin of R_B = 20 mm in a 20 mm long bearing (the bars are drawn 0.1 m
wide), 50 um radial clearance.

The change point: at t = 0.71 s the cranks lie along the ground line and all five bars on
one line; there the joints' constraint Jacobian loses rank (their x equations are more
than the bodies' x coordinates), and only the middle crank chooses the parallelogram
branch.  Exudyn's index-3 generalized-alpha steps over it at the example's 1e-2 s (and at
1e-3 s and 1e-4 s), but its Newton stalls there at short steps: the ideal model at a
fixed 1e-5 s stops at t = 0.7144 s ("SolveDynamic terminated").  The clearance model takes
short steps at its contacts and meets the same stall: with the example's settings Exudyn
stops at t = 0.7115 s (its steps cut to 1e-8 s, the residual stalled at 1.5e-6 of the
force residual), and with an absolute Newton tolerance of 1e-8, 1e-6 or 1e-4 at 0.711 s to
0.714 s, so the tolerance is not the cause; the joint's note says where and why
(:func:`exuclear.engine.diagnostics.stopped_note`).  Up to the change point the clearance
model follows the ideal one: the tip of the left crank differs from the ideal model's by
at most a few clearances (``probe``).

::

    (0, 1) o---- coupler 1 ----o---- coupler 3 ----o (2, 1)
           |                   |(1, 1)             |
        crank 0            crank 2              crank 4
           |                   |                   |
    ground o (0, 0)     ground @ (1, 0)     ground o (2, 0)
                        clearance joint
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, joint_parameters, register, scaled_end, solver_settings_like

EXAMPLE = "main/pythonDev/TestModels/fourBarMechanismIftomm.py"
BODIES = "ObjectRigidBody2D, NodeRigidBody2D with initial velocities, two closed loops through a change point"
REPLACED = "ground - middle crank (bar 2) at (1, 0, 0), axis z"

MASS, LENGTH, GRAVITY, V0 = 1.0, 1.0, 9.81, 1.0  # the example's values (SI)
INERTIA = MASS * LENGTH**2 / 12  # the example's InertiaRodX(mass, L), about z
#: The example's settings: 4 s at 1e-2 s, spectral radius 0.95.
END_TIME, STEP, SPECTRAL_RADIUS = 4.0, 1e-2, 0.95
#: Our pin: bearing radius, radial clearance, bearing length [m].
BEARING_RADIUS, CLEARANCE, BEARING_LENGTH = 20e-3, 50e-6, 20e-3
#: The example's bars: (x, y, angle) of each centre and (vx, vy, omega) at the start;
#: the cranks 0, 2, 4 stand upright and turn clockwise, the couplers 1, 3 move along x.
BARS = [((0.0, 0.5, 0.5 * math.pi), (0.5 * V0, 0.0, -V0 / LENGTH)),
        ((0.5, 1.0, 0.0), (V0, 0.0, 0.0)),
        ((1.0, 0.5, 0.5 * math.pi), (0.5 * V0, 0.0, -V0 / LENGTH)),
        ((1.5, 1.0, 0.0), (V0, 0.0, 0.0)),
        ((2.0, 0.5, 0.5 * math.pi), (0.5 * V0, 0.0, -V0 / LENGTH))]
#: The example's joints in its order: (body, end) pairs, end -1 / +1 the bar's start / end
#: (local x = -L/2, +L/2), body None the ground at x = end [m]; index 1 is the one replaced.
JOINTS = [((None, 0.0), (0, -1)), ((None, 1.0), (2, -1)), ((None, 2.0), (4, -1)),
          ((0, 1), (1, -1)), ((1, 1), (3, -1)), ((2, 1), (3, -1)), ((3, 1), (4, 1))]
REPLACED_JOINT = 1


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    bars = []
    for reference, velocity in BARS:
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=list(reference), initialVelocities=list(velocity)))
        bar = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, physicsMass=MASS, physicsInertia=INERTIA))
        mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=bar)),
                                         loadVector=[0, -GRAVITY, 0]))
        bars.append(bar)
    ground = mbs.AddObject(ObjectGround())

    def marker(body: int | None, end: float) -> Any:
        if body is None:
            return mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[end, 0, 0]))
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=bars[body], localPosition=[0.5 * LENGTH * end, 0, 0]))

    joint = None
    for index, (first, second) in enumerate(JOINTS):
        if clearance and index == REPLACED_JOINT:
            (_ground, x), (crank, _start) = first, second
            joint = exuclear.CreateClearanceJoint(mbs, name="middle pivot", itemNumbers=[ground, bars[crank]],
                                                  position=[x, 0, 0], axis=[0, 0, 1],
                                                  **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                     **joint_options))
        else:
            mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[marker(*first), marker(*second)]))
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    ti = ss.timeIntegration
    ti.generalizedAlpha.spectralRadius = SPECTRAL_RADIUS  # the example's
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.newton.useModifiedNewton = True
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (Exudyn's default)

    def probe(m: exu.MainSystem) -> np.ndarray:
        """The tips (x, y) [m] of the left crank and of the middle crank, which carries the journal."""
        return np.concatenate([np.asarray(m.GetObjectOutputBody(bars[b], exu.OutputVariableType.Position,
                                                                 localPosition=[0.5 * LENGTH, 0, 0]))[:2]
                               for b in (0, 2)])

    return ZooModel("four_bar_iftomm", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
