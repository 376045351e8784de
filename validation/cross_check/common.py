"""The cross-check's cases, settings and pass/fail criteria, each with its reason, and
the metrics that the journal-bearing, reference and library comparisons share."""
from __future__ import annotations

import math
import os
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams

DEFAULT_OUT = os.path.join("results", "cross_check")

# -- cases ----------------------------------------------------------------------------

#: Restitution coefficients of the journal-bearing sweep (the paper's Figs. 4 and 5).
CR_SWEEP = (0.3, 0.5, 0.7, 0.9, 1.0)
#: Laws of the quick run.
QUICK_LAWS = ("wang-liu", "lankarani-nikravesh")
#: Slider-crank cases: restitution, journal material (bearing steel), friction.
SC_CRS = (0.3, 0.9)
SC_JOURNALS = ("steel", "aluminium")
SC_FRICTIONS = ("none", "paper")
SC_BEARING = "steel"
#: Crank revolutions of the full slider-crank runs (docs/physics.md section 6.2: at least two).
REVOLUTIONS = 2.0
#: Horizon of the quick slider-crank runs [s]: the paper case's impacts all begin before
#: 0.024 s (the reference's onset times, :attr:`validation.reference.slider_crank.Result.onsets`);
#: after that the journal stays in contact.
QUICK_HORIZON = 0.03
#: The two slider-crank cases of the quick run: (cr, journal, friction).
QUICK_SC_CASES = ((0.9, "steel", "none"), (0.3, "aluminium", "paper"))

# -- reference settings ---------------------------------------------------------------

#: Reference integrator and tolerances: DOP853 at rtol 1e-10; atol 1e-13 meets
#: penetrations of ~1e-6 m with seven digits.
REF_METHOD, REF_RTOL, REF_ATOL = "DOP853", 1e-10, 1e-13
#: Tolerances of the reference's convergence check: 100 times tighter.
REF_TIGHT_RTOL, REF_TIGHT_ATOL = 1e-12, 1e-15
#: Case of the convergence check: the paper's own (cr 0.9, steel, no friction), a long
#: sequence of bounces.
CONVERGENCE_CASE = (0.9, "steel", "none")
#: Output interval of the reference [s]: the library's paths are compared at the library's
#: own accepted steps (up to 1e-4 s apart, too far apart to interpolate a free-flight
#: parabola between them), with the reference interpolated linearly between its samples;
#: over 2e-6 s that misses by at most (2e-6)^2 / 8 * 7e3 m/s^2 (a 2 kN impact on
#: 0.3 kg) = 3.5e-9 m = 3.5e-5 c.
GRID_STEP = 2e-6
#: Output interval on which the reference's peak force is read [s]: 1/400 of a ~40 us
#: impact (docs/physics.md section 8), so sampling lowers a sine-like peak by < (pi / 400)^2 / 2 = 3e-5.
PEAK_STEP = 1e-7
#: Perturbation of the sensitivity check [m]: the clearance is enlarged by this (the
#: journal radius shrinks by it), which shifts the journal's free path to every wall by
#: 1e-9 m = 1e-5 c; the reference has no argument for its initial state.
PERTURBATION = 1e-9

# -- library settings -----------------------------------------------------------------

#: Output interval of the library's slider-crank runs [s].  Exudyn records at the first
#: accepted step at or after each output instant, so this records every accepted step
#: longer than 1e-7 s: peaks and onsets are those of the solver's own steps, not of a
#: 1e-5 s sampling.
EXUDYN_OUTPUT_STEP = 1e-7


class Variant(NamedTuple):
    """Solver settings of one slider-crank row: changes to the formulation's default."""

    formulation: str
    kind: str                       # "default" or "converged"
    changes: tuple[tuple[str, float], ...]


#: The four rows per slider-crank case.  Converged settings: DOPRI5 at rtol 1e-9 (1000
#: times tighter than the default) and generalized-alpha at 1e-6 s (its error shrinks as
#: h^2: 1/100 of the default step's).
VARIANTS = (
    Variant("minimal", "default", ()),
    Variant("minimal", "converged", (("rtol", 1e-9), ("atol", 1e-12))),
    Variant("redundant", "default", ()),
    Variant("redundant", "converged", (("step", 1e-6), ("impact_step", None))),
)

# -- pass/fail criteria -----------------------------------------------------------------


class Criterion(NamedTuple):
    """A pass/fail bound: ``|value| <= limit``, with the reason for the limit."""

    key: str
    label: str
    limit: float
    reason: str


