"""The spatial translational clearance joint (a box in a rectangular channel) and the finite
guide (exuclear/prismatic.py): the corners' geometry, both kernels, the builder's checks, and
the analytic checks of validation/translational_box.py."""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D
from exudyn.utilities import InertiaCuboid

import exuclear
from exuclear.engine import kernel
from exuclear.engine.layout import SECOND_FIELDS, SECOND_LAYOUT, pair_data_columns, read, second_parameters
from exuclear.joint import make_prismatic_joint
from exuclear.prismatic import (
    BOX_CORNER_SIGNS,
    BOX_PAIRS,
    BOX_WALLS,
    box_corner_kinematics,
    corner_kinematics,
    leave_guide,
    pair_name,
)
from exuclear.spatial import rotation_xyz
from validation import translational as planar
from validation import translational_box as val

compiled_only = pytest.mark.skipif(kernel.COMPILED is None, reason="the compiled kernel is not built")
BOX = dict(slider_length=planar.SLIDER_LENGTH, slider_height=planar.SLIDER_HEIGHT, clearance=planar.CLEARANCE,
           slider_width=val.SLIDER_WIDTH)


def test_the_box_has_eight_corners_against_four_walls():
    joint = make_prismatic_joint(**BOX, stiffness=1e8, cr=0.5, guide_length=0.3)
    g = joint.geometry
    assert g.spatial and g.pairs == BOX_PAIRS and len(BOX_PAIRS) == 32
    assert g.clearance_width == planar.CLEARANCE  # the default: the clearance across the height
    assert g.channel_half_width == pytest.approx(0.5 * val.SLIDER_WIDTH + planar.CLEARANCE, rel=1e-15)
    d = second_parameters(joint, 7.0)
    assert (read(d, "token", SECOND_FIELDS), read(d, "guide_length", SECOND_FIELDS)) == (7.0, 0.3)
    assert read(d, "slider_half_width", SECOND_FIELDS) == 0.5 * val.SLIDER_WIDTH
    assert pair_name(9, spatial=True) == "corner front-lower-far / upper wall"
    # the planar joint keeps its eight pairs, an infinite guide and zeros in the second matrix
    flat = make_prismatic_joint(slider_length=0.1, slider_height=0.05, clearance=1e-3, stiffness=1e8, cr=0.5)
    assert not flat.geometry.spatial and flat.geometry.half_guide == math.inf
    assert np.count_nonzero(second_parameters(flat, 7.0)) == 1  # the token only


def test_a_turned_box_penetrates_its_walls_as_by_hand():
    # the box turned by (0.01, -0.02, 0.015) rad and moved by (1, 0.4, -0.3) mm: each pair's
    # penetration is s (p + A c_k)_a - w_a, A from Exudyn's own RotXYZ2RotationMatrix
    from exudyn.rigidBodyUtilities import RotXYZ2RotationMatrix

    half = (0.05, 0.025, 0.02)
    walls = (0.026, 0.021)
    angles, p = (0.01, -0.02, 0.015), np.array([1e-3, 4e-4, -3e-4])
    a = RotXYZ2RotationMatrix(angles)
    zero = (0.0, 0.0, 0.0)
    for pair, (corner, wall) in enumerate(BOX_PAIRS):
        q = p + a @ (np.array(BOX_CORNER_SIGNS[corner]) * half)
        axis, s = BOX_WALLS[wall]
        kin = box_corner_kinematics(*half, *walls, corner, wall, tuple(p), rotation_xyz(angles), zero, zero, zero)
        assert kin.delta == pytest.approx(s * q[axis] - walls[axis - 1], abs=1e-15), pair_name(pair, True)


