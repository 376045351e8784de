"""Wear of the clearance joint (docs/physics.md section 11): the worn-in journal against its
closed-form law (eqs. (82)-(84)), the invariants of Archard's law, and the input checks."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import exuclear
from exuclear.wear import analytic
from exuclear.wear.law import Wear
from validation.wear import worn_in_journal as scene

R_J = scene.RADIUS - scene.CLEARANCE


# -- the closed-form law -----------------------------------------------------------------
def test_the_law_tends_to_the_early_and_the_late_forms():
    """eq. (83) integrated: the early law where d0 << c, 2 k_D F / (pi r L) per metre of slip late."""
    args = (500.0, 1e-10, R_J, scene.CLEARANCE, scene.LENGTH)
    s = 1e-4
    assert analytic.depth_after_slip(s, *args) == pytest.approx(analytic.early_depth(s, *args), rel=0.01)
    late = 2.0 * 1e-10 * 500.0 / (math.pi * R_J * scene.LENGTH)
    assert analytic.depth_rate(5e-3, *args) == pytest.approx(late, rel=1e-12)  # half-angle 90 deg at 5 mm
    assert analytic.contact_half_angle(0.0, R_J, scene.CLEARANCE) == 0.0


def test_friction_slows_the_law_by_its_resultant():
    """With Coulomb friction the normal resultant is F / sqrt(1 + mu^2) (eq. (84))."""
    args = (R_J, scene.CLEARANCE, scene.LENGTH)
    for d in (1e-6, 5e-5, 1e-3):
        plain = analytic.depth_rate(d, 500.0, 1e-10, *args)
        assert analytic.depth_rate(d, 500.0, 1e-10, *args, mu=0.3) == pytest.approx(plain / math.sqrt(1.09), rel=1e-12)


# -- the joint against it ----------------------------------------------------------------
@pytest.fixture(scope="module")
def worn():
    """The worn-in journal over 0.1 s (slip 0.099 m), frictionless and with mu = 0.2."""
    return {mu: scene.run(0.1, mu=mu) for mu in (0.0, 0.2)}


@pytest.mark.parametrize("mu", [0.0, 0.2])
def test_the_worn_in_journal_follows_the_law(worn, mu):
    """The depth under the load within 0.5 % of eq. (83) at 36 um, 18 times the elastic
    approach; with friction the deepest point turns by atan(mu) (eq. (84)), within a node."""
    r = worn[mu]
    depth, angle = r.profile.deepest()
    assert r.state.delta < depth / 10.0  # the imprint is deep against the elastic approach
    assert depth == pytest.approx(scene.law_depth(r.slip, mu=mu), rel=0.005)
    turn = math.degrees(angle) - 180.0
    assert turn == pytest.approx(-math.degrees(math.atan(mu)), abs=0.5)


def test_frictionless_wear_is_symmetric_about_the_load(worn):
    """A load along -x on a frictionless joint wears the bearing symmetrically about 180 deg."""
    bearing = worn[0.0].profile.bearing
    n = len(bearing)
    k = np.arange(1, n // 4)
    left, right = bearing[n // 2 - k], bearing[n // 2 + k]
    assert np.max(np.abs(left - right)) < 1e-3 * bearing.max()


def test_the_imprint_takes_the_journals_arc(worn):
    """The worn bearing is the journal's circle about its centre where it carries load: the
    imprint's volume equals the lens the journal's circle, sunk by d0, cuts from the
    bearing's (eq. (82)), within 1 %."""
    p = worn[0.0].profile
    d0 = p.deepest()[0]
    e = scene.CLEARANCE + d0
    theta = np.linspace(-math.pi / 2, math.pi / 2, 20001)
    rho = e * np.cos(theta) + np.sqrt(R_J**2 - (e * np.sin(theta)) ** 2)
    lens = 0.5 * scene.LENGTH * np.trapezoid(np.maximum(rho**2 - scene.RADIUS**2, 0.0), theta)
    assert p.volume["bearing"] == pytest.approx(lens, rel=0.01)


