"""Whether the joint's own step rules make a run at the user's own step worse (issue 30).

Source problem: the paper's slider-crank (Wang et al., JMST 2017, example 2: cr 0.9, steel
journal and bearing, no friction; ``models/slider_crank.py``), built as an Exudyn user
builds it, in the redundant 2D and the spatial formulation, and run through a plain
``mbs.SolveDynamic`` with generalized-alpha (spectral radius 0.9) at a fixed number of steps
and Exudyn's default adaptive step.  Each run is made twice: with the joint's defaults, and
with its rules off (``rate_limit = 0``, ``steer_newton = False``).  Its journal path (the
eccentricity in the global frame) is compared with the independent SciPy reference
(``validation/reference``, DOP853 at rtol 1e-10) on the reference's 1e-5 s grid: the largest
distance, in % of the clearance.  A step the joint redoes shorter should leave a fine run as
it is and make a coarse one better.

Printed per formulation and step: the path error with the joint's defaults and with its rules
off, their ratio, and the steps the joint redid::

    python -m validation.cost fine_steps [--steps 1e-6,2e-6,5e-6,1e-5] [--formulations spatial,redundant] [--end-time 0.24]

(about two minutes with the defaults; the 22 impacts of the paper's case end by 0.024 s).
"""
from __future__ import annotations

import argparse
import math
import warnings
from dataclasses import dataclass, replace

import exudyn as exu
import numpy as np

from exuclear.models.slider_crank import SliderCrankParams, build, columns
from validation._tables import markdown_table
from validation.reference import slider_crank as sc_reference

#: The reference's tolerances and output grid (validation/cross_check/common.py's).
REF_RTOL, REF_ATOL, REF_GRID = 1e-10, 1e-13, 1e-5
#: The issue's steps [s]: the paper's 22 impacts last 87 to 255 us, about 9 to 250 steps.
DEFAULT_STEPS = (1e-6, 2e-6, 5e-6, 1e-5)
FORMULATIONS = ("spatial", "redundant")
#: Exudyn's default spectral radius of generalized-alpha.
SPECTRAL_RADIUS = 0.9


@dataclass(frozen=True)
class PathError:
    """One run against the reference: the largest distance of the journal paths [fraction
    of c], the steps the joint redid, and its impacts."""

    error: float
    rejected: int
    impacts: int


def paper_case(formulation: str, end_time: float) -> SliderCrankParams:
    """The paper's slider-crank in ``formulation``, over ``end_time`` [s]."""
    p = SliderCrankParams.paper(formulation=formulation)
    return replace(p, revolutions=end_time * p.crank_speed / (2.0 * math.pi))


def reference(params: SliderCrankParams) -> dict[str, np.ndarray]:
    """The SciPy reference's columns on its grid (:data:`REF_RTOL`)."""
    result = sc_reference.simulate(params, rtol=REF_RTOL, atol=REF_ATOL, output_step=REF_GRID)
    if not result.success:
        raise RuntimeError(f"the reference failed: {result.message}")
    return result.columns


def path_error(params: SliderCrankParams, step: float, rules: bool, ref: dict[str, np.ndarray]) -> PathError:
    """Run ``params`` through a plain ``mbs.SolveDynamic`` at ``step`` [s] (the joint's
    defaults, or its rules off) and compare its journal path with ``ref``."""
    model = build(params)
    joint = model.joint
    if not rules:
        joint.rate_limit = 0.0
        joint.steer_newton = False
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = params.end_time
    ss.timeIntegration.numberOfSteps = int(round(params.end_time / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = SPECTRAL_RADIUS
    ss.timeIntegration.verboseMode = 0
    ss.solution.sensors.writePeriod = REF_GRID
    ss.solution.file.write = False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joint's notes are not what this script measures
        ok = model.mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    if not ok:
        raise RuntimeError(f"the {params.formulation} run at {step:g} s stopped")
    cols = columns(model)
    t = ref["time"]
    ex = np.interp(t, cols["time"], cols["ecc_x"])
    ey = np.interp(t, cols["time"], cols["ecc_y"])
    error = float(np.max(np.hypot(ex - ref["ecc_x"], ey - ref["ecc_y"]))) / params.clearance
    counts = joint.counts
    return PathError(error, counts["rejected_steps"], counts["impacts"])


def _floats(text: str) -> list[float]:
    values = [float(x) for x in text.split(",") if x.strip()]
    if not values or not all(v > 0.0 for v in values):
        raise ValueError(f"positive numbers, comma-separated, got {text!r}")
    return values


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost fine_steps", description=__doc__.split("\n")[0])
    ap.add_argument("--steps", default=",".join(f"{s:g}" for s in DEFAULT_STEPS),
                    help="the user's steps [s], comma-separated (default %(default)s)")
    ap.add_argument("--formulations", default=",".join(FORMULATIONS),
                    help="slider-crank formulations, comma-separated (default %(default)s)")
    ap.add_argument("--end-time", type=float, default=0.24, help="end time [s] (default 0.24: two revolutions)")
    args = ap.parse_args(argv)
    try:
        steps = _floats(args.steps)
    except ValueError as err:
        ap.error(f"--steps: {err}")
    formulations = [f.strip() for f in args.formulations.split(",") if f.strip()]
    unknown = [f for f in formulations if f not in FORMULATIONS]
    if unknown or not formulations:
        ap.error(f"--formulations: choose from {', '.join(FORMULATIONS)}, got {args.formulations!r}")
    if not args.end_time > 0.0:
        ap.error(f"--end-time must be positive, got {args.end_time}")
    rows = []
    for formulation in formulations:
        params = paper_case(formulation, args.end_time)
        ref = reference(params)
        for step in steps:
            on, off = path_error(params, step, True, ref), path_error(params, step, False, ref)
            rows.append([formulation, f"{step:g}", f"{100 * on.error:.3g}", f"{100 * off.error:.3g}",
                         f"{on.error / off.error:.3g}", on.rejected, f"{on.impacts} / {off.impacts}"])
            print(f"{formulation} {step:g} s: done", flush=True)
    print("\n" + markdown_table(["formulation", "step [s]", "path error, joint's defaults [% c]",
                                 "rules off [% c]", "ratio", "steps redone", "impacts (defaults / off)"], rows))
    return 0