def test_a_corner_slips_over_its_wall_in_two_directions():
    # a spinning box over a turning channel: the corner's velocity over the wall's point under
    # it is dv + dw x r - w_j x p (module docstring); its part along the wall's normal is the
    # penetration rate, the rest the slip
    half, walls = (0.05, 0.025, 0.02), (0.026, 0.021)
    p, dv, dw, w_j = (1e-3, 2e-4, -1e-4), (0.3, -0.1, 0.2), (1.0, -2.0, 3.0), (0.5, 0.2, -0.4)
    for corner, wall in ((6, 1), (4, 2)):  # front-upper-near / upper wall, rear-lower-near / far wall
        kin = box_corner_kinematics(*half, *walls, corner, wall, p, rotation_xyz((0.0, 0.0, 0.0)), dv, dw, w_j)
        r = np.array(BOX_CORNER_SIGNS[corner]) * half
        v = np.array(dv) + np.cross(dw, r) - np.cross(w_j, p)
        axis, s = BOX_WALLS[wall]
        assert kin.delta_dot == pytest.approx(s * v[axis], rel=1e-14)
        slip = v.copy()
        slip[axis] = 0.0
        np.testing.assert_allclose(kin.v_s, slip, rtol=1e-14)
        assert kin.v_t == pytest.approx(np.linalg.norm(slip), rel=1e-14)


def test_a_box_kept_in_the_plane_has_the_planar_corners():
    # Tait-Bryan angles (0, 0, theta): the box's corners at z = -+B/2 are the rectangle's,
    # bit for bit (the same products; the rotation's zeros add nothing)
    zero = (0.0, 0.0, 0.0)
    for corner in range(4):
        for wall in range(2):
            flat = corner_kinematics(0.05, 0.025, 0.026, corner, wall, 1e-4, -3e-4, 0.02, 0.1, 0.2, 3.0, 0.0)
            for far_near in (0, 4):
                box = box_corner_kinematics(0.05, 0.025, 0.02, 0.026, 0.021, corner + far_near, wall, (1e-4, -3e-4, 0.0),
                                            rotation_xyz((0.0, 0.0, 0.02)), (0.1, 0.2, 0.0), (0.0, 0.0, 3.0), zero)
                assert (box.delta, box.delta_dot, box.ex, box.ey, box.v_s[0]) == (flat.delta, flat.delta_dot, flat.ex,
                                                                                   flat.ey, flat.v_t)


def test_a_corner_beyond_the_guide_has_no_wall():
    kin = corner_kinematics(0.05, 0.025, 0.026, 1, 0, 0.06, -0.0015, 0.0, 0.0, 0.0, 0.0, 0.0)  # front corner at x = 0.11
    assert kin.delta > 0.0 and leave_guide(kin, 0.2).delta == kin.delta
    assert leave_guide(kin, 0.1).delta == -math.inf


def _body_3d(mbs):
    inertia = InertiaCuboid(val.DENSITY, sideLengths=[0.1, 0.05, 0.04])
    return mbs.CreateRigidBody(inertia=inertia, nodeType=exu.NodeType.RotationRxyz, referencePosition=[0.0, 0.0, 0.0])


@pytest.mark.parametrize(("change", "message"), [
    ({"slider_width": -0.04}, r"`slider_width` must be positive"),
    ({"clearance_width": 0.0}, r"`clearance_width` must be positive"),
    ({"guide_length": -0.1}, r"`guide_length` must be positive"),
    ({"slider_width": None, "clearance_width": 1e-3}, r"`clearance_width` is the spatial joint's play"),
    ({"slider_width": None, "height_axis": [0.0, 1.0, 0.0]}, r"`height_axis` orients the spatial joint's box"),
    ({"height_axis": [2.0, 0.0, 0.0]}, r"`height_axis` must not be parallel to `axis`"),
    ({"axis": [0.0, 0.0, 1.0]}, r"`axis` is along z: give `height_axis`"),
    ({"slider_width": None, "axis": [0.0, 0.6, 0.8]}, r"give `slider_width` for the spatial joint"),
])
def test_bad_input_is_refused_naming_the_argument(change, message):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    kwargs = {**BOX, "stiffness": 1e8, "cr": 0.5, **change}
    kwargs = {k: v for k, v in kwargs.items() if v is not None}
    with pytest.raises(ValueError, match=message):
        exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, _body_3d(mbs)], **kwargs)


