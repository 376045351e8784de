"""``python -m validation.exudyn_examples [--quick] [--group beyond | --models a,b] [--out DIR]``: run the
zoo (by default its table, the group "zoo"; ``--group beyond``: more of Exudyn's examples)."""
from __future__ import annotations

import argparse
from pathlib import Path

from ._common import DEFAULT_GROUP, GROUPS
from ._table import run_zoo, show


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m validation.exudyn_examples", description=__doc__)
    ap.add_argument("--quick", action="store_true", help="one run per timing, no convergence check, shorter time limit")
    ap.add_argument("--group", default=DEFAULT_GROUP, choices=list(GROUPS),
                    help=f"the group of models to run (default: {DEFAULT_GROUP}, the zoo's table)")
    ap.add_argument("--models", default="", help="comma-separated model names of any group (default: the group's)")
    ap.add_argument("--end-time", type=float, default=None, help="end time [s] for every model (default: the examples')")
    ap.add_argument("--no-convergence", action="store_true", help="skip the convergence check of the full run")
    ap.add_argument("--out", type=Path, default=None,
                    help="output folder (default: results/exudyn_examples, for another group _<group> appended)")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = Path("results/exudyn_examples" + ("" if args.group == DEFAULT_GROUP else f"_{args.group}"))
    names = [n.strip() for n in args.models.split(",") if n.strip()]
    try:
        table = run_zoo(names, quick=args.quick, convergence=not args.no_convergence, end_time=args.end_time,
                        out=args.out, group=args.group)
    except ValueError as err:  # an unknown model name
        ap.error(str(err))
    print(show(table))
    print(f"written: {args.out / 'zoo.csv'}, {args.out / 'report.md'}")


if __name__ == "__main__":
    main()
