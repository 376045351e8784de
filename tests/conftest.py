"""Shared fixtures: the paper's journal-bearing geometry and steel-steel modulus."""
from __future__ import annotations

import pytest

import exuclear

#: The paper's example 1 (docs/physics.md section 6.1): R_J = 9.9 mm, R_B = 10 mm, L = 15 mm.
PAPER_GEOMETRY = exuclear.BearingGeometry(9.9e-3, 10e-3, 15e-3)


@pytest.fixture
def geometry() -> exuclear.BearingGeometry:
    return PAPER_GEOMETRY


@pytest.fixture
def e_star() -> float:
    return exuclear.composite_modulus("steel", "steel")
