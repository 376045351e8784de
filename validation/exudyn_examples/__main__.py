"""``python -m validation.exudyn_examples [--quick] [--models a,b] [--out DIR]``: run the zoo."""
from __future__ import annotations

import argparse
from pathlib import Path

from ._table import run_zoo, show


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m validation.exudyn_examples", description=__doc__)
    ap.add_argument("--quick", action="store_true", help="one run per timing, no convergence check, shorter time limit")
    ap.add_argument("--models", default="", help="comma-separated model names (default: all registered)")
    ap.add_argument("--end-time", type=float, default=None, help="end time [s] for every model (default: the examples')")
    ap.add_argument("--no-convergence", action="store_true", help="skip the convergence check of the full run")
    ap.add_argument("--out", type=Path, default=Path("results/exudyn_examples"), help="output folder")
    args = ap.parse_args(argv)
    names = [n.strip() for n in args.models.split(",") if n.strip()]
    try:
        table = run_zoo(names, quick=args.quick, convergence=not args.no_convergence, end_time=args.end_time,
                        out=args.out)
    except ValueError as err:  # an unknown model name
        ap.error(str(err))
    print(show(table))
    print(f"written: {args.out / 'zoo.csv'}, {args.out / 'report.md'}")


if __name__ == "__main__":
    main()
