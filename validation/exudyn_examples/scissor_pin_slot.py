"""Exudyn's ``TestModels/scissorPrismaticRevolute2D.py``: a planar scissor lift whose crossing
points slide along a diagonal bar.

The model as Exudyn writes it (its last case, with Cartesian spring-dampers at the scissor's
pivots): n = 3 pairs of ``ObjectRigidBody2D`` bars (1.6 m, mass 1 kg, inertia 1 kg m^2), one
horizontal and one vertical per pair at (L i, L i), L = 0.8 m, joined by
``CartesianSpringDamper`` connectors (k = 1e4 N/m, d = 100 N s/m); a diagonal bar D at 45
degrees, held to the ground by a spring-damper, on which the vertical bars' centres of pairs 1
and 2 slide (``PrismaticJoint2D``, rotation free: a point on a line); the first vertical bar
turned by a rotational spring-damper, gravity 0.981 m/s^2 in -y; generalized-alpha (Newmark,
index-2 constraints), spectral radius 0.6, full Newton, 10 s at 0.02 s.  Replaced: the
sliding joint of pair 2 by ``exuclear.CreatePinSlotClearanceJoint``: a pin of 10 mm on the
vertical bar in a slot of 20.2 mm (c = 0.1 mm) along bar D, 1.6 m between its end centres,
Hertz with Lankarani-Nikravesh damping, cr 0.9.  The probe: the centre of pair 2's vertical
bar, which the joint carries.
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    Force,
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCartesianSpringDamper,
    ObjectConnectorCoordinate,
    ObjectConnectorCoordinateSpringDamper,
    ObjectGround,
    ObjectJointPrismatic2D,
    ObjectRigidBody2D,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, register, scaled_end, solver_settings_like

EXAMPLE = "TestModels/scissorPrismaticRevolute2D.py"
BODIES = "ObjectRigidBody2D, CartesianSpringDamper, PrismaticJoint2D"
REPLACED = "sliding joint of pair 2 on the diagonal bar (a pin in a slot)"

L, N_PAIRS, MASS, GRAVITY = 0.8, 3, 1.0, 0.981
K, D = 1e4, 1e2  # the spring-dampers' stiffness [N/m] and damping [N s/m]
END_TIME, STEPS = 10.0, 500
#: The replaced joint: pin radius, slot width, its end centres' distance and the pin's length [m].
PIN_RADIUS, SLOT_WIDTH, SLOT_LENGTH, PIN_LENGTH = 10e-3, 20.2e-3, 2 * L, 20e-3
JOINT = {"law": "hertz+lankarani-nikravesh", "cr": 0.9}


def _angle_spring(mbs: exu.MainSystem, t: float, item: int, u: float, v: float, k: float, d: float,
                  offset: float) -> float:
    """The example's rotational spring's user function: k (u + offset) + d v."""
    return k * (u + offset) + v * d


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    m_ground = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0, 0, 0]))
    last_v = last_h = m_ground
    body_d = m_d_com = None
    joint, probe_node = None, None
    for i in range(N_PAIRS):
        n_h = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[L * i, L * i, 0]))
        o_h = mbs.AddObject(ObjectRigidBody2D(mass=MASS, inertia=MASS, nodeNumber=n_h))
        m_h0, m_h1, m_h = (mbs.AddMarker(MarkerBodyPosition(bodyNumber=o_h, localPosition=[x, 0, 0])) for x in (-L, L, 0))
        n_v = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[L * i, L * i, 0.5 * math.pi]))
        o_v = mbs.AddObject(ObjectRigidBody2D(mass=MASS, inertia=MASS, nodeNumber=n_v))
        m_v0, m_v1 = (mbs.AddMarker(MarkerBodyPosition(bodyNumber=o_v, localPosition=[x, 0, 0])) for x in (-L, L))
        m_v = mbs.AddMarker(MarkerBodyRigid(bodyNumber=o_v, localPosition=[0, 0, 0]))
        if i == 0:
            n_d = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0.25 * math.pi]))
            body_d = mbs.AddObject(ObjectRigidBody2D(mass=MASS, inertia=MASS, nodeNumber=n_d))
            m_d_com = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_d, localPosition=[0, 0, 0]))
            mbs.AddLoad(Force(markerNumber=m_d_com, loadVector=[0, -MASS * GRAVITY, 0]))
            mbs.AddObject(ObjectConnectorCartesianSpringDamper(markerNumbers=[m_d_com, m_ground], stiffness=[K] * 3,
                                                               damping=[D] * 3))
            for m in (m_h, m_v):
                mbs.AddObject(ObjectConnectorCartesianSpringDamper(markerNumbers=[m, m_ground], stiffness=[K] * 3,
                                                                   damping=[D] * 3))
            n_ground = mbs.AddNode(NodePointGround(referenceCoordinates=[L, 0, 0]))
            m_coord = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0))
            mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[
                m_coord, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_h, coordinate=2))]))
            mbs.AddObject(ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[m_coord, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_v, coordinate=2))],
                stiffness=1e4, damping=10e3, offset=0.25 * math.pi, springForceUserFunction=_angle_spring))
        else:
            if i == N_PAIRS - 1 and clearance:
                joint = exuclear.CreatePinSlotClearanceJoint(
                    mbs, name="slot", itemNumbers=[body_d, o_v], position=[L * i, L * i, 0], axis=[0.5**0.5, 0.5**0.5, 0],
                    pin_radius=PIN_RADIUS, slot_width=SLOT_WIDTH, slot_length=SLOT_LENGTH, length=PIN_LENGTH,
                    **{**JOINT, **joint_options})
            else:
                m_d = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_d, localPosition=[i * L * 2**0.5, 0, 0]))
                mbs.AddObject(ObjectJointPrismatic2D(markerNumbers=[m_v, m_d], axisMarker0=[1, 0, 0],
                                                     normalMarker1=[0, 1, 0], constrainRotation=False))
            for pair in ((m_h, m_v), (m_h0, last_v), (m_v0, last_h)):
                mbs.AddObject(ObjectConnectorCartesianSpringDamper(markerNumbers=list(pair), stiffness=[K] * 3,
                                                                   damping=[D] * 3))
        last_h, last_v = m_h1, m_v1
        for m in (m_h, m_v):
            mbs.AddLoad(Force(markerNumber=m, loadVector=[0, -MASS * GRAVITY, 0]))
        probe_node = n_v
    mbs.Assemble()

    ss = example_settings(END_TIME, STEPS)
    ss.timeIntegration.newton.useModifiedNewton = False
    ss.timeIntegration.newton.numericalDifferentiation.forODE2connectors = True
    ss.timeIntegration.generalizedAlpha.useNewmark = True
    ss.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.6
    ss.timeIntegration.generalizedAlpha.computeInitialAccelerations = True
    ss.timeIntegration.adaptiveStep = False
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Centre of pair 2's vertical bar (x, y) [m]."""
        return np.asarray(m.GetNodeOutput(probe_node, exu.OutputVariableType.Position))[:2]

    return ZooModel("scissor_pin_slot", mbs, ss, solver, joint, 0.5 * SLOT_WIDTH - PIN_RADIUS if clearance else None,
                    probe, solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
