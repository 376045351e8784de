"""Four-bar mechanism as a kinematic tree closed by a joint, after Exudyn's example
main/pythonDev/Examples/FurtherExamples/fourBarKinematicTreeGravity.py (jgerstmayr/EXUDYN).

::

    (0, 0.5) o------- link 1 (coupler, 1 m) -------o (1, 0.5)
             |                                     |
      link 0 (crank, 0.5 m)                 link 2 (rocker, 1 m)
             |                                     |
    ground   o (0, 0)                              |
                                                   o (1, -0.5)  closing joint to the ground:
                                                                here the clearance joint

The example: three cuboid links (0.5 m, 1 m, 1 m long, 50 mm x 50 mm, density 1000
kg/m^3) in one ``ObjectKinematicTree`` of ``RevoluteZ`` joints (the crank turned by
+90 deg about z, the coupler and the rocker each by -90 deg against their parent), the
tree's base the ground pivot (0, 0, 0), released at rest; the loop is closed by an
``ObjectJointGeneric`` between a ground marker at (1, -0.5, 0) and a
``MarkerKinematicTreeRigid`` at the rocker's end, holding x and y only (the tree holds
the rest); gravity [0.5, -9.81, 0] m/s^2 (the example's x component sets the square in
motion).  A crank-rocker (0.5 + 1.118 < 1 + 1, Grashof, the shortest link the crank):
no change point.  Exudyn's default solver (generalized-alpha, spectral radius 0.9) and
Newton settings, step 5 ms, 10 s.

Kept: links, joint frames, inertia, gravity, solver and step, the closing joint.
Changed: no renderer, no real-time simulation, no solution file.  Replaced with
``clearance=True``: the closing joint (rocker - ground), a pin in the plane of the
mechanism, is the loop's one joint outside the tree, so the clearance joint replaces it
as it stands: ``exuclear.AddClearanceJoint`` between the ground marker (bearing) and
the tree marker at the rocker's end (journal), axis z; nothing else changes, as the
tree holds the rocker's axial motion and tilt, as it held them for the replaced joint.
Pin: the example draws its joints as cylinders of radius 0.4 w = 20 mm; L = w = 50 mm
(the links' width), c = 40 um.
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    MarkerKinematicTreeRigid,
    NodeGenericODE2,
    ObjectGround,
    ObjectJointGeneric,
    ObjectKinematicTree,
)
from exudyn.rigidBodyUtilities import InertiaCuboid, RotationMatrixZ

import exuclear

from .._common import (
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    joint_parameters,
    register,
    scaled_end,
    solver_settings_like,
)

EXAMPLE = "main/pythonDev/Examples/FurtherExamples/fourBarKinematicTreeGravity.py"
BODIES = "ObjectKinematicTree (3 links, RevoluteZ), closed by a joint to the ground on a MarkerKinematicTreeRigid"
REPLACED = "closing joint rocker (link 2) - ground at (1, -0.5, 0), axis z"

# -- the example's model (m, kg) ---------------------------------------------------------
LENGTHS = (0.5, 1.0, 1.0)   # crank, coupler, rocker [m]
WIDTH = 0.05                # cross-section w x w [m]
DENSITY = 1000.0            # [kg/m^3]
GRAVITY = (0.5, -9.81, 0.0)  # the example's gravity with its disturbance in x [m/s^2]
#: Each link's joint frame turned about z against its parent's [rad].
JOINT_ANGLES = (0.5 * math.pi, -0.5 * math.pi, -0.5 * math.pi)
#: The closing joint's ground point [m]: the rocker's end in the reference configuration.
CLOSING_POINT = (LENGTHS[1], LENGTHS[0] - LENGTHS[2], 0.0)

# -- the example's solver settings -------------------------------------------------------
END_TIME = 10.0             # [s]
STEP = 0.005                # [s]

# -- the clearance joint -----------------------------------------------------------------
CLEARANCE = 40e-6           # radial clearance c [m]
BEARING_RADIUS = 0.4 * WIDTH  # R_B [m]: the example's joint cylinder
BEARING_LENGTH = WIDTH      # L [m]


def _links() -> list:
    """The links' inertia (``RigidBodyInertia`` about the link's joint, the bar along its x axis)."""
    return [InertiaCuboid(density=DENSITY, sideLengths=[length, WIDTH, WIDTH]).Translated([0.5 * length, 0.0, 0.0])
            for length in LENGTHS]


def _energy(mbs: exu.MainSystem, markers: list[int], inertias: list) -> Any:
    """``ZooModel.energy``: the links' kinetic energy and the gravity potential ``-m g . r``
    of their centres of mass (markers there) [J]."""
    g = np.asarray(GRAVITY)

    def energy(system: exu.MainSystem) -> tuple[float, float]:
        kinetic = potential = 0.0
        for marker, inertia in zip(markers, inertias):
            v = system.GetMarkerOutput(marker, exu.OutputVariableType.Velocity)
            w = system.GetMarkerOutput(marker, exu.OutputVariableType.AngularVelocityLocal)
            r = system.GetMarkerOutput(marker, exu.OutputVariableType.Position)
            kinetic += 0.5 * inertia.Mass() * v @ v + 0.5 * w @ inertia.InertiaCOM() @ w
            potential -= inertia.Mass() * g @ r
        return kinetic, potential

    return energy


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    """The example's four-bar; ``clearance=True`` makes the closing joint a clearance joint."""
    mbs = exu.SystemContainer().AddSystem()
    inertias = _links()
    n = len(LENGTHS)
    offsets = [[0.0, 0.0, 0.0]] + [[length, 0.0, 0.0] for length in LENGTHS[:-1]]  # each at its parent's end
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                       initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    tree = mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, jointTypes=[exu.JointType.RevoluteZ] * n, linkParents=list(range(-1, n - 1)),
        jointTransformations=exu.Matrix3DList([RotationMatrixZ(a) for a in JOINT_ANGLES]),
        jointOffsets=exu.Vector3DList(offsets), linkMasses=[i.Mass() for i in inertias],
        linkCOMs=exu.Vector3DList([i.COM() for i in inertias]),
        linkInertiasCOM=exu.Matrix3DList([i.InertiaCOM() for i in inertias]), gravity=list(GRAVITY)))
    ground = mbs.AddObject(ObjectGround(referencePosition=list(CLOSING_POINT)))
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0])),
               mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=n - 1,
                                                      localPosition=[LENGTHS[-1], 0.0, 0.0]))]
    joint = None
    if clearance:
        joint = exuclear.AddClearanceJoint(mbs, markers, axis=[0.0, 0.0, 1.0], name="closing pin",
                                           **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                              **joint_options))
    else:
        mbs.AddObject(ObjectJointGeneric(markerNumbers=markers, constrainedAxes=[1, 1, 0, 0, 0, 0]))
    centres = [mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=k, localPosition=list(i.COM())))
               for k, i in enumerate(inertias)]
    coupler_end = mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=1,
                                                         localPosition=[LENGTHS[1], 0.0, 0.0]))
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # the example's (Exudyn's default)

    def probe(system: exu.MainSystem) -> np.ndarray:
        """The coupler's end (the rocker's top pivot), x, y [m]: the rocker, which the
        replaced joint carries, hangs from it."""
        return np.asarray(system.GetMarkerOutput(coupler_end, exu.OutputVariableType.Position), dtype=float)[:2]

    return ZooModel("four_bar_kinematic_tree", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), energy=_energy(mbs, centres, inertias),
                    probe_bound=PROBE_BOUND_CARRIED)
