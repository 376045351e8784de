"""Spatial slider-crank (the IFToMM benchmark), after Exudyn's test model
main/pythonDev/TestModels/sliderCrank3Dbenchmark.py (jgerstmayr/EXUDYN).

::

            crank AB (0.08 m) turns about x at A = (0, 0.1, 0.12): the main bearing,
       B o  here the clearance joint
         |\\
       A o \\ conrod BC (0.3 m), spherical joint at B,
            \\ universal-type joint at C (the conrod's axis normal to the slider's y axis)
             \\
              o C = (0.2, 0, 0)  slider [==] on the x axis (prismatic joint to the ground)
    gravity -9.81 m/s^2 along z

The example: the IFToMM library's spatial rigid slider-crank (crank 0.12 kg, conrod
0.5 kg, slider 2 kg, their inertia tensors as given there), three rigid bodies on
Euler-parameter nodes by ``mbs.CreateRigidBody`` with gravity, joined to the ground and to
each other by ``mbs.CreateGenericJoint``: the crank's revolute joint about x at A
(constrained axes [1, 1, 1, 0, 1, 1]), the slider's prismatic joint along x ([0, 1, 1,
1, 1, 1]), a spherical joint at B ([1, 1, 1, 0, 0, 0]) and at C a joint holding the
position and the rotation about z of the global frame ([1, 1, 1, 0, 0, 1]); the crank
starts at 0 deg (B straight above A) at 6 rad/s, the conrod and the slider with the
velocities that go with it (the example's values); no drive, no damping: the mechanism
runs freely under gravity.  Generalized-alpha, spectral radius 0.9, step 1e-4 s, 5 s,
modified Newton, sparse solver, initial accelerations computed, no Lie-group tangent
operator.

Kept: all of it, except: no renderer, no solution file, the torsional spring-damper
(stiffness 0) that the example adds only to measure full crank revolutions when graphics
are on, and the conrod's initial angular velocity.  The example's [1.92, -0.96, 0.48]
rad/s breaks the joint at C: that joint keeps the conrod's x axis (global x at the start)
normal to the slider's y axis, which asks for a conrod angular velocity without z
component at the start.  Exudyn's index-3 generalized-alpha corrects it in its first
steps by a velocity oscillation that its numerical damping removes within some 5 ms,
taking 1.0e-4 J of the mechanism's 0.77 J with it, at any step.  The model gives the
conrod the spin about its own axis (B to C, the direction (2, -1, -2) / 3) that makes up
the difference, 0.72 rad/s: [2.4, -1.2, 0] rad/s; the velocities of B and C are the
example's, and the ideal model keeps its energy from the start.

Replaced with ``clearance=True``: the crank's main bearing (ground - crank at A, axis x),
the mechanism's one revolute joint: ``exuclear.CreateClearanceJoint(itemNumbers=
[ground, crank])`` at A, axis x, ``constrainAxial=True`` so that the crank's axial motion
and tilt stay held as the replaced joint held them (no other joint holds them).  Pin:
the example draws the crank as a link of radius 10 mm and width 20 mm: R_B = 10 mm,
L = 20 mm, c = 30 um.
"""
from __future__ import annotations

import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.rigidBodyUtilities import RigidBodyInertia

import exuclear

from .._common import (
    PROBE_BOUND_CARRIED,
    ZooModel,
    example_settings,
    joint_parameters,
    register,
    rigid_body_energy,
    scaled_end,
    solver_settings_like,
)

EXAMPLE = "main/pythonDev/TestModels/sliderCrank3Dbenchmark.py"
BODIES = "mbs.CreateRigidBody (Euler parameters), mbs.CreateGenericJoint: revolute, prismatic, spherical, universal"
REPLACED = "the crank's main bearing (ground - crank) at A = (0, 0.1, 0.12), axis x"

# -- the benchmark's model (m, kg, s) ----------------------------------------------------
GRAVITY = (0.0, 0.0, -9.81)
CRANK_LENGTH, CONROD_LENGTH = 0.08, 0.3   # AB, BC [m]
A_Y, A_Z = 0.1, 0.12                      # the crank's axis through (0, A_Y, A_Z) [m]
CRANK_MASS, CONROD_MASS, SLIDER_MASS = 0.12, 0.5, 2.0
CRANK_INERTIA = (1e-4, 1e-4, 1e-5)        # about the crank's centre, its axis along z [kg m^2]
CONROD_INERTIA = (4e-4, 4e-3, 4e-3)       # the conrod's axis along x (the example's choice)
SLIDER_INERTIA = (1e-4, 1e-4, 1e-4)
CRANK_OMEGA = (6.0, 0.0, 0.0)             # the crank's initial angular velocity [rad/s]
#: The conrod's and the slider's initial velocities that go with it: the example's, except
#: the conrod's spin about its own axis (module docstring).
CONROD_VELOCITY, CONROD_OMEGA = (0.12, -0.24, 0.0), (2.4, -1.2, 0.0)
SLIDER_VELOCITY = (0.24, 0.0, 0.0)

