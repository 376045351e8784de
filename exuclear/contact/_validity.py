"""The one call that warns of a contact model used outside its source's range
(:class:`~exuclear.exceptions.ValidityWarning`)."""
from __future__ import annotations

from ..checks import warn_at_caller
from ..exceptions import ValidityWarning


def _warn_validity(message: str) -> None:
    warn_at_caller(message, ValidityWarning)
