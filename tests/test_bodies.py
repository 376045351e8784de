"""Every body a user brings (issue 21): flexible elements, node markers, kinematic trees,
and ``CreateClearanceJoint`` as a drop-in for ``mbs.CreateRevoluteJoint``."""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    MarkerBodyRigid,
    MarkerKinematicTreeRigid,
    MarkerNodeRigid,
    NodeGenericODE2,
    NodePoint2DSlope1,
    NodeRigidBody2D,
    ObjectANCFCable2D,
    ObjectBeamGeometricallyExact2D,
    ObjectGround,
    ObjectKinematicTree,
    ObjectRigidBody2D,
    SensorObject,
)
from exudyn.rigidBodyUtilities import InertiaCuboid

import exuclear
from exuclear.engine.bodies import body_mass
from exuclear.engine.connector import revolute_frame

R_B, R_J, L = 10e-3, 9.9e-3, 15e-3
PIN = dict(journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.9)
OV, REF = exu.OutputVariableType, exu.ConfigurationType.Reference

#: An ANCF cable element, tilted in the plane (slope (0.6, 0.8)), and its mass.
CABLE_START, CABLE_SLOPE, CABLE_LENGTH, CABLE_RHO_A = np.array([0.1, 0.2, 0.0]), np.array([0.6, 0.8, 0.0]), 0.04, 10.0
#: Two geometrically exact 2D beam elements along x: length, mass per length.
BEAM_LENGTH, BEAM_RHO_A = 0.05, 0.02


def _cable(mbs):
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[*(CABLE_START + s * CABLE_SLOPE)[:2], 0.6, 0.8]))
             for s in (0.0, CABLE_LENGTH)]
    return mbs.AddObject(ObjectANCFCable2D(nodeNumbers=nodes, length=CABLE_LENGTH, massPerLength=CABLE_RHO_A,
                                           bendingStiffness=1.0, axialStiffness=1e3))


def _beams(mbs):
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[k * BEAM_LENGTH, 0.0, 0.0])) for k in range(3)]
    beams = [mbs.AddObject(ObjectBeamGeometricallyExact2D(
        nodeNumbers=nodes[k:k + 2], length=BEAM_LENGTH, massPerLength=BEAM_RHO_A, crossSectionInertia=1e-8,
        bendingStiffness=1e-2, axialStiffness=1e3, shearStiffness=1e3)) for k in range(2)]
    return nodes, beams


def test_create_on_an_ancf_cable_puts_the_journal_at_position_on_its_axis():
    # before: "ObjectANCFCable2D (a body) has no OutputVariableType 'RotationMatrix'"
    mbs = exu.SystemContainer().AddSystem()
    ground, cable = mbs.AddObject(ObjectGround()), _cable(mbs)
    position = CABLE_START + 0.5 * CABLE_LENGTH * CABLE_SLOPE  # the element's midpoint
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, cable], position=position.tolist(), **PIN)
    for marker in handle.markerNumbers:
        assert np.allclose(mbs.GetMarkerOutput(marker, OV.Position, configuration=REF), position, rtol=0, atol=1e-15)
    # the journal's marker sits on the element at half its length, its frame is the joint frame
    assert np.allclose(mbs.GetMarker(handle.markerNumbers[1])["localHT"][:3, 3], [0.5 * CABLE_LENGTH, 0, 0])
    assert np.allclose(handle.frame, revolute_frame(np.array([0.0, 0.0, 1.0])), atol=1e-15)


def test_body_mass_reads_flexible_elements_and_node_markers():
    # before: NaN for both elements (step="auto" refused), and mbs.GetObject(None) for a node marker
    mbs = exu.SystemContainer().AddSystem()
    cable = _cable(mbs)
    nodes, _ = _beams(mbs)
    on_cable = mbs.AddMarker(MarkerBodyRigid(bodyNumber=cable, localPosition=[0, 0, 0]))
    assert body_mass(mbs, on_cable) == pytest.approx(CABLE_RHO_A * CABLE_LENGTH, rel=1e-15)
    # a node's lumped mass: half of each two-node element it belongs to
    end, middle = (mbs.AddMarker(MarkerNodeRigid(nodeNumber=n)) for n in (nodes[0], nodes[1]))
    assert body_mass(mbs, end) == pytest.approx(0.5 * BEAM_RHO_A * BEAM_LENGTH, rel=1e-15)
    assert body_mass(mbs, middle) == pytest.approx(BEAM_RHO_A * BEAM_LENGTH, rel=1e-15)


