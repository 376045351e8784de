"""exuclear.nonlinear on the driven damped pendulum built in Exudyn
(exuclear.models.driven_pendulum), against its textbook windows (Baker and Gollub,
Chaotic Dynamics, 2nd ed. (1996), ch. 3: q = 2, omega_D = 2/3; g = 0.9 periodic,
1.07 period two, 1.15 chaotic) and against an independent SciPy integration of its
equation and of its tangent (variational) equation, written here from the equation of
motion, not from the model's code."""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from exuclear.models import driven_pendulum as pendulum
from exuclear.nonlinear import Driven, classify, exponent_of, lyapunov, orbit_diagram, run_sections

Q, W = 2.0, 2.0 / 3.0
PERIOD = 2.0 * math.pi / W
#: Periods left out: the slowest transient here (g = 1.07) decays as exp(-0.04 t), to 2e-8
#: of its start over 100 periods (942 time units: its exponent is -0.04, measured below).
TRANSIENT = 100


@functools.lru_cache
def reference(g: float, periods: int = 200, transient: int = TRANSIENT) -> tuple[float, np.ndarray]:
    """SciPy DOP853 at rtol 1e-12 of theta'' + theta'/q + sin(theta) = g cos(W t) with its
    tangent equation dx'' = -cos(theta) dx - dx'/q, the tangent renormalised every period
    (Benettin); returns the exponent over the last ``periods`` [1/s] and (theta, omega) at
    the end of each of them."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        theta, omega, a, b = y
        return [omega, g * math.cos(W * t) - math.sin(theta) - omega / Q, b, -math.cos(theta) * a - b / Q]

    y = np.array([0.0, 0.0, 1.0, 0.0])
    logs, sections = [], []
    for k in range(transient + periods):
        y = solve_ivp(rhs, [k * PERIOD, (k + 1) * PERIOD], y, method="DOP853", rtol=1e-12, atol=1e-12).y[:, -1].copy()
        d = math.hypot(y[2], y[3])
        logs.append(math.log(d))
        y[2:] /= d
        sections.append(y[:2].copy())
    return float(np.sum(logs[transient:])) / (periods * PERIOD), np.array(sections[transient:])


@pytest.fixture(scope="module")
def runs():
    """The pendulum at the three amplitudes, two copies each (exponent and sections), 200
    sampled periods."""
    return {g: run_sections(pendulum.driven({"forcing": g}), periods=200, transient_periods=TRANSIENT,
                            perturbation=1e-6) for g in (0.9, 1.07, 1.15)}


@pytest.mark.parametrize(("g", "kind"), [(0.9, "period-1"), (1.07, "period-2"), (1.15, "chaotic")])
def test_textbook_windows(runs, g, kind):
    run = runs[g]
    assert run.success, run.message
    samples = np.column_stack(list(run.samples.values()))
    assert classify(samples).kind == kind
    # the independent integration sees the same window (the textbook's values hold)
    _, sections = reference(g)
    ref = np.column_stack([sections[:, 1], np.cos(sections[:, 0]), np.sin(sections[:, 0])])
    assert classify(ref).kind == kind


@pytest.mark.parametrize("g", [0.9, 1.07])
def test_sections_agree_with_scipy_on_periodic_windows(runs, g):
    # a periodic response is stable, so both integrations sit on the same orbit: the section
    # samples (Hermite-interpolated between DOPRI5 steps at rtol 1e-9) agree with DOP853 at
    # rtol 1e-12 to the DOPRI5 error, 4e-8 measured; bound 1e-6 (the period test's 1e-3 is far)
    _, sections = reference(g)
    run = runs[g]
    assert np.max(np.abs(run.samples["omega"] - sections[:, 1])) < 1e-6
    assert np.max(np.abs(run.samples["cos"] - np.cos(sections[:, 0]))) < 1e-6


@pytest.mark.parametrize("g", [0.9, 1.07])
def test_exponent_of_periodic_windows_against_the_tangent_equation(runs, g):
    # over 200 periods the finite-time estimate of a periodic orbit still carries the
    # start of the perturbation's direction, O(1 / periods): 6e-4 measured; bound 2e-3.
    # Both negative: a driven periodic response contracts (the drive is no neutral direction)
    exponent = exponent_of(runs[g], TRANSIENT)[0]
    expected, _ = reference(g)
    assert expected < 0.0 and exponent < 0.0
    assert abs(exponent - expected) < 2e-3


def test_exponent_of_chaos_against_the_tangent_equation(runs):
    # the two chaotic trajectories part within the transient (the integrators differ by
    # 1e-8), so the two finite-time averages over 200 periods sample the attractor
    # independently: they differ by 0.01 (9 %) here, as the reference itself moves by 0.007
    # between 60 and 200 periods; bound 0.025.  Both clearly positive.
    exponent = exponent_of(runs[1.15], TRANSIENT)[0]
    expected, _ = reference(1.15)
    assert expected > 0.05 and exponent > 0.05
    assert abs(exponent - expected) < 0.025


def test_lyapunov_matches_run_sections():
    result = lyapunov(pendulum.driven({"forcing": 0.9}).build, pendulum.SETTINGS, period=PERIOD, periods=20,
                      transient_periods=10)
    run = run_sections(pendulum.driven({"forcing": 0.9}), periods=20, transient_periods=10, perturbation=1e-6)
    assert result.exponent == exponent_of(run, 10)[0]  # the same run, deterministic
    assert result.running.shape == (20,) and result.running[-1] == result.exponent


def test_lyapunov_refuses_models_it_cannot_perturb():
    from exudyn.itemInterface import MarkerNodeCoordinate, NodePointGround, ObjectConnectorCoordinate

    def constrained(mbs):
        node = pendulum.build(mbs)
        ground = mbs.AddNode(NodePointGround())
        markers = [mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n, coordinate=0)) for n in (ground, node)]
        mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=markers))
        return node

    settings = pendulum.SETTINGS
    with pytest.raises(ValueError, match="constraints"):
        lyapunov(constrained, settings, period=PERIOD, periods=1)
    calls = []

    def unequal(mbs):
        calls.append(1)
        return pendulum.build(mbs, theta0=0.1 * len(calls))

    with pytest.raises(ValueError, match="same model"):
        lyapunov(unequal, settings, period=PERIOD, periods=1)


def test_driven_checks_its_input():
    with pytest.raises(ValueError, match="period"):
        Driven(pendulum.build, pendulum.SETTINGS, 0.0)
    with pytest.raises(ValueError, match="SolverSettings"):
        Driven(pendulum.build, {"method": "dopri5"}, 1.0)
    with pytest.raises(ValueError, match="unknown parameters"):
        pendulum.driven({"gain": 1.0})
    with pytest.raises(ValueError, match="periods"):
        run_sections(pendulum.driven({}), periods=0)


def test_orbit_diagram_table_resumes_and_sweeps(tmp_path):
    out = tmp_path / "pendulum.csv"
    table = orbit_diagram("exuclear.models.driven_pendulum", "forcing", [0.9, 1.07], periods=20,
                          transient_periods=TRANSIENT, workers=1, progress=False, out=out)
    assert list(table["kind"]) == ["period-1", "period-2"]
    assert len(table["omega"].iloc[0]) == 20 and np.isnan(table["exponent"]).all()
    again = orbit_diagram("exuclear.models.driven_pendulum", "forcing", [0.9, 1.07], periods=20,
                          transient_periods=TRANSIENT, workers=1, progress=False, out=out)
    assert again.attrs["resumed"] == 2 and again.attrs["ran"] == 0
    # a sweep up and down, each value from the last one's end: the period-1 and period-2
    # attractors are the only ones at these amplitudes from these starts, so the down run
    # lands where the up run did
    sweep = orbit_diagram("exuclear.models.driven_pendulum", "forcing", [0.9, 1.07], periods=20,
                          transient_periods=40, sweep=True, progress=False)
    assert list(sweep["direction"]) == ["up", "up", "down"]
    assert list(sweep["kind"]) == ["period-1", "period-2", "period-1"]
    first, last = np.asarray(sweep["omega"].iloc[0]), np.asarray(sweep["omega"].iloc[2])
    assert abs(first[-1] - last[-1]) < 1e-6  # the same stable orbit, within the DOPRI5 error


def test_orbit_diagram_checks_its_input():
    with pytest.raises(ValueError, match="unknown scene"):
        orbit_diagram("no-such-scene", "x", [1.0], periods=1)
    with pytest.raises(ValueError, match="settings"):
        orbit_diagram(pendulum.build, "forcing", [1.0], periods=1)
    with pytest.raises(ValueError, match="empty"):
        orbit_diagram("exuclear.models.driven_pendulum", "forcing", [], periods=1)
    with pytest.raises(ValueError, match="unknown parameters"):
        orbit_diagram("exuclear.models.driven_pendulum", "gain", [1.0], periods=1)
    with pytest.raises(ValueError, match="one after the other"):
        orbit_diagram("exuclear.models.driven_pendulum", "forcing", [1.0], periods=1, sweep=True, workers=2)


def test_orbit_diagram_of_a_users_build():
    table = orbit_diagram(pendulum.build, "forcing", [1.07], periods=20, transient_periods=TRANSIENT,
                          settings=pendulum.SETTINGS, period=PERIOD, observe=pendulum.observe, workers=1,
                          progress=False)
    assert table["kind"].iloc[0] == "period-2"


def test_command_line_writes_table_and_figures(tmp_path, capsys):
    from exuclear.nonlinear.cli import main

    out = tmp_path / "pendulum.csv"
    status = main(["exuclear.models.driven_pendulum", "--parameter", "forcing", "--values", "0.9,1.07", "--periods",
                   "20", "--transient", str(TRANSIENT), "--exponent", "--workers", "1", "--no-progress", "--out",
                   str(out)])
    printed = capsys.readouterr().out
    assert status == 0, printed
    assert "forcing = 0.9: period-1" in printed and "forcing = 1.07: period-2" in printed
    assert out.exists() and (tmp_path / "pendulum_omega.png").exists() and (tmp_path / "pendulum_exponent.png").exists()
    assert main(["exuclear.models.driven_pendulum", "--parameter", "forcing", "--values", "1.0", "--periods", "2",
                 "--set", "q", "--out", str(tmp_path / "bad.csv")]) == 2
    assert "`--set` is NAME=VALUE" in capsys.readouterr().err


@pytest.mark.slow
def test_orbit_diagram_on_a_dask_cluster_equals_the_serial_one():
    # the runs are deterministic: a row depends on its parameters, not on where it ran
    options = dict(periods=20, transient_periods=20, exponent=True, progress=False)
    serial = orbit_diagram("exuclear.models.driven_pendulum", "forcing", [0.9, 1.15], workers=1, **options)
    cluster = orbit_diagram("exuclear.models.driven_pendulum", "forcing", [0.9, 1.15], workers=2, scheduler="local",
                            **options)
    for column in ("omega", "cos", "kind", "exponent", "steps"):
        assert list(cluster[column]) == list(serial[column]), column
