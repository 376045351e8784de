"""The clearance joint as an Exudyn connector: backends, balance laws, body types, Exudyn habits.

References: momentum balance of docs/physics.md section 4 (sum of forces zero; moment of
the pair ``delta F_T``); the Python kernel (the readable statement) for the compiled
one; the paper's departure velocity (0.269 m/s at cr 0.9, docs/physics.md section 6.1).
"""
from __future__ import annotations

import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    SensorObject,
)

import exuclear
from exuclear.engine import kernel

R_B, R_J, L = 10e-3, 9.9e-3, 15e-3
C = R_B - R_J
COMPILED = pytest.mark.skipif(kernel.STATUS != kernel.STATUS_DIRECT, reason=f"compiled kernel: {kernel.STATUS}")
LAWS = [("wang-liu", 0.6), ("lankarani-nikravesh", 0.6), ("hunt-crossley", 0.6), ("flores", 0.6), ("hertz", None),
        # every other stiffness model of the library, with a damping model it has not met above
        ("johnson+gonthier", 0.6), ("radzimovsky+hu-guo", 0.6), ("esdu-78035+lee-wang", 0.6),
        ("dubowsky-freudenstein+carvalho-martins", 0.6), ("pereira+herbert-mcwhannell", 0.6)]
FRICTIONS = ["none", "coulomb:0.2", "paper"]


def _two_free_bodies(backend, law="wang-liu", cr=0.6, friction="paper", spin=(30.0, -50.0), offset=0.3 * C):
    """A bearing (a free 2D body) and a journal, both spinning, the journal pressed
    ``offset`` into the bearing wall along (cos 30deg, sin 30deg) and moving into it."""
    mbs = exu.SystemContainer().AddSystem()
    n = np.array([math.cos(math.pi / 6), math.sin(math.pi / 6)])
    pj = (C + offset) * n
    nb = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0.1, -0.05, spin[0]]))
    nj = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[pj[0], pj[1], 0.2],
                                     initialVelocities=[0.3 * n[0], 0.3 * n[1], spin[1]]))
    bearing = mbs.AddObject(ObjectRigidBody2D(nodeNumber=nb, mass=0.3, inertia=4e-5))
    journal = mbs.AddObject(ObjectRigidBody2D(nodeNumber=nj, mass=0.04, inertia=2e-6))
    mb = mbs.AddMarker(MarkerBodyRigid(bodyNumber=bearing, localPosition=[0, 0, 0]))
    mj = mbs.AddMarker(MarkerBodyRigid(bodyNumber=journal, localPosition=[0, 0, 0]))
    handle = exuclear.AddClearanceJoint(mbs, [mb, mj], journal_radius=R_J, bearing_radius=R_B, length=L, law=law,
                                        cr=cr, friction=friction, backend=backend)
    mbs.Assemble()
    return mbs, handle, (nb, nj), (0.3, 0.04), (4e-5, 2e-6)


