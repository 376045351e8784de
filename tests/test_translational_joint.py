"""The planar translational clearance joint (a slider in a guide, exuclear/prismatic.py): its
law, both kernels, its builder's checks, its outputs and the analytic checks of
validation/translational.py."""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import MarkerBodyRigid, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine import kernel
from exuclear.engine.layout import JOINT_TYPE_CODES, pair_data_columns, parameters, read
from exuclear.joint import make_prismatic_joint
from exuclear.materials import composite_modulus
from exuclear.prismatic import PAIRS, corner_kinematics, pair_name
from validation import translational as val

compiled_only = pytest.mark.skipif(kernel.COMPILED is None, reason="the compiled kernel is not built")
GUIDE = dict(slider_length=val.SLIDER_LENGTH, slider_height=val.SLIDER_HEIGHT, clearance=val.CLEARANCE)


def test_the_corner_law_is_the_given_power_law():
    joint = make_prismatic_joint(**GUIDE, stiffness=2e9, exponent=1.3, damping="carvalho-martins", cr=0.4)
    law = joint.law
    assert law.kernel_parameters() == (2e9, 1.3)
    # F_e = K delta^n exactly (the same float operations)
    assert law.elastic_force(1e-5) == 2e9 * 1e-5**1.3
    assert joint.geometry.clearance == pytest.approx(val.CLEARANCE, rel=1e-12)  # (H/2 + c) - H/2: round-off
    p = parameters(joint, 0, 0, 1e-3)
    assert read(p, "joint_type") == JOINT_TYPE_CODES["prismatic"]
    assert read(p, "length") == val.SLIDER_LENGTH


def test_a_rounded_corner_takes_hertz_on_a_flat():
    # Hertz's sphere on a flat (docs/physics.md eq. (13), R_B -> infinity): K = 4/3 E* sqrt(r)
    joint = make_prismatic_joint(**GUIDE, stiffness="hertz", corner_radius=1e-3, cr=0.5)
    e_star = composite_modulus("steel", "steel")
    assert joint.law.kernel_parameters() == pytest.approx((4.0 / 3.0 * e_star * 1e-3**0.5, 1.5), rel=1e-15)
    with pytest.raises(ValueError, match=r"needs `corner_radius`"):
        make_prismatic_joint(**GUIDE, stiffness="hertz", cr=0.5)
    with pytest.raises(ValueError, match=r"a numeric `stiffness` is the corner's K itself: leave out `corner_radius`"):
        make_prismatic_joint(**GUIDE, stiffness=1e9, corner_radius=1e-3, cr=0.5)
    with pytest.raises(ValueError, match=r"`stiffness` must be a number K \[N/m\^n\] or a stiffness model of a "
                                         r"corner on a flat wall, 'hertz' .* got 'liu' \(its formula needs the outer"):
        make_prismatic_joint(**GUIDE, stiffness="liu", corner_radius=1e-3, cr=0.5)


