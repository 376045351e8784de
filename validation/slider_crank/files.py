"""Figures and CSV tables of the sweeps and the diagnostics."""
from __future__ import annotations

import os
from collections.abc import Sequence

import numpy as np

import exuclear
from exuclear.models.figures import crank_angle_panels, slider_crank_sweep_figures
from exuclear.models.slider_crank import SliderCrankParams, ideal_joint_force
from validation._tables import write_csv
from validation.slider_crank.cases import BAND, CR_SWEEP, FROZEN_FIGURES, SPECTRUM_STEP, STARTUP, Runner, Sweep
from validation.slider_crank.diagnostics import Diagnostics, SweepRows
from validation.slider_crank.metrics import dead_points
from validation.slider_crank.tables import _case_record, _history_record, _records

# -- files ----------------------------------------------------------------------------

def write_sweep_files(sweep: Sweep, rows: SweepRows, ideal: dict[str, np.ndarray], directory: str,
                      revolutions: float) -> list[str]:
    """The figures and the CSV table of one sweep; returns the paths."""
    cases = [(v.label, r.columns) for v, _, r, _ in rows if r.success]
    paths = []
    if cases:
        paths += slider_crank_sweep_figures(
            cases, ideal, rows[0][1].clearance, directory, sweep.stem, title=sweep.title,
            dead_points=dead_points(360.0 * revolutions), zoom_after=STARTUP, band=BAND, spectrum_step=SPECTRUM_STEP,
            deviation_after=STARTUP)
    paths.append(write_csv(os.path.join(directory, f"{sweep.stem}.csv"), _records(sweep, rows)))
    return paths


def write_diagnostic_files(runner: Runner, done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics,
                           ideal: dict[str, np.ndarray], directory: str, revolutions: float) -> list[str]:
    """CSV tables and figures of the diagnostics; returns the paths."""
    paths = [write_csv(os.path.join(directory, "diagnostics_tolerance.csv"),
                       [{"case": name, "rtol": rtol, "steps": r.steps, "wall [s]": r.wall_time,
                         **_case_record("value", "", m, not r.success)} for name, rtol, r, m in diag.tolerance])]
    if diag.histories:
        paths.append(write_csv(os.path.join(directory, "diagnostics_history.csv"),
                               [_history_record(stem, value, h) for (stem, value), h in diag.histories.items()]))
    frozen = [{"friction": fr, **_case_record("cr", v.value, m, not r.success)}
              for fr, rows in diag.frozen.items() for v, _, r, m in rows]
    if frozen:
        paths.append(write_csv(os.path.join(directory, "diagnostics_frozen_v0.csv"), frozen))
    marks = dead_points(360.0 * revolutions)
    paths.append(_history_figure(runner, done, directory, revolutions))
    for friction, rows in diag.frozen.items():
        cases = [(f"{v.label}, v_min {diag.frozen_v_min:.3f} m/s", r.columns) for v, _, r, _ in rows if r.success]
        if cases:
            paths += slider_crank_sweep_figures(
                cases, ideal, rows[0][1].clearance, directory, f"diagnostic_frozen_v0_friction-{friction}",
                title=f"restitution sweep with v0 floored at the first impact's speed, friction {friction}",
                dead_points=marks, zoom_after=STARTUP, band=BAND, spectrum_step=SPECTRUM_STEP, deviation_after=STARTUP,
                quantities=FROZEN_FIGURES)
    if "none" in diag.frozen:
        paths.append(_frozen_overview(diag, done, ideal, directory, marks))
    return paths


def _history_figure(runner: Runner, done: Sequence[tuple[Sweep, SweepRows]], directory: str,
                    revolutions: float) -> str:
    """Normal force against the ideal force, eccentricity direction and v0 of the restitution sweeps."""
    force_curves, angle_curves, v0_curves = [], [], []
    for sweep, rows in done:
        if sweep.kind != "cr":
            continue
        for variant, params, _, _ in {id(row): row for row in (rows[0], rows[-1])}.values():
            hist = runner.ran_history(params)
            if hist is None or not hist.success:
                continue
            label = f"{variant.label}, friction {sweep.friction}"
            out, theta = hist.out, hist.theta
            force_curves.append((label, theta, out["normal_force"], "-"))
            angle_curves.append((label, theta, np.degrees(np.unwrap(np.arctan2(out["ecc_y"], out["ecc_x"]))), "-"))
            v0_curves.append((label, theta, out["v0"], "-"))
    theta = np.linspace(0.0, 360.0 * revolutions, 20001)
    fx, fy = ideal_joint_force(SliderCrankParams.paper(), np.radians(theta))
    force_curves.append(("ideal joint force (closed form)", theta, np.hypot(fx, fy), "k--"))
    angle_curves.append(("ideal F direction", theta, np.degrees(np.unwrap(np.arctan2(fy, fx))), "k--"))
    path = os.path.join(directory, "diagnostic_contact_history.png")
    return crank_angle_panels([("normal force [N]", force_curves), ("eccentricity direction [°]", angle_curves),
                               ("v0 of the current contact [m/s]", v0_curves)], path, log_panels=(0, 2),
                              marks=dead_points(360.0 * revolutions),
                              title="contact history at every accepted step (restitution sweeps, lowest and highest cr)")


def _frozen_overview(diag: Diagnostics, done: Sequence[tuple[Sweep, SweepRows]], ideal: dict[str, np.ndarray],
                     directory: str, marks: Sequence[float]) -> str:
    """Acceleration deviation at cr 0.3 and 0.9 (no friction), default v_min against the raised one."""
    default = {v.value: r.columns for s, rows in done if s.kind == "cr" and s.friction == "none"
               for v, _, r, _ in rows}
    frozen = {v.value: r.columns for v, _, r, _ in diag.frozen["none"]}
    panels = []
    for value in (f"{CR_SWEEP[0]:g}", f"{CR_SWEEP[-1]:g}"):
        curves = []
        for name, cols in ((f"v_min {exuclear.contact.V_MIN_DEFAULT:g} m/s", default.get(value)),
                           (f"v_min {diag.frozen_v_min:.3f} m/s", frozen.get(value))):
            if cols is not None:
                dev = cols["slider_a"] - np.interp(cols["time"], ideal["time"], ideal["slider_a"])
                curves.append((name, cols["crank_angle"], np.clip(dev, -500.0, 500.0), "-"))
        panels.append((f"a - ideal [m/s²], cr = {value}", curves))
    path = os.path.join(directory, "diagnostic_frozen_v0_slider_a.png")
    return crank_angle_panels(panels, path, marks=marks,
                              title="slider acceleration deviation, no friction: default v0 treatment against v0 "
                                    "floored at the first impact's speed (clipped at ±500 m/s²)")
