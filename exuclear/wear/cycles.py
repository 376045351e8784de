"""Wear over many cycles: :func:`predict_wear` runs one cycle with the current profiles,
multiplies its wear by ``dN`` and repeats (docs/physics.md section 11.5)."""
from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..checks import check_positive
from .law import Wear
from .profile import WearProfile

#: The explicit update of the profiles diverges once ``dN`` times a node's ``sum k_D K ds``
#: over the cycle exceeds this (docs/physics.md eq. (81)).
DIVERGENCE_BOUND = 2.0
#: By default ``dN`` is this share of the bound: the error of the profile's shape then
#: halves from one update to the next, without a change of sign.
SAFETY_DEFAULT = 0.5


@dataclass
class WearPrediction:
    """What :func:`predict_wear` returns: after each update, the cycles done, the profiles,
    the ``dN`` of the update and its bound; ``complete`` False where the prediction was
    interrupted (the updates up to there are kept), and its wall time [s]."""

    cycles: list[float] = field(default_factory=list)
    profiles: list[WearProfile] = field(default_factory=list)
    steps: list[float] = field(default_factory=list)
    bounds: list[float] = field(default_factory=list)
    complete: bool = False
    wall_time: float = 0.0

    @property
    def final(self) -> WearProfile:
        """The profiles after the last update."""
        return self.profiles[-1]

    def deepest(self, surface: str = "bearing") -> np.ndarray:
        """The largest depth [m] of ``surface`` after each update."""
        return np.array([p.deepest(surface)[0] for p in self.profiles])


def predict_wear(run_cycle: Callable[[Wear], Any], wear: Wear, cycles: float, *, dN: float | None = None,
                 safety: float = SAFETY_DEFAULT, check_bound: bool = True, progress: bool = True) -> WearPrediction:
    """Predict the wear of ``cycles`` cycles of a mechanism by extrapolating one cycle at a time.

    Parameters
    ----------
    run_cycle : callable
        ``run_cycle(wear)`` builds the model with ``wear=wear`` on its worn joint, runs one
        cycle and returns the joint's handle (whose ``wear_profile()`` is read).
    wear : Wear
        The joint's wear; its ``bearing`` and ``journal`` profiles are where it starts (a
        spatial joint's: slices x nodes, docs/physics.md section 11.7).
    cycles : float
        How many cycles to predict.
    dN : float, optional
        Cycles per update; default ``safety`` times the stability bound of each cycle,
        ``2 / max_k sum k_D K ds`` (eq. (81)), at least 1 (every cycle simulated).
    safety : float
        The share of the bound taken by default, in (0, 1).
    check_bound : bool
        False: take a ``dN`` beyond the bound all the same (to see the update diverge).
    progress : bool
        A progress bar on stderr (tqdm).

    An interrupt (Ctrl-C) ends the prediction with the updates done so far
    (``complete`` False).  ``ValueError`` where a given ``dN`` breaks the bound.
    """
    cycles = check_positive("cycles", cycles)
    if dN is not None:
        check_positive("dN", dN)
    if not 0.0 < safety < 1.0:
        raise ValueError(f"`safety` must lie in (0, 1), got {safety}")
    from tqdm.auto import tqdm

    out = WearPrediction()
    start = time.perf_counter()
    current, done = wear, 0.0
    bar = tqdm(total=cycles, unit="cycle", disable=not progress, file=sys.stderr)
    try:
        while done < cycles:
            profile = run_cycle(current).wear_profile()
            # a spatial joint's profiles are slices x nodes (section 11.7): the start broadcast to them
            before_b = np.zeros_like(profile.bearing) + (current.bearing if current.bearing is not None else 0.0)
            before_j = np.zeros_like(profile.journal) + (current.journal if current.journal is not None else 0.0)
            largest = float(profile.stability.max())
            bound = DIVERGENCE_BOUND / largest if largest > 0.0 else math.inf
            step = max(1.0, math.floor(safety * bound)) if dN is None else dN
            if dN is not None and check_bound and dN > bound:
                raise ValueError(f"`dN` = {dN:g} cycles breaks the stability bound of this cycle, 2 / (sum k_D K ds) = "
                                 f"{bound:.4g} cycles (docs/physics.md eq. (81)): the profile's update would diverge; give "
                                 f"dN <= {bound:.4g}, or leave dN out for {SAFETY_DEFAULT:g} of the bound")
            step = min(step, cycles - done)
            bearing = before_b + step * (profile.bearing - before_b)
            journal = before_j + step * (profile.journal - before_j)
            current = wear.starting_from(bearing if wear.wears_bearing else None,
                                         journal if wear.wears_journal else None)
            done += step
            out.cycles.append(done)
            out.profiles.append(WearProfile(profile.theta, bearing, journal, step * profile.slip,
                                            step * profile.stability, profile.journal_radius, profile.bearing_radius,
                                            profile.length))
            out.steps.append(step)
            out.bounds.append(bound)
            bar.update(step)
        out.complete = True
    except KeyboardInterrupt:
        print(f"\npredict_wear: interrupted after {done:g} of {cycles:g} cycles; the updates so far are returned",
              file=sys.stderr)
    finally:
        bar.close()
        out.wall_time = time.perf_counter() - start
    return out
