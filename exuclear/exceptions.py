"""The warnings exuclear issues, in one module that imports nothing (as ``numpy.exceptions``).

Every other module imports its warning from here, so that a user can filter any of them
(``warnings.simplefilter("error", exuclear.AccuracyWarning)``) without importing the module
that issues it, and so that no module imports another one only for a warning class.
"""
from __future__ import annotations

__all__ = ["AccuracyWarning", "KernelWarning", "OutOfPlaneWarning", "UnitWarning", "ValidityWarning"]


class UnitWarning(UserWarning):
    """A value that is valid but looks like a unit mistake (mm for m, GPa for Pa, ...)."""


class ValidityWarning(UserWarning):
    """A contact model used outside the range its source established it for."""


class AccuracyWarning(UserWarning):
    """A run finished, but its path may not be converged (e.g. numerical contact chatter)."""


class KernelWarning(UserWarning):
    """The compiled kernel cannot be used as intended; exuclear runs the Python kernel."""


class OutOfPlaneWarning(UserWarning):
    """A clearance joint's journal can move along the axis or tilt, and nothing in the
    model holds it (the replaced revolute joint did): see
    :func:`exuclear.engine.unheld_motion`."""
