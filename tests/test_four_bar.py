"""models/four_bar: the ideal configuration it starts from, and its parameter checks."""
from __future__ import annotations

import math

import numpy as np
import pytest

from exuclear.models.four_bar import FourBarParams, ideal_configuration

CASE = FourBarParams.crank_rocker()


@pytest.mark.parametrize("theta", [0.0, 1.0, 2.5, 4.0, 5.5])
def test_ideal_configuration_closes_the_loop_and_its_rates_are_the_derivatives(theta):
    a, b, c, d = CASE.crank_length, CASE.coupler_length, CASE.rocker_length, CASE.ground_length
    w = CASE.crank_speed
    s = ideal_configuration(CASE, theta, w)
    b_from_a = a * np.array([math.cos(theta), math.sin(theta)]) + b * np.array([math.cos(s["coupler"][0]),
                                                                                 math.sin(s["coupler"][0])])
    b_from_o4 = np.array([d, 0.0]) + c * np.array([math.cos(s["rocker"][0]), math.sin(s["rocker"][0])])
    assert np.abs(b_from_a - b_from_o4).max() < 1e-15  # round-off of 0.3 m lengths
    assert b_from_a[1] > 0.0  # the open branch: B above the ground link
    h = 1e-6  # central differences: error ~ h^2 * (third derivative) ~ 1e-11 rad/s
    up, down = ideal_configuration(CASE, theta + h, w), ideal_configuration(CASE, theta - h, w)
    for link in ("coupler", "rocker"):
        assert s[link][1] == pytest.approx((up[link][0] - down[link][0]) / (2 * h) * w, abs=1e-7)


@pytest.mark.parametrize("changes, message", [
    ({"crank_length": 0.26}, "crank-rocker"),                  # crank no longer the shortest link
    ({"ground_length": 0.45}, "crank-rocker"),                 # 0.05 + 0.45 > 0.25 + 0.20
    ({"crank_speed": 0.0}, "`crank_speed` must be non-zero"),
    ({"clearance": 0.01}, "`clearance` must be smaller"),
])
def test_bad_parameters_are_refused(changes, message):
    with pytest.raises(ValueError, match=message):
        FourBarParams.crank_rocker(**changes)
