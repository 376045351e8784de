"""The command line ``exuclear bifurcation SCENE``: an orbit diagram of a scene over one
parameter (:func:`~exuclear.nonlinear.orbit_diagram`), its table and its figures.

::

    exuclear bifurcation slider-crank --parameter crank_speed --values 40:120:5 --periods 100 \\
        --transient 100 --exponent --scheduler local --out results/bifurcation.csv
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .diagram import RUN_KEYS


def _parser() -> argparse.ArgumentParser:
    from ..study.cli import _Parser

    ap = _Parser(prog="exuclear bifurcation", description="Orbit (bifurcation) diagram of a scene over one parameter: "
                 "each value run for --transient + --periods driving periods and sampled once per period; the table "
                 "(CSV, resumed when run again) and the figures next to it.")
    ap.add_argument("scene", help="a scene's short name (slider-crank) or a module path with driven(values) "
                    "(exuclear.models.driven_pendulum)")
    ap.add_argument("--parameter", required=True, help="the parameter swept (slider-crank: a SliderCrankParams field "
                    "such as crank_speed [rad/s] or clearance [m], or rpm)")
    ap.add_argument("--values", required=True, help="its values: a,b,c or start:stop:step (stop included)")
    ap.add_argument("--periods", type=int, required=True, help="periods sampled per value")
    ap.add_argument("--transient", type=int, default=0, help="periods run first and left out (default %(default)s)")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="another parameter, the same for every value (repeatable)")
    ap.add_argument("--exponent", action="store_true", help="also the largest Lyapunov exponent (twice the cost)")
    ap.add_argument("--perturbation", type=float, default=1e-6, help="the exponent's distance d0 (default %(default)s)")
    ap.add_argument("--sweep", action="store_true", help="up and down carrying the state over (hysteresis), in "
                    "this process, instead of independent values")
    ap.add_argument("--observable", help="what the figures show (default: the first the model records)")
    ap.add_argument("--workers", type=int, help="local worker processes (default: all cores; 1: serial), or the "
                    "workers of --scheduler local")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address (tcp://host:8786), or 'local'")
    ap.add_argument("--out", required=True, metavar="FILE.csv", help="the table; an existing one is resumed")
    ap.add_argument("--no-figures", action="store_true", help="the table only")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    return ap


def _fixed(items: list[str]) -> dict:
    from ..study.spec import _number

    fixed = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise ValueError(f"`--set` is NAME=VALUE, got {item!r}")
        fixed[name.strip()] = _number(value.strip())
    return fixed


def _figures(table, parameter: str, observable: str | None, out: Path) -> list[Path]:
    from .plot import bifurcation, exponent_plot

    columns = [c for c in table.columns if c not in (parameter, *RUN_KEYS)]
    recorded = [c for c in columns if len(table) and isinstance(table[c].iloc[0], list)
                and c not in ("section_times", "final_q", "final_v")]
    if observable is not None and observable not in recorded:
        raise ValueError(f"`--observable` {observable!r} is not recorded; recorded: {', '.join(recorded)}")
    written = []
    for name in [observable] if observable else recorded[:1]:
        path = out.with_name(f"{out.stem}_{name.replace('.', '_')}.png")
        written.append(Path(bifurcation(table, parameter, name, path=path)))
    if "exponent" in table.columns and table["exponent"].astype(float).notna().any():
        written.append(Path(exponent_plot(table, parameter, path=out.with_name(f"{out.stem}_exponent.png"))))
    return written


def main(argv: list[str] | None = None) -> int:
    """Run ``exuclear bifurcation ...``; returns the exit status."""
    from ..study.cli import guarded
    from ..study.spec import parse_values
    from .diagram import orbit_diagram

    args = _parser().parse_args(argv)
    out = Path(args.out)

    def work():
        table = orbit_diagram(args.scene, args.parameter, parse_values(args.values), periods=args.periods,
                              transient_periods=args.transient, fixed=_fixed(args.set), exponent=args.exponent,
                              perturbation=args.perturbation, sweep=args.sweep, out=out, workers=args.workers,
                              scheduler=args.scheduler, progress=not args.no_progress)
        return table, [] if args.no_figures else _figures(table, args.parameter, args.observable, out)

    done, status = guarded(work)
    if status is not None:
        return status
    table, figures = done
    failed = int((~table["success"].astype(bool)).sum())
    for _, row in table.iterrows():
        where = f" {row['direction']}" if "direction" in table.columns else ""
        print(f"{args.parameter} = {row[args.parameter]}{where}: {row['verdict'] or row['message']}")
    print(f"{len(table)} runs, {failed} failed; table {out}" + "".join(f"; figure {p}" for p in figures))
    return 0


if __name__ == "__main__":
    sys.exit(main())
