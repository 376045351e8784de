"""Properties of the contact laws, materials and friction laws (pure physics, no Exudyn)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import exuclear
from exuclear import contact_law
from exuclear.contact import CONTACT_LAWS
from exuclear.friction import ModifiedCoulomb, smooth_step

DAMPED = [name for name in CONTACT_LAWS if name != "hertz"]


def _law(name, geometry, e_star, cr=0.7):
    return contact_law(name, geometry, e_star, 1.0 if name == "hertz" else cr)


def test_composite_modulus_steel_steel():
    # eq. (9) by hand: 1 / (2 (1 - 0.3^2) / 207 GPa)
    assert exuclear.composite_modulus("steel", "steel") == pytest.approx(207e9 / (2 * 0.91), rel=1e-12)


def test_composite_modulus_mixed_is_between_the_pure_ones():
    steel, copper = (exuclear.composite_modulus(m, m) for m in ("steel", "copper"))
    assert copper < exuclear.composite_modulus("copper", "steel") < steel


@pytest.mark.parametrize("name", list(CONTACT_LAWS))
def test_no_force_without_penetration(name, geometry, e_star):
    law = _law(name, geometry, e_star)
    for delta in (-1e-4, -1e-9, 0.0):
        for rate in (-1.0, 0.0, 1.0):
            assert law.normal_force(delta, rate, 0.3) == 0.0


@pytest.mark.parametrize("name", list(CONTACT_LAWS))
def test_continuous_at_onset(name, geometry, e_star):
    # F ~ delta^1.5: at delta = 1e-12 m with a 1 m/s approach the force is below 1e-3 N
    law = _law(name, geometry, e_star)
    assert law.normal_force(1e-12, 1.0, 0.3) < 1e-3
    assert law.normal_force(1e-12, 1.0, 0.3) > 0.0


@pytest.mark.parametrize("name", list(CONTACT_LAWS))
def test_never_negative(name, geometry, e_star):
    law = _law(name, geometry, e_star, cr=0.3)
    rng = np.random.default_rng(1)
    for delta, rate, v0 in zip(rng.uniform(-1e-5, 1e-5, 500), rng.uniform(-5, 5, 500), rng.uniform(0, 1, 500), strict=True):
        assert law.normal_force(delta, rate, v0) >= 0.0


@pytest.mark.parametrize("name", list(CONTACT_LAWS))
def test_elastic_part_increases_with_penetration(name, geometry, e_star):
    law = _law(name, geometry, e_star)
    forces = [law.normal_force(d, 0.0, 0.3) for d in np.linspace(1e-9, 5e-5, 200)]
    assert np.all(np.diff(forces) > 0.0)


def test_wang_liu_formula_by_hand(geometry, e_star):
    # paper eqs. (7)-(8), docs/physics.md eqs. (9)-(12), evaluated independently
    law = contact_law("wang-liu", geometry, e_star, 0.5)
    delta, rate, v0 = 2e-6, 0.1, 0.3
    k = math.pi * e_star * 0.015 / 2 * math.sqrt(1 / (2 * (1e-4 + delta)))
    d = 3 * (1 - 0.25) * math.exp(1.0) / 4
    assert law.normal_force(delta, rate, v0) == pytest.approx(k * delta**1.5 * (1 + d * rate / v0), rel=1e-12)


def test_lankarani_nikravesh_formula_by_hand(geometry, e_star):
    law = contact_law("lankarani-nikravesh", geometry, e_star, 0.5)
    k = 4 / 3 * e_star * math.sqrt(10e-3 * 9.9e-3 / 1e-4)
    assert law.normal_force(2e-6, 0.1, 0.3) == pytest.approx(k * 2e-6**1.5 * (1 + 0.75 * 0.75 * 0.1 / 0.3), rel=1e-12)


@pytest.mark.parametrize("name", DAMPED)
def test_no_damping_at_full_restitution(name, geometry, e_star):
    assert _law(name, geometry, e_star, cr=1.0).damping_factor == 0.0


@pytest.mark.parametrize("name", DAMPED)
def test_v0_floor(name, geometry, e_star):
    # v0 below v_min (including 0) is replaced by v_min: same force as v0 = v_min
    law = _law(name, geometry, e_star)
    ref = law.normal_force(1e-6, 1e-3, law.v_min)
    assert law.normal_force(1e-6, 1e-3, 0.0) == ref
    assert law.normal_force(1e-6, 1e-3, 1e-9) == ref


def test_hertz_rejects_dissipation(geometry, e_star):
    with pytest.raises(ValueError, match="`cr` must be 1"):
        contact_law("hertz", geometry, e_star, 0.9)


# -- friction ------------------------------------------------------------------------------
def test_smooth_step_ends_and_middle():
    assert smooth_step(-1.0, 0.0, 2.0, 1.0, 4.0) == 2.0
    assert smooth_step(2.0, 0.0, 2.0, 1.0, 4.0) == 4.0
    assert smooth_step(0.5, 0.0, 2.0, 1.0, 4.0) == pytest.approx(3.0)


def test_paper_friction_values_and_oddness():
    mu = ModifiedCoulomb.paper()  # the paper's Table 1
    assert mu(1e-2) == pytest.approx(0.25) and mu(1.0) == pytest.approx(0.25)
    assert mu(1e-4) == pytest.approx(0.3)
    assert mu(0.0) == 0.0
    for v in (3e-5, 2e-4, 5e-3, 0.5):
        assert mu(-v) == -mu(v)


@pytest.mark.parametrize("v", [1e-4, 1e-2, -1e-4, -1e-2])
def test_paper_friction_value_and_slope_continuous_at_transitions(v):
    mu, h = ModifiedCoulomb.paper(), 1e-12
    assert mu(v - h) == pytest.approx(mu(v + h), abs=1e-9)
    # zero slope on both sides of every transition of the cubic step (docs/physics.md eq. (21)).
    # Tolerance: |mu''| <= 6 * 0.3 / (2e-4)^2 = 4.5e7 near v_s, so the one-sided difference
    # quotient is off by up to mu'' h / 2 = 2.3e-5, plus rounding 1e-16 / h = 1e-4.
    assert (mu(v + h) - mu(v)) / h == pytest.approx(0.0, abs=1e-3)
    assert (mu(v) - mu(v - h)) / h == pytest.approx(0.0, abs=1e-3)


def test_friction_never_drives_the_slip():
    # F_T v_T = mu(v_T) v_T F_N >= 0: friction dissipates for every slip velocity
    for law in (ModifiedCoulomb.paper(), exuclear.friction.Coulomb(0.1), exuclear.friction.NO_FRICTION):
        for v in np.linspace(-0.05, 0.05, 401):
            assert law(v) * v >= 0.0


def test_friction_names():
    assert exuclear.friction_law("none") is exuclear.friction.NO_FRICTION
    assert exuclear.friction_law("coulomb:0.01") == exuclear.friction.Coulomb(0.01)
    assert exuclear.friction_law("paper") == ModifiedCoulomb.paper()


def test_friction_coefficient_above_one_warns_and_a_negative_one_is_refused():
    # "coulomb:1.5" was taken without a word (issue 21): dry steel on steel is about 0.75,
    # only clean dry soft metals reach 1 to 1.35 (exuclear.friction.MU_WARN, with its source)
    import warnings

    with pytest.warns(exuclear.ValidityWarning, match=r"`mu` = 1.5 is above 1"):
        exuclear.friction_law("coulomb:1.5")
    with pytest.warns(exuclear.ValidityWarning, match=r"`mu_s` = 1.2"):
        ModifiedCoulomb(mu_s=1.2, mu_d=0.9, v_s=1e-4, v_d=1e-2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the paper's values and the bound itself are quiet
        ModifiedCoulomb.paper()
        exuclear.friction_law(f"coulomb:{exuclear.friction.MU_WARN}")
    with pytest.raises(ValueError, match="`mu` must be non-negative, got -0.1"):
        exuclear.friction_law("coulomb:-0.1")



@pytest.mark.parametrize("law", [ModifiedCoulomb.paper(), exuclear.friction.Coulomb(0.1, v_eps=2e-4)], ids=["paper", "coulomb"])
def test_friction_expression_matches_the_branch_formula(law):
    # eq. (11) of the paper written with branches, as docs/physics.md eq. (22) states it; the
    # laws evaluate one branch-free expression (shared with the compiled element)
    def by_branches(v):
        if isinstance(law, exuclear.friction.Coulomb):
            return math.copysign(smooth_step(abs(v), -law.v_eps, -law.mu, law.v_eps, law.mu), v)
        speed = abs(v)
        if speed >= law.v_d:
            return math.copysign(law.mu_d, v)
        if speed >= law.v_s:
            return math.copysign(smooth_step(speed, law.v_s, law.mu_s, law.v_d, law.mu_d), v)
        return smooth_step(v, -law.v_s, -law.mu_s, law.v_s, law.mu_s)

    for v in np.concatenate([np.linspace(-0.02, 0.02, 801), [0.0, 1e-4, -1e-4, 1e-2, -1e-2]]):
        assert law(v) == pytest.approx(by_branches(v), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("name", sorted(CONTACT_LAWS))
def test_nan_rate_gives_nan_force_not_zero(name, geometry, e_star):
    # the no-adhesion clamp must not turn a diverged state into a silent zero force:
    # the NaN reaches the state, where the step hook stops the run and says so
    law = contact_law(name, geometry, e_star, 1.0 if name == "hertz" else 0.5)
    assert math.isnan(law.normal_force(1e-6, math.nan, 0.3))