def test_a_geometrically_exact_beam_is_refused_naming_the_node_marker():
    # before: built, then "illegal call to CObjectBody::GetAngularVelocityLocal" at the first step
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    nodes, beams = _beams(mbs)
    n_markers = mbs.systemData.NumberOfMarkers()
    with pytest.raises(ValueError, match=r"`itemNumbers\[1\]` is on object .* ObjectBeamGeometricallyExact2D.*"
                                         r"MarkerNodeRigid.*AddClearanceJoint"):
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, beams[0]], **PIN)
    assert mbs.systemData.NumberOfMarkers() == n_markers  # refused before any item is added
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)), mbs.AddMarker(MarkerBodyRigid(bodyNumber=beams[0]))]
    with pytest.raises(ValueError, match=r"`markerNumbers\[1\]` \(a MarkerBodyRigid\).*MarkerNodeRigid"):
        exuclear.AddClearanceJoint(mbs, markers, **PIN)


def test_a_node_marker_in_item_numbers_runs_through_simulate():
    # before: simulate raised "failed to convert to ObjectIndex, but received None" (_diagnostics._body_of)
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    nodes, _ = _beams(mbs)
    node_marker = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0]))
    with pytest.raises(ValueError, match="`position` must be omitted"):
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, node_marker], position=[0.1, 0, 0], **PIN)
    handle = exuclear.CreateClearanceJoint(mbs, name="pin", itemNumbers=[ground, node_marker], **PIN)
    assert handle.markerNumbers[1] != node_marker  # a copy turned into the joint frame, as Exudyn makes it
    assert np.allclose(mbs.GetMarkerOutput(handle.markerNumbers[0], OV.Position, configuration=REF), 0.0)
    assert handle.nodes == [int(nodes[0])]
    mbs.Assemble()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3))
    assert result.success, result.message


def _tree(mbs):
    """A crank (RevoluteZ) and, on it, a pin link with in-plane play (PrismaticX, PrismaticY, RevoluteZ)."""
    types = [exu.JointType.RevoluteZ, exu.JointType.PrismaticX, exu.JointType.PrismaticY, exu.JointType.RevoluteZ]
    n = len(types)
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                       initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    return mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, linkParents=[-1, 0, 1, 2], jointTypes=types,
        jointTransformations=exu.Matrix3DList([np.eye(3)] * n),
        jointOffsets=exu.Vector3DList([[0, 0, 0], [0.2, 0, 0], [0, 0, 0], [0, 0, 0]]),
        linkInertiasCOM=exu.Matrix3DList([np.diag([0, 0, 1e-3])] * n), linkCOMs=exu.Vector3DList([[0, 0, 0]] * n),
        linkMasses=[1.0, 0.0, 0.0, 0.5], gravity=[0, -9.81, 0]))


def test_a_kinematic_tree_is_refused_and_its_link_markers_are_taken():
    # before: "ObjectKinematicTree (a body) has no OutputVariableType 'Position'"
    mbs = exu.SystemContainer().AddSystem()
    tree = _tree(mbs)
    with pytest.raises(ValueError, match=r"ObjectKinematicTree.*PrismaticX and PrismaticY.*MarkerKinematicTreeRigid"):
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[tree, tree], position=[0.2, 0, 0], **PIN)
    links = [mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=k, localPosition=p))
             for k, p in ((0, [0.2, 0, 0]), (3, [0, 0, 0]))]
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=links, **PIN)
    mbs.Assemble()
    assert body_mass(mbs, handle.markerNumbers[1]) == 0.5
    assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3)).success


def _pendulum():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=mbs.AddNode(NodeRigidBody2D()), mass=1.0, inertia=1e-3))
    return mbs, ground, body


def test_create_revolute_joint_keywords_are_taken():
    mbs, ground, body = _pendulum()
    with pytest.warns(DeprecationWarning, match="`bodyNumbers` is deprecated.*`itemNumbers`"):
        handle = exuclear.CreateClearanceJoint(mbs, bodyNumbers=[ground, body], axisRadius=0.02, axisLength=0.05,
                                               color=[1, 0, 0, 1], **PIN)
    assert handle._drawing == {"radius": 0.02, "length": 0.05, "color": [1.0, 0.0, 0.0, 1.0]}
    mbs, ground, body = _pendulum()
    with pytest.raises(ValueError, match="give `itemNumbers` only"):
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], bodyNumbers=[ground, body], **PIN)
    with pytest.raises(ValueError, match="`axisRadius` must be positive"):
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], axisRadius=-1.0, **PIN)
    # positional, in mbs.CreateRevoluteJoint's order
    handle = exuclear.CreateClearanceJoint(mbs, "j", [ground, body], [0, 0, 0], [0, 0, 1], True, False, 0.1, 0.4,
                                           **PIN)
    assert handle.name == "j" and handle.drawingNumber is None


