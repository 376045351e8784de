"""validation/cost/spectral_radius.py: it compares only models whose solver has a spectral radius,
the radius it sets reaches the solver, and its inputs are checked."""
from __future__ import annotations

import numpy as np
import pytest

from validation.cost import spectral_radius as sr
from validation.exudyn_examples._common import REGISTRY, load_models

load_models()


def final_coordinates(name: str, rho: float) -> np.ndarray:
    model = REGISTRY[name](False, None)
    sr.solve(model, rho)
    return np.asarray(model.mbs.systemData.GetODE2Coordinates())


def test_the_radius_changes_a_generalized_alpha_run():
    # the beam pendulum (generalized-alpha proper): its unresolved bending modes are damped
    # per step by about the spectral radius, so the end state moves
    assert sr.generalized_alpha(REGISTRY["beam_pendulum_2d"](False, None))
    assert not np.allclose(final_coordinates("beam_pendulum_2d", 0.9), final_coordinates("beam_pendulum_2d", 0.5),
                           rtol=0.0, atol=1e-9)


def test_a_model_refused_for_want_of_a_spectral_radius_has_none():
    # the rigid-body tutorial runs the trapezoidal rule (Newmark): the radius changes nothing,
    # so the script refuses it rather than print a comparison of identical runs
    model = REGISTRY["rigid_body_tutorial3"](False, None)
    assert not sr.generalized_alpha(model)
    np.testing.assert_array_equal(final_coordinates("rigid_body_tutorial3", 0.9),
                                  final_coordinates("rigid_body_tutorial3", 0.5))
    with pytest.raises(SystemExit) as stop:
        sr.main(["--models", "rigid_body_tutorial3"])
    assert stop.value.code == 2


@pytest.mark.parametrize("argv", [["--radii", "1.5"], ["--radii", ""], ["--radii", "x"], ["--factor", "1"],
                                  ["--models", "no_such_model"], ["--restitutions", "0"]])
def test_bad_arguments_are_refused(argv):
    with pytest.raises(SystemExit) as stop:
        sr.main(argv)
    assert stop.value.code == 2