def _rhs(mbs):
    """The system's generalized forces at the initial state (Exudyn's own evaluation)."""
    solver = exu.MainSolverExplicit()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.solverType = exu.DynamicSolverType.DOPRI5
    solver.InitializeSolver(mbs, ss)
    solver.ComputeODE2RHS(mbs)
    return np.asarray(solver.GetSystemResidual())


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_forces_balance_and_the_pair_has_the_moment_delta_ft(backend):
    # docs/physics.md section 4: F_i + F_j = 0 exactly; the moment of all loads about the
    # origin is delta F_T (the friction forces act at Q_J and Q_B, delta apart)
    mbs, handle, (nb, nj), _, _ = _two_free_bodies(backend)
    f = _rhs(mbs)
    fb, fj = f[0:3], f[3:6]
    scale = np.abs(f).max()
    assert scale > 1.0  # in contact: a real load
    assert abs(fb[0] + fj[0]) <= 1e-14 * scale and abs(fb[1] + fj[1]) <= 1e-14 * scale
    state = handle.history.state  # the initial state, accepted by the first evaluation
    assert state.in_contact and state.tangential_force != 0.0
    pb = np.array(mbs.GetNodeOutput(nb, exu.OutputVariableType.Position))
    pj = np.array(mbs.GetNodeOutput(nj, exu.OutputVariableType.Position))
    moment = (pb[0] * fb[1] - pb[1] * fb[0] + fb[2]) + (pj[0] * fj[1] - pj[1] * fj[0] + fj[2])
    # round-off of moments of size R_B * F (1e-2 m * scale)
    assert moment == pytest.approx(state.delta * state.tangential_force, abs=1e-13 * R_B * scale)


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_linear_momentum_is_conserved_through_an_impact(backend):
    mbs, handle, (nb, nj), masses, _ = _two_free_bodies(backend, offset=-0.2 * C)
    v = [np.array(mbs.GetNodeOutput(n, exu.OutputVariableType.Velocity)) for n in (nb, nj)]
    p0 = masses[0] * v[0] + masses[1] * v[1]
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-4, method="dopri5", step=1e-6, rtol=1e-8,
                                                            atol=1e-12))
    assert result.success, result.message
    assert handle.history.onsets >= 1 and handle.impacts()  # an impact happened and ended
    v = [np.array(mbs.GetNodeOutput(n, exu.OutputVariableType.Velocity)) for n in (nb, nj)]
    p1 = masses[0] * v[0] + masses[1] * v[1]
    impulse = handle.impacts()[0].peak_force * 1e-5  # the scale of the exchanged momentum
    assert np.abs(p1 - p0).max() <= 1e-12 * impulse


@COMPILED
@pytest.mark.parametrize("law,cr", LAWS)
@pytest.mark.parametrize("friction", FRICTIONS)
def test_compiled_kernel_equals_python_kernel(law, cr, friction):
    # the Python kernel is the statement; the compiled one must reproduce it to round-off
    runs = {}
    for backend in ("python", "compiled"):
        mbs, handle, nodes, _, _ = _two_free_bodies(backend, law=law, cr=cr, friction=friction, offset=-0.1 * C)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=3e-4, method="dopri5", step=1e-6, rtol=1e-8,
                                                                atol=1e-12, output_step=1e-6))
        assert result.success, result.message
        runs[backend] = (handle.outputs(), handle.impacts(), result.steps)
    (out_p, imp_p, steps_p), (out_c, imp_c, steps_c) = runs["python"], runs["compiled"]
    assert steps_p == steps_c
    assert len(imp_p) == len(imp_c) >= 1
    for key in ("normal_force", "tangential_force", "penetration", "ecc_x", "slip_velocity", "v0"):
        scale = max(np.abs(out_p[key]).max(), 1e-30)
        assert np.abs(out_p[key] - out_c[key]).max() <= 1e-10 * scale, key  # round-off, amplified by integration
    for a, b in zip(imp_p, imp_c):
        assert np.allclose(a, b, rtol=1e-10, atol=0.0)


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
@pytest.mark.parametrize("builder", ["CreateClearanceJoint", "add_clearance_joint"])
def test_paper_departure_velocity_with_a_direct_solve_dynamic(backend, builder):
    # docs/physics.md section 6.1: cr 0.9 gives 0.269 m/s (the paper); a plain
    # mbs.SolveDynamic, twice: the second run must start from a fresh history.  The deprecated
    # body-point builder (exuclear.engine.legacy) builds the same joint and names the call to write
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    # centred in the reference configuration, touching the wall at the start (initial displacement c)
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[C, 0, 0],
                                       initialVelocities=[0.3, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6))
    law = dict(journal_radius=R_J, bearing_radius=R_B, length=L, law="wang-liu", cr=0.9, backend=backend)
    if builder == "CreateClearanceJoint":
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], axis=[0, 0, 1], **law)
        along_x = 2  # the sensor's column of global x: the frame of mbs.CreateRevoluteJoint (axis z: x_J = -y, y_J = x)
    else:
        with pytest.warns(DeprecationWarning, match=r"add_clearance_joint\(mbs, journal_body, bearing_body, ...\) "
                                                    r"is deprecated; write exuclear.CreateClearanceJoint\(mbs, "):
            joint = exuclear.engine.add_clearance_joint(mbs, body, ground, **law)
        along_x = 1  # the markers' frames: global
    force_sensor = mbs.AddSensor(SensorObject(objectNumber=joint.objectNumber, storeInternal=True, writeToFile=False,
                                              outputVariableType=exu.OutputVariableType.ForceLocal))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 2e-4
    ss.timeIntegration.numberOfSteps = 200
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = 1e-6
    records = []
    for _ in range(2):
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.DOPRI5)
        v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]
        assert v == pytest.approx(-0.269, abs=0.0005)  # the paper's 0.269 m/s to its 3 digits
        records.append(joint.impacts())
    assert records[0] == records[1] and len(records[0]) == 1  # one impact each run, identical
    force = np.asarray(mbs.GetSensorStoredData(force_sensor))
    # the sensor sees the impact, along global x in the joint frame
    assert force[:, along_x].max() == pytest.approx(records[1][0].peak_force, rel=0.02)


