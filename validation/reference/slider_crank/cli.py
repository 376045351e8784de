"""SciPy reference run of the paper's slider-crank (docs/physics.md section 6.2).

The command line of :mod:`validation.reference.slider_crank`::

    python -m validation.reference.slider_crank [--law L] [--cr CR] [--friction F] [--ideal] [--csv FILE] ...
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams
from validation.reference.slider_crank.driver import METHODS, simulate
from validation.reference.slider_crank.outputs import COLUMNS


def _parser() -> argparse.ArgumentParser:
    p = SliderCrankParams.paper()
    ap = argparse.ArgumentParser(prog="python -m validation.reference.slider_crank",
                                 description="SciPy reference run of the paper's slider-crank (docs/physics.md section 6.2).")
    ap.add_argument("--law", default=p.law, help="contact law (default %(default)s)")
    ap.add_argument("--cr", type=float, default=p.cr, help="coefficient of restitution (default %(default)s)")
    ap.add_argument("--friction", default=p.friction, help="none, coulomb:MU or paper (default %(default)s)")
    ap.add_argument("--journal", default=p.journal_material, help="journal material (default %(default)s)")
    ap.add_argument("--clearance", type=float, default=p.clearance, help="radial clearance [m] (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=p.revolutions, help="crank revolutions (default %(default)s)")
    ap.add_argument("--ideal", action="store_true", help="ideal joint at B (closed form)")
    ap.add_argument("--method", default="DOP853", choices=METHODS, help="solve_ivp method (default %(default)s)")
    ap.add_argument("--rtol", type=float, default=1e-10, help="relative tolerance (default %(default)s)")
    ap.add_argument("--atol", type=float, default=1e-13, help="absolute tolerance (default %(default)s)")
    ap.add_argument("--max-step", type=float, default=None, help="largest step [s] (default unbounded)")
    ap.add_argument("--output-step", type=float, default=1e-5, help="output interval [s] (default %(default)s)")
    ap.add_argument("--csv", metavar="FILE", help="write the columns to FILE")
    return ap


def _write_csv(path: str, columns: dict[str, np.ndarray]) -> None:
    """:data:`COLUMNS` as CSV (every value a float, written as Python writes it; CRLF line ends)."""
    import pandas as pd

    table = pd.DataFrame({k: np.asarray(columns[k], dtype=float) for k in COLUMNS})
    table.to_csv(path, index=False, na_rep="nan", lineterminator="\r\n")


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        params = replace(SliderCrankParams.paper(), law=args.law, cr=args.cr, friction=args.friction,
                         journal_material=args.journal, clearance=args.clearance, revolutions=args.revolutions,
                         ideal=args.ideal)
        result = simulate(params, method=args.method, rtol=args.rtol, atol=args.atol, max_step=args.max_step,
                          output_step=args.output_step)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    cols = result.columns
    print(f"slider-crank reference: {params.law}, cr = {params.cr}, friction {params.friction}, "
          f"c = {params.clearance:g} m, {params.revolutions:g} revolutions, {args.method} rtol {args.rtol:g}")
    print(f"  peak contact force  {cols['contact_force'].max():.1f} N")
    print(f"  peak |crank moment| {np.abs(cols['crank_moment']).max():.2f} N m")
    print(f"  impacts             {result.n_impacts}")
    print(f"  rhs evaluations     {result.n_rhs}")
    print(f"  wall time           {result.wall_time:.2f} s")
    if args.csv:
        _write_csv(args.csv, cols)
        print(f"wrote {args.csv}")
    if not result.success:
        print(f"error: {result.message}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
