"""Cross-check of the Exudyn path against the independent SciPy reference solver.

The command line of :mod:`validation.cross_check`.
"""
from __future__ import annotations

import argparse
import sys

from validation._cli import add_workers_option
from validation.cross_check.common import DEFAULT_OUT, QUICK_HORIZON
from validation.cross_check.report import write_outputs
from validation.cross_check.runs import cross_check


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.cross_check", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="directory of the report and CSV tables "
                    "(default %(default)s)")
    ap.add_argument("--quick", action="store_true",
                    help=f"two laws and the first {QUICK_HORIZON:g} s of two slider-crank cases")
    add_workers_option(ap)
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the cross-check and write the report; 1 if a case that must pass failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    x = cross_check(quick=args.quick, workers=args.workers)
    for path in write_outputs(x, args.out):
        print(f"wrote {path}")
    print(f"total runtime {x.runtime:.1f} s")
    failures = x.failures()
    for failure in failures:
        print(f"error: FAILING: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
