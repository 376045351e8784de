"""3D rigid-body tutorial, after Exudyn's example main/pythonDev/Examples/rigidBodyTutorial3.py
(jgerstmayr/EXUDYN).

The example: two cuboids (density 5000 kg/m^3, 50 kg each) on Euler-parameter
nodes under gravity -9.81 m/s^2 in y.  Link 0 (1 m x 0.1 m x 0.1 m, reference point at
(0.5, 0, 0), centre of mass shifted by -0.25 m along its length) turns about the global z
axis at the origin; link 1 (0.1 m x 0.1 m x 1 m, centre at (1, 0, 0.5)) hangs from link 0's
end at (1, 0, 0) and turns about the global x axis.  Both bodies start at rest;
TrapezoidalIndex2, step 1e-3 s, 4 s.

Kept: bodies, inertias, joint positions and axes, solver, step and end time.  Changed:
the example's ``AddRigidBody`` / ``AddRevoluteJoint`` utilities are written with their
successors ``mbs.CreateRigidBody`` / ``mbs.CreateRevoluteJoint`` (the same kinds of items); no graphics,
no renderer, no solution file.  Replaced: the second revolute joint (link 0 to link 1 at
(1, 0, 0), axis x; both bodies move): the bearing on link 0, the journal on link 1, a pin
of R_B = 20 mm (the example draws the joint axis with radius 0.2 w) in a bearing as long
as the links are wide (L = w = 0.1 m), 40 um radial clearance.  ``constrainAxial=True``:
the clearance joint acts only in the plane normal to x, and nothing else in the model
holds link 1 along x or against tilt about y and z, which the replaced joint did; link 0
turns about z, which swings link 1 outwards along x and tilts it.  Without the
constraint (``constrainAxial=False``), ``exuclear.simulate`` stops at t = 0.134 s at the
joint's penetration limit; since branch drop it first warns (``OutOfPlaneWarning``) that
nothing holds the joint's axial translation and tilt, and names ``constrainAxial=True``.  ``friction="paper"`` (the paper's modified
Coulomb law) gives the registered variant ``rigid_body_tutorial3_friction``.

                   y
    ground o-------|-------- link 0 ---------o (1, 0, 0) clearance joint, axis x
       axis z                                 \\
                                               link 1 (along z, turns about x)
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import exudyn.utilities as eu
import numpy as np

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

EXAMPLE = "main/pythonDev/Examples/rigidBodyTutorial3.py"
BODIES = "mbs.CreateRigidBody (NodeRigidBodyEP, COM offset), mbs.CreateRevoluteJoint, constrainAxial"
REPLACED = "second revolute joint, link 0 to link 1 at (1, 0, 0), axis x"

DENSITY, LENGTH, WIDTH, GRAVITY = 5000.0, 1.0, 0.1, 9.81  # the example's values (SI)
#: The example's settings: TrapezoidalIndex2, 4 s at 1e-3 s.
END_TIME, STEP = 4.0, 1e-3
#: Our pin: bearing radius (the example's drawn axis radius 0.2 w), radial clearance,
#: bearing length (the links' width) [m].
BEARING_RADIUS, CLEARANCE, BEARING_LENGTH = 0.2 * WIDTH, 40e-6, WIDTH


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    gravity = [0, -GRAVITY, 0]
    inertia0 = eu.InertiaCuboid(DENSITY, [LENGTH, WIDTH, WIDTH]).Translated([-0.25 * LENGTH, 0, 0])
    link0 = mbs.CreateRigidBody(inertia=inertia0, referencePosition=[0.5 * LENGTH, 0, 0], gravity=gravity,
                                nodeType=exu.NodeType.RotationEulerParameters)
    mbs.CreateRevoluteJoint(itemNumbers=[ground, link0], position=[0, 0, 0], axis=[0, 0, 1])
    inertia1 = eu.InertiaCuboid(DENSITY, [WIDTH, WIDTH, LENGTH])
    link1 = mbs.CreateRigidBody(inertia=inertia1, referencePosition=[LENGTH, 0, 0.5 * LENGTH], gravity=gravity,
                                nodeType=exu.NodeType.RotationEulerParameters)
    position, axis = [LENGTH, 0, 0], [1, 0, 0]
    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="link0-link1", itemNumbers=[link0, link1], position=position,
                                              axis=axis,
                                              **{"constrainAxial": True,  # the docstring says why
                                                 **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                    **joint_options)})
    else:
        mbs.CreateRevoluteJoint(itemNumbers=[link0, link1], position=position, axis=axis)
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.TrapezoidalIndex2  # the example's

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Tip of link 1 (the example's sensor, local (0, 0, 0.5)), x y z [m]."""
        return np.asarray(m.GetObjectOutputBody(link1, exu.OutputVariableType.Position,
                                                localPosition=[0, 0, 0.5 * LENGTH]))

    return ZooModel("rigid_body_tutorial3", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED,
                    energy=rigid_body_energy([link0, link1], [inertia0, inertia1], gravity))


register(build, name="rigid_body_tutorial3_friction", friction="paper")
