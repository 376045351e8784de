"""Exudyn's ``TestModels/sliderCrankFloatingTest.py``: a slider-crank on a floating frame.

The model as Exudyn writes it (its floating case): a frame (``ObjectRigidBody2D``, 2 kg,
1 kg m^2) held to the ground by three coordinate spring-dampers (k = 5000, d = 50); on it a
crank (0.1 m, 0.2 kg), a rod (0.3 m, 0.2 kg) and a slider (0.4 kg, 4e-4 kg m^2) joined by
``RevoluteJoint2D``; the slider in a ``PrismaticJoint2D`` (rotation held) on the frame at
(0.4, 0); a torque of 0.1 N m on the crank for t <= 2 s, no gravity; generalized-alpha
(Newmark, index-2 constraints), spectral radius 0.5, modified Newton with tolerances 1e-8,
3 s at 6e-5 s.  Replaced: the prismatic joint by ``exuclear.CreatePrismaticClearanceJoint``
on the frame (the guide) and the slider: the slider's 50 mm x 50 mm block (the example's
graphics) in a guide with c = 0.1 mm per side, corners ``K = 1e10 N/m^1.5`` with
Lankarani-Nikravesh damping, cr 0.9.  The guide turns with the frame.  The probe: the
slider's centre, which the joint carries.
"""
from __future__ import annotations

from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadCoordinate,
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodePosition,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinateSpringDamper,
    ObjectJointPrismatic2D,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
)

import exuclear

from ._common import PROBE_BOUND_CARRIED, ZooModel, example_settings, register, scaled_end, solver_settings_like

EXAMPLE = "TestModels/sliderCrankFloatingTest.py"
BODIES = "ObjectRigidBody2D, RevoluteJoint2D, PrismaticJoint2D"
REPLACED = "prismatic joint of the slider on the floating frame (a slider in a guide)"

L1, L2, M1, M2, M3 = 0.1, 0.3, 0.2, 0.2, 0.4
K_FRAME, TORQUE, TORQUE_END = 5000.0, 0.1, 2.0
END_TIME, STEPS = 3.0, 50000
#: The replaced joint: the slider block's size and the play per side [m], the corners' law.
SLIDER_SIZE, CLEARANCE = 0.05, 1e-4
JOINT = {"stiffness": 1e10, "exponent": 1.5, "damping": "lankarani-nikravesh", "cr": 0.9}


def _torque(mbs: exu.MainSystem, t: float, load: float) -> float:
    """The example's crank torque: on until t = 2 s."""
    return load if t <= TORQUE_END else 0.0


@register
def build(clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
    mbs = exu.SystemContainer().AddSystem()
    m_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    n_frame = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
    frame = mbs.AddObject(ObjectRigidBody2D(mass=2.0, inertia=1.0, nodeNumber=n_frame))
    for k in range(3):
        mbs.AddObject(ObjectConnectorCoordinateSpringDamper(
            markerNumbers=[m_ground, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_frame, coordinate=k))],
            stiffness=K_FRAME, damping=0.01 * K_FRAME))
    n_crank = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.5 * L1, 0, 0]))
    crank = mbs.AddObject(ObjectRigidBody2D(mass=M1, inertia=M1 / 12 * L1**2, nodeNumber=n_crank))
    rod = mbs.AddObject(ObjectRigidBody2D(mass=M2, inertia=M2 / 12 * L2**2, nodeNumber=mbs.AddNode(
        NodeRigidBody2D(referenceCoordinates=[L1 + 0.5 * L2, 0, 0]))))
    n_slider = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[L1 + L2, 0, 0]))
    slider = mbs.AddObject(ObjectRigidBody2D(mass=M3, inertia=0.001 * M3, nodeNumber=n_slider))

    def point(body: int, x: float) -> int:
        return mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[x, 0, 0]))

    for m0, m1 in ((mbs.AddMarker(MarkerNodePosition(nodeNumber=n_frame)), point(crank, -0.5 * L1)),
                   (point(crank, 0.5 * L1), point(rod, -0.5 * L2)), (point(rod, 0.5 * L2), point(slider, 0.0))):
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[m0, m1]))
    joint = None
    if clearance:
        joint = exuclear.CreatePrismaticClearanceJoint(
            mbs, name="guide", itemNumbers=[frame, slider], position=[L1 + L2, 0, 0], axis=[1, 0, 0],
            slider_length=SLIDER_SIZE, slider_height=SLIDER_SIZE, clearance=CLEARANCE, **{**JOINT, **joint_options})
    else:
        mbs.AddObject(ObjectJointPrismatic2D(markerNumbers=[
            mbs.AddMarker(MarkerBodyRigid(bodyNumber=frame, localPosition=[L1 + L2, 0, 0])),
            mbs.AddMarker(MarkerBodyRigid(bodyNumber=slider, localPosition=[0, 0, 0]))], constrainRotation=True))
    mbs.AddLoad(LoadCoordinate(markerNumber=mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_crank, coordinate=2)),
                               load=TORQUE, loadUserFunction=_torque))
    mbs.Assemble()

    ss = example_settings(END_TIME, STEPS)
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.timeIntegration.newton.relativeTolerance = 1e-8
    ss.timeIntegration.newton.absoluteTolerance = 1e-8
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.5
    ss.timeIntegration.generalizedAlpha.useNewmark = True
    ss.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    scaled_end(ss, end_time)
    solver = exu.DynamicSolverType.GeneralizedAlpha

    def probe(m: exu.MainSystem) -> np.ndarray:
        """The slider's centre (x, y) [m]."""
        return np.asarray(m.GetNodeOutput(n_slider, exu.OutputVariableType.Position))[:2]

    return ZooModel("slider_crank_floating", mbs, ss, solver, joint, CLEARANCE if clearance else None, probe,
                    solver_settings_like(ss, solver), probe_bound=PROBE_BOUND_CARRIED)
