"""The Exudyn items every clearance joint adds, whatever its type: the bearing-spin probe,
the data node, the joint's connector, the torque connector (``add_connectors``), then its
drawing, parameters, registration and sensors (``finish_items``).  A joint type's builder
(:mod:`~exuclear.engine.connector` for the revolute joint, :mod:`~exuclear.engine.spherical`
for the spherical one) makes its two rigid markers and calls these two, in this order:
Exudyn evaluates connectors in the order of their indices, and the probe must come before
the joint's connector, the torque connector after it (:mod:`~exuclear.engine.connector`)."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import exudyn as exu
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeGenericData,
    ObjectConnectorRigidBodySpringDamper,
    ObjectGround,
    SensorNode,
    SensorObject,
    VObjectConnectorRigidBodySpringDamper,
    VObjectGround,
)

from .handle import ClearanceJointHandle
from .registry import register


def add_connectors(mbs: exu.MainSystem, handle: ClearanceJointHandle, markers: list, rotation0: list,
                   bearing_rotates: bool, n_data: int, show: bool, draw_size: float) -> None:
    """The probe (where the bearing rotates), the data node of ``n_data`` entries, the joint's
    connector between ``markers`` [bearing or socket, journal or ball] in the joint frame
    ``rotation0`` (marker 0's frame), and the torque connector; their numbers into ``handle``."""
    name = handle.name
    m_bearing, m_journal = markers
    fns = handle.user_functions()
    hidden = VObjectConnectorRigidBodySpringDamper(show=False)
    m_ground = None
    if bearing_rotates:
        # the bearing can rotate: probe before the joint, torque connector after it
        ground = mbs.AddObject(ObjectGround(visualization=VObjectGround(show=False)))
        m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
        probe_node = mbs.AddNode(NodeGenericData(initialCoordinates=[0.0], numberOfDataCoordinates=1))
        handle.probeNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
            name=f"{name}:probe" if name else "", markerNumbers=[m_bearing, m_ground], nodeNumber=probe_node,
            rotationMarker0=rotation0, springForceTorqueUserFunction=fns["probe"],
            postNewtonStepUserFunction=fns["probe_post_newton"], visualization=hidden))
    handle.nodeNumber = mbs.AddNode(NodeGenericData(initialCoordinates=[0.0] * n_data, numberOfDataCoordinates=n_data))
    handle.objectNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
        name=name, markerNumbers=[m_bearing, m_journal], nodeNumber=handle.nodeNumber,
        rotationMarker0=rotation0,  # marker 1's rotation enters only Exudyn's relative angles, unused here
        springForceTorqueUserFunction=fns["force_torque"], postNewtonStepUserFunction=fns["post_newton"],
        visualization=VObjectConnectorRigidBodySpringDamper(show=show, drawSize=draw_size)))
    if m_ground is not None:
        handle.torqueNumber = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
            name=f"{name}:torque" if name else "", markerNumbers=[m_bearing, m_ground], rotationMarker0=rotation0,
            springForceTorqueUserFunction=fns["torque"], visualization=hidden))


def finish_items(mbs: exu.MainSystem, handle: ClearanceJointHandle, drawing: Callable[[Any], Any] | None,
                 record: bool, load_sensors: bool) -> None:
    """The drawing (``drawing(handle)``, a graphics function; None: not drawn), the parameters,
    the registration in the system, and, where the joint records (``record``), the data node's
    sensor and, with ``load_sensors``, the connector's ``ForceLocal`` and ``TorqueLocal`` sensors."""
    if drawing is not None:  # drawn by a graphics function, which only a renderer calls
        handle.drawingNumber = mbs.AddObject(ObjectGround(visualization=VObjectGround(
            show=True, graphicsDataUserFunction=drawing(handle))))
    handle._write_parameters()
    register(mbs, handle)
    if record:
        handle.sensorNumber = mbs.AddSensor(SensorNode(nodeNumber=handle.nodeNumber, storeInternal=True,
                                                       writeToFile=False,
                                                       outputVariableType=exu.OutputVariableType.Coordinates))
        if load_sensors:  # the resultant load of all contacts, as the connector applies it
            handle.loadSensorNumbers = [mbs.AddSensor(SensorObject(
                objectNumber=handle.objectNumber, storeInternal=True, writeToFile=False, outputVariableType=kind))
                for kind in (exu.OutputVariableType.ForceLocal, exu.OutputVariableType.TorqueLocal)]