def test_narrow_contact_wears_k_times_the_normal_force_times_the_slip():
    """Archard's volume: k_D F_N s while the contact arc is narrow (cos phi ~ 1); early in
    the worn-in journal (d0 = 1.3 um, a half-angle of 9 degrees) within 1.5 %."""
    k = 1e-12
    r = scene.run(0.05, coefficient=k)
    assert r.profile.volume["bearing"] == pytest.approx(k * scene.FORCE * r.slip, rel=0.015)
    assert r.profile.volume["journal"] == 0.0


def test_no_slip_no_wear():
    """A journal that rests on the bearing without turning does not wear it."""
    r = scene.run(0.02, spin=0.0)
    assert r.state.in_contact and r.profile.bearing.max() == 0.0


def test_the_wear_converges_in_the_grid_and_the_step():
    """The depth changes by less than 0.2 % from 360 to 1440 nodes, and from steps of 1e-4 s
    to 2.5e-5 s (fixed steps)."""
    depth = {n: scene.run(0.05, nodes=n).profile.deepest()[0] for n in (360, 1440)}
    assert depth[360] == pytest.approx(depth[1440], rel=0.002)
    steps = {h: scene.run(0.05, step=h, adaptive=False).profile.deepest()[0] for h in (1e-4, 2.5e-5)}
    assert steps[1e-4] == pytest.approx(steps[2.5e-5], rel=0.002)


def test_the_journal_wears_uniformly_when_it_turns_under_a_fixed_load():
    """A turning journal under a fixed load carries it with each point of its surface in
    turn: over two whole turns its wear is uniform around it, and its volume equals the
    bearing's (the same pressure, the same slip, the same coefficient), within 0.1 %."""
    r = scene.run(4.0 * math.pi / scene.SPIN, surface="both", coefficient=1e-12)
    journal = r.profile.journal
    assert journal.min() > 0.9 * journal.mean()
    assert r.profile.volume["journal"] == pytest.approx(r.profile.volume["bearing"], rel=1e-3)


def test_an_unstable_update_stops_the_run_and_says_the_step():
    """A step whose k_D K ds exceeds 1 (eq. (81)) stops the run, naming the cause and the step."""
    with pytest.raises(Exception, match=r"wear update is unstable: k_D K ds = .* give a step of at most"):  # noqa: PT011 - Exudyn's own error type
        scene.run(0.01, coefficient=1e-7, step=1e-3, adaptive=False)


