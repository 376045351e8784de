"""ANCF cable clamped to a driven hub, after Exudyn's example
main/pythonDev/Examples/ANCFrotatingCable2D.py (jgerstmayr/EXUDYN).

::

      hub (10 mm cube, ObjectRigidBody2D), pinned to the ground (RevoluteJoint2D: here
      |   the clearance joint), its angle prescribed (CoordinateConstraint)
      v
      #==========================================   16 ObjectANCFCable2D elements,
      cable clamped to the hub (GenericJoint:       a 2 m steel strip 10 mm x 10 mm,
      x, y and the rotation about z)                released straight under gravity

The example: a 2 m steel cable (E = 2e11 Pa, 7800 kg/m^3, 10 mm x 10 mm, bending damping
0.02 EI) of 16 ``ObjectANCFCable2D`` elements under gravity -9.81 m/s^2 in y, clamped by
an ``ObjectJointGeneric`` (x, y and the rotation about z) to a hub, a 10 mm cube of
density 1000 kg/m^3 (1 g) made by ``mbs.CreateRigidBody(create2D=True)``; the hub is
pinned to the ground at the origin by an ``ObjectJointRevolute2D``, and a
``CoordinateConstraint`` sets its angle: 0 until 2 s, pi sin(pi t) rad from 2 s to 6 s
(the cable swings through +-180 deg), 0 after.  The angle is continuous, its rate is
not: it jumps from 0 to pi^2 rad/s at 2 s and back at 6 s, so the drive strikes the hub,
and the hub's pin takes the cable's impulse.  Generalized-alpha (Exudyn's default
spectral radius), step 2 ms, 10 s, modified Newton with relative tolerance 1e-6, sparse
solver.

Kept: all of it, built without the deprecated ``Cable2D`` / ``GenerateStraightLineANCFCable2D``
helpers (the same nodes, elements and mass-proportional loads), except: no renderer, no
solution file.  Replaced with ``clearance=True``: the hub's pin (its revolute joint to
the ground), where the cable's weight and, while the hub swings it, its centrifugal pull
load a real bearing: ``exuclear.CreateClearanceJoint(itemNumbers=[ground, hub])`` at the
origin, axis z, bearing on the ground, journal on the hub; the hub's angle stays
prescribed.  Pin: R_B = 4 mm in the 10 mm hub, L = 10 mm (the hub's and the cable's
width), c = 20 um.

The journal is the 1 g hub, whose contact period is microseconds, carrying a 1.56 kg
cable through a clamp.  At 2 s the drive's jump in rate drives the journal into its wall
within one step: a contact the example's 2 ms step cannot resolve and the joint's
shortest step (ten times Exudyn's minimum step) not either, which the joint's
AccuracyWarning says.  The impulse contact mode needs the trapezoidal rule (spectral radius
1), under which the angle's kink leaves the hub's rate alternating about pi^2 rad/s from step
to step for good, and the pin's force changing sign each step (the ideal pin's too): a
clearance joint cannot pull, and the mode stops the run at the strike, saying so
(tests/test_impulse_strike.py).
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodeRigid,
    NodePointGround,
    ObjectConnectorCoordinate,
    ObjectGround,
    ObjectJointGeneric,
    ObjectJointRevolute2D,
)
from exudyn.rigidBodyUtilities import InertiaCuboid

import exuclear

from .._common import (
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    joint_parameters,
    register,
    scaled_end,
    solver_settings_like,
    straight_ancf_cable,
)

EXAMPLE = "main/pythonDev/Examples/ANCFrotatingCable2D.py"
BODIES = "ObjectANCFCable2D on NodePoint2DSlope1 nodes, clamped to an ObjectRigidBody2D hub with a prescribed angle"
REPLACED = "the hub's pin to the ground (ObjectJointRevolute2D) at the origin"

# -- the example's model (m, kg, s) ------------------------------------------------------
N_ELEMENTS = 16
LENGTH = 2.0                 # [m]
E_MODULUS = 2e11             # [Pa]
DENSITY = 7800.0             # [kg/m^3]
WIDTH = HEIGHT = 0.01        # cross-section [m]
BENDING_DAMPING = 0.02       # times the bending stiffness EI [s]
GRAVITY = (0.0, -9.81, 0.0)  # [m/s^2]
HUB_SIZE, HUB_DENSITY = 0.01, 1000.0  # the hub, a cube [m], [kg/m^3]
#: The hub's angle: 0 before SWING_START, pi sin(pi t) until SWING_END, 0 after [s].
SWING_START, SWING_END = 2.0, 6.0

# -- the example's solver settings -------------------------------------------------------
END_TIME = 10.0              # [s]
STEP = 2e-3                  # [s]
NEWTON_RTOL = 1e-6           # the example's relative Newton tolerance

# -- the clearance joint: a steel pin in the hub -----------------------------------------
CLEARANCE = 20e-6            # radial clearance c [m]
BEARING_RADIUS = 4e-3        # R_B [m]: an 8 mm pin in the 10 mm hub
BEARING_LENGTH = WIDTH       # L [m]


def hub_angle(t: float) -> float:
    """The example's prescribed hub angle [rad] at time t [s]."""
    return math.pi * math.sin(math.pi * t) if SWING_START <= t < SWING_END else 0.0


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    """The example's cable on its hub; ``clearance=True`` puts a clearance joint at the hub's pin."""
    mbs = exu.SystemContainer().AddSystem()
    area, second_moment = WIDTH * HEIGHT, WIDTH * HEIGHT ** 3 / 12
    nodes, _cables = straight_ancf_cable(mbs, LENGTH, N_ELEMENTS, GRAVITY, massPerLength=DENSITY * area,
                                         bendingStiffness=E_MODULUS * second_moment, axialStiffness=E_MODULUS * area,
                                         bendingDamping=BENDING_DAMPING * E_MODULUS * second_moment,
                                         useReducedOrderIntegration=0)
    ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
    hub = mbs.CreateRigidBody(referencePosition=[0.0, 0.0, 0.0], inertia=InertiaCuboid(HUB_DENSITY, [HUB_SIZE] * 3),
                              create2D=True, returnDict=True, show=False)
    hub_marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=hub["bodyNumber"], localPosition=[0.0, 0.0, 0.0]))
    mbs.AddObject(ObjectJointGeneric(markerNumbers=[mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0])), hub_marker],
                                     constrainedAxes=[1, 1, 0, 0, 0, 1]))

    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="hub pin", itemNumbers=[ground, hub["bodyNumber"]],
                                              position=[0.0, 0.0, 0.0], axis=[0.0, 0.0, 1.0],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
            hub_marker, mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))]))

    def prescribed_angle(mbs_: exu.MainSystem, t: float, item: int, offset: float) -> float:
        return hub_angle(t)

    mbs.AddObject(ObjectConnectorCoordinate(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0)),
                       mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub["nodeNumber"], coordinate=2))],
        offset=0.0, offsetUserFunction=prescribed_angle))
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.timeIntegration.newton.relativeTolerance = NEWTON_RTOL
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.solution.sensors.writePeriod = END_TIME / 1000  # the example's solution write period

    tip = nodes[-1]

    def probe(system: exu.MainSystem) -> np.ndarray:
        """The cable's tip, x, y [m], and the hub's centre, x, y [m]."""
        return np.concatenate([system.GetNodeOutput(tip, exu.OutputVariableType.Position)[:2],
                               system.GetNodeOutput(hub["nodeNumber"], exu.OutputVariableType.Position)[:2]])

    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (Exudyn's default)
    return ZooModel("ancf_rotating_cable", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver, newton_rtol=NEWTON_RTOL), probe_bound=PROBE_BOUND_CARRIED)
