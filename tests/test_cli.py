"""Command lines of models/ and the API checks of issue 15, section 3.

Each test runs ``main`` in this process (as ``python -m`` would) or the API directly;
a few run a real process where the exact stderr matters.
"""
from __future__ import annotations

import contextlib
import io
import math
import os
import subprocess
import sys
import warnings

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import SensorObject

import exuclear
from exuclear.engine import OUTPUT_COLUMNS
from exuclear.models import figures
from exuclear.models import journal_bearing as jb
from exuclear.models import slider_crank as sc
from exuclear.models.slider_crank import SliderCrankParams

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cli(module, *args: str) -> tuple[int, str, str]:
    """Run ``module.main(args)``; returns (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("always")
        try:
            status = module.main(list(args))
        except SystemExit as stop:  # argparse
            status = stop.code
    return status, out.getvalue(), err.getvalue()


def read_csv(path) -> tuple[list[str], np.ndarray]:
    lines = path.read_text(encoding="utf-8").splitlines()
    head = 1 if lines[0].startswith("#") else 0
    return lines[head].split(","), np.loadtxt(path, delimiter=",", skiprows=head + 1, ndmin=2)


# -- the ideal joint's force at B ------------------------------------------------------
def test_ideal_joint_force_is_the_reaction_exudyn_computes():
    # the closed form of the ideal run's contact_force column against Exudyn's own
    # Lagrange multiplier of the ideal revolute joint at B (the last JointRevolute2D built)
    params = SliderCrankParams.paper(ideal=True, formulation="redundant", revolutions=1.0)
    model = sc.build(params)
    mbs = model.mbs
    revolutes = [i for i in range(mbs.systemData.NumberOfObjects())
                 if mbs.GetObject(i)["objectType"] == "JointRevolute2D"]
    sensor = mbs.AddSensor(SensorObject(objectNumber=revolutes[-1], storeInternal=True, writeToFile=False,
                                        outputVariableType=exu.OutputVariableType.Force))
    mbs.Assemble()
    assert exuclear.simulate(mbs, sc.default_settings(params)).success
    cols = sc.columns(model)
    reaction = np.asarray(mbs.GetSensorStoredData(sensor))
    exudyn_force = np.hypot(reaction[:, 1], reaction[:, 2])
    settled = cols["time"] > 1e-3  # generalized-alpha's accelerations settle within a few steps
    # 1e-3 of the 45 N peak: the accelerations' O(h^2) error, as in test_slider_crank
    assert np.abs(cols["contact_force"] - exudyn_force)[settled].max() < 1e-3 * 45.0
    # 9-45 N over a revolution (issue 15; validation/slider_crank/metrics.py's closed form: 9.08-45.24 N)
    assert 9.0 < cols["contact_force"].min() < 9.2 and 45.1 < cols["contact_force"].max() < 45.4


def test_ideal_csv_writes_the_joint_force(tmp_path):
    path = tmp_path / "ideal.csv"
    status, out, _ = cli(sc, "--ideal", "--revolutions", "1", "--csv", str(path))
    assert status == 0
    names, data = read_csv(path)
    force = data[:, names.index("contact_force")]
    assert 9.0 < force.min() < 9.2 and 45.1 < force.max() < 45.4  # the closed form's range (test above)
    assert "joint force at B 9.1 to 45.2 N" in out


class _SavedFigures:
    """The figures saved during a test, numbered from 1 as pyplot numbers its own (the
    plotting helpers make their figures outside pyplot, so pyplot does not list them)."""

    def __init__(self) -> None:
        self.figures: list = []

    def get_fignums(self) -> list[int]:
        return list(range(1, len(self.figures) + 1))

    def figure(self, number: int):
        return self.figures[number - 1]


@pytest.fixture
def kept_figures(monkeypatch):
    """Figures the plotting helpers save, kept for inspection."""
    from matplotlib.figure import Figure

    saved = _SavedFigures()
    savefig = Figure.savefig

    def keep(figure, *args, **kwargs):
        saved.figures.append(figure)
        return savefig(figure, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", keep)
    return saved


def _spectrum_axes(figures):
    return [ax for n in figures.get_fignums() for ax in figures.figure(n).axes if ax.get_xlabel() == "frequency [Hz]"]


def test_ideal_plot_draws_the_force_and_no_empty_orbit(tmp_path, kept_figures):
    status, out, _ = cli(sc, "--ideal", "--revolutions", "1", "--plot", str(tmp_path))
    assert status == 0
    written = sorted(os.listdir(tmp_path))
    assert "slider_crank_orbit.png" not in written and "slider_crank_contact_force.png" in written
    force_axes = [ax for n in kept_figures.get_fignums() for ax in kept_figures.figure(n).axes
                  if ax.get_ylabel() == "contact force at B [N]"]
    assert min(line.get_ydata().max() for line in force_axes[0].lines) > 45.0  # not a line at 0 N


def test_spectrum_has_a_log_frequency_axis_with_room_below_the_crank_line(tmp_path, kept_figures):
    # the crank line at 500 rpm is 8.33 Hz; on a linear 0-1000 Hz axis it sat at 0.8 % of the width
    crank_hz = 500.0 / 60.0
    status, _, _ = cli(sc, "--revolutions", "2", "--plot", str(tmp_path))
    assert status == 0
    # the sweep figures of validation/ share the axis helper
    t = np.arange(0.0, 0.24, 1e-5)
    cols = {"time": t, "crank_angle": np.degrees(2 * np.pi * crank_hz * t), "slider_a": np.cos(2 * np.pi * crank_hz * t)}
    figures.slider_crank_sweep_figures([("case", cols)], None, 1e-4, str(tmp_path), "sweep",
                                       quantities=("spectrum",))
    axes = _spectrum_axes(kept_figures)
    assert len(axes) == 2
    for ax in axes:
        low, high = ax.get_xlim()
        assert ax.get_xscale() == "log"
        # a decade of the axis holds the crank line well inside: at least 1/4 decade from the left edge
        assert math.log10(crank_hz / low) > 0.25 and high == pytest.approx(1000.0, rel=0.01)


# -- output interval -------------------------------------------------------------------
def test_dt_out_thins_the_slider_crank_csv_but_counts_every_impact(tmp_path):
    fine, coarse = tmp_path / "fine.csv", tmp_path / "coarse.csv"
    status, out_fine, _ = cli(sc, "--revolutions", "0.5", "--csv", str(fine))
    assert status == 0
    status, out_coarse, _ = cli(sc, "--revolutions", "0.5", "--dt-out", "1e-3", "--csv", str(coarse))
    assert status == 0
    _, data = read_csv(coarse)
    # 0.06 s at 1e-3 s: 61 instants (outputs at the first accepted step at or after each)
    assert 55 <= len(data) <= 62 and len(read_csv(fine)[1]) > 10 * len(data)
    # impacts come from the accepted steps: 22 in the start-up at cr 0.9 (README), whatever the interval
    assert "impacts 22" in out_fine and "impacts 22" in out_coarse
    assert "(in the outputs every 0.001 s)" in out_coarse


def test_journal_bearing_dt_out_end_time_and_csv(tmp_path):
    path = tmp_path / "jb.csv"
    status, out, _ = cli(jb, "--dt-out", "1e-6", "--end-time", "2e-4", "--csv", str(path), "--json")
    assert status == 0
    names, data = read_csv(path)
    assert names == ["time", *OUTPUT_COLUMNS]
    assert 195 <= len(data) <= 202  # 2e-4 s every 1e-6 s
    # the paper's departure velocity at cr 0.9: 0.269 m/s (paper, example 1)
    assert '"departure_velocity": 0.26' in out
    # an end time before the journal leaves the wall: the CSV is marked, the message names the option
    status, _, err = cli(jb, "--end-time", "1e-5", "--csv", str(path))
    assert status == 1 and "raise `end_time` (--end-time)" in err
    assert path.read_text(encoding="utf-8").startswith("# INCOMPLETE: the journal had not left the wall")


# -- clockwise cranks ------------------------------------------------------------------
def test_clockwise_ideal_mechanism_follows_the_closed_form():
    # x = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta)) with theta = w t, w < 0
    params = SliderCrankParams.paper(ideal=True, formulation="redundant", crank_speed=-sc.PAPER_CRANK_SPEED,
                                     revolutions=0.5)
    result = sc.run(params)
    assert result.success and params.end_time == pytest.approx(0.06)
    c = result.columns
    r, l, w = params.crank_length, params.rod_length, params.crank_speed
    theta = w * c["time"]
    assert np.abs(np.radians(c["crank_angle"]) - theta).max() < 1e-8  # turning clockwise
    root = np.sqrt(l**2 - (r * np.sin(theta)) ** 2)
    assert np.abs(c["slider_x"] - (r * np.cos(theta) + root)).max() < 1e-9
    v = -r * w * np.sin(theta) * (1.0 + r * np.cos(theta) / root)
    assert np.abs(c["slider_v"] - v).max() < 1e-4 * 2.7  # as the counter-clockwise test in test_slider_crank


def test_clockwise_crank_mirrors_the_counter_clockwise_one():
    # without gravity the clockwise mechanism is the mirror image (y -> -y) of the other:
    # same slider motion and force, mirrored journal path; both start centred and at rest
    # relative to the bearing (initial velocities of the ideal mechanism)
    runs = []
    for sign in (1.0, -1.0):
        params = SliderCrankParams.paper(gravity=0.0, crank_speed=sign * sc.PAPER_CRANK_SPEED, revolutions=0.1)
        runs.append(sc.run(params))
    ccw, cw = (r.columns for r in runs)
    assert all(r.success for r in runs) and runs[0].impacts == runs[1].impacts
    t = ccw["time"]

    def on_ccw(key):
        return np.interp(t, cw["time"], cw[key])

    c = 1e-4
    # 1 % of c, the cross-check's path criterion: each default run errs by up to 1.4e-3 c
    # (README) and the two runs' output instants differ; a sign error would be of order c
    assert np.abs(on_ccw("ecc_x") - ccw["ecc_x"]).max() < 1e-2 * c
    assert np.abs(on_ccw("ecc_y") + ccw["ecc_y"]).max() < 1e-2 * c
    assert np.abs(on_ccw("slider_x") - ccw["slider_x"]).max() < 1e-2 * c
    assert cw["crank_angle"][-1] == pytest.approx(-36.0, abs=0.1)
    assert runs[1].peak_force == pytest.approx(runs[0].peak_force, rel=1e-2)


def test_negative_rpm_runs_and_zero_is_refused():
    status, out, _ = cli(sc, "--rpm", "-500", "--revolutions", "0.05")
    assert status == 0 and "simulated 0.006 s (0.05 revolutions)" in out
    status, _, err = cli(sc, "--rpm", "0")
    assert status == 2 and "error: `rpm` must be non-zero" in err


# -- penetration limit, early stops ----------------------------------------------------
def test_max_penetration_option(tmp_path):
    # the paper's impact reaches 3.4 um (README); a 1 um limit stops it
    status, _, err = cli(jb, "--max-penetration", "1e-6")
    assert status == 1 and "exceeds the limit 1e-06 m" in err
    status, out, err = cli(sc, "--max-penetration", "1e-6", "--revolutions", "0.1")
    assert status == 1 and "exceeds the limit 1e-06 m" in err
    status, _, err = cli(sc, "--max-penetration", "-1")
    assert status == 2 and "`max_penetration` must be positive" in err


def test_an_early_stop_prints_what_was_reached():
    # the first impact (within 0.03 s, README) passes a 1 um penetration limit
    status, out, err = cli(sc, "--max-penetration", "1e-6")
    assert status == 1
    assert "simulated 0.24 s (2 revolutions)" not in out
    line = next(x for x in out.splitlines() if "STOPPED EARLY" in x)
    reached = float(line.split("t = ")[1].split(" s")[0])
    stopped = float(err.split("stopped at t = ")[1].split(" s")[0])
    # the last output lies at most one output interval (1e-5 s) or one step (<= 1e-4 s) before the stop
    assert 0.0 < reached <= stopped < 0.03 and stopped - reached <= 1e-4


# -- option combinations ---------------------------------------------------------------
def test_implicit_method_on_the_minimal_formulation_gets_implicit_steps():
    args = sc._parser().parse_args(["--method", "generalized-alpha"])
    settings = sc._settings(args, SliderCrankParams.paper())
    assert (settings.step, settings.impact_step) == (sc.REDUNDANT_DEFAULTS["step"], sc.REDUNDANT_DEFAULTS["impact_step"])
    status, out_alpha, _ = cli(sc, "--method", "generalized-alpha", "--revolutions", "0.1")
    assert status == 0
    status, out_dopri, _ = cli(sc, "--revolutions", "0.1")

    def peak(text):
        return float(text.split("peak contact force ")[1].split(" N")[0])

    # 1e-4 s fixed steps gave 2.4e7 N (issue 15); the two methods' peaks agree to 1 % (cross-check: both
    # within 0.5 % of the reference)
    assert peak(out_alpha) == pytest.approx(peak(out_dopri), rel=1e-2)
    # a step given at or below the impact step: plain fixed steps
    args = sc._parser().parse_args(["--method", "trapezoidal", "--step", "1e-6"])
    assert sc._settings(args, SliderCrankParams.paper()).impact_step is None


def test_clearance_joints_named_twice_are_refused_and_a_chosen_formulation_is_said():
    status, _, err = cli(sc, "--clearance-joints", "BB")
    assert status == 2 and "`clearance_joints` must name each joint once" in err
    with pytest.raises(ValueError, match="each joint once"):
        SliderCrankParams.paper(clearance_joints=("A", "A"))
    status, out, _ = cli(sc, "--clearance-joints", "OB", "--revolutions", "0.01")
    assert status == 0 and "redundant coordinates (chosen for --clearance-joints OB" in out


@pytest.mark.parametrize("module, option", [(sc, "--csv"), (sc, "--plot"), (jb, "--csv"), (jb, "--plot")])
def test_empty_output_names_are_refused(module, option):
    status, _, err = cli(module, option, "")
    assert status == 2 and f"error: `{option}` must name a" in err


def test_a_csv_in_a_folder_yet_to_be_made_is_written(tmp_path):
    # the check before the run passes a folder that can be made: the run must then make it,
    # not fail at the end with a traceback
    path = tmp_path / "new" / "folder" / "impact.csv"
    status, out, _ = cli(jb, "--csv", str(path))
    assert status == 0 and f"wrote {path}" in out
    assert read_csv(path)[0] == ["time", *OUTPUT_COLUMNS]


@pytest.mark.parametrize("module, args", [
    ("exuclear.models.slider_crank", ("--cr",)),
    ("exuclear.models.slider_crank", ("--method", "rk45")),
    ("exuclear.models.journal_bearing", ("--mass", "4e-2kg")),
    ("exuclear.models.journal_bearing", ("--no-such-option",)),
])
def test_parser_errors_are_one_line(module, args):
    # README: "Bad input prints one line `error: ...` and exits with status 2"
    proc = subprocess.run([sys.executable, "-m", module, *args], capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    # without a compiler at install time, the import also says so, in one line of its own
    lines = [line for line in proc.stderr.splitlines() if "KernelWarning" not in line]
    assert len(lines) == 1 and lines[0].startswith("error: ") and "--help" in lines[0]


@pytest.mark.parametrize("module, args, message", [
    (sc, ("--clearance", "-1e-4"), "`clearance` must be positive, got -0.0001"),  # the API's own text
    (sc, ("--dt-out", "-1e-5"), "`--dt-out` must be positive, got -1e-05"),
    (sc, ("--step", "-.5"), "`step` must be positive, got -0.5"),
    (jb, ("--length", "-1e-4"), "`length` must be positive, got -0.0001"),
    (jb, ("--mass", "-4E-2"), "`mass` must be positive, got -0.04"),
    (jb, ("--velocity", "-inf"), "`impact_velocity` must be finite, got -inf"),
])
def test_a_negative_value_gets_the_rule_it_breaks(module, args, message):
    # argparse read "-1e-4" as an option and said "expected one argument" (issue 21)
    status, _, err = cli(module, *args)
    assert status == 2 and err.strip() == f"error: {message}", err


# -- API checks ------------------------------------------------------------------------
def test_millimetre_dimensions_warn_naming_the_quantity_that_is_off_at_the_caller():
    with pytest.warns(exuclear.UnitWarning, match="the bearing radius 10 m and the length 15 m are above 1 m; .*were "
                                                  "they given in mm") as caught:
        exuclear.BearingGeometry(9.9, 10.0, 15.0)  # the paper's joint in mm: clearance 1 % of R_J, no other hint
    assert caught[0].filename == __file__  # the user's line, not the library's check
    with pytest.warns(exuclear.UnitWarning, match=r"^the length 15 m is above 1 m; .*was it given in mm") as caught:
        exuclear.BearingGeometry(9.9e-3, 10e-3, 15.0)
    assert "radius" not in str(caught[0].message)  # the radius is fine: only the length is named
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        exuclear.BearingGeometry(9.9e-3, 10e-3, 15e-3)  # the paper's, in m
        exuclear.BearingGeometry(0.495, 0.5, 0.8)  # a large pin, still below a metre


def test_min_step_above_step_is_refused():
    with pytest.raises(ValueError, match="`min_step` must not exceed `step`"):
        exuclear.SolverSettings(end_time=0.1, step=1e-5, min_step=1e-4)
    exuclear.SolverSettings(end_time=0.1, step=1e-5, min_step=1e-5)


def test_spectral_radius_with_an_explicit_method_is_refused():
    with pytest.raises(ValueError, match="`spectral_radius` applies to the implicit methods"):
        exuclear.SolverSettings(end_time=0.1, method="dopri5", spectral_radius=0.5)
    exuclear.SolverSettings(end_time=0.1, method="dopri5")  # the default 0.9 is not a choice of the user
    exuclear.SolverSettings(end_time=0.1, method="generalized-alpha", spectral_radius=0.5)


def test_the_scenes_offer_no_contact_mode():
    # the joint has one contact mode (the compliant law): the removed prototype's option is unknown
    status, _, err = cli(jb, "--contact-mode", "follow")
    assert status == 2 and "unrecognized arguments: --contact-mode follow" in err
