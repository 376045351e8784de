"""What friction costs in the zoo's models, and why (issue 20).

Source problem: the zoo's rigid-body models with friction (``validation/exudyn_examples``,
``double_pendulum_2d`` and ``rigid_body_tutorial3``) cost far more than without it, with
their own solver settings through a plain ``mbs.SolveDynamic``.  This script runs each model
with the ideal joint and with the clearance joint under four friction settings, side by side
(``--repeat`` rounds, wall times are medians):

- no friction;
- Coulomb friction at the paper's dynamic coefficient, ``Coulomb(0.25, v_eps=1e-4)``: the
  same regularisation as the paper's law (its ``v_s``), a flat characteristic;
- the paper's modified Coulomb law (``friction="paper"``: mu_s = 0.3 at v_s = 0.1 mm/s,
  falling to mu_d = 0.25 at v_d = 10 mm/s, docs/physics.md eq. (22));
- the paper's law again at 4x the steps and a quarter of the joint's ``rate_limit`` (what
  ``exuclear.check_convergence`` refines): its impacts tell whether the run's impacts are the
  model's or the steps'.

It prints per model and setting the wall time and its ratio to the ideal model's, the
accepted steps, the impacts and their median onset speed.  A friction coefficient that falls
with the slip speed is a negative damping of the sliding motion (the classic source of
stick-slip and friction-induced vibration): the journal chatters along its wall in impacts
of a few mm/s, each resolved by the joint's rate criterion, and the 4x refined run has more
of them, not fewer, at onset speeds of the same few mm/s.  Run::

    python -m validation.cost friction [--models double_pendulum_2d,rigid_body_tutorial3] [--repeat 3] [--end-time T]

(about a minute with the defaults).
"""
from __future__ import annotations

import argparse
import statistics
import time
import warnings
from typing import Any

import numpy as np

from exuclear.friction import Coulomb, FrictionLaw, ModifiedCoulomb
from validation._cli import _positive_int
from validation._tables import markdown_table
from validation.exudyn_examples._common import REGISTRY, ZooModel, model_names

#: The clearance joint's friction settings compared, by label: the paper's dynamic
#: coefficient with the paper's regularisation, flat; and the paper's falling law.
FRICTIONS: dict[str, str | FrictionLaw] = {
    "none": "none",
    "Coulomb 0.25 (flat)": Coulomb(0.25, v_eps=ModifiedCoulomb.paper().v_s),
    "paper (0.3 -> 0.25)": "paper",
}
#: The refinement of the last row (steps and rate limit), as in exuclear.check_convergence.
REFINE = 4


def impact_summary(impacts: list[Any]) -> tuple[int, float]:
    """Number of impacts and the median of their onset speeds |v0| [m/s] (NaN without any),
    from a joint's ``impacts()`` rows (onset time, onset velocity, ...)."""
    if not impacts:
        return 0, float("nan")
    return len(impacts), float(np.median(np.abs([row[1] for row in impacts])))


def build(name: str, friction: str | FrictionLaw | None, end_time: float | None, refine: int = 1) -> ZooModel:
    """Zoo model ``name`` with its own settings: the ideal joint (``friction`` None) or the
    clearance joint with ``friction``; ``refine`` times the steps and 1/refine of the joint's
    rate limit."""
    if friction is None:
        model = REGISTRY[name](False, end_time)
    else:
        model = REGISTRY[name](True, end_time, friction=friction)
    if refine != 1:
        ti = model.simulation_settings.timeIntegration
        ti.numberOfSteps *= refine
        model.joint.rate_limit = model.joint.rate_limit / refine
    return model


def run(model: ZooModel) -> tuple[float, int, bool]:
    """Wall time [s], accepted steps, and whether the run reached its end time."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a note of the joint is shown in the table's last column
        start = time.perf_counter()
        try:
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        except Exception:  # noqa: BLE001 - Exudyn's own error types; the table says "stopped"
            pass
        wall = time.perf_counter() - start
    end = model.simulation_settings.timeIntegration.endTime
    reached = abs(model.mbs.systemData.GetTime() - end) <= 1e-9 * end
    return wall, model.mbs.sys["dynamicSolver"].it.currentStepIndex - 1, reached


def model_rows(name: str, repeat: int, end_time: float | None) -> list[list[str]]:
    """The table rows of one model: the ideal joint, the friction settings, the refined run."""
    settings: dict[str, str | FrictionLaw | None] = {"ideal joint": None, **FRICTIONS}
    walls: dict[str, list[float]] = {label: [] for label in settings}
    last: dict[str, tuple[ZooModel, int, bool]] = {}
    for _ in range(repeat):  # side by side, each round every setting once
        for label, friction in settings.items():
            model = build(name, friction, end_time)
            wall, steps, reached = run(model)
            walls[label].append(wall)
            last[label] = (model, steps, reached)
    refined_label = f"paper, {REFINE}x steps, rate_limit / {REFINE}"
    model = build(name, "paper", end_time, REFINE)
    wall, steps, reached = run(model)
    walls[refined_label] = [wall]
    last[refined_label] = (model, steps, reached)
    ideal = statistics.median(walls["ideal joint"])
    rows = []
    for label, times in walls.items():
        model, steps, reached = last[label]
        wall = statistics.median(times)
        count, speed = impact_summary(model.joint.impacts()) if model.joint is not None else (0, float("nan"))
        rows.append([name, label, f"{wall:.3f}", f"{wall / ideal:.1f}x", str(steps),
                     "-" if model.joint is None else str(count),
                     "-" if model.joint is None or count == 0 else f"{1e3 * speed:.2f}",
                     "yes" if reached else "stopped"])
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost friction", description=__doc__.split("\n")[0])
    ap.add_argument("--models", default="double_pendulum_2d,rigid_body_tutorial3",
                    help="zoo models with rigid bodies, comma-separated (default %(default)s)")
    ap.add_argument("--repeat", type=_positive_int, default=3,
                    help="timing rounds, each setting once per round; wall times are medians (default %(default)s)")
    ap.add_argument("--end-time", type=float, default=None,
                    help="end time [s] of every run (default: each example's own)")
    args = ap.parse_args(argv)
    if args.end_time is not None and not args.end_time > 0.0:
        ap.error(f"--end-time must be positive, got {args.end_time}")
    try:
        names = model_names(args.models)
    except ValueError as err:
        ap.error(str(err))
    rows = []
    for name in names:
        rows += model_rows(name, args.repeat, args.end_time)
        print(f"{name}: done", flush=True)
    print(f"\neach model's own solver settings, plain mbs.SolveDynamic; wall times: medians of {args.repeat} "
          f"(the refined run: one)\n")
    print(markdown_table(["model", "joint / friction", "wall [s]", "/ ideal", "steps", "impacts",
                          "median onset speed [mm/s]", "reached the end"], rows))
    return 0
