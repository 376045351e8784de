"""The worn profiles of a joint after a run: :class:`WearProfile`, with its polar plot."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass(frozen=True)
class WearProfile:
    """A joint's worn profiles (``handle.wear_profile()``; docs/physics.md section 11).

    A planar joint's profiles are arrays of the nodes; a spatial joint's are 2D, slices x
    nodes, one row per slice from the bearing's end at ``z = -L/2`` (section 11.7):
    :attr:`slices` says how many, :meth:`slice` gives one slice's profiles.

    Attributes
    ----------
    theta : ndarray
        The nodes' angles [rad] in the bearing's joint frame (the journal's profile is on
        the same angles of its own frame).
    bearing, journal : ndarray
        The depth [m] worn off the bearing (radially from its centre) and off the journal
        (along its radius) at each node (a spatial joint's: each slice's row).
    volume : dict
        The worn volume [m^3] of ``"bearing"`` and of ``"journal"`` (a spatial joint's:
        summed over its slices, each of length ``L / N``).
    slip : ndarray
        The slip [m] each bearing node has seen while it carried pressure.
    stability : ndarray
        Each bearing node's sum of the steps' ``k_D K ds`` (eq. (81)): the bound of
        :func:`exuclear.predict_wear` on the cycles one update may extrapolate.
    journal_radius, bearing_radius, length : float
        The unworn geometry [m] (``length`` the bearing's whole length ``L``).
    """

    theta: np.ndarray
    bearing: np.ndarray
    journal: np.ndarray
    slip: np.ndarray
    stability: np.ndarray
    journal_radius: float
    bearing_radius: float
    length: float
    volume: dict[str, float] = field(init=False)

    def __post_init__(self) -> None:
        d = 2.0 * math.pi / len(self.theta)
        r_b, r_j, length = self.bearing_radius, self.journal_radius, self.length / max(self.slices, 1)
        volume = {"bearing": float(0.5 * length * d * np.sum((r_b + self.bearing) ** 2 - r_b * r_b)),
                  "journal": float(0.5 * length * d * np.sum(r_j * r_j - (r_j - self.journal) ** 2))}
        object.__setattr__(self, "volume", volume)

    @property
    def slices(self) -> int:
        """The spatial joint's slices (the rows of the profiles); 0 for the planar joint."""
        return self.bearing.shape[0] if np.ndim(self.bearing) == 2 else 0

    def slice(self, k: int) -> WearProfile:
        """Slice ``k``'s profiles of a spatial joint, as a planar joint's of length ``L / N``."""
        if not self.slices:
            raise ValueError("a planar joint's profiles have no slices")
        return WearProfile(self.theta, self.bearing[k], self.journal[k], self.slip[k], self.stability[k],
                           self.journal_radius, self.bearing_radius, self.length / self.slices)

    def deepest(self, surface: str = "bearing") -> tuple[float, float]:
        """The largest depth [m] of ``surface`` and its angle [rad] (in its own frame); a
        spatial joint's over all its slices (per slice: :meth:`slice`)."""
        depth = self._depth(surface)
        k = int(np.argmax(depth)) % len(self.theta)
        return float(np.max(depth)), float(self.theta[k])

    def _depth(self, surface: str) -> np.ndarray:
        if surface not in ("bearing", "journal"):
            raise ValueError(f"`surface` must be 'bearing' or 'journal', got {surface!r}")
        return self.bearing if surface == "bearing" else self.journal

    def plot(self, ax: Any = None, surface: str = "bearing", unit: float = 1e-6, label: str | None = None) -> Any:
        """A polar plot of the depth of ``surface`` (in ``unit`` metres, default um) over
        the angle, a spatial joint's slice by slice; returns the matplotlib axes (a new polar
        one where ``ax`` is None)."""
        import matplotlib.pyplot as plt

        depth = self._depth(surface)
        if ax is None:
            ax = plt.figure(figsize=(4.5, 4.5)).add_subplot(projection="polar")
        theta = np.append(self.theta, self.theta[0] + 2.0 * math.pi)
        for k, row in enumerate(np.atleast_2d(depth)):
            name = label if not self.slices else f"{label + ' ' if label else ''}slice {k}"
            ax.plot(theta, np.append(row, row[0]) / unit, lw=1.2 if not self.slices else 0.8, label=name)
        # depth 0 on a circle, as the unworn surface: the map reads as the worn outline
        ax.set_rorigin(-0.5 * max(ax.get_ylim()[1], float(depth.max()) / unit))
        ax.set_title(f"{surface} wear depth [{'um' if unit == 1e-6 else f'{unit:g} m'}]", fontsize=10)
        return ax
