"""Where an implicit run with a clearance joint spends its Newton iterations (issue 20).

Source problem: the zoo's models (``validation/exudyn_examples``) with their own solver
settings through a plain ``mbs.SolveDynamic``.  Their cost beyond the ideal model is steps
and, per step, Newton iterations with their Jacobians; Exudyn's counters give the totals,
this script shows what the iterates do.  It runs a model with the joint's Python kernel
and records every contact-force evaluation (Newton iterates, Jacobian perturbations and
redone steps alike) with the accepted state it starts from, then prints per model, over
the window ``[--start, --end]``:

- accepted step starts in the window and force evaluations per step start (median, 90 %,
  largest);
- how many steps evaluate a penetration more than 10 times the deepest of the step's start
  (``delta > 10 max(delta_0, 1 nm)``): Newton's first iterates overshoot into the wall;
- the evaluations of the costliest step: penetration, its rate and the normal force of each
  distinct iterate.

A step in settled contact whose first iterate lies a thousand times deeper than its start
converges back from above, where the force grows like ``delta^n (1 + D delta_dot / v_min)``
(docs/physics.md eq. (9)): each Newton iteration then removes only about half of the
excess, and the modified Newton method takes a Jacobian at nearly every one.  Run::

    python -m validation.cost newton [--models beam_pendulum_2d,double_pendulum_2d_friction] [--start S] [--end E]

(the Python kernel is 3 to 10 times slower than the compiled one; a window of 0.05 s of the
beam pendulum takes about half a minute).
"""
from __future__ import annotations

import argparse
import warnings
from collections import defaultdict
from typing import Any

import numpy as np

from exuclear.engine import _python_kernel
from validation._tables import markdown_table
from validation.exudyn_examples._common import REGISTRY, model_names

#: A penetration this many times the step start's (at least 1 nm) counts as an overshoot.
OVERSHOOT = 10.0
#: The floor of the step start's penetration in that comparison [m].
OVERSHOOT_FLOOR = 1e-9
#: Iterates of the costliest step printed, and the relative change of penetration that
#: separates two (a Jacobian's perturbations change it far less).
ITERATES_SHOWN = 16
ITERATE_CHANGE = 0.01


def record_evaluations(name: str, end: float) -> list[tuple[float, float, float, float, float]]:
    """Run zoo model ``name`` to ``end`` with the Python kernel; every contact-force evaluation as
    (step start time, penetration, its rate, normal force, the step start's penetration)."""
    rows: list[tuple[float, float, float, float, float]] = []
    evaluate = _python_kernel.contact_response

    def recorded(normal_force: Any, friction: Any, delta: float, delta_dot: float, v_t: float, history: Any,
                 share: float = 1.0) -> Any:
        response = evaluate(normal_force, friction, delta, delta_dot, v_t, history, share)
        rows.append((history.time, delta, delta_dot, response.f_n, history.delta))
        return response

    _python_kernel.contact_response = recorded  # the kernel's one call of the contact law
    try:
        model = REGISTRY[name](True, end, backend="python")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the joint's notes are not what this script measures
            try:
                model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
            except Exception:  # noqa: BLE001 - a run that Exudyn stops still shows its iterates
                pass
    finally:
        _python_kernel.contact_response = evaluate
    return rows


def summary(name: str, rows: list[tuple[float, float, float, float, float]], start: float) -> tuple[list[str], str]:
    """The table row of one model and the iterates of its costliest step."""
    steps: dict[float, list[tuple[float, float, float, float, float]]] = defaultdict(list)
    for row in rows:
        if row[0] >= start:
            steps[row[0]].append(row)
    if not steps:
        return [name, "0", "-", "-"], ""
    counts = np.array([len(v) for v in steps.values()])
    overshoot = sum(1 for v in steps.values()
                    if max(r[1] for r in v) > OVERSHOOT * max(v[0][4], OVERSHOOT_FLOOR))
    worst_time, worst = max(steps.items(), key=lambda item: len(item[1]))
    iterates: list[tuple[float, float, float]] = []
    for _, d, dd, f, _ in worst:  # a Jacobian's perturbations move the penetration by far less than 1 %
        if not iterates or abs(d - iterates[-1][0]) > ITERATE_CHANGE * abs(iterates[-1][0]):
            iterates.append((d, dd, f))
    iterates = iterates[:ITERATES_SHOWN]
    detail = (f"{name}: costliest step from t = {worst_time:.6g} s (start penetration {worst[0][4]:.3g} m), "
              f"{len(worst)} evaluations; its iterates, each where the penetration moved by more than "
              f"{100 * ITERATE_CHANGE:g} % (penetration [m], rate [m/s], normal force [N]):\n"
              + "\n".join(f"  {d:.3e}  {dd:.3e}  {f:.3e}" for d, dd, f in iterates))
    row = [name, str(len(steps)),
           f"{np.median(counts):.0f} / {np.percentile(counts, 90):.0f} / {counts.max()}",
           f"{overshoot} ({100.0 * overshoot / len(steps):.0f} %)"]
    return row, detail


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost newton", description=__doc__.split("\n")[0])
    ap.add_argument("--models", default="beam_pendulum_2d,double_pendulum_2d",
                    help="zoo models, comma-separated (default %(default)s)")
    ap.add_argument("--start", type=float, default=0.2, help="window start [s] (default %(default)s)")
    ap.add_argument("--end", type=float, default=0.25, help="window end = end of the run [s] (default %(default)s)")
    args = ap.parse_args(argv)
    if not 0.0 <= args.start < args.end:
        ap.error(f"need 0 <= --start < --end, got {args.start} and {args.end}")
    try:
        names = model_names(args.models)
    except ValueError as err:
        ap.error(str(err))
    table, details = [], []
    for name in names:
        row, detail = summary(name, record_evaluations(name, args.end), args.start)
        table.append(row)
        details.append(detail)
    print(f"window {args.start:g} s to {args.end:g} s, Python kernel, each model's own solver settings\n")
    print(markdown_table(["model", "step starts", "force evaluations per step: median / 90 % / max",
                          f"steps with an iterate > {OVERSHOOT:g}x the start's penetration"], table))
    print("\n" + "\n\n".join(d for d in details if d))
    return 0
