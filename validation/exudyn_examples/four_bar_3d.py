"""Spatial four-bar mechanism, after Exudyn's example
main/pythonDev/Examples/fourBarMechanism3D.py (jgerstmayr/EXUDYN).

The example: three equal cuboid links (1 m x 0.1 m x 0.1 m, density 5000 kg/m^3, 50 kg
each) on Euler-parameter nodes form a square with the ground: the crank (link 0) stands
on the ground point (0, 0, 0), the coupler (link 1) lies along the top from (0, 1, 0) to
(1, 1, 0), the rocker (link 2) hangs from (1, 1, 0) down to the ground point (1, 0, 0).
Four ``ObjectJointGeneric`` revolute joints (constrained axes [1, 1, 1, 1, 1, 0]: rotation
about z free) close the loop; gravity [0.1, -9.81, 0] m/s^2 (the example's small x
component sets the square in motion); all start at rest.  The loop is over-constrained
(3 redundant constraints); the example's header names the cures: ignore the singular
Jacobian, or hold only x and y in the last joint (rocker - ground).  Generalized-alpha
(Exudyn's default, spectral radius 0.9), modified Newton, step 1e-3 s.

Kept: bodies, gravity, solver, step, modified Newton; the joints with the example's cure 3
(the last joint [1, 1, 0, 0, 0, 0]): as written, Exudyn 1.13.6 runs the redundant loop
past 0.1 s but stops before 2 s ("GeneralMatrixEXUdense::Solve(...): matrix is not
factorized!").  With the clearance joint the last joint is a full revolute joint again:
the clearance joint holds nothing out of plane, so the loop has no redundant constraint
and the rocker needs all five.
Changed: the example's ``AddRigidBody`` is written with its successor
``mbs.CreateRigidBody``; no renderer, no real-time simulation, no solution file; the end
time.  The example's 20 s is a real-time viewing length (``simulateInRealtime = True``);
the zoo's default is :data:`END_TIME` = 1.5 s: the square leaves its unstable upright
position and the crank turns from 90 deg to about 40 deg.  At t = 1.70 s the crank passes
0 deg, the parallelogram's change point (crank tip on the rocker's ground pivot), where
the joint load of the toggle reaches 113 kN and the clearance joint's penetration 0.41 c,
converged (0.408 c at the example's 1e-3 s, 0.395 c at simulate's automatic 8.2e-5 s,
0.407 c at 2e-5 s): physical, but above the zoo's 0.1 c rule for a wrong step, so the
zoo's default run stops before it (``end_time=2.0`` runs through it).  Replaced: the joint
between the coupler and the rocker at (1, 1, 0), axis z (both bodies move): the bearing
in the coupler, the journal on the rocker; a pin of R_B = 20 mm (the example draws the
joint axes with radius 0.2 w), a bearing as long as the links are wide (L = w = 0.1 m),
40 um radial clearance.  ``constrainAxial=False`` (the default): the coupler is held along
z and against tilt by its joint to the crank, the rocker by its joint to the ground, so
nothing is left unheld; the axial constraint would restore the loop's three redundant
constraints, which the clearance joint removes.

Over 1.5 s the example's settings reach the end with a
largest penetration of 0.067 c (8.6 kN, the first contact after the 50 kg links fall
across the gap); ``exuclear.simulate`` (auto step 8.2e-5 s, with the joint's
AccuracyWarning about steps it could not shorten) 0.061 c.

::

    (0, 1) o-------- link 1 (coupler) --------o (1, 1)  clearance joint, axis z
           |                                  |
     link 0 (crank)                     link 2 (rocker)
           |                                  |
    ground o (0, 0)                    ground o (1, 0)
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import exudyn.utilities as eu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid, ObjectJointGeneric

import exuclear

from ._common import (
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    joint_parameters,
    register,
    rigid_body_energy,
    scaled_end,
    solver_settings_like,
)

EXAMPLE = "main/pythonDev/Examples/fourBarMechanism3D.py"
BODIES = "mbs.CreateRigidBody (NodeRigidBodyEP), ObjectJointGeneric revolute joints, closed (redundant) loop"
REPLACED = "coupler (link 1) - rocker (link 2) at (1, 1, 0), axis z"

DENSITY, LENGTH, WIDTH = 5000.0, 1.0, 0.1  # the example's values (SI)
GRAVITY = (0.1, -9.81, 0.0)                # the example's gravity with its disturbance [m/s^2]
#: The example's step [s]; the zoo's end time [s] (module docstring: the example's 20 s is
#: a real-time viewing length).
STEP, END_TIME = 1e-3, 1.5
#: Our pin: bearing radius (the example's drawn axis radius 0.2 w), radial clearance,
#: bearing length (the links' width) [m].
BEARING_RADIUS, CLEARANCE, BEARING_LENGTH = 0.2 * WIDTH, 40e-6, WIDTH
#: The example's revolute joint: all but the rotation about the joint's z axis held.
REVOLUTE_Z = [1, 1, 1, 1, 1, 0]
#: The example's cure 3 for its last joint (rocker - ground): x and y only, which removes
#: the closed loop's three redundant constraints (z, rotation about x and y).
PLANAR_CLOSURE = [1, 1, 0, 0, 0, 0]


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    inertia = eu.InertiaCuboid(DENSITY, [LENGTH, WIDTH, WIDTH])  # centre of mass at the link's middle
    half = 0.5 * LENGTH
    # (centre, rotation about z) of crank, coupler, rocker; each link's local x runs along it
    poses = [([0.0, half, 0.0], 0.5 * math.pi), ([half, LENGTH, 0.0], 0.0), ([LENGTH, half, 0.0], -0.5 * math.pi)]
    crank, coupler, rocker = (mbs.CreateRigidBody(inertia=inertia, referencePosition=p,
                                                  referenceRotationMatrix=eu.RotationMatrixZ(angle),
                                                  gravity=list(GRAVITY), nodeType=exu.NodeType.RotationEulerParameters)
                              for p, angle in poses)

    def marker(body: Any, local: list[float]) -> Any:
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=local))

    def revolute(m0: Any, m1: Any) -> None:
        mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=REVOLUTE_Z))

    revolute(marker(ground, [0, 0, 0]), marker(crank, [-half, 0, 0]))
    revolute(marker(crank, [half, 0, 0]), marker(coupler, [-half, 0, 0]))
    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="coupler-rocker", itemNumbers=[coupler, rocker],
                                              position=[LENGTH, LENGTH, 0.0], axis=[0, 0, 1],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        revolute(marker(coupler, [half, 0, 0]), marker(rocker, [-half, 0, 0]))
    # the ideal loop's last joint holds x and y only (the example's cure 3, module docstring);
    # with the clearance joint the loop is open out of plane and the rocker needs all five
    mbs.AddObject(ObjectJointGeneric(markerNumbers=[marker(rocker, [half, 0, 0]), marker(ground, [LENGTH, 0, 0])],
                                     constrainedAxes=REVOLUTE_Z if clearance else PLANAR_CLOSURE))
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    ss.timeIntegration.newton.useModifiedNewton = True  # the example's
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (Exudyn's default)

    def probe(m: exu.MainSystem) -> np.ndarray:
        """The example's sensor on the coupler (local (0, 0, 0.5 L)), x y z [m]."""
        return np.asarray(m.GetObjectOutputBody(coupler, exu.OutputVariableType.Position,
                                                localPosition=[0, 0, half]))

    return ZooModel("four_bar_3d", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), energy=rigid_body_energy([crank, coupler, rocker], [inertia] * 3, GRAVITY),
                    probe_bound=PROBE_BOUND_CARRIED)
