"""Planar double pendulum, after Exudyn's example main/pythonDev/Examples/doublePendulum2D.py
(jgerstmayr/EXUDYN).

The example: two ``ObjectRigidBody2D`` links of 1 kg, inertia 1 kg m^2 (as the example
sets it), 1 m long, released from rest along the x axis under gravity -9.81 m/s^2 in y;
``RevoluteJoint2D`` from the ground to link 0 at (-0.5, 0) and from link 0 to link 1 at
(0.5, 0); gravity as point loads on the nodes; Exudyn's default solver (generalized-alpha,
spectral radius 0.9), 10000 steps over 10 s.

Kept: bodies, loads, joints, solver and step.  Changed: no renderer, no real-time
simulation (``simulateInRealtime``) and no solution file.  Replaced: the joint between
link 0 and link 1 (both moving): the bearing on link 0, the journal on link 1, a 10 mm
steel pin in a 10 mm long bearing with 50 um radial clearance (the links are drawn as
lines, so the pin is our choice).  ``friction="paper"`` (the paper's modified Coulomb law)
gives the registered variant ``double_pendulum_2d_friction``.

    ground o-------- link 0 --------o-------- link 1 --------
        (-0.5, 0)                (0.5, 0) clearance joint    (1.5, 0)
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    Force,
    MarkerBodyRigid,
    MarkerNodePosition,
    NodeRigidBody2D,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, joint_parameters, register, scaled_end, solver_settings_like

EXAMPLE = "main/pythonDev/Examples/doublePendulum2D.py"
BODIES = "ObjectRigidBody2D, NodeRigidBody2D"
REPLACED = "joint between link 0 and link 1 at (0.5, 0, 0), axis z"

MASS, INERTIA, LENGTH, GRAVITY = 1.0, 1.0, 1.0, 9.81  # the example's values (SI)
#: The example's settings: 10 s in 10000 steps.
END_TIME, STEPS = 10.0, 10000
#: Our pin: bearing radius, radial clearance, bearing length [m].
BEARING_RADIUS, CLEARANCE, BEARING_LENGTH = 10e-3, 50e-6, 10e-3


def _energy(nodes: list[int]) -> Any:
    """Kinetic and gravity potential energy [J] of the links (potential 0 at y = 0)."""
    def energy(mbs: exu.MainSystem) -> tuple[float, float]:
        kinetic = potential = 0.0
        for n in nodes:
            v = mbs.GetNodeOutput(n, exu.OutputVariableType.Velocity)
            w = mbs.GetNodeOutput(n, exu.OutputVariableType.AngularVelocity)[2]
            y = mbs.GetNodeOutput(n, exu.OutputVariableType.Position)[1]
            kinetic += 0.5 * MASS * (v[0] ** 2 + v[1] ** 2) + 0.5 * INERTIA * w ** 2
            potential += MASS * GRAVITY * y
        return kinetic, potential
    return energy


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0, 0])) for x in (0.0, LENGTH)]
    links = [mbs.AddObject(ObjectRigidBody2D(mass=MASS, inertia=INERTIA, nodeNumber=n)) for n in nodes]
    ground = mbs.AddObject(ObjectGround())
    half = 0.5 * LENGTH
    m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[-half, 0, 0]))
    m00 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=links[0], localPosition=[-half, 0, 0]))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[m_ground, m00]))
    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="elbow", itemNumbers=[links[0], links[1]],
                                              position=[half, 0, 0], axis=[0, 0, 1],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        m01 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=links[0], localPosition=[half, 0, 0]))
        m10 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=links[1], localPosition=[-half, 0, 0]))
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[m01, m10]))
    for n in nodes:
        mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=n)),
                          loadVector=[0, -MASS * GRAVITY, 0]))
    mbs.Assemble()

    ss = example_settings(END_TIME, STEPS)
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (Exudyn's default)

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Free end of link 1 (x, y) [m]."""
        return np.asarray(m.GetObjectOutputBody(links[1], exu.OutputVariableType.Position,
                                                localPosition=[half, 0, 0]))[:2]

    return ZooModel("double_pendulum_2d", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED, energy=_energy(nodes))


register(build, name="double_pendulum_2d_friction", friction="paper")
