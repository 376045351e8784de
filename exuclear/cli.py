"""The ``exuclear`` console command: one entry point for the command lines of the paper's
scenes and of the study runner.

::

    exuclear slider-crank [options]        # = python -m exuclear.models.slider_crank [options]
    exuclear journal-bearing [options]     # = python -m exuclear.models.journal_bearing [options]
    exuclear study SCENE [options]         # = python -m exuclear.study SCENE [options]
    exuclear bifurcation SCENE [options]   # = python -m exuclear.nonlinear.cli SCENE [options]

Each subcommand hands its arguments unchanged to that module's ``main``, so the options,
the output and the exit status are the ``python -m`` form's (``exuclear slider-crank
--help`` lists them).  Bad input exits with status 2 and one line ``error: ...`` on stderr.
``pip install`` makes the command (``[project.scripts]`` in pyproject.toml);
``python -m exuclear.cli`` is the same without it.
"""
from __future__ import annotations

import importlib
import sys

#: Exit status for bad input, as argparse and the scenes' command lines use.
EXIT_BAD_INPUT = 2

#: Subcommand -> (module whose ``main(argv)`` runs it, what it does).
SUBCOMMANDS: dict[str, tuple[str, str]] = {
    "slider-crank": ("exuclear.models.slider_crank", "the paper's slider-crank with a clearance joint at B "
                     "(or the ideal mechanism, --ideal)"),
    "journal-bearing": ("exuclear.models.journal_bearing", "the paper's journal-bearing impact (with oil: "
                        "--viscosity)"),
    "study": ("exuclear.study", "a parameter study of a scene (grid or sample, CSV table, progress bar), "
                                "or `study plot TABLE ...`"),
    "bifurcation": ("exuclear.nonlinear.cli", "an orbit (bifurcation) diagram of a scene over one parameter: Poincare "
                    "samples, verdicts, Lyapunov exponents, table and figures"),
}


def usage() -> str:
    """The text of ``exuclear --help``."""
    width = max(map(len, SUBCOMMANDS))
    lines = ["usage: exuclear SUBCOMMAND [options]", "", "Clearance joints for Exudyn: the paper's scenes "
             "and parameter studies from the command line.", "", "subcommands:"]
    lines += [f"  {name:<{width}}  {what}" for name, (_, what) in SUBCOMMANDS.items()]
    lines += ["", "options:", f"  {'-h, --help':<{width}}  this message; `exuclear SUBCOMMAND --help` lists a "
              "subcommand's options", f"  {'--version':<{width}}  the installed exuclear version", "",
              "Each subcommand is the same as `python -m MODULE`: " + ", ".join(
                  f"{name} = {module}" for name, (module, _) in SUBCOMMANDS.items()) + "."]
    return "\n".join(lines)


def _bad_input(message: str) -> int:
    print(f"error: {message} (see exuclear --help)", file=sys.stderr)
    return EXIT_BAD_INPUT


def main(argv: list[str] | None = None) -> int:
    """Run ``exuclear SUBCOMMAND [options]``; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv:
        return _bad_input("give a subcommand: " + ", ".join(SUBCOMMANDS))
    command, rest = argv[0], argv[1:]
    if command in ("-h", "--help"):
        print(usage())
        return 0
    if command == "--version":
        from exuclear import __version__

        print(f"exuclear {__version__}")
        return 0
    if command not in SUBCOMMANDS:
        return _bad_input(f"unknown subcommand {command!r}; choose from " + ", ".join(SUBCOMMANDS))
    module = importlib.import_module(SUBCOMMANDS[command][0])  # on demand: `exuclear --help` imports no scene
    return module.main(rest)


if __name__ == "__main__":
    sys.exit(main())
