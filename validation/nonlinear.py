"""The nonlinear tools on the paper's slider-crank: its verdicts, and what an orbit diagram costs.

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2)
(2017) 587-597 (the slider-crank with a clearance joint at B, 500 rpm, c = 0.1 mm), in its
minimal formulation (``exuclear.models.slider_crank.driven``).

``verdicts``: the paper's operating point without friction (the paper's case) and with
the paper's modified Coulomb friction, each run for ``--transient`` crank periods and then
sampled for ``--periods``, with the largest Lyapunov exponent (two copies in one system);
then the same at half the largest step and half the tolerances (the convergence check),
and the friction case at the scene's own tolerances, ten times looser, where the copies'
distance meets its floor (``models/_slider_crank_nonlinear.py``).  ``diagram``: an orbit diagram over the crank speed
(``--values``, rpm) or another ``--parameter`` (``mu``: a Coulomb coefficient), written as
table and figures.

``speed`` (TIMING: run it on a quiet machine): an orbit diagram of ``--count`` crank
speeds (default 64, 300 to 1300 rpm), ``--periods`` crank periods each (default 100, no
transient), (a) ``--alone`` of the values one by one in this process (the cost of a single
run per crank period), (b) all values on the local cores, (c) all through a Dask
``LocalCluster`` of as many workers; prints the wall times, the cost per crank period
and the speed-up of (b) and (c) over (a).

Run from the repository root::

    python -m validation.nonlinear verdicts [--transient 100] [--periods 40]
    python -m validation.nonlinear diagram [--parameter rpm] [--values 300:1500:100] [--set friction=paper]
        [--periods 50] [--transient 100]
    python -m validation.nonlinear speed [--count 64] [--periods 100] [--quick]

``speed --quick``: 2 values x 3 periods, a smoke test of the script.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from exuclear.nonlinear import classify, exponent_of, orbit_diagram, run_sections
from validation._cli import add_workers_option

SCENE = "slider-crank"


def _verdict(values: dict, transient: int, periods: int, step: float = 1.0, tolerance: float = 1.0) -> str:
    """The verdict of the slider-crank at ``values`` with its exponent and the run's steps,
    at the largest step and the tolerances of ``slider_crank.driven`` times ``step`` and
    ``tolerance``."""
    from exuclear.models.slider_crank import driven

    model = driven(values)
    s = model.settings
    model = replace(model, settings=replace(s, step=s.step * step, rtol=s.rtol * tolerance, atol=s.atol * tolerance))
    run = run_sections(model, periods=periods, transient_periods=transient, perturbation=1e-6)
    if not run.success:
        return f"FAILED ({run.message}); {run.steps} steps"
    exponent = exponent_of(run, transient)[0]
    samples = np.column_stack([run.samples[k] for k in ("B.ex", "B.ey", "B.vx", "B.vy")])
    return f"{classify(samples, exponent=exponent)}; {run.steps} steps"


#: The runs of ``verdicts``: label, parameters, factors of the largest step and of the tolerances.
VERDICT_RUNS = (
    ("paper's case (no friction)", {}, 1.0, 1.0),
    ("paper's case (no friction), half the step and the tolerances", {}, 0.5, 0.5),
    ("modified Coulomb friction", {"friction": "paper"}, 1.0, 1.0),
    ("modified Coulomb friction, half the step and the tolerances", {"friction": "paper"}, 0.5, 0.5),
    ("modified Coulomb friction, the scene's own tolerances (10x: the floor)", {"friction": "paper"}, 1.0, 10.0),
)


def verdicts(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.nonlinear verdicts")
    ap.add_argument("--transient", type=int, default=100)
    ap.add_argument("--periods", type=int, default=40)
    args = ap.parse_args(argv)
    for label, values, step, tolerance in VERDICT_RUNS:
        start = time.perf_counter()
        text = _verdict(values, args.transient, args.periods, step, tolerance)
        print(f"{label}: {text}, {time.perf_counter() - start:.1f} s", flush=True)
    return 0


def diagram(argv: list[str]) -> int:
    from exuclear.study.spec import parse_values

    ap = argparse.ArgumentParser(prog="python -m validation.nonlinear diagram")
    ap.add_argument("--parameter", default="rpm", help="the parameter swept (default %(default)s; mu: a Coulomb "
                    "coefficient)")
    ap.add_argument("--values", default="300:1500:100", help="its values")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--periods", type=int, default=50)
    ap.add_argument("--transient", type=int, default=100)
    ap.add_argument("--out", default="results/nonlinear/diagram.csv")
    add_workers_option(ap)
    args = ap.parse_args(argv)
    from exuclear.nonlinear.cli import _figures, _fixed

    table = orbit_diagram(SCENE, args.parameter, parse_values(args.values), fixed=_fixed(args.set), periods=args.periods,
                          transient_periods=args.transient, exponent=True, workers=args.workers, out=args.out)
    for _, row in table.iterrows():
        print(f"{args.parameter} = {row[args.parameter]}: {row['verdict'] or row['message']}")
    for path in _figures(table, args.parameter, "B.ey", Path(args.out)):
        print(f"wrote {path}")
    return 0


def speed(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.nonlinear speed")
    ap.add_argument("--count", type=int, default=64, help="crank speeds in the diagram (default %(default)s)")
    ap.add_argument("--periods", type=int, default=100, help="crank periods per value (default %(default)s)")
    ap.add_argument("--alone", type=int, default=8, help="values run one by one in this process, spread over the "
                    "sweep, for the cost of a single run (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="2 values x 3 periods: a smoke test")
    add_workers_option(ap)
    args = ap.parse_args(argv)
    count, periods, alone = (2, 3, 1) if args.quick else (args.count, args.periods, args.alone)
    rpm = [float(v) for v in np.linspace(300.0, 1300.0, count)]
    subset = rpm[::max(1, count // alone)][:alone]
    workers = args.workers or os.cpu_count() or 1
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ways = ((f"{len(subset)} of the values one by one, in this process", subset, {"workers": 1}),
                (f"{count} values, {workers} local processes", rpm, {"workers": workers}),
                (f"{count} values, {workers}-worker Dask LocalCluster", rpm, {"workers": workers, "scheduler": "local"}))
        for k, (label, values, options) in enumerate(ways):
            start = time.perf_counter()
            table = orbit_diagram(SCENE, "rpm", values, periods=periods, out=os.path.join(tmp, f"{k}.csv"),
                                  progress=False, **options)
            wall = time.perf_counter() - start
            failed = int((~table["success"].astype(bool)).sum())
            rows.append((label, len(values), wall))
            print(f"{label}: {len(values)} runs in {wall:.2f} s ({failed} failed)", flush=True)
    single = rows[0][2] / (rows[0][1] * periods)  # wall time per crank period of a run alone
    print(f"\n{count} crank speeds {rpm[0]:g}-{rpm[-1]:g} rpm x {periods} crank periods, on {os.cpu_count()} cores; "
          f"a single run costs {1e3 * single:.3f} ms per crank period (mean of {len(subset)} values alone)")
    print(f"{'way':<50} {'wall [s]':>9} {'per crank period [ms]':>22} {'speed-up':>9}")
    for label, n, wall in rows:
        per_period = wall / (n * periods)
        print(f"{label:<50} {wall:9.2f} {1e3 * per_period:22.3f} {single / per_period:9.2f}")
    print("(speed-up: the cost per crank period of a run alone over the way's, wall time including the start of "
          "the workers)")
    return 0


COMMANDS = {"verdicts": verdicts, "diagram": diagram, "speed": speed}


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] not in COMMANDS:
        print(f"usage: python -m validation.nonlinear {{{','.join(COMMANDS)}}} [options]", file=sys.stderr)
        return 2
    return COMMANDS[argv[0]](argv[1:])


if __name__ == "__main__":
    sys.exit(main())
