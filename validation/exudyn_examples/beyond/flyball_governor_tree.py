"""Stiff flyball governor as one kinematic tree, after Exudyn's example
main/pythonDev/Examples/stiffFlyballGovernorKT.py (jgerstmayr/EXUDYN).

::

               z
               |     shaft (link 0), RevoluteZ about the z axis, spinning at 2 pi rad/s
      rod BD   |   rod AC: RevoluteY on the shaft at A; here the clearance joint
            B o|o A
            /  |  \\        each rod 1 m with a 5 kg point mass at its end, 30 deg below
        5 kg   |   5 kg    the horizontal, held up by a stiff spring-damper from the slider
          \\  [=]  /
           spring-dampers   slider (link 1), PrismaticZ along the shaft

The example: the IFToMM library's stiff flyball governor as one
``ObjectKinematicTree``: the shaft (1 m x 10 mm x 10 mm, density 3000 kg/m^3) turning
about z, the slider (a 0.1 m cube) sliding along it, two rods (1 m x 10 mm x 10 mm) on
``RevoluteY`` joints at +-50 mm from the axis, tilted by 30 deg and 150 deg about y,
each carrying a 5 kg point mass at its end; two ``ObjectConnectorSpringDamper`` (k = 8e5
N/m, d = 4e4 N s/m, relaxed length 0.5 m) from the slider's sides to the rods' middles;
gravity -9.81 m/s^2 along z; the shaft starts at 2 pi rad/s.  ``TrapezoidalIndex2``,
step 0.5 ms, 10 s, modified Newton with at most 2 modified iterations, relative
tolerance 1e-6, no connector Jacobian derivative, spectral radius 0.7 (no effect on the
trapezoidal rule), initial accelerations computed.

Kept: all of it, except: no renderer and no sensor.  Replaced with ``clearance=True``:
rod AC's pin on the shaft, which holds the rod against the spinning 5 kg mass's pull (m
omega^2 r = 180 N at the start) and the spring's push.  As in ``kinematic_tree_chain``,
the tree holds a joint's freedom, so rod AC gets the pin's in-plane play: two massless
links (``PrismaticX``, ``PrismaticZ``) in the pin's joint frame, then the rod on its
original ``RevoluteY``; the tree keeps holding the rod's axial motion and tilt, as it
held them for the replaced joint.  ``exuclear.AddClearanceJoint`` between
``MarkerKinematicTreeRigid`` markers (bearing: the shaft at A; journal: rod AC at its
joint; axis: y).  Pin: R_B = 4 mm in the 10 mm rod, L = 10 mm, c = 20 um.  The pin's
load never lets go: the journal stays on its wall from its first contact on (no impact
ends).
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerKinematicTreeRigid, NodeGenericODE2, ObjectConnectorSpringDamper, ObjectKinematicTree
from exudyn.rigidBodyUtilities import InertiaCuboid, InertiaMassPoint, RotationMatrixY

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

EXAMPLE = "main/pythonDev/Examples/stiffFlyballGovernorKT.py"
BODIES = "ObjectKinematicTree (shaft, slider, two rods with point masses; clearance: + PrismaticX/Z links), spring-dampers"
REPLACED = "rod AC's pin (RevoluteY) on the shaft"

# -- the example's model (m, kg, s) ------------------------------------------------------
SHAFT_LENGTH, SHAFT_WIDTH = 1.0, 0.01
ROD_LENGTH, ROD_WIDTH = 1.0, 0.01
SLIDER_SIZE = 0.1
SLIDER_POSITION = 0.5        # along the shaft, from its lower end [m]
PIN_DISTANCE = 0.1           # between the rods' pins A and B [m]
ROD_ANGLE = math.radians(30.0)  # the rods' tilt about y [rad]
DENSITY = 3000.0             # [kg/m^3]
END_MASS = 5.0               # the point mass at each rod's end [kg]
GRAVITY = (0.0, 0.0, -9.81)  # [m/s^2]
OMEGA = 2.0 * math.pi        # the shaft's initial angular velocity [rad/s]
SPRING_STIFFNESS, SPRING_DAMPING, SPRING_LENGTH = 8e5, 4e4, 0.5  # [N/m], [N s/m], [m]

# -- the example's solver settings -------------------------------------------------------
END_TIME = 10.0              # [s]
STEP = 5e-4                  # [s]
NEWTON_RTOL = 1e-6
MAX_MODIFIED_NEWTON_ITERATIONS = 2
SPECTRAL_RADIUS = 0.7        # set by the example; the trapezoidal rule does not use it

# -- the clearance joint -----------------------------------------------------------------
CLEARANCE = 20e-6            # radial clearance c [m]
BEARING_RADIUS = 4e-3        # R_B [m]: an 8 mm pin in the 10 mm rod
BEARING_LENGTH = ROD_WIDTH   # L [m]


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    """The example's governor; ``clearance=True`` puts a clearance joint at rod AC's pin."""
    mbs = exu.SystemContainer().AddSystem()
    rod = (InertiaCuboid(density=DENSITY, sideLengths=[ROD_LENGTH, ROD_WIDTH, ROD_WIDTH]).Translated(
        [0.5 * ROD_LENGTH, 0.0, 0.0]) + InertiaMassPoint(mass=END_MASS).Translated([ROD_LENGTH, 0.0, 0.0]))
    shaft = InertiaCuboid(density=DENSITY, sideLengths=[SHAFT_WIDTH, SHAFT_WIDTH, SHAFT_LENGTH])
    slider = InertiaCuboid(density=DENSITY, sideLengths=[SLIDER_SIZE] * 3)
    pin_a = [0.5 * PIN_DISTANCE, 0.0, 0.5 * SHAFT_LENGTH]  # in the shaft's frame
    pin_b = [-0.5 * PIN_DISTANCE, 0.0, 0.5 * SHAFT_LENGTH]
    nothing = np.zeros((3, 3))

    # links: (joint type, parent, rotation, offset, inertia or None for a massless link)
    links = [(exu.JointType.RevoluteZ, -1, np.eye(3), [0.0, 0.0, 0.5 * SHAFT_LENGTH], shaft),
             (exu.JointType.PrismaticZ, 0, np.eye(3), [0.0, 0.0, SLIDER_POSITION - 0.5 * SHAFT_LENGTH], slider)]
    if clearance:  # rod AC's play: two massless sliders in its joint frame, then its pin
        links += [(exu.JointType.PrismaticX, 0, RotationMatrixY(ROD_ANGLE), pin_a, None),
                  (exu.JointType.PrismaticZ, 2, np.eye(3), [0.0, 0.0, 0.0], None),
                  (exu.JointType.RevoluteY, 3, np.eye(3), [0.0, 0.0, 0.0], rod)]
    else:
        links += [(exu.JointType.RevoluteY, 0, RotationMatrixY(ROD_ANGLE), pin_a, rod)]
    links += [(exu.JointType.RevoluteY, 0, RotationMatrixY(math.pi - ROD_ANGLE), pin_b, rod)]
    rod_ac, rod_bd = len(links) - 2, len(links) - 1
    n = len(links)
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                       initialCoordinates_t=[OMEGA] + [0.0] * (n - 1), numberOfODE2Coordinates=n))
    tree = mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, jointTypes=[k[0] for k in links], linkParents=[k[1] for k in links],
        jointTransformations=exu.Matrix3DList([k[2] for k in links]), jointOffsets=exu.Vector3DList([k[3] for k in links]),
        linkMasses=[0.0 if k[4] is None else k[4].Mass() for k in links],
        linkCOMs=exu.Vector3DList([np.zeros(3) if k[4] is None else k[4].COM() for k in links]),
        linkInertiasCOM=exu.Matrix3DList([nothing if k[4] is None else k[4].InertiaCOM() for k in links]),
        gravity=list(GRAVITY)))

    def tree_marker(link: int, position: list[float]) -> int:
        return mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=link, localPosition=position))

    for rod_link, side in ((rod_ac, 1.0), (rod_bd, -1.0)):
        mbs.AddObject(ObjectConnectorSpringDamper(
            markerNumbers=[tree_marker(1, [side * 0.5 * SLIDER_SIZE, 0.0, 0.0]),
                           tree_marker(rod_link, [0.5 * ROD_LENGTH, 0.0, 0.0])],
            stiffness=SPRING_STIFFNESS, damping=SPRING_DAMPING, referenceLength=SPRING_LENGTH))
    joint = None
    if clearance:
        joint = exuclear.AddClearanceJoint(mbs, [tree_marker(0, pin_a), tree_marker(rod_ac, [0.0, 0.0, 0.0])],
                                           axis=[0.0, 1.0, 0.0], name="pin A",
                                           **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                              **joint_options))
    end_of_rod = tree_marker(rod_ac, [ROD_LENGTH, 0.0, 0.0])
    slider_centre = tree_marker(1, [0.0, 0.0, 0.0])
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    ti = ss.timeIntegration
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.generalizedAlpha.spectralRadius = SPECTRAL_RADIUS
    ti.newton.useModifiedNewton = True
    ti.newton.maxModifiedNewtonIterations = MAX_MODIFIED_NEWTON_ITERATIONS
    ti.newton.numericalDifferentiation.jacobianConnectorDerivative = False
    ti.newton.relativeTolerance = NEWTON_RTOL
    ti.absoluteTolerance = ti.relativeTolerance = 1e-6  # as the example (the adaptive explicit methods' tolerances)

    def probe(system: exu.MainSystem) -> np.ndarray:
        """Rod AC's end (its 5 kg mass) [m], which the replaced pin carries, and the slider's centre [m]."""
        return np.concatenate([system.GetMarkerOutput(end_of_rod, exu.OutputVariableType.Position),
                               system.GetMarkerOutput(slider_centre, exu.OutputVariableType.Position)])

    solver = exu.DynamicSolverType.TrapezoidalIndex2
    return ZooModel("flyball_governor_tree", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver, newton_rtol=NEWTON_RTOL), probe_bound=PROBE_BOUND_CARRIED)
