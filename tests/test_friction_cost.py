"""validation/cost/friction.py: its impact summary on rows whose answer is known, and its settings."""
from __future__ import annotations

import math

import pytest

from exuclear.friction import ModifiedCoulomb
from validation.cost import friction as fc


def test_impacts_are_counted_with_the_median_onset_speed():
    rows = [(0.1, -0.004, 50.0, 3e-4, 4e-7), (0.2, 0.002, 30.0, 3e-4, 2e-7), (0.3, -0.010, 90.0, 3e-4, 9e-7)]
    assert fc.impact_summary(rows) == (3, 0.004)  # |v0| = 4, 2, 10 mm/s
    count, speed = fc.impact_summary([])
    assert count == 0 and math.isnan(speed)


def test_the_flat_law_has_the_papers_regularisation_and_dynamic_coefficient():
    paper, flat = ModifiedCoulomb.paper(), fc.FRICTIONS["Coulomb 0.25 (flat)"]
    assert flat.v_eps == paper.v_s and flat.mu == paper.mu_d
    # flat above its regularisation, where the paper's law falls from mu_s to mu_d
    assert flat(1e-3) == flat(1e-2) == 0.25
    assert paper(1e-3) > paper(1e-2) == pytest.approx(0.25)


def test_a_bad_end_time_is_refused():
    with pytest.raises(SystemExit):
        fc.main(["--end-time", "-1"])
