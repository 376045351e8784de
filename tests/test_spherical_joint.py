"""The spherical clearance joint (a ball in a socket, docs/physics.md section 13): its law,
both kernels, its builder's checks, its outputs and the analytic checks of validation/spherical.py."""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import exudyn.utilities as eu
import numpy as np
import pytest

import exuclear
from exuclear.contact import DAMPING_MODELS
from exuclear.engine import kernel
from exuclear.engine.layout import JOINT_TYPE_CODES
from exuclear.joint import make_spherical_joint
from exuclear.materials import composite_modulus
from validation import spherical as val

R_B, R_S = val.BALL_RADIUS, val.SOCKET_RADIUS
compiled_only = pytest.mark.skipif(kernel.COMPILED is None, reason="the compiled kernel is not built")


def test_hertz_is_the_ball_in_its_socket():
    # issue 49: K = 4/3 E* sqrt(R_S R_B / (R_S - R_B)), exponent 1.5, the default stiffness
    law = make_spherical_joint(ball_radius=R_B, socket_radius=R_S, cr=0.9).law
    e_star = composite_modulus("steel", "steel")
    assert law.stiffness_model.k0 == pytest.approx(4.0 / 3.0 * e_star * math.sqrt(R_S * R_B / (R_S - R_B)), rel=1e-14)
    assert law.exponent == 1.5
    assert law.name == "hertz+lankarani-nikravesh"


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"ball_radius": 10e-3, "socket_radius": 10e-3}, r"`ball_radius` must be smaller than `socket_radius`"),
    ({"socket_radius": 10e-3}, r"`ball_radius` is required"),
    ({"ball_radius": 9.9e-3}, r"`socket_radius` is required"),
    ({"ball_radius": 9.9e-3, "socket_radius": 10e-3, "law": "no-such-law"}, r"law|stiffness|damping"),
    ({"ball_radius": 9.9e-3, "socket_radius": 10e-3, "law": "wang-liu", "cr": 0.9},
     r"'liu' is a line-contact law .* spherical joint's contact is a point"),
    ({"ball_radius": -1e-3, "socket_radius": 10e-3}, r"`ball_radius`"),
])
def test_bad_input_is_refused_naming_the_argument(kwargs, message):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(0.03, 9.9e-3), referencePosition=[0, 0, 0])
    with pytest.raises(ValueError, match=message):
        exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, ball], **{"cr": 0.9, **kwargs})


def test_a_body_without_a_rigid_marker_is_refused():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    point = mbs.CreateMassPoint(mass=0.03, referencePosition=[0, 0, 0])
    with pytest.raises(ValueError, match=r"`itemNumbers\[1\]`.*rigid marker"):
        exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, point], ball_radius=R_B, socket_radius=R_S,
                                               cr=0.9)


def test_a_position_marker_is_refused():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(0.03, R_B), referencePosition=[0, 0, 0])
    marker = mbs.AddMarker(eu.MarkerBodyPosition(bodyNumber=ball))
    with pytest.raises(ValueError, match=r"`itemNumbers\[1\]` is a BodyPosition marker.*rigid markers"):
        exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, marker], ball_radius=R_B, socket_radius=R_S,
                                               cr=0.9)


def _spinning_socket(backend: str) -> tuple[exu.MainSystem, object]:
    """A free socket body spinning about x and z with the ball flying inside it, friction on:
    every term of the ball's kinematics and loads, the probe and torque connectors active."""
    mbs = exu.SystemContainer().AddSystem()
    socket = mbs.CreateRigidBody(inertia=eu.InertiaCuboid(7850.0, [0.04, 0.04, 0.04]), referencePosition=[0, 0, 0],
                                 initialAngularVelocity=[3.0, 0.0, 20.0],
                                 nodeType=exu.NodeType.RotationRotationVector)
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(val.MASS, R_B), referencePosition=[0, 0, 0],
                               initialVelocity=[0.3, -0.2, 0.1], initialAngularVelocity=[0.0, 50.0, 0.0],
                               nodeType=exu.NodeType.RotationRotationVector)
    joint = exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[socket, ball], ball_radius=R_B, socket_radius=R_S,
                                                   law="hertz+hunt-crossley", cr=0.8, friction="coulomb:0.2",
                                                   backend=backend)
    mbs.Assemble()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=2e-3, method="dopri5", step=1e-6,
                                                                rtol=1e-8, atol=1e-12))
    assert result.success, result.message
    return mbs, joint


