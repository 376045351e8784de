"""The pin-in-slot clearance joint (exuclear/slot.py): its geometry, both kernels, its
builder's checks, and the checks of validation/translational.py (the revolute joint at slot
length 0, a pin sliding along a flat side)."""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import pytest
from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine import kernel
from exuclear.geometry import BearingGeometry, contact_kinematics
from exuclear.slot import slot_kinematics
from validation import translational as val

compiled_only = pytest.mark.skipif(kernel.COMPILED is None, reason="the compiled kernel is not built")
SLOT = dict(pin_radius=val.PIN_RADIUS, slot_width=val.SLOT_WIDTH, length=val.PIN_LENGTH)


def test_one_formula_for_the_flat_sides_and_the_ends():
    g = BearingGeometry(val.PIN_RADIUS, 0.5 * val.SLOT_WIDTH, val.PIN_LENGTH)
    c = g.clearance
    a = 0.05
    # on a flat side: the distance to the segment is |p_y|
    flat = slot_kinematics(g, a, 0.03, -1.2 * c, 0.0, 0.0, 0.0, 0.0)
    assert flat.delta == pytest.approx(0.2 * c, rel=1e-9)
    assert (flat.nx, flat.ny) == (0.0, -1.0)
    # beyond an end: the distance to the end centre (a, 0), by hand
    px, py = a + 0.6 * c, 0.9 * c
    end = slot_kinematics(g, a, px, py, 0.0, 0.0, 0.0, 0.0)
    assert end.delta == pytest.approx(math.hypot(px - a, py) - c, abs=1e-18)
    assert end.segment == a


def test_a_slot_of_length_zero_is_the_revolute_joints_kinematics():
    g = BearingGeometry(val.PIN_RADIUS, 0.5 * val.SLOT_WIDTH, val.PIN_LENGTH)
    args = (1.1e-4, -0.4e-4, 0.3, -0.2, 40.0)
    slot = slot_kinematics(g, 0.0, *args, 20.0)
    revolute = contact_kinematics(g, *args, 0.0, 0.0, 0.0, 0.0, 20.0)
    assert tuple(slot)[:-1] == tuple(revolute)  # the same floats
    # the slot's record is the revolute joint's fields, read by the same names, and the segment's point
    assert slot._fields == (*type(revolute)._fields, "segment") and slot.delta == revolute.delta and slot.segment == 0.0


@pytest.mark.parametrize(("change", "message"), [
    ({"slot_width": 2 * val.PIN_RADIUS}, r"`slot_width` must be larger than the pin's diameter"),
    ({"slot_length": -0.01}, r"`slot_length`"),
    ({"pin_radius": -1.0}, r"`pin_radius` must be positive"),
    ({"slot_length": None}, r"`slot_length` is required"),
    ({"axis": [0.0, 0.6, 0.8]}, r"`axis` must lie in the global x-y plane"),
])
def test_bad_input_is_refused_naming_the_argument(change, message):
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=val.PIN_MASS, inertia=val.PIN_INERTIA))
    kwargs = {**SLOT, "slot_length": 0.1, "cr": 0.7, "axis": [1.0, 0.0, 0.0], **change}
    kwargs = {k: v for k, v in kwargs.items() if v is not None}
    with pytest.raises(ValueError, match=message):
        exuclear.CreatePinSlotClearanceJoint(mbs, itemNumbers=[ground, body], **kwargs)


def test_slot_length_zero_is_the_revolute_clearance_joint():
    # the slot's frame is the revolute joint's for the z axis (x along -y): the same floats throughout
    same = val.pin_against_revolute(axis=(0.0, -1.0, 0.0))
    assert same["impacts"] == same["revolute_impacts"] >= 10
    assert same["difference"] == 0.0
    # another frame: round-off, which the adaptive steps (rtol 1e-8) turn into other steps; measured 1.2e-7
    turned = val.pin_against_revolute(axis=(0.8, 0.6, 0.0))
    assert turned["difference"] < 1e-6
    assert turned["impacts"] == turned["revolute_impacts"]


def _turning_slot(backend: str):
    """A slot 30 mm long turning at 20 rad/s, the pin flung along it spinning, friction: every
    term of the slot's kinematics and loads (flat sides and ends), probe and torque active."""
    mbs, joint, node = val.pin_in_slot(0.03, backend, axis=(0.8, 0.6, 0.0), velocity=(0.6, 0.1, 40.0),
                                       slot_spin=20.0, friction="coulomb:0.15")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.08, **val.SETTINGS))
    assert result.success, result.message
    return mbs, joint


@compiled_only
def test_both_kernels_give_the_same_pin_to_round_off(kernels_agree):
    compiled = _turning_slot("compiled")
    assert len(compiled[1].impacts()) >= 3
    kernels_agree(compiled, _turning_slot("python"))


def test_pin_sliding_on_a_flat_side_follows_coulomb():
    s = val.pin_sliding()
    # F_T = mu F_N at every output in contact (the slip is far above the smoothing speed)
    assert s["ratio_min"] == pytest.approx(s["mu"], rel=1e-9)
    assert s["ratio_max"] == pytest.approx(s["mu"], rel=1e-9)
    # v0 - mu g t and 2 mu g t / R_P while it slips (constant forces: DOPRI5 is exact but for
    # round-off and the resting contact's residual oscillation); measured 5e-13
    assert s["speed"] == pytest.approx(s["coulomb_speed"], rel=1e-9)
    assert s["spin"] == pytest.approx(s["coulomb_spin"], rel=1e-9)
