"""Exudyn's ``TestModels/revoluteJointPrismaticJointTest.py``: a 3D chain of five bars joined by
revolute joints about turned axes and one prismatic joint.

The model as Exudyn writes it: five bars 0.4 m x 0.1 m x 0.1 m (1000 kg/m^3, 4 kg) from
``mbs.CreateRigidBody`` (Euler parameters) in a line along x under gravity -9.81 m/s^2 in y;
the joint at the start of bar ``i`` (``x = 0.4 i``, to the ground for ``i = 0``) an
``ObjectJointRevoluteZ`` in the frame ``A_i`` (unit, ``R_y(90 deg)``, ``R_z(90 deg)``,
``R_x(-90 deg)``, ``R_z(90 deg)``), except bar 2's: an ``ObjectJointPrismaticX`` in
``R_z(90 deg)`` (bar 2 slides along global y on bar 1's end), held by a
``CartesianSpringDamper`` (k = 500 N/m, d = 10 N s/m) between the two joint points; 20 N
along z at the chain's free end; generalized-alpha, spectral radius 0.8, modified Newton,
0.25 s at 1e-3 s.  Replaced: the prismatic joint by the spatial
``exuclear.CreatePrismaticClearanceJoint`` (bar 1 the guide, bar 2 the slider): a 0.1 m cube
of bar 2 at the joint point (the bar's cross-section, as long) in a channel with
``c = c_z = 0.5`` mm per side, corners ``K = 1e10 N/m^1.5`` with Lankarani-Nikravesh damping,
cr 0.9; the spring stays.  The end load bends the chain about two axes, so the cube is held
in its channel by corners on several walls at once.  The probe: bar 2's joint point, the
slider's centre.  It has no geometric bound (``probe_bound`` None): along the joint's axis
the slider hangs on the soft spring (three bars' weight on k = 500 N/m), so its place there
follows the whole chain's motion; across the gap the slider falls freely before its corners
take bar 2's moment (its joint point 0.5 g t^2 = 0.49 mm in the first 10 ms, the ideal
joint's 0.19 mm), and the chain's swing grows that start into millimetres along the axis
(2.7 mm at 50 ms; ``python -m validation.exudyn_examples`` reports it).

    ground o== bar 0 ==o== bar 1 ==[]== bar 2 ==o== bar 3 ==o== bar 4 ==> 20 N (z)
              revolute   revolute  prismatic  revolute   revolute
                                   (along y)
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadForceVector,
    MarkerBodyRigid,
    ObjectConnectorCartesianSpringDamper,
    ObjectJointPrismaticX,
    ObjectJointRevoluteZ,
)
from exudyn.rigidBodyUtilities import InertiaCuboid, RotationMatrixX, RotationMatrixY, RotationMatrixZ

import exuclear

from ._common import ZooModel, example_settings, register, scaled_end, solver_settings_like

EXAMPLE = "TestModels/revoluteJointPrismaticJointTest.py"
BODIES = "mbs.CreateRigidBody (NodeRigidBodyEP), ObjectJointRevoluteZ, ObjectJointPrismaticX"
REPLACED = "prismatic joint of bar 2 on bar 1 (a box in a channel, spatial)"

BARS, BAR_LENGTH, BAR_SIZE, DENSITY, GRAVITY = 5, 0.4, 0.1, 1000.0, 9.81  # [-, m, m, kg/m^3, m/s^2]
SPRING, DAMPER, END_LOAD = 500.0, 10.0, 20.0  # [N/m, N s/m, N]
#: The bar whose joint is prismatic, and the joints' frames (Exudyn's example).
PRISMATIC_BAR = 2
FRAMES = (np.eye(3), RotationMatrixY(0.5 * math.pi), RotationMatrixZ(0.5 * math.pi), RotationMatrixX(-0.5 * math.pi),
          RotationMatrixZ(0.5 * math.pi))
END_TIME, STEPS = 0.25, 250
#: The replaced joint: the play per side across both directions [m] and the corners' law.
CLEARANCE = 5e-4
JOINT = {"stiffness": 1e10, "exponent": 1.5, "damping": "lankarani-nikravesh", "cr": 0.9}


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    previous, end = mbs.CreateGround(), [0.0, 0.0, 0.0]  # the body before the joint and the joint's point on it
    inertia = InertiaCuboid(DENSITY, sideLengths=[BAR_LENGTH, BAR_SIZE, BAR_SIZE])
    bars, joint = [], None
    for i, frame in enumerate(FRAMES):
        bar = mbs.CreateRigidBody(inertia=inertia, referencePosition=[(i + 0.5) * BAR_LENGTH, 0.0, 0.0],
                                  gravity=[0.0, -GRAVITY, 0.0])
        start = [-0.5 * BAR_LENGTH, 0.0, 0.0]
        # the joint's markers in its frame (Exudyn's rotationMarker0/1, given as the markers' localHT)
        m0, m1 = (mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localHT=exu.HT(rotation=frame, translation=point)))
                  for body, point in ((previous, end), (bar, start)))
        if i != PRISMATIC_BAR:
            mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[m0, m1]))
        else:
            if clearance:
                joint = exuclear.CreatePrismaticClearanceJoint(
                    mbs, name="prismatic", itemNumbers=[previous, bar], position=[i * BAR_LENGTH, 0.0, 0.0],
                    axis=(frame @ [1.0, 0.0, 0.0]).tolist(), slider_length=BAR_SIZE, slider_height=BAR_SIZE,
                    slider_width=BAR_SIZE, clearance=CLEARANCE, **{**JOINT, **joint_options})
            else:
                mbs.AddObject(ObjectJointPrismaticX(markerNumbers=[m0, m1]))
            mbs.AddObject(ObjectConnectorCartesianSpringDamper(markerNumbers=[m0, m1], stiffness=[SPRING] * 3,
                                                               damping=[DAMPER] * 3))
        previous, end = bar, [0.5 * BAR_LENGTH, 0.0, 0.0]
        bars.append(bar)
    last = mbs.AddMarker(MarkerBodyRigid(bodyNumber=previous, localPosition=end))
    mbs.AddLoad(LoadForceVector(markerNumber=last, loadVector=[0.0, 0.0, END_LOAD]))
    mbs.Assemble()

    ss = example_settings(END_TIME, STEPS)
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    ss.timeIntegration.generalizedAlpha.computeInitialAccelerations = True
    ss.timeIntegration.newton.useModifiedNewton = True
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (SolveDynamic's default)
    slider = bars[PRISMATIC_BAR]

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Bar 2's joint point, the slider's centre (x, y, z) [m]."""
        return np.asarray(m.GetObjectOutputBody(slider, exu.OutputVariableType.Position,
                                                localPosition=[-0.5 * BAR_LENGTH, 0.0, 0.0]))

    return ZooModel("revolute_prismatic_chain", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver))