@compiled_only
def test_both_kernels_give_the_same_ball_to_round_off(kernels_agree):
    compiled = _spinning_socket("compiled")
    assert len(compiled[1].impacts()) >= 3  # several impacts, sliding with friction
    kernels_agree(compiled, _spinning_socket("python"))


@compiled_only
def test_the_kernels_know_the_same_joint_types():
    assert dict(kernel.COMPILED.JOINT_TYPES) == JOINT_TYPE_CODES


def test_outputs_impacts_and_drawing():
    mbs, joint = _spinning_socket("python")
    out = joint.outputs()
    assert set(out) == {"time", *exuclear.engine.outputs.BALL_OUTPUT_COLUMNS}
    ecc = np.sqrt(out["ecc_x"] ** 2 + out["ecc_y"] ** 2 + out["ecc_z"] ** 2)
    # penetration = |e| - (R_S - R_B) (docs/physics.md eq. (94)) at every output; round-off
    np.testing.assert_allclose(out["penetration"], ecc - (R_S - R_B), rtol=0, atol=1e-15)
    sliding = out["normal_force"] > 0.0
    # Coulomb's law at the recorded slip speed (eq. (20)): F_T = mu F_N beyond v_eps
    fast = sliding & (out["slip_velocity"] > 1e-2)
    assert fast.sum() > 0
    np.testing.assert_allclose(out["tangential_force"][fast], 0.2 * out["normal_force"][fast], rtol=1e-9)
    assert out["force"].shape == (len(out["time"]), 3)
    assert all(r.peak_force > 0.0 for r in joint.impacts())
    draw = exuclear.engine.drawing.ball_drawing_function(joint, exu.ConfigurationType.Current)
    assert len(draw(mbs, 0)) == 2  # the ball and the socket


def test_the_handle_keeps_its_joint_type():
    mbs, joint = _spinning_socket("python")
    revolute = exuclear.make_joint(journal_radius=R_B, bearing_radius=R_S, length=0.01, cr=0.9)
    with pytest.raises(ValueError, match="spherical joint cannot take the physics of a revolute joint"):
        joint.joint = revolute


# -- the analytic checks of validation/spherical.py ---------------------------------------------------
def test_resting_sink_is_hertz_static():
    sink, static = val.resting_sink()
    # (m g / K)^(2/3) once the contact's oscillation has died out under its damping; measured 1e-12
    assert sink == pytest.approx(static, rel=1e-6)


@pytest.mark.parametrize("damping", sorted(set(DAMPING_MODELS) - {"none"}))
def test_frictionless_oblique_impact_restitution_is_the_laws(damping):
    r = val.oblique_impact(damping)
    # the normal turns about 5 degrees during the contact (the ball's centre slides on a sphere
    # of radius c); about the deepest point's normal the measured restitution is the law's to
    # within 1 % (validation/spherical.py measures the rest)
    assert r.restitution == pytest.approx(val.law_restitution(damping), rel=1e-2)
    assert r.across < 1e-2  # nothing across the normal, within the same turn of the normal
    assert r.spin_change == 0.0  # the normal force passes through the ball's centre: no moment at all


def test_oblique_impact_with_friction_follows_the_impulse_balance():
    r = val.oblique_impact(mu=val.IMPACT_MU)
    # sliding throughout: dv_t = -mu P_n s / m and dw = R_B n x (-mu P_n s) / J; the turn of the
    # normal during the contact (see above) bounds the tangential velocity's agreement: 1 %
    assert np.linalg.norm(r.v_t_after - r.v_t_expected) <= 1e-2 * np.linalg.norm(r.v_t_expected)
    # the spin follows the friction impulse alone, whatever the normal's turn: measured 3e-5
    assert np.linalg.norm(r.w_after - r.w_expected) <= 1e-3 * np.linalg.norm(r.w_expected)


def test_spherical_pendulum_converges_to_the_ideal_joint():
    big, small = val.pendulum_errors((1e-4, 1e-5), end_time=0.1)
    # the pivot's offset in its socket moves the bar by about c: first order in c, a tenth
    # for a tenth of the clearance (measured 0.101); 2 c bounds each (measured 1.2 c)
    assert small <= 0.15 * big
    assert big <= 2e-4 and small <= 2e-5


