"""Film laws of the lubricated joint (exuclear/film/, docs/physics.md section 10): published
numbers, closed forms and properties.  Pure physics, no Exudyn, no reference solver
(tests/test_reynolds.py compares with that)."""
from __future__ import annotations

import math

import pytest

from exuclear.film import (
    FILM_MODELS,
    Lubrication,
    attitude_angle,
    blend_eccentricity,
    film_kinematics,
    minimum_film_thickness,
    sommerfeld_number,
)
from exuclear.geometry import BearingGeometry

R = 0.01        # journal radius [m]
C = 10e-6       # radial clearance [m]: psi = 1e-3
ETA = 0.02      # [Pa s]
OMEGA = 300.0   # [rad/s]
MODELS = list(FILM_MODELS)


def geometry(width_ratio: float) -> BearingGeometry:
    return BearingGeometry(R, R + C, 2.0 * R * width_ratio)


def law(model: str, width_ratio: float = 0.5, viscosity: float = ETA):
    return Lubrication(viscosity=viscosity, model=model).law(geometry(width_ratio))


def so_beta(film, eps: float, omega: float = OMEGA) -> tuple[float, float]:
    """Sommerfeld number and attitude angle [deg] of a journal at e = (eps c, 0) spinning at omega."""
    load = film.load(eps * C, 0.0, 0.0, 0.0, omega, 0.0)
    return (sommerfeld_number(math.hypot(load.fx, load.fy), film.geometry, film.viscosity, omega),
            math.degrees(attitude_angle(eps * C, 0.0, load.fx, load.fy)))


def ocvirk(width_ratio: float, eps: float) -> tuple[float, float]:
    """Ocvirk's closed form as the brief states it: F = eta omega R L^3 / (4 c^2) eps
    sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (1 - eps^2)^2, so So = (B/D)^2 / 2 times the rest;
    tan(beta) = pi sqrt(1 - eps^2) / (4 eps)."""
    so = width_ratio ** 2 / 2 * eps * math.sqrt(math.pi ** 2 * (1 - eps ** 2) + 16 * eps ** 2) / (1 - eps ** 2) ** 2
    return so, math.degrees(math.atan(math.pi * math.sqrt(1 - eps ** 2) / (4 * eps)))


# -- inputs ------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, word", [
    (dict(viscosity=-0.01), "viscosity"),
    (dict(viscosity=0.0), "viscosity"),
    (dict(viscosity=float("nan")), "viscosity"),
    (dict(viscosity=0.01, model="petroff"), "model"),
    (dict(viscosity=0.01, eps_film=1.2), "eps_film"),
    (dict(viscosity=0.01, eps_film=0.9, eps_cap=0.85), "eps_cap"),
    (dict(viscosity=0.01, eps_cap=1.0), "eps_cap"),
])
def test_bad_input_names_the_argument(kwargs, word):
    with pytest.raises(ValueError, match=word):
        Lubrication(**kwargs)


def test_viscosity_in_mpa_s_warns():
    from exuclear.checks import UnitWarning

    with pytest.warns(UnitWarning, match="mPa s"):
        Lubrication(viscosity=40.0)


@pytest.mark.parametrize("width_ratio", [0.1, 1.5])
def test_finite_model_outside_its_range_fails(width_ratio):
    with pytest.raises(ValueError, match="B/D"):
        law("finite", width_ratio)


@pytest.mark.parametrize("model", MODELS)
def test_film_alone_refuses_the_wall(model):
    with pytest.raises(ValueError, match="eps"):
        law(model).load(C, 0.0, 0.0, 0.0, OMEGA, 0.0)


