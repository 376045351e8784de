"""Planar slider-crank, after Exudyn's example main/pythonDev/Examples/SliderCrank.py
(jgerstmayr/EXUDYN).

The example: a crank (``ObjectRigidBody2D``, 0.5 m x 0.1 m, 2 kg, inertia m l^2 / 12)
turning about the origin, a connecting rod (1 m x 0.1 m, 4 kg) and a slider
(``ObjectMassPoint2D``, 1 kg) whose y coordinate a ``CoordinateConstraint`` holds at 0;
``RevoluteJoint2D`` joints ground - crank at (0, 0), crank - rod at (0.5, 0) and rod -
slider at (1.5, 0); a constant torque of 10 N m drives the crank from rest, no gravity
(the example defines g but applies none).  Generalized-alpha with spectral radius 0.5,
modified Newton, relative Newton tolerance 1e-10, 200000 steps over 2 s (1e-5 s).

Kept: bodies, joints, drive, solver and its settings.  Changed: no renderer, no solution
file, no plot.  The rod's node: the example puts it 100 m off its place (reference x =
2 a0 + a1 + 100) and leaves it to the index-3 joints to pull it in; Exudyn 1.13.6 fails
on that at the example's step ("SolveDynamic terminated"), and a clearance joint cannot
start 100 m out of its bearing, so the rod starts where the joints put it (x = 1 m); the
ideal model then reaches the slider position 1.355 m at 1 s (the example's reference
1.3514 m is for its test-suite run of 1000 steps).  Replaced: the crank - rod joint at
(0.5, 0) (both bodies move): the bearing in the rod's big end, the journal (crank pin) on
the crank; a pin of R_B = 20 mm (the example's bars are 0.1 m high) in a 20 mm long
bearing, 30 um radial clearance.  The rod - slider joint stays ideal: the slider is a
mass point, which has no rotation to carry a bearing or a journal
(``CreateClearanceJoint`` needs rigid bodies).  ``energy`` is None: the torque drives it.

Over 2 s the example's settings stop at t = 0.061 s,
"SolveDynamic terminated", and the joint's note says why: the example's Newton relative
tolerance 1e-10, which the joint keeps, lies below the round-off floor of the stiff
contact; the joint's absolute tolerance 1e-8 (in place of Exudyn's 1e-10, with which the run
stopped at 0.027 s) ends Newton at the floor until the pin's load grows (with a relative
tolerance of 1e-8 the same run reaches 0.1 s at 0.044 c).  ``exuclear.simulate`` (auto step 5e-5 s)
reaches 2 s; its largest penetration, 0.105 c, is the crank pin's steady contact at the
end (the crank at about 30 rad/s, 2.45 kN), converged (0.1049 c at a step of 1e-5 s),
though above the zoo's 0.1 c rule for a wrong step.

::

              crank            connecting rod            slider
    ground o==========o-------------------------------o [ ]  ==> x (y held at 0)
        (0, 0)   (0.5, 0) clearance joint         (1.5, 0)
        torque 10 N m
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodePoint2D,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinate,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectMassPoint2D,
    ObjectRigidBody2D,
    Torque,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, joint_parameters, register, scaled_end, solver_settings_like

EXAMPLE = "main/pythonDev/Examples/SliderCrank.py"
BODIES = "ObjectRigidBody2D, ObjectMassPoint2D, CoordinateConstraint, torque drive"
REPLACED = "crank - connecting rod at (0.5, 0, 0), axis z"

# -- the example's mechanism (SI) ----------------------------------------------------------
CRANK_HALF, CRANK_MASS = 0.25, 2.0       # half length [m], mass [kg]
ROD_HALF, ROD_MASS = 0.5, 4.0
SLIDER_MASS = 1.0
DRIVE_TORQUE = 10.0                      # on the crank [N m]
#: The example's settings: 2 s in 200000 steps, spectral radius 0.5, Newton rtol 1e-10.
END_TIME, STEPS = 2.0, 200000
SPECTRAL_RADIUS, NEWTON_RTOL = 0.5, 1e-10
#: Our pin: bearing radius, radial clearance, bearing length [m].
BEARING_RADIUS, CLEARANCE, BEARING_LENGTH = 20e-3, 30e-6, 20e-3


def _bar_inertia(mass: float, half: float) -> float:
    """The example's inertia of a bar of length 2 half about its centre [kg m^2]."""
    return mass / 12 * (2 * half) ** 2


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    ground_node = mbs.AddNode(NodePointGround())
    crank_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[CRANK_HALF, 0, 0]))
    crank = mbs.AddObject(ObjectRigidBody2D(mass=CRANK_MASS, inertia=_bar_inertia(CRANK_MASS, CRANK_HALF),
                                            nodeNumber=crank_node))
    pin = 2 * CRANK_HALF  # crank - rod joint, x [m]
    rod = mbs.AddObject(ObjectRigidBody2D(mass=ROD_MASS, inertia=_bar_inertia(ROD_MASS, ROD_HALF), nodeNumber=mbs.AddNode(
        NodeRigidBody2D(referenceCoordinates=[pin + ROD_HALF, 0, 0]))))  # the docstring: not 100 m off
    slider_node = mbs.AddNode(NodePoint2D(referenceCoordinates=[pin + 2 * ROD_HALF, 0]))
    slider = mbs.AddObject(ObjectMassPoint2D(mass=SLIDER_MASS, nodeNumber=slider_node))

    crank_support = mbs.AddMarker(MarkerBodyRigid(bodyNumber=crank, localPosition=[-CRANK_HALF, 0, 0]))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground)),
                                                       crank_support]))
    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="crank pin", itemNumbers=[rod, crank], position=[pin, 0, 0],
                                              axis=[0, 0, 1],
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
            mbs.AddMarker(MarkerBodyPosition(bodyNumber=crank, localPosition=[CRANK_HALF, 0, 0])),
            mbs.AddMarker(MarkerBodyPosition(bodyNumber=rod, localPosition=[-ROD_HALF, 0, 0]))]))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=rod, localPosition=[ROD_HALF, 0, 0])),
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=slider))]))
    mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[  # the slider's guide: y = 0
        mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0)),
        mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=slider_node, coordinate=1))]))
    mbs.AddLoad(Torque(markerNumber=crank_support, loadVector=[0, 0, DRIVE_TORQUE]))
    mbs.Assemble()

    ss = example_settings(END_TIME, STEPS)
    ti = ss.timeIntegration
    ti.newton.relativeTolerance = NEWTON_RTOL  # the example's
    ti.newton.useModifiedNewton = True
    ti.generalizedAlpha.spectralRadius = SPECTRAL_RADIUS
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's

    def probe(m: exu.MainSystem) -> np.ndarray:
        """The slider's x [m] (the example's output) and the rod's centre (x, y) [m]."""
        rod_centre = np.asarray(m.GetObjectOutputBody(rod, exu.OutputVariableType.Position, localPosition=[0, 0, 0]))
        return np.array([m.GetNodeOutput(slider_node, exu.OutputVariableType.Position)[0], *rod_centre[:2]])

    return ZooModel("slider_crank_2d", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