def _journal_on(mbs, kind):
    """A journal body of the given kind, centred at the origin in the reference configuration,
    displaced by c along x (touching the wall) and moving into it at 0.3 m/s; returns
    (body or marker, is_marker, node)."""
    from exudyn.itemInterface import MarkerKinematicTreeRigid, NodeGenericODE2, ObjectKinematicTree
    from exudyn.utilities import InertiaCylinder

    if kind == "rigid-2d":
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[C, 0, 0],
                                           initialVelocities=[0.3, 0, 0]))
        return mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=2e-6)), False, node
    if kind.startswith("rigid-3d"):
        node_type = {"rigid-3d-rxyz": exu.NodeType.RotationRxyz, "rigid-3d-ep": exu.NodeType.RotationEulerParameters,
                     "rigid-3d-rotvec": exu.NodeType.RotationRotationVector}[kind]
        inertia = InertiaCylinder(density=0.04 / (math.pi * R_J**2 * L), length=L, outerRadius=R_J, axis=2)
        body = mbs.CreateRigidBody(inertia=inertia, referencePosition=[0, 0, 0], initialDisplacement=[C, 0, 0],
                                   initialVelocity=[0.3, 0, 0], nodeType=node_type, returnDict=True)
        return body["bodyNumber"], False, body["nodeNumber"]
    # a kinematic-tree link on a prismatic X joint
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0], initialCoordinates=[C],
                                       initialCoordinates_t=[0.3], numberOfODE2Coordinates=1))
    tree = mbs.AddObject(ObjectKinematicTree(nodeNumber=node, jointTypes=[exu.JointType.PrismaticX], linkParents=[-1],
                                             jointTransformations=exu.Matrix3DList([np.eye(3)]),
                                             jointOffsets=exu.Vector3DList([[0, 0, 0]]),
                                             linkInertiasCOM=exu.Matrix3DList([np.eye(3) * 1e-6]),
                                             linkCOMs=exu.Vector3DList([[0, 0, 0]]), linkMasses=[0.04],
                                             baseOffset=[0, 0, 0], gravity=[0, 0, 0]))
    return mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=0, localPosition=[0, 0, 0])), True, node


BODY_KINDS = {"rigid-2d": "dopri5", "rigid-3d-rxyz": "dopri5", "rigid-3d-rotvec": "dopri5",
              "rigid-3d-ep": "generalized-alpha", "kinematic-tree": "dopri5"}


