"""The command line ``python -m exuclear.study``: a scene's sweep (each parameter an
option taking a value, a list or a range) and ``plot`` of a study table."""
from __future__ import annotations

import argparse
import os
import re
import sys
import warnings
from collections.abc import Callable
from typing import Any

from .batch import warned
from .runner import run_study
from .scenes import scene, scene_names
from .spec import Params, Study, _number, grid, parse_bounds, parse_values, sample
from .table import load_table


def _option(name: str) -> str:
    return "--" + name.replace("_", "-")


#: What the study's parsers take for a negative value, not an option: "-" and a digit
#: (``-1e-4``, ``-.5``, ``-2:0:1``, ``-1,0,1``), ``-inf``, ``-nan``.  argparse's own pattern
#: (Python < 3.13) misses the exponent and list forms, and ``--clearance -1e-4`` was
#: "expected one argument" instead of the rule the value breaks.
_NEGATIVE_VALUE = re.compile(r"^-(\.?\d|inf|nan)", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` that reads negative numbers (:data:`_NEGATIVE_VALUE`) as values."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_VALUE  # argparse's hook for what a negative number is


def _scene_parser(study: Study, prog: str) -> argparse.ArgumentParser:
    ap = _Parser(
        prog=prog, description=f"Sweep the {study.name} scene: each parameter option takes one value, a list "
        "a,b,c or a range start:stop:step (stop included); with --sample N, low:high bounds to draw from.")
    columns = study.columns or {}
    for name, default in (study.parameters or {}).items():
        column = columns.get(name)
        flags = [_option(name)] + [_option(alias) for alias in (column.aliases if column else ())]
        what = f"{column.axis_label}; " if column else ""
        ap.add_argument(*flags, dest=name, metavar="VALUES", help=f"{what}default {default!r}".replace("%", "%%"))
    ap.add_argument("--sample", type=int, metavar="N", help="draw N parameter sets in the low:high bounds "
                    "instead of the grid")
    # not --method, which on the scenes' command lines is the solver
    ap.add_argument("--sampling", choices=("lhs", "random"), default="lhs",
                    help="how --sample draws: Latin hypercube or independent uniform (default %(default)s)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the sample (default %(default)s)")
    ap.add_argument("--workers", type=int, help="local worker processes (default: all cores; 1: serial), or the "
                    "workers of --scheduler local")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address (tcp://host:8786), or 'local' "
                    "for a Dask LocalCluster")
    ap.add_argument("--batch-size", type=int, help="runs per task (default: about 1 s of work)")
    ap.add_argument("--retry-failed", action="store_true", help="redo the runs that failed in an existing table")
    ap.add_argument("--out", required=True, metavar="FILE.csv", help="the study's table; an existing one is resumed")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    return ap


def _runs_from_args(study: Study, args: argparse.Namespace) -> list[Params]:
    given = {name: getattr(args, name) for name in (study.parameters or {}) if getattr(args, name) is not None}
    if args.sample is None:
        axes = {}
        for name, text in given.items():
            try:
                axes[name] = parse_values(text)
            except ValueError as err:
                raise ValueError(f"`{_option(name)}`: {err}") from None
        return grid(**axes)
    bounds, fixed = {}, {}
    for name, text in given.items():
        if ":" in text:
            try:
                bounds[name] = parse_bounds(text)
            except ValueError as err:
                raise ValueError(f"`{_option(name)}`: {err}") from None
        else:
            values = parse_values(text)
            if len(values) != 1:
                raise ValueError(f"`{_option(name)}`: with --sample, give low:high bounds or one value, got {text!r}")
            fixed[name] = values[0]
    return sample(bounds, args.sample, seed=args.seed, method=args.sampling, fixed=fixed)


def _plot_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="python -m exuclear.study plot",
                                 description="Plot a metric of a study table over one parameter (lines, one per "
                                 "value of --by) or two (heat map, --y).")
    ap.add_argument("table", help="the study's CSV")
    ap.add_argument("--metric", required=True, help="column to plot")
    ap.add_argument("--x", required=True, help="parameter on the horizontal axis")
    ap.add_argument("--y", help="second parameter: a heat map")
    ap.add_argument("--by", help="one line (or point set) per value of this parameter")
    ap.add_argument("--points", action="store_true", help="markers only (a bifurcation-style diagram)")
    ap.add_argument("--where", action="append", default=[], metavar="NAME=VALUE",
                    help="keep the rows with this parameter value (repeatable)")
    ap.add_argument("--scene", help="the scene whose study made the table, for axis labels with units (default: the "
                    "installed scene whose parameters are all columns of the table)")
    ap.add_argument("--logx", action="store_true")
    ap.add_argument("--logy", action="store_true")
    ap.add_argument("--out", required=True, metavar="FILE", help="figure file (png, pdf, svg)")
    return ap


def _scene_of(table) -> Study | None:
    """The installed scene (:func:`scene_names`) whose parameters are all columns of
    ``table``, if exactly one is; None otherwise."""
    found = []
    for name in scene_names():
        try:
            study = scene(name)
        except ValueError:  # a broken entry point does not stop a plot
            continue
        if study.parameters and set(study.parameters) <= set(table.columns):
            found.append(study)
    return found[0] if len(found) == 1 else None


def _plot_main(argv: list[str]) -> int:
    args = _plot_parser().parse_args(argv)
    try:
        from .plot import plot_metric

        table = load_table(args.table)
        where = {}
        for item in args.where:
            name, sep, value = item.partition("=")
            if not sep:
                raise ValueError(f"`--where` is NAME=VALUE, got {item!r}")
            where[name] = _number(value)
        study = scene(args.scene) if args.scene else _scene_of(table)
        path = plot_metric(table, args.metric, args.x, y=args.y, by=args.by, where=where, points=args.points,
                           logx=args.logx, logy=args.logy, path=args.out, columns=study.columns if study else None)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print(f"wrote {path}")
    return 0


def _one_line_warnings() -> None:
    """Show warnings of the parameter checks (a unit slip, before any run) as one line
    ``warning: ...`` on stderr, as the scenes' command lines do; the runs' own warnings go
    into their rows."""

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001 - warnings' signature
        print(f"warning: {category.__name__}: {message}", file=sys.stderr)

    warnings.showwarning = show


def main(argv: list[str] | None = None) -> int:
    """``python -m exuclear.study SCENE [options]`` or ``python -m exuclear.study plot TABLE ...``."""
    argv = list(sys.argv[1:] if argv is None else argv)
    prog = "python -m exuclear.study"
    if not argv or argv[0] in ("-h", "--help"):
        names = ", ".join(sorted(scene_names())) or "none installed"
        print(f"usage: {prog} SCENE [--PARAMETER VALUES ...] --out FILE.csv   (SCENE: {names}, "
              f"or a module path)\n       {prog} SCENE --help\n       {prog} plot TABLE --metric M "
              f"--x P [--by P | --y P] --out FIG")
        return 0 if argv else 2
    if argv[0] == "plot":
        return _plot_main(argv[1:])
    with warnings.catch_warnings():  # the caller's way of showing warnings comes back after it
        _one_line_warnings()
        return _scene_main(argv, prog)


def _scene_main(argv: list[str], prog: str) -> int:
    """``python -m exuclear.study SCENE [options]``."""
    try:
        study = scene(argv[0])
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    args = _scene_parser(study, f"{prog} {argv[0]}").parse_args(argv[1:])
    table, status = guarded(lambda: run_study(
        study, _runs_from_args(study, args), args.out, workers=args.workers, scheduler=args.scheduler,
        batch_size=args.batch_size, retry_failed=args.retry_failed, progress=not args.no_progress))
    if status is not None:
        return status
    print(_summary_line(table, args.out))
    return 0


def guarded(work: Callable[[], Any]) -> tuple[Any, int | None]:
    """Run a command line's ``work``: its result and None, or, on bad input (``ValueError``),
    one line ``error: ...`` on stderr and status 2, on Ctrl-C the runner's message (where
    the finished rows are) and status 130."""
    try:
        return work(), None
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return None, 2
    except KeyboardInterrupt as err:
        print(f"{err or 'interrupted'}", file=sys.stderr)
        return None, 130


def _summary_line(table, out: str | os.PathLike) -> str:
    """The command line's last line: runs made now and taken from the file, failed runs,
    and runs with warnings (:func:`warned`)."""
    failed = int((~table["success"].astype(bool)).sum())
    with_warnings = int(warned(table).sum()) if len(table) else 0
    ran, resumed = table.attrs.get("ran", len(table)), table.attrs.get("resumed", 0)
    runs = f"{len(table)} runs ({ran} ran now, {resumed} taken from {out})" if resumed else f"{len(table)} runs"
    warns = f", {with_warnings} with warnings (see their message)" if with_warnings else ""
    return f"{runs}, {failed} failed{warns}; table {out}"
