"""exuclear.nonlinear without Exudyn: Poincare sections of signals with known sections, the
0-1 test and the verdict on the logistic map, whose windows are textbook (May, Nature 261
(1976) 459; the period-doubling values of r from Feigenbaum's cascade: period 2 for
3 < r < 1 + sqrt(6) = 3.449, period 4 up to 3.544, chaos at r = 4)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from exuclear.nonlinear import classify, crossings, period_of, stroboscopic, test01
from exuclear.nonlinear.chaos import MIN_SAMPLES


def logistic(r: float, n: int = 1000, skip: int = 1000, x: float = 0.3) -> np.ndarray:
    """``n`` iterates of ``x -> r x (1 - x)`` after ``skip`` (the transient: at r = 3.5 the
    orbit reaches period 4 to 1e-12 within a few hundred iterates)."""
    out = np.empty(n)
    for i in range(skip + n):
        x = r * x * (1.0 - x)
        if i >= skip:
            out[i - skip] = x
    return out


@pytest.mark.parametrize(("r", "kind"), [(3.2, "period-2"), (3.5, "period-4"), (3.83, "period-3"), (4.0, "chaotic"),
                                         (3.7, "chaotic")])
def test_logistic_map_verdicts(r, kind):
    # 3.83 lies in the period-3 window (3.8284 to 3.8415); 3.7 is chaotic (its Lyapunov exponent is +0.36)
    verdict = classify(logistic(r))
    assert verdict.kind == kind
    assert str(verdict).startswith(kind)


@pytest.mark.parametrize(("r", "chaotic"), [(3.2, False), (3.5, False), (4.0, True)])
def test_01_test_on_the_logistic_map(r, chaotic):
    # K tends to 0 (regular) or 1 (chaos) as N grows; Gottwald and Melbourne (2009) report
    # |K - limit| below 0.1 from N = 1000 on for the logistic map: the bound used here
    k = test01(logistic(r)).K
    assert (abs(k - 1.0) if chaotic else abs(k)) < 0.1, k


def test_01_test_quasi_periodic_is_regular():
    # an irrational rotation (golden mean) is quasi-periodic: its translation variables stay
    # bounded, K -> 0 (Gottwald and Melbourne 2009, fig. 2); 0.1 as above
    x = np.cos(2.0 * math.pi * np.arange(1000) * (math.sqrt(5.0) - 1.0) / 2.0)
    assert abs(test01(x).K) < 0.1
    assert classify(x).kind == "quasi-periodic"


def test_01_test_guards():
    constant = test01(np.full(200, 0.37))
    assert constant.K == 0.0 and "constant" in constant.note
    with pytest.raises(ValueError, match=f"at least {MIN_SAMPLES}"):
        test01(np.arange(MIN_SAMPLES - 1, dtype=float))
    with pytest.raises(ValueError, match="1-d"):
        test01(np.zeros((60, 2)))
    with pytest.raises(ValueError, match="finite"):
        test01(np.r_[np.zeros(60), np.nan])


def test_the_same_seed_gives_the_same_k():
    x = logistic(3.9, 300)
    assert test01(x, seed=3).K == test01(x, seed=3).K


def test_period_tolerance_is_tied_to_the_size_not_the_spread():
    # a period-1 response with round-off noise of 1e-9: spread-relative tolerances call it
    # aperiodic (shared/research); a tolerance of 1e-3 of its size calls it period 1
    x = 0.8 + 1e-9 * np.random.default_rng(1).standard_normal(100)
    assert period_of(x) == 1
    assert classify(x).kind == "period-1"


def test_short_aperiodic_series_is_undecided_without_an_exponent():
    x = logistic(4.0, 20)
    assert classify(x).kind == "aperiodic"
    assert classify(x, exponent=0.5).kind == "chaotic"  # the exponent decides
    assert classify(x, exponent=-0.1).kind == "quasi-periodic"


def test_exponent_overrules_k_and_says_so():
    verdict = classify(logistic(4.0), exponent=-0.2)
    assert verdict.kind == "quasi-periodic" and "exponent decides" in verdict.note


def test_classify_checks_its_input():
    with pytest.raises(ValueError, match="max_period"):
        classify(logistic(3.2), max_period=17)
    with pytest.raises(ValueError, match="rtol"):
        classify(logistic(3.2), rtol=-1.0)
    with pytest.raises(ValueError, match="shape"):
        classify(np.zeros((2, 2, 2)))


def test_stroboscopic_samples_at_the_section_times():
    # x = sin(w t + 0.3) recorded at uneven instants (steps 1e-3 to 5e-3 of a period 1):
    # once per period it is sin(0.3) at phase 0 and sin(0.3 + w 0.25) at phase 0.25; the
    # modified Akima interpolant's slopes are estimated from the neighbours, so it errs by
    # about (w h)^3 = 3.1e-5 at the largest step h = 5e-3 on uneven steps: bound 5e-5
    rng = np.random.default_rng(0)
    t = np.cumsum(rng.uniform(1e-3, 5e-3, 4000))
    w = 2.0 * math.pi
    x = np.column_stack([np.sin(w * t + 0.3), np.cos(w * t + 0.3)])
    t_k, x_k = stroboscopic(t, x, 1.0)
    assert np.allclose(t_k, np.arange(math.ceil(t[0]), math.floor(t[-1]) + 1))
    assert np.max(np.abs(x_k - [math.sin(0.3), math.cos(0.3)])) < 5e-5
    _, x_q = stroboscopic(t, x[:, 0], 1.0, phase=0.25)
    assert np.max(np.abs(x_q - math.sin(0.3 + w * 0.25))) < 5e-5
    _, x_lin = stroboscopic(t, x[:, 0], 1.0, interpolation="linear")
    # linear: h^2 w^2 / 8 ~ 1.2e-4 at most
    assert np.max(np.abs(x_lin - math.sin(0.3))) < 1.3e-4


def test_stroboscopic_checks_its_input():
    with pytest.raises(ValueError, match="period"):
        stroboscopic([0.0, 1.0], [0.0, 1.0], 0.0)
    with pytest.raises(ValueError, match="decrease"):
        stroboscopic([0.0, 1.0, 0.5], [0.0, 1.0, 2.0], 0.1)
    with pytest.raises(ValueError, match="one row per time"):
        stroboscopic([0.0, 1.0], [0.0, 1.0, 2.0], 0.1)
    with pytest.raises(ValueError, match="interpolation"):
        stroboscopic([0.0, 0.5, 1.0], [0.0, 1.0, 2.0], 0.1, interpolation="spline")


def test_crossings_find_the_angle_by_root_search():
    # a crank turning unevenly, phi = w t + 0.2 sin(w t), recorded every 2e-3 s and wrapped
    # to (-pi, pi]; it crosses 1.0 + 2 pi k where w t + 0.2 sin(w t) = 1.0 + 2 pi k, and there
    # x = t; Brent's method on the cubic interpolant finds it within O(h^3 phi''') ~ 1e-7
    from scipy.optimize import brentq

    w = 3.0
    t = np.arange(0.0, 10.0, 2e-3)
    phi = w * t + 0.2 * np.sin(w * t)
    wrapped = np.angle(np.exp(1j * phi))
    t_k, x_k = crossings(t, wrapped, t, at=1.0)
    exact = [brentq(lambda s, k=k: w * s + 0.2 * math.sin(w * s) - 1.0 - 2.0 * math.pi * k, 0.0, 12.0)
             for k in range(len(t_k))]
    assert len(t_k) == math.floor((phi[-1] - 1.0) / (2.0 * math.pi)) + 1
    assert np.max(np.abs(t_k - exact)) < 1e-7
    assert np.max(np.abs(x_k - t_k)) < 1e-7
    assert crossings(t, wrapped, t, at=1.0, direction=-1)[0].size == 0  # it never turns back
