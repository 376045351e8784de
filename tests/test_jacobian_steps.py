"""validation/cost/jacobian_steps.py: its former rule leaves the run-start setting alone, and its inputs are checked."""
from __future__ import annotations

import argparse

import pytest

from exuclear.engine import handle
from validation.cost import jacobian_steps as js


def test_the_former_rule_ignores_the_joints_asks_and_is_undone():
    library = handle._RunStart.jacobian_per_step
    with js.rule("whole run"):
        assert handle._RunStart.jacobian_per_step is not library
        assert handle._RunStart.jacobian_per_step(object(), True) is None  # touches no solver
    assert handle._RunStart.jacobian_per_step is library
    with js.rule("with the steps"):
        assert handle._RunStart.jacobian_per_step is library


def test_restitutions_are_checked():
    assert js.parse_restitutions("0.89,0.9") == [0.89, 0.9]
    for bad in ("", "0.9,1.5", "0"):
        with pytest.raises(argparse.ArgumentTypeError):
            js.parse_restitutions(bad)
