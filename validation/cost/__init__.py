"""The cost, timing and step-accuracy scripts, under one command line::

    python -m validation.cost                  # lists the scripts
    python -m validation.cost NAME [options]   # runs one; NAME --help shows its options

Each script is a module of this package with a ``main(argv)``; the name on the command
line is the module's name (:data:`SCRIPTS`).  Their timings come from a shared machine:
each script says how it repeats and medians them, and writes or prints what it measured,
so that a number quoted elsewhere names the script that gives it.

- ``benchmark``: the native connector's speed targets, side by side in one run;
- ``work_precision``: wall time against error for every formulation and setting (the
  slider-crank's defaults are chosen from it);
- ``study_benchmark``, ``speed_sweep``: the study runner's throughput and its showcase
  sweep over crank speed;
- ``film``, ``friction``, ``jacobian``, ``newton``: what the film, friction, one Newton
  Jacobian and the Newton iterations cost;
- ``spectral_radius``, ``jacobian_steps``: the generalized-alpha method's damping and the
  joint's Jacobian per step, against cost;
- ``fine_steps``: accuracy at the user's own steps against the SciPy reference.
"""
from __future__ import annotations

import ast
import importlib
import pkgutil
import sys
from pathlib import Path

#: The scripts by command name: every module of this package not starting with ``_``.
SCRIPTS = tuple(sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_")))

USAGE = "usage: python -m validation.cost NAME [options]   (python -m validation.cost NAME --help: its options)"


def summary(name: str) -> str:
    """The first paragraph of script ``name``'s docstring, read without importing it (the
    scripts import Exudyn and build models at import)."""
    source = Path(__file__).with_name(f"{name}.py").read_text(encoding="utf-8")
    return " ".join((ast.get_docstring(ast.parse(source)) or "").split("\n\n")[0].split())


def listing() -> str:
    """The usage line and one line per script."""
    width = max(map(len, SCRIPTS))
    return "\n".join([USAGE, "", "scripts:"] + [f"  {name:{width}s}  {summary(name)}" for name in SCRIPTS])


def main(argv: list[str] | None = None) -> int:
    """Run the script named by ``argv[0]`` with the rest of ``argv``; its exit status.

    No name, ``-h`` or ``--help``: the listing, status 0.  An unknown name: the listing on
    stderr, status 2 (as argparse does for a bad option).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(listing())
        return 0
    name, rest = argv[0], argv[1:]
    if name not in SCRIPTS:
        print(f"{listing()}\n\nerror: unknown script {name!r}; known: {', '.join(SCRIPTS)}", file=sys.stderr)
        return 2
    status = importlib.import_module(f"{__name__}.{name}").main(rest)
    return 0 if status is None else int(status)
