"""The contact-law library (issue 13): stiffness models, damping models and their pairs.

Reference values: the former laws' formulas (git history of the module ``exuclear.contact``, a package now,
written out here), closed forms of the sources, the exact restitution relation of the
Hunt-Crossley force, an independent one-degree-of-freedom SciPy integration
(:func:`validation.contact_laws.one_dof_impact`) and the paper's published departure
velocities.  Pure physics, no Exudyn.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import exuclear
from exuclear import contact as C
from validation.contact_laws import one_dof_impact

GRID_DELTA = (1e-12, 1e-9, 3.3e-7, 1e-6, 4.7e-6, 2e-5)
GRID_RATE = (-0.7, -1e-4, 0.0, 0.05, 0.3, 2.0)
GRID_V0 = (-0.1, 0.0, 5e-4, 0.3)


def _law(name, geometry, e_star, cr):
    return C.contact_law(name, geometry, e_star, cr)


# -- the five named laws: unchanged forces ---------------------------------------------------
def _old_force(name, g, e_star, cr, delta, rate, v0, v_min=C.V_MIN_DEFAULT):
    """The former classes' normal_force (the module exuclear.contact before issue 13), operation for operation."""
    if delta <= 0.0:
        return 0.0
    v0_eff = v0 if v0 > v_min else v_min
    hertz_k = 4.0 / 3.0 * e_star * math.sqrt(g.bearing_radius * g.journal_radius / g.clearance)
    if name == "wang-liu":
        k = math.pi * e_star * g.length / 2.0 * math.sqrt(1.0 / (2.0 * (g.clearance + delta)))
        d = 3.0 * (1.0 - cr**2) * math.exp(2.0 * (1.0 - cr)) / 4.0
    else:
        k = hertz_k
        d = {"lankarani-nikravesh": 3.0 * (1.0 - cr**2) / 4.0, "hertz": 0.0, "hunt-crossley": 1.5 * (1.0 - cr),
             "flores": 8.0 * (1.0 - cr) / (5.0 * cr)}[name]
    f = k * delta**1.5 * (1.0 + d * rate / v0_eff)
    return 0.0 if f < 0.0 else f


@pytest.mark.parametrize("name", sorted(C.CONTACT_LAWS))
def test_named_laws_are_bit_identical_to_the_former_formulas(name, geometry, e_star):
    # equality, not approx: the aliases must evaluate the same float operations in the same order
    for cr in ((1.0,) if name == "hertz" else (0.3, 0.7, 0.9, 1.0)):
        law = _law(name, geometry, e_star, cr)
        by_class = C.CONTACT_LAWS[name](geometry, e_star, cr)
        for delta in (-1e-6, 0.0, *GRID_DELTA):
            for rate in GRID_RATE:
                for v0 in GRID_V0:
                    old = _old_force(name, geometry, e_star, cr, delta, rate, v0)
                    assert law.normal_force(delta, rate, v0) == old
                    assert by_class(delta, rate, v0) == old


@pytest.mark.parametrize("name", sorted(C.ALIASES))
def test_named_law_equals_its_pair(name, geometry, e_star):
    cr = 1.0 if name == "hertz" else 0.6
    alias, pair = _law(name, geometry, e_star, cr), _law("+".join(C.ALIASES[name]), geometry, e_star, cr)
    assert alias.name == name and pair.name == "+".join(C.ALIASES[name])
    assert (alias.kernel_code, alias.kernel_parameters(), alias.damping_factor, alias.exponent) == \
           (pair.kernel_code, pair.kernel_parameters(), pair.damping_factor, pair.exponent)
    for delta in GRID_DELTA:
        assert alias.normal_force(delta, 0.1, 0.3) == pair.normal_force(delta, 0.1, 0.3)


def test_wang_liu_reads_as_liu_plus_zhiying_qishao():
    assert C.ALIASES["wang-liu"] == ("liu", "zhiying-qishao")
    assert isinstance(C.WangLiu(exuclear.BearingGeometry(9.9e-3, 10e-3, 15e-3), 1e11, 0.5), C.ContactLaw)
    assert C.WangLiu.name == "wang-liu" and C.DEFAULT_LAW == "wang-liu"