def test_force_local_is_in_the_frame_of_the_replaced_revolute_joint():
    # issue 21: the 3D double pendulum (validation/exudyn_examples/double_pendulum_3d.py),
    # elbow replaced; means of ForceLocal over the last 0.3 s of 1 s.  Before: ideal
    # [2.30, 5.88] N, clearance [5.72, -2.35] N (the global frame, 90 degrees off)
    from validation.exudyn_examples import double_pendulum_3d

    means = []
    for clearance in (False, True):
        model = double_pendulum_3d.build(clearance)
        mbs = model.mbs
        elbow = model.joint.objectNumber if clearance else [
            i for i in range(mbs.systemData.NumberOfObjects()) if mbs.GetObject(i)["objectType"] == "JointRevoluteZ"][1]
        sensor = mbs.AddSensor(SensorObject(objectNumber=elbow, storeInternal=True, writeToFile=False,
                                            outputVariableType=OV.ForceLocal))
        mbs.Assemble()
        mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        data = mbs.GetSensorStoredData(sensor)
        means.append(data[data[:, 0] >= data[-1, 0] - 0.3, 1:].mean(axis=0))
    ideal, clearance = means
    assert ideal[:2] == pytest.approx([2.30, 5.88], abs=0.01)  # measured, Exudyn 1.13.6
    # the clearance's impacts and sliding move the mean by 0.05 and 0.16 N (measured): 0.3 N
    assert np.allclose(clearance, ideal, rtol=0.0, atol=0.3)
    assert math.isclose(clearance[2], 0.0, abs_tol=1e-9)


def test_step_auto_names_the_body_whose_mass_is_not_read():
    # before: "the mass of one of its bodies is not read", not naming which
    from exudyn.itemInterface import ObjectGenericODE2

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D())
    mbs.AddObject(ObjectGenericODE2(nodeNumbers=[node], massMatrix=np.eye(3)))  # a mass matrix, no mass
    exuclear.CreateClearanceJoint(mbs, "pin", [ground, mbs.AddMarker(MarkerNodeRigid(nodeNumber=node))], **PIN)
    mbs.Assemble()
    with pytest.raises(ValueError, match=r"the mass of its journal body \(node 0\) is not read.*give `step`"):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3, method="generalized-alpha", step="auto",
                                                       joint_steps=False))


@pytest.mark.parametrize("constrain", [False, True])
def test_out_of_plane_motion_nothing_holds_is_named_before_the_run(constrain):
    # issue 21: rigidBodyTutorial3 with its second joint replaced and constrainAxial=False
    # drifted 6 mm along the axis and stopped with "contact too soft for the load ... or a
    # unit is off", never naming the cause
    from validation.exudyn_examples import rigid_body_tutorial3

    model = rigid_body_tutorial3.build(True, 1e-3, constrainAxial=constrain)
    assert exuclear.engine.unheld_motion(model.mbs) == ({} if constrain else
                                                 {model.joint.name: ["axial translation", "tilt"]})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        exuclear.simulate(model.mbs, replace_step(model.solver_settings))
    notes = [str(w.message) for w in caught if issubclass(w.category, exuclear.engine.OutOfPlaneWarning)]
    if constrain:
        assert notes == []
    else:
        assert len(notes) == 1 and "axial translation and tilt" in notes[0] and "constrainAxial=True" in notes[0]


def replace_step(settings):
    from dataclasses import replace

    return replace(settings, end_time=1e-3)


@pytest.mark.parametrize("name", ["double_pendulum_2d", "piston_engine", "kinematic_tree_chain", "ancf_pendulum",
                                  "four_bar_kinematic_tree", "flyball_governor_tree", "slider_crank_3d",
                                  "ancf_rotating_cable"])
def test_models_whose_joints_hold_the_plane_are_not_warned(name):
    # planar bodies, closed loops and kinematic trees hold what the replaced joint held (the
    # zoo's models and those of its group beyond)
    from validation.exudyn_examples import REGISTRY, load_models

    load_models(None)
    assert exuclear.engine.unheld_motion(REGISTRY[name](True, 1e-3).mbs) == {}


@pytest.mark.parametrize("axis", [[0, 0, 1], [1, 0, 0], [0.6, 0.8, 0]])
def test_no_deprecated_rotation_marker_for_any_axis(axis):
    # before: AddClearanceJoint with an axis other than marker 0's z gave its connectors
    # rotationMarker0, which Exudyn 1.13 deprecates (a DeprecationWarning from Exudyn);
    # CreateClearanceJoint, with the frame of mbs.CreateRevoluteJoint, for every axis
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.CreateRigidBody(inertia=InertiaCuboid(1000.0, [0.1, 0.1, 0.1]),
                               referencePosition=[0.5, 0, 0])
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=b, localPosition=p)) for b, p in ((ground, [0.5, 0, 0]),
                                                                                          (body, [0, 0, 0]))]
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        handle = exuclear.AddClearanceJoint(mbs, markers, axis=axis, constrainAxial=True, **PIN)
        created = exuclear.CreateClearanceJoint(mbs, itemNumbers=[body, ground], position=[0.5, 0, 0], axis=axis, **PIN)
    unit = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    for h in (handle, created):
        assert np.allclose(h.frame[:, 2], unit, rtol=0, atol=1e-15)  # the joint frame's z is the axis
        assert np.allclose(mbs.GetMarkerOutput(h.markerNumbers[0], OV.Position, configuration=REF), [0.5, 0, 0])
