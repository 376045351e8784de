"""The joint's Jacobian per step, switched with its steps or held for the whole run (issue 20).

Source problem: the zoo's models (``validation/exudyn_examples``).  Where a model's largest
step exceeds half the joint's contact period, the joint asks Exudyn's modified Newton for a
Jacobian at every step (``exuclear.engine.steering``); its kernel switches the ask with the
steps it accepts, redoes and grows.  The other rule holds the ask for the whole run.  This
script runs both side by side, the held rule by leaving the ask as the run started it (the
kernel's ``jacobian_per_step`` calls do nothing), over a set of restitutions (chaotic models move
with any change of a bounce, so one run says little), with each model's own settings
through a plain ``mbs.SolveDynamic`` and through ``exuclear.simulate``.  It prints per run
the wall time, steps and impacts, and per model and path the sums of the wall times; with
``--convergence`` also, for the own-settings runs, the distance of the |e|/c spectrum to
the 4x refined run's (``exuclear.check_convergence``; it agrees below 0.1).  Run::

    python -m validation.cost jacobian_steps [--models a,b] [--restitutions 0.89,0.9,0.91] [--paths own,simulate] [--convergence]

(about two minutes with the defaults, nothing else running).
"""
from __future__ import annotations

import argparse
import time
import warnings
from collections import defaultdict
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import exuclear
from exuclear.engine import handle
from validation._tables import markdown_table
from validation.exudyn_examples._common import REGISTRY, ZooModel, model_names

#: The rules compared, in the order they run in each round.
RULES = ("whole run", "with the steps")
PATHS = ("own", "simulate")


@contextmanager
def rule(name: str) -> Iterator[None]:
    """Run with the Jacobian rule ``name``: "with the steps" (the library's) or "whole run"
    (the joint's asks after the run start do nothing: the setting stays as it began)."""
    ask = handle._RunStart.jacobian_per_step
    if name == "whole run":
        handle._RunStart.jacobian_per_step = lambda self, wanted: None  # type: ignore[method-assign]
    try:
        yield
    finally:
        handle._RunStart.jacobian_per_step = ask  # type: ignore[method-assign]


def build(name: str, cr: float) -> ZooModel:
    return REGISTRY[name](True, None, cr=cr)


def run(name: str, cr: float, path: str, convergence: bool) -> tuple[float, int, int, float]:
    """Wall time [s], accepted steps, impacts and (own path with ``convergence``, else NaN)
    the |e|/c spectrum distance to the 4x refined run."""
    model = build(name, cr)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joint's notes are not what this script measures
        start = time.perf_counter()
        if path == "own":
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        else:
            exuclear.simulate(model.mbs, model.solver_settings)
        wall = time.perf_counter() - start
        steps = model.mbs.sys["dynamicSolver"].it.currentStepIndex - 1
        impacts = model.joint.counts["impacts"]
        distance = float("nan")
        if convergence and path == "own":
            distance = spectrum_distance(name, cr, model)
    return wall, steps, impacts, distance


def spectrum_distance(name: str, cr: float, model: ZooModel) -> float:
    """The |e|/c spectrum distance of an own-settings run to its 4x refined run."""
    def refined(settings: Any) -> exuclear.RunRecord:
        m = build(name, cr)
        ok = bool(m.mbs.SolveDynamic(settings, solverType=m.solver_type))
        return exuclear.RunRecord.from_mbs(m.mbs, {"joint": m.joint}, success=ok)

    baseline = exuclear.RunRecord.from_mbs(model.mbs, {"joint": model.joint})
    check = exuclear.check_convergence(refined, model.simulation_settings, baseline=baseline)
    return next((float(s.value) for s in check.joints["joint"].statistics if s.name.startswith("spectrum")),
                float("nan"))


def parse_restitutions(text: str) -> list[float]:
    values = [float(x) for x in text.split(",") if x.strip()]
    if not values or not all(0.0 < v <= 1.0 for v in values):
        raise argparse.ArgumentTypeError(f"restitutions in (0, 1], comma-separated, got {text!r}")
    return values


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost jacobian_steps", description=__doc__.split("\n")[0])
    ap.add_argument("--models", default="rigid_body_tutorial3_friction,double_pendulum_2d_friction,four_bar_3d,"
                                        "piston_engine", help="zoo models, comma-separated (default %(default)s)")
    ap.add_argument("--restitutions", type=parse_restitutions, default=parse_restitutions("0.89,0.9,0.91"),
                    help="coefficients of restitution of the joint, comma-separated (default 0.89,0.9,0.91)")
    ap.add_argument("--paths", default="own,simulate", help="own (plain mbs.SolveDynamic) and/or simulate")
    ap.add_argument("--convergence", action="store_true",
                    help="also the own-settings runs' spectrum distance to their 4x refined runs")
    args = ap.parse_args(argv)
    try:
        names = model_names(args.models)
    except ValueError as err:
        ap.error(str(err))
    paths = [p for p in args.paths.split(",") if p]
    if not paths or any(p not in PATHS for p in paths):
        ap.error(f"--paths: {', '.join(PATHS)}, got {args.paths!r}")
    rows, sums = [], defaultdict(float)
    for name in names:
        for path in paths:
            for cr in args.restitutions:
                cells: list[str] = [name, path, f"{cr:g}"]
                for r in RULES:  # side by side
                    with rule(r):
                        wall, steps, impacts, distance = run(name, cr, path, args.convergence)
                    sums[name, path, r] += wall
                    cells += [f"{wall:.2f}", str(steps), str(impacts)]
                    if args.convergence:
                        cells.append(f"{distance:.3f}" if path == "own" else "-")
                rows.append(cells)
            print(f"{name}, {path}: done", flush=True)
    header = ["model", "path", "cr"]
    for r in RULES:
        header += [f"{r}: wall [s]", "steps", "impacts"] + (["spectrum distance"] if args.convergence else [])
    print("\n" + markdown_table(header, rows))
    print("\n" + markdown_table(["model", "path", "sum of wall times: whole run [s]", "with the steps [s]", "ratio"],
                                [[n, p, f"{sums[n, p, RULES[0]]:.2f}", f"{sums[n, p, RULES[1]]:.2f}",
                                  f"{sums[n, p, RULES[1]] / sums[n, p, RULES[0]]:.2f}"]
                                 for n in names for p in paths]))
    return 0