def test_a_2d_body_is_refused_for_the_box():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3))
    with pytest.raises(ValueError, match=r"`slider_width` makes the translational joint spatial, for 3D bodies; "
                                         r"`itemNumbers\[1\]` \(RigidBody2D\) is a 2D body"):
        exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, body], **BOX, stiffness=1e8, cr=0.5)


def test_the_height_axis_turns_the_box():
    # axis along global z, the height along global x: the joint frame's y is global x
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[ground, _body_3d(mbs)], axis=[0.0, 0.0, 1.0],
                                                   height_axis=[1.0, 0.0, 0.3], **BOX, stiffness=1e8, cr=0.5)
    mbs.Assemble()
    np.testing.assert_allclose(joint.frame, [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], atol=1e-15)


def _turning_channel(backend: str):
    """A free channel turning about all three axes, the box spinning and rattling inside it
    against every wall, Coulomb friction, a finite guide: every term of the box corners'
    kinematics and loads, the probe and torque connectors active."""
    mbs = exu.SystemContainer().AddSystem()
    guide = mbs.CreateRigidBody(inertia=InertiaCuboid(2000.0, sideLengths=[0.3, 0.1, 0.1]),
                                nodeType=exu.NodeType.RotationRxyz, referencePosition=[0.0, 0.0, 0.0],
                                initialAngularVelocity=[1.0, -2.0, 5.0])
    inertia = InertiaCuboid(val.DENSITY, sideLengths=[0.1, 0.05, 0.04])
    body = mbs.CreateRigidBody(inertia=inertia, nodeType=exu.NodeType.RotationRxyz, referencePosition=[0.0, 0.0, 0.0],
                               initialVelocity=[0.8, 0.3, 0.2], initialAngularVelocity=[2.0, 1.0, 3.0])
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[guide, body], **BOX, guide_length=0.12,
                                                   stiffness=1e8, cr=0.5, friction="coulomb:0.2", backend=backend)
    mbs.Assemble()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.03, **planar.SETTINGS))
    assert result.success, result.message
    return mbs, joint


@compiled_only
def test_both_kernels_give_the_same_box_to_round_off(kernels_agree):
    compiled = _turning_channel("compiled")
    joint = compiled[1]
    # several corners on three walls or more, and a corner that left the guide's end (x beyond 0.06 m)
    assert len({r.pair.split(" / ")[1] for r in joint.impacts()}) >= 3
    assert (np.abs(joint.outputs()["ecc_x"]) > 0.06).any()
    kernels_agree(compiled, _turning_channel("python"))


@compiled_only
def test_the_kernels_second_layout_agrees():
    # the compiled kernel's copy of the damping matrix's fields (name, row, column, size)
    assert [tuple(f) for f in kernel.COMPILED.SECOND_LAYOUT] == [(f.name, f.row, f.column, f.size)
                                                                 for f in SECOND_LAYOUT]


def test_outputs_and_drawing_of_the_box():
    mbs, joint = _turning_channel("python")
    out = joint.outputs()
    assert out["penetration"].shape == (len(out["time"]), len(BOX_PAIRS))
    assert len(pair_data_columns(len(BOX_PAIRS))) == mbs.GetNode(joint.nodeNumber)["numberOfDataCoordinates"]
    # Coulomb's law where a corner slides faster than the smoothing (eq. (20)): F_T = mu F_N
    fast = (out["normal_force"] > 0.0) & (out["slip_velocity"] > 1e-2)
    assert fast.sum() > 0
    np.testing.assert_allclose(out["tangential_force"][fast], 0.2 * out["normal_force"][fast], rtol=1e-9)
    # no corner beyond the guide's end touches
    assert not (out["in_contact"].astype(bool) & (np.abs(out["ecc_x"]) > 0.06)).any()
    draw = exuclear.engine.drawing.slider_drawing_function(joint, exu.ConfigurationType.Current)
    assert len(draw(mbs, 0)) == 5  # the box and the channel's four walls
    assert {r.pair for r in joint.impacts()} <= {pair_name(k, spatial=True) for k in range(len(BOX_PAIRS))}


