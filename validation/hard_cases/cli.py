"""Hard cases: numerical stability of the clearance joint at the edges of its use.

The command line of :mod:`validation.hard_cases`.
"""
from __future__ import annotations

import argparse
import sys

from validation._cli import add_workers_option
from validation.hard_cases.cases import run_study
from validation.hard_cases.common import DEFAULT_OUT
from validation.hard_cases.report import write_outputs


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.hard_cases", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="directory of the report (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="shorter runs (under a minute)")
    add_workers_option(ap)
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the study and write the report; 1 if a case failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    study = run_study(quick=args.quick, workers=args.workers)
    for path in write_outputs(study, args.out):
        print(f"wrote {path}")
    print(f"total runtime {study.runtime:.1f} s")
    for row in study.failures():
        print(f"error: FAILING: {row.case.title}: {row.outcome.measured}", file=sys.stderr)
    return 1 if study.failures() else 0


if __name__ == "__main__":
    sys.exit(main())
