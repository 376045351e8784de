"""Slider-crank with a revolute clearance joint: the paper's Figs. 10-20 and its claims.

The command line of :mod:`validation.slider_crank`: every run that waits for no other goes
to the study runner at once (on all cores by default), then the sweeps are measured,
the diagnostics run and the files written.
"""
from __future__ import annotations

import argparse
import os
import sys
import time

from exuclear.models.slider_crank import SliderCrankParams
from validation._cli import add_workers_option
from validation.slider_crank.cases import DEFAULT_OUT, MIN_REVOLUTIONS, Runner, ideal_params, paper_sweeps
from validation.slider_crank.diagnostics import first_runs, run_diagnostics, run_sweep, sweep_lags
from validation.slider_crank.files import write_diagnostic_files, write_sweep_files
from validation.slider_crank.report import write_report

# -- command line ---------------------------------------------------------------------

def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.slider_crank", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT,
                    help="directory of the figures, tables and report (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=SliderCrankParams.paper().revolutions,
                    help=f"crank revolutions per run, at least {MIN_REVOLUTIONS:.4g} (default %(default)s)")
    add_workers_option(ap)
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the sweeps and diagnostics, write figures, CSV tables and the report; 1 if any run failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    if not args.revolutions >= MIN_REVOLUTIONS:
        ap.error(f"--revolutions must be at least {MIN_REVOLUTIONS:.4g} (the first dead point and its window), "
                 f"got {args.revolutions}")
    start = time.perf_counter()
    os.makedirs(args.out, exist_ok=True)
    runner = Runner(args.workers)
    sweeps = paper_sweeps(args.revolutions)
    first = first_runs(sweeps, args.revolutions)
    print(f"running the ideal mechanism, the sweeps, the tolerance ladder and the contact histories "
          f"({len(first)} runs with repeats)", flush=True)
    runner.run(first)
    ideal = runner.result(ideal_params(args.revolutions)).columns
    done, paths = [], []
    for k, sweep in enumerate(sweeps, start=1):
        rows = run_sweep(runner, sweep, ideal, k, len(sweeps))
        paths += write_sweep_files(sweep, rows, ideal, args.out, args.revolutions)
        done.append((sweep, rows))
    lags = {s.stem: sweep_lags(rows, ideal) for s, rows in done if s.kind == "material"}
    diag = run_diagnostics(runner, sweeps, ideal, args.revolutions)
    paths += write_diagnostic_files(runner, done, diag, ideal, args.out, args.revolutions)
    wall = time.perf_counter() - start
    paths.append(write_report(os.path.join(args.out, "slider_crank.md"), args.revolutions, done, diag, lags, ideal,
                              runner, wall))
    for path in paths:
        print(f"wrote {path}")
    print(f"{len(runner.results) + len(runner.histories)} runs, wall time {wall:.1f} s")
    failures = runner.failures()
    for name, message in failures:
        print(f"error: run failed: {name}: {message}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