# -- the analytic checks of validation/translational_box.py ---------------------------------------
def test_resting_box_carries_a_quarter_of_its_weight_on_each_lower_corner():
    r = val.resting()
    # the corners' oscillation has died out under the damping in 0.3 s (as the planar slider's)
    np.testing.assert_allclose(r["force"], r["quarter_weight"], rtol=1e-6)
    np.testing.assert_allclose(r["sink"], r["static_sink"], rtol=1e-6)


def test_a_box_sliding_diagonally_slows_as_coulomb_says():
    s = val.sliding()
    # F_T = mu F_N at every sliding output (the slip is far above the smoothing speed)
    assert s["ratio_min"] == pytest.approx(s["mu"], rel=1e-9)
    assert s["ratio_max"] == pytest.approx(s["mu"], rel=1e-9)
    v, expected = np.asarray(s["velocity"]), np.asarray(s["coulomb_velocity"])
    # the speed v0 - mu g t: the integration's error at rtol 1e-8 (measured 1.5e-10 relative)
    assert np.linalg.norm(v) == pytest.approx(np.linalg.norm(expected), rel=1e-8)
    # along the first direction, but for the compliant corners' rocking: friction below the centre
    # pitches and rolls the box at rates its two inertias make unequal, so the corners' slip leaves
    # the centre's direction for a moment while the rocking settles (measured: turned by 1.0e-6 rad)
    turn = np.arctan2(v[2], v[0]) - np.arctan2(expected[2], expected[0])
    assert abs(turn) < 1e-5 and abs(v[1]) < 1e-12


def test_elastic_box_corners_keep_the_energy():
    e = val.elastic_rattle()
    assert e["contacts"] >= 10 and len(e["walls"]) == 4
    # DOPRI5 at rtol 1e-8 over the impacts, as the planar rattle (1e-4 there)
    assert e["end"] == pytest.approx(e["start"], rel=1e-4)


def test_a_box_kept_in_the_plane_moves_as_the_planar_slider():
    p = val.in_plane()
    # two corners for each corner of the rectangle, each with K/2, over some ten impacts
    assert p["contacts"] == 2 * p["planar_contacts"] >= 16
    # out of the plane at most the round-off of the far and near corners' opposite moments (measured 0)
    assert p["out_of_plane"] < 1e-15
    # the same loads to round-off (2 (K/2) delta^n is K delta^n; the moments' sums may differ in
    # their last bit), integrated at the same fixed steps: round-off (measured 0, bit for bit)
    assert p["difference"] < 1e-12


@pytest.mark.parametrize("spatial", [False, True])
def test_a_slider_leaving_its_guide_loses_the_contact_at_the_end(spatial):
    g = val.guide_exit(spatial)
    # the front corner touches while x <= guide_length / 2 and is free from the first output beyond it
    assert g["touching_beyond"] == 0
    assert g["x_last_in"] <= g["half_guide"] < g["x_first_out"]
    # outputs about every 1e-4 s (at the first step past each output time) at 0.5 m/s: both
    # within 5.5e-5 m of the guide's end (measured 2e-16 m and 5.0e-5 m)
    assert g["half_guide"] - g["x_last_in"] <= 5.5e-5
    assert g["x_first_out"] - g["half_guide"] <= 5.5e-5


def test_a_box_that_starts_outside_its_channel_is_refused():
    # 2 mm across the width with 1 mm of play: its near corners 1 mm into the near wall, far
    # beyond the joint's penetration limit; the run refuses to start and names what placed it
    mbs, joint, _ = val.box_in_channel(start=(0.0, 0.0, 2e-3))
    with pytest.raises(ValueError, match=r"the slider starts outside its guide \(penetration 0.001 m.*the joint's "
                                         r"`position` and the initial coordinates of the bodies in `itemNumbers`"):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3, **planar.SETTINGS))
