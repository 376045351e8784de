"""The impulse mode's reads of two markers (:class:`exuclear.engine.condition.MarkerState`)
against Exudyn's own marker outputs, and the 3-vector helpers (:mod:`exuclear.vectors`)
against numpy."""
from __future__ import annotations

import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import NodePoint2DSlope1, ObjectANCFCable2D
from exudyn.utilities import InertiaCuboid, MarkerBodyRigid

from exuclear.engine.condition import MarkerState
from exuclear.vectors import SECANT_SLOPE, angle, cross, dot, norm, secant_normal

#: Exudyn computes a marker's velocity as its maps times the rates in a few products of
#: terms of order 1: the two agree to round-off of those terms.
ROUND_OFF = 1e-12


def _two_bodies(shared: bool) -> tuple[exu.MainSystem, list[int]]:
    """Two rigid bodies of different rotation parameters (Euler parameters, Tait-Bryan
    angles), a marker off each body's centre; ``shared``: two ANCF cable elements that
    share a node, a marker on each."""
    mbs = exu.SystemContainer().AddSystem()
    if shared:
        nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[0.1 * k, 0.0, 1.0, 0.0])) for k in range(3)]
        bodies = [mbs.AddObject(ObjectANCFCable2D(nodeNumbers=nodes[k:k + 2], length=0.1, massPerLength=1.0,
                                                  bendingStiffness=1.0, axialStiffness=100.0)) for k in range(2)]
    else:
        inertia = InertiaCuboid(1000.0, [0.2, 0.1, 0.05])
        bodies = [mbs.CreateRigidBody(inertia=inertia, referencePosition=[0.3 * k, 0.0, 0.0], nodeType=node)
                  for k, node in enumerate((exu.NodeType.RotationEulerParameters, exu.NodeType.RotationRxyz))]
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=offset))
               for body, offset in zip(bodies, ([0.05, -0.02, 0.0], [0.03, 0.04, 0.0]))]
    mbs.Assemble()
    return mbs, markers


@pytest.mark.parametrize("shared", [False, True])
def test_the_velocity_maps_give_exudyns_marker_velocities_at_any_rates(shared):
    # markers on two rigid bodies are probed in one setting; on two elements that share a
    # node one after the other (a rate of the shared node moves both)
    mbs, markers = _two_bodies(shared)
    rng = np.random.default_rng(7)
    data = mbs.systemData
    q = data.GetODE2Coordinates() + 0.03 * rng.standard_normal(len(data.GetODE2Coordinates()))
    data.SetODE2Coordinates(q.tolist())
    state = MarkerState(mbs, markers)
    maps = state.maps(mbs, (True, True))
    indices = state.index_arrays
    for _ in range(3):  # the maps depend on the coordinates alone: any rates
        rates = rng.standard_normal(len(q))
        data.SetODE2Coordinates_t(rates.tolist())
        for marker, (velocity, spin), rows in zip(markers, maps, indices):
            v = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.Velocity))
            w = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.AngularVelocity))
            assert np.allclose(rates[rows] @ velocity, v, rtol=0.0, atol=ROUND_OFF * np.abs(rates).sum())
            assert np.allclose(rates[rows] @ spin, w, rtol=0.0, atol=ROUND_OFF * np.abs(rates).sum())
    # the probe leaves the system's rates as they were
    assert np.array_equal(data.GetODE2Coordinates_t(), rates)


def test_poses_are_read_again_where_the_coordinates_moved():
    mbs, markers = _two_bodies(False)
    state = MarkerState(mbs, markers)
    before = state.poses(mbs)
    assert state.poses(mbs) is before  # the same state: read once
    data = mbs.systemData
    q = data.GetODE2Coordinates()
    q[0] += 0.1  # the first body moves along x
    data.SetODE2Coordinates(q.tolist())
    after = state.poses(mbs)
    assert after is not before
    assert after.positions[0][0] == pytest.approx(before.positions[0][0] + 0.1, abs=1e-15)
    assert np.array_equal(after.positions[1], before.positions[1])


def test_the_3_vector_helpers_are_numpys_and_the_angle_keeps_small_angles():
    rng = np.random.default_rng(3)
    a, b = rng.standard_normal(3), rng.standard_normal(3)
    assert np.allclose(cross(a, b), np.cross(a, b), rtol=0.0, atol=1e-15)
    assert dot(a, b) == pytest.approx(float(a @ b), abs=1e-15)
    assert norm(a) == pytest.approx(float(np.linalg.norm(a)), rel=1e-15)
    # a turn of 1e-9 rad: acos of the dot product returns 0 (1 - 5e-19 rounds to 1), atan2 the turn
    tiny = 1e-9
    turned = (math.cos(tiny), math.sin(tiny), 0.0)
    assert angle((1.0, 0.0, 0.0), turned) == pytest.approx(tiny, rel=1e-12)
    assert angle((2.0, 0.0, 0.0), (-3.0, 0.0, 0.0)) == pytest.approx(math.pi, rel=1e-15)


def test_the_secant_normal_is_the_fixed_point_of_a_linear_turn():
    """A step held in the normal at angle ``p`` reaches the normal at ``a + g p`` (a linear
    map; ``g = -0.81`` is the ratio of successive misses measured on the zoo's
    rigid_body_tutorial3 at its step): its fixed point is ``a / (1 - g)``.  Repeating the
    reached normal leaves ``|g|`` of the miss per computation; the secant through two
    computations lands on the fixed point up to the circle's curvature over the turn."""
    g = -0.81

    def normal(p: float) -> tuple[float, float, float]:
        return (0.0, math.cos(p), math.sin(p))

    for a in (0.003, 0.03):
        first, second = 0.0, a  # held at 0, then in the normal the first reached
        aim = secant_normal(normal(first), normal(a + g * first), normal(second), normal(a + g * second))
        # unit vectors stand for angles: the secant through chords misses the arcs' fixed point
        # at third order in the turn (0.33 a^3: 9e-12 at 0.003 rad, 9e-9 at 0.03 rad)
        assert math.atan2(aim[2], aim[1]) == pytest.approx(a / (1.0 - g), abs=0.5 * a ** 3)
        assert norm(aim) == pytest.approx(1.0, abs=1e-15)
    # no secant where the held normals coincide, or where it would step past the reached normal
    # by more than the miss (a slope of SECANT_SLOPE or more)
    assert secant_normal(normal(0.0), normal(0.1), normal(0.0), normal(0.1)) is None
    slope = SECANT_SLOPE + 0.1
    assert secant_normal(normal(0.0), normal(0.1), normal(0.1), normal(0.1 + 0.1 * slope)) is None
