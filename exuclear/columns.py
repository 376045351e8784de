"""What a column of a table holds: its label, its unit and its other spellings.

One small type that the study runner (:mod:`exuclear.study`: option help, axis labels of
its plots) and the scenes (their command lines and study columns) both read, so that
neither has to import the other's internals.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Column:
    """What a column of a study table holds: a parameter's option help and other
    spellings, and the axis label of a plot (:mod:`exuclear.study.plot`).

    Parameters
    ----------
    label : str
        What the value is, without its unit (``"radial clearance"``).
    unit : str
        Its unit (``"m"``, ``"N"``, ``"rpm"``); empty for a number without one.
    aliases : tuple of str
        Other names of a parameter, as the scene's command line spells them too
        (``("length",)`` for ``bearing_length``): accepted by :meth:`exuclear.study.Study.complete`
        and as options (``--length``).
    """

    label: str
    unit: str = ""
    aliases: tuple[str, ...] = ()

    @property
    def axis_label(self) -> str:
        """``"label [unit]"``, or the label alone."""
        return f"{self.label} [{self.unit}]" if self.unit else self.label

