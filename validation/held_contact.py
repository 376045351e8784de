"""``python -m validation.held_contact [--models ...] [--caps inf,8,6,4,3,2] [--reference 64]``:
the joint's cap on a step through which a contact is held
(:data:`exuclear.engine.steering.HELD_CONTACT_PERIODS`), measured on zoo models at their own
settings and end times.

For each model the compliant joint (compiled kernel) runs at the example's steps once per
cap (``inf``: no cap), and once at ``--reference`` times the steps without a cap (there the
example's step over the reference factor is below any cap measured).  Each row gives the
steps, the wall time, Newton iterations per step, the probe's largest and final difference
from the reference run in units of c (``ZooModel.probe`` on the example's own step grid), and
the contact statistics: mean and peak normal force, contact onsets.  In a chaotic model (the
piston engine: a 1e-9 m/s kick of its initial velocities moves its finest run by clearances)
only the statistics compare.

Run it with nothing else on the machine (it prints wall times); the two default models take
about 2 minutes.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from array import array

import numpy as np

from exuclear.engine import steering
from exuclear.engine.layout import DATA_COLUMNS
from validation._tables import markdown_table
from validation.exudyn_examples._common import load_models

MODELS = ("beam_pendulum_2d", "piston_engine")
CAPS = (math.inf, 8.0, 6.0, 4.0, 3.0, 2.0)


class Recorder:
    """A post-step function: the probe interpolated onto ``grid`` between accepted steps and
    the joint's normal force at every accepted step."""

    def __init__(self, model: object, grid: np.ndarray) -> None:
        self.model, self.grid = model, grid
        self.last_t, self.last_p = 0.0, np.asarray(model.probe(model.mbs), dtype=float)
        self.probe = np.full((len(grid), len(self.last_p)), np.nan)
        self.probe[0], self.next = self.last_p, 1
        self.t, self.force = array("d"), array("d")
        self.column = DATA_COLUMNS.index("normal_force")

    def __call__(self, mbs: object, t: float) -> bool:
        p = np.asarray(self.model.probe(mbs), dtype=float)
        grid = self.grid
        while self.next < len(grid) and grid[self.next] <= t + 1e-9 * grid[1]:
            w = min(1.0, (grid[self.next] - self.last_t) / (t - self.last_t))
            self.probe[self.next] = self.last_p + w * (p - self.last_p)
            self.next += 1
        self.last_t, self.last_p = t, p
        self.t.append(t)
        self.force.append(mbs.GetSensorValues(self.model.joint.sensorNumber)[self.column])
        return True


def statistics(joint: object, recorder: Recorder) -> dict[str, float]:
    """The joint's contact statistics over the run: the normal force's mean over time, the
    peak normal force and the contact onsets."""
    history = joint.history
    t, force = np.asarray(recorder.t), np.asarray(recorder.force)
    peaks = [r.peak_force for r in history.impacts] + [history.state.peak_force]
    return {"mean_force": float(np.sum(force * np.diff(t, prepend=0.0)) / recorder.last_t),
            "peak_force": max(peaks), "onsets": history.onsets}


def solve(name: str, refine: int, cap: float) -> dict:
    """Model ``name`` with its clearance joint at ``refine`` times the example's steps, the
    joint's cap at ``cap`` contact periods."""
    saved = steering.HELD_CONTACT_PERIODS
    steering.HELD_CONTACT_PERIODS = cap
    try:
        model = load_models()[name](clearance=True)
        mbs, ss = model.mbs, model.simulation_settings
        ti = ss.timeIntegration
        steps = int(ti.numberOfSteps)
        ti.numberOfSteps = steps * refine
        recorder = Recorder(model, np.linspace(0.0, ti.endTime, steps + 1))
        mbs.SetPostStepUserFunction(recorder)
        start = time.perf_counter()
        mbs.SolveDynamic(ss, solverType=model.solver_type)
        wall = time.perf_counter() - start
    finally:
        steering.HELD_CONTACT_PERIODS = saved
    it = mbs.sys["dynamicSolver"].it
    taken = it.currentStepIndex - 1
    return {"probe": recorder.probe, "c": model.clearance, "steps": taken, "wall": wall,
            "newton": it.newtonStepsCount / taken, "stats": statistics(model.joint, recorder)}


def rows(name: str, caps: list[float], reference: int) -> list[list[str]]:
    ref = solve(name, reference, math.inf)
    table = [[name, f"{reference}x steps, no cap", str(ref["steps"]), f"{ref['wall']:.2f}", f"{ref['newton']:.2f}",
              "-", "-", f"{ref['stats']['mean_force']:.4g}", f"{ref['stats']['peak_force']:.4g}",
              str(ref["stats"]["onsets"])]]
    for cap in caps:
        run = solve(name, 1, cap)
        off = np.abs(run["probe"] - ref["probe"]).max(axis=1) / run["c"]
        table.append([name, "no cap" if cap == math.inf else f"{cap:g} T_c", str(run["steps"]), f"{run['wall']:.2f}",
                      f"{run['newton']:.2f}", f"{np.nanmax(off):.3g}", f"{off[-1]:.3g}",
                      f"{run['stats']['mean_force']:.4g}", f"{run['stats']['peak_force']:.4g}",
                      str(run["stats"]["onsets"])])
        print(" | ".join(table[-1]), flush=True)
    return table


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.held_contact", description=__doc__.split("\n\n")[0])
    parser.add_argument("--models", default=",".join(MODELS), help=f"zoo models (default {','.join(MODELS)})")
    parser.add_argument("--caps", default=",".join(f"{c:g}" for c in CAPS),
                        help="caps in contact periods, inf: none (default %(default)s)")
    parser.add_argument("--reference", type=int, default=64, help="the reference run's step factor (default 64)")
    args = parser.parse_args(argv)
    caps = [float(c) for c in args.caps.split(",")]
    if any(not c > 0.0 for c in caps) or args.reference < 1:
        parser.error("caps must be positive (inf for none) and --reference at least 1")
    table = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints' notes (chatter at the example's steps) are not the measurement
        for name in args.models.split(","):
            table += rows(name, caps, args.reference)
    print()
    print(markdown_table(["model", "run", "steps", "wall [s]", "Newton / step", "probe off reference, largest [c]",
                          "at the end [c]", "mean F_n [N]", "peak F_n [N]", "onsets"], table))
    return 0


if __name__ == "__main__":
    sys.exit(main())
