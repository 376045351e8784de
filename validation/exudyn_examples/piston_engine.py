"""Four-cylinder piston engine in 3D, after Exudyn's example
main/pythonDev/Examples/engineOpenVR.py (jgerstmayr/EXUDYN; the same engine as
Examples/openVRengine.py).

::

        piston 0   piston 1   piston 2   piston 3      pistons along y (90 deg), sliding in
          [ ]        [ ]        [ ]        [ ]         the engine block (GenericJoint: y, rz)
           |          |          |          |  conrods (revolute joints at the pistons)
           o <-- big end of cylinder 0: the clearance joint (bearing in the conrod,
          /           |     \\    |          journal = the crank pin of the crankshaft)
    ==o==/=====o======o======\\==o=====o==    crankshaft along z, throws at 0, 90, 270, 180 deg;
      main bearing (revolute joint to the block), driven at the crank's rotation coordinate

The example: ``EngineParameters([0, 90, 270, 180], [90] * 4)``, an in-line four of steel
parts (7850 kg/m^3): crankshaft of bearing cylinders, arms and 8 mm crank pins; conrods
of 100 mm; pistons of 20 mm radius; an engine block (a dummy rigid body fixed to the
ground by a ``GenericJoint``), all ``RotationEulerParameters`` nodes, no gravity.
Joints: the main bearing (revolute, block - crank), per cylinder a revolute at the crank
pin (crank - conrod) and at the piston pin (conrod - piston), and the piston's guide
(``GenericJoint`` holding y and the rotation about z in the piston's frame).  Drive: a
velocity-level ``CoordinateConstraint`` between the block's and the crank's rotation
coordinate 2, ramped by ``SmoothStep`` to omega = pi rad/s over 0.5 s, and switched off at
t = 1 s (``fixedSpeed = False``), after which the engine runs freely.  Generalized-alpha
(Exudyn's default spectral radius), step 2 ms, ``computeInitialAccelerations = False``,
``lieGroupAddTangentOperator = False``, sparse solver.

Kept: all of that, built with ``mbs.CreateRigidBody`` and ``mbs.CreateRevoluteJoint`` as
in openVRengine.py (engineOpenVR.py uses the older ``AddRigidBody`` /
``AddRevoluteJoint``), without graphics.  Changed: the end time.  The example's 3600 s is
the length of an interactive real-time VR session (``simulateInRealtime = True``), not a
simulated horizon; the zoo's default is :data:`END_TIME` = 2 s (the ramp, the driven
phase, the switch-off and a second of free running).  With ``clearance=True``:
cylinder 0's crank-pin (big-end) revolute joint becomes a clearance joint by
``exuclear.CreateClearanceJoint(itemNumbers=[conrod, crank])`` at the same position and
axis, with ``constrainAxial=True`` so that the conrod's axial motion and tilt stay held
as the replaced joint held them (no other joint holds them: conrod and piston would
float out of plane).  Pin: the example's crank pin, R_B = 8 mm, L = 24 mm; c = 30 um.

What each way of running it gives is checked in ``tests/test_exudyn_examples.py`` and
reported, with its numbers (reached time, wall time, steps, largest penetration,
verdict), by ``python -m validation.exudyn_examples --models piston_engine,piston_engine_lubricated``.

Variant ``piston_engine_lubricated`` (issue 23): the same big end with an oil film
(``lubrication=``, :data:`OIL`): an SAE 40 engine oil at SAE J300's smallest
high-temperature high-shear viscosity of its grade, 3.7 mPa s at 150 degC (the oil of
``validation/lubricated_slider_crank.py``, where its source is given), in the long-bearing
model: the pin's B/D = 24 / 16 = 1.5 lies above the finite model's fits (1/8 ... 1), and of
the two limits the long bearing is the nearer; it leaves out the leakage at the bearing's
ends, so it overestimates the film's load (docs/physics.md section 10.6: by 10.7 % still at
B/D = 8).  The engine turns at pi rad/s without gravity: the big end's load is a fraction
of a newton, and the film holds the journal near the centre of its bearing: the
example's own settings reach the end without metal contact.  Once the drive is off
(1 s), the film's viscous moment (docs/physics.md eq. (69)) brakes the free-running
engine, so its crank speed falls slightly below the ideal engine's and piston 0 lags.
"""
from __future__ import annotations