# -- published numbers and closed forms --------------------------------------------------------
@pytest.mark.parametrize("eps, so_published, half_digit", [(0.5, 0.02345, 0.5e-5), (0.9, 0.750, 0.5e-3)])
def test_short_model_is_ocvirk(eps, so_published, half_digit):
    # Ocvirk's closed form at B/D = 1/8; the published values are printed to 4 and 3 digits
    so, beta = so_beta(law("short", 1 / 8), eps)
    so_ocvirk, beta_ocvirk = ocvirk(1 / 8, eps)
    assert so == pytest.approx(so_ocvirk, rel=1e-12)     # the same formula: round-off only
    assert beta == pytest.approx(beta_ocvirk, abs=1e-10)
    assert so == pytest.approx(so_published, abs=half_digit)


@pytest.mark.parametrize("eps", [0.1, 0.5, 0.9, 0.99])
def test_long_model_rotation_is_half_sommerfeld(eps):
    # the half-Sommerfeld long bearing in closed form (textbook result, e.g. Hamrock, Schmid,
    # Jacobson, Fundamentals of Fluid Film Lubrication, 2004): F_r = 12 eta omega R^3 B eps^2 / (c^2 (2 + eps^2)(1 - eps^2)),
    # F_t = 6 pi eta omega R^3 B eps / (c^2 (2 + eps^2) sqrt(1 - eps^2))
    film = law("long", 2.0)
    load = film.load(eps * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
    b = film.geometry.length
    f_r = 12 * ETA * OMEGA * R ** 3 * b * eps ** 2 / (C ** 2 * (2 + eps ** 2) * (1 - eps ** 2))
    f_t = 6 * math.pi * ETA * OMEGA * R ** 3 * b * eps / (C ** 2 * (2 + eps ** 2) * math.sqrt(1 - eps ** 2))
    assert load.fx == pytest.approx(-f_r, rel=1e-11)
    assert load.fy == pytest.approx(f_t, rel=1e-11)


# Butenschoen's table (Diss. Karlsruhe 1976; the rotation values DIN 31652 rests on):
# (B/D, eps, So, beta [deg]).  The finite model is his fit to it; the fit's own error
# is what the tolerance allows: So within 5 %, beta within 1.6 deg (measured: -2.6 %,
# +4.8 %, +1.0 %, +2.3 % and +1.15, -0.43, +1.56, -0.90 deg, in the order below).
BUTENSCHOEN = [(1.0, 0.5, 0.8903, 56.705), (1.0, 0.9, 8.4352, 26.482), (1 / 8, 0.5, 0.0231, 53.784),
               (1 / 8, 0.9, 0.6776, 21.089)]
FIT_SO_TOL = 0.05
FIT_BETA_TOL = 1.6


@pytest.mark.parametrize("width_ratio, eps, so_table, beta_table", BUTENSCHOEN)
def test_finite_model_against_butenschoens_table(width_ratio, eps, so_table, beta_table):
    so, beta = so_beta(law("finite", width_ratio), eps)
    assert so == pytest.approx(so_table, rel=FIT_SO_TOL)
    assert beta == pytest.approx(beta_table, abs=FIT_BETA_TOL)


@pytest.mark.parametrize("rate", [1.0, -1.0])
def test_finite_model_squeeze_is_the_short_half_film_times_the_fit(rate):
    # eq. (66): So_V is the short model's half-film squeeze (the Guembel arc around the
    # smallest gap when approaching, around the largest when leaving: eps -> -eps) times
    # a8 (1 - x) / (-a9 - x), x = eps sign(eps_dot)
    width_ratio, eps = 0.5, 0.6
    finite, short = law("finite", width_ratio), law("short", width_ratio)
    f_fin = finite.load(eps * C, 0.0, rate * C, 0.0).fx
    f_short = short.load(eps * C, 0.0, rate * C, 0.0).fx
    a8, a9 = finite._coefficients[7:]
    x = eps * rate
    assert f_fin / f_short == pytest.approx(a8 * (1 - x) / (-a9 - x), rel=1e-12)


# -- properties --------------------------------------------------------------------------------
@pytest.mark.parametrize("model", MODELS)
def test_no_force_when_centred_and_not_squeezing(model):
    load = law(model).load(0.0, 0.0, 0.0, 0.0, OMEGA, -0.3 * OMEGA)
    assert (load.fx, load.fy) == (0.0, 0.0)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("eps", [0.0, 0.3, 0.8])
@pytest.mark.parametrize("direction_deg", [0.0, 40.0, 180.0, 250.0])
def test_squeeze_force_opposes_the_squeeze_velocity(model, eps, direction_deg):
    # pure squeeze (no spin, no whirl): journal at e = (eps c, 0) approaching or leaving the
    # wall along e (off centre a tangential part would be a whirl); from the centre any direction
    a = math.radians(direction_deg)
    vx, vy = (0.5 * C * math.cos(a), 0.0) if eps > 0 else (0.5 * C * math.cos(a), 0.5 * C * math.sin(a))
    load = law(model).load(eps * C, 0.0, vx, vy)
    power = load.fx * vx + load.fy * vy
    assert power < 0.0
    assert abs(load.fx * vy - load.fy * vx) <= 1e-12 * math.hypot(load.fx, load.fy) * math.hypot(vx, vy)


@pytest.mark.parametrize("model", MODELS)
def test_wedge_force_is_linear_in_viscosity_and_speed(model):
    e = (0.4 * C, -0.5 * C)
    base = law(model).load(*e, 0.0, 0.0, OMEGA, 0.0)
    for factor in (0.25, 3.0):
        faster = law(model).load(*e, 0.0, 0.0, factor * OMEGA, 0.0)
        thicker = law(model, viscosity=factor * ETA).load(*e, 0.0, 0.0, OMEGA, 0.0)
        for other in (faster, thicker):
            assert other.fx == pytest.approx(factor * base.fx, rel=1e-12)
            assert other.fy == pytest.approx(factor * base.fy, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("eps", [0.2, 0.7])
def test_half_frequency_whirl_carries_no_wedge_load(model, eps):
    # journal spinning at omega, its centre whirling at omega / 2 on a circle: no squeeze,
    # omega_J + omega_B - 2 dphi/dt = 0, so no pressure at all
    phi, whirl = 0.7, 0.5 * OMEGA
    e = (eps * C * math.cos(phi), eps * C * math.sin(phi))
    v = (-whirl * e[1], whirl * e[0])
    load = law(model).load(*e, *v, OMEGA, 0.0)
    assert load.omega_eff == pytest.approx(0.0, abs=1e-9 * OMEGA)
    assert math.hypot(load.fx, load.fy) <= 1e-9 * math.hypot(*law(model).load(*e, 0.0, 0.0, OMEGA, 0.0)[:2])


@pytest.mark.parametrize("model", MODELS)
def test_whirl_enters_only_through_omega_eff(model):
    # a whirling journal carries what a fixed one carries at omega_eff = omega_J + omega_B - 2 dphi/dt
    e, whirl, w_j, w_b = (0.3 * C, 0.4 * C), 70.0, 400.0, -50.0
    moving = law(model).load(*e, -whirl * e[1], whirl * e[0], w_j, w_b)
    fixed = law(model).load(*e, 0.0, 0.0, w_j + w_b - 2 * whirl, 0.0)
    assert (moving.fx, moving.fy) == pytest.approx((fixed.fx, fixed.fy), rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_reversed_spin_mirrors_the_force(model):
    ahead = law(model).load(0.6 * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
    back = law(model).load(0.6 * C, 0.0, 0.0, 0.0, -OMEGA, 0.0)
    assert (back.fx, back.fy) == pytest.approx((ahead.fx, -ahead.fy), rel=1e-12)
    assert ahead.f_n < 0.0 and ahead.fy > 0.0   # pushed back to the centre, and ahead of e for omega > 0


@pytest.mark.parametrize("model", ["short", "long"])
def test_force_is_continuous_where_the_cavitated_arc_turns(model):
    # the Guembel arc turns with eps_dot; the force must not jump as eps_dot changes sign
    film = law(model)
    forces = [film.load(0.5 * C, 0.0, s * 1e-9 * C, 0.0, OMEGA, 0.0) for s in (-1.0, 0.0, 1.0)]
    for f in forces[::2]:
        assert (f.fx, f.fy) == pytest.approx((forces[1].fx, forces[1].fy), rel=1e-7)


@pytest.mark.parametrize("model", MODELS)
def test_torques_balance_the_couple_of_the_film_force(model):
    # the film stores no angular momentum: M_J + M_B + (e x F)_z = 0 (physics.md eq. (69))
    e, v = (0.5 * C, -0.3 * C), (0.2 * C, 0.1 * C)
    load = law(model).load(*e, *v, OMEGA, 0.2 * OMEGA)
    couple = e[0] * load.fy - e[1] * load.fx
    assert load.torque_journal + load.torque_bearing + couple == pytest.approx(0.0, abs=1e-12 * abs(couple))
    assert load.torque_journal < 0.0   # the film brakes the faster journal


def test_petroff_torque_of_a_centred_journal():
    # Petroff (1883): M = 2 pi eta R^3 B (omega_J - omega_B) / c, no load
    film = law("short")
    load = film.load(0.0, 0.0, 0.0, 0.0, OMEGA, 0.0)
    petroff = 2 * math.pi * ETA * R ** 3 * film.geometry.length * OMEGA / C
    assert load.torque_journal == pytest.approx(-petroff, rel=1e-13)
    assert load.torque_bearing == pytest.approx(petroff, rel=1e-13)


def test_helpers():
    assert minimum_film_thickness(0.75, C) == pytest.approx(0.25 * C)
    kin = film_kinematics(0.0, 0.0, 0.0, 2 * C, 1.0, 2.0, C)
    assert (kin.nx, kin.ny, kin.eps_dot, kin.omega_eff) == (0.0, 1.0, 2.0, 3.0)
    film = law("short", 1 / 8)
    load = film.load(0.5 * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
    assert sommerfeld_number(math.hypot(load.fx, load.fy), film.geometry, ETA, -OMEGA) == pytest.approx(
        ocvirk(1 / 8, 0.5)[0], rel=1e-12)


# -- the blend to metal contact (physics.md eq. (70)) --------------------------------------------
def test_blend_is_the_identity_below_eps_film():
    for eps in (0.0, 0.5, 0.9):
        assert blend_eccentricity(eps, 3.0) == (eps, 3.0)


def test_blend_is_smooth_monotone_and_stays_off_the_wall():
    h = 1e-6
    for eps in (0.9, 0.95, 1.0, 1.3):
        below, _ = blend_eccentricity(eps - h, 0.0)
        above, _ = blend_eccentricity(eps + h, 0.0)
        _, rate = blend_eccentricity(eps, 1.0)
        assert (above - below) / (2 * h) == pytest.approx(rate, rel=1e-6)   # eps_dot_b is d eps_b / dt
        assert below < above < 0.97
    assert blend_eccentricity(0.9 + 1e-7, 1.0)[1] == pytest.approx(1.0, rel=1e-9)   # slope 1 at eps_film


@pytest.mark.parametrize("model", ["short", "long", "finite"])
def test_blended_film_is_finite_and_growing_through_the_wall(model):
    film = law(model)
    radial = [-film.blended_load(eps * C, 0.0, 0.0, 0.0, OMEGA, 0.0).f_n for eps in (0.85, 0.9, 0.95, 1.0, 1.05, 1.5)]
    assert all(math.isfinite(f) for f in radial)
    assert radial == sorted(radial)
    assert film.blended_load(0.85 * C, 0.0, 0.1 * C, 0.0, OMEGA, 0.0) == film.load(0.85 * C, 0.0, 0.1 * C, 0.0,
                                                                                    OMEGA, 0.0)


@pytest.mark.parametrize("eps", [0.3, 0.8])
def test_finite_model_torque_is_butenschoens_friction_coefficient(eps):
    # Butenschoen's (and DIN 31652's) friction coefficient of the journal,
    # mu = psi (pi / (sqrt(1 - eps^2) So) + sin(beta) eps / 2), M_J = -mu F R (omega_B = 0)
    film = law("finite", 0.5)
    load = film.load(eps * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
    force = math.hypot(load.fx, load.fy)
    so, beta = film.rotation(eps)
    mu = C / R * (math.pi / (math.sqrt(1 - eps ** 2) * so) + math.sin(beta) * eps / 2)
    assert load.torque_journal == pytest.approx(-mu * force * R, rel=1e-12)


def _quadrature(model: str, eps: float, eps_dot: float, omega_eff: float, n: int = 200_000) -> tuple[float, float]:
    """(F_n, F_p) by brute force: the positive part of the full-film pressure, eq. (58) or
    (61), summed on n points in theta (midpoint rule); none of the closed forms."""
    import numpy as np

    theta = (np.arange(n) + 0.5) * 2 * np.pi / n
    k = 1 + eps * np.cos(theta)
    b = 2.0 * R * 0.5
    if model == "short":   # eq. (58) integrated over z: eta B^3 / (2 c^2) (...) / k^3
        line = ETA * b ** 3 / (2 * C ** 2) * (eps * omega_eff * np.sin(theta) - 2 * eps_dot * np.cos(theta)) / k ** 3
    else:                  # eq. (61) times the width
        line = 6 * ETA * R ** 2 / C ** 2 * b * (
            eps * omega_eff * np.sin(theta) * (2 + eps * np.cos(theta)) / ((2 + eps ** 2) * k ** 2)
            + eps_dot * (3 * eps - 4 * np.cos(theta) - 2 * eps * np.cos(theta) ** 2) / ((2 + 3 * eps ** 2) * k ** 2))
    line = np.maximum(line, 0.0)
    # the pressure at theta pushes the journal along (cos(theta), sin(theta)) in (n, n + 90 deg)
    return (R * float(np.sum(line * np.cos(theta))) * 2 * np.pi / n,
            R * float(np.sum(line * np.sin(theta))) * 2 * np.pi / n)


@pytest.mark.parametrize("model", ["short", "long"])
@pytest.mark.parametrize("seed", range(6))
def test_closed_forms_match_brute_force_quadrature_of_the_positive_pressure(model, seed):
    # random journals (eps, eps_dot, omega_eff of either sign): the arcs found as polynomial
    # roots and the integrals in Sommerfeld's variable against a plain sum over theta.
    # 2e5 midpoints: the kinks at the arcs' ends leave at most 7e-11 of the force (measured); 1e-6 allowed
    import random

    rng = random.Random(seed)
    eps = rng.uniform(0.0, 0.9)
    eps_dot, omega_eff = rng.uniform(-1, 1) * OMEGA, rng.choice([-1, 1]) * rng.uniform(0, 1) * OMEGA
    f_n, f_p = law(model).components(eps, eps_dot, omega_eff)
    q_n, q_p = _quadrature(model, eps, eps_dot, omega_eff)
    assert (f_n, f_p) == pytest.approx((q_n, q_p), abs=1e-6 * math.hypot(q_n, q_p))


def _long_by_adaptive_quadrature(eps: float, eps_dot: float, omega_eff: float) -> tuple[tuple[float, float], list]:
    """(F_n, F_p) of the long model straight from eq. (61), and the zeros of its pressure:
    the numerator's sign changes on a grid in theta, each refined by brentq to round-off, and
    the positive part integrated between them by adaptive quadrature (the integrand vanishes
    at the zeros, so their error enters only squared).  None of the model's formulas: no
    Sommerfeld variable, no quartic, no antiderivatives."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    def numerator(t: float) -> float:   # eq. (61)'s bracket times (1 + eps cos)^2
        return (eps * omega_eff * math.sin(t) * (2 + eps * math.cos(t)) / (2 + eps ** 2)
                + eps_dot * (3 * eps - 4 * math.cos(t) - 2 * eps * math.cos(t) ** 2) / (2 + 3 * eps ** 2))

    g = geometry(0.5)   # its clearance (R + C) - R, as the law has it
    scale = 6 * ETA * g.journal_radius ** 3 * g.length / g.clearance ** 2
    grid = [2 * math.pi * k / 720 for k in range(721)]
    zeros = [brentq(numerator, lo, hi, xtol=1e-15, rtol=4 * 2.3e-16)
             for lo, hi in zip(grid[:-1], grid[1:]) if numerator(lo) * numerator(hi) < 0]
    ends = [0.0, *zeros, 2 * math.pi]
    # absolute tolerance: 1e-14 of the largest pressure times the circumference (a force
    # component can be far smaller than the force, e.g. F_p under pure squeeze)
    tol = 1e-14 * 2 * math.pi * max(abs(numerator(t)) / (1 + eps * math.cos(t)) ** 2 for t in grid)
    forces = [0.0, 0.0]
    for lo, hi in zip(ends[:-1], ends[1:]):
        if numerator(0.5 * (lo + hi)) > 0:
            for k, trig in enumerate((math.cos, math.sin)):
                forces[k] += scale * quad(lambda t, trig=trig: numerator(t) / (1 + eps * math.cos(t)) ** 2 * trig(t), lo, hi,
                                          epsabs=tol, epsrel=1e-13, limit=200)[0]
    return (forces[0], forces[1]), zeros


#: (eps, eps_dot [1/s], omega_eff [rad/s]): wedge- and squeeze-dominated, pure squeeze both ways,
#: either spin, eps near 0 and at the blend's cap eps_cap = 0.97 (the largest the joint evaluates)
LONG_STATES = [(0.5, 1e-4, OMEGA), (0.8, -1e-3, -OMEGA), (0.5, 100.0, 1e-3), (0.6, 50.0, 0.0), (0.3, -100.0, 0.0),
               (0.4, 30.0, -200.0), (0.7, -80.0, 150.0), (1e-6, 40.0, OMEGA), (0.05, -3.0, OMEGA),
               (0.97, 20.0, OMEGA), (0.97, -200.0, 50.0), (0.95, 5.0, -OMEGA), (0.9, 300.0, 10.0)]


@pytest.mark.parametrize("eps, eps_dot, omega_eff", LONG_STATES)
def test_long_model_against_adaptive_quadrature_of_sommerfelds_pressure(eps, eps_dot, omega_eff):
    # the cavitation boundaries of physics.md eqs. (62a)-(62c) and the closed-form integrals of
    # eq. (63) against eq. (61) integrated directly.  Measured: within 2e-13 at (0.97, -200, 50),
    # 3e-15 elsewhere (numpy's eigenvalue roots, used before: 1.1e-12 and 1.5e-14); 1e-11 leaves
    # round-off room near the wall and catches any change of the physics
    (q_n, q_p), zeros = _long_by_adaptive_quadrature(eps, eps_dot, omega_eff)
    assert len(zeros) == 2   # exactly two zeros, one in each half circle (the lemma of eq. (62a))
    assert zeros[0] < math.pi < zeros[1]
    f_n, f_p = law("long").components(eps, eps_dot, omega_eff)
    assert (f_n, f_p) == pytest.approx((q_n, q_p), rel=0, abs=1e-11 * math.hypot(q_n, q_p))


@pytest.mark.parametrize("eps", [0.2, 0.6, 0.97])
def test_long_model_squeeze_alone_ends_where_the_closed_form_puts_them(eps):
    # squeeze alone: eq. (61) vanishes where 2 eps cos^2 + 4 cos - 3 eps = 0, so
    # cos(theta) = (sqrt(4 + 6 eps^2) - 2) / (2 eps) (physics.md section 10.2): a check of the
    # quadrature's zeros, which the test above takes as the reference
    _, zeros = _long_by_adaptive_quadrature(eps, 50.0, 0.0)
    cos_zero = (math.sqrt(4 + 6 * eps ** 2) - 2) / (2 * eps)
    assert [math.cos(z) for z in zeros] == pytest.approx([cos_zero, cos_zero], abs=1e-13)
    assert zeros[0] < math.pi / 2 and zeros[1] > 3 * math.pi / 2   # the film spans the smallest gap, theta = pi


def test_film_module_is_pure_physics():
    # STYLE.md: laws never import exudyn; the library never imports matplotlib
    import ast
    import pathlib

    import exuclear.film

    files = sorted(pathlib.Path(exuclear.film.__file__).parent.glob("*.py"))  # the film package, by role
    own = {path.stem for path in files}
    for path in files:
        tree = ast.parse(path.read_text())
        imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}
        imported |= {node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
        assert not {name for name in imported if name.split(".")[0] in ("exudyn", "matplotlib")}, path.name
        assert imported - own <= {"__future__", "math", "abc", "dataclasses", "typing", "numpy", "checks", "geometry"}, \
            path.name


# -- the finite model's width range and its smoothness where a journal comes to rest -------------
def test_finite_model_accepts_its_width_range_within_the_clearance_ratio():
    # Butenschoen's fits are for 1/8 <= B/D <= 1 (DIN 31652-2); D may be the journal's or the
    # bearing's diameter, which differ by c/R (1e-3 here): a bearing as long as its own bore
    # (B/D = 1.001 with the journal's) and one an eighth of the journal's diameter are inside
    psi = C / R
    for length in (2.0 * (R + C), 2.0 * R / 8.0):
        Lubrication(viscosity=ETA, model="finite").law(BearingGeometry(R, R + C, length))
    # beyond, by a tenth of the clearance ratio: refused, naming B/D and the diameter
    for length, word in ((2.0 * (R + C) * (1.0 + 0.1 * psi), "bearing's"), (2.0 * R / 8.0 * (1.0 - 0.1 * psi),
                                                                           "journal's")):
        with pytest.raises(ValueError, match=f"B/D .*D the {word} diameter"):
            Lubrication(viscosity=ETA, model="finite").law(BearingGeometry(R, R + C, length))


@pytest.mark.parametrize("width_ratio", [1 / 8, 1 / 2, 1.0])
@pytest.mark.parametrize("eps", [0.8, 0.896, 0.9, 0.95, 0.99])
def test_rotating_finite_film_is_smooth_in_the_squeeze_rate_at_rest(width_ratio, eps):
    # a loaded journal comes to rest at eps_dot = 0; there the film's slope in eps_dot (its
    # damping, which dominates Newton's matrix) is the same from both sides and equals
    # eq. (66a)'s mean of the approaching and leaving numbers (blended eccentricity near the
    # wall, eq. (70)).  Butenschoen's switch alone made the two one-sided slopes differ by the
    # factor So_V(eps) / So_V(-eps), 281 at B/D = 1, eps 0.896.  Differences over 1e-6 of the
    # wedge: the one-sided slopes agree to that order (second derivative times the increment)
    film = law("finite", width_ratio)
    g = film.geometry
    eps_b, _ = blend_eccentricity(eps, 0.0, film.eps_film, film.eps_cap)
    _, rate_factor = blend_eccentricity(eps, 1.0, film.eps_film, film.eps_cap)
    h = 1e-6 * eps_b * OMEGA * math.sqrt(1.0 - eps_b ** 2) / 2.0  # [1/s]
    f0, fp, fm = (film.blended_load(eps * C, 0.0, v * C, 0.0, OMEGA, 0.0).fx for v in (0.0, h, -h))
    slope_up, slope_down = (f0 - fp) / h, (fm - f0) / h
    unit = g.length * 2.0 * R * ETA / (C / R) ** 2  # eq. (67)
    mean = 0.5 * (film.squeeze(eps_b) + film.squeeze(-eps_b)) * unit * rate_factor
    assert slope_up == pytest.approx(mean, rel=1e-4)
    assert slope_down == pytest.approx(mean, rel=1e-4)