def test_body_numbers_is_exudyns_deprecated_name():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(val.MASS, R_B), referencePosition=[0, 0, 0])
    with pytest.warns(DeprecationWarning, match="use `itemNumbers`"):
        joint = exuclear.CreateSphericalClearanceJoint(mbs, bodyNumbers=[ground, ball], ball_radius=R_B,
                                                       socket_radius=R_S, cr=0.9)
    assert joint.joint_type == "spherical"


def test_the_convergence_check_reads_the_balls_path_in_space():
    from exuclear.convergence import RunRecord

    def run(settings):
        p0, v0 = val.impact_start()
        mbs, _ball, joint = val.socket_scene(p0, v0, friction="coulomb:0.1")
        mbs.Assemble()
        return RunRecord.from_handles(exuclear.simulate(mbs, settings), {"ball": joint})

    result = exuclear.check_convergence(run, exuclear.SolverSettings(end_time=3e-4, method="generalized-alpha",
                                                                     step="auto"))
    comparison = result.joints["ball"]
    # one impact in both runs, the paths (all three components of the eccentricity) within the
    # check's default bound of 1 % of c: measured 3e-4
    assert result.path_agrees and comparison.impacts == comparison.impacts_ref == 1
    assert comparison.max_de < 0.01


def test_lengths_in_millimetres_are_questioned():
    # exuclear.UnitWarning, as for the revolute joint: a socket of 10 m is a unit slip
    with pytest.warns(exuclear.UnitWarning, match="socket radius 10 m .* given in mm"):
        make_spherical_joint(ball_radius=9.9, socket_radius=10.0, cr=0.9)


@pytest.mark.parametrize("node_type", ["RotationEulerParameters", "RotationRxyz", "RotationRotationVector"])
def test_every_rotation_node_type_carries_the_ball(node_type):
    settings = exuclear.SolverSettings(end_time=val.IMPACT_SETTINGS.end_time, method="generalized-alpha", step=2e-7)
    r = val.oblique_impact(node_type=getattr(exu.NodeType, node_type), settings=settings)
    # generalized-alpha at 2e-7 s (some 170 steps per contact): the law's restitution within 1 %
    assert r.restitution == pytest.approx(val.law_restitution("lankarani-nikravesh"), rel=1e-2)


def test_a_beams_node_carries_the_ball():
    """A steel beam (ObjectBeamGeometricallyExact, four elements on Lie-group nodes) hanging by
    its end node, a MarkerNodeRigid, from a socket on the ground."""
    from exudyn.itemInterface import MarkerNodeRigid, NodeRigidBodyRotVecLG, ObjectBeamGeometricallyExact

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    e, g, rho, a = 2.1e11, 8e10, 7850.0, 0.01  # steel, a square section of 10 mm
    area, second = a * a, a**4 / 12
    section = exu.BeamSection()
    section.stiffnessMatrix = np.diag([e * area, g * area, g * area, 2 * g * second, e * second, e * second])
    section.dampingMatrix = 1e-3 * section.stiffnessMatrix
    section.massPerLength = rho * area
    section.inertia = rho * np.diag([2 * second, second, second])
    elements, length = 4, 0.2
    nodes = [mbs.AddNode(NodeRigidBodyRotVecLG(referenceCoordinates=[k * length / elements, 0, 0, 0, 0, 0]))
             for k in range(elements + 1)]
    for k in range(elements):
        element = mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[k], nodes[k + 1]],
                                                             length=length / elements, sectionData=section))
        mbs.AddLoad(eu.Gravity(markerNumber=mbs.AddMarker(eu.MarkerBodyMass(bodyNumber=element)),
                               loadVector=[0, -9.81, 0]))
    end = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0]))
    c = 1e-4
    joint = exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, end], ball_radius=5e-3 - c,
                                                   socket_radius=5e-3, cr=0.9)
    mbs.Assemble()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.05, method="generalized-alpha", step="auto"))
    assert result.success, result.message
    out = joint.outputs()
    assert len(joint.impacts()) >= 1 and not joint.notes
    # the beam falls across its clearance and comes to hang: the penetration is what its weight
    # and impacts need (measured 0.007 c), far below a tenth of the gap
    assert out["penetration"].max() < 0.1 * c


def test_wear_is_the_revolute_joints():
    law = make_spherical_joint(ball_radius=R_B, socket_radius=R_S, cr=0.9).law
    with pytest.raises(ValueError, match="`wear` is modelled for the revolute joint.*spherical joint"):
        exuclear.ClearanceJoint(law, wear=exuclear.Wear(coefficient=1e-10))
