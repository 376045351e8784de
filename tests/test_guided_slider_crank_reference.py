"""The SciPy reference of the slider-crank with a translational clearance joint
(validation/reference/guided_slider_crank.py) on its own evidence: the paper's mass
matrix, the guide's geometry at the first contact, and energy kept by elastic corners."""
from __future__ import annotations

import math

import numpy as np
import pytest

from validation.reference import guided_slider_crank as ref


def test_mass_matrix_is_the_papers_closed_form():
    """Flores, Leine, Glocker (2010) eqs. (90)-(94): M11 = J1 + (m1/4 + m2 + m3) l1^2,
    M12 = (m2/2 + m3) l1 l2 cos(theta2 - theta1), M22 = J2 + (m2/4 + m3) l2^2, M33 = J3.
    The reference builds M from the centres' Jacobians instead; the two agree to round-off
    (1e-15 relative: a few operations on numbers of one magnitude)."""
    p = ref.GuidedSliderCrank.benchmark()
    m = ref._model(p)
    rng = np.random.default_rng(1)
    for q in rng.uniform(-math.pi, math.pi, size=(5, 3)):
        M = ref.mass_matrix(m, q)
        M11 = p.crank_inertia + (p.crank_mass / 4 + p.rod_mass + p.slider_mass) * p.crank_length ** 2
        M12 = (p.rod_mass / 2 + p.slider_mass) * p.crank_length * p.rod_length * math.cos(q[1] - q[0])
        M22 = p.rod_inertia + (p.rod_mass / 4 + p.slider_mass) * p.rod_length ** 2
        paper = np.array([[M11, M12, 0.0], [M12, M22, 0.0], [0.0, 0.0, p.slider_inertia]])
        np.testing.assert_allclose(M, paper, rtol=1e-15, atol=1e-15 * M11)


def test_first_contact_is_the_upper_corners_at_one_clearance():
    """Before any contact nothing turns the slider (the rod pulls at its centre): its angle
    stays 0, so the first contact is both upper corners at once when the centre has risen by
    the clearance (within the event's round-off, 1e-12 m)."""
    p = ref.GuidedSliderCrank.benchmark()
    result = ref.simulate(p, 0.004, output_step=1e-4)
    t_first, pair, v0 = result.impacts[0]
    assert ref.PAIRS[pair][1] == 1 and v0 > 0.0
    assert {ref.PAIRS[k][0] for t, k, _ in result.impacts if t == t_first} == {0, 1}
    before = result.time < t_first
    assert np.all(result.q[before, 2] == 0.0)
    th1, th2 = ref.simulate(p, t_first, output_step=t_first).q[-1, :2]
    y = p.crank_length * math.sin(th1) + p.rod_length * math.sin(th2)
    assert y == pytest.approx(p.clearance, abs=1e-12)


def test_elastic_corners_keep_the_energy_over_two_crank_turns():
    """Undamped corners without friction dissipate nothing: kinetic, gravitational and the
    corners' elastic energy add up to the start's over the benchmark's two crank turns, to
    1e-7 relative (DOP853 at rtol 1e-10 over some ten impacts, each integrated through)."""
    p = ref.GuidedSliderCrank.benchmark(damping="none", cr=1.0, friction="none")
    result = ref.simulate(p, 0.15, output_step=1e-4)
    assert result.success and len(result.impacts) > 2
    assert result.q[-1, 0] > 4 * math.pi  # two crank turns
    drift = np.abs(result.energy - result.energy[0]).max() / result.energy[0]
    assert drift < 1e-7
