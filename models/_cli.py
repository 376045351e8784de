"""What the command lines of the scenes (exuclear.models) share: one-line warnings and errors, no tracebacks.

Every scene's ``main(argv)`` is :func:`run_main` with the scene's :class:`SceneRun`: the
steps all scenes take (parse, warnings, bad input, output paths, CSV, "wrote PATH", the
exit status) are here, what is the scene's own (its parameters, its summary, its plots) is
in its ``SceneRun``.
"""
from __future__ import annotations

import argparse
import math
import os
import re
import sys
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple, TextIO

import numpy as np

from exuclear.contact import law_and_restitution

from ._params import add_param_options

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


def scene_parser(name: str, doc: str, defaults: object) -> OneLineParser:
    """The command line of the scene module ``exuclear.models.NAME``, described by the first
    line of its docstring ``doc``: the contact-law options and one option per field of its
    parameters ``defaults`` (their values the defaults).  The scene adds its own options."""
    ap = OneLineParser(prog=f"python -m exuclear.models.{name}", description=doc.split("\n")[0])
    add_law_options(ap, defaults.law, defaults.cr)
    add_param_options(ap, defaults)
    return ap


class Table(NamedTuple):
    """What ``--csv`` writes (:func:`write_csv`): ``columns[name]`` for ``names``, the
    ``incomplete`` note of a run that stopped early and the ``notes`` on its accuracy."""

    columns: Mapping[str, np.ndarray]
    names: Sequence[str]
    incomplete: str = ""
    notes: Sequence[str] = ()


class SceneRun:
    """One run of a scene's command line: the parts that are the scene's own, for :func:`run_main`.

    A scene's subclass sets its parameters (:meth:`prepare`), runs them (:meth:`simulate`,
    keeping the result in :attr:`result`) and says what came of it (:meth:`summary`, and
    :meth:`table`, :meth:`plots`, :meth:`finish` where it has them).  ``args`` are the parsed
    options, ``argv`` the arguments as given.
    """

    #: The run's result: its ``success`` and ``message`` say whether and why the run stopped
    #: early (:attr:`incomplete`, :meth:`errors`).
    result: Any = None

    def __init__(self, args: argparse.Namespace, argv: Sequence[str]) -> None:
        self.args = args
        self.argv = argv

    def prepare(self, law: str, cr: float) -> None:
        """Set the parameters and solver settings from :attr:`args`, with the contact law
        ``law`` and restitution ``cr`` they resolve to; ``ValueError`` for bad input."""
        raise NotImplementedError

    def simulate(self) -> None:
        """Run the scene and keep what :meth:`summary` and the outputs need; ``ValueError``
        for input the scene refuses only once it builds the model."""
        raise NotImplementedError

    def summary(self) -> None:
        """Print what the run gave."""
        raise NotImplementedError

    def table(self) -> Table:
        """What ``--csv`` writes (scenes with that option)."""
        raise NotImplementedError

    def plots(self, directory: str) -> list[str]:
        """Write the figures of ``--plot`` to ``directory``; returns their paths (scenes with
        that option)."""
        raise NotImplementedError

    def finish(self) -> None:
        """What the scene does after its outputs are written (a further check)."""

    @property
    def incomplete(self) -> str:
        """Why the run stopped early, or "" where it reached its end."""
        return "" if self.result.success else self.result.message

    def errors(self) -> list[str]:
        """The messages of the runs that stopped early: ``error: ...`` lines and exit status 1."""
        return [self.incomplete] if self.incomplete else []

    @property
    def notices(self) -> TextIO:
        """Where ``wrote PATH`` goes: stdout, or stderr where stdout is the data (``--json``)."""
        return sys.stderr if getattr(self.args, "json", False) else sys.stdout


def run_main(argv: Sequence[str] | None, parser: argparse.ArgumentParser,
             scene_run: Callable[[argparse.Namespace, Sequence[str]], SceneRun]) -> int:
    """A scene's ``main``: parse ``argv`` (default the process's arguments) with ``parser``
    (:func:`scene_parser`), make the scene's :class:`SceneRun` with ``scene_run(args, argv)``,
    run it and write its outputs; returns the exit status.

    Bad input, found before the run or when the model is built, is one line ``error: ...``
    and status :data:`EXIT_BAD_INPUT`; the output paths (``--csv`` a file, ``--plot`` a
    directory; folders that do not exist yet are made) are checked once the parameters are,
    before the run.  A run that stopped early still writes what it reached (the CSV with its
    ``# INCOMPLETE`` line first), then ``error: MESSAGE`` and status 1.
    """
    given = list(sys.argv[1:] if argv is None else argv)
    args = parser.parse_args(given)
    one_line_warnings()
    csv, plot = getattr(args, "csv", None), getattr(args, "plot", None)
    try:
        law, cr = law_and_restitution(args.law, args.stiffness, args.damping, args.cr, args.paper_law,
                                       args.paper_cr)
        scene = scene_run(args, given)
        scene.prepare(law, cr)
        if csv is not None:
            check_output_file("--csv", csv)
        if plot is not None:
            check_output_dir("--plot", plot)
        scene.simulate()
    except ValueError as err:
        return bad_input(err)
    scene.summary()
    if csv is not None:
        os.makedirs(os.path.dirname(os.path.abspath(csv)), exist_ok=True)  # a folder check_output_file let pass
        write_csv(csv, *scene.table())
        print(f"wrote {csv}", file=scene.notices)
    if plot is not None:
        for path in scene.plots(plot):
            print(f"wrote {path}", file=scene.notices)
    scene.finish()
    errors = scene.errors()
    for message in errors:
        print(f"error: {message}", file=sys.stderr)
    return 1 if errors else 0
