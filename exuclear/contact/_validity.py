"""The warning of a contact model used outside its source's range, and the one call that issues it."""
from __future__ import annotations

import warnings


class ValidityWarning(UserWarning):
    """A contact model used outside the range its source established it for."""


def _warn_validity(message: str) -> None:
    warnings.warn(message, ValidityWarning, stacklevel=5)
