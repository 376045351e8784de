"""The one call that warns of a contact model used outside its source's range
(:class:`~exuclear.exceptions.ValidityWarning`)."""
from __future__ import annotations

import warnings

from ..exceptions import ValidityWarning


def _warn_validity(message: str) -> None:
    warnings.warn(message, ValidityWarning, stacklevel=5)
