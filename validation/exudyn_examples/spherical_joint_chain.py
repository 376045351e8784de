"""Exudyn's ``TestModels/sphericalJointTest.py``: a chain of four rigid bodies on spherical joints.

The model as Exudyn writes it: four ``ObjectRigidBody`` (Euler-parameter nodes, mass 2 kg,
inertia diag(6, 1, 6) kg m^2, 0.6 m long) along x, hanging from the ground under gravity
-9.81 m/s^2 in y, each joined to the next by ``SphericalJoint`` 0.1 m off their axes in z (the
first one to the ground, holding y and z only); generalized-alpha, spectral radius 0.6,
modified Newton, 1 s at 1e-3 s.  Replaced: the last joint (between bodies 3 and 4) by
``exuclear.CreateSphericalClearanceJoint`` on the two bodies, a steel ball of 9.9 mm in a
socket of 10 mm (c = 0.1 mm), Hertz with Lankarani-Nikravesh damping, cr 0.9.  The probe:
the free end of body 4.

    ground -o- body 1 -o- body 2 -o- body 3 -(o)- body 4
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import exudyn.utilities as eu
import numpy as np

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, register, scaled_end, solver_settings_like

EXAMPLE = "TestModels/sphericalJointTest.py"
BODIES = "ObjectRigidBody (NodeRigidBodyEP), SphericalJoint"
REPLACED = "spherical joint between bodies 3 and 4"

N_BODIES, HALF_LENGTH, OFFSET_Z, MASS, INERTIA = 4, 0.3, 0.1, 2.0, [6.0, 1.0, 6.0, 0.0, 0.0, 0.0]
END_TIME, STEPS = 1.0, 1000
#: The replaced joint: ball and socket radius [m], the zoo's law and restitution.
BALL_RADIUS, SOCKET_RADIUS = 9.9e-3, 10e-3
JOINT = {"law": "hertz+lankarani-nikravesh", "cr": 0.9, "ball_material": "steel", "socket_material": "steel"}


def chain_settings(end: float, steps: int, end_time: float | None) -> exu.SimulationSettings:
    """The settings of Exudyn's rigid-body chain tests (this one and genericJointUserFunctionTest):
    generalized-alpha, spectral radius 0.6, modified Newton, index-3 constraints."""
    ss = example_settings(end, steps)
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.timeIntegration.generalizedAlpha.useIndex2Constraints = False
    ss.timeIntegration.generalizedAlpha.useNewmark = False
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.6
    scaled_end(ss, end_time)
    return ss


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(eu.ObjectGround())
    m_last = mbs.AddMarker(eu.MarkerBodyPosition(bodyNumber=ground, localPosition=[-HALF_LENGTH, 0, 0]))
    bodies, joint = [], None
    for i in range(N_BODIES):
        node = mbs.AddNode(eu.NodeRigidBodyEP(referenceCoordinates=[-HALF_LENGTH + 2 * i * HALF_LENGTH, 0, 0]
                                              + list(eu.eulerParameters0)))
        body = mbs.AddObject(eu.ObjectRigidBody(physicsMass=MASS, physicsInertia=INERTIA, nodeNumber=node))
        mbs.AddLoad(eu.Gravity(markerNumber=mbs.AddMarker(eu.MarkerBodyMass(bodyNumber=body)), loadVector=[0, -9.81, 0]))
        if i == N_BODIES - 1 and clearance:
            centre = [-HALF_LENGTH + (2 * i - 1) * HALF_LENGTH, 0, OFFSET_Z]
            joint = exuclear.CreateSphericalClearanceJoint(mbs, name="last", itemNumbers=[bodies[-1], body],
                                                           position=centre, ball_radius=BALL_RADIUS,
                                                           socket_radius=SOCKET_RADIUS, **{**JOINT, **joint_options})
        else:
            m_pos = (mbs.AddMarker(eu.MarkerNodePosition(nodeNumber=node)) if i == 0 else
                     mbs.AddMarker(eu.MarkerBodyPosition(bodyNumber=body, localPosition=[-HALF_LENGTH, 0, OFFSET_Z])))
            mbs.AddObject(eu.SphericalJoint(markerNumbers=[m_last, m_pos], constrainedAxes=[0, 1, 1] if i == 0 else
                                            [1, 1, 1]))
        m_last = mbs.AddMarker(eu.MarkerBodyPosition(bodyNumber=body, localPosition=[HALF_LENGTH, 0, OFFSET_Z]))
        bodies.append(body)
    mbs.Assemble()

    ss = chain_settings(END_TIME, STEPS, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Free end of body 4 (x, y, z) [m]."""
        return np.asarray(m.GetObjectOutputBody(bodies[-1], exu.OutputVariableType.Position,
                                                localPosition=[HALF_LENGTH, 0, OFFSET_Z]))

    return ZooModel("spherical_joint_chain", mbs, ss, solver, joint, SOCKET_RADIUS - BALL_RADIUS if clearance else None,
                    probe, solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