# -- the example's solver settings -------------------------------------------------------
END_TIME = 5.0                            # [s]
STEP = 1e-4                               # [s]
SENSOR_PERIOD = 1e-3                      # [s]

# -- the clearance joint -----------------------------------------------------------------
CLEARANCE = 30e-6                         # radial clearance c [m]
BEARING_RADIUS = 0.01                     # R_B [m]: the crank's drawn radius
BEARING_LENGTH = 0.02                     # L [m]: the crank's drawn width


def geometry() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Points A, B, C [m] at crank angle 0 (B above A) and the conrod's rotation matrix
    (its x axis from B to C, its z axis in the plane of BC and A's position vector)."""
    a = np.array([0.0, A_Y, A_Z])
    b = a + [0.0, 0.0, CRANK_LENGTH]
    c = np.array([math.sqrt(CONROD_LENGTH ** 2 - A_Y ** 2 - (A_Z + CRANK_LENGTH) ** 2), 0.0, 0.0])
    x = (c - b) / np.linalg.norm(c - b)
    z = b - (b @ x) * x
    z /= np.linalg.norm(z)
    return a, b, c, np.column_stack([x, -np.cross(x, z), z])


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    """The benchmark's slider-crank; ``clearance=True`` puts a clearance joint at the crank's bearing."""
    mbs = exu.SystemContainer().AddSystem()
    node_type = exu.NodeType.RotationEulerParameters
    a, b, c, conrod_rotation = geometry()
    inertias = [RigidBodyInertia(mass=CRANK_MASS, inertiaTensor=np.diag(CRANK_INERTIA)).Translated(
                    [0.0, 0.0, 0.5 * CRANK_LENGTH]),
                RigidBodyInertia(mass=CONROD_MASS, inertiaTensor=np.diag(CONROD_INERTIA)),
                RigidBodyInertia(mass=SLIDER_MASS, inertiaTensor=np.diag(SLIDER_INERTIA))]
    crank = mbs.CreateRigidBody(inertia=inertias[0], nodeType=node_type, referencePosition=a,
                                initialAngularVelocity=list(CRANK_OMEGA), gravity=list(GRAVITY), show=False)
    conrod = mbs.CreateRigidBody(inertia=inertias[1], nodeType=node_type, referencePosition=0.5 * (b + c),
                                 referenceRotationMatrix=conrod_rotation, initialVelocity=list(CONROD_VELOCITY),
                                 initialAngularVelocity=list(CONROD_OMEGA), gravity=list(GRAVITY), show=False)
    slider = mbs.CreateRigidBody(inertia=inertias[2], nodeType=node_type, referencePosition=c,
                                 initialVelocity=list(SLIDER_VELOCITY), gravity=list(GRAVITY), show=False)
    ground = mbs.CreateGround(show=False)

    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(mbs, name="main bearing", itemNumbers=[ground, crank],
                                              position=a.tolist(), axis=[1.0, 0.0, 0.0], constrainAxial=True,
                                              **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH,
                                                                 **joint_options))
    else:
        mbs.CreateGenericJoint(itemNumbers=[ground, crank], position=a.tolist(), constrainedAxes=[1, 1, 1, 0, 1, 1],
                               useGlobalFrame=False, show=False)
    mbs.CreateGenericJoint(itemNumbers=[ground, slider], position=[0.0, 0.0, 0.0], constrainedAxes=[0, 1, 1, 1, 1, 1],
                           useGlobalFrame=False, show=False)
    mbs.CreateGenericJoint(itemNumbers=[crank, conrod], position=[0.0, 0.0, CRANK_LENGTH],
                           constrainedAxes=[1, 1, 1, 0, 0, 0], useGlobalFrame=False, show=False)
    mbs.CreateGenericJoint(itemNumbers=[conrod, slider], position=c.tolist(), constrainedAxes=[1, 1, 1, 0, 0, 1],
                           useGlobalFrame=True, show=False)
    mbs.Assemble()

    ss = example_settings(END_TIME, END_TIME / STEP)
    scaled_end(ss, end_time)
    ti = ss.timeIntegration
    ti.generalizedAlpha.spectralRadius = 0.9
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.generalizedAlpha.lieGroupAddTangentOperator = False
    ti.newton.useModifiedNewton = True
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.solution.sensors.writePeriod = SENSOR_PERIOD

    def probe(system: exu.MainSystem) -> np.ndarray:
        """The slider's position [m], which the crank drives through the conrod."""
        return np.asarray(system.GetObjectOutputBody(slider, exu.OutputVariableType.Position,
                                                     localPosition=[0.0, 0.0, 0.0]), dtype=float)

    solver = exu.DynamicSolverType.GeneralizedAlpha
    return ZooModel("slider_crank_3d", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver),
                    energy=rigid_body_energy([crank, conrod, slider], inertias, GRAVITY),
                    probe_bound=PROBE_BOUND_CARRIED)
