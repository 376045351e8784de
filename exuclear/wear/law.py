"""What a worn joint is given: :class:`Wear`, the local Archard law and how it is applied.

docs/physics.md section 11 states the physics.  Pure Python (no exudyn).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..checks import check_positive, warn_unit

#: The surfaces that can wear.
SURFACES = ("bearing", "journal", "both")
#: The pressure distributions over the contact arc (docs/physics.md section 11.2).
PRESSURES = ("winkler", "hertz")
#: Profile nodes around the circumference by default (0.5 degree apart).
NODES_DEFAULT = 720
#: Fewer nodes than this cannot resolve a contact arc of a few degrees.
NODES_MIN = 16
#: Wear coefficients ``k_D = k / H`` above this [1/Pa] are legal (an accelerated test) but
#: look like the dimensionless ``k`` (1e-8 to 1e-2) given instead: mild steel on mild steel
#: has ``k_D`` of about 3.5e-12 1/Pa (k = 7e-3, H = 2 GPa).
COEFFICIENT_WARN_ABOVE = 1e-6


@dataclass(frozen=True)
class Wear:
    """Wear of a clearance joint by the local Archard law ``dh = k_D p ds`` (docs/physics.md
    section 11), given as ``wear=`` to :func:`exuclear.make_joint`,
    :func:`exuclear.CreateClearanceJoint` or :func:`exuclear.AddClearanceJoint`.

    Parameters
    ----------
    coefficient : float
        The dimensional wear coefficient ``k_D = k / H`` [1/Pa] (``k`` Archard's
        dimensionless coefficient, ``H`` the hardness of the softer surface).
    surface : str
        Which surfaces wear: ``"bearing"`` (default), ``"journal"`` or ``"both"`` (each with
        ``coefficient``).
    nodes : int
        Nodes of each surface's depth profile around the circumference (default 720).
    pressure : str
        The pressure over the contact arc: ``"winkler"`` (default; an elastic foundation on
        the worn profiles) or ``"hertz"`` (the Hertz strip of two circles), section 11.2.
    bearing, journal : sequence of float, optional
        Depth profiles [m] to start from (``nodes`` values each, >= 0; the bearing's in its
        joint frame, the journal's in its own), e.g. those :func:`exuclear.predict_wear`
        extrapolated; default unworn.  For a spatial joint also ``slices`` x ``nodes``
        values, one row per slice (docs/physics.md section 11.7; the joint checks the rows
        against its slices); one row: every slice starts from it.
    """

    coefficient: float
    surface: str = "bearing"
    nodes: int = NODES_DEFAULT
    pressure: str = "winkler"
    bearing: tuple[float, ...] | tuple[tuple[float, ...], ...] | None = None
    journal: tuple[float, ...] | tuple[tuple[float, ...], ...] | None = None

    def __post_init__(self) -> None:
        k = check_positive("coefficient", self.coefficient)
        if k > COEFFICIENT_WARN_ABOVE:
            warn_unit(f"the wear coefficient {k:.3g} 1/Pa is above {COEFFICIENT_WARN_ABOVE:g}: it is k_D = k / H in "
                      "1/Pa (mild steel: about 3.5e-12); was the dimensionless k given?")
        if self.surface not in SURFACES:
            raise ValueError(f"unknown `surface` {self.surface!r}; known: {', '.join(SURFACES)}")
        if self.pressure not in PRESSURES:
            raise ValueError(f"unknown `pressure` {self.pressure!r}; known: {', '.join(PRESSURES)}")
        if isinstance(self.nodes, bool) or not isinstance(self.nodes, int) or self.nodes < NODES_MIN:
            raise ValueError(f"`nodes` must be a whole number >= {NODES_MIN}, got {self.nodes!r}")
        for name in ("bearing", "journal"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _profile(name, value, self.nodes))
        if self.journal is not None and not self.wears_journal and _worn(self.journal):
            raise ValueError("a worn `journal` profile is given but only the bearing wears (`surface='bearing'`): "
                             "give surface='journal' or 'both', or leave `journal` out")
        if self.bearing is not None and not self.wears_bearing and _worn(self.bearing):
            raise ValueError("a worn `bearing` profile is given but only the journal wears (`surface='journal'`): "
                             "give surface='bearing' or 'both', or leave `bearing` out")

    @property
    def wears_bearing(self) -> bool:
        return self.surface in ("bearing", "both")

    @property
    def wears_journal(self) -> bool:
        return self.surface in ("journal", "both")

    def starting_from(self, bearing: Any, journal: Any) -> Wear:
        """The same wear, starting from the depth profiles ``bearing`` and ``journal`` [m]
        (``nodes`` values, or ``slices`` x ``nodes`` for a spatial joint)."""
        return replace(self, bearing=bearing, journal=journal)

    def profile_rows(self, name: str) -> int:
        """The rows of the starting profile ``name`` (``"bearing"`` or ``"journal"``): 0 where
        it is one profile (or none), else its slices."""
        value = getattr(self, name)
        return len(value) if value is not None and isinstance(value[0], tuple) else 0

    def profile_row(self, name: str, row: int) -> tuple[float, ...]:
        """The starting profile ``name`` of slice ``row``: its row of a slices x nodes
        profile, the one profile for every slice."""
        value = getattr(self, name)
        return value[row] if self.profile_rows(name) else value


def _worn(value: tuple) -> bool:
    return any(any(row) if isinstance(row, tuple) else row for row in value)


def _profile(name: str, values: Any, nodes: int) -> tuple[float, ...] | tuple[tuple[float, ...], ...]:
    """``values`` as a tuple of ``nodes`` finite depths >= 0, or as a tuple of such rows
    (slices x nodes), or ``ValueError`` naming ``name``."""
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be a sequence of {nodes} depths [m] (or slices x {nodes})") from None
    if array.ndim not in (1, 2) or array.shape[-1] != nodes or array.shape[0] == 0:
        got = array.shape[0] if array.ndim == 1 else f"shape {array.shape}"
        raise ValueError(f"`{name}` must have `nodes` = {nodes} depths, got {got} (a spatial joint's: slices x "
                         f"{nodes})")
    if not np.all(np.isfinite(array) & (array >= 0.0)):
        raise ValueError(f"`{name}` depths must be finite and >= 0 [m]")
    if array.ndim == 1:
        return tuple(float(v) for v in array)
    return tuple(tuple(float(v) for v in row) for row in array)