import math

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    MarkerNodeRotationCoordinate,
    ObjectConnectorCoordinate,
    ObjectGround,
    ObjectJointGeneric,
    VObjectConnectorCoordinate,
    VObjectJointGeneric,
)
from exudyn.rigidBodyUtilities import InertiaCuboid, InertiaCylinder, RotationMatrixZ
from exudyn.utilities import SmoothStep

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, joint_parameters, register, solver_settings_like

EXAMPLE = "main/pythonDev/Examples/engineOpenVR.py"
BODIES = "ObjectRigidBody (mbs.CreateRigidBody, Euler parameters), revolute and generic joints, velocity drive"
REPLACED = "crank pin (big end) of cylinder 0, crank - conrod"

# -- the example's engine (m, kg, rad) --------------------------------------------------
CRANK_ANGLES = (0.0, 90.0, 270.0, 180.0)   # crank throws [deg]
PISTON_ANGLES = (90.0, 90.0, 90.0, 90.0)   # cylinder axes [deg]
DENSITY = 7850.0                           # steel [kg/m^3]
PISTON_LENGTH, PISTON_RADIUS = 0.05, 0.02
CONROD_LENGTH, CONROD_HEIGHT, CONROD_WIDTH = 0.1, 0.02, 0.02
ARM_LENGTH, ARM_HEIGHT, ARM_WIDTH = 0.04, 0.016, 0.01
MAIN_BEARING_WIDTH, MAIN_BEARING_RADIUS = 0.012, 0.01
PIN_LENGTH, PIN_RADIUS = 0.024, 0.008      # crank pin (conrod - crank bearing)
CYLINDER_PITCH = MAIN_BEARING_WIDTH + 2 * ARM_WIDTH + PIN_LENGTH  # z distance of the cylinders
ENGINE_LENGTH = CYLINDER_PITCH * len(CRANK_ANGLES) + MAIN_BEARING_WIDTH
BLOCK_DENSITY, BLOCK_SIZE = 1000.0, 1.0    # the dummy engine block

# -- the example's drive and solver settings --------------------------------------------
OMEGA_DRIVE = 2 * math.pi * 0.5            # [rad/s]
RAMP_TIME = 0.5                            # the drive's SmoothStep from 0 to OMEGA_DRIVE [s]
DRIVE_OFF_TIME = 1.0                       # the drive is switched off here [s]
STEP = 0.002                               # [s]
END_TIME = 2.0                             # the zoo's default; the example: 3600 (module docstring)

# -- the clearance joint -----------------------------------------------------------------
CLEARANCE = 30e-6                          # radial clearance c [m]
BEARING_RADIUS = PIN_RADIUS                # R_B [m]
BEARING_LENGTH = PIN_LENGTH                # L [m]
REPLACED_CYLINDER = 0
#: The lubricated variant's oil (module docstring).
OIL = exuclear.Lubrication(viscosity=3.7e-3, model="long")


def _crank_inertia():
    """The crankshaft's inertia: main bearings, arms and crank pins, as the example sums them."""
    inertia = InertiaCylinder(DENSITY, MAIN_BEARING_WIDTH, MAIN_BEARING_RADIUS, axis=2).Translated(
        [0.0, 0.0, 0.5 * ENGINE_LENGTH - 0.5 * MAIN_BEARING_WIDTH])
    arm = InertiaCuboid(DENSITY, sideLengths=[ARM_LENGTH, ARM_HEIGHT, ARM_WIDTH])
    bearing = InertiaCylinder(DENSITY, MAIN_BEARING_WIDTH, MAIN_BEARING_RADIUS, axis=2)
    pin = InertiaCylinder(DENSITY, PIN_LENGTH, PIN_RADIUS, axis=2)
    for k, angle in enumerate(CRANK_ANGLES):
        a = RotationMatrixZ(math.radians(angle))
        z = _z_offset(k)
        inertia += bearing.Translated([0.0, 0.0, z + 0.5 * MAIN_BEARING_WIDTH])
        inertia += arm.Rotated(a).Translated(a @ [0.5 * ARM_LENGTH, 0.0, z + MAIN_BEARING_WIDTH + 0.5 * ARM_WIDTH])
        inertia += pin.Translated(a @ [ARM_LENGTH, 0.0, z + MAIN_BEARING_WIDTH + ARM_WIDTH + 0.5 * PIN_LENGTH])
        inertia += arm.Rotated(a).Translated(a @ [0.5 * ARM_LENGTH, 0.0,
                                                  z + MAIN_BEARING_WIDTH + 1.5 * ARM_WIDTH + PIN_LENGTH])
    return inertia