@pytest.mark.parametrize("kind", sorted(BODY_KINDS))
@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_every_body_type_gives_the_paper_departure_velocity(kind, backend):
    # docs/physics.md section 6.1: 0.269 m/s at cr 0.9, whatever body carries the journal
    # (Euler-parameter nodes need an implicit method: Exudyn refuses explicit ones for them)
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    journal, is_marker, node = _journal_on(mbs, kind)
    physics = dict(journal_radius=R_J, bearing_radius=R_B, length=L, law="wang-liu", cr=0.9, friction="paper",
                   backend=backend)
    if is_marker:
        bearing = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
        exuclear.AddClearanceJoint(mbs, [bearing, journal], **physics)
    else:
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, journal], position=[0, 0, 0], **physics)
    mbs.Assemble()
    method = BODY_KINDS[kind]
    settings = (exuclear.SolverSettings(end_time=2e-4, method=method, step=1e-6, rtol=1e-9, atol=1e-13)
                if method == "dopri5" else exuclear.SolverSettings(end_time=2e-4, method=method, step=2e-7))
    result = exuclear.simulate(mbs, settings)
    assert result.success, result.message
    v = np.atleast_1d(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates_t))[0]
    # the paper's 0.269 m/s to its 3 digits; generalized-alpha's numerical damping (spectral
    # radius 0.9) at 2e-7 s steps costs less than that
    assert -v == pytest.approx(0.269, abs=5e-4)


@COMPILED
def test_the_kernels_layout_constants_agree():
    # the compiled kernel's data-node width, stiffness codes and parameter layout (field by
    # field: name, row, column, size) are those layout.py writes
    from exuclear.engine.layout import DATA_COLUMNS, KERNEL_STIFFNESS_CODES, LAYOUT, MATRIX_SIZE

    assert [tuple(f) for f in kernel.COMPILED.LAYOUT] == [(f.name, f.row, f.column, f.size) for f in LAYOUT]
    cells = [(f.row, f.column + i) for f in LAYOUT for i in range(f.size)]
    assert len(set(cells)) == len(cells)  # no two fields share an entry
    assert all(0 <= r < MATRIX_SIZE and 0 <= c < MATRIX_SIZE for r, c in cells)
    assert kernel.COMPILED.N_DATA == len(DATA_COLUMNS)
    assert set(range(kernel.COMPILED.STIFFNESS_CODES)) == KERNEL_STIFFNESS_CODES
    assert {law.kernel_code for law in (exuclear.contact_law(name + "+none", _GEOMETRY, 1e11)
                                        for name in exuclear.contact.STIFFNESS_MODELS)} == KERNEL_STIFFNESS_CODES


@COMPILED
def test_the_kernels_read_the_same_run_start_record_and_step_constants():
    # the run-start record's fields the compiled kernel reads by name (layout.RunStart), and its
    # step-control constants, against the Python kernel's
    from exuclear.engine import _python_kernel
    from exuclear.engine.layout import RunStart

    assert list(kernel.COMPILED.RUN_START_FIELDS) == list(RunStart._fields)
    constants = kernel.COMPILED.STEP_CONSTANTS
    assert constants and {name: getattr(_python_kernel, name) for name in constants} == dict(constants)


@COMPILED
def test_the_compiled_step_control_is_the_one_table_in_its_order_with_its_defaults():
    # layout.STEP_CONTROL describes the step control once: the compiled kernel's StepControl
    # (joint_state.hpp's field lists) holds its fields in its order, starts at its defaults
    # (nan compared as nan), and the Python kernel's is made from it
    from exuclear.engine._python_kernel import StepControl
    from exuclear.engine.layout import STEP_CONTROL, RunStart

    names = [f.name for f in STEP_CONTROL]
    assert list(kernel.COMPILED.STEP_CONTROL_FIELDS) == names
    assert names[:len(RunStart._fields)] == list(RunStart._fields)
    joint_id = kernel.COMPILED.new_joint()
    try:
        compiled = dict(kernel.COMPILED.step_control(joint_id))
    finally:
        kernel.COMPILED.release(joint_id)
    python = StepControl().as_dict()
    for f in STEP_CONTROL:
        for copy in (compiled, python):
            assert copy[f.name] == f.default or (f.default != f.default and copy[f.name] != copy[f.name]), f.name