# -- the kernel contract -----------------------------------------------------------------------
def test_kernel_codes_are_distinct_and_parameters_fit_the_layout(geometry, e_star):
    codes = [cls.kernel_code for cls in C.STIFFNESS_MODELS.values()]
    assert len(set(codes)) == len(codes)
    assert C.Liu.kernel_code == 1 and C.PointContact.kernel_code == 0
    for name in C.STIFFNESS_MODELS:
        assert 1 <= len(C.stiffness_model(name, geometry, e_star).kernel_parameters()) <= 6


@pytest.mark.parametrize("name", ["hertz", "pereira", "liu"])
def test_kernel_parameters_reproduce_the_explicit_formulas(name, geometry, e_star):
    # the formulas the compiled kernel will transcribe, written from the parameters alone;
    # equality: the same operations in the same order
    m = C.stiffness_model(name, geometry, e_star)
    p = m.kernel_parameters()
    for delta in GRID_DELTA:
        if name == "liu":
            expected = p[0] * math.sqrt(1.0 / (2.0 * (p[1] + delta))) * delta ** p[2]
        else:
            expected = p[0] * delta ** p[1]
        assert m.elastic_force(delta) == expected


IMPLICIT = ["johnson", "radzimovsky", "esdu-78035", "dubowsky-freudenstein"]


@pytest.mark.parametrize("name", IMPLICIT)
def test_implicit_models_solve_their_defining_equation(name, geometry, e_star):
    # delta = s (ln(C/s) + beta), s = F / (pi L E*), evaluated forwards from the returned force;
    # 1e-13 relative: the solver's stopping step is 1e-13 and Newton's next correction is far smaller
    m = C.stiffness_model(name, geometry, e_star)
    ks, c, beta, rtol, max_iter = m.kernel_parameters()
    assert ks == math.pi * geometry.length * e_star and (rtol, max_iter) == (C.IMPLICIT_RTOL, C.IMPLICIT_MAX_ITER)
    for delta in (1e-12, 1e-9, 1e-7, 1e-6, 1e-5, 0.3 * m.max_penetration, 0.999 * m.max_penetration):
        s = m.elastic_force(delta) / ks
        assert s * (math.log(c / s) + beta) == pytest.approx(delta, rel=1e-13)
    assert math.isnan(m.elastic_force(1.001 * m.max_penetration))  # beyond its largest penetration: no force


@pytest.mark.parametrize("name", IMPLICIT)
def test_implicit_models_have_a_force_up_to_the_last_float_below_their_peak(name, geometry, e_star):
    # at the peak ds/d(delta) is infinite (the defining equation's slope ln(C/s) + beta - 1 is 0
    # there); a bisection over (0, c] reaches the last float below it, where Newton's step was a
    # division by zero in the Python kernel: the force there is the peak's, F = pi L E* s_peak
    m = C.stiffness_model(name, geometry, e_star)
    ks, c, beta = m.kernel_parameters()[:3]
    s_peak = c * math.exp(beta - 1.0)
    assert m.elastic_force(math.nextafter(m.max_penetration, 0.0)) == pytest.approx(ks * s_peak, rel=1e-6)


def test_johnson_is_the_two_cylinder_formula_with_the_hertz_half_width(geometry, e_star):
    # Johnson (1985) for the approach of two cylinders, written with both radii and the Hertz
    # half-width b = 2 sqrt(F R* / (pi L E*)), R* = R_J R_B / (R_B - R_J) for the conforming pair;
    # 1e-12: the two forms differ only by rounding in the logarithms
    m = C.stiffness_model("johnson", geometry, e_star)
    r_j, r_b, length = geometry.journal_radius, geometry.bearing_radius, geometry.length
    r_star = r_j * r_b / geometry.clearance
    for delta in (1e-8, 1e-6, 1e-5):
        f = m.elastic_force(delta)
        b = 2.0 * math.sqrt(f * r_star / (math.pi * length * e_star))
        approach = f / (math.pi * length * e_star) * (math.log(4 * r_j / b) + math.log(4 * r_b / b) - 1.0)
        assert approach == pytest.approx(delta, rel=1e-12)
        r = C.stiffness_model("radzimovsky", geometry, e_star).elastic_force(delta)
        b = 2.0 * math.sqrt(r * r_star / (math.pi * length * e_star))
        approach = r / (math.pi * length * e_star) * (2.0 / 3.0 + math.log(4 * r_j / b) + math.log(4 * r_b / b))
        assert approach == pytest.approx(delta, rel=1e-12)


