"""Exudyn's ``TestModels/genericJointUserFunctionTest.py``: a chain of five rigid bodies, driven.

The model as Exudyn writes it: five ``ObjectRigidBody`` (Euler-parameter nodes, mass 2 kg,
inertia diag(6, 1, 6) kg m^2, 0.6 m long) along x under gravity -9.81 m/s^2 in y; the first
two joints ``GenericJoint`` whose offsets (a user function) turn the chain about x and z
over 4 s, the third a ``SphericalJoint``, the last two ``GenericJoint`` with one free rotation
each; all on ``MarkerBodyRigid``; generalized-alpha, spectral radius 0.6, modified Newton,
2.5 s at 5e-3 s.  Replaced: the spherical joint (between bodies 2 and 3) by
``exuclear.CreateSphericalClearanceJoint`` on the example's two rigid markers, a steel ball of
9.9 mm in a socket of 10 mm (c = 0.1 mm), Hertz with Lankarani-Nikravesh damping, cr 0.9.
The probe: the centre of body 5.

    ground =G= body 1 =G= body 2 -(o)- body 3 =G= body 4 =G= body 5
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import exudyn.utilities as eu
import numpy as np

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, register, solver_settings_like
from .spherical_joint_chain import BALL_RADIUS, INERTIA, JOINT, MASS, SOCKET_RADIUS, chain_settings

EXAMPLE = "TestModels/genericJointUserFunctionTest.py"
BODIES = "ObjectRigidBody (NodeRigidBodyEP), GenericJoint with offsetUserFunction, SphericalJoint"
REPLACED = "spherical joint between bodies 2 and 3"

N_BODIES, HALF_LENGTH = 5, 0.3
END_TIME, STEPS = 2.5, 500
DRIVE_PERIOD = 4.0  # [s], the example's


def _drive(mbs: exu.MainSystem, t: float, item: int, parameters: Any) -> list:
    """The example's offsets of the first two generic joints: a turn about x and z."""
    ramp = 0.5 * (1.0 - np.cos(t * 2.0 * math.pi / DRIVE_PERIOD))
    return [0, 0, 0, -0.5 * math.pi * ramp / N_BODIES, 0, -2.0 * math.pi * ramp / N_BODIES]


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(eu.ObjectGround())
    m_last = mbs.AddMarker(eu.MarkerBodyRigid(bodyNumber=ground, localPosition=[-HALF_LENGTH, 0, 0]))
    bodies, joint = [], None
    for i in range(N_BODIES):
        node = mbs.AddNode(eu.NodeRigidBodyEP(referenceCoordinates=[2 * i * HALF_LENGTH, 0, 0]
                                              + list(eu.eulerParameters0)))
        body = mbs.AddObject(eu.ObjectRigidBody(physicsMass=MASS, physicsInertia=INERTIA, nodeNumber=node,
                                                physicsCenterOfMass=[0, 0, 0]))
        mbs.AddLoad(eu.Gravity(markerNumber=mbs.AddMarker(eu.MarkerBodyMass(bodyNumber=body)), loadVector=[0, -9.81, 0]))
        m_pos = mbs.AddMarker(eu.MarkerBodyRigid(bodyNumber=body, localPosition=[-HALF_LENGTH, 0, 0]))
        if i < 2:
            mbs.AddObject(eu.GenericJoint(markerNumbers=[m_pos, m_last], constrainedAxes=[0 if i == 0 else 1, 1, 1, 1, 1, 1],
                                          offsetUserFunctionParameters=[0, 0, 0, 0, 0, 0], offsetUserFunction=_drive))
        elif i == 3:
            mbs.AddObject(eu.GenericJoint(markerNumbers=[m_last, m_pos], constrainedAxes=[1, 1, 1, 1, 0, 1]))
        elif i == 4:
            mbs.AddObject(eu.GenericJoint(markerNumbers=[m_last, m_pos], constrainedAxes=[1, 1, 1, 1, 1, 0]))
        elif clearance:
            joint = exuclear.CreateSphericalClearanceJoint(mbs, name="ball", itemNumbers=[m_last, m_pos],
                                                           ball_radius=BALL_RADIUS, socket_radius=SOCKET_RADIUS,
                                                           **{**JOINT, **joint_options})
        else:
            mbs.AddObject(eu.SphericalJoint(markerNumbers=[m_last, m_pos], constrainedAxes=[1, 1, 1]))
        m_last = mbs.AddMarker(eu.MarkerBodyRigid(bodyNumber=body, localPosition=[HALF_LENGTH, 0, 0]))
        bodies.append(body)
    mbs.Assemble()

    ss = chain_settings(END_TIME, STEPS, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Centre of body 5 (x, y, z) [m]."""
        return np.asarray(m.GetObjectOutputBody(bodies[-1], exu.OutputVariableType.Position, localPosition=[0, 0, 0]))

    return ZooModel("generic_joint_chain", mbs, ss, solver, joint, SOCKET_RADIUS - BALL_RADIUS if clearance else None,
                    probe, solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