def test_a_rounded_corner_edge_takes_dubowsky_freudenstein_on_a_flat():
    # Dubowsky and Freudenstein (J. Eng. Ind. 93 (1971) 305-309, as compiled by Pereira et al.,
    # Nonlinear Dyn. 63 (2011) 681-697): delta = F (s_i + s_j) / L [ln(L^3 dR / (F (s_i + s_j) R_J R_B)) + 1],
    # s_k = (1 - nu_k^2) / (pi E_k); a cylinder of radius r on a flat: dR / (R_J R_B) = 1/r - 1/R_B -> 1/r.
    # Evaluated here from the two materials (steel on aluminium), not from the model's E*.
    r, length = 0.5e-3, 0.02
    joint = make_prismatic_joint(**GUIDE, stiffness="dubowsky-freudenstein", corner_radius=r, corner_length=length,
                                 slider_material="steel", guide_material="aluminium", cr=0.5)
    steel, aluminium = exuclear.MATERIALS["steel"], exuclear.MATERIALS["aluminium"]
    s = sum((1.0 - m.nu**2) / (math.pi * m.E) for m in (steel, aluminium))
    for delta in (1e-8, 1e-6, 2e-5):
        f = joint.law.elastic_force(delta)
        by_hand = f * s / length * (math.log(length**3 / (f * s * r)) + 1.0)
        # the model's root is exact to 1e-13 (IMPLICIT_RTOL); E* from the materials agrees to round-off
        assert by_hand == pytest.approx(delta, rel=1e-12)
    line = dict(stiffness="dubowsky-freudenstein", corner_radius=r, cr=0.5)
    with pytest.raises(ValueError, match=r"is a line contact along the rounded corner edge: give `corner_length`"):
        make_prismatic_joint(**GUIDE, **line)
    with pytest.raises(ValueError, match=r"`exponent` is fixed by the 'dubowsky-freudenstein' stiffness"):
        make_prismatic_joint(**GUIDE, **line, corner_length=length, exponent=1.5)
    with pytest.raises(ValueError, match=r"stiffness='hertz' is a corner rounded to a ball, a point contact: leave out "
                                         r"`corner_length`"):
        make_prismatic_joint(**GUIDE, stiffness="hertz", corner_radius=r, corner_length=length, cr=0.5)
    for name in ("johnson", "radzimovsky", "esdu-78035", "pereira"):
        with pytest.raises(ValueError, match=rf"got '{name}' \(its formula needs the outer radius of a conforming pair"):
            make_prismatic_joint(**GUIDE, stiffness=name, corner_radius=r, corner_length=length, cr=0.5)
    with pytest.raises(ValueError, match=r"`corner_length` must be positive"):
        make_prismatic_joint(**GUIDE, **line, corner_length=-1.0)


def test_corners_and_walls():
    # the slider turned by 0.01 rad, lifted by 0.5 mm: each pair's penetration is s q_y - (H/2 + c), by hand
    half_l, half_h, half_w = 0.05, 0.025, 0.026
    theta, py = 0.01, 5e-4
    for pair, (corner, wall) in enumerate(PAIRS):
        sx, sy = ((-1, -1), (1, -1), (1, 1), (-1, 1))[corner]
        s = (-1, 1)[wall]
        qy = py + np.sin(theta) * sx * half_l + np.cos(theta) * sy * half_h
        kin = corner_kinematics(half_l, half_h, half_w, corner, wall, 0.0, py, theta, 0.0, 0.0, 0.0, 0.0)
        assert kin.delta == pytest.approx(s * qy - half_w, abs=1e-15), pair_name(pair)
    assert pair_name(1) == "corner front-lower / lower wall"


@pytest.mark.parametrize(("change", "message"), [
    ({"slider_length": None}, r"`slider_length` is required"),
    ({"stiffness": None}, r"`stiffness` is required"),
    ({"clearance": -1e-3}, r"`clearance` must be positive"),
    ({"stiffness": -1.0}, r"`stiffness` must be positive"),
    ({"cr": None}, r"`cr` is required with damping='lankarani-nikravesh'"),
    ({"damping": "no-such-damping"}, r"damping"),
    ({"axis": [0.6, 0.0, 0.8]}, r"`axis` must lie in the global x-y plane"),
])
def test_bad_input_is_refused_naming_the_argument(change, message):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=val.MASS, inertia=val.INERTIA))
    kwargs = {**GUIDE, "stiffness": 1e8, "cr": 0.5, "axis": [1.0, 0.0, 0.0], **change}
    kwargs = {k: v for k, v in kwargs.items() if v is not None}
    with pytest.raises(ValueError, match=message):
        exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, body], **kwargs)


def test_a_marker_is_refused():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=val.MASS, inertia=val.INERTIA))
    marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
    with pytest.raises(ValueError, match=r"`itemNumbers` must be \[guide body, slider body\]"):
        exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, marker], **GUIDE, stiffness=1e8, cr=0.5)


