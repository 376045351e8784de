"""validation/cost/newton.py: the counts it prints, on evaluations whose answer is known."""
from __future__ import annotations

from validation.cost import newton as nc


def test_steps_evaluations_and_overshoots_are_counted():
    # two step starts: the first converges from 1000x its start's penetration (an overshoot),
    # the second stays near its start (a Jacobian's perturbations at 1e-9 relative)
    first = [(0.1, d, 0.0, 1.0, 1e-8) for d in (1e-5, 5e-6, 2.5e-6, 1.1e-8)]
    second = [(0.2, 1e-8 * (1.0 + k * 1e-9), 0.0, 1.0, 1e-8) for k in range(3)]
    before = [(0.05, 5e-5, 0.0, 1.0, 1e-8)]  # before the window: not counted
    row, detail = nc.summary("m", before + first + second, start=0.1)
    assert row == ["m", "2", "4 / 4 / 4", "1 (50 %)"]  # median of (4, 3) is 3.5, printed rounded
    assert "costliest step from t = 0.1 s" in detail and "4 evaluations" in detail
    iterates = [line.split() for line in detail.splitlines() if line.startswith("  ")]
    assert [float(i[0]) for i in iterates] == [1e-5, 5e-6, 2.5e-6, 1.1e-8]  # each moved by more than 1 %


def test_an_empty_window_says_so():
    assert nc.summary("m", [(0.05, 1e-6, 0.0, 1.0, 1e-8)], start=0.1) == (["m", "0", "-", "-"], "")