def test_the_removed_following_mode_is_refused_with_what_to_use():
    # contact_mode="follow" (a prototype, docs/design/contact_following.md) was removed:
    # refused by name with the compliant default as the way; "compliant" itself is accepted
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0])),
                                          mass=0.04, inertia=2e-6))
    joint = dict(itemNumbers=[ground, pin], position=[0, 0, 0], journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.9)
    with pytest.raises(ValueError, match="'follow' was removed .*leave `contact_mode` out for the compliant contact"):
        exuclear.CreateClearanceJoint(mbs, contact_mode="follow", **joint)
    with pytest.raises(ValueError, match=r"`contact_mode` must be one of \['compliant', 'impulse'\]"):
        exuclear.CreateClearanceJoint(mbs, contact_mode="rigid", **joint)
    assert exuclear.CreateClearanceJoint(mbs, contact_mode="compliant", **joint).objectNumber is not None


_GEOMETRY = exuclear.BearingGeometry(R_J, R_B, L)


def test_the_deprecated_add_clearance_joint_is_gone_from_the_package():
    # CreateClearanceJoint (bodies) and AddClearanceJoint (markers) are the two ways in
    assert not hasattr(exuclear, "add_clearance_joint") and "add_clearance_joint" not in dir(exuclear)
    assert callable(exuclear.CreateClearanceJoint) and callable(exuclear.AddClearanceJoint)


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_helper_connectors_are_off_where_the_loads_do_not_use_the_bearing_spin(backend):
    # docs/physics.md section 4.1: a planar, dry, frictionless joint needs neither the
    # bearing's spin nor its extra moment, so its probe and torque connectors are off; its
    # motion equals that of the same joint with them on (Coulomb with mu = 0: F_T = 0
    # exactly), through an implicit solver whose Jacobian differentiates them, to the last
    # bit; only the slip output differs, by the bearing's term (R_B - R_J) omega_B, eq. (8)
    runs = {}
    for friction in ("none", "coulomb:0"):
        mbs, handle, (nb, nj), _, _ = _two_free_bodies(backend, friction=friction, offset=-0.1 * C)
        active = [mbs.GetObject(n)["activeConnector"] for n in (handle.probeNumber, handle.torqueNumber)]
        assert active == [friction != "none"] * 2
        ss = exu.SimulationSettings()
        ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 3e-4, 300
        ss.solution.sensors.writePeriod = 1e-6
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
        runs[friction] = (handle.outputs(), [np.array(mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates))
                                             for n in (nb, nj)], mbs, nb)
    (out_off, q_off, _, _), (out_on, q_on, mbs, nb) = runs["none"], runs["coulomb:0"]
    assert out_off["normal_force"].max() > 1.0  # an impact happened
    for a, b in zip(q_off, q_on):
        assert np.array_equal(a, b)
    assert np.array_equal(out_off["normal_force"], out_on["normal_force"])
    omega_b = np.asarray(mbs.GetNodeOutput(nb, exu.OutputVariableType.AngularVelocity))[2]
    assert out_on["slip_velocity"][-1] - out_off["slip_velocity"][-1] == pytest.approx(omega_b * C, rel=1e-9)


def test_helper_connectors_follow_the_physics_between_runs():
    mbs, handle, _, _, _ = _two_free_bodies("python", friction="none")
    assert not mbs.GetObject(handle.probeNumber)["activeConnector"]
    handle.joint = exuclear.make_joint(journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.6, friction="paper")
    assert mbs.GetObject(handle.probeNumber)["activeConnector"] and mbs.GetObject(handle.torqueNumber)["activeConnector"]
