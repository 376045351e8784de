"""Shared fixtures: the paper's journal-bearing geometry and steel-steel modulus, and the
check that the compiled and the Python kernel ran a model alike."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
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


def _kernels_agree(compiled: tuple[Any, Any], python: tuple[Any, Any]) -> None:
    """``(mbs, joint)`` of one model run with the compiled and with the Python kernel: the
    same outputs and the same final coordinates.  The same formulas in the same order, no
    fused multiply-add (setup.py): round-off only, hence rtol 1e-12."""
    (m_c, j_c), (m_p, j_p) = compiled, python
    out_c, out_p = j_c.outputs(), j_p.outputs()
    assert set(out_c) == set(out_p)
    for key in out_c:
        np.testing.assert_allclose(out_c[key], out_p[key], rtol=1e-12, atol=1e-15, err_msg=key)
    np.testing.assert_allclose(m_c.systemData.GetODE2Coordinates(), m_p.systemData.GetODE2Coordinates(),
                               rtol=1e-12, atol=1e-15)


@pytest.fixture
def kernels_agree() -> Callable[[tuple[Any, Any], tuple[Any, Any]], None]:
    return _kernels_agree
