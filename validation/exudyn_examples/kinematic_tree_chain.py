"""Serial chain as one ObjectKinematicTree, after Exudyn's example
main/pythonDev/Examples/kinematicTreeAndMBS.py (jgerstmayr/EXUDYN).

::

    ground
      o-- link 0 --o-- link 1 --o-- link 2 --o-- link 3 --o-- link 4     five 2 m bars,
     J0           J1           J2           J3           J4             joint axes tilted
                   \\ here the clearance joint: bearing on link 0, journal on link 1
                     (the tree gives link 1 the in-plane play: PrismaticX, PrismaticY,
                      then the original RevoluteZ, in J1's joint frame)

The example: five links (2 m x 0.1 m x 0.1 m, density 1000, 20 kg each) in one
``ObjectKinematicTree`` (its C++ branch, built through ``Robot.CreateKinematicTree``),
revolute joints about the z axes of joint frames that are rotated by
``RotXYZ2RotationMatrix([0.5 pi, 0.25 pi, 0])`` or ``[0, 0.25 pi, 0]`` (so the chain moves
in 3D), offsets of 2 m, gravity 10 m/s^2 along -y, released at rest from the straight
configuration; ``ExplicitEuler``, step 1e-2 s, 1 s.  Kept: links, joint frames,
inertia, gravity, solver and step, the tree built directly as ``ObjectKinematicTree``
(the example's own alternative branch) with no graphics; the example's Python
``ObjectGenericODE2`` variant (``KinematicTree66``, also in the file) is left out.

Changed with ``clearance=True``: joint J1 (between links 0 and 1) becomes a clearance
joint.  The tree holds a joint's freedom, so J1's link gets the in-plane play: two
massless links (``PrismaticX``, ``PrismaticY``) in J1's joint frame, then link 1 on its
``RevoluteZ``; the tree itself keeps holding axial motion and tilt, as the replaced joint
did.  ``exuclear.AddClearanceJoint`` between ``MarkerKinematicTreeRigid`` markers (bearing:
link 0 at J1; journal: link 1 at its origin; axis: J1's z axis in link 0's frame), as the
README says for kinematic-tree links; ``exuclear.CreateClearanceJoint`` given the tree
itself refuses it, saying that the journal's link needs its play in the tree and that
the markers go in ``itemNumbers`` (which it takes, as ``mbs.CreateRevoluteJoint``
does).  Pin:
R_B = 20 mm in the 100 mm links, L = 100 mm, c = 50 um.

``exuclear.simulate`` has no explicit Euler (its methods: dopri5, ode23, rk44,
generalized-alpha, trapezoidal): ``solver_settings`` takes the nearest fixed-step
explicit method, ``"rk44"``, with ``step="auto"``.

The example's explicit Euler step of 1e-2 s spans a whole contact (well under a
millisecond): explicit Euler has no error estimate to shorten it by, and does not hold
the stiff contact even at the steps the joint asks for, which its AccuracyWarning says.
``exuclear.simulate`` takes its automatic step, a fraction of that contact.
What each way of running it gives is checked in ``tests/test_exudyn_examples.py`` and
reported, with its numbers (reached time, wall time, steps, largest penetration,
verdict), by ``python -m validation.exudyn_examples --models kinematic_tree_chain``.
"""
from __future__ import annotations

import math

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerKinematicTreeRigid, NodeGenericODE2, ObjectKinematicTree
from exudyn.rigidBodyUtilities import InertiaCuboid, RotXYZ2RotationMatrix

import exuclear

from ._common import OUTPUTS_PER_RUN, ZooModel, example_settings, joint_parameters, register

EXAMPLE = "main/pythonDev/Examples/kinematicTreeAndMBS.py"
BODIES = "ObjectKinematicTree (5 links, tilted RevoluteZ joints; clearance: + PrismaticX/Y links)"
REPLACED = "joint J1 between links 0 and 1"

# -- the example's model ---------------------------------------------------------------
N_LINKS = 5
LINK_LENGTH = 2.0         # [m]
LINK_WIDTH = 0.1          # [m]
DENSITY = 1000.0          # [kg/m^3]
GRAVITY = (0.0, -10.0, 0.0)
REPLACED_JOINT = 1        # index of the joint made a clearance joint

# -- the example's solver settings -----------------------------------------------------
END_TIME = 1.0            # [s]
STEP = 1e-2               # [s]

