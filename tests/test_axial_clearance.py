"""Axial clearance of the spatial joint (docs/physics.md section 9.6): shoulder contact.

References: the flat-punch law written again here (F = 2 E* R_S delta, Sneddon 1965) for
the static penetration; the free-mass restitution of the damping model
(``restitution_of_damping``, eq. (16c)) for a dissipative axial impact; energy for an
elastic one, with tilt and spin; the friction couple mu F R_e of eq. (51) on a spinning
journal pressed against a face; compiled against Python; faces that never touch against no
faces, bit for bit.
"""
from __future__ import annotations

import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import LoadForceVector, MarkerBodyRigid, ObjectJointGeneric
from exudyn.utilities import InertiaCylinder

import exuclear
from exuclear.contact import restitution_of_damping
from exuclear.engine import kernel

R_B, R_J, L = 10e-3, 9.9e-3, 15e-3
C = R_B - R_J
E, NU = 207e9, 0.3
E_STAR = 1.0 / (2.0 * (1.0 - NU**2) / E)
PLAY, R_S = 0.1e-3, 14e-3  # total axial play; outer radius of the shoulder's contact annulus
K_FACE = 2.0 * E_STAR * R_S  # docs/physics.md eq. (52), written again: a flat punch of radius R_S
R_E = 2.0 / 3.0 * (R_S**3 - R_B**3) / (R_S**2 - R_B**2)  # eq. (51), the friction radius
COMPILED = pytest.mark.skipif(kernel.STATUS != kernel.STATUS_DIRECT, reason=f"compiled kernel: {kernel.STATUS}")
BACKENDS = ["python", pytest.param("compiled", marks=COMPILED)]
SHAFT = InertiaCylinder(7800.0, 0.04, R_J, 2)  # a steel journal 40 mm long, axis z