JB_CRITERIA = (
    Criterion("departure", "departure velocity, relative", 1e-6,
              "read in free flight, where it is constant: only integration error enters; DOPRI5 at rtol 1e-9 over "
              "~400 steps against DOP853 at rtol 1e-11 leaves ~1e-8, so 1e-6 has a wide margin"),
    Criterion("peak_force", "peak force, relative", 1e-4,
              "the library records at its accepted steps (at most 1e-7 s apart, output every 1e-8 s); a sine-like "
              "pulse of ~40 us sampled 1e-7 s off its peak is low by (pi 1e-7 / 40e-6)^2 / 2 = 3e-5; the reference "
              "refines its peak on the dense output; 1e-4 is three times the sampling bound"),
    Criterion("peak_penetration", "peak penetration, relative", 1e-4,
              "as the peak force (same sampling; penetration is flatter at its peak)"),
    Criterion("duration", "contact duration, relative", 1e-4,
              "the release instant is interpolated linearly between samples at most 1e-7 s apart on a ~40 us "
              "contact; curvature of the penetration there moves it by far less than 1e-4"),
)

#: Bound of the eccentricity difference, in units of the clearance c (reason below).
ECC_LIMIT = 0.01

SC_CRITERIA = (
    Criterion("ecc", "max abs(delta e) / c", ECC_LIMIT,
              "1 % of the clearance (1 um here): an orbit drawn in the clearance circle does not change visibly; "
              "the reference's own error is checked to stay below 1/100 of it"),
    Criterion("peak_force", "peak contact force, relative", 0.01,
              "1 %: the level at which the paper's force plots can be read; with F ~ v0^1.2 (Hertz scaling) it is "
              "0.8 % of the impact speed. Library: largest value at its accepted steps (recorded every step); "
              "reference: dense output sampled every 1e-7 s up to its peak, so sampling adds < 3e-5 there"),
    Criterion("onset_shift", "max onset shift [s]", 1e-5,
              "1e-5 s, the paper's largest step and output interval (0.03 deg of crank angle): an onset that moves "
              "less stays in the same output interval. Onsets of the library: its `onset_times`, interpolated "
              "linearly between accepted steps (checked against its recorded penetration, see onset bookkeeping)"),
)

#: Not a pass/fail criterion, reported only: the relative RMS of the slider-acceleration
#: difference (why: the report's ``acc_note``, :data:`REPORT_TEMPLATE`).

#: Onset bookkeeping: :attr:`SliderCrankResult.onset_times` must agree with the zero
#: crossings of the recorded penetration, which interpolate between the same accepted
#: states in the same way, to 1 % of the step across the crossing (round-off and
#: recording gaps below 1e-7 s stay far below that; a wrong time stamp shows as a whole step).
ONSET_BOOKKEEPING_LIMIT = 0.01

#: Convergence of the reference: its own eccentricity error must be 1/100 of the
#: library's bound, so that the comparison measures the library.
REF_CONVERGENCE_LIMIT = ECC_LIMIT / 100.0
#: Sensitivity: point-by-point comparison ends where the perturbed reference departs by
#: more than 1/10 of the eccentricity bound (it starts 1e-5 c apart).
SENSITIVITY_LIMIT = ECC_LIMIT / 10.0

def _relative(a: float, b: float) -> float:
    return (a - b) / b

class CrankCase(NamedTuple):
    """One slider-crank case: restitution, journal material, friction law."""

    cr: float
    journal: str
    friction: str

    @property
    def label(self) -> str:
        return f"cr {self.cr:g}, {self.journal}, friction {self.friction}"

    def params(self, horizon: float | None, formulation: str = "minimal") -> SliderCrankParams:
        """The paper's slider-crank with this case; ``horizon`` [s] or :data:`REVOLUTIONS`."""
        p = SliderCrankParams.paper(cr=self.cr, journal_material=self.journal, bearing_material=SC_BEARING,
                                    friction=self.friction, formulation=formulation, revolutions=REVOLUTIONS)
        if horizon is None:
            return p
        return replace(p, revolutions=horizon * p.crank_speed / (2.0 * math.pi))


def crank_cases(quick: bool) -> list[CrankCase]:
    """The slider-crank cases of a full or quick run."""
    if quick:
        return [CrankCase(*c) for c in QUICK_SC_CASES]
    return [CrankCase(cr, j, f) for cr in SC_CRS for j in SC_JOURNALS for f in SC_FRICTIONS]

def eccentricity_difference(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> np.ndarray:
    """``|e_a - e_b|`` on ``b``'s times, ``a`` interpolated linearly onto them [m]."""
    t = b["time"]
    dx = np.interp(t, a["time"], a["ecc_x"]) - b["ecc_x"]
    dy = np.interp(t, a["time"], a["ecc_y"]) - b["ecc_y"]
    return np.hypot(dx, dy)

def onset_shift(library: np.ndarray, reference: np.ndarray, horizon: float) -> tuple[float, str]:
    """Largest shift of paired onsets (in order) up to ``horizon`` [s], and a note.

    The note says when the counts differ; the shift then covers the first pairs only.
    """
    a, b = np.sort(library[library <= horizon]), np.sort(reference[reference <= horizon])
    n = min(len(a), len(b))
    shift = float(np.abs(a[:n] - b[:n]).max()) if n else (0.0 if len(a) == len(b) else math.nan)
    note = "" if len(a) == len(b) else f"onset counts differ ({len(a)} vs {len(b)}); shift over the first {n} pairs"
    return shift, note
