"""What the command lines of models/ share: one-line warnings and errors, no tracebacks."""
from __future__ import annotations

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