# -- the clearance joint ---------------------------------------------------------------
CLEARANCE = 50e-6         # radial clearance c [m]
BEARING_RADIUS = 0.02     # R_B [m]: a 40 mm pin in the 100 mm links
BEARING_LENGTH = LINK_WIDTH  # L [m]


def joint_frame(i: int) -> tuple[np.ndarray, np.ndarray]:
    """Rotation and offset [m] of joint i's frame in its parent link's frame, by the
    example's rule (odd joints turned about y, joints with i % 3 >= 1 also about x)."""
    rotation = np.eye(3)
    if i % 2 != 0:
        rotation = RotXYZ2RotationMatrix([0.0, 0.25 * math.pi, 0.0])
    if i % 3 >= 1:
        rotation = RotXYZ2RotationMatrix([0.5 * math.pi, 0.25 * math.pi, 0.0])
    offset = np.zeros(3) if i == 0 else np.array([LINK_LENGTH, 0.0, 0.0])
    return rotation, offset


@register
def build(clearance: bool, end_time: float | None = None, **joint_options) -> ZooModel:
    """The example's chain; ``clearance=True`` puts a clearance joint at J1."""
    mbs = exu.SystemContainer().AddSystem()
    bar = InertiaCuboid(density=DENSITY, sideLengths=[LINK_LENGTH, LINK_WIDTH, LINK_WIDTH])
    com = np.array([0.5 * LINK_LENGTH, 0.0, 0.0])  # the bar from its joint along x
    nothing = np.zeros((3, 3))

    # links of the tree: (joint type, parent, rotation, offset, mass, COM, inertia at COM)
    links = []
    for i in range(N_LINKS):
        rotation, offset = joint_frame(i)
        parent = len(links) - 1
        if clearance and i == REPLACED_JOINT:  # J1's play: two massless sliders in its joint frame
            links.append((exu.JointType.PrismaticX, parent, rotation, offset, 0.0, np.zeros(3), nothing))
            links.append((exu.JointType.PrismaticY, parent + 1, np.eye(3), np.zeros(3), 0.0, np.zeros(3), nothing))
            parent, rotation, offset = parent + 2, np.eye(3), np.zeros(3)
        links.append((exu.JointType.RevoluteZ, parent, rotation, offset, bar.Mass(), com, bar.InertiaCOM()))
    n = len(links)
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                       initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    tree = mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, jointTypes=[k[0] for k in links], linkParents=[k[1] for k in links],
        jointTransformations=exu.Matrix3DList([k[2] for k in links]),
        jointOffsets=exu.Vector3DList([k[3] for k in links]),
        linkMasses=[k[4] for k in links], linkCOMs=exu.Vector3DList([k[5] for k in links]),
        linkInertiasCOM=exu.Matrix3DList([k[6] for k in links]), gravity=list(GRAVITY)))
    tip = mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=n - 1,
                                                 localPosition=[LINK_LENGTH, 0.0, 0.0]))

    joint = None
    if clearance:
        rotation, offset = joint_frame(REPLACED_JOINT)
        journal_link = REPLACED_JOINT + 2  # after the two sliders
        markers = [mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=REPLACED_JOINT - 1,
                                                          localPosition=offset.tolist())),
                   mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=journal_link,
                                                          localPosition=[0.0, 0.0, 0.0]))]
        joint = exuclear.AddClearanceJoint(mbs, markers, axis=rotation[:, 2].tolist(), name="J1",
                                           **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                              **joint_options))
    mbs.Assemble()

    t_end = END_TIME if end_time is None else float(end_time)
    ss = example_settings(t_end, t_end / STEP)
    ss.solution.sensors.writePeriod = STEP
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0  # as the example (unused by explicit Euler)

    def probe(system: exu.MainSystem) -> np.ndarray:
        """Global position [m] of the chain's end (link 4 at 2 m)."""
        return np.asarray(system.GetMarkerOutput(tip, exu.OutputVariableType.Position), dtype=float)

    return ZooModel(name="kinematic_tree_chain", mbs=mbs, simulation_settings=ss,
                    solver_type=exu.DynamicSolverType.ExplicitEuler, joint=joint,
                    clearance=CLEARANCE if clearance else None, probe=probe,
                    solver_settings=exuclear.SolverSettings(end_time=t_end, method="rk44", step="auto",
                                                            output_step=t_end / OUTPUTS_PER_RUN),
                    # no probe bound: the ideal chain at the example's own explicit Euler step
                    # is itself 2.7 mm (54 c) off the converged path after 0.05 s
                    probe_bound=None)
