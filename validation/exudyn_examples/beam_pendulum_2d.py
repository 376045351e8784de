"""Flexible pendulum of geometrically exact 2D beams, after Exudyn's example
main/pythonDev/Examples/pendulumGeomExactBeam2D.py (jgerstmayr/EXUDYN).

::

      ground pivot (ObjectJointRevolute2D: ground - node 0; here the clearance joint)
        o===|===|===|===|===|===|===|===|===|===   10 ObjectBeamGeometricallyExact2D
        node 0                                     on NodeRigidBody2D nodes, 0.5 m,
        |  g                                       released horizontally
        v

The example: a very soft (E = 1e8 Pa) strip, 0.5 m x 10 mm x 2 mm, of ten
``ObjectBeamGeometricallyExact2D`` elements (Timoshenko-Reissner) on ``NodeRigidBody2D``
nodes, pinned at node 0 to the ground by an ``ObjectJointRevolute2D`` and released from
the horizontal under gravity; generalized-alpha (Exudyn's default spectral radius), step
2.5 ms, 5 s, modified Newton, sparse solver.  Kept: all of it (the parameters are
given by the element's current names, ``length`` etc., as ``physicsLength`` etc. are
deprecated in Exudyn 1.13), except that no solution file is written.  Changed with
``clearance=True``: the pivot becomes a clearance joint, bearing on the ground, journal
on node 0.  Pin: the strip is 2 mm thick and 10 mm wide, so R_B = 1 mm, L = 10 mm,
c = 20 um (a 0.01 kg pendulum on a 2 mm steel pin).

Route:

- A ``MarkerBodyRigid`` on the beam element cannot carry the joint: the element has no
  ``RotationMatrix`` output and gives the connector no local angular velocity, so
  ``exuclear.CreateClearanceJoint`` and ``exuclear.AddClearanceJoint`` refuse such a
  marker at creation, naming a ``MarkerNodeRigid`` on one of the element's nodes.
- Used here: ``exuclear.CreateClearanceJoint`` with itemNumbers [ground, a
  ``MarkerNodeRigid`` on node 0] (a marker in ``itemNumbers``, as ``mbs.CreateRevoluteJoint``
  takes it; the marker sets the joint's centre).  For ``step="auto"`` the mass behind a
  node marker is the lumped mass of its elements (half of each two-node element's
  ``massPerLength`` * ``length``).

The journal sits on node 0, a fraction of a gram, whose contact period is microseconds
against the example's 2.5 ms step; ``exuclear.simulate``'s automatic step comes from node
0's lumped mass.  What each way of running it gives is checked in ``tests/test_exudyn_examples.py`` and
reported, with its numbers (reached time, wall time, steps, largest penetration,
verdict), by ``python -m validation.exudyn_examples --models beam_pendulum_2d``.
"""
from __future__ import annotations

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyPosition,
    MarkerNodePosition,
    MarkerNodeRigid,
    NodeRigidBody2D,
    ObjectBeamGeometricallyExact2D,
    ObjectGround,
    ObjectJointRevolute2D,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, joint_parameters, register, solver_settings_like

EXAMPLE = "main/pythonDev/Examples/pendulumGeomExactBeam2D.py"
BODIES = "ObjectBeamGeometricallyExact2D on NodeRigidBody2D nodes"
REPLACED = "ground pivot at node 0 (ObjectJointRevolute2D)"

# -- the example's model ---------------------------------------------------------------
N_ELEMENTS = 10
LENGTH = 0.5              # pendulum length [m]
E_MODULUS = 1e8           # very soft elastomer [Pa]
DENSITY = 1000.0          # [kg/m^3]
HEIGHT = 0.002            # cross-section height [m]
WIDTH = 0.01              # cross-section width [m]
POISSON = 0.3
GRAVITY = (0.0, -9.81, 0.0)

# -- the example's solver settings -----------------------------------------------------
END_TIME = 5.0            # [s]
STEP = 0.0025             # [s]
WRITE_PERIOD = 0.005      # the example's solution write period [s], used for sensors

# -- the clearance joint: a steel pin sized to the strip -------------------------------
CLEARANCE = 20e-6         # radial clearance c [m]
BEARING_RADIUS = 1e-3     # R_B [m]: half the strip's 2 mm thickness
BEARING_LENGTH = WIDTH    # L [m]: the strip's width


def _element() -> dict:
    """The element parameters of the example (a Timoshenko-Reissner strip)."""
    area, second_moment = WIDTH * HEIGHT, WIDTH * HEIGHT ** 3 / 12
    shear_correction = 10 * (1 + POISSON) / (12 + 11 * POISSON)
    shear_modulus = E_MODULUS / (2 * (1 + POISSON))
    return dict(length=LENGTH / N_ELEMENTS, massPerLength=DENSITY * area, crossSectionInertia=DENSITY * second_moment,
                bendingStiffness=E_MODULUS * second_moment, axialStiffness=E_MODULUS * area,
                shearStiffness=shear_correction * shear_modulus * area)


@register
def build(clearance: bool, end_time: float | None = None, **joint_options) -> ZooModel:
    """The example's pendulum; ``clearance=True`` puts a clearance joint at the pivot."""
    mbs = exu.SystemContainer().AddSystem()
    element = _element()
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[k * element["length"], 0.0, 0.0]))
             for k in range(N_ELEMENTS + 1)]
    beams = [mbs.AddObject(ObjectBeamGeometricallyExact2D(nodeNumbers=[nodes[k], nodes[k + 1]], **element))
             for k in range(N_ELEMENTS)]
    ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))

    joint = None
    if clearance:
        # the element gives no running MarkerBodyRigid: the journal on node 0's MarkerNodeRigid
        joint = exuclear.CreateClearanceJoint(mbs, name="pivot",
                                              itemNumbers=[ground, mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0]))],
                                              axis=[0.0, 0.0, 1.0],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
            mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0])),
            mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[0]))]))
    for beam in beams:
        mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=beam)),
                                         loadVector=list(GRAVITY)))
    mbs.Assemble()

    t_end = END_TIME if end_time is None else float(end_time)
    ss = example_settings(t_end, t_end / STEP)
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.solution.sensors.writePeriod = WRITE_PERIOD

    tip = nodes[-1]

    def probe(system: exu.MainSystem) -> np.ndarray:
        """Tip position x, y [m] and the pivot node's position x, y [m]."""
        return np.concatenate([system.GetNodeOutput(tip, exu.OutputVariableType.Position)[:2],
                               system.GetNodeOutput(nodes[0], exu.OutputVariableType.Position)[:2]])

    solver = exu.DynamicSolverType.GeneralizedAlpha
    return ZooModel(name="beam_pendulum_2d", mbs=mbs, simulation_settings=ss, solver_type=solver, joint=joint,
                    clearance=CLEARANCE if clearance else None, probe=probe,
                    solver_settings=solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
