"""What the command lines of models/ share: one-line warnings and errors, no tracebacks."""
from __future__ import annotations

import os
import sys
import warnings

#: Exit status for bad input (as argparse uses for bad options).
EXIT_BAD_INPUT = 2


def one_line_warnings() -> None:
    """Show warnings (e.g. :class:`exuclear.UnitWarning`) as ``warning: ...`` on stderr."""

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001 - warnings' signature
        print(f"warning: {message}", file=sys.stderr)

    warnings.showwarning = show


def bad_input(err: Exception) -> int:
    """Print ``error: ...`` for bad input and return the exit status."""
    print(f"error: {err}", file=sys.stderr)
    return EXIT_BAD_INPUT


def check_output_dir(option: str, path: str) -> str:
    """Fail before a run, not after it, when ``path`` cannot be (made into) a directory to
    write to: ``ValueError`` naming the command-line ``option``.  Returns ``path``."""
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
    if os.path.isdir(path):
        raise ValueError(f"`{option}` {path!r} is a directory, not a file name")
    check_output_dir(option, os.path.dirname(os.path.abspath(path)))
    return path
