"""3D double pendulum of two steel bars, after exuclear issue 20 (not an Exudyn example).

The model of the issue: two steel bars 0.3 m x 20 mm x 20 mm (7850 kg/m^3, 0.942 kg
each) from ``mbs.CreateRigidBody``, released from rest along the x axis under gravity
-9.81 m/s^2 in y; the shoulder (ground to bar 1 at the origin, axis z) a
``mbs.CreateRevoluteJoint``, the elbow (bar 1 to bar 2 at (0.3, 0, 0), axis z) an
``exuclear.CreateClearanceJoint``: R_B 10 mm, R_J 9.9 mm (c = 0.1 mm), L 20 mm, Wang-Liu,
cr 0.7, steel on steel, no friction, and the joint's default ``constrainAxial=False`` as
in the issue (gravity and the contact act in the xy plane through the bars' axes, so
nothing drives the axial or tilt motion the clearance joint leaves free; ``exuclear.simulate``
warns that nothing holds it, ``OutOfPlaneWarning``).  The clearance joint's ``ForceLocal``
is in the replaced revolute joint's frame (tests/test_bodies.py compares the two).  Exudyn's
default generalized-alpha (spectral radius 0.9), 1 s, at the issue's fixed step 1e-4 s
(Exudyn's default of 100 steps per second would be 1e-2 s).

Known (issue 20): at 1e-4 s the plain path gives a penetration of 0.35 c and 6.6 kN
silently; at 2e-4 s it stops with "check your Python code!"; at 2.5e-5 s it is right.
Measured with this model (Exudyn 1.13.6, plain ``mbs.SolveDynamic``): at 1e-4 s the
Euler-parameter and rotation-vector models finish at 0.011 c / 265 N and 0.007 c / 168 N
(the issue's 0.35 c is not reproduced), the Rxyz model stops at t = 0.072 s at the
joint's penetration limit; at 2e-4 s all three stop there, with Exudyn's "check your
Python code!"; at 2.5e-5 s the Euler-parameter model is right (tests/test_exudyn_examples.py).
The node type of both bars is a parameter: the zoo registers one model per rotation
parametrisation (Euler parameters, Rxyz, rotation vector), and the Euler-parameter model
once more with ``friction="paper"`` (the paper's modified Coulomb law).

    ground o========= bar 1 =========o========= bar 2 =========
           shoulder (0, 0, 0)     elbow (0.3, 0, 0), clearance joint
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import exudyn.utilities as eu
import numpy as np

import exuclear

from ._common import (
    JOINT_DEFAULTS,
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    register,
    rigid_body_energy,
    scaled_end,
    solver_settings_like,
)

EXAMPLE = "exuclear issue 20 (3D double pendulum of two steel bars)"
BODIES = "mbs.CreateRigidBody (NodeRigidBodyEP / Rxyz / RotVecLG), mbs.CreateRevoluteJoint"
REPLACED = "elbow between bar 1 and bar 2 at (0.3, 0, 0), axis z"

DENSITY, BAR_LENGTH, BAR_WIDTH, GRAVITY = 7850.0, 0.3, 0.02, 9.81  # steel bar [kg/m^3, m, m, m/s^2]
#: The issue's settings: 1 s at a fixed step of 1e-4 s.
END_TIME, STEP = 1.0, 1e-4
#: The issue's joint: journal radius, bearing radius, length [m]; cr 0.7.
JOURNAL_RADIUS, BEARING_RADIUS, BEARING_LENGTH, CR = 9.9e-3, 10e-3, 20e-3, 0.7

#: Node types of the registered variants.
NODE_TYPES = {"ep": exu.NodeType.RotationEulerParameters, "rxyz": exu.NodeType.RotationRxyz,
              "rotvec": exu.NodeType.RotationRotationVector}


def build(clearance: bool, end_time: float | None = None, node_type: str = "ep", **joint_options: Any) -> ZooModel:
    if node_type not in NODE_TYPES:
        raise ValueError(f"`node_type` must be one of {sorted(NODE_TYPES)}, got {node_type!r}")
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    inertia = eu.InertiaCuboid(DENSITY, [BAR_LENGTH, BAR_WIDTH, BAR_WIDTH])
    bars = [mbs.CreateRigidBody(inertia=inertia, referencePosition=[(k + 0.5) * BAR_LENGTH, 0, 0],
                                gravity=[0, -GRAVITY, 0], nodeType=NODE_TYPES[node_type]) for k in range(2)]
    mbs.CreateRevoluteJoint(itemNumbers=[ground, bars[0]], position=[0, 0, 0], axis=[0, 0, 1])
    elbow = [BAR_LENGTH, 0, 0]
    joint = None
    if clearance:
        options = {**JOINT_DEFAULTS, "cr": CR, **joint_options}
        joint = exuclear.CreateClearanceJoint(mbs, name="elbow", itemNumbers=bars, position=elbow, axis=[0, 0, 1],
                                              journal_radius=JOURNAL_RADIUS, bearing_radius=BEARING_RADIUS,
                                              length=BEARING_LENGTH, **options)
    else:
        mbs.CreateRevoluteJoint(itemNumbers=bars, position=elbow, axis=[0, 0, 1])
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha  # Exudyn's default

    def probe(m: exu.MainSystem) -> np.ndarray:
        """Free end of bar 2 (x, y, z) [m]."""
        return np.asarray(m.GetObjectOutputBody(bars[1], exu.OutputVariableType.Position,
                                                localPosition=[0.5 * BAR_LENGTH, 0, 0]))

    return ZooModel(f"double_pendulum_3d_{node_type}", mbs, ss, solver, joint,
                    BEARING_RADIUS - JOURNAL_RADIUS if clearance else None, probe, solver_settings_like(ss, solver),
                    probe_bound=PROBE_BOUND_CARRIED, energy=rigid_body_energy(bars, [inertia] * 2, [0, -GRAVITY, 0]))


for _name in NODE_TYPES:  # one registered model per node type
    register(build, name=f"double_pendulum_3d_{_name}", node_type=_name)
register(build, name="double_pendulum_3d_ep_friction", node_type="ep", friction="paper")