def _turning_guide(backend: str):
    """A free guide turning at 5 rad/s with the slider spinning and rattling inside it,
    Coulomb friction: every term of the corners' kinematics and loads, the probe and torque
    connectors active."""
    mbs, joint, node = val.slider_in_guide(backend, velocity=(0.2, 0.3, 3.0), gravity=0.0, guide_spin=5.0,
                                           friction="coulomb:0.2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.02, **val.SETTINGS))
    assert result.success, result.message
    return mbs, joint


@compiled_only
def test_both_kernels_give_the_same_slider_to_round_off(kernels_agree):
    compiled = _turning_guide("compiled")
    assert len(compiled[1].impacts()) >= 4  # several corners, both walls
    kernels_agree(compiled, _turning_guide("python"))


def test_outputs_name_the_pairs():
    mbs, joint = _turning_guide("python")
    out = joint.outputs()
    assert set(out) == {"time", *exuclear.engine.outputs.PAIR_OUTPUT_COLUMNS}
    assert out["penetration"].shape == (len(out["time"]), len(PAIRS))
    assert len(pair_data_columns(len(PAIRS))) == mbs.GetNode(joint.nodeNumber)["numberOfDataCoordinates"]
    # Coulomb's law where a corner slides faster than the smoothing (eq. (20)): F_T = mu |F_N|, signed with the slip
    fast = (out["normal_force"] > 0.0) & (np.abs(out["slip_velocity"]) > 1e-2)
    assert fast.sum() > 0
    np.testing.assert_allclose(out["tangential_force"][fast],
                               0.2 * np.sign(out["slip_velocity"][fast]) * out["normal_force"][fast], rtol=1e-9)
    draw = exuclear.engine.drawing.slider_drawing_function(joint, exu.ConfigurationType.Current)
    assert len(draw(mbs, 0)) == 3  # the slider and the guide's two walls
    # impacts() names each contact's corner and wall: per pair, as many records as its history
    # closed, the last one that history's last contact (the same floats)
    impacts = joint.impacts()
    assert [r.onset_time for r in impacts] == sorted(r.onset_time for r in impacts)
    assert len({r.pair for r in impacts}) >= 4  # several corners, both walls
    for k, state in enumerate(joint.pair_states()):
        mine = [r for r in impacts if r.pair == pair_name(k)]
        assert len(mine) == state.closed
        if mine and not state.in_contact:
            assert (mine[-1].onset_time, mine[-1].peak_force) == (state.onset_time, state.peak_force)


# -- the analytic checks of validation/translational.py ---------------------------------------------
def test_resting_slider_carries_half_its_weight_on_each_lower_corner():
    r = val.resting()
    # the corners' oscillation has died out under the damping in 0.3 s: measured agreement 1e-12
    np.testing.assert_allclose(r["force"], r["half_weight"], rtol=1e-6)
    np.testing.assert_allclose(r["sink"], r["static_sink"], rtol=1e-6)


def test_resting_slider_sinks_as_dubowsky_freudenstein_says_on_rounded_edges():
    # corner edges rounded to r along l: each lower corner carries m g / 2 and sinks
    # delta = F / (pi l E*) [ln(pi l^3 E* / (F r)) + 1], the law's own equation evaluated forwards
    # (a soft E* keeps the contact period above the run's 1e-5 s steps)
    r, length, e_star = 1e-3, 0.02, 1e9
    mbs, joint, _ = val.slider_in_guide(stiffness="dubowsky-freudenstein", exponent=None, corner_radius=r,
                                        corner_length=length, E_star=e_star)
    val.run(mbs, 0.3)
    out = joint.outputs()
    f = val.MASS * val.GRAVITY / 2.0
    sink = f / (math.pi * length * e_star) * (math.log(math.pi * length**3 * e_star / (f * r)) + 1.0)
    # the oscillation has died out under the damping in 0.3 s (as for the K delta^n corners): measured 1e-9
    np.testing.assert_allclose(out["normal_force"][-1, :2], f, rtol=1e-6)
    np.testing.assert_allclose(out["penetration"][-1, :2], sink, rtol=1e-6)


def test_sliding_slider_slows_as_coulomb_says():
    s = val.sliding()
    # F_T = mu F_N at every sliding output (the slip is far above the smoothing speed)
    assert s["ratio_min"] == pytest.approx(s["mu"], rel=1e-9)
    assert s["ratio_max"] == pytest.approx(s["mu"], rel=1e-9)
    # v0 - mu g t: the integration's error at rtol 1e-8; measured 1e-9 relative
    assert s["speed"] == pytest.approx(s["coulomb_speed"], rel=1e-6)


def test_elastic_corners_keep_the_energy():
    e = val.elastic_rattle()
    assert e["contacts"] >= 20
    # DOPRI5 at rtol 1e-8 over some 50 impacts: measured 1.3e-5 relative
    assert e["end"] == pytest.approx(e["start"], rel=1e-4)