@pytest.mark.parametrize("name", sorted(C.STIFFNESS_MODELS))
def test_stiffness_models_start_at_zero_and_increase(name, geometry, e_star):
    m = C.stiffness_model(name, geometry, e_star)
    assert m.elastic_force(0.0) == 0.0 and m.elastic_force(-1e-6) == 0.0
    # continuity at onset: 1 pm of penetration carries less than a millinewton in every model
    assert 0.0 < m.elastic_force(1e-12) < 1e-3
    forces = [m.elastic_force(d) for d in np.linspace(1e-9, 2e-5, 300)]
    assert np.all(np.diff(forces) > 0.0)
    # the secant stiffness and the exponent describe the same force (the interface of the glue)
    assert m.stiffness(3e-6) * 3e-6**m.exponent == pytest.approx(m.elastic_force(3e-6), rel=1e-14)


def test_pereira_in_the_units_of_the_fit(geometry, e_star):
    # Pereira et al. (2011) write F [N] = (a dR + b) L E* delta^n / dR in mm and MPa; the SI
    # conversion must agree to rounding (1e-12), and the two branches of Y meet at 0.34954 mm
    m = C.stiffness_model("pereira", geometry, e_star)
    y = 1.51 * math.log(100.0) ** -0.151  # dR = 0.1 mm = 100 um
    n = y * 0.1**-0.005
    assert m.exponent == pytest.approx(n, rel=1e-15)
    for delta in (1e-7, 1e-6, 1e-5):
        f_mm = (0.965 * 0.1 + 0.0965) * 15.0 * (e_star * 1e-6) / 0.1 * (delta * 1e3) ** n
        assert m.elastic_force(delta) == pytest.approx(f_mm, rel=1e-12)
    branch = 0.34954
    assert 1.51 * math.log(branch * 1e3) ** -0.151 == pytest.approx(0.0151 * branch + 1.151, abs=1e-4)
    # the fit is close to Johnson's theory where both apply (Pereira et al.'s own finding): 3 %
    johnson = C.stiffness_model("johnson", geometry, e_star)
    assert m.elastic_force(1e-6) == pytest.approx(johnson.elastic_force(1e-6), rel=0.03)


def test_pereira_outside_its_clearance_range_warns_or_refuses(e_star):
    with pytest.warns(C.ValidityWarning, match="fitted for clearances of 0.005 to 10 mm"):
        C.stiffness_model("pereira", exuclear.BearingGeometry(10e-3 - 3e-6, 10e-3, 15e-3), e_star)
    with pytest.raises(ValueError, match="undefined for a clearance of 1 um or less"):
        C.stiffness_model("pereira", exuclear.BearingGeometry(10e-3 - 1e-6, 10e-3, 15e-3), e_star)


# -- damping models ---------------------------------------------------------------------------------
#: D at cr = 0.5 from each source's formula, evaluated by hand.
D_AT_HALF = {
    "lankarani-nikravesh": 3 * 0.75 / 4, "hunt-crossley": 0.75, "flores": 1.6, "gonthier": 1.5, "hu-guo": 1.5,
    "zhiying-qishao": 3 * 0.75 * math.e / 4, "lee-wang": 0.375, "herbert-mcwhannell": 1.0,
}


@pytest.mark.parametrize("name", sorted(D_AT_HALF))
def test_damping_factors_by_hand(name):
    assert C.damping_model(name, 0.5).factor == pytest.approx(D_AT_HALF[name], rel=1e-15)
    assert C.damping_model(name, 1.0).factor == 0.0


