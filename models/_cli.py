"""What the command lines of the scenes (exuclear.models) share: one-line warnings and errors, no tracebacks."""
from __future__ import annotations

import argparse
import math
import os
import re
import sys
import warnings
from collections.abc import Mapping, Sequence

import numpy as np

#: Exit status for bad input (as argparse uses for bad options).
EXIT_BAD_INPUT = 2

#: What argparse takes for a negative number, a value and not an option: anything that starts
#: with "-" and a digit (``-1e-4``, ``-.5``, ``-2:0:1``) or is ``-inf``/``-nan``.  argparse's
#: own pattern (Python < 3.13) misses the exponent form, so ``--clearance -1e-4`` was "expected
#: one argument" instead of the rule it breaks.  No option of the scenes looks like this.
NEGATIVE_NUMBER = re.compile(r"^-(\.?\d|inf|nan)", re.IGNORECASE)


def one_line_warnings() -> None:
    """Show warnings (e.g. :class:`exuclear.UnitWarning`) as ``warning: ...`` on stderr."""

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001 - warnings' signature
        print(f"warning: {message}", file=sys.stderr)

    warnings.showwarning = show


class OneLineParser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose errors are one line ``error: ...`` (no usage block),
    with exit status :data:`EXIT_BAD_INPUT`, like every other bad input of the command lines.

    A negative number (:data:`NEGATIVE_NUMBER`) is an option's value, so that a negative
    value reaches the rule it breaks (```clearance` must be positive, got -0.0001``)."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER  # argparse's hook for what a negative number is

    def error(self, message: str) -> None:  # noqa: D102 - argparse's hook
        self.exit(EXIT_BAD_INPUT, f"error: {message} (see {self.prog} --help)\n")


def bad_input(err: Exception) -> int:
    """Print ``error: ...`` for bad input and return the exit status."""
    print(f"error: {err}", file=sys.stderr)
    return EXIT_BAD_INPUT


def check_output_dir(option: str, path: str) -> str:
    """Fail before a run, not after it, when ``path`` cannot be (made into) a directory to
    write to, or is empty: ``ValueError`` naming the command-line ``option``.  Returns ``path``."""
    if not path.strip():
        raise ValueError(f"`{option}` must name a directory, got an empty name")
    full = os.path.abspath(path)
    existing = full
    while not os.path.exists(existing):  # the nearest part of the path that exists
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing) or not os.access(existing, os.W_OK | os.X_OK):
        kind = "not a directory" if not os.path.isdir(existing) else "not writable"
        raise ValueError(f"`{option}` {path!r} cannot be written: {existing!r} is {kind}")
    return path


def check_output_file(option: str, path: str) -> str:
    """As :func:`check_output_dir`, for a file to be written at ``path``."""
    if not path.strip():
        raise ValueError(f"`{option}` must name a file, got an empty name")
    if os.path.isdir(path):
        raise ValueError(f"`{option}` {path!r} is a directory, not a file name")
    check_output_dir(option, os.path.dirname(os.path.abspath(path)))
    return path


def write_csv(path: str, columns: Mapping[str, np.ndarray], names: Sequence[str], incomplete: str = "",
              notes: Sequence[str] = ()) -> None:
    """Write the arrays ``columns[name]`` for ``names`` as CSV with a header line.

    ``incomplete``: why the run stopped early; it then goes first, as a comment line
    ``# INCOMPLETE: ...`` before the header.  ``notes``: why the path may not be
    converged, one comment line ``# NOTE: ...`` each, after it.
    """
    data = np.column_stack([columns[name] for name in names])
    comments = [f"# INCOMPLETE: {' '.join(incomplete.split())}"] if incomplete else []
    comments += [f"# NOTE: {' '.join(note.split())}" for note in notes]
    header = "\n".join([*comments, ",".join(names)])
    np.savetxt(path, data, delimiter=",", header=header, comments="", fmt="%.10g")


def add_rpm_option(ap: argparse.ArgumentParser, crank_speed: float) -> None:
    """``--rpm``: the crank speed of a scene in rpm, defaulting to its ``crank_speed`` [rad/s]
    (:func:`exuclear.models._params.crank_speed_from_rpm` reads it back)."""
    ap.add_argument("--rpm", type=float, default=crank_speed * 30.0 / math.pi,
                    help="crank speed [rpm], negative for a clockwise crank (default %(default).0f)")


def add_law_options(ap: argparse.ArgumentParser, law: str, cr: float) -> None:
    """The contact-law options every scene has: ``--law``, ``--stiffness``, ``--damping``,
    ``--cr``, with the scene's own ``law`` and ``cr`` as what they fall back to
    (:func:`exuclear.contact.law_and_restitution` resolves them)."""
    from exuclear.contact import ALIASES, CONTACT_LAWS, DAMPING_MODELS, STIFFNESS_MODELS

    ap.add_argument("--law", help=f"contact law: {', '.join(CONTACT_LAWS)}, or STIFFNESS+DAMPING (default {law})")
    ap.add_argument("--stiffness", help=f"stiffness model, instead of --law: {', '.join(STIFFNESS_MODELS)} "
                                        f"(default with --damping: {ALIASES[law][0]})")
    ap.add_argument("--damping", help=f"damping model, instead of --law: {', '.join(DAMPING_MODELS)} "
                                      f"(default with --stiffness: {ALIASES[law][1]})")
    ap.add_argument("--cr", type=float,
                    help=f"coefficient of restitution in (0, 1] (default {cr}; 1 for the elastic laws)")
    ap.set_defaults(paper_law=law, paper_cr=cr)  # what --law and --cr fall back to