def _journal(backend, law="hertz", cr=None, friction="none", velocity=(0.0, 0.0, 0.0), spin=(0.0, 0.0, 0.0),
             displacement=(0.0, 0.0, 0.0), slices=10, **axial):
    """A journal (3D body) in a fixed bearing along z, with shoulders: ``axial`` are the
    keyword arguments of the axial clearance (default PLAY, R_S; ``{}`` for none)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    body = mbs.CreateRigidBody(inertia=SHAFT, referencePosition=[0, 0, 0], initialDisplacement=list(displacement),
                               initialVelocity=list(velocity), initialAngularVelocity=list(spin),
                               nodeType=exu.NodeType.RotationRxyz, returnDict=True)
    axial = axial if axial else {"axial_clearance": PLAY, "shoulder_radius": R_S}
    if axial.get("axial_clearance") is None:
        axial = {}
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body["bodyNumber"]], position=[0, 0, 0],
                                           slices=slices, journal_radius=R_J, bearing_radius=R_B, length=L, law=law,
                                           cr=cr, friction=friction, backend=backend, show=False, **axial)
    return mbs, handle, body, ground


def _settings(end_time, rtol=1e-10, atol=1e-14):
    return exuclear.SolverSettings(end_time=end_time, method="dopri5", step=1e-6, rtol=rtol, atol=atol,
                                   output_step=1e-6)


@pytest.mark.parametrize("after_a_dynamic_run", [False, True], ids=["static", "static after dynamic"])
@pytest.mark.parametrize("backend", BACKENDS)
def test_a_journal_pushed_axially_rests_at_the_face_with_the_flat_punch_penetration(backend, after_a_dynamic_run):
    # eq. (53) at rest: K_f delta = P. The journal held radially and in tilt, pushed along -z:
    # its upper shoulder (face 1, z = +L/2) carries P.  After a dynamic run of the same system
    # too: a static solve's load step is no time, and the joint's step rules (the held
    # contact's cap in contact periods) must not reject it (steering.static_run)
    load = 500.0
    mbs, handle, body, ground = _journal(backend, law="wang-liu", cr=0.7, displacement=(0, 0, -0.5 * PLAY - 1e-7))
    mg = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    mj = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body["bodyNumber"], localPosition=[0, 0, 0]))
    mbs.AddObject(ObjectJointGeneric(markerNumbers=[mg, mj], constrainedAxes=[1, 1, 0, 1, 1, 1]))
    mbs.AddLoad(LoadForceVector(markerNumber=mj, loadVector=[0, 0, -load]))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.staticSolver.newton.relativeTolerance = 1e-12
    # the residual's round-off floor: eq. (49) subtracts numbers of size L/2, so K_f ulp(L/2) = 2.4e-9 N
    ss.staticSolver.newton.absoluteTolerance = 1e-8
    ss.staticSolver.verboseMode = 0
    if after_a_dynamic_run:
        ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps, ss.timeIntegration.verboseMode = 1e-5, 10, 0
        mbs.SolveDynamic(ss)
    assert mbs.SolveStatic(ss)
    q = mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Coordinates)
    delta = load / K_FACE  # 0.16 um
    # the residual 1e-8 N is 4e-18 m of penetration, ulp(L/2) ~ 9e-19 m; relative to p_z ~ 5e-5 m
    assert q[2] == pytest.approx(-(0.5 * PLAY + delta), rel=1e-12)
    upper, lower = handle.face_states()[1], handle.face_states()[0]
    assert upper.delta == pytest.approx(delta, rel=1e-10) and upper.in_contact  # measured 2e-12: see above
    assert lower.delta == pytest.approx(-PLAY - delta, rel=1e-9) and not lower.in_contact
    assert all(not s.in_contact for s in handle.slice_states())  # held on the axis: no radial contact
    force = mbs.GetObjectOutput(handle.objectNumber, exu.OutputVariableType.ForceLocal)
    assert force[2] == pytest.approx(-load, rel=1e-9)  # on the bearing, along -z (eq. (54))
    assert abs(force[0]) + abs(force[1]) == 0.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_an_elastic_axial_impact_returns_the_axial_speed(backend):
    # eq. (53) with D = 0 is a linear spring: the journal leaves each face with the speed it
    # came with (0.2 m/s; 0.25 ms to cross half the play, ~19 us in contact)
    v = 0.2
    mbs, handle, body, _ = _journal(backend, velocity=(0, 0, -v))
    mbs.Assemble()
    result = exuclear.simulate(mbs, _settings(1.2e-3))
    assert result.success, result.message
    upper, lower = handle.face_impacts()[1], handle.face_impacts()[0]
    assert len(upper) == 1 and len(lower) == 1  # down onto face 1, back across the play onto face 0
    assert upper[0].onset_velocity == pytest.approx(v, rel=1e-9)
    assert upper[0].duration == pytest.approx(math.pi * math.sqrt(SHAFT.Mass() / K_FACE), rel=1e-4)
    # the largest penetration at an accepted step (1 us output, ~19 us contact): measured 3e-5 short
    assert upper[0].max_penetration == pytest.approx(v * math.sqrt(SHAFT.Mass() / K_FACE), rel=1e-3)
    vz = mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Velocity)[2]
    # DOPRI5 at rtol 1e-10 over two impacts: measured |vz| / v - 1 = -9.6e-9
    assert abs(vz) == pytest.approx(v, rel=1e-7) and vz < 0.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_dissipative_axial_impact_has_the_damping_models_restitution(backend):
    # eq. (16c) holds for any elastic force, so the face's linear law has the same free-mass
    # restitution as the joint law's damping model
    v = 0.2
    mbs, handle, body, _ = _journal(backend, law="lankarani-nikravesh", cr=0.8, velocity=(0, 0, -v))
    mbs.Assemble()
    result = exuclear.simulate(mbs, _settings(0.6e-3))
    assert result.success, result.message
    (record,) = handle.face_impacts()[1]
    vz = mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Velocity)[2]
    e = restitution_of_damping(handle.joint.law.damping_factor)
    # before contact the journal flies free, so eq. (18) interpolates v0 exactly
    assert record.onset_velocity == pytest.approx(v, rel=1e-9)
    assert vz == pytest.approx(e * v, rel=1e-6)  # measured 6e-9: DOPRI5 at rtol 1e-10


def _tumbling(backend, friction="none", play=PLAY):
    """A journal tilting, spinning and moving axially: slices and both faces get hit."""
    return _journal(backend, friction=friction, velocity=(0.2, 0.1, -0.25), spin=(0.6, 0.4, 30.0),
                    axial_clearance=play, shoulder_radius=R_S)


@pytest.mark.parametrize("backend", BACKENDS)
def test_elastic_shoulders_and_slices_conserve_energy_under_tilt_and_spin(backend):
    # eqs. (47), (50), (54): the face force along e_z at the shoulder's centre is the gradient of
    # K_f delta_f^2 / 2, tilt included
    mbs, handle, body, _ = _tumbling(backend)
    mbs.Assemble()
    node = body["nodeNumber"]

    def energy():
        vel = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity))
        w = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocityLocal))
        k = 4.0 / 3.0 * E_STAR * math.sqrt(R_B * R_J / C)
        slices = sum(k * s.delta**2.5 / 2.5 / handle.slices for s in handle.slice_states() if s.delta > 0)
        faces = sum(0.5 * K_FACE * s.delta**2 for s in handle.face_states() if s.delta > 0)
        return 0.5 * SHAFT.Mass() * vel @ vel + 0.5 * w @ np.asarray(SHAFT.InertiaCOM()) @ w + slices + faces

    e0 = 0.5 * SHAFT.Mass() * (0.2**2 + 0.1**2 + 0.25**2) + 0.5 * np.array([0.6, 0.4, 30.0]) @ \
        np.asarray(SHAFT.InertiaCOM()) @ np.array([0.6, 0.4, 30.0])
    result = exuclear.simulate(mbs, _settings(4e-3))
    assert result.success, result.message
    assert all(len(r) >= 3 for r in handle.face_impacts())  # both faces, several times
    assert sum(len(r) for r in handle.slice_impacts()) >= 10  # and radial edge contacts
    out = handle.outputs()
    assert np.abs(out["tilt_x"]).max() > 0.5 * C / L and np.abs(out["tilt_y"]).max() > 0.5 * C / L
    # the integrator's error: measured drift -2.7e-6, -3.2e-9, 3.3e-10 of the energy at DOPRI5
    # rtol 1e-8, 1e-10, 1e-12 (10 face and 23 slice contacts), falling with the tolerance
    assert energy() == pytest.approx(e0, rel=1e-7)


@pytest.mark.parametrize("backend", BACKENDS)
def test_face_friction_is_the_couple_mu_f_r_e_against_the_spin(backend):
    # eqs. (51), (53), (54): a journal pressed on face 1 by P and spinning at 50 rad/s slows at
    # mu P R_e / I_zz; no friction force, and the face's recorded slip is R_e * spin
    load, mu, spin = 20.0, 0.2, 50.0
    mbs, handle, body, ground = _journal(backend, law="wang-liu", cr=0.5, friction=f"coulomb:{mu}",
                                         displacement=(0, 0, -0.5 * PLAY - load / K_FACE), spin=(0, 0, spin))
    mj = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body["bodyNumber"], localPosition=[0, 0, 0]))
    mbs.AddLoad(LoadForceVector(markerNumber=mj, loadVector=[0, 0, -load]))
    mbs.Assemble()
    result = exuclear.simulate(mbs, _settings(1e-3, rtol=1e-9, atol=1e-13))
    assert result.success, result.message
    node = body["nodeNumber"]
    w = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)
    i_zz = SHAFT.InertiaCOM()[2][2]
    expected = spin - mu * load * R_E / i_zz * 1e-3  # about 10 rad/s less
    # starting at the static penetration the face force stays P (no impact): measured 4e-14
    assert w[2] == pytest.approx(expected, rel=1e-9)
    assert abs(w[0]) + abs(w[1]) <= 1e-12 * spin
    face = handle.face_states()[1]
    assert face.slip_velocity == pytest.approx(R_E * w[2], rel=1e-12)
    assert face.tangential_force == pytest.approx(mu * face.normal_force, rel=1e-12)
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
    assert abs(v[0]) + abs(v[1]) == 0.0  # a pure couple: no radial force


@COMPILED
def test_compiled_kernel_equals_python_kernel_with_shoulders():
    runs = {}
    for backend in ("python", "compiled"):
        mbs, handle, body, _ = _tumbling(backend, friction="paper")
        mbs.Assemble()
        result = exuclear.simulate(mbs, _settings(1.5e-3, rtol=1e-8, atol=1e-12))
        assert result.success, result.message
        runs[backend] = (handle.outputs(), handle.impacts(), result.steps)
    (out_p, imp_p, steps_p), (out_c, imp_c, steps_c) = runs["python"], runs["compiled"]
    assert steps_p == steps_c and len(imp_p) == len(imp_c)
    assert any(r.onset_velocity > 0 for r in imp_p)
    assert out_p["face_normal_force"].max() > 0.0 and out_p["face_tangential_force"].max() > 0.0
    for key in ("normal_force", "tangential_force", "penetration", "slip_velocity", "v0", "tilt_x", "tilt_y",
                "axial_displacement", "face_normal_force", "face_tangential_force", "face_penetration",
                "face_penetration_rate", "face_slip_velocity", "face_v0"):
        scale = max(np.abs(out_p[key]).max(), 1e-30)
        assert np.abs(out_p[key] - out_c[key]).max() <= 1e-10 * scale, key  # round-off, amplified by integration
    for a, b in zip(imp_p, imp_c):
        assert np.allclose(a, b, rtol=1e-10, atol=0.0)


@pytest.mark.parametrize("backend", BACKENDS)
def test_faces_that_never_touch_change_nothing_bit_for_bit(backend):
    # the face loop skips contacts without penetration, so a play wider than the motion gives
    # the joint without axial clearance exactly
    runs = []
    for play in (None, 0.1):
        mbs, handle, body, _ = _tumbling(backend, friction="paper", play=play)
        mbs.Assemble()
        result = exuclear.simulate(mbs, _settings(1e-3, rtol=1e-8, atol=1e-12))
        assert result.success, result.message
        out = handle.outputs()
        runs.append((np.concatenate([mbs.GetNodeOutput(body["nodeNumber"], t) for t in
                                     (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t)]),
                     out["normal_force"], result.steps))
    assert runs[0][2] == runs[1][2]
    assert np.array_equal(runs[0][0], runs[1][0]) and np.array_equal(runs[0][1], runs[1][1])


# -- bad input -----------------------------------------------------------------------------------
def _create(**kwargs):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    body = mbs.CreateRigidBody(inertia=SHAFT, referencePosition=[0, 0, 0], nodeType=exu.NodeType.RotationRxyz)
    args = dict(slices=5, journal_radius=R_J, bearing_radius=R_B, length=L, law="hertz")
    args.update(kwargs)
    return exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], **args)


@pytest.mark.parametrize("kwargs,match", [
    ({"axial_clearance": 1e-4}, "needs the shoulder geometry"),
    ({"axial_clearance": -1e-4, "shoulder_radius": R_S}, "`axial_clearance` must be positive, got -0.0001"),
    ({"axial_clearance": 0.0, "shoulder_radius": R_S}, "`axial_clearance` must be positive"),
    ({"axial_clearance": 1e-4, "shoulder_radius": -R_S}, "`shoulder_radius` must be positive"),
    ({"axial_clearance": 1e-4, "shoulder_radius": R_B}, "`shoulder_radius` must exceed `bearing_radius`"),
    ({"shoulder_radius": R_S}, "without `axial_clearance`"),
    ({"axial_clearance": 1e-4, "shoulder_radius": R_S, "slices": None}, "needs the spatial joint"),
    ({"axial_clearance": 1e-4, "shoulder_radius": R_S, "constrainAxial": True}, "constrainAxial"),
    ({"axial_clearance": "0.1 mm", "shoulder_radius": R_S}, "`axial_clearance` must be a real number"),
])
def test_bad_axial_clearance_is_refused_by_name(kwargs, match):
    with pytest.raises(ValueError, match=match):
        _create(**kwargs)