def _z_offset(k: int) -> float:
    """z [m] where cylinder k's section of the crankshaft begins."""
    return -0.5 * ENGINE_LENGTH + k * CYLINDER_PITCH


def _slider_crank(crank_angle: float, piston_angle: float) -> tuple[float, np.ndarray]:
    """Conrod angle [rad] and piston distance from the crank axis [m] of one cylinder
    (the planar slider-crank, in the cylinder's frame)."""
    phi1 = crank_angle - piston_angle
    phi2 = math.asin(ARM_LENGTH * math.sin(phi1) / CONROD_LENGTH)
    return piston_angle - phi2, ARM_LENGTH * math.cos(phi1) + CONROD_LENGTH * math.cos(phi2)


@register
def build(clearance: bool, end_time: float | None = None, **joint_options) -> ZooModel:
    """The example's engine; ``clearance=True`` puts a clearance joint at cylinder 0's crank pin."""
    mbs = exu.SystemContainer().AddSystem()
    node_type = exu.NodeType.RotationEulerParameters
    ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
    block = mbs.CreateRigidBody(inertia=InertiaCuboid(BLOCK_DENSITY, sideLengths=[BLOCK_SIZE] * 3),
                                nodeType=node_type, referencePosition=[0.0, 0.0, 0.0], returnDict=True, show=False)
    mbs.AddObject(ObjectJointGeneric(
        markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=block["bodyNumber"])),
                       mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))],
        constrainedAxes=[1] * 6, visualization=VObjectJointGeneric(show=False)))

    conrod_inertia = InertiaCuboid(DENSITY, sideLengths=[CONROD_LENGTH, CONROD_HEIGHT, CONROD_WIDTH])
    piston_inertia = InertiaCylinder(DENSITY, length=PISTON_LENGTH, outerRadius=PISTON_RADIUS,
                                     innerRadius=0.5 * PISTON_RADIUS, axis=0)
    cylinders = []
    for k, (crank_deg, piston_deg) in enumerate(zip(CRANK_ANGLES, PISTON_ANGLES)):
        crank_angle, piston_angle = math.radians(crank_deg), math.radians(piston_deg)
        conrod_angle, distance = _slider_crank(crank_angle, piston_angle)
        z_pin = _z_offset(k) + MAIN_BEARING_WIDTH + ARM_WIDTH + 0.5 * PIN_LENGTH  # the cylinder's mid-plane
        a_crank, a_conrod, a_piston = (RotationMatrixZ(a) for a in (crank_angle, conrod_angle, piston_angle))
        pin = a_crank @ [ARM_LENGTH, 0.0, 0.0] + np.array([0.0, 0.0, z_pin])
        conrod = mbs.CreateRigidBody(inertia=conrod_inertia, nodeType=node_type,
                                     referencePosition=pin + a_conrod @ [0.5 * CONROD_LENGTH, 0.0, 0.0],
                                     referenceRotationMatrix=a_conrod)
        piston_pin = a_piston @ [distance, 0.0, 0.0] + np.array([0.0, 0.0, z_pin])
        piston = mbs.CreateRigidBody(inertia=piston_inertia, nodeType=node_type, referencePosition=piston_pin,
                                     referenceRotationMatrix=a_piston)
        cylinders.append((conrod, piston, pin, piston_pin, a_piston))
    crank = mbs.CreateRigidBody(inertia=_crank_inertia(), nodeType=node_type, referencePosition=[0.0, 0.0, 0.0],
                                returnDict=True)

    mbs.CreateRevoluteJoint(itemNumbers=[block["bodyNumber"], crank["bodyNumber"]],
                            position=[0.0, 0.0, -0.5 * ENGINE_LENGTH], axis=[0.0, 0.0, 1.0], show=False)
    joint = None
    for k, (conrod, piston, pin, piston_pin, a_piston) in enumerate(cylinders):
        if clearance and k == REPLACED_CYLINDER:
            joint = exuclear.CreateClearanceJoint(
                mbs, name="big end 0", itemNumbers=[conrod, crank["bodyNumber"]], position=pin.tolist(),
                axis=[0.0, 0.0, 1.0], constrainAxial=True,
                **joint_parameters(BEARING_RADIUS, CLEARANCE, BEARING_LENGTH, **joint_options))
        else:
            mbs.CreateRevoluteJoint(itemNumbers=[crank["bodyNumber"], conrod], position=pin.tolist(),
                                    axis=[0.0, 0.0, 1.0], show=False)
        mbs.CreateRevoluteJoint(itemNumbers=[conrod, piston], position=piston_pin.tolist(), axis=[0.0, 0.0, 1.0],
                                show=False)
        guide = exu.HT(rotation=a_piston, translation=piston_pin)  # the cylinder's frame in the block
        mbs.AddObject(ObjectJointGeneric(  # the piston's guide: y and rotation about z, in the cylinder's frame
            markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=piston, localPosition=[0.0, 0.0, 0.0])),
                           mbs.AddMarker(MarkerBodyRigid(bodyNumber=block["bodyNumber"], localHT=guide))],
            constrainedAxes=[0, 1, 0, 0, 0, 1], visualization=VObjectJointGeneric(show=False)))

    def drive_offset(mbs_: exu.MainSystem, t: float, item: int, offset: float) -> float:
        return 0.0

    def drive_speed(mbs_: exu.MainSystem, t: float, item: int, offset: float) -> float:
        return SmoothStep(t, 0.0, RAMP_TIME, 0.0, OMEGA_DRIVE)

    drive = mbs.AddObject(ObjectConnectorCoordinate(
        markerNumbers=[mbs.AddMarker(MarkerNodeRotationCoordinate(nodeNumber=block["nodeNumber"], rotationCoordinate=2)),
                       mbs.AddMarker(MarkerNodeRotationCoordinate(nodeNumber=crank["nodeNumber"], rotationCoordinate=2))],
        velocityLevel=True, offsetUserFunction=drive_offset, offsetUserFunction_t=drive_speed,
        visualization=VObjectConnectorCoordinate(show=False)))

    def switch_off_drive(mbs_: exu.MainSystem, t: float) -> bool:
        if t >= DRIVE_OFF_TIME:  # the example's fixedSpeed = False
            mbs_.SetObjectParameter(drive, "activeConnector", False)
        return True

    mbs.SetPreStepUserFunction(switch_off_drive)
    mbs.Assemble()

    t_end = END_TIME if end_time is None else float(end_time)
    ss = example_settings(t_end, t_end / STEP)
    ss.timeIntegration.generalizedAlpha.computeInitialAccelerations = False
    ss.timeIntegration.generalizedAlpha.lieGroupAddTangentOperator = False
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.solution.sensors.writePeriod = 10 * STEP

    piston0 = cylinders[REPLACED_CYLINDER][1]

    def probe(system: exu.MainSystem) -> np.ndarray:
        """Position [m] of piston 0, which the replaced joint carries through its conrod."""
        return np.asarray(system.GetObjectOutputBody(piston0, exu.OutputVariableType.Position,
                                                     localPosition=[0.0, 0.0, 0.0]), dtype=float)

    solver = exu.DynamicSolverType.GeneralizedAlpha
    return ZooModel(name="piston_engine", mbs=mbs, simulation_settings=ss, solver_type=solver, joint=joint,
                    clearance=CLEARANCE if clearance else None, probe=probe,
                    solver_settings=solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)


register(build, name="piston_engine_lubricated", lubrication=OIL)
