"""The Markdown report of the slider-crank validation."""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams
from validation._tables import markdown_table
from validation.slider_crank.cases import ATOL, BAND, DEAD_WINDOW, RTOL, STARTUP, Runner, Sweep
from validation.slider_crank.claims import (
    claim_dead_points_md,
    claim_materials_md,
    claim_motion_md,
    claim_spectrum_md,
    friction_md,
    frozen_md,
    sampling_md,
    tolerance_md,
)
from validation.slider_crank.diagnostics import Diagnostics, SweepRows
from validation.slider_crank.tables import history_table_md, sweep_table_md

# -- report ----------------------------------------------------------------------------

def _intro_md(revolutions: float) -> str:
    p = SliderCrankParams.paper()
    return (
        "# Slider-crank with a revolute clearance joint: the paper's Figs. 10-20\n\n"
        "Source problem: example 2 of Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597 "
        f"(docs/physics.md section 6.2). Crank {p.crank_length:g} m at {p.crank_speed * 30 / math.pi:.0f} rpm, rod "
        f"{p.rod_length:g} m, slider {p.slider_mass:g} kg; clearance joint between rod and slider, R_B = "
        f"{p.bearing_radius * 1e3:g} mm, c = {p.clearance * 1e3:g} mm, L = {p.bearing_length * 1e3:g} mm, Wang-Liu "
        f"law; the journal starts centred. {revolutions:g} revolutions.\n\n"
        "Runs: minimal formulation (kinematic tree), DOPRI5 with steps ≤ 1e-5 s (the paper's maximum) and "
        f"rtol = {RTOL:g}, atol = {ATOL:g} m instead of the paper's rtol 1e-6 (the tolerance ladder below shows "
        "why); outputs every 1e-5 s. Baseline: the ideal mechanism (redundant formulation, generalized-alpha, "
        "step 1e-5 s), dashed in every figure; for the contact force it is the force the ideal joint transmits, "
        "from the closed form `ideal_joint_force` (the `contact_force` column of the ideal run). Friction \"none\" or "
        "\"paper\" (eq. 11, Table 1: μ_s = 0.3, μ_d = 0.25, v_s = 0.1 mm/s, v_d = 10 mm/s).\n\n"
        "Definitions: *deviation* = value minus the ideal mechanism's at the same instant; *start-up* = crank "
        f"angle below {STARTUP:g}° (the journal's first bounces); *dead-point windows* = ±{DEAD_WINDOW:g}° around "
        "the interior dead points (crank at 180°, 360°, ...), compared with the rest after the start-up; *band* "
        f"= RMS of the one-sided amplitude spectrum between {BAND[0]:g} and {BAND[1]:g} Hz (whole run as the "
        "paper's FFT, and for the acceleration deviation after the start-up with a Hann window); *impacts* = "
        "contact onsets at accepted steps. Figures: position and velocity overlaid with their deviation below; "
        "acceleration, contact force, crank moment and spectra one panel per case, y-range fitted to the curves "
        "after the start-up (off-scale start-up peaks are written in the panel); dotted lines mark the dead "
        "points.\n")


def _claims_summary_md(claims: Sequence[tuple[str, str, str]]) -> str:
    return "## The paper's claims\n\n" + markdown_table(["claim (docs/physics.md section 6.2)", "verdict"],
                                                    [[name, verdict] for name, verdict, _ in claims]) + "\n"


def _sweep_section_md(sweep: Sweep, rows: SweepRows, lags: list[float] | None) -> str:
    quantities = ("slider_x", "slider_v", "slider_a", "contact_force", "crank_moment", "orbit", "spectrum",
                  "deviation_spectrum")
    figures = "\n".join(f"![{sweep.title}: {q}]({sweep.stem}_{q}.png)" for q in quantities)
    lag_text = ""
    if lags is not None:
        lag_text = ("\n\nLag of the acceleration deviation after the start-up behind the first case: "
                    + ", ".join(f"{v.value} {x * 1e6:.0f} µs" for (v, *_), x in zip(rows, lags, strict=True)) + ".")
    return (f"### {sweep.title}\n\nCSV: `{sweep.stem}.csv`.\n\n{sweep_table_md(sweep, rows)}{lag_text}\n\n"
            f"{figures}\n")


def _failures_md(failures: list[tuple[str, str]]) -> str:
    if not failures:
        return ""
    return "## Failed runs\n\n" + "\n".join(f"- {name}: {message}" for name, message in failures) + "\n"


def write_report(path: str, revolutions: float, done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics,
                 lags: dict[str, list[float]], ideal: dict[str, np.ndarray], runner: Runner, wall: float) -> str:
    """Write the Markdown report; returns ``path``."""
    p = SliderCrankParams.paper()
    crank_frequency = p.crank_speed / (2.0 * math.pi)
    resolution = 1.0 / (ideal["time"][-1] - ideal["time"][0])
    claims = [
        ("cr and material barely change slider position and velocity", *claim_motion_md(done, ideal)),
        ("slider acceleration, contact force and crank moment oscillate strongly near the dead points, more so for "
         "higher cr", *claim_dead_points_md(done, diag)),
        ("main acceleration spectrum near the crank frequency, band near 150-350 Hz growing with cr",
         *claim_spectrum_md(done, crank_frequency, resolution)),
        ("softer journal materials delay the response", *claim_materials_md(done, diag, lags)),
    ]
    parts = [_intro_md(revolutions), _claims_summary_md(claims)]
    parts += [f"### Claim {k}: {name}\n\n{text}\n" for k, (name, _, text) in enumerate(claims, start=1)]
    parts.append("### What the friction law changes\n\n" + friction_md(done, diag) + "\n")
    parts.append("## Sweeps\n")
    parts += [_sweep_section_md(s, rows, lags.get(s.stem) if s.kind == "material" else None) for s, rows in done]
    parts.append("## Diagnostics\n\n### Solver tolerance\n\nThe two extreme cases at three DOPRI5 tolerances "
                 "(outputs every 1e-5 s). CSV: `diagnostics_tolerance.csv`.\n\n" + tolerance_md(diag) + "\n")
    parts.append("### Contact history at every accepted step\n\nThe same runs recording every accepted step "
                 "(`v0` is the joint's onset speed, see docs/physics.md section 2.3). CSV: `diagnostics_history.csv`. "
                 "![contact history](diagnostic_contact_history.png)\n\n" + history_table_md(diag, [s for s, _ in done])
                 + "\n\n" + sampling_md(done, diag) + "\n")
    parts.append("### v0 floored at the first impact's speed\n\nCSV: `diagnostics_frozen_v0.csv`. "
                 "![frozen v0](diagnostic_frozen_v0_slider_a.png)\n\n" + frozen_md(diag, done) + "\n")
    parts.append(f"Total: {len(runner.results) + len(runner.histories)} runs, wall time {wall:.0f} s.\n")
    parts.append(_failures_md(runner.failures()))
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(part for part in parts if part))
    return path
