"""Flexible pendulum of ANCF cable elements, after Exudyn's example
main/pythonDev/Examples/flexiblePendulumANCF.py (jgerstmayr/EXUDYN).

::

      hinge (node 0: x, y held by CoordinateConstraints; here the clearance joint)
        o--------------------------------------   25 ObjectANCFCable2D elements on
        node 0                                    NodePoint2DSlope1 nodes, 1 m,
        |  g                                      released horizontally
        v

The example: a 1 m cable (rhoA = 10 kg/m, 50 mm x 50 mm, E = 2.1e10 Pa) of 25
``ObjectANCFCable2D`` elements, hinged at node 0 (``GenerateStraightLineANCFCable2D``
with ``fixedConstraintsNode0=[1, 1, 0, 0]``: coordinate constraints on the node's x and
y, the slope free), released from the horizontal under gravity; ``TrapezoidalIndex2``,
step 1e-4 s, 3 s, modified Newton with relative and absolute tolerance 1e-6, adaptive
step, sparse solver.  Kept: all of it, built without the deprecated helper (the same
nodes, elements, mass-proportional loads and constraints), except: one thread instead
of the example's four (the cores are shared here, and exuclear's connectors assume
Exudyn's single-threaded evaluation order), and no renderer.  Changed with
``clearance=True``: the hinge (the two coordinate constraints) becomes a clearance
joint, bearing on the ground, journal on a ``MarkerBodyRigid`` at the start of the first
cable element (``exuclear.CreateClearanceJoint``, itemNumbers [ground, first element]).
Pin: R_B = 10 mm in the 50 mm cable, L = 50 mm (the cable's width), c = 30 um.

Route (Exudyn 1.13):

- ``MarkerBodyRigid`` on an ``ObjectANCFCable2D`` exists in Exudyn 1.13 (position and
  the slope's rotation about z).
- The cable element has no ``RotationMatrix`` output: ``exuclear.CreateClearanceJoint``
  reads the element's planar rotation angle and places the marker at ``position`` on
  the element's axis (connector.py ``_reference_pose``).
- For ``step="auto"`` the contact period needs the cable element's mass,
  ``massPerLength`` * ``length`` (``_diagnostics.body_mass``).

The example's step is adaptive, so where its path meets a contact depends on the end
time; ``exuclear.simulate``'s automatic step comes from the element's mass.
What each way of running it gives is checked in ``tests/test_exudyn_examples.py`` and
reported, with its numbers (reached time, wall time, steps, largest penetration,
verdict), by ``python -m validation.exudyn_examples --models ancf_pendulum``.
"""
from __future__ import annotations

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerNodeCoordinate, NodePointGround, ObjectConnectorCoordinate, ObjectGround

import exuclear

from ._common import (
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    joint_parameters,
    register,
    solver_settings_like,
    straight_ancf_cable,
)

EXAMPLE = "main/pythonDev/Examples/flexiblePendulumANCF.py"
BODIES = "ObjectANCFCable2D on NodePoint2DSlope1 nodes"
REPLACED = "hinge at node 0 (coordinate constraints on x, y)"

# -- the example's model ---------------------------------------------------------------
N_ELEMENTS = 25
LENGTH = 1.0              # [m]
MASS_PER_LENGTH = 10.0    # beam and discrete masses [kg/m]
HEIGHT = WIDTH = 0.05     # cross-section [m]
E_MODULUS = 2.1e10        # [Pa]
GRAVITY = (0.0, -9.81, 0.0)

# -- the example's solver settings -----------------------------------------------------
END_TIME = 3.0            # [s]
STEP = 1e-4               # [s]
WRITE_PERIOD = 100 * STEP  # the example's sensor write period [s]
NEWTON_TOLERANCE = 1e-6   # the example's relative and absolute Newton tolerance

# -- the clearance joint: a steel pin sized to the cable --------------------------------
CLEARANCE = 30e-6         # radial clearance c [m]
BEARING_RADIUS = 0.01     # R_B [m]: a 20 mm pin in the 50 mm cable
BEARING_LENGTH = WIDTH    # L [m]


@register
def build(clearance: bool, end_time: float | None = None, **joint_options) -> ZooModel:
    """The example's cable pendulum; ``clearance=True`` puts a clearance joint at the hinge."""
    mbs = exu.SystemContainer().AddSystem()
    area, second_moment = WIDTH * HEIGHT, WIDTH * HEIGHT ** 3 / 12
    nodes, cables = straight_ancf_cable(mbs, LENGTH, N_ELEMENTS, GRAVITY, massPerLength=MASS_PER_LENGTH,
                                        bendingStiffness=E_MODULUS * second_moment, axialStiffness=E_MODULUS * area,
                                        useReducedOrderIntegration=0)
    ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))

    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="hinge", itemNumbers=[ground, cables[0]],
                                              position=[0.0, 0.0, 0.0], axis=[0.0, 0.0, 1.0],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:  # the example's hinge: node 0's x and y held to a ground coordinate
        fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
        for coordinate in (0, 1):
            mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[
                fixed, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coordinate))]))
    mbs.Assemble()

    t_end = END_TIME if end_time is None else float(end_time)
    ss = example_settings(t_end, t_end / STEP)
    ti = ss.timeIntegration
    ti.newton.useModifiedNewton = True
    ti.newton.relativeTolerance = NEWTON_TOLERANCE
    ti.newton.absoluteTolerance = NEWTON_TOLERANCE
    ti.generalizedAlpha.spectralRadius = 0.8  # as the example (no effect on the trapezoidal rule)
    ti.adaptiveStep = True
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.parallel.numberOfThreads = 1  # the example: 4 (module docstring)
    ss.solution.sensors.writePeriod = WRITE_PERIOD

    tip = nodes[-1]

    def probe(system: exu.MainSystem) -> np.ndarray:
        """Tip position x, y [m] and node 0's position x, y [m]."""
        return np.concatenate([system.GetNodeOutput(tip, exu.OutputVariableType.Position)[:2],
                               system.GetNodeOutput(nodes[0], exu.OutputVariableType.Position)[:2]])

    solver = exu.DynamicSolverType.TrapezoidalIndex2
    return ZooModel(name="ancf_pendulum", mbs=mbs, simulation_settings=ss, solver_type=solver, joint=joint,
                    clearance=CLEARANCE if clearance else None, probe=probe,
                    solver_settings=solver_settings_like(ss, solver, newton_rtol=NEWTON_TOLERANCE,
                                                         newton_atol=NEWTON_TOLERANCE),
                    probe_bound=PROBE_BOUND_CARRIED)