def test_carvalho_martins_meets_cr_exactly():
    # the root of (1 + D) / (1 - D cr) = exp(D (1 + cr)); tends to Hunt-Crossley's 3 (1 - cr) / 2
    # in log form; 1e-10 relative because 1 - D cr (1.8e-4 at cr = 0.1) amplifies the rounding of D
    for cr in (0.1, 0.5, 0.9, 0.999):
        d = C.damping_model("carvalho-martins", cr).factor
        assert math.log1p(d) - math.log1p(-d * cr) == pytest.approx(d * (1 + cr), rel=1e-10)
        assert C.restitution_of_damping(d) == pytest.approx(cr, abs=1e-13)  # the inverse solve, to round-off
    assert C.damping_model("carvalho-martins", 0.999).factor == pytest.approx(1.5e-3, rel=2e-3)


def _reference_law(damping, cr, geometry, e_star, stiffness="hertz"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", C.ValidityWarning)
        return C.contact_law(f"{stiffness}+{damping}", geometry, e_star, cr)


DISSIPATIVE = sorted(n for n, cls in C.DAMPING_MODELS.items() if cls.dissipative)


def test_restitution_of_every_damping_model_against_the_one_dof_integration(geometry, e_star):
    # the paper's impact with a power-law stiffness, integrated by solve_ivp (DOP853, rtol
    # 1e-11) until the penetration is 0 again; the exact relation D (1 + e) = ln(1 + D) -
    # ln(1 - D e) must hold to the integration's accuracy. Measured largest deviation:
    # 3.8e-11 (validation/contact_laws.py, all 90 cases); 1e-8 leaves room for other platforms.
    worst = 0.0
    for name in DISSIPATIVE:
        for cr in (0.1, 0.5, 0.9):
            law = _reference_law(name, cr, geometry, e_star)
            e = one_dof_impact(law).restitution
            worst = max(worst, abs(e - C.restitution_of_damping(law.damping_factor)))
    assert worst < 1e-8


@pytest.mark.parametrize("stiffness", ["liu", "johnson", "pereira"])
def test_restitution_does_not_depend_on_the_stiffness(stiffness, geometry, e_star):
    # the first integral m v dv / (1 + D v / v0) = -F_e dx closes for any F_e: the same e
    # for non-power-law stiffness (Liu, Johnson) and other exponents (Pereira); 1e-8 as above
    for name, cr in (("flores", 0.3), ("carvalho-martins", 0.5), ("lankarani-nikravesh", 0.8)):
        law = _reference_law(name, cr, geometry, e_star, stiffness)
        assert one_dof_impact(law).restitution == pytest.approx(C.restitution_of_damping(law.damping_factor),
                                                                abs=1e-8)


@pytest.mark.parametrize("cr, departure", [(0.3, 0.098), (0.5, 0.145), (0.9, 0.269)])
def test_paper_departure_velocities_of_the_wang_liu_law(cr, departure, geometry, e_star):
    # the paper's section 5.1 (docs/physics.md section 6.1), published to three decimals: +-0.0005 m/s
    impact = one_dof_impact(_law("wang-liu", geometry, e_star, cr))
    assert impact.restitution * 0.3 == pytest.approx(departure, abs=5e-4)


def test_hu_guo_form_is_the_one_that_meets_cr():
    # the chosen 3 (1 - cr) / (2 cr) stays within 0.035 of cr for cr >= 0.1 (exact relation);
    # the half form quoted elsewhere misses cr = 0.5 by 0.16
    for cr in np.arange(0.1, 1.0, 0.1):
        d = C.damping_model("hu-guo", float(cr)).factor
        assert abs(C.restitution_of_damping(d) - cr) < 0.035
    assert C.restitution_of_damping(3 * 0.5 / (4 * 0.5)) - 0.5 > 0.15


def test_restitution_of_damping_limits():
    assert C.restitution_of_damping(0.0) == 1.0
    # small D: e = 1 - (2/3) D + O(D^2) (series of the exact relation), so 1e-6 -> 1 - 6.67e-7;
    # 1e-9: the relation's slope in e is -D^2, so rounding (2e-16 D) moves the root by ~2e-16 / D
    assert C.restitution_of_damping(1e-6) == pytest.approx(1 - 2e-6 / 3, abs=1e-9)
    with pytest.raises(ValueError, match="`D` must be non-negative"):
        C.restitution_of_damping(-1.0)


def test_zhiying_qishao_warns_below_its_range():
    with pytest.warns(C.ValidityWarning, match="established for cr >= 0.3"):
        C.damping_model("zhiying-qishao", 0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        C.damping_model("zhiying-qishao", 0.3)


# -- names and bad input ------------------------------------------------------------------------
def test_unknown_names_list_the_known_ones(geometry, e_star):
    with pytest.raises(ValueError, match="unknown `stiffness` 'persson'; known: dubowsky-freudenstein, esdu-78035"):
        C.contact_law("persson+flores", geometry, e_star, 0.5)
    with pytest.raises(ValueError, match="unknown `damping` 'kelvin'; known: carvalho-martins, flores"):
        C.contact_law("hertz+kelvin", geometry, e_star, 0.5)
    with pytest.raises(ValueError, match="unknown `law` 'hertzian'; known: flores, hertz, hunt-crossley"):
        C.contact_law("hertzian", geometry, e_star, 0.5)


def test_elastic_pairing_refuses_dissipation_and_says_why(geometry, e_star):
    with pytest.raises(ValueError, match="damping 'none' dissipates no energy"):
        C.contact_law("johnson+none", geometry, e_star, 0.8)
    with pytest.raises(ValueError, match="`cr` must be 1 for the elastic Hertz law, got 0.9"):
        C.contact_law("hertz", geometry, e_star, 0.9)
    assert C.contact_law("johnson+none", geometry, e_star).damping_factor == 0.0


def test_fixed_exponents_are_not_overridden(geometry, e_star):
    with pytest.raises(ValueError, match="`exponent` is fixed by the 'pereira' stiffness model"):
        C.contact_law("pereira+flores", geometry, e_star, 0.5, exponent=1.5)
    assert C.contact_law("liu+flores", geometry, e_star, 0.5, exponent=1.2).exponent == 1.2


def test_make_joint_takes_a_pair():
    dims = dict(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3)
    joint = exuclear.make_joint(**dims, stiffness="pereira", damping="gonthier", cr=0.7)
    assert joint.law.name == "pereira+gonthier" and joint.law.cr == 0.7
    assert exuclear.make_joint(**dims, stiffness="johnson", cr=0.7).law.name == "johnson+zhiying-qishao"
    assert exuclear.make_joint(**dims, stiffness="johnson", damping="none").law.cr == 1.0
    assert exuclear.make_joint(**dims, cr=0.5).law.name == "wang-liu"
    with pytest.raises(ValueError, match="give either `law` or `stiffness`/`damping`"):
        exuclear.make_joint(**dims, law="flores", damping="flores", cr=0.5)


def test_command_line_options_resolve_law_and_cr():
    # --law hertz alone takes cr = 1 (it used to fail on the default cr 0.9)
    assert C.law_and_restitution("hertz") == ("hertz", 1.0)
    assert C.law_and_restitution(stiffness="johnson", damping="none") == ("johnson+none", 1.0)
    assert C.law_and_restitution() == ("wang-liu", 0.9)
    assert C.law_and_restitution(stiffness="pereira", damping="gonthier", cr=0.4) == ("pereira+gonthier", 0.4)
    with pytest.raises(ValueError, match="unknown `law` 'foo'"):
        C.law_and_restitution("foo")


@pytest.mark.parametrize("stiffness", sorted(C.STIFFNESS_MODELS))
@pytest.mark.parametrize("damping", DISSIPATIVE)
def test_every_pair_keeps_the_law_properties(stiffness, damping, geometry, e_star):
    # docs/physics.md eq. (9) for every pairing: no force without penetration, never negative (no adhesion),
    # v0 below v_min acts as v_min, and a NaN rate is not turned into a silent zero
    law = _reference_law(damping, 0.4, geometry, e_star, stiffness)
    rng = np.random.default_rng(7)
    for delta, rate, v0 in zip(rng.uniform(-1e-5, 2e-5, 60), rng.uniform(-5, 5, 60), rng.uniform(0, 1, 60),
                               strict=True):
        f = law.normal_force(delta, rate, v0)
        assert f >= 0.0 and (f == 0.0 if delta <= 0.0 else True)
    assert law.normal_force(1e-6, 1e-3, 0.0) == law.normal_force(1e-6, 1e-3, law.v_min)
    assert math.isnan(law.normal_force(1e-6, math.nan, 0.3))