# -- input -------------------------------------------------------------------------------
@pytest.mark.parametrize(("kwargs", "words"), [
    ({"coefficient": -1.0}, "must be positive"),
    ({"coefficient": 1e-12, "surface": "shaft"}, "unknown `surface`"),
    ({"coefficient": 1e-12, "pressure": "flat"}, "unknown `pressure`"),
    ({"coefficient": 1e-12, "nodes": 8}, "`nodes` must be a whole number >= 16"),
    ({"coefficient": 1e-12, "nodes": 16, "bearing": [0.0] * 15}, "16 depths, got 15"),
    ({"coefficient": 1e-12, "nodes": 16, "bearing": [-1e-6] * 16}, ">= 0"),
    ({"coefficient": 1e-12, "nodes": 16, "journal": [1e-6] * 16}, "only the bearing wears"),
])
def test_bad_wear_input_is_refused(kwargs, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        Wear(**kwargs)


def test_a_dimensionless_coefficient_is_questioned():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        Wear(coefficient=7e-3)
    assert any(issubclass(w.category, exuclear.UnitWarning) and "k_D = k / H" in str(w.message) for w in caught)


def test_a_joint_without_wear_has_no_profile():
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

    mbs = exu.SystemContainer().AddSystem()
    g = mbs.AddObject(ObjectGround())
    b = mbs.AddObject(ObjectRigidBody2D(nodeNumber=mbs.AddNode(NodeRigidBody2D()), mass=1.0, inertia=1e-4))
    h = exuclear.AddClearanceJoint(mbs, [mbs.AddMarker(MarkerBodyRigid(bodyNumber=g)),
                                         mbs.AddMarker(MarkerBodyRigid(bodyNumber=b))],
                                   journal_radius=R_J, bearing_radius=scene.RADIUS, length=scene.LENGTH, cr=0.9, show=False,
                                   name="pin")
    with pytest.raises(ValueError, match="joint 'pin' has no wear"):
        h.wear_profile()


# -- many cycles -------------------------------------------------------------------------
def _revolutions(cycles: float, **kwargs):
    """predict_wear over ``cycles`` revolutions of the worn-in journal (k_D = 1e-12 1/Pa)."""
    from exuclear.wear.cycles import predict_wear

    period = 2.0 * math.pi / scene.SPIN
    return predict_wear(lambda wear: scene.run(period, wear=wear).handle, Wear(coefficient=1e-12), cycles,
                        progress=False, **kwargs)


def _ripples(depth: np.ndarray) -> int:
    """Local maxima of a profile where it is worn."""
    inner = depth[1:-1]
    return int(np.sum((inner > depth[:-2]) & (inner > depth[2:]) & (inner > 1e-7)))


def test_extrapolated_cycles_follow_the_law():
    """100 revolutions in updates of half the stability bound (eq. (81)): the depth within
    0.2 % of eq. (83), one smooth imprint; the bound grows as the imprint widens."""
    p = _revolutions(100)
    slip = 100 * 2.0 * math.pi * R_J
    assert p.complete and p.cycles[-1] == 100
    assert p.deepest()[-1] == pytest.approx(scene.law_depth(slip, coefficient=1e-12), rel=0.002)
    assert _ripples(p.final.bearing) == 1
    assert p.bounds[-1] > 2.0 * p.bounds[0]
    assert all(s <= 0.5 * b or s == 1 or s == 100 - c0 for s, b, c0 in zip(p.steps, p.bounds, [0, *p.cycles[:-1]]))


@pytest.mark.slow
def test_extrapolation_converges_in_dn():
    """Halving the share of the bound (0.5 -> 0.25) moves the depth after 100 revolutions by
    less than 0.1 %."""
    half, quarter = _revolutions(100), _revolutions(100, safety=0.25)
    assert half.deepest()[-1] == pytest.approx(quarter.deepest()[-1], rel=1e-3)
    assert len(quarter.steps) > len(half.steps)


def test_extrapolation_past_the_bound_diverges_and_is_refused():
    """dN = 40 breaks the bound of the first cycles (4 to 9 revolutions): the profile's shape
    error grows into ripples (several local maxima, the depth 2 % off after 400 revolutions);
    predict_wear refuses that dN unless told not to check."""
    p = _revolutions(400, dN=40, check_bound=False)
    assert min(p.bounds) < 40
    assert _ripples(p.final.bearing) >= 3
    with pytest.raises(ValueError, match=r"`dN` = 40 cycles breaks the stability bound"):
        _revolutions(400, dN=40)


@pytest.mark.parametrize(("viscosity", "wears"), [(2.0, False), (0.01, True)])
def test_a_lubricated_joint_wears_where_metal_touches(viscosity, wears):
    """A journal started at the bearing's centre: oil of 2 Pa s carries the 500 N on a film
    (Sommerfeld number 0.8, no metal contact): no wear; oil of 0.01 Pa s cannot (Sommerfeld
    number 170): the journal touches the wall and the bearing wears (docs/physics.md
    section 11.3)."""
    mbs, handle, _ = scene.build(Wear(coefficient=1e-10), start=0.0,
                                 lubrication=exuclear.Lubrication(viscosity=viscosity, model="finite"))
    mbs.Assemble()
    mbs.SolveDynamic(scene.settings(0.05, 1e-4))
    touched = bool(np.any(handle.outputs()["regime"] == 2))
    assert touched == wears
    assert (handle.wear_profile().bearing.max() > 0.0) == wears
