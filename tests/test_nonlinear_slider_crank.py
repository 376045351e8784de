"""The nonlinear tools on the paper's slider-crank (Wang et al. 2017, example 2: 500 rpm,
c = 0.1 mm, Wang-Liu law cr = 0.9), minimal formulation.  Slow: two copies over 140 crank
turns each.  The numbers come from ``python -m validation.nonlinear verdicts``, which
runs longer and prints them.

With the paper's modified Coulomb friction the journal settles against the bearing wall
within the first turn and stays there: a period-1 response with a negative largest
exponent (a driven mechanism's periodic response contracts), the same at half the step
and half the tolerances.  Without friction (the paper's case) nothing holds the
journal's slide along the wall: it never settles, and its exponent does not fall below
zero by more than the noise of a finite window.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from exuclear.models import slider_crank
from exuclear.nonlinear import classify, exponent_of, run_sections

TRANSIENT, PERIODS = 100, 40


def verdict(values: dict, refine: float = 1.0):
    """The verdict of the slider-crank at ``values``; ``refine``: the largest step and the
    tolerances divided by it (the convergence check)."""
    model = slider_crank.driven(values)
    if refine != 1.0:
        s = model.settings
        model = replace(model, settings=replace(s, step=s.step / refine, rtol=s.rtol / refine,
                                                atol=s.atol / refine))
    run = run_sections(model, periods=PERIODS, transient_periods=TRANSIENT, perturbation=1e-6)
    assert run.success, run.message
    samples = np.column_stack([run.samples[k] for k in ("B.ex", "B.ey", "B.vx", "B.vy")])
    return classify(samples, exponent=exponent_of(run, TRANSIENT)[0]), run


@pytest.mark.slow
@pytest.mark.parametrize("refine", [1.0, 2.0])
def test_friction_settles_into_permanent_contact(refine):
    found, run = verdict({"friction": "paper"}, refine)
    assert found.kind == "period-1", str(found)
    assert found.exponent < 0.0, str(found)
    # on the wall: |e| / c just above 1 (the law's penetration, below 1 % of c)
    ecc = np.hypot(run.samples["B.ex"], run.samples["B.ey"])
    assert np.all((ecc > 1.0) & (ecc < 1.01))


@pytest.mark.slow
def test_without_friction_the_journal_never_settles():
    # nothing damps the slide along the wall: no period up to 16 within 1e-3, and no
    # contraction (the exponent sits near zero or above: -0.33 1/s over turns 100-140,
    # +8.8 1/s over turns 150-200, against -9.8 1/s with friction); -3 1/s divides them
    found, _ = verdict({})
    assert not found.kind.startswith("period"), str(found)
    assert found.exponent > -3.0, str(found)


def test_driven_checks_its_input():
    with pytest.raises(ValueError, match="once"):
        slider_crank.driven({"rpm": 500, "crank_speed": 50.0})
    with pytest.raises(ValueError, match="formulation"):
        slider_crank.driven({"formulation": "redundant"})
    with pytest.raises(ValueError, match="unknown slider-crank parameter"):
        slider_crank.driven({"speed": 1.0})
    model = slider_crank.driven({"rpm": 600})
    assert model.period == pytest.approx(0.1) and model.drive == (slider_crank.CRANK_ANGLE,)


def test_scenes_are_found_by_their_short_names():
    from exuclear.nonlinear.diagram import scene_model

    assert scene_model("slider-crank").module == "exuclear.models.slider_crank"
    with pytest.raises(ValueError, match="no `driven"):
        scene_model("journal-bearing")  # a scene without a driving period
